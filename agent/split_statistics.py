"""The statistics that decide whether, where and along which dimension a leaf splits (section IV.B).

Pure functions on NumPy arrays of a leaf's state-error pairs ``(s_k, delta_k)``:
the three-condition test, the split dimension of eq. (12) and the split point of eq. (13).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


def should_split(
    n_samples: int,
    error_mean: float,
    error_variance: float,
    *,
    min_samples: int,
    max_abs_mean: float,
    min_variance: float,
) -> bool:
    """The three split conditions of section IV.B, all at once.

    1. the leaf holds at least ``min_samples`` = N_th state-error pairs (the paper prints
       "smaller than"; read as "at least", see docs/paper-notes.md),
    2. ``|mu_e| < mu_th`` (the estimate has settled on average),
    3. ``sigma_e^2 > sigma_th^2`` (the inputs of the leaf disagree).
    """
    return (
        n_samples >= min_samples
        and abs(error_mean) < max_abs_mean
        and error_variance > min_variance
    )


def t_statistics(positive: FloatArray, negative: FloatArray, ranges: FloatArray) -> FloatArray:
    """Eq. (12): range-weighted Welch t statistic of each input dimension.

    ``t_i = range_i |mu_1i - mu_2i| / sqrt(s_1i^2 / n_1 + s_2i^2 / n_2)`` where group 1 holds the
    inputs with a positive estimation error and group 2 those with a negative one, and s^2 is the
    unbiased sample variance. A dimension in which both groups are constant gets ``inf`` if their
    means differ, else 0.

    Args:
        positive: ``(n_1, d)`` inputs of group g_1 (n_1 >= 2).
        negative: ``(n_2, d)`` inputs of group g_2 (n_2 >= 2).
        ranges: ``(d,)`` range_i of the leaf (already normalised if so configured).
    """
    n1, n2 = positive.shape[0], negative.shape[0]
    if n1 < 2 or n2 < 2:
        raise ValueError(f"eq. (12) needs at least 2 samples per group, got {n1} and {n2}")
    gap = np.abs(positive.mean(axis=0) - negative.mean(axis=0))
    spread = np.sqrt(positive.var(axis=0, ddof=1) / n1 + negative.var(axis=0, ddof=1) / n2)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(
            spread > 0.0, gap / np.where(spread > 0.0, spread, 1.0), np.where(gap > 0, np.inf, 0.0)
        )
    return np.asarray(ranges, dtype=np.float64) * t


def density_crossing(
    mean1: float, var1: float, n1: int, mean2: float, var2: float, n2: int
) -> float | None:
    """Eq. (13): the point between the two means where n_j N(mu_j, sigma_j^2) are equal.

    Solves the QUEST quadratic (Loh and Shih, 1997)
    ``(v1 - v2) x^2 + 2 (m1 v2 - m2 v1) x + m2^2 v1 - m1^2 v2 + 2 v1 v2 ln(n1 s2 / (n2 s1)) = 0``
    with ``v_j = sigma_j^2`` and ``s_j = sigma_j`` (natural logarithm), linear when the variances
    are equal. Returns the root strictly between the means (the one nearest their midpoint if
    there are two), or None if there is none (equal means, a zero variance, complex roots, roots
    outside the means).
    """
    if mean1 == mean2 or var1 <= 0.0 or var2 <= 0.0 or n1 <= 0 or n2 <= 0:
        return None
    log_term = 2.0 * var1 * var2 * math.log(n1 * math.sqrt(var2) / (n2 * math.sqrt(var1)))
    a = var1 - var2
    b = 2.0 * (mean1 * var2 - mean2 * var1)
    c = mean2 * mean2 * var1 - mean1 * mean1 * var2 + log_term
    if abs(a) <= 1e-12 * max(var1, var2):
        roots = [-c / b] if b != 0.0 else []
    else:
        disc = b * b - 4.0 * a * c
        if disc < 0.0:
            return None
        sq = math.sqrt(disc)
        roots = [(-b - sq) / (2.0 * a), (-b + sq) / (2.0 * a)]
    low, high = min(mean1, mean2), max(mean1, mean2)
    inside = [r for r in roots if low < r < high]
    if not inside:
        return None
    middle = 0.5 * (mean1 + mean2)
    return min(inside, key=lambda r: abs(r - middle))


def split_point(
    positive: FloatArray,
    negative: FloatArray,
    low: float,
    high: float,
    margin: float,
    rule: str = "quest",
) -> float:
    """Eq. (13) in one dimension with its fallback, never outside the leaf.

    ``rule="quest"``: the density crossing of :func:`density_crossing` (unbiased sample
    variances); without one, the midpoint of the two means. ``rule="midpoint"``: always the
    midpoint of the two means (the alternative reading). The result is clipped to
    ``[low + margin, high - margin]`` so that neither child is narrower than ``margin``.
    """
    m1, m2 = float(positive.mean()), float(negative.mean())
    point = None
    if rule == "quest":
        v1, v2 = float(positive.var(ddof=1)), float(negative.var(ddof=1))
        point = density_crossing(m1, v1, positive.shape[0], m2, v2, negative.shape[0])
    elif rule != "midpoint":
        raise ValueError(f"split point rule must be 'quest' or 'midpoint', got {rule!r}")
    if point is None:
        point = 0.5 * (m1 + m2)
    return min(max(point, low + margin), high - margin)


def choose_split(
    inputs: FloatArray,
    errors: FloatArray,
    low: FloatArray,
    high: FloatArray,
    ranges: FloatArray,
    min_width: FloatArray,
    point_rule: str = "quest",
    min_t: float = 0.0,
) -> tuple[int, float] | None:
    """Split dimension by eq. (12) and split point by eq. (13) for one leaf.

    Inputs with a positive error form g_1, those with a negative error g_2 (a zero error joins
    neither). Dimensions too narrow to leave two children of ``min_width`` are not eligible.
    ``point_rule`` is passed to :func:`split_point`.
    ``min_t`` (beyond the paper; 0 turns it off) is a significance gate: no split unless some
    eligible dimension's Welch t statistic, without eq. (12)'s range weight, reaches it, i.e.
    unless the inputs with positive and negative errors lie apart in the leaf by more than the
    noise of their positions explains.
    Returns ``(dimension, value)`` or None when no dimension is eligible, a group has fewer than
    two samples or the gate is not passed.
    """
    pos, neg = inputs[errors > 0.0], inputs[errors < 0.0]
    if pos.shape[0] < 2 or neg.shape[0] < 2:
        return None
    eligible = (high - low) >= 2.0 * min_width
    if not eligible.any():
        return None
    if min_t > 0.0:
        raw = t_statistics(pos, neg, np.ones(inputs.shape[1]))
        if not (np.where(eligible, raw, -np.inf) >= min_t).any():
            return None
    t = t_statistics(pos, neg, ranges)
    t = np.where(eligible, t, -np.inf)
    dim = int(np.argmax(t))
    value = split_point(
        pos[:, dim],
        neg[:, dim],
        float(low[dim]),
        float(high[dim]),
        float(min_width[dim]),
        point_rule,
    )
    return dim, value
