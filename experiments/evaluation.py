"""Greedy episodes of a trained agent: the evaluation behind ``run.py evaluate`` and ``render``."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from agent.env_checks import checked_reward


@dataclass(frozen=True)
class Episode:
    """One greedy episode."""

    steps: int
    episode_return: float
    success: bool
    truncated: bool
    collisions: int
    positions: np.ndarray
    """Robot (x, y) at every step, the reset position first: (steps + 1) x 2."""
    tipped: bool = False
    """The robot had tipped over by the end (a dynamic maze env's ``info["tipped"]``)."""


@dataclass(frozen=True)
class Evaluation:
    """Greedy episodes of an agent, with their summary."""

    episodes: tuple[Episode, ...]

    @property
    def success_rate(self) -> float:
        """Fraction of episodes that reached the goal."""
        return float(np.mean([e.success for e in self.episodes]))

    @property
    def steps(self) -> np.ndarray:
        """Steps of each episode (a capped episode counts its cap)."""
        return np.array([e.steps for e in self.episodes])

    @property
    def tipped(self) -> int:
        """Episodes that ended with the robot tipped over."""
        return sum(e.tipped for e in self.episodes)

    @property
    def successful_steps(self) -> np.ndarray:
        """Steps of the episodes that reached the goal."""
        return np.array([e.steps for e in self.episodes if e.success])


def greedy_episode(
    env: Any, agent: Any, seed: int | None = None, collision_key: str = "collision"
) -> Episode:
    """Run ``agent.predict(obs, deterministic=True)`` until the episode ends (a reward that is
    not a finite number is a ValueError naming the step, as in training:
    :func:`agent.env_checks.checked_reward`)."""
    obs, _ = env.reset(seed=seed)
    positions = [np.asarray(obs, dtype=float)[:2].copy()]
    steps, total, collisions = 0, 0.0, 0
    success = truncated = False
    while True:
        obs, reward, terminated, truncated, info = env.step(agent.predict(obs))
        steps += 1
        total += checked_reward(reward, f"env.step (step {steps} of a greedy episode)")
        collisions += bool(info.get(collision_key, False))
        positions.append(np.asarray(obs, dtype=float)[:2].copy())
        if terminated or truncated:
            success = bool(info.get("is_success", terminated))
            break
    # cut by the time limit only: an episode that ends on its last allowed step is not
    # "truncated" (the learner's episode statistics count it the same way)
    cut = bool(truncated) and not terminated
    tipped = bool(info.get("tipped", False))
    return Episode(steps, total, success, cut, collisions, np.array(positions), tipped)


def evaluate(env: Any, agent: Any, episodes: int, seed: int = 0) -> Evaluation:
    """``episodes`` greedy episodes; the first reset is seeded, so the whole set repeats."""
    return Evaluation(
        tuple(greedy_episode(env, agent, seed if i == 0 else None) for i in range(episodes))
    )
