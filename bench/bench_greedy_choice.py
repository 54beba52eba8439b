"""Cost of the greedy choice among supported actions (``TreeConfig.greedy_min_epochs`` and
``greedy_cell_epochs``, issue 9, parts 23 and 24) in ``predict``.

One agent of the general preset learns MountainCar-v0 (and one the ``paper`` maze, and one
Taxi-v4, whose integer input makes every leaf a single-input cell); then ``predict`` is timed on
the same random states with the preset's options (2 epochs, 1 in a cell) and with neither
(part 22's greedy choice), in interleaved rounds (CPU time of this process). Training is the
same either way (the option changes no training step), so only ``predict`` is timed. Prints
microseconds per call and the ratio (median over rounds, with its range).

    python bench/bench_greedy_choice.py             # 5 rounds, about a minute
    python bench/bench_greedy_choice.py --rounds 3 --episodes 100
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
import time

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa: F401 (registers BulletMaze-v0)
from agent import adapt_env, preset
from agent.tree_ensemble import tree_agent_class

TASKS = {
    "MountainCar-v0": {},
    "BulletMaze-v0": {"maze": "paper", "max_episode_steps": 5000},
    "Taxi-v4": {},
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=5, help="interleaved rounds (5)")
    parser.add_argument("--episodes", type=int, default=200, help="training episodes (200)")
    parser.add_argument("--calls", type=int, default=20000, help="predict calls a round (20,000)")
    args = parser.parse_args()
    if min(args.rounds, args.episodes, args.calls) < 1:
        parser.error("--rounds, --episodes and --calls must be at least 1")
    general = preset("general")
    for task, kwargs in TASKS.items():
        env = adapt_env(gym.make(task, **kwargs))  # Taxi's index as one integer input
        agent = tree_agent_class(general.config)(
            env.observation_space, env.action_space, general.make_exploration(), 0, general.config
        )
        agent.learn(env, args.episodes, reset_seed=0)
        space = env.observation_space
        low = np.maximum(space.low, -10.0)  # type: ignore[attr-defined]
        high = np.minimum(space.high, 10.0)  # type: ignore[attr-defined]
        states = np.random.default_rng(0).uniform(low, high, size=(args.calls, len(low)))
        if np.issubdtype(space.dtype, np.integer):  # type: ignore[arg-type]
            states = np.rint(states).astype(space.dtype)
        off = dataclasses.replace(general.config, greedy_min_epochs=0, greedy_cell_epochs=None)
        configs = {1: general.config, 0: off}
        times: dict[int, list[float]] = {0: [], 1: []}
        changed = 0
        for _ in range(args.rounds):
            chosen = {}
            for k, config in configs.items():
                agent.config = config
                start = time.process_time()
                chosen[k] = [agent.predict(s) for s in states]
                times[k].append((time.process_time() - start) / args.calls * 1e6)
            changed = sum(a != b for a, b in zip(chosen[0], chosen[1], strict=True))
        agent.config = general.config
        ratios = [new / old for new, old in zip(times[1], times[0], strict=True)]
        print(
            f"{task}: {agent.n_leaves} leaves after {args.episodes} episodes; predict "
            f"{statistics.median(times[1]):.1f} us (greedy_min_epochs 2, 1 in a cell) against "
            f"{statistics.median(times[0]):.1f} us (0): ratio {statistics.median(ratios):.3f} "
            f"[{min(ratios):.3f}, {max(ratios):.3f}]; {changed} of {args.calls:,} random states "
            "choose another action"
        )
        env.close()


if __name__ == "__main__":
    main()
