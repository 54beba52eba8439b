"""The learned partition drawn over the maze: each leaf's box, its value and its greedy action.

Uses the agent's inspection API (``agent.leaves()`` -> ``LeafInfo`` with ``low``, ``high`` and
``q_values``) and the layout's geometry (arena, walls, obstacles, start square, goal circle).
Only the first two observation dimensions (x, y) are drawn.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import PatchCollection
from matplotlib.figure import Figure
from matplotlib.patches import Circle, Rectangle

from experiments.plots import save


def draw_layout(axes: Axes, layout: Any) -> None:
    """Arena outline, walls, obstacles (grey), start square (green) and goal circle (red)."""
    width, height = layout.arena
    axes.add_patch(Rectangle((0, 0), width, height, fill=False, edgecolor="k", linewidth=2))
    for wall in layout.walls:
        (cx, cy), (sx, sy) = wall.center, wall.size
        axes.add_patch(
            Rectangle((cx - sx / 2, cy - sy / 2), sx, sy, facecolor="0.35", edgecolor="k", zorder=3)
        )
    for obstacle in layout.obstacles:
        axes.add_patch(
            Circle(obstacle.center, obstacle.radius, facecolor="0.55", edgecolor="0.2", zorder=3)
        )
    size = layout.start_size
    axes.add_patch(
        Rectangle(
            (layout.start[0] - size / 2, layout.start[1] - size / 2),
            size,
            size,
            facecolor="tab:green",
            alpha=0.8,
            zorder=4,
        )
    )
    axes.add_patch(
        Circle(layout.goal, layout.goal_radius, facecolor="tab:red", alpha=0.8, zorder=4)
    )
    axes.set_xlim(0, width)
    axes.set_ylim(0, height)
    axes.set_aspect("equal")
    axes.set_xlabel("x (maze units)")
    axes.set_ylabel("y (maze units)")


def greedy_actions(leaves: Sequence[Any]) -> np.ndarray:
    """Greedy action of each leaf (``LeafInfo.greedy``, what ``agent.predict`` chooses there);
    -1 when all of a leaf's values are equal (nothing learned there)."""
    actions = np.full(len(leaves), -1)
    for index, leaf in enumerate(leaves):
        q = np.asarray(leaf.q_values, dtype=float)
        if q.size and not np.all(q == q[0]):
            actions[index] = int(leaf.greedy)
    return actions


def draw_partition(
    axes: Axes, leaves: Sequence[Any], directions: np.ndarray, colorbar: bool = True
) -> None:
    """Leaf boxes coloured by max Q, with an arrow for each leaf's greedy action."""
    boxes = [
        Rectangle(
            (leaf.low[0], leaf.low[1]), leaf.high[0] - leaf.low[0], leaf.high[1] - leaf.low[1]
        )
        for leaf in leaves
    ]
    values = np.array([max(leaf.q_values) for leaf in leaves], dtype=float)
    collection = PatchCollection(
        boxes, cmap="viridis", edgecolor="0.3", linewidth=0.4, alpha=0.45, zorder=1
    )
    collection.set_array(values)
    axes.add_collection(collection)
    if colorbar:
        axes.figure.colorbar(collection, ax=axes, shrink=0.8, label="max Q of the leaf")
    actions = greedy_actions(leaves)
    learned = actions >= 0
    if not learned.any():
        return
    centres = np.array([[(leaf.low[d] + leaf.high[d]) / 2 for d in (0, 1)] for leaf in leaves])
    sizes = np.array(
        [min(leaf.high[0] - leaf.low[0], leaf.high[1] - leaf.low[1]) for leaf in leaves]
    )
    arrows = directions[actions[learned]] * (0.4 * sizes[learned])[:, None]
    axes.quiver(
        centres[learned, 0],
        centres[learned, 1],
        arrows[:, 0],
        arrows[:, 1],
        angles="xy",
        scale_units="xy",
        scale=1,
        pivot="middle",
        color="k",
        width=0.003,
        headwidth=4,
        zorder=5,
    )


def partition_figure(
    agent: Any,
    layout: Any,
    directions: np.ndarray,
    path: Path,
    title: str = "",
    trajectory: np.ndarray | None = None,
) -> Path:
    """PNG of the agent's partition over the maze (and a greedy trajectory, if given)."""
    figure = Figure(figsize=(7.5, 6.5), layout="constrained")
    axes = figure.subplots()
    leaves = agent.leaves()
    draw_partition(axes, leaves, directions)
    draw_layout(axes, layout)
    if trajectory is not None and len(trajectory):
        axes.plot(
            trajectory[:, 0],
            trajectory[:, 1],
            color="tab:orange",
            linewidth=1.5,
            zorder=6,
            label="greedy episode",
        )
        axes.legend(loc="lower right", fontsize="small")
    axes.set_title(title or f"{len(leaves)} leaves; arrows: greedy action")
    return save(figure, path)
