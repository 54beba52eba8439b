"""Probe (part 27): the tree's ancestors break the greedy choice's ties with paired,
leaf-by-leaf differences instead of part 26's pooled targets.

Part 26's ancestors compare each tied action's mean stored eq. (8) target over every leaf below
the ancestor. Those means pool epochs from wherever each action happened to be tried, so a
difference between two actions can be a difference between the places they were tried; on
MountainCar the rule lost two runs at -110 (dev seeds 10-49). Here an ancestor compares two
actions a, b only inside the leaves below it where both have at least ``greedy_min_epochs``
stored epochs: d_l = Q-bar(l, a) - Q-bar(l, b), each leaf counted once, with the standard error
of the mean of d over those leaves (a paired comparison, stratified by leaf). The tied set is cut
to the actions whose mean difference from the ancestor's best lies within z standard errors; the
first ancestor that leaves one action decides, and if none does, the root's best among those left (as part
26's ``anc`` variants).

Scored on part 22's training (``general_as_of(22)``), the same runs as parts 25-26's probes,
beside part 25's choice (``p25``) and part 26's pooled ancestors (``anc1``).

    python tie_strata.py TASK OUT SEED [SEED ...]        (classic: 20 greedy episodes)
    python tie_strata.py maze:LAYOUT OUT SEED [SEED ...] (600 episodes as maze_support.py)

``VARIANTS`` in the environment picks the forms: ``strZ`` uses z = Z for the leaf's tie test and
for the ancestors, ``sZ_Y`` Z for the leaf's and Y for the ancestors'; a trailing ``f`` keeps the leaf's best where
even the root leaves a tie, instead of the root's best among those left (default
``p25,anc1,str0.5,str1,str2,str3,str5,s0.5_2``).
"""

from __future__ import annotations

import math
import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve()
sys.path.insert(0, str(HERE.parents[1] / "issue9_part26_dev"))
from tie_ancestor import (  # noqa: E402
    ancestor_action,
    general_as_of,
    node_stats,
    run_probe,
)

VARIANTS = tuple(os.environ.get("VARIANTS", "p25,anc1,str0.5,str1,str2,str3,str5,s0.5_2").split(","))


def pair_stats(agent) -> dict[tuple[int, int, int], tuple[int, float, float]]:
    """(node, a, b), a < b -> (leaves, sum, sum of squares) of Q-bar(l, a) - Q-bar(l, b) over
    the leaves l below the node where both actions have ``greedy_min_epochs`` stored epochs."""
    part, k, stats = agent.partition, max(agent.config.greedy_min_epochs, 1), {}
    for leaf in part.leaves():
        counts = agent.support(leaf)
        ok = [a for a in range(agent.n_actions) if counts[a] >= k]
        row = agent.q[leaf]
        diffs = [(a, b, row[a] - row[b]) for i, a in enumerate(ok) for b in ok[i + 1 :]]
        if not diffs:
            continue
        node = part._parent[leaf]
        while node >= 0:
            for a, b, d in diffs:
                n, s, ss = stats.get((node, a, b), (0, 0.0, 0.0))
                stats[(node, a, b)] = (n + 1, s + d, ss + d * d)
            node = part._parent[node]
    return stats


def paired(stats, node: int, a: int, b: int) -> tuple[float, float]:
    """Mean of Q-bar(a) - Q-bar(b) over the node's shared leaves, and its standard error."""
    if a > b:
        mean, se = paired(stats, node, b, a)
        return -mean, se
    n, s, ss = stats.get((node, a, b), (0, 0.0, 0.0))
    if n < 2:
        return 0.0, math.inf
    mean = s / n
    var = max(ss - s * s / n, 0.0) / (n - 1)
    return mean, math.sqrt(var / n)


def strata_action(
    agent, obs, z: float, stats: dict, counts: dict, za: float | None = None, leaf_falls: bool = False
) -> int:
    za = z if za is None else za
    x = np.asarray(obs, dtype=np.float64).reshape(-1).tolist()
    leaf = agent.partition.leaf_of(x)
    row = agent.q[leaf]
    allowed = agent._supported([agent], [leaf])
    tied = agent._tied([agent], [leaf], row, allowed, z)
    first = tied[0]
    counts["decisions"] = counts.get("decisions", 0) + 1
    if len(tied) < 2:
        return first
    counts["ties"] = counts.get("ties", 0) + 1
    node = agent.partition._parent[leaf]
    while node >= 0 and len(tied) > 1:
        score = {a: sum(paired(stats, node, a, b)[0] for b in tied if b != a) for a in tied}
        best = max(tied, key=score.__getitem__)
        keep = [best]
        for a in tied:
            if a == best:
                continue
            mean, se = paired(stats, node, best, a)
            if not mean > za * se:
                keep.append(a)
        tied = keep
        node = agent.partition._parent[node]
    if len(tied) > 1:
        counts["unresolved"] = counts.get("unresolved", 0) + 1
    choice = first if leaf_falls and len(tied) > 1 else tied[0]
    if choice != first:
        counts["changed"] = counts.get("changed", 0) + 1
    return choice


def choosers(agent):
    """Variant -> (choose(obs), counts)."""
    p25 = general_as_of(26)  # part 25's preset (the neighbours)
    pooled = node_stats(agent) if any(v.startswith("anc") for v in VARIANTS) else {}
    strata = pair_stats(agent)
    out = {}
    for name in VARIANTS:
        counts: dict = {}
        if name == "p25":
            def choose(obs):
                agent.config = p25
                return agent.predict(obs)
        elif name.startswith("anc"):
            def choose(obs, z=float(name[3:]), counts=counts):
                agent.config = p25
                return ancestor_action(agent, obs, z, pooled, counts)
        else:  # strZ: z for the leaf's ties and the ancestors; sZ_Y: Z for the leaf's, Y theirs;
            # a trailing f: where even the root leaves a tie, the leaf's best (not the root's)
            falls = name.endswith("f")
            zs = name.removesuffix("f")
            zs = zs[3:] if zs.startswith("str") else zs[1:]
            z, _, za = zs.partition("_")
            def choose(obs, z=float(z), za=float(za or z), counts=counts, falls=falls):
                agent.config = p25
                return strata_action(agent, obs, z, strata, counts, za, falls)
        out[name] = (choose, counts)
    return out


if __name__ == "__main__":
    run_probe(choosers, sys.argv)
