"""Every agent's ``learn`` refuses a bad episode count or a mismatched action space by name
(one shared check, ``agent.episode_stats.check_learn_arguments``)."""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import pytest

from agent import AdaptiveQAgent, TileCodingAgent, preset


def _agents(env: gym.Env) -> list[Any]:
    space, actions = env.observation_space, env.action_space
    return [
        preset("paper").agent(space, actions, 0),
        preset("general").agent(space, actions, 0),
        AdaptiveQAgent(space, actions, 0),
        TileCodingAgent(space, actions, 0),
    ]


@pytest.mark.parametrize("episodes", [True, -1, 2.0, "3", None])
def test_a_bad_episode_count_is_refused_by_every_agent(episodes: object) -> None:
    env = gym.make("MountainCar-v0")
    for agent in _agents(env):
        with pytest.raises(ValueError, match=r"episodes must be an int >= 0, got "):
            agent.learn(env, episodes)
    env.close()


def test_an_env_with_other_actions_is_refused_by_every_agent() -> None:
    env, other = gym.make("MountainCar-v0"), gym.make("CartPole-v1")
    for agent in _agents(env):
        with pytest.raises(ValueError, match="does not match the agent's 3 actions"):
            agent.learn(other, 1)
        assert agent.learn(env, 0) == []
    env.close()
    other.close()
