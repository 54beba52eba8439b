"""The fixed uniform grid baseline: the paper's "divide the state space uniformly" (section I)."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

MAX_GRID_CELLS = 1_000_000
"""Most cells a uniform grid may have (Q-bar holds a row of floats per cell)."""


class UniformGrid:
    """``resolution[i]`` equal cells per dimension over ``[low, high]``; never splits.

    Cell ids are row-major (the last dimension varies fastest). Inputs outside the box fall in
    the nearest edge cell.
    """

    kind = "grid"
    records_errors = False

    def __init__(
        self, low: list[float], high: list[float], resolution: int | Sequence[int]
    ) -> None:
        self.dims = len(low)
        items = (
            [resolution] * self.dims
            if isinstance(resolution, int | np.integer)
            else list(resolution)
            if isinstance(resolution, Sequence | np.ndarray) and not isinstance(resolution, str)
            else None
        )
        whole = items is not None and all(
            isinstance(r, int | np.integer) and not isinstance(r, bool | np.bool_) for r in items
        )
        cells = [int(r) for r in items] if items is not None and whole else []
        if len(cells) != self.dims or any(c < 1 for c in cells):
            raise ValueError(
                f"resolution must be a positive int or {self.dims} positive ints, "
                f"got {resolution!r}"
            )
        if math.prod(cells) > MAX_GRID_CELLS:  # before any table is sized (a lidar's 10^38)
            raise ValueError(
                f"resolution {resolution!r} over {self.dims} dimensions gives "
                f"{math.prod(cells):,} cells, at most {MAX_GRID_CELLS:,}"
            )
        self.resolution = cells
        self.root_low = [float(v) for v in low]
        self.root_high = [float(v) for v in high]
        self._scale = [
            c / (h - lo) for c, lo, h in zip(cells, self.root_low, self.root_high, strict=True)
        ]
        strides = [1] * self.dims
        for i in range(self.dims - 2, -1, -1):
            strides[i] = strides[i + 1] * cells[i + 1]
        self._strides = strides
        self._terms = list(
            zip(range(self.dims), self.root_low, self._scale, cells, strides, strict=True)
        )
        self.n_leaves = int(np.prod(cells))
        self.n_ids = self.n_leaves
        self.depth = 0

    def leaf_of(self, x: Sequence[float]) -> int:
        leaf = 0
        for i, lo, scale, n, stride in self._terms:
            c = int((x[i] - lo) * scale)
            if c < 0:
                c = 0
            elif c >= n:
                c = n - 1
            leaf += c * stride
        return leaf

    def cell_index(self, leaf: int) -> list[int]:
        """Per-dimension cell indices of a leaf id."""
        return [(leaf // s) % n for s, n in zip(self._strides, self.resolution, strict=True)]

    def leaves(self) -> list[int]:
        return list(range(self.n_leaves))

    def is_leaf(self, node: int) -> bool:
        return 0 <= node < self.n_leaves

    def leaf_bounds(self, leaf: int) -> tuple[list[float], list[float]]:
        idx = self.cell_index(leaf)
        low = [lo + c / s for lo, c, s in zip(self.root_low, idx, self._scale, strict=True)]
        high = [lo + (c + 1) / s for lo, c, s in zip(self.root_low, idx, self._scale, strict=True)]
        return low, high

    def leaf_depth(self, leaf: int) -> int:
        return 0

    def record(
        self, leaf: int, xs: list[list[float]], errors: list[float]
    ) -> tuple[int, int] | None:
        return None

    def render_lines(self, describe_leaf: Callable[[int], str]) -> list[str]:
        cells = " x ".join(map(str, self.resolution))
        header = f"uniform grid {cells} over {self.root_low}..{self.root_high}"
        return [header] + [f"  {describe_leaf(leaf)}" for leaf in self.leaves()]

    def to_arrays(self) -> tuple[dict[str, NDArray[Any]], dict[str, Any]]:
        return {}, {
            "root_low": self.root_low,
            "root_high": self.root_high,
            "resolution": self.resolution,
        }
