"""Fuzzing integer inputs: random discrete observation spaces through ``agent.adapt_env``, and
hostile integer boxes handed to the agent directly (issue 9, part 15).

Every case's outcome is asserted. A discrete space of any shape becomes an integer box that
passes Gymnasium's checker; the general preset's tree is one leaf per cell when the cells fit
``table_cells`` (and every sampled observation lands in the leaf of its own cell); the agent
learns a few episodes, saves and loads. A box the agents cannot take is refused by name.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces
from gymnasium.utils.env_checker import check_env

from agent import adapt_env, preset
from agent.spaces import observation_bounds
from agent.tree_ensemble import tree_agent_class


class RandomEnv(gym.Env[Any, int]):
    """Observations sampled from ``observation_space``; an episode is 3 steps, reward 1 on
    the last (so the optimism of the general preset has a positive return to read)."""

    def __init__(self, observation_space: spaces.Space) -> None:
        self.observation_space = observation_space
        self.action_space = spaces.Discrete(3)
        self._t = 0

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None) -> Any:
        super().reset(seed=seed)
        self.observation_space.seed(seed)
        self._t = 0
        return self.observation_space.sample(), {}

    def step(self, action: int) -> Any:
        self._t += 1
        done = self._t >= 3
        return self.observation_space.sample(), float(done), done, False, {}


def random_discrete_space(rng: np.random.Generator, depth: int = 0) -> spaces.Space:
    kind = int(rng.integers(5 if depth < 2 else 3))
    seed = int(rng.integers(1 << 30))
    if kind == 0:
        return spaces.Discrete(int(rng.integers(1, 40)), start=int(rng.integers(-5, 6)), seed=seed)
    if kind == 1:
        nvec = rng.integers(1, 6, size=int(rng.integers(1, 4)))
        return spaces.MultiDiscrete(nvec, start=rng.integers(-3, 4, size=nvec.shape), seed=seed)
    if kind == 2:
        return spaces.MultiBinary(int(rng.integers(1, 4)), seed=seed)
    parts = [random_discrete_space(rng, depth + 1) for _ in range(int(rng.integers(1, 4)))]
    if kind == 3:
        return spaces.Tuple(parts, seed=seed)
    return spaces.Dict({f"k{i}": part for i, part in enumerate(parts)}, seed=seed)


@pytest.mark.parametrize("case", range(40))
def test_any_discrete_observation_becomes_a_table_of_its_cells(case: int, tmp_path: Path) -> None:
    rng = np.random.default_rng(1500 + case)
    source = random_discrete_space(rng)
    env = adapt_env(RandomEnv(source))
    box = env.observation_space
    assert isinstance(box, spaces.Box)
    assert box.dtype == np.int64
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the checker's note that env is wrapped
        check_env(env, skip_render_check=True)
    cells = math.prod(int(h - lo + 1) for lo, h in zip(box.low, box.high, strict=True))
    budget = int(rng.choice([1, 7, 64, 16384]))
    config = dataclasses.replace(preset("general").config, table_cells=budget)
    agent = tree_agent_class(config)(env.observation_space, env.action_space, "tabu", case, config)
    if cells <= budget:
        assert agent.n_leaves == cells, (source, cells)
        low, high = observation_bounds(box, None)
        assert low == [float(v) - 0.5 for v in box.low]
        assert high == [float(v) + 0.5 for v in box.high]
        for _ in range(20):
            x = env.observation(source.sample())
            leaf = agent.partition.leaf_of([float(v) for v in x])
            leaf_low, leaf_high = agent.partition.leaf_bounds(leaf)
            assert all(lo < v < h for v, lo, h in zip(x.tolist(), leaf_low, leaf_high, strict=True))
            assert all(h - lo == 1.0 for lo, h in zip(leaf_low, leaf_high, strict=True))
    else:
        dims = len(box.low)  # the presplit, once per dimension, limited beyond the preset's cap
        limit, beyond = config.presplit_max_dimensions, config.presplit_beyond_dimensions
        assert limit is not None
        assert agent.n_leaves == 2 ** (dims if dims <= limit else beyond)
    history = agent.learn(env, 4, reset_seed=case)
    assert len(history) == 4
    again = type(agent).load(agent.save(tmp_path / "agent"))
    obs, _ = env.reset(seed=case)
    assert again.predict(obs) == agent.predict(obs)


@pytest.mark.parametrize(
    ("box", "defect"),
    [
        (spaces.Box(0, 3, (2, 2), dtype=np.int64), "must be one-dimensional"),
        (spaces.Box(0, 3, (0,), dtype=np.int64), "observation_space has no dimensions"),
        (spaces.Box(0.0, 1.0, (0,)), "observation_space has no dimensions"),
    ],
)
def test_integer_boxes_the_agents_cannot_take_are_refused_by_name(
    box: spaces.Box, defect: str
) -> None:
    with pytest.raises((ValueError, TypeError), match=defect):
        preset("general").agent(box, spaces.Discrete(2))


def test_a_huge_integer_box_is_no_table_and_still_learns() -> None:
    """2^40 cells (two int64 dimensions of a million values each): no table, no crash."""
    box = spaces.Box(0, 1 << 20, (2,), dtype=np.int64)
    env = RandomEnv(box)
    agent = preset("general").agent(box, env.action_space, seed=0)
    assert agent.n_leaves == 4
    assert len(agent.learn(env, 3, reset_seed=0)) == 3
