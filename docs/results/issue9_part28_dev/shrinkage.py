"""Probe (part 28, round 4): hierarchical shrinkage of the actions' advantages instead of a tie
test (Agarwal, Tan, Ronen, Singh and Yu, "Hierarchical Shrinkage: Improving the Accuracy and
Interpretability of Tree-Based Methods", ICML 2022).

Part 27's rule lets the ancestors speak only where the leaf's actions are tied, and part 26-28's
probes found Acrobot's gains where coarse evidence spoke more. Hierarchical shrinkage lets every
level speak, each in proportion to how much data stands behind it. A leaf's advantage vector is
A_l(a) = Q-bar(l, a) - mean_b Q-bar(l, b), over the "complete" leaves, where every action has a
stored epoch. A node's m(node) is the mean of A_l over the complete leaves below it, N(node)
their count (a node with none takes its parent's m). Along the path root = n_0, ..., n_k = the
state's leaf,

    A_hs = m(n_0) + sum_i (m(n_i) - m(n_{i-1})) / (1 + lambda / N(n_{i-1})),

and the greedy action is the argmax of A_hs among the leaf's supported actions
(``greedy_min_epochs``), as ``predict`` allows them. ``hsL`` is lambda = L. Scored on part 22's
training (today's training), beside today's ``predict`` (``str1``).

    python shrinkage.py TASK OUT SEED [SEED ...]   (part 26's run_probe: 20 greedy episodes)
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve()
sys.path.insert(0, str(HERE.parents[1] / "issue9_part26_dev"))
from tie_ancestor import run_probe  # noqa: E402

from agent import preset  # noqa: E402

VARIANTS = tuple(os.environ.get("VARIANTS", "str1,hs1,hs4,hs16").split(","))


def node_means(agent) -> tuple[dict[int, np.ndarray], dict[int, int]]:
    """Sum of the complete leaves' advantage vectors below each node, and their count."""
    part, sums, counts = agent.partition, {}, {}
    for leaf in part.leaves():
        if min(agent.support(leaf)) < 1:
            continue
        row = np.asarray(agent.q[leaf], dtype=np.float64)
        adv = row - row.mean()
        node = leaf
        while node >= 0:
            sums[node] = sums.get(node, 0.0) + adv
            counts[node] = counts.get(node, 0) + 1
            node = part._parent[node]
    return {n: s / counts[n] for n, s in sums.items()}, counts


def shrunk_action(agent, obs, lam: float, means, counts, tally: dict) -> int:
    x = np.asarray(obs, dtype=np.float64).reshape(-1).tolist()
    leaf = agent.partition.leaf_of(x)
    path = [leaf]
    while agent.partition._parent[path[-1]] >= 0:
        path.append(agent.partition._parent[path[-1]])
    path.reverse()  # root first
    zero = np.zeros(agent.n_actions)
    m_prev = means.get(path[0], zero)
    value = m_prev.copy()
    for parent, node in zip(path, path[1:]):
        m = means.get(node, m_prev)
        value += (m - m_prev) / (1.0 + lam / max(counts.get(parent, 0), 1))
        m_prev = m
    allowed = agent._supported([agent], [leaf]) or list(range(agent.n_actions))
    choice = max(allowed, key=lambda a: value[a])
    plain = max(allowed, key=agent.q[leaf].__getitem__)
    tally["decisions"] = tally.get("decisions", 0) + 1
    tally["changed"] = tally.get("changed", 0) + (choice != plain)
    return choice


def choosers(agent):
    today = preset("general").config
    means, counts = node_means(agent)
    out = {}
    for name in VARIANTS:
        tally: dict = {}
        if name == "str1":
            def choose(obs):
                agent.config = today
                return agent.predict(obs)
        else:
            def choose(obs, lam=float(name[2:]), tally=tally):
                agent.config = today
                return shrunk_action(agent, obs, lam, means, counts, tally)
        out[name] = (choose, tally)
    return out


if __name__ == "__main__":
    run_probe(choosers, sys.argv)
