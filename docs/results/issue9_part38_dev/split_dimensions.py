"""Part 38 diagnostic: which input dimensions does the general preset's tree cut?

    python split_dimensions.py TASK OUT SEED [SEED ...]

Trains today's general preset (1,000 episodes, reset seed = agent seed) and writes one JSON line
per seed: the number of splits on each input dimension beyond the presplit, and the median
width of the leaves on each dimension as a fraction of the root's.
"""

from __future__ import annotations

import json
import sys
import warnings
from collections import Counter
from pathlib import Path

import gymnasium as gym
import numpy as np

from agent import adapt_env, preset


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, out = argv[1], Path(argv[2])
    for seed in map(int, argv[3:]):
        env = adapt_env(gym.make(task))
        agent = preset("general").agent(env.observation_space, env.action_space, seed=seed)
        agent.learn(env, 1000, reset_seed=seed)
        tree = agent.partition
        dims = tree.dims
        splits = Counter(d for d in tree._dim if d >= 0)
        root = np.asarray(tree.root_high) - np.asarray(tree.root_low)
        widths = np.array(
            [np.subtract(*reversed(tree.leaf_bounds(leaf))) / root for leaf in tree.leaves()]
        )
        row = {
            "task": task,
            "seed": seed,
            "leaves": tree.n_leaves,
            # the presplit cuts dimension d at each of the 2^d nodes of level d
            "splits_beyond_presplit": [splits[d] - 2**d for d in range(dims)],
            "median_width": [round(float(np.median(widths[:, d])), 4) for d in range(dims)],
        }
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
