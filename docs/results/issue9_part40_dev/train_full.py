"""Part 40 dev: train today's general preset on a task and keep the whole trained agent.

    python train_full.py TASK AGENT_DIR OUT EPISODES SEED [SEED ...]

Part 30's classic protocol (training from reset seed = agent seed; 20 greedy episodes from reset
seeds 10^6 + 1,000 seed + i; part 39's ``protocol.py``). Unlike part 39's ``train_save.py`` the
agent is saved with its model over the leaves (``AGENT_DIR/TASK-SEED.npz``), so that
``slope_probe.py`` can fit lines to each (leaf, action)'s stored epochs. One JSON line per seed:
the mean greedy return, each greedy episode's length, the leaves and the CPU seconds of training.
"""

from __future__ import annotations

import json
import sys
import time
import warnings
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "issue9_part39_dev"))
from protocol import greedy_episodes

from agent import adapt_env, preset
from agent.tree_ensemble import tree_agent_class


def append_scored(out: Path, row: dict[str, Any], returns: list[float], lengths: list[int]) -> None:
    """Add the mean greedy return and each episode's length to ``row``; append it to ``out``."""
    row["mean"] = round(float(np.mean(returns)), 2)
    row["lengths"] = lengths
    with out.open("a") as f:
        f.write(json.dumps(row) + "\n")


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, agent_dir, out, episodes = argv[1], Path(argv[2]), Path(argv[3]), int(argv[4])
    agent_dir.mkdir(parents=True, exist_ok=True)
    general = preset("general")
    for seed in map(int, argv[5:]):
        env = adapt_env(gym.make(task))
        config = general.config
        agent = tree_agent_class(config)(
            env.observation_space, env.action_space, general.make_exploration(), seed, config
        )
        start = time.process_time()
        agent.learn(env, episodes, reset_seed=seed)
        cpu = round(time.process_time() - start, 1)
        agent.save(agent_dir / f"{task}-{seed}.npz")
        returns, lengths = greedy_episodes(env, agent.predict, seed)
        row = {"task": task, "seed": seed, "cpu": cpu, "leaves": agent.n_leaves}
        append_scored(out, row, returns, lengths)


if __name__ == "__main__":
    main(sys.argv)
