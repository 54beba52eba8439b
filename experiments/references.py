"""Reference returns of Gymnasium tasks, for scores normalised across tasks.

A return task's normalised score is ``(return - random) / (solved - random)``: 0 is the return of
a uniformly random policy, 1 the task's solved threshold (the human-normalised score of the
Atari benchmarks, with the solved threshold in place of the human's score; Agarwal et al.,
"Deep Reinforcement Learning at the Edge of the Statistical Precipice", NeurIPS 2021, aggregate
such scores).

- **Solved thresholds** are Gymnasium's own ``reward_threshold`` registrations (``CartPole-v1``
  475, ``MountainCar-v0`` -110, ``Acrobot-v1`` -100), read from the registry, not copied here.
- **Random-policy returns** were measured with :func:`random_policy_return` (1,000 episodes,
  seed 0, the id's registered time limit): :data:`RANDOM_RETURNS`, with their standard errors.

Both hold only at the id's registered time limit (a random MountainCar run returns minus its
cap); at another cap, or for another id, an experiment gives ``random_return`` and
``solved_return`` in the task's table.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

RANDOM_EPISODES = 1000
"""Episodes behind each entry of :data:`RANDOM_RETURNS`."""


@dataclass(frozen=True)
class RandomReturn:
    """The mean return of a uniformly random policy at the id's registered time limit."""

    mean: float
    standard_error: float
    max_episode_steps: int


RANDOM_RETURNS = {
    "CartPole-v1": RandomReturn(22.546, 0.3811, 500),
    "MountainCar-v0": RandomReturn(-200.0, 0.0, 200),
    "Acrobot-v1": RandomReturn(-499.326, 0.2899, 500),
}
"""Measured with ``random_policy_return(id, 1000, seed=0)`` (gymnasium 1.4.0)."""


@dataclass(frozen=True)
class References:
    """The two ends of a return task's normalised score."""

    random_return: float
    solved_return: float
    source: str
    """Where the two values came from (for the report)."""


def default_references(env_id: str, max_episode_steps: int) -> References | None:
    """The references of a Gymnasium task at its registered time limit (None if unknown)."""
    from gymnasium.envs.registration import registry

    known = RANDOM_RETURNS.get(env_id)
    spec = registry.get(env_id)
    if known is None or spec is None or spec.reward_threshold is None:
        return None
    if max_episode_steps != known.max_episode_steps or spec.max_episode_steps != max_episode_steps:
        return None
    return References(
        known.mean,
        float(spec.reward_threshold),
        f"random policy {known.mean:g} (mean of {RANDOM_EPISODES:,} episodes, "
        f"experiments/references.py); solved {spec.reward_threshold:g} (Gymnasium's "
        "reward_threshold)",
    )


def random_policy_return(
    env_id: str,
    episodes: int,
    seed: int = 0,
    max_episode_steps: int | None = None,
    action_bins: int | None = None,
) -> tuple[float, float]:
    """Mean return and its standard error of ``episodes`` episodes of uniformly random actions
    (the actions and the first reset drawn from generators seeded with ``seed``), at the id's
    registered time limit or ``max_episode_steps``, through ``agent.adapt_env`` (a Box action
    is a grid of ``action_bins`` values a dimension, 5 by default), as the harness runs it."""
    import gymnasium as gym

    from agent import adapt_env

    env = adapt_env(gym.make(env_id, max_episode_steps=max_episode_steps), action_bins)
    try:
        rng = np.random.default_rng(seed)
        returns = []
        for episode in range(episodes):
            env.reset(seed=seed if episode == 0 else None)
            total, done = 0.0, False
            while not done:
                action = int(rng.integers(env.action_space.n))  # type: ignore[attr-defined]
                _, reward, terminated, truncated, _ = env.step(action)
                total += float(reward)
                done = terminated or truncated
            returns.append(total)
    finally:
        env.close()
    values = np.asarray(returns)
    error = float(values.std(ddof=1) / np.sqrt(values.size)) if values.size > 1 else 0.0
    return float(values.mean()), error
