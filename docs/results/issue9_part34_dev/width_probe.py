"""Part 34 dev diagnostic (round 2): does ``predict`` gain from a tie width beyond 2?

Today's general preset is trained once per seed (part 30's classic protocol: 1,000 episodes from
reset seed = agent seed), then scored on the same 20 greedy episodes (reset seeds
10^6 + 1,000 seed + i) with ``predict`` as the agent stands (``sel``) and with the trial set
aside and both tie widths (``greedy_tie_errors``, ``greedy_tie_ancestors``) at each of
``WIDTHS``. Training is untouched, so every column is the same trained policy.

    python width_probe.py TASK OUT SEED [SEED ...]
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

HERE = Path(__file__).resolve()
sys.path.insert(0, str(HERE.parents[1] / "issue9_part30_dev"))
from trial_runs import scored  # noqa: E402

WIDTHS = (1.0, 2.0, 3.0, 4.0, 6.0)


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, out = argv[1], Path(argv[2])
    for seed in map(int, argv[3:]):
        env = adapt_env(gym.make(task))
        general = preset("general")
        agent = tree_agent_class(general.config)(
            env.observation_space, env.action_space, general.make_exploration(), seed, general.config
        )
        start = time.process_time()
        agent.learn(env, 1000, reset_seed=seed)
        row = {"task": task, "seed": seed, "cpu": round(time.process_time() - start, 1)}
        row["adopted"] = agent.tie_trial.adopted
        for label, width in [("sel", None)] + [(f"z{w:g}", w) for w in WIDTHS]:
            choose = scored(agent, width)
            returns = []
            for i in range(20):
                obs, _ = env.reset(seed=1_000_000 + 1000 * seed + i)
                total, done = 0.0, False
                while not done:
                    obs, reward, term, trunc, _ = env.step(choose(obs))
                    total += float(reward)
                    done = term or trunc
                returns.append(total)
            row[label] = round(float(np.mean(returns)), 2)
            row[label + "_long"] = sum(r <= -200 for r in returns)
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
