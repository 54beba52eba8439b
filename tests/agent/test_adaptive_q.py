"""The adaptive Q-learning baseline (Sinclair, Banerjee and Yu 2019), by hand and learning."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent.adaptive_q import AdaptiveQAgent, BoxTree


def test_box_tree_splits_into_halves_that_inherit() -> None:
    tree = BoxTree([0.0, 0.0], [2.0, 4.0], value=7.0, max_depth=3)
    tree.visits[0] = 5
    tree.split(0)
    assert tree.n_leaves == 4
    # child index bit d set = upper half of dimension d
    assert tree.leaf_of([1.5, 1.0]) == 2  # x high, y low: index 0b01 -> first + 1
    assert (tree.low[2], tree.high[2]) == ([1.0, 0.0], [2.0, 2.0])
    assert tree.q[1:] == [7.0] * 4
    assert tree.visits[1:] == [5] * 4


def test_one_update_by_hand() -> None:
    box = spaces.Box(0.0, 1.0, shape=(1,))
    agent = AdaptiveQAgent(box, spaces.Discrete(2), gamma=0.5, r_max=1.0, bonus_scale=0.5)
    # H = 2, V_max = 2. First visit: t = 1, rate (H + 1) / (H + 1) = 1,
    # target = r + gamma * min(V_max, V') + bonus_scale * range / sqrt(1)
    agent.update([0.25], 1, 0.5, next_value=3.0)
    tree = agent.trees[1]
    assert tree.n_leaves == 2  # t = 1 >= 4^0: split at once, children inherit
    assert tree.q[tree.leaf_of([0.25])] == pytest.approx(0.5 + 0.5 * 2.0 + 0.5)
    assert agent.trees[0].q[0] == 2.0  # untouched action: V_max
    # second visit of the lower child: t = 2, rate 3 / 4
    agent.update([0.25], 1, 0.0, next_value=0.0)
    leaf = tree.leaf_of([0.25])
    bonus = 0.5 / np.sqrt(2)
    assert tree.q[leaf] == pytest.approx(0.25 * 2.0 + 0.75 * (0.0 + bonus))


def test_explores_the_corridor_reproducibly(make_corridor: Callable[..., Any]) -> None:
    def train() -> tuple[AdaptiveQAgent, list[int]]:
        env = make_corridor()
        agent = AdaptiveQAgent(
            env.observation_space, env.action_space, seed=0, gamma=0.9, r_max=5.0, reward_range=6.0
        )
        return agent, [s.steps for s in agent.learn(env, 30, reset_seed=0)]

    agent, steps = train()
    assert steps == train()[1]
    assert min(steps) < 200  # the optimism reaches the goal
    assert agent.n_leaves > 100  # and refines where it went
    arrays, meta = agent.state()
    copy = AdaptiveQAgent(agent.observation_space, agent.action_space, **meta["params"])
    copy.restore(arrays, meta)
    assert copy.predict([0.3, 0.3]) == agent.predict([0.3, 0.3])
    assert copy.n_leaves == agent.n_leaves


def test_cartpole_default_constructor() -> None:
    env = gym.make("CartPole-v1")
    agent = AdaptiveQAgent(env.observation_space, env.action_space, seed=0)
    assert agent.unbounded == [False, True, False, True]
    assert len(agent.learn(env, 2, reset_seed=0)) == 2


@pytest.mark.parametrize(
    ("kwargs", "error"),
    [
        ({"gamma": 1.0}, ValueError),
        ({"reward_range": 0.0}, ValueError),
        ({"bonus_scale": float("nan")}, ValueError),
        ({"r_max": "1"}, TypeError),
        ({"max_depth": -1}, ValueError),
        ({"max_boxes": 0}, ValueError),
    ],
)
def test_bad_arguments_are_named(kwargs: dict, error: type) -> None:
    box = spaces.Box(0.0, 1.0, shape=(2,))
    with pytest.raises(error, match="AdaptiveQAgent"):
        AdaptiveQAgent(box, spaces.Discrete(2), **kwargs)
