"""Part 39 dev: train today's general preset, keep the trained agent, score its greedy policy.

    python train_save.py TASK AGENT_DIR OUT SEED [SEED ...]

Part 30's classic protocol (1,000 episodes from reset seed = agent seed; 20 greedy episodes from
reset seeds 10^6 + 1,000 seed + i), as in part 34's ``override_runs.py``. Each trained agent is
saved policy-only to ``AGENT_DIR/TASK-SEED.npz`` so that ``stall_probe.py`` can score other
greedy rules on the very same agents. One JSON line per seed: the mean greedy return, each
greedy episode's length, the leaves and the CPU seconds of training.
"""

from __future__ import annotations

import json
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np
from protocol import greedy_episodes  # this folder

from agent import adapt_env, preset
from agent.tree_ensemble import tree_agent_class


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, agent_dir, out = argv[1], Path(argv[2]), Path(argv[3])
    agent_dir.mkdir(parents=True, exist_ok=True)
    general = preset("general")
    for seed in map(int, argv[4:]):
        env = adapt_env(gym.make(task))
        config = general.config
        agent = tree_agent_class(config)(
            env.observation_space, env.action_space, general.make_exploration(), seed, config
        )
        start = time.process_time()
        agent.learn(env, 1000, reset_seed=seed)
        cpu = round(time.process_time() - start, 1)
        agent.save(agent_dir / f"{task}-{seed}.npz", policy_only=True)
        returns, lengths = greedy_episodes(env, agent.predict, seed)
        row = {"task": task, "seed": seed, "cpu": cpu, "leaves": agent.n_leaves}
        row["mean"] = round(float(np.mean(returns)), 2)
        row["long"] = sum(r <= -200 for r in returns)
        row["lengths"] = lengths
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
