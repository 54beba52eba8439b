"""Collision splits (beyond the paper): cut a leaf where one action's collided and free epochs part.

A leaf beside a pillar or a door post holds places from which an action collides and places
from which the same action passes. Its Q-bar averages the two, so the action is avoided from
the whole leaf and the greedy route goes round (docs/paper-notes.md, "Collision splits").
Section IV.B's test needs N_th new pairs before it splits, and a model split
(:mod:`agent.model_split`) needs ``model_split_epochs`` stored epochs; a route the agent has
given up supplies neither.

With ``TreeConfig.collision_splits`` the learner marks each stored epoch of the model of
``planning="sweep"`` (:mod:`agent.leaf_model`) that ended on a collision (the env's
``info[collision_key]`` at its last step). After an epoch that ended on a collision, when no
other test split its leaf, the stored epochs of (leaf, a) are labelled collided or free, and
the axis-aligned cut between two neighbouring first inputs that leaves the fewest epochs on the
wrong side (each side takes its majority label) is taken, if

- both labels are stored,
- the cut leaves fewer epochs on the wrong side than no cut does, and
- each child is at least the tree's smallest leaf (``min_leaf_fraction``) wide.

Ties go to the cut nearest the middle of the leaf, then to the lower dimension and value. The
children inherit Q-bar and the stored epochs as after any split (eqs. 11-13 choose the paper's
splits; this rule only adds cuts). An env that reports no collisions never triggers it.

With ``TreeConfig.collision_splits_collided_only`` as well, a (leaf, a) whose stored epochs all
collided is cut too (:func:`choose_collided_only_split`): a collision says where it happened,
but with no free epoch to cut against, the whole leaf would keep the collided value, and a long
leaf beside one pillar would give a up along its whole length (issue 9, part 32; the dev forests
`forest:seed=15` and `forest:seed=7`, docs/paper-notes.md, "Cuts for an action that only
collided").
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]


def choose_collision_split(
    firsts: FloatArray,
    collided: BoolArray,
    low: FloatArray,
    high: FloatArray,
    min_width: FloatArray,
) -> tuple[int, float] | None:
    """The (dimension, value) of the collision split of one (leaf, action), or None.

    Args:
        firsts: ``(n, d)`` first input of each stored epoch.
        collided: ``(n,)`` whether each epoch ended on a collision.
        low, high: the leaf's box (``(d,)``).
        min_width: ``(d,)`` narrowest child allowed per dimension.
    """
    n = len(collided)
    bad = int(collided.sum())
    if n < 2 or bad in (0, n):
        return None
    dims = firsts.shape[1]
    best: tuple[int, float, int, float] | None = None
    best_errors = min(bad, n - bad)  # a cut must misplace fewer epochs than no cut
    sizes = np.arange(1, n)
    for dim in range(dims):
        order = np.argsort(firsts[:, dim], kind="stable")
        xs = firsts[order, dim]
        left_bad = np.cumsum(collided[order])[:-1]
        right_bad = bad - left_bad
        errors = np.minimum(left_bad, sizes - left_bad) + np.minimum(
            right_bad, n - sizes - right_bad
        )
        middle, width = 0.5 * (low[dim] + high[dim]), high[dim] - low[dim]
        for i in np.flatnonzero(errors <= best_errors):
            if xs[i] == xs[i + 1]:
                continue
            value = 0.5 * (float(xs[i]) + float(xs[i + 1]))
            if value - low[dim] < min_width[dim] or high[dim] - value < min_width[dim]:
                continue
            key = (int(errors[i]), abs(value - middle) / width, dim, value)
            if key[0] < best_errors or (best is not None and key < best):
                best, best_errors = key, key[0]
    return None if best is None else (best[2], best[3])


def choose_collided_only_split(
    firsts: FloatArray,
    collided: BoolArray,
    low: FloatArray,
    high: FloatArray,
    min_width: FloatArray,
) -> tuple[int, float] | None:
    """``TreeConfig.collision_splits_collided_only``: the (dimension, value) that cuts off the
    largest part of the leaf holding no first input of the collided epochs, or None.

    Only where every stored epoch of (leaf, a) collided (at least one). In each dimension d,
    with the collided first inputs spanning [lo, hi] and w = ``min_width[d]``, the candidates
    are the cuts at lo - w (the part below, lo - w - low[d] wide, holds none of them) and at
    hi + w (the part above, high[d] - hi - w wide); a cut is allowed when both children are at
    least w wide. The widest empty part wins; ties go to the lower dimension, then the lower
    side. The margin w keeps a first input that sits on the cut on its collided side.

    Args:
        firsts: ``(n, d)`` first input of each stored epoch.
        collided: ``(n,)`` whether each epoch ended on a collision.
        low, high: the leaf's box (``(d,)``).
        min_width: ``(d,)`` narrowest child allowed per dimension.
    """
    n = len(collided)
    if n == 0 or int(collided.sum()) != n:
        return None
    best: tuple[float, int, float] | None = None
    for dim in range(firsts.shape[1]):
        lo, hi = float(firsts[:, dim].min()), float(firsts[:, dim].max())
        w = float(min_width[dim])
        for value, empty in (
            (lo - w, lo - w - float(low[dim])),
            (hi + w, float(high[dim]) - hi - w),
        ):
            if value - float(low[dim]) < w or float(high[dim]) - value < w:
                continue
            if best is None or empty > best[0]:
                best = (empty, dim, value)
    return None if best is None else (best[1], best[2])
