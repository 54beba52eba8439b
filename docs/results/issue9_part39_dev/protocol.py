"""Part 39 dev: the classic protocol the part's scripts share (part 30's).

Training from reset seed = agent seed; then 20 greedy episodes from reset seeds
10^6 + 1,000 seed + i.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

GREEDY_EPISODES = 20


def reset_seed(seed: int, i: int) -> int:
    """The reset seed of greedy episode ``i`` of the run with agent seed ``seed``."""
    return 1_000_000 + 1000 * seed + i


def greedy_episodes(
    env: Any, act: Callable[[Any], int], seed: int
) -> tuple[list[float], list[int]]:
    """The return and the length of each of the run's greedy episodes, ``act(obs)`` choosing."""
    returns, lengths = [], []
    for i in range(GREEDY_EPISODES):
        obs, _ = env.reset(seed=reset_seed(seed, i))
        total, steps, done = 0.0, 0, False
        while not done:
            obs, reward, term, trunc, _ = env.step(act(obs))
            total += float(reward)
            steps += 1
            done = term or trunc
        returns.append(total)
        lengths.append(steps)
    return returns, lengths


def tenths(history: Sequence[Any], episodes: int) -> list[float]:
    """The mean training return of each tenth of the run."""
    tenth = max(1, episodes // 10)
    return [
        round(float(np.mean([h.episode_return for h in history[i : i + tenth]])), 1)
        for i in range(0, episodes, tenth)
    ]
