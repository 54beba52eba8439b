"""Part 41 dev: does settling the model over the leaves before the greedy episodes move them?

    python settle_probe.py TASK AGENT_DIR OUT SEED [SEED ...]

Loads part 40's saved agents (today's preset, 1,000 episodes, with their model), scores today's
``predict``, then runs ``LeafModel.backup_all`` passes until no V-bar moves by more than 1e-9 of
the agent's scale (at most 400 passes) and scores ``predict`` again on the same 20 greedy
episodes (part 39's protocol). One JSON line per (seed, rule), with the passes and the largest
change of the first pass.
"""

from __future__ import annotations

import json
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "issue9_part39_dev"))
from protocol import greedy_episodes

from agent import adapt_env, preset
from agent.tree_ensemble import tree_agent_class


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, agent_dir, out = argv[1], Path(argv[2]), Path(argv[3])
    config = preset("general").config
    for seed in map(int, argv[4:]):
        env = adapt_env(gym.make(task))
        agent = tree_agent_class(config).load(agent_dir / f"{task}-{seed}.npz")
        r0, l0 = greedy_episodes(env, agent.predict, seed)
        start = time.process_time()
        first, passes, biggest = None, 0, float("inf")
        while passes < 400 and biggest > 1e-9:
            changes = agent.model.backup_all(agent.q)
            biggest = max(changes.values(), default=0.0)
            first = biggest if first is None else first
            passes += 1
        agent.forget_greedy_cache()
        cpu = time.process_time() - start
        r1, l1 = greedy_episodes(env, agent.predict, seed)
        row = {
            "task": task,
            "seed": seed,
            "today": round(float(np.mean(r0)), 2),
            "settled": round(float(np.mean(r1)), 2),
            "passes": passes,
            "first_change": first,
            "last_change": biggest,
            "cpu": round(cpu, 1),
            "lengths_today": l0,
            "lengths_settled": l1,
        }
        with open(out, "a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
