"""Probe (part 25): part 24's gated smoothing (``gated_smoothing.py``) used only as a tie-break.

In the state's leaf the allowed actions are part 24's (at least 2 stored epochs). The leaf's own
Q-bar picks the greedy action unless another allowed action's Q-bar is within z standard errors
of it (the standard error of each action's mean eq. (8) target over its stored epochs, combined
as sqrt(se_a^2 + se_b^2)). Only then do the tied actions compete on the gated, smoothed row
(the leaf's row averaged with the rows of the leaves +-h leaf widths away that the model has
moved between). The idea: a maze's actions are separated by their evidence, so it keeps its
choice; where the evidence cannot tell the actions apart, neighbours break the tie.

    python tie_gated.py TASK OUT SEED [SEED ...]        (classic: 20 greedy episodes)
    python tie_gated.py maze:LAYOUT OUT SEED [SEED ...] (600 episodes as maze_support.py)

Training is part 24's (``general_as_of(22)``: greedy-only parts 23-24 do not change it).
"""

from __future__ import annotations

import json
import math
import sys
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

HERE = Path(__file__).resolve()
sys.path.insert(0, str(HERE.parents[1] / "issue9_part23_dev"))
sys.path.insert(0, str(HERE.parents[1] / "issue9_part24_dev"))
from supported_greedy import greedy_returns  # noqa: E402

import bullet_maze  # noqa: E402, F401
from float_tasks_support import train  # noqa: E402
from gated_smoothing import connected, maze_run  # noqa: E402

VARIANTS = ((0.0, 0.0), (0.5, 1.0), (1.0, 0.5), (1.0, 1.0), (1.0, 2.0))
"""(h, z); h = 0 is part 24's choice."""


def smoothed_row(agent, x, leaf, h):
    part, model = agent.partition, agent.model
    rows = [agent.q[leaf]]
    low, high = part.leaf_bounds(leaf)
    for j, (lo, hi) in enumerate(zip(low, high)):
        if not (math.isfinite(lo) and math.isfinite(hi)):
            continue
        for sign in (-1.0, 1.0):
            y = list(x)
            y[j] += sign * h * (hi - lo)
            other = part.leaf_of(y)
            if other != leaf and connected(model, leaf, other):
                rows.append(agent.q[other])
    return [sum(r[a] for r in rows) / len(rows) for a in range(agent.n_actions)]


def standard_error(agent, leaf, a) -> float:
    _, values = agent.model.targets(leaf, a, agent.q)
    n = len(values)
    if n < 2:
        return math.inf
    return float(np.std(values, ddof=1)) / math.sqrt(n)


def tie_action(agent, obs, h: float, z: float, stats: dict) -> int:
    x = np.asarray(obs, dtype=np.float64).reshape(-1).tolist()
    leaf = agent.partition.leaf_of(x)
    model, row = agent.model, agent.q[leaf]
    allowed = [a for a in range(agent.n_actions) if model.count(leaf, a) >= 2] or list(range(agent.n_actions))
    best = max(allowed, key=row.__getitem__)
    if h == 0.0 or len(allowed) < 2:
        return best
    se = {a: standard_error(agent, leaf, a) for a in allowed}
    tied = [a for a in allowed if a == best or abs(row[best] - row[a]) <= z * math.hypot(se[best], se[a])]
    stats["decisions"] = stats.get("decisions", 0) + 1
    if len(tied) < 2:
        return best
    stats["ties"] = stats.get("ties", 0) + 1
    smooth = smoothed_row(agent, x, leaf, h)
    choice = max(tied, key=smooth.__getitem__)
    if choice != best:
        stats["changed"] = stats.get("changed", 0) + 1
    return choice


if __name__ == "__main__":
    warnings.simplefilter("ignore")
    task, out = sys.argv[1], Path(sys.argv[2])
    for seed in map(int, sys.argv[3:]):
        if task.startswith("maze:"):
            maze = task[len("maze:"):]
            env, agent = maze_run(maze, seed)
            optimum = env.unwrapped.optimal_steps
            for h, z in VARIANTS:
                steps, stats = [], {}
                for i in range(10):
                    obs, _ = env.reset(seed=10**6 + i)
                    n, done = 0, False
                    while not done:
                        obs, _, term, trunc, _ = env.step(tie_action(agent, obs, h, z, stats))
                        n += 1
                        done = term or trunc
                    steps.append(n)
                with out.open("a") as f:
                    f.write(json.dumps({"maze": maze, "seed": seed, "h": h, "z": z, "greedy": round(float(np.mean(steps)) / optimum, 3), "capped": sum(s >= 5000 for s in steps), **stats}) + "\n")
            continue
        env, agent, cpu = train(task, seed)
        starts = [1_000_000 + 1000 * seed + i for i in range(20)]
        for h, z in VARIANTS:
            stats = {}
            returns = greedy_returns(agent, env, 0, starts, lambda obs, h=h, z=z, s=stats: tie_action(agent, obs, h, z, s))
            with out.open("a") as f:
                f.write(json.dumps({"task": task, "seed": seed, "h": h, "z": z, "greedy": round(float(np.mean(returns)), 2), "cpu": round(cpu, 1), **stats}) + "\n")
