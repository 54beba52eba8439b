"""The fast loop's own copy of the world's sweep (``fast_loop._sweep_queries``) and its in-call
cell import answer exactly as ``World.sweep_collides`` and ``FastRunner._import_cells`` do."""

from __future__ import annotations

import gc
import math
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from agent import fast_loop
from bullet_maze.world import CELL
from experiments import factory
from experiments.config import load_config
from experiments.seeding import derive_seeds, run_seed

FOREST = "forest:seed=0,count=60,width=300,height=300,gap=11"
FIG4 = load_config("paper_fig4")


def fig4_agent(name: str, env: gym.Env) -> Any:
    return factory.make_agent(FIG4, FIG4.strategy(name), env, derive_seeds(run_seed(0, 0)).agent)


def _world_state(world: Any) -> tuple[Any, ...]:
    cells = {
        cell: None if b is None else (b.cx, b.cy, b.pieces) for cell, b in world._cells.items()
    }
    return world._safe, world._probe_xy, list(cells.items())


@pytest.mark.parametrize("maze", [None, FOREST])
def test_the_mirrored_queries_answer_as_sweep_collides(maze: str | None) -> None:
    """Same moves on two copies of one world: ``sweep_collides`` on one, on the other what the
    kernel and the driver do (the safe ball, then the mirrored lines from the unseen cell's
    bounds, or ``certified_free`` on a known cell then the mirrored queries); the answers, safe
    ball, probe position and cell cache agree after every move (one solid body: the inline
    ``_closest``; a forest of many bodies: ``World._closest`` itself)."""
    kwargs = {} if maze is None else {"maze": maze}
    envs = [gym.make("BulletMaze-v0", **kwargs) for _ in range(2)]
    try:
        worlds = [env.unwrapped.world for env in envs]
        assert (worlds[0]._single is not None) == (maze is None)
        queries = fast_loop._sweep_queries(worlds[1])
        width, height = envs[0].unwrapped._arena
        rng = np.random.default_rng(7)
        x, y = width / 2, height / 2
        decided = unseen = 0
        for i in range(1500):
            if i % 50 == 0:  # a new start anywhere (inside solids too)
                x, y = (float(v) for v in rng.uniform(-5.0, [width + 5.0, height + 5.0]))
            length = 0.0 if i % 97 == 0 else float(rng.choice([0.5, 1.0, 3.0, 30.0]))
            angle = float(rng.uniform(0.0, 2 * np.pi))
            x1, y1 = x + length * np.cos(angle), y + length * np.sin(angle)
            expected = worlds[0].sweep_collides(x, y, x1, y1)
            world = worlds[1]
            cx, cy, safe = world._safe
            cell = (int(x // CELL), int(y // CELL))
            if math.hypot(x1 - cx, y1 - cy) <= safe and math.hypot(x - cx, y - cy) <= safe:
                found = False  # what the kernel proves itself
            elif cell not in world._cells:  # the kernel's known = 2
                found = queries(x, y, x1, y1, 2)
                unseen += 1
            elif world.certified_free(x, y, x1, y1):  # a known cell: no side effect
                found = False
            else:  # known = 1
                found = queries(x, y, x1, y1, 1)
                decided += 1
            assert found == expected, (i, x, y, x1, y1)
            assert _world_state(worlds[1]) == _world_state(worlds[0]), i
            if not expected:
                x, y = x1, y1
        assert decided > 150  # the mirrored lines answered many of them
        assert unseen > 100
    finally:
        for env in envs:
            env.close()


def test_the_in_call_cell_import_writes_what_the_general_import_writes() -> None:
    """After a run whose cells came in through the callback, the kernel's tables hold, for
    every cell, the bounds a fresh import of the world's cell dict gives."""
    env = gym.make("BulletMaze-v0", max_episode_steps=600)
    try:
        agent = fig4_agent("eps-greedy-0.1", env)
        runner = fast_loop.episode_runner(agent, env)
        assert isinstance(runner, fast_loop.FastRunner)
        calls = [0]
        original = runner._import_cells_in_call

        def counting(cells: Any) -> None:
            calls[0] += 1
            original(cells)

        runner._import_cells_in_call = counting  # type: ignore[method-assign]
        for i in range(5):
            obs, _ = env.reset(seed=3 if i == 0 else None)
            runner(env, obs)
        assert calls[0] > 50

        def decoded(r: Any) -> dict[tuple[int, int], Any]:
            out: dict[tuple[int, int], Any] = {}
            for cx, cy in zip(*np.nonzero(r.cells != fast_loop_kernel().CELL_UNSEEN), strict=True):
                index = int(r.cells[cx, cy])
                if index < 0:
                    out[int(cx), int(cy)] = index
                    continue
                first, count = (int(v) for v in r.bounds_r[index])
                out[int(cx), int(cy)] = (
                    tuple(r.bounds_c[index].tolist()),
                    r.pieces[first : first + count].tolist(),
                )
            return out

        fresh = fast_loop.FastRunner(fig4_agent("eps-greedy-0.1", env), env, fast_loop_kernel())
        fresh._import_cells(runner.cell_table)  # the general import (NumPy item assignment)
        assert len(runner.cell_table) == runner.ncells == fresh.ncells
        assert decoded(runner) == decoded(fresh)
    finally:
        env.close()


def fast_loop_kernel() -> Any:
    kernel = fast_loop.load_kernel()
    assert kernel is not None
    return kernel


@pytest.mark.parametrize("enabled", [True, False])
def test_the_collector_is_as_the_caller_left_it_after_an_episode_even_one_that_raised(
    enabled: bool,
) -> None:
    env = gym.make("BulletMaze-v0", max_episode_steps=600)
    try:
        agent = fig4_agent("adaptive+tabu", env)
        world = env.unwrapped.world
        original = world.sweep_collides
        calls = [0]
        limit = [10**9]
        seen: list[bool] = []

        def failing(*args: float) -> bool:
            calls[0] += 1
            seen.append(gc.isenabled())
            if calls[0] == limit[0]:
                raise RuntimeError("a sweep failed")
            return original(*args)

        world.sweep_collides = failing
        (gc.enable if enabled else gc.disable)()
        agent.learn(env, 1, reset_seed=1)
        assert gc.isenabled() == enabled
        limit[0] = calls[0] + 5
        with pytest.raises(RuntimeError, match="a sweep failed"):
            agent.learn(env, 3)
        assert gc.isenabled() == enabled
        assert calls[0] == limit[0]
        assert seen
        assert not any(seen)  # off inside the episodes
    finally:
        gc.enable()
        env.close()
