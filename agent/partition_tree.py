"""The paper's adaptive decision tree over the observation box (section IV.B).

A binary tree stored in flat Python lists indexed by node id (the per-step leaf lookup walks
plain lists, which is several times faster than NumPy for one vector). A node is a leaf while
``dim[node] == -1``; an internal node sends ``x[dim] < threshold`` to its left child
``left[node]`` and the rest to ``left[node] + 1``. Node ids are never reused, so leaf ids
are stable until the leaf splits. Each leaf holds a bounded :class:`ErrorBuffer` of
state-error pairs; when the three conditions hold the leaf splits along the dimension of eq. (12)
at the point of eq. (13).

A dimension whose declared bounds are infinite (CartPole's velocities) is "grown from the data":
the root is unbounded there, and wherever eq. (12)'s range_i, the minimum leaf width and the
clipping of eq. (13)'s split point need a width, the leaf's box is cut to the smallest and
largest value that dimension has shown in any stored state-error pair so far (``seen_bounds``).
Bounded dimensions use their declared bounds, as before.

Integer inputs (``integer=True``: an integer-typed observation box, :mod:`agent.spaces`) are
cells ``[k - 0.5, k + 0.5]``: no child is narrower than one cell, and with
``TreeConfig.table_cells`` a box of few enough cells starts as a table, one leaf per cell.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from agent.config import TreeConfig
from agent.error_buffer import ErrorBuffer
from agent.split_statistics import choose_split, should_split

if TYPE_CHECKING:
    from agent.scale import ReturnScale, ReturnSpread, RewardScale


class PartitionTree:
    """Adaptive binary partition of ``[low, high]`` (section IV.B)."""

    kind = "tree"
    records_errors = True

    def __init__(
        self, low: list[float], high: list[float], config: TreeConfig, integer: bool = False
    ) -> None:
        self.config = config
        self.dims = len(low)
        self.integer = integer
        """Whether the inputs are integers, each the cell ``[k - 0.5, k + 0.5]``."""
        self.root_low = [float(v) for v in low]
        self.root_high = [float(v) for v in high]
        self._unbounded = [
            not (math.isfinite(lo) and math.isfinite(hi))
            for lo, hi in zip(self.root_low, self.root_high, strict=True)
        ]
        self._grown = [d for d, free in enumerate(self._unbounded) if free]
        """Dimensions whose bounds are grown from the data."""
        self._seen_low = [math.inf] * self.dims
        self._seen_high = [-math.inf] * self.dims
        self._root_width = np.asarray(self.root_high) - np.asarray(self.root_low)
        self.scale: ReturnScale | ReturnSpread | RewardScale | None = None
        """Set by the agent when ``config.threshold_units == "scale"``: the split thresholds are
        then multiples of ``scale.value`` (the variance threshold of its square)."""
        self._dim: list[int] = [-1]
        self._threshold: list[float] = [0.0]
        self._left: list[int] = [-1]
        self._parent: list[int] = [-1]
        self._low: list[list[float]] = [list(self.root_low)]
        self._high: list[list[float]] = [list(self.root_high)]
        self._depth: list[int] = [0]
        self._buffers: dict[int, ErrorBuffer] = {}
        self.n_leaves = 1
        cuts = self._table_cuts()
        if cuts is not None:
            for d, points in enumerate(cuts):
                self._cut_every_leaf(d, points)
            return
        depth = config.initial_depth + self._presplit_dimensions()
        if depth > 16:
            raise ValueError(
                f"the tree would start with 2^{depth} leaves (initial_depth "
                f"{config.initial_depth}, presplit_each_dimension over {self.dims} dimensions); "
                "at most 2^16: set TreeConfig.presplit_max_dimensions to presplit fewer"
            )
        self._presplit(depth)

    def _presplit_dimensions(self) -> int:
        """How many dimensions ``presplit_each_dimension`` splits: every one, unless the input
        has more than ``presplit_max_dimensions``; then its first
        ``presplit_beyond_dimensions``."""
        config = self.config
        if not config.presplit_each_dimension:
            return 0
        most = config.presplit_max_dimensions
        if most is None or self.dims <= most:
            return self.dims
        return min(config.presplit_beyond_dimensions, self.dims)

    def _presplit(self, depth: int) -> None:
        """``TreeConfig.initial_depth``: split every leaf at its midpoint, level by level, along
        the dimensions in turn (an unbounded dimension once, at 0)."""
        order: list[int] = []
        used_unbounded: set[int] = set()
        dim = 0
        while len(order) < depth and (len(used_unbounded) < self.dims):
            d = dim % self.dims
            dim += 1
            if self._unbounded[d]:
                if d in used_unbounded:
                    if all(self._unbounded):
                        break
                    continue
                used_unbounded.add(d)
            order.append(d)
            if dim > 64 * self.dims:
                break
        for d in order:
            for leaf in self.leaves():
                low, high = self._low[leaf][d], self._high[leaf][d]
                if math.isfinite(low) and math.isfinite(high):
                    point = self._presplit_point(d, low, high)
                elif low < (point := self._unbounded_presplit_point(d)) < high:
                    pass
                elif low < 0.0 < high:
                    point = 0.0
                else:
                    continue
                self.split(leaf, d, point)

    def _table_cuts(self) -> list[list[float]] | None:
        """``TreeConfig.table_cells``: per dimension, the half-integers strictly inside the root
        box, when the inputs are integers, the box is bounded and it holds at most
        ``table_cells`` cells; None otherwise (no table)."""
        budget = self.config.table_cells
        if budget is None or not self.integer or any(self._unbounded):
            return None
        cuts: list[list[float]] = []
        cells = 1
        for low, high in zip(self.root_low, self.root_high, strict=True):
            first, last = math.floor(low + 0.5) + 0.5, math.ceil(high - 0.5) - 0.5
            if first <= low:
                first += 1.0
            if last >= high:
                last -= 1.0
            count = max(0, int(last - first) + 1)
            cells *= count + 1
            if cells > budget:
                return None
            cuts.append([first + i for i in range(count)])
        return cuts

    def _cut_every_leaf(self, dim: int, points: list[float]) -> None:
        """Split every leaf at each of ``points`` along ``dim``, halving the points at each
        level (the table's depth grows as log2 of its cells)."""
        pending = [(leaf, points) for leaf in self.leaves()]
        while pending:
            leaf, cut = pending.pop()
            if not cut:
                continue
            middle = len(cut) // 2
            left, right = self.split(leaf, dim, cut[middle])
            pending += [(left, cut[:middle]), (right, cut[middle + 1 :])]

    def _presplit_point(self, dim: int, low: float, high: float) -> float:
        """Where the presplit cuts a bounded dimension: the midpoint (a shifted tree of
        :mod:`agent.tree_ensemble` moves it)."""
        return 0.5 * (low + high)

    def _unbounded_presplit_point(self, dim: int) -> float:
        """Where the presplit cuts an unbounded dimension, if inside the leaf: 0 (a shifted
        tree moves it with ``TreeConfig.ensemble_unbounded_offsets``)."""
        return 0.0

    @property
    def n_ids(self) -> int:
        return len(self._dim)

    @property
    def depth(self) -> int:
        """Largest leaf depth (0 for the root alone)."""
        return max(self._depth[leaf] for leaf in self.leaves())

    def leaf_of(self, x: Sequence[float]) -> int:
        dims, thresholds, left = self._dim, self._threshold, self._left
        node = 0
        d = dims[0]
        while d >= 0:
            node = left[node] if x[d] < thresholds[node] else left[node] + 1
            d = dims[node]
        return node

    def leaves(self) -> list[int]:
        return [node for node, d in enumerate(self._dim) if d < 0]

    def is_leaf(self, node: int) -> bool:
        return 0 <= node < len(self._dim) and self._dim[node] < 0

    def parent(self, node: int) -> int:
        """Id of the node that split into ``node`` (-1 for the root)."""
        return self._parent[node]

    def children(self, node: int) -> tuple[int, int] | None:
        """Ids of the two halves ``node`` split into (None for a leaf)."""
        if self._dim[node] < 0:
            return None
        first = self._left[node]
        return first, first + 1

    def leaf_bounds(self, leaf: int) -> tuple[list[float], list[float]]:
        return list(self._low[leaf]), list(self._high[leaf])

    @property
    def cuts(self) -> list[tuple[int, float]]:
        """Every node's (dimension, threshold) in node order; (-1, 0.0) for a leaf. Two trees
        with equal cuts partition the inputs alike."""
        return list(zip(self._dim, self._threshold, strict=True))

    def leaf_depth(self, leaf: int) -> int:
        return self._depth[leaf]

    def buffer(self, leaf: int) -> ErrorBuffer | None:
        """The leaf's state-error pairs (None until it has any)."""
        return self._buffers.get(leaf)

    def record(
        self, leaf: int, xs: list[list[float]], errors: list[float]
    ) -> tuple[int, int] | None:
        """Store the pairs, then run the split test of section IV.B once N_th pairs are held.

        In ``error_buffer="clear"`` mode the pairs are dropped after each test that does not
        split; in ``"window"`` mode the buffer is a FIFO of the last N_th pairs, tested each epoch.
        """
        cfg = self.config
        for d in self._grown:
            seen_low, seen_high = self._seen_low[d], self._seen_high[d]
            for x in xs:
                v = x[d]
                if v < seen_low:
                    seen_low = v
                if v > seen_high:
                    seen_high = v
            self._seen_low[d], self._seen_high[d] = seen_low, seen_high
        buf = self._buffers.get(leaf)
        if buf is None:
            buf = self._buffers[leaf] = ErrorBuffer(self.dims, cfg.split_min_samples)
        buf.add(xs, errors)
        if buf.count < cfg.split_min_samples:
            return None
        mean, variance = buf.mean_variance()
        max_abs_mean, min_variance = cfg.split_max_abs_mean, cfg.split_min_variance
        if self.scale is not None:
            unit = self.scale.value
            max_abs_mean, min_variance = max_abs_mean * unit, min_variance * unit * unit
        children = None
        if should_split(
            buf.count,
            mean,
            variance,
            min_samples=cfg.split_min_samples,
            max_abs_mean=max_abs_mean,
            min_variance=min_variance,
        ):
            children = self._try_split(leaf, buf)
        if children is None and cfg.error_buffer == "clear":
            buf.clear()
        return children

    def may_split(self) -> bool:
        """Whether the tree may grow a leaf now (``max_leaves``)."""
        return self.n_leaves < self.config.max_leaves

    def split_box(self, leaf: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """A leaf's box and the root's width (unbounded dimensions cut to the data), and the
        narrowest child allowed in each dimension (``min_leaf_fraction`` of the root's width)."""
        low, high = np.asarray(self._low[leaf]), np.asarray(self._high[leaf])
        root_width = self._root_width
        if self._grown:
            low, high, root_width = self._grown_box(low, high)
        min_width = root_width * self.config.min_leaf_fraction
        if self.integer:
            min_width = np.maximum(min_width, 1.0)  # a child holds at least one integer
        return low, high, root_width, min_width

    def split_with_samples(self, leaf: int, dim: int, value: float) -> tuple[int, int]:
        """:meth:`split`, handing the leaf's state-error pairs to the child that holds each
        (``children_inherit_samples``; else they are dropped)."""
        buf = self._buffers.get(leaf)
        children = self.split(leaf, dim, value)
        if self.config.children_inherit_samples and buf is not None and buf.count:
            inputs, errors = buf.arrays()
            goes_left = inputs[:, dim] < value
            for child, mask in zip(children, (goes_left, ~goes_left), strict=True):
                if mask.any():
                    child_buf = ErrorBuffer(self.dims, self.config.split_min_samples)
                    child_buf.add(inputs[mask].tolist(), errors[mask].tolist())
                    self._buffers[child] = child_buf
        return children

    def _try_split(self, leaf: int, buf: ErrorBuffer) -> tuple[int, int] | None:
        if not self.may_split():
            return None
        low, high, root_width, min_width = self.split_box(leaf)
        if not ((high - low) >= 2.0 * min_width).any():
            return None  # checked before copying the buffer: in "window" mode this runs each epoch
        inputs, errors = buf.arrays()
        ranges = high - low
        if self.config.range_normalization == "root":
            with np.errstate(divide="ignore", invalid="ignore"):
                ranges = np.where(root_width > 0.0, ranges / root_width, 0.0)
        choice = choose_split(
            inputs,
            errors,
            low,
            high,
            ranges,
            min_width,
            self.config.split_point,
            self.config.split_min_t,
        )
        if choice is None:
            return None
        dim, value = choice
        return self.split_with_samples(leaf, dim, value)

    def _grown_box(
        self, low: np.ndarray, high: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """A leaf's box and the root's width with the unbounded dimensions cut to the data.

        A dimension that has shown no value yet (or a single one) gets width 0, so it is not
        eligible for a split.
        """
        low, high = low.copy(), high.copy()
        root_width = self._root_width.copy()
        for d in self._grown:
            seen_low, seen_high = self._seen_low[d], self._seen_high[d]
            if not seen_low < seen_high:
                low[d] = high[d] = root_width[d] = 0.0
                continue
            low[d] = min(max(low[d], seen_low), seen_high)
            high[d] = max(min(high[d], seen_high), seen_low)
            root_width[d] = seen_high - seen_low
        return low, high, root_width

    @property
    def seen_bounds(self) -> tuple[list[float], list[float]]:
        """Smallest and largest value each unbounded dimension has shown (inf, -inf: none)."""
        return list(self._seen_low), list(self._seen_high)

    def split(self, leaf: int, dim: int, value: float) -> tuple[int, int]:
        """Split ``leaf`` at ``x[dim] = value`` into two new leaves; returns their ids."""
        if self._dim[leaf] >= 0:
            raise ValueError(f"node {leaf} is not a leaf")
        if not 0 <= dim < self.dims:
            raise ValueError(f"split dimension {dim} outside 0..{self.dims - 1}")
        low, high = self._low[leaf], self._high[leaf]
        if not low[dim] < value < high[dim]:
            raise ValueError(
                f"split value {value} outside leaf {leaf}'s range ({low[dim]}, {high[dim]}) "
                f"in dimension {dim}"
            )
        first = len(self._dim)
        self._dim[leaf] = dim
        self._threshold[leaf] = float(value)
        self._left[leaf] = first
        left_high = list(high)
        left_high[dim] = float(value)
        right_low = list(low)
        right_low[dim] = float(value)
        for child_low, child_high in ((list(low), left_high), (right_low, list(high))):
            self._dim.append(-1)
            self._threshold.append(0.0)
            self._left.append(-1)
            self._parent.append(leaf)
            self._low.append(child_low)
            self._high.append(child_high)
            self._depth.append(self._depth[leaf] + 1)
        self._buffers.pop(leaf, None)
        self.n_leaves += 1
        return first, first + 1

    def render_lines(self, describe_leaf: Callable[[int], str]) -> list[str]:
        lines: list[str] = []
        stack: list[tuple[int, str]] = [(0, "")]
        while stack:
            node, label = stack.pop()
            indent = "  " * self._depth[node]
            d = self._dim[node]
            if d < 0:
                lines.append(f"{indent}{label}{describe_leaf(node)}")
                continue
            t = self._threshold[node]
            lines.append(f"{indent}{label}node {node}: split x[{d}] at {t:.6g}")
            left = self._left[node]
            stack.append((left + 1, f"x[{d}] >= {t:.6g}: "))
            stack.append((left, f"x[{d}] < {t:.6g}: "))
        return lines

    def to_arrays(self) -> tuple[dict[str, Any], dict[str, Any]]:
        arrays: dict[str, Any] = {
            "dim": np.asarray(self._dim, dtype=np.int64),
            "threshold": np.asarray(self._threshold, dtype=np.float64),
            "left": np.asarray(self._left, dtype=np.int64),
            "parent": np.asarray(self._parent, dtype=np.int64),
            "low": np.asarray(self._low, dtype=np.float64),
            "high": np.asarray(self._high, dtype=np.float64),
            "depth": np.asarray(self._depth, dtype=np.int64),
        }
        leaves = sorted(self._buffers)
        capacity = self.config.split_min_samples
        states = [self._buffers[leaf].state() for leaf in leaves]
        arrays["buffer_leaf"] = np.asarray(leaves, dtype=np.int64)
        arrays["buffer_inputs"] = np.asarray([s[0] for s in states], dtype=np.float64).reshape(
            len(leaves), capacity * self.dims
        )
        arrays["buffer_errors"] = np.asarray([s[1] for s in states], dtype=np.float64).reshape(
            len(leaves), capacity
        )
        arrays["buffer_counters"] = np.asarray([s[2] for s in states], dtype=np.float64).reshape(
            len(leaves), 4
        )
        arrays["seen_low"] = np.asarray(self._seen_low, dtype=np.float64)
        arrays["seen_high"] = np.asarray(self._seen_high, dtype=np.float64)
        return arrays, {"root_low": self.root_low, "root_high": self.root_high}

    @classmethod
    def from_arrays(
        cls,
        arrays: dict[str, NDArray[Any]],
        meta: dict[str, Any],
        config: TreeConfig,
        integer: bool = False,
    ) -> PartitionTree:
        """Inverse of :meth:`to_arrays` (``integer``: the observation box's, which the file
        keeps as its dtype)."""
        tree = cls(meta["root_low"], meta["root_high"], config, integer)
        if "seen_low" in arrays:
            tree._seen_low = [float(v) for v in arrays["seen_low"]]
            tree._seen_high = [float(v) for v in arrays["seen_high"]]
        tree._dim = [int(v) for v in arrays["dim"]]
        tree._threshold = [float(v) for v in arrays["threshold"]]
        tree._left = [int(v) for v in arrays["left"]]
        tree._parent = [int(v) for v in arrays["parent"]]
        tree._low = arrays["low"].tolist()
        tree._high = arrays["high"].tolist()
        tree._depth = [int(v) for v in arrays["depth"]]
        tree.n_leaves = sum(1 for d in tree._dim if d < 0)
        counters = arrays["buffer_counters"]
        for row, leaf in enumerate(arrays["buffer_leaf"].tolist()):
            c = counters[row]
            tree._buffers[leaf] = ErrorBuffer.restore(
                tree.dims,
                config.split_min_samples,
                arrays["buffer_inputs"][row],
                arrays["buffer_errors"][row],
                [int(c[0]), int(c[1]), float(c[2]), float(c[3])],
            )
        return tree


class GatedPartitionTree(PartitionTree):
    """The tree with a leaf budget that grows with the terminal transitions seen (beyond the
    paper; ``TreeConfig.leaves_per_terminal``).

    The split test is the paper's (:meth:`PartitionTree.record`); a leaf that passes it splits
    only while the tree holds fewer than its initial leaves + ``leaves_per_terminal`` x
    :attr:`terminals` leaves. Its pairs are then dropped as after any failed test
    (``error_buffer="clear"``), so the leaf is tested again on fresh errors.
    """

    def __init__(
        self, low: list[float], high: list[float], config: TreeConfig, integer: bool = False
    ) -> None:
        super().__init__(low, high, config, integer)
        self.initial_leaves = self.n_leaves
        """Leaves after the presplit (the budget's base)."""
        self.terminals = 0
        """Terminal transitions seen so far (the learner counts them)."""

    @property
    def leaf_budget(self) -> int:
        """Most leaves the tree may hold now."""
        grown = self.initial_leaves + self.config.leaves_per_terminal * self.terminals
        return min(grown, self.config.max_leaves)

    def may_split(self) -> bool:
        """Whether the tree may grow a leaf now (the budget, :attr:`leaf_budget`)."""
        return self.n_leaves < self.leaf_budget
