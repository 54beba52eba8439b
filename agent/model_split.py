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


def spread_below(targets: list[float], min_gap: float) -> bool:
    """Whether the targets' range is below ``min_gap``: :func:`choose_model_split`'s first test
    (it then returns None), in plain Python, so that a caller skips building the arrays and the
    leaf's box for the three tests in four that end there (issue 9, part 34:
    ``bench/bench_model_split.py``)."""
    return max(targets) - min(targets) < min_gap


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
    if n < 2 * MIN_SIDE or spread_below(targets.tolist(), min_gap):
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


def choose_policy_split(
    firsts: FloatArray,
    targets: FloatArray,
    other_firsts: FloatArray,
    other_targets: FloatArray,
    low: FloatArray,
    high: FloatArray,
    min_width: FloatArray,
    *,
    min_gap: float,
    min_t: float,
) -> tuple[float, int, float] | None:
    """The (t, dimension, value) of the policy split of one leaf between actions a and b, or
    None (``TreeConfig.policy_splits``).

    Args:
        firsts, targets: the stored epochs of a: ``(n_a, d)`` first inputs and ``(n_a,)``
            eq. (8) targets under the current values.
        other_firsts, other_targets: the same for b.
        low, high, min_width: the leaf's box and the narrowest child allowed (``(d,)``).
        min_gap: least change of the advantage across the cut (reward units).
        min_t: least change in pooled standard errors.

    A cut along one input divides both actions' epochs. With the mean targets of a and b on
    each side, the advantages ``d_L = a_L - b_L`` and ``d_R = a_R - b_R`` must have opposite
    signs (eq. (11)'s greedy choice between a and b flips across the cut), each side must hold
    at least :data:`MIN_SIDE` epochs of each action, each child must be at least
    ``min_width`` wide, and ``|d_L - d_R|`` must be at least ``min_gap`` and at least
    ``min_t`` standard errors (the variance pooled within the four groups, ``n - 4`` degrees
    of freedom; ``inf`` when every group agrees within itself). Among the admissible cuts
    the largest t wins; ties go to the lower dimension, then the lower value. This is the
    policy-disagreement split of Munos and Moore (2002, "Variable resolution discretization
    in optimal control"), read on the stored epochs.
    """
    n_a, n_b = len(targets), len(other_targets)
    n = n_a + n_b
    if n_a < 2 * MIN_SIDE or n_b < 2 * MIN_SIDE:
        return None
    # |d_L - d_R| = |(a_L - a_R) - (b_L - b_R)| is at most the sum of the targets' ranges
    if float(np.ptp(targets)) + float(np.ptp(other_targets)) < min_gap:
        return None
    xs = np.concatenate([firsts, other_firsts])
    ys = np.concatenate([targets, other_targets])
    is_a = np.concatenate([np.ones(n_a), np.zeros(n_b)])
    order = np.argsort(xs, axis=0, kind="stable")  # (n, d): each input's order
    x = np.take_along_axis(xs, order, axis=0)
    y = ys[order]
    in_a = is_a[order]
    in_b = 1.0 - in_a
    # left-side sums at each cut i (between sorted positions i and i + 1)
    count_a = np.cumsum(in_a, axis=0)[:-1]
    count_b = np.cumsum(in_b, axis=0)[:-1]
    sum_a = np.cumsum(y * in_a, axis=0)[:-1]
    sum_b = np.cumsum(y * in_b, axis=0)[:-1]
    square_a = np.cumsum(y * y * in_a, axis=0)[:-1]
    square_b = np.cumsum(y * y * in_b, axis=0)[:-1]
    total_a, total_b = float(targets.sum()), float(other_targets.sum())
    total_square_a = float(np.dot(targets, targets))
    total_square_b = float(np.dot(other_targets, other_targets))
    groups = (
        (count_a, sum_a, square_a),
        (count_b, sum_b, square_b),
        (n_a - count_a, total_a - sum_a, total_square_a - square_a),
        (n_b - count_b, total_b - sum_b, total_square_b - square_b),
    )
    value = 0.5 * (x[:-1] + x[1:])
    ok = (x[:-1] != x[1:]) & (value - low >= min_width) & (high - value >= min_width)
    for count, _, _ in groups:
        ok &= count >= MIN_SIDE
    if not ok.any():
        return None
    safe = [np.maximum(count, 1.0) for count, _, _ in groups]
    means = [total / c for (_, total, _), c in zip(groups, safe, strict=True)]
    within = sum(
        square - count * mean * mean for (count, _, square), mean in zip(groups, means, strict=True)
    )
    advantage_left, advantage_right = means[0] - means[1], means[2] - means[3]
    change = np.abs(advantage_left - advantage_right)
    spread = np.sqrt(np.maximum(within, 0.0) / (n - 4))
    error = spread * np.sqrt(sum(1.0 / c for c in safe))
    with np.errstate(divide="ignore"):
        t = np.where(error > 0.0, change / np.where(error > 0.0, error, 1.0), math.inf)
    ok &= (advantage_left * advantage_right < 0.0) & (change >= min_gap) & (t >= min_t)
    if not ok.any():
        return None
    score = np.where(ok, t, -1.0)
    # the largest t; ties: the lower dimension, then the lower value (the cuts of one input
    # are in increasing order, and argmax takes the first)
    best_t = float(score.max())
    best: tuple[float, int, float] | None = None
    for dim in range(xs.shape[1]):
        hits = np.flatnonzero(score[:, dim] == best_t)
        if hits.size:
            best = (best_t, dim, float(value[hits[0], dim]))
            break
    return best
