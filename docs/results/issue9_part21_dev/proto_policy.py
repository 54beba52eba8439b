"""Issue 9, part 21 (development prototype, not the library): policy splits.

Imported for its side effect: ``SMDPAgent._model_split`` also tries, when the model split of
(leaf, a) finds no cut, a cut where the greedy choice between a and another action b flips.
With the stored epochs of a and b in the leaf (each at least ``model_split_epochs``), their
eq. (8) targets under the current values, and a cut along one input, the two sides' mean
differences d_L = mean_a,L - mean_b,L and d_R = mean_a,R - mean_b,R must have opposite signs,
|d_L - d_R| must be at least ``model_split_gap`` units and at least ``PS_T`` standard errors
(pooled within the four groups). The largest t wins (Munos and Moore's policy-disagreement
splits, 2002, read on stored epochs). Environment: ``PS_T`` (default 3), ``PS_MIN`` (epochs of
each action on each side, default 2).
"""

from __future__ import annotations

import os

import numpy as np

from agent.learner import SMDPAgent
from agent.partition_tree import PartitionTree

T_MIN = float(os.environ.get("PS_T", "3"))
SIDE = int(os.environ.get("PS_MIN", "2"))
COUNTS = {"policy_splits": 0}


def choose_policy_split(fa, ya, fb, yb, low, high, min_width, min_gap, min_t):
    na, nb = len(ya), len(yb)
    x_all = np.concatenate([fa, fb])
    y_all = np.concatenate([ya, yb])
    is_a = np.concatenate([np.ones(na), np.zeros(nb)])
    n = na + nb
    best = None
    for dim in range(x_all.shape[1]):
        order = np.argsort(x_all[:, dim], kind="stable")
        xs, ys, ia = x_all[order, dim], y_all[order], is_a[order]
        ib = 1.0 - ia
        ca, cb = np.cumsum(ia)[:-1], np.cumsum(ib)[:-1]
        sa, sb = np.cumsum(ys * ia)[:-1], np.cumsum(ys * ib)[:-1]
        qa, qb = np.cumsum(ys * ys * ia)[:-1], np.cumsum(ys * ys * ib)[:-1]
        ta, tb = float(np.sum(ys * ia)), float(np.sum(ys * ib))
        qta, qtb = float(np.sum(ys * ys * ia)), float(np.sum(ys * ys * ib))
        cut = 0.5 * (xs[:-1] + xs[1:])
        ok = (xs[:-1] != xs[1:]) & (cut - low[dim] >= min_width[dim]) & (high[dim] - cut >= min_width[dim])
        counts = [ca, cb, na - ca, nb - cb]
        for c in counts:
            ok &= c >= SIDE
        if not ok.any():
            continue
        with np.errstate(divide="ignore", invalid="ignore"):
            groups = [(ca, sa, qa), (cb, sb, qb), (na - ca, ta - sa, qta - qa), (nb - cb, tb - sb, qtb - qb)]
            means = [s / c for c, s, _ in groups]
            within = sum(q - c * m * m for (c, _, q), m in zip(groups, means))
            d_left, d_right = means[0] - means[1], means[2] - means[3]
            diff = np.abs(d_left - d_right)
            spread = np.sqrt(np.maximum(within, 0.0) / (n - 4))
            error = spread * np.sqrt(sum(1.0 / c for c in counts))
            t = np.where(error > 0, diff / error, np.inf)
        ok &= (d_left * d_right < 0) & (diff >= min_gap) & (t >= min_t)
        if not ok.any():
            continue
        score = np.where(ok, np.where(np.isinf(t), 1e300, t), -1.0)
        i = int(np.argmax(score))
        if best is None or score[i] > best[0]:
            best = (float(score[i]), dim, float(cut[i]))
    return best


original = SMDPAgent._model_split


def _model_split(self, leaf, action):
    children = original(self, leaf, action)
    if children is not None:
        return children
    cfg, model, partition = self.config, self.model, self.partition
    least = cfg.model_split_epochs
    if least is None or model is None or not isinstance(partition, PartitionTree):
        return None
    if model.count(leaf, action) < least or not partition.may_split():
        return None
    fa, ya = model.targets(leaf, action, self.q)
    low, high, _, min_width = partition.split_box(leaf)
    best = None
    for other in range(model.n_actions):
        if other == action or model.count(leaf, other) < least:
            continue
        fb, yb = model.targets(leaf, other, self.q)
        choice = choose_policy_split(
            np.asarray(fa, dtype=np.float64), np.asarray(ya, dtype=np.float64),
            np.asarray(fb, dtype=np.float64), np.asarray(yb, dtype=np.float64),
            low, high, min_width, self._in_units(cfg.model_split_gap), T_MIN,
        )
        if choice is not None and (best is None or choice[0] > best[0]):
            best = choice
    if best is None:
        return None
    COUNTS["policy_splits"] += 1
    return partition.split_with_samples(leaf, best[1], best[2])


SMDPAgent._model_split = _model_split


def _report() -> None:
    import sys

    sys.stderr.write(f"policy splits: {COUNTS['policy_splits']}\n")


import atexit  # noqa: E402

atexit.register(_report)
