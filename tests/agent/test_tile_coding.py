"""The tile-coding baseline: the tiles, one Sarsa(lambda) step by hand, learning, bad input."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent.tile_coding import TileCoder, TileCodingAgent


def test_offset_tilings_by_hand() -> None:
    # [0, 1], 2 tilings of 2 tiles: tile width 0.5, tiling 1 shifted by half a tile
    coder = TileCoder([0.0], [1.0], tilings=2, tiles=2, max_features=16)
    assert coder.features([0.3]) == [0, 1]  # 0.6 -> tile 0; 0.6 + 0.5 -> tile 1
    assert coder.features([0.6]) == [2, 1]  # 1.2 -> tile 1 (new); 1.7 -> tile 1 again
    assert coder.features([0.3]) == [0, 1]
    assert coder.features([0.9], allocate=False) == [2]  # 2.3 -> tile 2 of tiling 1: unseen
    # 2-D: displacement (1, 3) / tilings per tiling
    coder2 = TileCoder([0.0, 0.0], [1.0, 1.0], tilings=4, tiles=4, max_features=64)
    assert coder2.offsets == [[0.0, 0.0], [0.25, 0.75], [0.5, 0.5], [0.75, 0.25]]
    full = TileCoder([0.0], [1.0], 1, 4, max_features=1)
    full.features([0.1])
    with pytest.raises(ValueError, match="tile table full"):
        full.features([0.9])


class OneStep(gym.Env[np.ndarray, int]):
    observation_space = spaces.Box(0.0, 1.0, shape=(1,))
    action_space = spaces.Discrete(2)

    def reset(self, *, seed: int | None = None, options: Any = None) -> tuple[np.ndarray, dict]:
        super().reset(seed=seed)
        return np.array([0.3]), {}

    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict]:
        return np.array([0.3]), 1.0, True, False, {}


def test_one_terminal_step_by_hand() -> None:
    env = OneStep()
    agent = TileCodingAgent(env.observation_space, env.action_space, tilings=2, tiles=2)
    [stats] = agent.learn(env, 1)
    # delta = 1 - 0; each of the 2 active weights of the action += (0.5 / 2) * 1
    acted = int(np.argmax(agent.weights.sum(axis=1)))
    assert agent.weights[acted, :2].tolist() == [0.25, 0.25]
    assert agent.q_values([0.3])[acted] == 0.5
    assert agent.predict([0.3]) == acted
    assert stats.steps == 1
    assert stats.success


def test_learns_the_corridor_and_repeats_itself(make_corridor: Callable[..., Any]) -> None:
    def train(seed: int) -> list[int]:
        env = make_corridor()
        agent = TileCodingAgent(env.observation_space, env.action_space, seed=seed, tiles=4)
        return [s.steps for s in agent.learn(env, 40, reset_seed=seed)]

    steps = train(0)
    assert steps == train(0)
    assert np.mean(steps[-10:]) < 20 < np.mean(steps[:5])


def test_unbounded_dimensions_are_squashed() -> None:
    env = gym.make("CartPole-v1")
    agent = TileCodingAgent(env.observation_space, env.action_space, seed=1)
    assert agent.coder.unbounded == [False, True, False, True]
    agent.learn(env, 3, reset_seed=1)
    assert agent.n_leaves > 8
    arrays, meta = agent.state()
    copy = TileCodingAgent(env.observation_space, env.action_space, **meta["params"])
    copy.restore(arrays, meta)
    obs, _ = env.reset(seed=3)
    assert copy.q_values(obs) == agent.q_values(obs)


@pytest.mark.parametrize(
    ("kwargs", "error"),
    [
        ({"tilings": 0}, ValueError),
        ({"tiles": 2.5}, ValueError),
        ({"alpha": 0.0}, ValueError),
        ({"lam": 1.5}, ValueError),
        ({"epsilon": True}, TypeError),
        ({"max_features": 1 << 30}, ValueError),
        ({"seed": "0"}, TypeError),
        ({"bounds": ([0.0, 0.0], [np.inf, 1.0])}, ValueError),
    ],
)
def test_bad_arguments_are_named(kwargs: dict, error: type) -> None:
    box = spaces.Box(0.0, 1.0, shape=(2,))
    with pytest.raises(error):
        TileCodingAgent(box, spaces.Discrete(2), **kwargs)
