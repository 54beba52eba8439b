"""Novel ends (beyond the paper): which inputs the agent has seen, on a fixed grid.

The adaptive tree refines where the agent has been (eqs. 11-13 split on the pairs its visits
leave), so a leaf that reaches from a visited room into an unvisited one holds the values
learnt in the visited part, and the optimism of untried actions (eq. 10 starts Q-bar at
``q_init``) never points into the new room. With ``TreeConfig.novelty_cells`` = c the model
of ``planning="sweep"`` (:mod:`agent.leaf_model`) also counts the inputs of every epoch on a
grid of c equal cells along each input dimension with finite bounds, and an epoch that ends in
a cell no input has been in is stored as a *novel end*: its eq. (8) target is

    y_e = R_e + D_e q_init        instead of   R_e + D_e V-bar(l'_e),

the value of an unknown state in R-max (Brafman and Tennenholtz 2002). The sweeps carry that
optimism back to the leaves that lead there. After ``TreeConfig.novelty_terminals`` terminal
epochs the agent has found what ends an episode, and every novel end is pointed at its end leaf
(:meth:`agent.leaf_model.LeafModel.end_novelty`); with ``TreeConfig.novelty_episodes`` also
once that many episodes have ended, for a task whose episodes never terminate.

Dimensions without finite bounds (a ``Box`` grown from the data) are left out of the cells:
their range is not known when the count begins. ``TreeConfig.novelty_max_cells`` bounds the
cells in all (:func:`cells_per_dimension`): on many inputs a fixed count per dimension makes a
grid so large that nearly every end is novel.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

Cell = tuple[int, ...]


def cells_per_dimension(cells: int, dims: int, max_cells: int | None) -> int:
    """The cells along each of ``dims`` bounded dimensions: ``cells``, or fewer where
    ``max_cells`` bounds the grid (the largest c with c^dims <= max_cells), and at least 2."""
    if max_cells is None or dims == 0:
        return cells
    c = min(cells, max(2, math.floor(max_cells ** (1.0 / dims))))
    while c > 2 and c**dims > max_cells:  # the float root may overshoot by one
        c -= 1
    while c < cells and (c + 1) ** dims <= max_cells:  # ... or fall short by one
        c += 1
    return c


class NoveltyGrid:
    """The cell of an input on a grid of ``cells`` equal parts of each bounded dimension (fewer
    where ``max_cells`` bounds the grid's cells in all: :func:`cells_per_dimension`)."""

    def __init__(
        self,
        low: Sequence[float],
        high: Sequence[float],
        cells: int,
        max_cells: int | None = None,
    ) -> None:
        if len(low) != len(high):
            raise ValueError(f"low has {len(low)} dimensions and high {len(high)}")
        if isinstance(cells, bool) or not isinstance(cells, int) or cells < 2:
            raise ValueError(f"novelty grid cells must be an int >= 2, got {cells!r}")
        bounded = [
            (d, float(lo), float(hi))
            for d, (lo, hi) in enumerate(zip(low, high, strict=True))
            if math.isfinite(lo) and math.isfinite(hi) and hi > lo
        ]
        cells = cells_per_dimension(cells, len(bounded), max_cells)
        self.cells = cells
        self.dims = [(d, lo, cells / (hi - lo)) for d, lo, hi in bounded]
        """(dimension, low, cells per unit) of each dimension the grid covers."""

    def cell(self, x: Sequence[float]) -> Cell:
        """The cell holding ``x`` (inputs outside the bounds, and infinities, fall in the edge
        cells; NaN in the first)."""
        last = self.cells - 1
        out = []
        for d, low, per_unit in self.dims:
            v = x[d]
            i = math.floor((v - low) * per_unit) if math.isfinite(v) else (last if v > 0 else 0)
            out.append(0 if i < 0 else last if i > last else i)
        return tuple(out)
