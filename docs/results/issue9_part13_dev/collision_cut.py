"""Part 13 dev prototype (not an agent option): cut a leaf where one action's collided and
free epochs separate.

The midpoint prototype (``collision_split.py``) splits blindly. This one, after an epoch that
ended on a collision (its last reward at most -0.5), looks at the model's stored epochs of
the same (leaf, action), labels each collided (its mean reward at most -0.5) or free, and
takes the axis-aligned cut between two neighbouring first inputs that leaves the fewest
epochs on the wrong side (each side's majority label; ties to the cut nearest the middle),
if both labels are present, the cut misclassifies fewer than the leaf unsplit does, and each
child is at least the smallest leaf width. Only when no other test split the leaf. Then part
8's maze driver (600 episodes) appends to ``maze_collision.jsonl``::

    PYTHONPATH=. python docs/results/issue9_part13_dev/collision_cut.py "forest:seed=0" 0
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "issue9_hold_terminals_dev"))
import curves  # noqa: E402  (part 8's maze driver, beside this folder)
from collision_split import patch_collision_splits  # noqa: E402  (the shared patch, beside this)


def best_cut(
    firsts: np.ndarray, bad: np.ndarray, low: np.ndarray, high: np.ndarray, min_width: np.ndarray
) -> tuple[int, float] | None:
    """The (dimension, value) that best separates ``bad`` from the rest, or None."""
    n = len(bad)
    unsplit = min(int(bad.sum()), n - int(bad.sum()))
    best: tuple[int, float] | None = None
    best_key = (unsplit, 0.0)
    for dim in range(firsts.shape[1]):
        order = np.argsort(firsts[:, dim], kind="stable")
        xs, labels = firsts[order, dim], bad[order]
        left_bad = np.cumsum(labels)[:-1]
        sizes = np.arange(1, n)
        right_bad = int(labels.sum()) - left_bad
        errors = np.minimum(left_bad, sizes - left_bad) + np.minimum(
            right_bad, n - sizes - right_bad
        )
        for i in range(n - 1):
            if xs[i] == xs[i + 1]:
                continue
            value = 0.5 * (xs[i] + xs[i + 1])
            if value - low[dim] < min_width[dim] or high[dim] - value < min_width[dim]:
                continue
            key = (
                int(errors[i]),
                abs(value - 0.5 * (low[dim] + high[dim])) / (high[dim] - low[dim]),
            )
            if key < best_key:
                best_key, best = key, (dim, value)
    return best  # ranked by (errors, distance from the middle)


def patch() -> None:
    def separating_cut(self: Any, leaf: int, action: int) -> Any:
        partition, model = self.partition, self.model
        records = model._records.get(leaf * self.n_actions + action) if model else None
        if not records or len(records) < 2:
            return None
        bad = np.array([r[1] <= -0.5 for r in records])
        if bad.all() or not bad.any():
            return None
        firsts = np.array([r[0] for r in records], dtype=np.float64)
        low, high, _, min_width = partition.split_box(leaf)
        cut = best_cut(firsts, bad, low, high, min_width)
        return None if cut is None else partition.split_with_samples(leaf, *cut)

    patch_collision_splits(separating_cut)


if __name__ == "__main__":
    maze, seed = sys.argv[1], int(sys.argv[2])
    patch()
    curves.run(maze, seed, "ccut", {}, HERE / "maze_collision.jsonl")
