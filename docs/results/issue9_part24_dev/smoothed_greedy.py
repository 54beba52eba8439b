"""Probe (not adopted unless stated in docs/paper-notes.md): a greedy choice over a smoothed
Q-bar. Training is today's preset (``general_as_of(22)``, the same training as part 24's); the
greedy action is the best of the actions with two stored epochs in the state's leaf (the
preset's rule), ranked by the mean Q-bar row over the leaves of 2d + 1 points: the state and the
state moved by +-h times the leaf's width along each dimension (a dimension whose leaf edge is
unbounded is not moved). h = 0 is the preset's own choice.

    python smoothed_greedy.py TASK OUT SEED [SEED ...]   (20 greedy episodes, as part 4)
"""

from __future__ import annotations

import json
import math
import sys
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "issue9_part23_dev"))
from supported_greedy import greedy_returns  # noqa: E402

from float_tasks_support import train  # noqa: E402


HS = (0.0, 0.25, 0.5, 1.0)


def smoothed_action(agent, obs, h: float) -> int:
    x = np.asarray(obs, dtype=np.float64).reshape(-1).tolist()
    part = agent.partition
    leaf = part.leaf_of(x)
    allowed = [a for a in range(agent.n_actions) if agent.model.count(leaf, a) >= 2] or list(range(agent.n_actions))
    if h == 0.0:
        row = agent.q[leaf]
    else:
        low, high = part.leaf_bounds(leaf)
        rows = [agent.q[leaf]]
        for j, (lo, hi) in enumerate(zip(low, high)):
            if not (math.isfinite(lo) and math.isfinite(hi)):
                continue
            for sign in (-1.0, 1.0):
                y = list(x)
                y[j] += sign * h * (hi - lo)
                rows.append(agent.q[part.leaf_of(y)])
        row = [sum(r[a] for r in rows) / len(rows) for a in range(agent.n_actions)]
    return max(allowed, key=row.__getitem__)


if __name__ == "__main__":
    warnings.simplefilter("ignore")
    task, out = sys.argv[1], Path(sys.argv[2])
    for seed in map(int, sys.argv[3:]):
        env, agent, cpu = train(task, seed)
        starts = [1_000_000 + 1000 * seed + i for i in range(20)]
        for h in HS:
            returns = greedy_returns(agent, env, 0, starts, lambda obs, h=h: smoothed_action(agent, obs, h))
            with out.open("a") as f:
                f.write(json.dumps({"task": task, "seed": seed, "h": h, "greedy": round(float(np.mean(returns)), 2), "leaves": agent.n_leaves, "cpu": round(cpu, 1)}) + "\n")
