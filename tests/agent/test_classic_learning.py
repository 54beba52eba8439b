"""Short learning checks on the classic tasks: the general preset learns, the paper's does not.

Not timed tests and not the issue's targets (those are experiments: docs/results.md, "A
learner that is fast everywhere"): a few seconds of training each, enough to show that the
measured units let the tree split and learn where Table I's reward units leave it at the root
or lost. Each is deterministic for its seed.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

from agent import preset


def greedy_returns(agent: object, env: gym.Env, episodes: int, seed: int) -> list[float]:
    """Returns of greedy episodes, reset with seeds ``10^6 + 1000 seed + i``."""
    out = []
    for i in range(episodes):
        obs, _ = env.reset(seed=1_000_000 + 1000 * seed + i)
        total, done = 0.0, False
        while not done:
            action = agent.predict(obs)  # type: ignore[attr-defined]
            obs, reward, terminated, truncated, _ = env.step(action)
            total += float(reward)
            done = terminated or truncated
        out.append(total)
    return out


def greedy_after(task: str, name: str, episodes: int, seed: int) -> tuple[float, int]:
    env = gym.make(task)
    agent = preset(name).agent(env.observation_space, env.action_space, seed)
    agent.learn(env, episodes, reset_seed=seed)
    score = float(np.mean(greedy_returns(agent, env, 3, seed)))
    env.close()
    return score, agent.n_leaves


@pytest.mark.parametrize(
    ("task", "episodes", "seed", "general_at_least", "paper_at_most"),
    [
        # the paper's tree never reaches the flag. 200 episodes since part 27: after 150, seed
        # 0's early greedy policy missed the flag (-200; seeds 1-4 -112, -111, -167, -160,
        # against part 25's choice's -105, -113, -167, -159); after 200 it scores -124
        ("MountainCar-v0", 200, 0, -180.0, -200.0),
        ("CartPole-v1", 250, 0, 120.0, 60.0),
        # 100 episodes since part 25: after 40, seed 0's early greedy policy missed the top
        # (-500; seeds 1-3 -371, -287, -459, against part 24's choice's -389, -321, -500)
        ("Acrobot-v1", 100, 0, -420.0, -500.0),  # -271 (part 24's choice: -247 over 5)
    ],
)
def test_general_preset_learns_where_the_paper_preset_does_not(
    task: str, episodes: int, seed: int, general_at_least: float, paper_at_most: float
) -> None:
    general, general_leaves = greedy_after(task, "general", episodes, seed)
    paper, paper_leaves = greedy_after(task, "paper", episodes, seed)
    assert general >= general_at_least
    assert paper <= paper_at_most
    assert general_leaves > 4 * paper_leaves
