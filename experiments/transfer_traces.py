"""Pictures of failing transfer episodes: where a policy goes wrong in a condition.

A stored cell holds each episode's outcome, not its path. :func:`replay` plays a cell's episodes
again exactly as :func:`experiments.evaluation.evaluate` did (the same seed, the same resets)
and records the robot's true position (``env.unwrapped.pose``; the observation may be noisy),
checking that every replayed episode took the stored number of steps. :func:`draw_failures`
draws the first failing episode of chosen cells over the agent's partition and its greedy
actions, with the collisions marked.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from experiments import factory
from experiments.transfer_cell import Cell
from experiments.transfer_state import TransferState


@dataclass(frozen=True)
class Trace:
    """One replayed episode."""

    cell: Cell
    episode: int
    """Its number in the cell, from 1."""
    positions: np.ndarray
    """True (x, y) at reset and after every step."""
    collisions: np.ndarray
    """Indices of the steps that touched a wall or an obstacle."""
    success: bool


def replay(cell: Cell, episode: int) -> tuple[Trace, Any]:
    """Play the cell's episodes 1..``episode`` again; the trace of the last, and the agent."""
    agent = factory.load_agent(cell.agent.path)
    env = factory.make_env(cell.env)
    played = factory.fitted_to(env, agent.observation_space.shape[0])
    inner: Any = env.unwrapped
    try:
        for number in range(1, episode + 1):
            obs, _ = played.reset(seed=cell.seed if number == 1 else None)
            positions = [np.array(inner.pose[:2], dtype=np.float64)]
            hits: list[int] = []
            while True:
                obs, _, terminated, truncated, info = played.step(agent.predict(obs))
                positions.append(np.array(inner.pose[:2], dtype=np.float64))
                if info.get("collision", False):
                    hits.append(len(positions) - 1)
                if terminated or truncated:
                    success = bool(info.get("is_success", terminated))
                    break
    finally:
        env.close()
    trace = Trace(cell, episode, np.array(positions), np.array(hits, dtype=int), success)
    return trace, agent


def failing_cells(
    state: TransferState,
    mode: str = "dynamic",
    levels: Sequence[str] = ("moderate", "strong"),
    limit: int = 6,
) -> list[tuple[Cell, int]]:
    """The first cell (in plan order) of each (recipe, robot) in ``mode`` with a failed
    episode, and that episode's number: at the first of ``levels`` first, then at the next
    for the recipes and robots that had none; at most ``limit``."""
    chosen: dict[tuple[str, str], tuple[Cell, int]] = {}
    for level in levels:
        for cell in state.finished:
            check = state.checks[cell.name]
            condition = cell.condition
            if condition.mode != mode or condition.level != level or check.columns is None:
                continue
            key = (cell.agent.group, condition.robot)
            failed = np.flatnonzero(check.columns["success"] == 0)
            if key not in chosen and failed.size:
                chosen[key] = (cell, int(failed[0]) + 1)
    return list(chosen.values())[:limit]


def draw_failures(picks: Sequence[tuple[Cell, int]], path: Path, stored: TransferState) -> Path:
    """One panel per pick: the layout, the agent's partition with its greedy actions, the
    replayed episode (collisions as crosses), its outcome in the title."""
    from matplotlib.figure import Figure

    from bullet_maze import load_layout
    from bullet_maze.actions import DIRECTIONS
    from experiments.partition import draw_layout, draw_partition
    from experiments.plots import save

    columns = min(3, max(1, len(picks)))
    rows = -(-len(picks) // columns) or 1
    figure = Figure(figsize=(4.2 * columns, 4.3 * rows), layout="constrained")
    grid = figure.subplots(rows, columns, squeeze=False)
    for axes in grid.flat[len(picks) :]:
        axes.set_visible(False)
    for axes, (cell, episode) in zip(grid.flat, picks, strict=False):
        trace, agent = replay(cell, episode)
        check = stored.checks[cell.name]
        assert check.columns is not None
        expected = int(check.columns["steps"][episode - 1])
        replayed = len(trace.positions) - 1
        layout = load_layout(str(cell.env.maze))
        if hasattr(agent, "leaves"):  # (a fixed baseline has no partition: the maze alone)
            draw_partition(axes, agent.leaves(), DIRECTIONS)
        draw_layout(axes, layout)
        axes.plot(
            trace.positions[:, 0], trace.positions[:, 1], color="tab:orange", lw=1.2, zorder=6
        )
        if trace.collisions.size:
            hit = trace.positions[trace.collisions]
            axes.plot(hit[:, 0], hit[:, 1], "x", color="k", ms=4, zorder=7)
        same = "" if replayed == expected else f" (stored {expected}: replay differs!)"
        condition = cell.condition
        axes.set_title(
            f"{cell.agent.group}\n{condition.robot} {condition.mode} {condition.level}, "
            f"episode {episode}: {replayed} steps{same},\n{trace.collisions.size} collisions, "
            f"{'goal' if trace.success else 'no goal'}",
            fontsize=7,
        )
        axes.set_xlabel("")
        axes.set_ylabel("")
    return save(figure, path)
