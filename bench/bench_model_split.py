"""The model split's shortcut in the general agent (issue 9, part 34): CPU with and without it.

``SMDPAgent._model_split`` (part 9) tests the stored epochs of the (leaf, action) that just
ended an epoch. About three tests in four end at their first condition, the targets' range below
``model_split_gap``, and part 34 answers that one in plain Python
(``agent.model_split.spread_below``) before the arrays and the leaf's box are built. This prints,
per task, the CPU seconds of ``--episodes`` learning episodes of the general preset with the
shortcut and with it bypassed (every test built in full, as before part 34), in interleaved
rounds (agent and reset seed = the round; CPU time of this process, the agent built before the
clock starts), their ratio (median over rounds, with its range), and whether the two runs of
each round ended with the same Q-bar, leaves and episode lengths (they must: the shortcut
changes no answer).

    python bench/bench_model_split.py                 # 3 rounds, about 3 minutes
    python bench/bench_model_split.py --rounds 1 --episodes 50
"""

from __future__ import annotations

import argparse
import gc
import time
from typing import Any

import gymnasium as gym
from ab_rounds import ab_rounds  # bench/ is the script's folder

import agent.learner
from agent import adapt_env, preset
from agent.model_split import spread_below

TASKS = ("CartPole-v1", "Acrobot-v1", "MountainCar-v0")


def _never(targets: list[float], min_gap: float) -> bool:
    """The bypass: no test ends before the arrays are built."""
    return False


def learning_run(task: str, shortcut: bool, episodes: int, seed: int) -> tuple[float, Any]:
    """CPU seconds of ``episodes`` learning episodes of the general preset, and what the run
    ended with (Q-bar, leaves, episode lengths)."""
    agent.learner.spread_below = spread_below if shortcut else _never  # type: ignore[assignment]
    try:
        env = adapt_env(gym.make(task))
        learner = preset("general").agent(env.observation_space, env.action_space, seed)
        gc.collect()
        start = time.process_time()
        history = learner.learn(env, episodes, reset_seed=seed)
        cpu = time.process_time() - start
        env.close()
    finally:
        agent.learner.spread_below = spread_below  # type: ignore[assignment]
    return cpu, (learner.q, learner.n_leaves, [h.steps for h in history])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--episodes", type=int, default=300)
    args = parser.parse_args()
    print(f"general preset, {args.episodes} episodes a run, {args.rounds} interleaved rounds")
    print("task | CPU-s bypassed | with the shortcut | ratio (median, range) | same runs")
    for task in TASKS:

        def run(shortcut: bool, seed: int, task: str = task) -> Any:
            return learning_run(task, shortcut, args.episodes, seed)

        row = ab_rounds(run, args.rounds)
        print(f"{task} | {row.cells()}")


if __name__ == "__main__":
    main()
