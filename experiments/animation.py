"""A GIF of one episode seen from above, the learned partition (a tree's or a grid's) drawn
underneath.

The background (partition and maze) is drawn once; each frame only moves the robot and extends
its track. Long episodes are subsampled to at most ``max_frames`` frames.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import imageio.v3 as iio
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.patches import Circle

from experiments.partition import draw_layout, draw_partition


def frame_indices(steps: int, max_frames: int) -> np.ndarray:
    """Which of the ``steps + 1`` positions become frames (always the first and the last)."""
    count = min(steps + 1, max_frames)
    return np.unique(np.linspace(0, steps, count).round().astype(int))


def render_gif(
    agent: Any,
    layout: Any,
    directions: np.ndarray,
    positions: np.ndarray,
    path: Path,
    fps: int = 15,
    max_frames: int = 150,
    title: str = "",
) -> Path:
    """Write a GIF of the robot following ``positions`` over the agent's partition."""
    figure = Figure(figsize=(5, 5), dpi=80, layout="constrained")
    canvas = FigureCanvasAgg(figure)
    axes = figure.subplots()
    if hasattr(agent, "leaves"):  # (a fixed baseline has no partition: the maze alone)
        draw_partition(axes, agent.leaves(), directions, colorbar=False)
    draw_layout(axes, layout)
    radius = getattr(layout, "robot_radius", 5.0)
    (track,) = axes.plot([], [], color="tab:orange", linewidth=1.5, zorder=6)
    robot = Circle(tuple(positions[0]), radius, facecolor="tab:blue", edgecolor="k", zorder=7)
    axes.add_patch(robot)
    label = axes.set_title(title)
    frames = []
    steps = len(positions) - 1
    for index in frame_indices(steps, max_frames):
        track.set_data(positions[: index + 1, 0], positions[: index + 1, 1])
        robot.center = (positions[index, 0], positions[index, 1])
        label.set_text(f"{title} step {index}/{steps}".strip())
        canvas.draw()
        frames.append(np.asarray(canvas.buffer_rgba())[..., :3].copy())
    path.parent.mkdir(parents=True, exist_ok=True)
    iio.imwrite(path, np.stack(frames), extension=".gif", duration=1000 / fps, loop=0)
    return path
