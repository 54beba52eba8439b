"""Unbounded observation dimensions: grown from the data, no bounds needed (CartPole)."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent import TreeAgent, TreeConfig, preset


def test_cartpole_default_constructor_and_learning() -> None:
    env = gym.make("CartPole-v1")
    agent = preset("general").agent(env.observation_space, env.action_space, seed=0)
    low, high = agent.bounds
    assert low[1] == -math.inf
    assert high[3] == math.inf
    agent.learn(env, 40, reset_seed=0)
    seen_low, seen_high = agent.partition.seen_bounds
    assert math.isfinite(seen_low[1])
    assert seen_low[1] < 0.0 < seen_high[1]
    assert seen_low[0] == math.inf  # bounded dimensions keep their declared box
    for leaf in agent.partition.leaves():
        a, b = agent.partition.leaf_bounds(leaf)
        for d in (1, 3):  # every split of a velocity lies inside the data seen
            for edge in (a[d], b[d]):
                assert not math.isfinite(edge) or seen_low[d] <= edge <= seen_high[d]
    assert agent.n_leaves > 1


def test_unbounded_tree_splits_inside_the_data() -> None:
    space = spaces.Box(-np.inf, np.inf, shape=(1,))
    agent = TreeAgent(space, spaces.Discrete(2), "greedy", config=TreeConfig(split_min_samples=4))
    xs = [[-3.0], [-2.0], [2.0], [3.0]]
    children = agent.partition.record(0, xs, [1.0, 1.0, -1.0, -1.0])
    assert children is not None
    value = agent.partition._threshold[0]
    assert -3.0 < value < 3.0
    assert agent.partition.seen_bounds == ([-3.0], [3.0])


def test_presplit_root_splits_unbounded_dimensions_at_zero_once() -> None:
    space = spaces.Box(
        np.array([0.0, -np.inf], dtype=np.float32), np.array([1.0, np.inf], dtype=np.float32)
    )
    agent = TreeAgent(space, spaces.Discrete(2), "greedy", config=TreeConfig(initial_depth=3))
    boxes = sorted(agent.partition.leaf_bounds(leaf) for leaf in agent.partition.leaves())
    assert len(boxes) == 8
    assert sorted({b[0][0] for b in boxes}) == [0.0, 0.25, 0.5, 0.75]
    assert sorted({b[0][1] for b in boxes}) == [-math.inf, 0.0]


@pytest.mark.parametrize(
    "bounds",
    [
        ([0.0, np.nan], [1.0, 1.0]),
        ([0.0, 1.0], [1.0, 1.0]),
    ],
)
def test_bad_bounds_are_refused(bounds: tuple) -> None:
    space = spaces.Box(-np.inf, np.inf, shape=(2,))
    with pytest.raises(ValueError, match="bounds"):
        TreeAgent(space, spaces.Discrete(2), bounds=bounds)
