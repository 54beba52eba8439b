"""The adaptive tree: lookup, splitting when and only when the three conditions hold."""

from __future__ import annotations

import numpy as np
import pytest

from agent.config import TreeConfig
from agent.partition_tree import PartitionTree


def pairs(
    n: int, offset: float, spread: float, seed: int = 0
) -> tuple[list[list[float]], list[float]]:
    """n inputs in the unit square; error offset + spread where x[1] < 0.3, offset - spread else."""
    rng = np.random.default_rng(seed)
    xs = rng.uniform(0.0, 1.0, size=(n, 2))
    errors = offset + np.where(xs[:, 1] < 0.3, spread, -spread)
    return xs.tolist(), errors.tolist()


def tree(**config: object) -> PartitionTree:
    return PartitionTree([0.0, 0.0], [1.0, 1.0], TreeConfig(split_min_samples=100, **config))  # type: ignore[arg-type]


def test_lookup_and_manual_split() -> None:
    t = tree()
    assert t.leaf_of([0.2, 0.9]) == 0
    left, right = t.split(0, 0, 0.5)
    assert (left, right) == (1, 2)
    assert t.leaf_of([0.2, 0.9]) == 1
    assert t.leaf_of([0.5, 0.1]) == 2
    t.split(2, 1, 0.25)
    assert t.leaf_of([0.7, 0.1]) == 3
    assert t.leaf_of([0.7, 0.3]) == 4
    assert t.leaves() == [1, 3, 4]
    assert t.n_leaves == 3
    assert t.depth == 2
    assert t.leaf_bounds(4) == ([0.5, 0.25], [1.0, 1.0])
    with pytest.raises(ValueError, match="not a leaf"):
        t.split(0, 0, 0.1)
    with pytest.raises(ValueError, match="outside"):
        t.split(1, 0, 0.7)


def test_splits_once_n_th_pairs_satisfy_the_conditions() -> None:
    t = tree()
    xs, errors = pairs(100, 0.0, 0.5)
    assert t.record(0, xs[:99], errors[:99]) is None  # condition 1 not yet
    children = t.record(0, xs[99:], errors[99:])
    assert children == (1, 2)
    assert t._dim[0] == 1  # the dimension along which the errors change sign
    assert 0.15 < t._threshold[0] < 0.65
    # the parent's pairs were divided between the children
    counts = [t.buffer(c).count if t.buffer(c) else 0 for c in children]  # type: ignore[union-attr]
    assert sum(counts) == 100


@pytest.mark.parametrize(
    ("offset", "spread", "why"),
    [(0.6, 0.5, "mean error too large"), (0.0, 0.1, "variance too small")],
)
def test_no_split_when_a_condition_fails(offset: float, spread: float, why: str) -> None:
    t = tree()
    xs, errors = pairs(100, offset, spread)
    assert t.record(0, xs, errors) is None, why
    assert t.n_leaves == 1
    assert t.buffer(0).count == 0  # type: ignore[union-attr]  # "clear": emptied after the test


def test_window_buffer_keeps_the_last_n_th_pairs() -> None:
    t = tree(error_buffer="window")
    xs, errors = pairs(150, 0.6, 0.5)
    assert t.record(0, xs, errors) is None
    assert t.buffer(0).count == 100  # type: ignore[union-attr]
    more_xs, more_errors = pairs(100, 0.0, 0.5, seed=1)
    assert t.record(0, more_xs, more_errors) == (1, 2)


def test_guards_bound_the_tree() -> None:
    t = tree(max_leaves=1)
    xs, errors = pairs(100, 0.0, 0.5)
    assert t.record(0, xs, errors) is None
    narrow = PartitionTree(
        [0.0, 0.0], [1.0, 1.0], TreeConfig(split_min_samples=100, min_leaf_fraction=0.5)
    )
    assert narrow.record(0, xs, errors) == (1, 2)  # exactly two halves still fit
    assert narrow._threshold[0] == 0.5


def test_every_partition_finds_the_same_leaf_for_a_stored_copy() -> None:
    """The model stores inputs as ``array('d')`` copies (agent.leaf_model) and re-files them
    through ``leaf_of`` after a split, so a copy must land where its list does."""
    from array import array

    from agent.adaptive_q import BoxTree
    from agent.uniform_grid import UniformGrid

    t = tree()
    t.split(0, 0, 0.5)
    t.split(2, 1, 0.25)
    boxes = BoxTree([0.0, 0.0], [1.0, 1.0], 0.0, 3)
    boxes.split(0)
    boxes.split(1)
    partitions = [t, UniformGrid([0.0, 0.0], [1.0, 1.0], 7), boxes]
    rng = np.random.default_rng(5)
    for x in rng.uniform(-0.2, 1.2, size=(200, 2)).tolist():
        for partition in partitions:
            assert partition.leaf_of(array("d", x)) == partition.leaf_of(x)
