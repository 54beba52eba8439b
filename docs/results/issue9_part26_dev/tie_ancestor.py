"""Probe (part 26): the tree's own ancestors break the greedy choice's ties, instead of the
spatial neighbours of part 25.

Part 12 found Acrobot's greedy actions wrong where the better action's Q-bar lies within a few
steps of the chosen one's, and a rule on one velocity's sign scores -78 to -83; the root's
presplit cuts every input at its middle, so a coarse ancestor of the leaf can hold that rule.
Here, where part 25's test finds the leaf's allowed actions tied (within z standard errors),
the ancestors are asked in turn, nearest first: each one's estimate of an action is the mean of
the stored eq. (8) targets of every leaf below it, with its standard error. The tied set is cut
to the actions within z standard errors of the ancestor's best among them; the first ancestor
that leaves one action decides. If none does, the leaf's best stands.

Scored on part 22's training (``general_as_of(22)``, the training of today's preset), the same
runs as part 25's probe, beside part 24's choice (``leaf``) and part 25's (``p25``).

    python tie_ancestor.py TASK OUT SEED [SEED ...]        (classic: 20 greedy episodes)
    python tie_ancestor.py maze:LAYOUT OUT SEED [SEED ...] (600 episodes as maze_support.py)

``VARIANTS=p25,anc1_nb,anc1_up2,anc1_up4`` in the environment picks the second round's forms:
``_nb`` gives part 25's neighbours the ties no ancestor resolves (instead of the leaf's best);
``_upK`` asks at most K ancestors (the nearest, whose regions are at most 2^K leaves wide).
"""

from __future__ import annotations

import json
import math
import os
import sys
import warnings
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve()
sys.path.insert(0, str(HERE.parents[1] / "issue9_part23_dev"))
sys.path.insert(0, str(HERE.parents[1] / "issue9_part24_dev"))
sys.path.insert(0, str(HERE.parents[1] / "issue9_part25_dev"))
from supported_greedy import greedy_returns  # noqa: E402

import bullet_maze  # noqa: E402, F401
from agent import general_as_of  # noqa: E402
from float_tasks_support import train  # noqa: E402
from gated_smoothing import maze_run  # noqa: E402
from tie_gated import smoothed_row  # noqa: E402

VARIANTS = tuple(os.environ.get("VARIANTS", "leaf,p25,anc0.5,anc1,anc2").split(","))


def node_stats(agent) -> dict[tuple[int, int], tuple[int, float, float]]:
    """(node, action) -> (n, sum, sum of squares) of the stored targets of every leaf below."""
    part, model, stats = agent.partition, agent.model, {}
    for leaf in part.leaves():
        for a in range(agent.n_actions):
            _, values = model.targets(leaf, a, agent.q)
            if not values:
                continue
            n, s, ss = len(values), math.fsum(values), math.fsum(v * v for v in values)
            node = part._parent[leaf]
            while node >= 0:
                old = stats.get((node, a), (0, 0.0, 0.0))
                stats[(node, a)] = (old[0] + n, old[1] + s, old[2] + ss)
                node = part._parent[node]
    return stats


def ancestor_action(
    agent, obs, z: float, stats: dict, counts: dict, up: int | None = None, nb: bool = False
) -> int:
    x = np.asarray(obs, dtype=np.float64).reshape(-1).tolist()
    leaf = agent.partition.leaf_of(x)
    row = agent.q[leaf]
    allowed = agent._supported([agent], [leaf])
    tied = agent._tied([agent], [leaf], row, allowed, z)
    counts["decisions"] = counts.get("decisions", 0) + 1
    if len(tied) < 2:
        return tied[0]
    counts["ties"] = counts.get("ties", 0) + 1
    node, asked = agent.partition._parent[leaf], 0
    while node >= 0 and len(tied) > 1 and (up is None or asked < up):
        asked += 1
        mean, se = {}, {}
        for a in tied:
            n, s, ss = stats.get((node, a), (0, 0.0, 0.0))
            mean[a] = s / n if n else -math.inf
            var = (ss - s * s / n) / (n - 1) if n > 1 else math.inf
            se[a] = math.sqrt(max(var, 0.0) / n) if n > 1 else math.inf
        best = max(tied, key=mean.__getitem__)
        tied = [best] + [
            a for a in tied if a != best and abs(mean[best] - mean[a]) <= z * math.hypot(se[best], se[a])
        ]
        node = agent.partition._parent[node]
    choice = tied[0]
    if nb and len(tied) > 1:  # part 25's neighbours among what no ancestor resolved
        smooth = smoothed_row(agent, x, leaf, 1.0)  # part 25's probe: h 1, linked leaves
        choice = max(tied, key=smooth.__getitem__)
    if choice != agent._tied([agent], [leaf], row, allowed, z)[0]:
        counts["changed"] = counts.get("changed", 0) + 1
    return choice


def choosers(agent):
    """Variant -> (choose(obs), counts)."""
    stats = node_stats(agent)
    configs = {"leaf": general_as_of(24), "p25": general_as_of(25)}
    out = {}
    for name in VARIANTS:
        counts: dict = {}
        if name in configs:
            def choose(obs, c=configs[name]):
                agent.config = c
                return agent.predict(obs)
        else:
            body, _, up = name[3:].partition("_up")
            nb = body.endswith("_nb")
            z = float(body.removesuffix("_nb"))
            def choose(obs, z=z, counts=counts, up=int(up) if up else None, nb=nb):
                agent.config = configs["p25"]
                return ancestor_action(agent, obs, z, stats, counts, up, nb)
        out[name] = (choose, counts)
    return out


def run_probe(choosers_of, argv: list[str]) -> None:
    """The probe's loop: train each seed (``argv``: TASK OUT SEED...), then score every chooser
    of ``choosers_of(agent)`` on the same greedy episodes; one JSON line per seed and variant.
    Part 27's ``tie_strata.py`` runs its own choosers through it."""
    warnings.simplefilter("ignore")
    task, out = argv[1], Path(argv[2])
    for seed in map(int, argv[3:]):
        if task.startswith("maze:"):
            maze = task[len("maze:"):]
            env, agent = maze_run(maze, seed)
            optimum = env.unwrapped.optimal_steps
            for name, (choose, counts) in choosers_of(agent).items():
                steps = []
                for i in range(10):
                    obs, _ = env.reset(seed=10**6 + i)
                    n, done = 0, False
                    while not done:
                        obs, _, term, trunc, _ = env.step(choose(obs))
                        n += 1
                        done = term or trunc
                    steps.append(n)
                with out.open("a") as f:
                    f.write(json.dumps({"maze": maze, "seed": seed, "variant": name, "greedy": round(float(np.mean(steps)) / optimum, 3), "capped": sum(s >= 5000 for s in steps), **counts}) + "\n")
            continue
        env, agent, cpu = train(task, seed)
        starts = [1_000_000 + 1000 * seed + i for i in range(20)]
        for name, (choose, counts) in choosers_of(agent).items():
            returns = greedy_returns(agent, env, 0, starts, choose)
            with out.open("a") as f:
                f.write(json.dumps({"task": task, "seed": seed, "variant": name, "greedy": round(float(np.mean(returns)), 2), "cpu": round(cpu, 1), **counts}) + "\n")


if __name__ == "__main__":
    run_probe(choosers, sys.argv)
