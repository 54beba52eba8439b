"""Learning-curve figures: one run's curve and the Figure 4 analog of an experiment.

Figures are built with ``matplotlib.figure.Figure`` and written by the Agg canvas, never through
``pyplot``, so nothing needs a display and no global figure state is touched.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path

import numpy as np
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from experiments.statistics import bootstrap_mean_band, moving_average

Band = tuple[np.ndarray, np.ndarray, np.ndarray]
"""Mean curve, lower and upper bound of its confidence band."""

_STYLES = ("-", "-.", ":")
"""Line styles once the ten default colours have been used."""


def save(figure: Figure, path: Path, dpi: int = 120) -> Path:
    """Write ``figure`` as a PNG through the Agg canvas."""
    path.parent.mkdir(parents=True, exist_ok=True)
    FigureCanvasAgg(figure)
    figure.savefig(path, dpi=dpi)
    return path


def learning_curve(
    steps: np.ndarray,
    leaves: np.ndarray,
    optimal: float,
    path: Path,
    window: int = 50,
    title: str = "",
    cap: int | None = None,
) -> Path:
    """One run: steps per episode (raw and moving average, log axis) and leaves per episode."""
    steps = np.asarray(steps, dtype=float)
    episodes = np.arange(1, steps.size + 1)
    figure = Figure(figsize=(8, 6), layout="constrained")
    top, bottom = figure.subplots(2, 1, sharex=True, height_ratios=(3, 1))
    top.plot(episodes, steps, color="0.75", linewidth=0.6, label="steps per episode")
    top.plot(
        episodes,
        moving_average(steps, window),
        color="C0",
        linewidth=1.6,
        label=f"{window}-episode moving average",
    )
    _reference_lines(top, optimal, cap)
    top.set_yscale("log")
    top.set_ylabel("steps to goal")
    top.legend(loc="upper right", fontsize="small")
    top.set_title(title)
    bottom.plot(episodes, leaves, color="C2")
    bottom.set_ylabel("leaves")
    bottom.set_xlabel("episode")
    return save(figure, path)


def smoothed_bands(
    steps_by_strategy: Mapping[str, np.ndarray], window: int, seed: int = 0
) -> dict[str, Band]:
    """Per strategy: each run smoothed by a trailing moving average, then mean and 95% band."""
    return {
        name: bootstrap_mean_band(moving_average(np.atleast_2d(steps), window), seed=seed)
        for name, steps in steps_by_strategy.items()
    }


def figure4(
    bands: Mapping[str, Band],
    optimal: float,
    path: Path,
    window: int,
    runs: Mapping[str, int],
    cap: int | None = None,
    title: str = "",
) -> Path:
    """The Figure 4 analog: average steps to the goal per episode, one curve per strategy."""
    figure = Figure(figsize=(9, 5.5), layout="constrained")
    axes = figure.subplots()
    for index, (name, (mean, low, high)) in enumerate(bands.items()):
        episodes = np.arange(1, mean.size + 1)
        color = f"C{index % 10}"
        axes.plot(
            episodes,
            mean,
            color=color,
            linewidth=1.4,
            linestyle=_STYLES[index // 10 % 3],
            label=f"{name} (n={runs.get(name, 0)})",
        )
        axes.fill_between(episodes, low, high, color=color, alpha=0.2, linewidth=0)
    _reference_lines(axes, optimal, cap)
    axes.set_yscale("log")
    axes.set_xlabel("episode")
    axes.set_ylabel(f"steps to goal ({window}-episode moving average)")
    axes.set_title(title or "Average steps to goal, mean over runs with 95% bootstrap band")
    axes.legend(loc="best", fontsize="small")
    return save(figure, path)


def leaves_figure(leaves_by_strategy: Mapping[str, np.ndarray], path: Path) -> Path:
    """Leaves (partition size) per episode, mean over runs, one curve per strategy."""
    figure = Figure(figsize=(9, 4), layout="constrained")
    axes = figure.subplots()
    for index, (name, leaves) in enumerate(leaves_by_strategy.items()):
        mean, low, high = bootstrap_mean_band(np.atleast_2d(leaves))
        episodes = np.arange(1, mean.size + 1)
        axes.plot(episodes, mean, color=f"C{index % 10}", label=name)
        axes.fill_between(episodes, low, high, color=f"C{index % 10}", alpha=0.2, linewidth=0)
    axes.set_xlabel("episode")
    axes.set_ylabel("leaves")
    axes.set_title("Size of the partition, mean over runs with 95% bootstrap band")
    axes.legend(loc="upper left", fontsize="small")
    return save(figure, path)


def _reference_lines(axes: Axes, optimal: float, cap: int | None) -> None:
    if np.isfinite(optimal):
        axes.axhline(
            optimal, color="k", linestyle="--", linewidth=1.0, label=f"optimal ({optimal:g} steps)"
        )
    if cap is not None:
        axes.axhline(cap, color="0.4", linestyle=":", linewidth=1.0, label=f"cap ({cap})")


Panel = tuple[str, Mapping[str, np.ndarray], str, tuple[tuple[str, float], ...], bool]
"""One task's panel: title, runs x episodes values by strategy, y label, labelled reference
lines, whether the y axis is logarithmic."""


def task_curves(panels: list[Panel], path: Path, window: int, seed: int = 0) -> Path:
    """One panel per task: each strategy's mean smoothed curve over runs, with its band."""
    columns = max(1, math.ceil(math.sqrt(len(panels))))
    rows = math.ceil(len(panels) / columns)
    figure = Figure(figsize=(3.6 * columns, 2.8 * rows + 0.6), layout="constrained")
    grid = figure.subplots(rows, columns, squeeze=False)
    names: list[str] = []
    for axes, (title, runs_by_strategy, ylabel, references, log_y) in zip(
        grid.flat, panels, strict=False
    ):
        for name, (mean, low, high) in smoothed_bands(runs_by_strategy, window, seed).items():
            if name not in names:
                names.append(name)
            index = names.index(name)
            episodes = np.arange(1, mean.size + 1)
            color = f"C{index % 10}"
            style = _STYLES[index // 10 % 3]
            axes.plot(episodes, mean, color=color, linestyle=style, linewidth=1.0, label=name)
            axes.fill_between(episodes, low, high, color=color, alpha=0.15, linewidth=0)
        for label, value in references:
            if np.isfinite(value):
                axes.axhline(value, color="k", linestyle="--", linewidth=0.8)
                axes.annotate(label, (1, value), fontsize="x-small", va="bottom")
        if log_y:
            axes.set_yscale("log")
        axes.set_title(title, fontsize="small")
        axes.set_ylabel(ylabel, fontsize="small")
        axes.tick_params(labelsize="x-small")
    for axes in list(grid.flat)[len(panels) :]:
        axes.set_visible(False)
    handles, labels = grid.flat[0].get_legend_handles_labels()
    figure.legend(handles, labels, loc="outside lower center", ncol=min(6, len(labels)))
    figure.suptitle(f"{window}-episode moving average, mean over runs with 95% bootstrap band")
    return save(figure, path)


def performance_profile(
    thresholds: np.ndarray,
    profiles: Mapping[str, Band],
    path: Path,
    xlabel: str,
    lower_is_better: bool,
    title: str,
) -> Path:
    """Fraction of runs (all tasks) whose score is at least as good as each threshold, one
    curve per strategy with its 95% stratified bootstrap band (Agarwal et al. 2021)."""
    figure = Figure(figsize=(7, 4.5), layout="constrained")
    axes = figure.subplots()
    for index, (name, (value, low, high)) in enumerate(profiles.items()):
        color = f"C{index % 10}"
        axes.plot(thresholds, value, color=color, linestyle=_STYLES[index // 10 % 3], label=name)
        axes.fill_between(thresholds, low, high, color=color, alpha=0.2, linewidth=0)
    if lower_is_better and thresholds.min() > 0:
        axes.set_xscale("log")
    axes.set_xlabel(xlabel)
    relation = "<=" if lower_is_better else ">="
    axes.set_ylabel(f"fraction of runs with score {relation} tau")
    axes.set_ylim(-0.02, 1.02)
    axes.set_title(title, fontsize="medium")
    axes.legend(loc="best", fontsize="small")
    return save(figure, path)
