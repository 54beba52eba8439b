"""The general agent on any Gymnasium task, whatever its spaces (issue 9, part 12).

    python examples/any_task.py Pendulum-v1 [--episodes 1000] [--action-bins 5] [--seed 0]
    python examples/any_task.py FrozenLake-v1 --episodes 2000

``agent.adapt_env`` gives the task the spaces the agent takes (an index input for a Discrete
or Tuple observation, a grid of ``--action-bins`` values a dimension for a Box action); the
task is otherwise untouched, and ``preset("general")`` learns it with its one set of defaults.
``train`` is what the tests call; it returns the per-episode statistics and the greedy policy's
return on a few evaluation episodes. A bad argument (an unknown task, a task that needs
arguments the command line cannot give, a bad bin count) is a one-line error, exit code 2.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass
from typing import Any

import gymnasium as gym
import numpy as np

from agent import EpisodeStats, SMDPAgent, adapt_env, preset
from experiments.evaluation import greedy_episode


@dataclass(frozen=True)
class TaskResult:
    """Training history and the greedy policy's evaluation."""

    agent: SMDPAgent
    history: list[EpisodeStats]
    eval_returns: list[float]
    """Return of each greedy evaluation episode."""


def train(
    task: str,
    episodes: int = 1000,
    seed: int = 0,
    action_bins: int | None = None,
    eval_episodes: int = 20,
) -> TaskResult:
    """Train ``preset("general")`` on ``task`` through ``adapt_env`` (``action_bins`` values a
    Box action dimension, default 5; refused by ``adapt_env`` for other actions); the first
    reset is seeded with ``seed`` and evaluation episode i with ``10**6 + i``."""
    env = adapt_env(gym.make(task), action_bins)
    agent = preset("general").agent(env.observation_space, env.action_space, seed=seed)
    history = agent.learn(env, episodes, reset_seed=seed)
    returns = [greedy_episode(env, agent, 10**6 + i).episode_return for i in range(eval_episodes)]
    env.close()
    return TaskResult(agent, history, returns)


def _positive(text: str) -> int:
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {value}")
    return value


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("task", help="a Gymnasium id, e.g. Pendulum-v1")
    parser.add_argument("--episodes", type=_positive, default=1000)
    parser.add_argument(
        "--action-bins", type=int, default=None, help="values per Box action dimension (5)"
    )
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    try:
        result = train(args.task, args.episodes, args.seed, args.action_bins)
    except (gym.error.Error, TypeError, ValueError) as error:
        print(f"any_task.py: {args.task}: {error}", file=sys.stderr)
        return 2
    last: Any = result.history[-100:]
    print(
        f"{args.task}: {len(result.history)} episodes, {result.agent.n_leaves} leaves; "
        f"training return over the last {len(last)} episodes "
        f"{np.mean([h.episode_return for h in last]):.3f}; greedy return over "
        f"{len(result.eval_returns)} episodes {np.mean(result.eval_returns):.3f}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
