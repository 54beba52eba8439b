"""Part 34 dev diagnostic (round 4): would a passive offset tree's mean help Acrobot's greedy
choice on top of today's preset?

Today's general preset with ``ensemble_trees`` 2 and ``ensemble_decisions`` "first" (part 28's
offset trees), except that training acts on tree 0's row alone: tree 1 learns every stretch
between two of tree 0's decisions as its own epochs but never chooses an action. So the
training run should be today's preset step for step (``sel0`` checks it against part 33's d2).
The trained agent is then scored on the same 20 greedy episodes (part 30's protocol) with
``predict`` over tree 0 alone (``sel0``) and over the mean of both trees' rows (``mean``), each
with today's tie rules and the width the run's trial adopted.

    python passive_probe.py TASK OUT SEED [SEED ...]
"""

from __future__ import annotations

import dataclasses
import json
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

from agent import adapt_env, preset
from agent.tree_ensemble import tree_agent_class


def passive_class(base):
    class Passive(base):
        acting_alone = True

        def mean_row(self, leaves):
            if self.acting_alone:
                return self.members[0].q[leaves[0]]
            return super().mean_row(leaves)

    return Passive


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, out = argv[1], Path(argv[2])
    general = preset("general")
    config = dataclasses.replace(general.config, ensemble_trees=2, ensemble_decisions="first")
    for seed in map(int, argv[3:]):
        env = adapt_env(gym.make(task))
        cls = passive_class(tree_agent_class(config))
        agent = cls(env.observation_space, env.action_space, general.make_exploration(), seed, config)
        start = time.process_time()
        agent.learn(env, 1000, reset_seed=seed)
        row = {"task": task, "seed": seed, "cpu": round(time.process_time() - start, 1)}
        row["leaves"] = [m.partition.n_leaves for m in agent.members]
        members = agent.members
        for label in ("sel0", "mean"):
            if label == "sel0":
                agent.members, agent.acting_alone = members[:1], True
            else:
                agent.members, agent.acting_alone = members, False
            agent.forget_greedy_cache()
            returns = []
            for i in range(20):
                obs, _ = env.reset(seed=1_000_000 + 1000 * seed + i)
                total, done = 0.0, False
                while not done:
                    obs, reward, term, trunc, _ = env.step(agent.predict(obs))
                    total += float(reward)
                    done = term or trunc
                returns.append(total)
            row[label] = round(float(np.mean(returns)), 2)
            row[label + "_long"] = sum(r <= -200 for r in returns)
        agent.members = members
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
