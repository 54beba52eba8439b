"""Every agent's ``learn`` refuses a bad episode count, callback, reset seed or a mismatched
action space by name (one shared check, ``agent.episode_stats.check_learn_arguments``), and its
``predict`` a ``deterministic`` that is not a bool (``agent.env_checks.deterministic_flag``)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.envs.classic_control import CartPoleEnv


@pytest.mark.parametrize("episodes", [True, -1, 2.0, "3", None])
def test_a_bad_episode_count_is_refused_by_every_agent(
    episodes: object, every_agent_kind: Callable[..., list[Any]]
) -> None:
    env = gym.make("MountainCar-v0")
    for agent in every_agent_kind(env.observation_space, env.action_space):
        with pytest.raises(ValueError, match=r"episodes must be an int >= 0, got "):
            agent.learn(env, episodes)
    env.close()


class FromOne(gym.Env):
    """Two actions numbered 1 and 2, which it reads as ``action - 1``: the agent's 0 would be
    read as action -1, silently."""

    observation_space = gym.spaces.Box(-1.0, 1.0, (2,), np.float32)
    action_space = gym.spaces.Discrete(2, start=1)

    def reset(self, seed: int | None = None, options: dict | None = None) -> tuple:
        super().reset(seed=seed)
        return np.zeros(2, np.float32), {}

    def step(self, action: int) -> tuple:
        return np.zeros(2, np.float32), float(action - 1), True, False, {}


def test_an_env_whose_actions_start_elsewhere_is_refused_by_every_agent(
    every_agent_kind: Callable[..., list[Any]],
) -> None:
    """An agent built for ``Discrete(2)`` sends 0 and 1; an env numbered from 1 has the same
    count, so the count alone let it through."""
    env = FromOne()
    for agent in every_agent_kind(env.observation_space, gym.spaces.Discrete(2)):
        with pytest.raises(
            ValueError,
            match=r"env.action_space Discrete\(2, start=1\) starts at 1, but the agent's "
            r"actions are 0 \.\. 1: .* agent.adapt_env\(env\) renumbers it",
        ):
            agent.learn(env, 1)


@pytest.mark.parametrize(
    ("env", "message"),
    [
        ("CartPole-v1", r"got the string 'CartPole-v1'; make it first, gymnasium.make\("),
        (CartPoleEnv, r"got the class CartPoleEnv; pass an instance"),
        (None, r"with reset\(\) and step\(\), got None \(NoneType\)"),
        (object(), r"with reset\(\) and step\(\), got <object object"),
    ],
)
def test_what_is_not_one_env_is_refused_by_every_agent(
    env: object, message: str, every_agent_kind: Callable[..., list[Any]]
) -> None:
    space = gym.make("CartPole-v1")
    for agent in every_agent_kind(space.observation_space, space.action_space):
        with pytest.raises(ValueError, match=r"env must be a Gymnasium env.*" + message):
            agent.learn(env, 1)


def test_a_vector_env_is_refused_by_every_agent(
    every_agent_kind: Callable[..., list[Any]],
) -> None:
    vector = gym.make_vec("CartPole-v1", num_envs=2, vectorization_mode="sync")
    single = gym.make("CartPole-v1")
    for agent in every_agent_kind(single.observation_space, single.action_space):
        with pytest.raises(ValueError, match=r"env is a vector env of 2 copies \(SyncVectorEnv\)"):
            agent.learn(vector, 1)
    vector.close()


def test_an_env_with_other_actions_is_refused_by_every_agent(
    every_agent_kind: Callable[..., list[Any]],
) -> None:
    env, other = gym.make("MountainCar-v0"), gym.make("CartPole-v1")
    for agent in every_agent_kind(env.observation_space, env.action_space):
        with pytest.raises(ValueError, match="does not match the agent's 3 actions"):
            agent.learn(other, 1)
        assert agent.learn(env, 0) == []
    env.close()
    other.close()


@pytest.mark.parametrize("callback", [5, "print", [print]])
def test_a_callback_that_cannot_be_called_is_refused_before_any_episode(
    callback: object, every_agent_kind: Callable[..., list[Any]]
) -> None:
    """A callback of 5 used to fail after the first episode with "cannot unpack
    non-iterable NoneType object"."""
    env = gym.make("MountainCar-v0")
    for agent in every_agent_kind(env.observation_space, env.action_space):
        with pytest.raises(ValueError, match=r"callback must be None or callable, got "):
            agent.learn(env, 2, callback=callback)
        assert agent.learn(env, 0) == []
    env.close()


@pytest.mark.parametrize("reset_seed", [-1, True, 2.5, "7", np.int64(3)])
def test_a_bad_reset_seed_is_refused_by_name(
    reset_seed: object, every_agent_kind: Callable[..., list[Any]]
) -> None:
    """Gymnasium's own refusal ("Seed must be a python integer") does not say which argument."""
    env = gym.make("MountainCar-v0")
    for agent in every_agent_kind(env.observation_space, env.action_space):
        with pytest.raises(ValueError, match=r"reset_seed must be None or an int >= 0, got "):
            agent.learn(env, 1, reset_seed=reset_seed)
    env.close()


@pytest.mark.parametrize("deterministic", [-1, 2.5, "no", None, [True]])
def test_predict_refuses_a_deterministic_that_is_not_a_bool(
    deterministic: object, every_agent_kind: Callable[..., list[Any]]
) -> None:
    env = gym.make("MountainCar-v0")
    obs, _ = env.reset(seed=0)
    for agent in every_agent_kind(env.observation_space, env.action_space):
        with pytest.raises(ValueError, match=r"deterministic must be True or False, got "):
            agent.predict(obs, deterministic=deterministic)
        assert agent.predict(obs, deterministic=np.bool_(True)) == agent.predict(obs)
    env.close()
