"""Every agent's ``learn`` refuses a bad episode count, callback, reset seed or a mismatched
action space by name (one shared check, ``agent.episode_stats.check_learn_arguments``), and its
``predict`` a ``deterministic`` that is not a bool (``agent.env_checks.deterministic_flag``)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import gymnasium as gym
import numpy as np
import pytest


@pytest.mark.parametrize("episodes", [True, -1, 2.0, "3", None])
def test_a_bad_episode_count_is_refused_by_every_agent(
    episodes: object, every_agent_kind: Callable[..., list[Any]]
) -> None:
    env = gym.make("MountainCar-v0")
    for agent in every_agent_kind(env.observation_space, env.action_space):
        with pytest.raises(ValueError, match=r"episodes must be an int >= 0, got "):
            agent.learn(env, episodes)
    env.close()


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
