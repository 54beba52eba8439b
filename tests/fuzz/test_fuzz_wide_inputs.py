"""Fuzzing wide inputs: random float boxes of 1 to 200 dimensions, some unbounded, handed to
the general preset and to hostile presplit settings (issue 9, part 17).

Every case's outcome is asserted. The general preset builds on any box of at most 64
dimensions (what an agent file holds), with 2^d leaves up to 8 dimensions and 2^4 beyond (the
first 4 split once each, an unbounded one at 0); it learns a few episodes, saves and loads to
the same greedy actions. A wider box is refused by every agent, naming the limit, before
anything is sized. A presplit that would start with more than 2^16 leaves is refused by name.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent import AdaptiveQAgent, TileCodingAgent, TreeConfig, preset
from agent.partition_tree import PartitionTree
from agent.tree_ensemble import tree_agent_class


class WideEnv(gym.Env[Any, int]):
    """Observations drawn from a fixed random box (unbounded dimensions drawn from a normal);
    an episode is 4 steps, reward -1 a step and +2 on the last."""

    def __init__(self, box: spaces.Box) -> None:
        self.observation_space = box
        self.action_space = spaces.Discrete(3)
        self._t = 0

    def _obs(self) -> np.ndarray:
        low, high = self.observation_space.low, self.observation_space.high
        finite = np.isfinite(low) & np.isfinite(high)
        draw = self.np_random.normal(size=low.shape) * 3.0
        inside = low + self.np_random.random(low.shape) * np.where(finite, high - low, 0.0)
        return np.where(finite, inside, draw).astype(self.observation_space.dtype)

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None) -> Any:
        super().reset(seed=seed)
        self._t = 0
        return self._obs(), {}

    def step(self, action: int) -> Any:
        self._t += 1
        done = self._t >= 4
        return self._obs(), 2.0 if done else -1.0, done, False, {}


def random_box(rng: np.random.Generator) -> spaces.Box:
    dims = int(rng.choice([1, 2, 5, 8, 9, 16, 17, 38, 64, 200]))
    low = rng.uniform(-100.0, 100.0, dims)
    high = low + rng.uniform(1e-3, 50.0, dims)
    free = rng.random(dims) < 0.2
    low[free], high[free] = -np.inf, np.inf
    return spaces.Box(low, high, dtype=np.float64)


@pytest.mark.parametrize("case", range(24))
def test_the_general_preset_takes_any_wide_box(case: int, tmp_path: Path) -> None:
    rng = np.random.default_rng(1700 + case)
    box = random_box(rng)
    dims = box.shape[0]
    config = preset("general").config
    make = tree_agent_class(config)
    if dims > 64:
        for build in (
            lambda: make(box, spaces.Discrete(3), "adaptive+tabu", case, config),
            lambda: TileCodingAgent(box, spaces.Discrete(3), case),
            lambda: AdaptiveQAgent(box, spaces.Discrete(3), case),
        ):
            with pytest.raises(ValueError, match=rf"has {dims} dimensions, at most 64"):
                build()
        return
    agent = make(box, spaces.Discrete(3), "adaptive+tabu", case, config)
    presplit = dims if dims <= 8 else 4
    assert agent.n_leaves == 2**presplit
    env = WideEnv(box)
    agent.learn(env, 3, reset_seed=case)
    loaded = type(agent).load(agent.save(tmp_path / "wide"))
    for _ in range(5):
        obs, _ = env.reset(seed=int(rng.integers(1 << 30)))
        assert loaded.predict(obs) == agent.predict(obs)


@pytest.mark.parametrize("case", range(12))
def test_a_presplit_beyond_two_to_the_sixteen_is_refused_by_name(case: int) -> None:
    rng = np.random.default_rng(1750 + case)
    dims = int(rng.integers(17, 300))
    limit = rng.choice([None, int(rng.integers(17, 40))])
    if limit is None:
        config = TreeConfig(presplit_each_dimension=True)
    else:  # a limit above 16 is itself refused
        with pytest.raises(ValueError, match="presplit_max_dimensions"):
            TreeConfig(presplit_each_dimension=True, presplit_max_dimensions=int(limit))
        return
    depth = int(rng.integers(0, 5))
    config = dataclasses.replace(config, initial_depth=depth)
    with pytest.raises(ValueError, match=rf"2\^{dims + depth} leaves.*presplit_max_dimensions"):
        PartitionTree([0.0] * dims, [1.0] * dims, config)
