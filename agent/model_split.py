"""Model-driven splits (beyond the paper): split a leaf where one action's stored epochs disagree.

Section IV.B splits a leaf from the TD errors of its recent inputs, N_th of them at a time, and
drops them after a test that fails. A leaf that the greedy path avoids is seldom tested, so a
leaf whose action sometimes hits a wall and sometimes passes (a door, a pillar's edge) keeps
one averaged value for both and is avoided for good.

With ``TreeConfig.model_split_epochs`` = k the learner also tests the epochs the model of
``planning="sweep"`` keeps for (leaf, a) (:mod:`agent.leaf_model`): once at least k are stored,
each epoch e has the eq. (8) target under the current values,

    y_e = R_e + D_e V-bar(l'_e)        (V-bar = 0 after a terminal state),

and its first input s_e. Ordering the epochs along each input dimension, the cut between two
neighbouring first inputs that most reduces the squared deviation of the targets (a regression
tree's split, Breiman et al. 1984) is taken if

- each side holds at least :data:`MIN_SIDE` epochs and each child is at least the tree's
  smallest leaf width (``min_leaf_fraction``) wide,
- the two sides' mean targets differ by at least ``model_split_gap`` (in threshold units), and
- that difference is at least ``model_split_t`` standard errors (pooled variance).

The stored epochs are re-valued under the current values at every test and are not dropped
after a test that fails, so a few visits suffice where the paper's test needs N_th new pairs.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

MIN_SIDE = 2
"""Fewest epochs on each side of a model split (a variance needs two)."""


def choose_model_split(
    firsts: FloatArray,
    targets: FloatArray,
    low: FloatArray,
    high: FloatArray,
    min_width: FloatArray,
    *,
    min_gap: float,
    min_t: float,
) -> tuple[int, float] | None:
    """The (dimension, value) of the model split of one (leaf, action), or None.

    Args:
        firsts: ``(n, d)`` first input of each stored epoch.
        targets: ``(n,)`` eq. (8) target of each epoch under the current values.
        low, high: the leaf's box (``(d,)``).
        min_width: ``(d,)`` narrowest child allowed per dimension.
        min_gap: least difference of the two sides' mean targets (reward units).
        min_t: least difference in pooled standard errors (``inf`` when both sides agree
            exactly within themselves).

    Among the admissible cuts, the one with the largest reduction of the targets' squared
    deviation wins; ties go to the lower dimension, then the lower value.
    """
    n, dims = firsts.shape
    if n < 2 * MIN_SIDE or float(targets.max() - targets.min()) < min_gap:
        return None
    best: tuple[float, int, float] | None = None
    for dim in range(dims):
        order = np.argsort(firsts[:, dim], kind="stable")
        xs = firsts[order, dim]
        ys = targets[order]
        sums = np.cumsum(ys)
        squares = np.cumsum(ys * ys)
        total, total_sq = float(sums[-1]), float(squares[-1])
        for i in range(MIN_SIDE - 1, n - MIN_SIDE):
            if xs[i] == xs[i + 1]:
                continue
            value = 0.5 * (float(xs[i]) + float(xs[i + 1]))
            if value - low[dim] < min_width[dim] or high[dim] - value < min_width[dim]:
                continue
            left_n, right_n = i + 1, n - i - 1
            left_mean = float(sums[i]) / left_n
            right_mean = (total - float(sums[i])) / right_n
            gap = abs(left_mean - right_mean)
            if gap < min_gap:
                continue
            within = (float(squares[i]) - left_n * left_mean**2) + (
                total_sq - float(squares[i]) - right_n * right_mean**2
            )
            spread = math.sqrt(max(within, 0.0) / (n - 2))
            error = spread * math.sqrt(1.0 / left_n + 1.0 / right_n)
            if error > 0.0 and gap / error < min_t:
                continue
            gain = left_n * right_n / n * gap * gap
            if best is None or gain > best[0]:
                best = (gain, dim, value)
    return None if best is None else (best[1], best[2])
