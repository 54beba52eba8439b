"""Diagnostic (part 26): does the general preset's Acrobot policy keep improving past the issue's
1,000 episodes? If the greedy return reaches -100 with more episodes, the miss is sample
efficiency; if it stalls near -135, it is what the tree's values can represent.

The general preset (today's; training is part 22's) learns in blocks up to EPISODES; after each
checkpoint, 20 greedy episodes with ``agent.predict`` on a separate environment, reset seeds
1,000,000 + 1,000 seed + i (the part 4 protocol). One JSON line per checkpoint.

    python longer_runs.py TASK OUT EPISODES SEED [SEED ...]
"""

from __future__ import annotations

import json
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

from agent import adapt_env, preset
from agent.tree_ensemble import tree_agent_class

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "issue9_part23_dev"))
from supported_greedy import greedy_returns  # noqa: E402

CHECKPOINTS = (250, 500, 1000, 1500, 2000, 3000, 4000, 5000)


def greedy(agent, env, seed: int) -> float:
    """Mean return of 20 greedy episodes of ``agent.predict``."""
    resets = [1_000_000 + 1000 * seed + i for i in range(20)]
    return float(np.mean(greedy_returns(agent, env, 0, resets, choose=agent.predict)))


def main(task: str, out: Path, episodes: int, seeds: list[int]) -> None:
    for seed in seeds:
        env, scorer = adapt_env(gym.make(task)), adapt_env(gym.make(task))
        general = preset("general")
        agent = tree_agent_class(general.config)(
            env.observation_space, env.action_space, general.make_exploration(), seed,
            general.config,
        )
        done, cpu = 0, 0.0
        for checkpoint in (c for c in CHECKPOINTS if c <= episodes):
            start = time.process_time()
            agent.learn(env, checkpoint - done, reset_seed=seed if done == 0 else None)
            cpu += time.process_time() - start
            done = checkpoint
            line = {"task": task, "seed": seed, "episodes": done,
                    "greedy": round(greedy(agent, scorer, seed), 2),
                    "leaves": agent.n_leaves, "cpu": round(cpu, 1)}
            with out.open("a") as f:
                f.write(json.dumps(line) + "\n")


if __name__ == "__main__":
    warnings.simplefilter("ignore")
    main(sys.argv[1], Path(sys.argv[2]), int(sys.argv[3]), [int(s) for s in sys.argv[4:]])
