"""Part 39 dev: greedy rules that break a stalled greedy episode, scored on trained agents.

    python stall_probe.py TASK AGENT_DIR OUT RULE SEED [SEED ...]

Loads ``AGENT_DIR/TASK-SEED.npz`` (``train_save.py``) and plays the same 20 greedy episodes
(reset seeds 10^6 + 1,000 seed + i). ``RULE`` is a JSON object:

* ``{}``: ``predict`` as it is (reproduces ``train_save.py``'s line);
* ``{"k": K, "eps": E}``: the episode counts its entries into each leaf (a step in a leaf other
  than the previous step's, and the first step). From the first entry that brings some leaf to
  K entries on, each step takes a uniformly random action with probability E (a generator
  seeded with the reset seed), else ``predict``'s;
* ``{"k": K, "eps": E, "once": true}``: the same, but only at the entries that bring a leaf to a
  multiple of K (one random action each, with probability E), greedy otherwise;
* ``{"k": K, "runner_up": true}``: at each entry that brings a leaf to a multiple of K, the
  action with the second-highest Q-bar in the leaf's row (no random draw); greedy otherwise.

One JSON line per seed: the mean greedy return, each episode's length, the step at which the
rule first fired in each episode (None when it never did) and, for ``{}``, the largest entry
count of any leaf in each episode.
"""

from __future__ import annotations

import json
import sys
import warnings
from collections import Counter
from pathlib import Path

import gymnasium as gym
import numpy as np
from protocol import GREEDY_EPISODES, reset_seed  # this folder

from agent import SMDPAgent, adapt_env


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, agent_dir, out = argv[1], Path(argv[2]), Path(argv[3])
    rule = json.loads(argv[4])
    k, eps, once = rule.get("k"), float(rule.get("eps", 0.0)), bool(rule.get("once", False))
    runner_up = bool(rule.get("runner_up", False))
    for seed in map(int, argv[5:]):
        agent = SMDPAgent.load(agent_dir / f"{task}-{seed}.npz")
        env = adapt_env(gym.make(task))
        returns, lengths, fired, most = [], [], [], []
        for i in range(GREEDY_EPISODES):
            reset = reset_seed(seed, i)
            rng = np.random.default_rng(reset)
            obs, _ = env.reset(seed=reset)
            entries: Counter[int] = Counter()
            previous, first_fire, on = -1, None, False
            total, steps, done = 0.0, 0, False
            while not done:
                x = np.asarray(obs, dtype=np.float64).reshape(-1).tolist()
                leaf = agent.partition.leaf_of(x)
                entered = leaf != previous
                if entered:
                    entries[leaf] += 1
                previous = leaf
                action = agent.predict(obs)
                if k is not None and entered and entries[leaf] % k == 0:
                    if first_fire is None:
                        first_fire = steps
                    on = True
                    if once and rng.random() < eps:
                        action = int(rng.integers(agent.n_actions))
                    if runner_up:
                        row = agent.q[leaf]
                        action = sorted(range(len(row)), key=lambda a: (-row[a], a))[1]
                if k is not None and on and not (once or runner_up) and rng.random() < eps:
                    action = int(rng.integers(agent.n_actions))
                obs, reward, term, trunc, _ = env.step(action)
                total += float(reward)
                steps += 1
                done = term or trunc
            returns.append(total)
            lengths.append(steps)
            fired.append(first_fire)
            most.append(max(entries.values()))
        row = {"task": task, "seed": seed, "rule": rule, "mean": round(float(np.mean(returns)), 2)}
        row["long"] = sum(r <= -200 for r in returns)
        row["lengths"], row["fired"] = lengths, fired
        if k is None:
            row["most_entries"] = most
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
