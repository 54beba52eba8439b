"""The report of a transfer (:mod:`experiments.transfer`): per-cell results, a table over agents
with bootstrap confidence intervals, the gap to each agent's training condition, and heatmaps.

Files: ``cells.csv`` (one row per agent and condition), ``summary.csv`` and ``report.md`` (one
row per training recipe, layout, robot, mode and level: agents, success rate, steps / optimum
and the gap, each a mean over agents with a 95% percentile bootstrap interval over agents),
``success.png`` and ``steps_ratio.png`` (one panel per training recipe: rows robot / mode,
columns layout / level, the mean over agents).
"""

from __future__ import annotations

import csv
import io
import math
from collections import defaultdict
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from experiments import store
from experiments.statistics import bootstrap_ci, interval_text
from experiments.transfer_cell import TransferAgent, robot_label
from experiments.transfer_state import (
    TRAIN_LEVEL,
    TransferSpec,
    TransferState,
    iter_finished,
    steps_ratio,
)

CELL_COLUMNS = (
    "group",
    "agent",
    "layout",
    "robot",
    "mode",
    "level",
    "episodes",
    "success_rate",
    "mean_steps",
    "optimal_steps",
    "steps_ratio",
    "collisions",
    "tipped",
    "train_success_rate",
    "gap",
)


@dataclass(frozen=True)
class CellRow:
    """One agent in one condition, summarised."""

    group: str
    agent: str
    layout: str
    robot: str
    mode: str
    level: str
    episodes: int
    success_rate: float
    mean_steps: float
    optimal_steps: float
    steps_ratio: float
    collisions: float
    tipped: float
    """Fraction of the episodes whose robot had tipped over by their end (NaN for a cell stored
    before falls were counted)."""
    train_success_rate: float
    gap: float
    """Success rate here minus in the agent's training condition (NaN without it)."""


@dataclass(frozen=True)
class SummaryRow:
    """One training recipe in one condition, over its agents."""

    group: str
    layout: str
    robot: str
    mode: str
    level: str
    agents: int
    success: tuple[float, float, float]
    """Mean over agents of the success rate, and its 95% interval."""
    ratio: tuple[float, float, float]
    gap: tuple[float, float, float]


@dataclass(frozen=True)
class TransferReport:
    """What :func:`write_transfer_report` wrote."""

    path: Path
    cells: tuple[CellRow, ...]
    summary: tuple[SummaryRow, ...]
    figures: tuple[Path, ...]
    skipped: tuple[tuple[str, str, str], ...]
    """(recipe, condition, reason) of each condition that did not apply, once each."""


def cell_rows(state: TransferState) -> list[CellRow]:
    """Every finished cell summarised, with its gap to the agent's training condition."""
    raw = []
    for cell, check in iter_finished(state):
        assert check.columns is not None
        assert check.meta is not None
        steps = check.columns["steps"]
        optimal = float(check.meta["optimal_steps"])
        raw.append(
            (
                cell,
                float(np.mean(check.columns["success"])),
                float(np.mean(steps)),
                optimal,
                steps_ratio(steps, optimal),
                float(np.mean(check.columns["collisions"])),
                # a cell stored before falls were counted does not say: NaN
                int(check.meta["tipped"]) / len(steps) if "tipped" in check.meta else math.nan,
            )
        )
    own = {c.agent.key: s for c, s, *_ in raw if c.condition.level == TRAIN_LEVEL}
    rows = []
    for cell, success, mean_steps, optimal, ratio, collisions, tipped in raw:
        reference = own.get(cell.agent.key, math.nan)
        rows.append(
            CellRow(
                cell.agent.group,
                cell.agent.key,
                Path(str(cell.agent.env.maze)).stem,
                robot_label(cell.condition.robot),
                cell.condition.mode,
                cell.condition.level,
                cell.episodes,
                success,
                mean_steps,
                optimal,
                ratio,
                collisions,
                tipped,
                reference,
                success - reference,
            )
        )
    return rows


def summarize_cells(rows: Sequence[CellRow], seed: int = 0) -> list[SummaryRow]:
    """One row per (recipe, layout, robot, mode, level), in the order first met."""
    groups: dict[tuple[str, str, str, str, str], list[CellRow]] = defaultdict(list)
    for row in rows:
        groups[(row.group, row.layout, row.robot, row.mode, row.level)].append(row)

    def interval(values: np.ndarray) -> tuple[float, float, float]:
        values = values[np.isfinite(values)]
        if not values.size:
            return (math.nan, math.nan, math.nan)
        low, high = bootstrap_ci(values, seed=seed)
        return (float(np.mean(values)), low, high)

    return [
        SummaryRow(
            key[0],
            key[1],
            key[2],
            key[3],
            key[4],
            len(members),
            interval(np.array([m.success_rate for m in members])),
            interval(np.array([m.steps_ratio for m in members])),
            interval(np.array([m.gap for m in members])),
        )
        for key, members in groups.items()
    ]


def write_transfer_report(
    spec: TransferSpec,
    agents: Sequence[TransferAgent],
    out: Path,
    state: TransferState,
    failures: Path | None = None,
) -> TransferReport:
    """Write ``cells.csv``, ``summary.csv``, the heatmaps and ``report.md`` into ``out``."""
    rows = cell_rows(state)
    summary = summarize_cells(rows)
    store.atomic_write_text(out / "cells.csv", _csv(CELL_COLUMNS, [_values(r) for r in rows]))
    store.atomic_write_text(
        out / "summary.csv",
        _csv(
            (
                "group",
                "layout",
                "robot",
                "mode",
                "level",
                "agents",
                "success",
                "success_low",
                "success_high",
                "steps_ratio",
                "steps_ratio_low",
                "steps_ratio_high",
                "gap",
                "gap_low",
                "gap_high",
            ),
            [
                (
                    s.group,
                    s.layout,
                    s.robot,
                    s.mode,
                    s.level,
                    s.agents,
                    *s.success,
                    *s.ratio,
                    *s.gap,
                )
                for s in summary
            ],
        ),
    )
    missing = [
        (robot_label(item.condition.robot), item.condition.mode)
        for item in state.skipped
        if item.condition.level != TRAIN_LEVEL
    ]
    figures = tuple(
        heatmaps(summary, metric, out / f"{metric}.png", missing)
        for metric in ("success", "steps_ratio")
    ) + ((failures,) if failures is not None else ())
    skipped: dict[tuple[str, str], str] = {}
    for item in state.skipped:
        skipped.setdefault((item.agent.group, item.condition.name), item.reason)
    skipped_rows = tuple((group, name, reason) for (group, name), reason in skipped.items())
    path = out / "report.md"
    text = _markdown(spec, agents, state, summary, figures, skipped_rows, rows)
    store.atomic_write_text(path, text)
    return TransferReport(path, tuple(rows), tuple(summary), figures, skipped_rows)


def heatmaps(
    summary: Sequence[SummaryRow],
    metric: str,
    path: Path,
    not_applicable: Sequence[tuple[str, str]] = (),
) -> Path:
    """One panel per training recipe: rows robot / mode, columns layout / level, each cell the
    mean over agents of ``metric`` (``success`` or ``steps_ratio``), written in the cell;
    ``not_applicable`` (robot, mode) pairs get a row of ``n/a``."""
    from matplotlib.figure import Figure

    from experiments.plots import save

    shown = [s for s in summary if s.level != TRAIN_LEVEL]
    groups = list(dict.fromkeys(s.group for s in shown))
    rows = list(dict.fromkeys(f"{s.robot} / {s.mode}" for s in shown))
    rows += [f"{r} / {m}" for r, m in dict.fromkeys(not_applicable) if f"{r} / {m}" not in rows]
    columns = list(dict.fromkeys(f"{s.layout} / {s.level}" for s in shown))
    figure = Figure(
        figsize=(max(6.0, 2.5 + 0.75 * len(columns)), 0.9 + (0.45 * len(rows) + 0.6) * len(groups))
    )
    axes_list = figure.subplots(max(1, len(groups)), 1, squeeze=False)[:, 0]
    vmax = 1.0 if metric == "success" else 4.0
    for axes, group in zip(axes_list, groups, strict=False):
        grid = np.full((len(rows), len(columns)), np.nan)
        for s in shown:
            if s.group == group:
                value = s.success[0] if metric == "success" else s.ratio[0]
                grid[
                    rows.index(f"{s.robot} / {s.mode}"), columns.index(f"{s.layout} / {s.level}")
                ] = value
        cmap = "RdYlGn" if metric == "success" else "RdYlGn_r"
        image = axes.imshow(
            grid, cmap=cmap, vmin=0.0 if metric == "success" else 1.0, vmax=vmax, aspect="auto"
        )
        for (i, j), value in np.ndenumerate(grid):
            if math.isfinite(value):
                text = f"{100 * value:.0f}" if metric == "success" else f"{value:.2f}"
                axes.text(j, i, text, ha="center", va="center", fontsize=7)
            else:
                axes.text(j, i, "n/a", ha="center", va="center", fontsize=6, color="0.4")
        axes.set_yticks(range(len(rows)), rows, fontsize=7)
        axes.set_xticks(range(len(columns)), columns, fontsize=7, rotation=40, ha="right")
        axes.set_title(group, fontsize=8)
        figure.colorbar(image, ax=axes, fraction=0.03, pad=0.01)
    label = (
        "success rate (%)"
        if metric == "success"
        else "steps / optimum (capped episodes at the cap)"
    )
    figure.suptitle(f"Transfer: {label}, mean over agents", fontsize=9)
    figure.tight_layout()
    return save(figure, path)


def _values(row: CellRow) -> tuple[Any, ...]:
    return tuple(getattr(row, name) for name in CELL_COLUMNS)


def _csv(columns: Sequence[str], rows: Sequence[Sequence[Any]]) -> str:
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(columns)
    for row in rows:
        writer.writerow([repr(v) if isinstance(v, float) else v for v in row])
    return buffer.getvalue()


def _ci(values: tuple[float, float, float], percent: bool) -> str:
    mean, low, high = values
    if not math.isfinite(mean):
        return "-"
    if percent:
        return f"{100 * mean:.0f}% {interval_text(100 * low, 100 * high, '.0f')}"
    return f"{mean:.2f} {interval_text(low, high, '.2f')}"


def _gap(values: tuple[float, float, float]) -> str:
    mean, low, high = values
    if not math.isfinite(mean):
        return "-"
    return f"{100 * mean:+.0f} {interval_text(100 * low, 100 * high, '+.0f')}"


def _markdown(
    spec: TransferSpec,
    agents: Sequence[TransferAgent],
    state: TransferState,
    summary: Sequence[SummaryRow],
    figures: Sequence[Path],
    skipped: Sequence[tuple[str, str, str]],
    rows: Sequence[CellRow] = (),
) -> str:
    grid = spec.conditions
    cap = (
        spec.max_episode_steps
        if spec.max_episode_steps is not None
        else "each agent's training cap"
    )
    lines = [
        f"# Transfer: {spec.name}",
        "",
        f"- agents: {len(agents)} ({len({a.group for a in agents})} training "
        f"recipes); cells finished: {len(state.finished)} of {len(state.cells)}",
        f"- conditions: robots {', '.join(grid.robots)}; modes {', '.join(grid.modes)}; levels "
        f"{', '.join(grid.levels)}; layouts "
        f"{', '.join(grid.layouts) if grid.layouts is not None else 'those of the agents'}",
        f"- {spec.episodes} greedy episodes per agent and condition, episode cap {cap}",
        "",
        *[f"![{f.stem}]({f.name})" for f in figures],
        "",
        "| training recipe | layout | robot | mode | level | agents | success rate [95% CI] "
        "| steps / optimum [95% CI] | gap to training condition, pp [95% CI] |",
        "|---|---|---|---|---|---:|---:|---:|---:|",
    ]
    for s in summary:
        lines.append(
            f"| {s.group} | {s.layout} | {s.robot} | {s.mode} | {s.level} | {s.agents} | "
            f"{_ci(s.success, True)} | {_ci(s.ratio, False)} | {_gap(s.gap)} |"
        )
    fell = [r for r in rows if r.tipped > 0]
    if fell:
        lines += [
            "",
            "## Robots that tipped over",
            "",
            'A tipped robot lies on its side until the episode\'s cap (`info["tipped"]`): '
            "each such episode is a failure counted at the cap.",
            "",
        ]
        lines += [
            f"- {r.agent}: {r.robot} / {r.mode} / {r.level} in {r.layout}: "
            f"{round(r.tipped * r.episodes)} of {r.episodes} episodes"
            for r in fell
        ]
    if skipped:
        lines += ["", "## Conditions that do not apply", ""]
        seen = set()
        for group, name, reason in skipped:
            if (name, reason) in seen:
                continue
            seen.add((name, reason))
            lines.append(f"- {name} ({group}): {reason}")
    lines += [
        "",
        "## Definitions",
        "",
        f"- **Level `{TRAIN_LEVEL}`**: the agent's own training environment, exactly as trained "
        "(the reference of the gap). Levels `none`, `moderate`, `strong` are "
        "`bullet_maze.perturbations.LEVELS`, the settings that apply to the robot and mode; "
        "the training environment's perturbations are replaced by them.",
        "- **Success rate**: fraction of an agent's greedy episodes that reached the goal; the "
        "table gives the mean over agents and a 95% percentile bootstrap interval over agents.",
        "- **Steps / optimum**: an agent's mean steps per episode (a capped episode counts its "
        "cap) divided by the layout's optimal number of steps.",
        "- **Gap**: an agent's success rate in the condition minus in its training condition, in "
        "percentage points, averaged over agents.",
        "- Each cell's episodes are seeded from the agent's run seed and the condition "
        "(`experiments.transfer.cell_seed`): the numbers do not depend on the backend or the "
        "number of workers.",
    ]
    return "\n".join(lines) + "\n"
