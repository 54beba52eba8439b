"""The interface shared by the two state partitions behind the learner.

The learner (:mod:`agent.learner`) owns Q-bar, the visit counts and the SMDP epochs; a
partition only maps an input vector to a leaf id and, if it adapts, receives the state-error
pairs of each epoch and may split a leaf. :class:`~agent.partition_tree.PartitionTree` is the
paper's adaptive decision tree (section IV.B), :class:`~agent.uniform_grid.UniformGrid` the
fixed uniform grid baseline.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray


class Partition(Protocol):
    """A partition of the observation box into leaves with integer ids."""

    kind: str
    """"tree" or "grid" (the saved file says which)."""
    records_errors: bool
    """Whether :meth:`record` does anything (the learner skips computing errors if not)."""
    n_leaves: int

    @property
    def n_ids(self) -> int:
        """Leaf ids are below this; the learner's tables have this many rows."""
        ...

    def leaf_of(self, x: Sequence[float]) -> int:
        """Leaf id of the input vector ``x`` (a list of floats, for speed, or a stored copy)."""
        ...

    def leaves(self) -> list[int]:
        """Ids of the current leaves."""
        ...

    def is_leaf(self, node: int) -> bool:
        """Whether ``node`` (an int) is the id of a current leaf."""
        ...

    def leaf_bounds(self, leaf: int) -> tuple[list[float], list[float]]:
        """Lower and upper corner of a leaf's box."""
        ...

    def leaf_depth(self, leaf: int) -> int:
        """Depth of a leaf (0 for the root of a tree; 0 for every grid cell)."""
        ...

    def record(
        self, leaf: int, xs: list[list[float]], errors: list[float]
    ) -> tuple[int, int] | None:
        """Store an epoch's state-error pairs; return the children if ``leaf`` split."""
        ...

    def render_lines(self, describe_leaf: Any) -> list[str]:
        """Text rendering, one line per node; ``describe_leaf(leaf) -> str`` labels leaves."""
        ...

    def to_arrays(
        self,
    ) -> tuple[dict[str, NDArray[np.float64] | NDArray[np.int64]], dict[str, Any]]:
        """Arrays and JSON-ready metadata that :func:`agent.serialization` saves."""
        ...
