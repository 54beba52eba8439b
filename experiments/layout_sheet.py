"""Contact sheets of maze layouts: each layout drawn with its start square, goal circle and
shortest collision-free path (``bullet_maze.shortest_path``) and titled with its least number of
steps, so that a user sees what they are about to train on (``run.py layouts``).

``bullet_maze`` is imported inside the functions, as in ``experiments.factory``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from matplotlib.figure import Figure

from experiments.partition import draw_layout
from experiments.plots import save

MAX_SHEET_LAYOUTS = 100
"""Most layouts on one sheet."""


def draw_layout_sheet(
    specs: Sequence[Any], path: Path, labels: Sequence[str] | None = None, columns: int = 0
) -> Path:
    """A PNG of the layouts ``specs`` (anything ``bullet_maze.load_layout`` takes), one panel
    each with the shortest path for the layout's robot and the default step; ``labels`` prefix
    the panels' titles (e.g. the split); ``columns`` 0 chooses a near-square sheet."""
    from bullet_maze import load_layout, shortest_path

    if not specs:
        raise ValueError("no layouts to draw")
    if len(specs) > MAX_SHEET_LAYOUTS:
        raise ValueError(f"{len(specs)} layouts, more than the {MAX_SHEET_LAYOUTS} of one sheet")
    layouts = [load_layout(spec) for spec in specs]
    columns = columns or math.ceil(math.sqrt(len(layouts)))
    rows = math.ceil(len(layouts) / columns)
    figure = Figure(figsize=(3.4 * columns, 3.6 * rows), layout="constrained")
    for index, layout in enumerate(layouts):
        axes = figure.add_subplot(rows, columns, index + 1)
        limit = shortest_path(layout)
        draw_layout(axes, layout)
        points = limit.waypoints
        axes.plot(points[:, 0], points[:, 1], color="tab:blue", linewidth=1.6, zorder=5)
        axes.set_xlabel("")
        axes.set_ylabel("")
        axes.tick_params(labelsize=6)
        prefix = f"{labels[index]}: " if labels else ""
        axes.set_title(
            f"{prefix}{_short(layout.name)}\n{limit.steps} steps, path {limit.length:.0f}",
            fontsize=8,
        )
    return save(figure, path)


def draw_suite_sheet(name: str, path: Path, split: str | None = None) -> Path:
    """The contact sheet of a suite's layouts (both splits, or one)."""
    from bullet_maze import load_suite

    suite = load_suite(name)
    splits = ("dev", "test") if split is None else (split,)
    specs = [spec for s in splits for spec in suite.split(s)]
    labels = [s for s in splits for _ in suite.split(s)]
    return draw_layout_sheet(specs, path, labels)


def _short(name: str, width: int = 34) -> str:
    return name if len(name) <= width else f"{name[: width - 3]}..."
