"""The general preset's discount gated on failure (``TreeConfig.failure_gamma``, issue 9 part 19)
on real Gymnasium tasks: the latch opens where the episode ends in a failure and stays shut
where it ends at a goal. The toy cases, to the number, are in test_tree_ensemble.py."""

from __future__ import annotations

import gymnasium as gym

from agent import preset
from agent.tree_ensemble import TreeEnsembleAgent


def _latched_by(task: str, episodes: int, seed: int = 0) -> tuple[int | None, TreeEnsembleAgent]:
    """The episode at whose start the latch opened (None: not within ``episodes``)."""
    env = gym.make(task)
    agent = preset("general").agent(env.observation_space, env.action_space, seed)
    assert isinstance(agent, TreeEnsembleAgent)
    for episode in range(episodes):
        agent.learn(env, 1, reset_seed=seed + episode)
        if agent.failure_discount:
            return episode, agent
    return None, agent


def test_cartpoles_fall_opens_the_latch() -> None:
    opened, agent = _latched_by("CartPole-v1", 100)
    assert opened is not None
    assert agent.terminals_fail
    assert agent.discount == agent.config.failure_gamma == 0.9995
    assert agent.config.gamma == 0.999  # the config itself is unchanged


def test_mountain_cars_goal_keeps_the_latch_shut() -> None:
    opened, agent = _latched_by("MountainCar-v0", 60)
    assert opened is None
    assert agent.terminals_seen > 0  # the flag was reached (11 times on seed 0)
    assert agent.terminal_reward_sum / agent.terminals_seen == -1.0
    assert agent.target_sum / agent.targets < -1.0  # going on costs more than the goal's -1
    assert agent.discount == 0.999
