"""The physical limit of a layout: the shortest collision-free path and the least number of steps.

For a robot disc of a given radius, ``shortest_path`` gives

* ``length``: the Euclidean length of the shortest collision-free path from the start to the goal
  circle (Dijkstra on an 8-connected grid with ``scipy.sparse.csgraph``, then pulled taut by
  line-of-sight shortcuts, so it is exact to within about one grid cell);
* ``l1_length``: the same with only axis-parallel moves (the L1 geodesic on a 4-connected grid);
* ``steps``: the least number of 4-direction steps of ``step_size`` that can cover the L1
  geodesic, ``ceil(l1_length / step_size)``: no sequence of steps of that length reaches the goal
  in fewer;
* ``lattice_steps``: the least number of noise-free steps from the exact start (a breadth-first
  search over the lattice of points start + step_size * (i, j)), with the actions that do it.
  It can exceed ``steps`` when the lattice does not line up with a gap.

Section V.A's steps carry noise, so a learner can only approach these on average.

The grid's cell is 0.5 units (finer if the goal or the robot is small) while the grid has at
most ``params.MAX_PLANNER_NODES`` nodes, and ``coarsest_cell(arena)`` in larger arenas, so that
time and memory stay bounded (about 0.5 s and 120 MB); lengths are exact to within about a cell.
The solids are only evaluated near themselves (``geometry.clearance_mask``,
``geometry.segments_clear``), so hundreds of solids cost little more than a few.
"""

from __future__ import annotations

import dataclasses
import functools
import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy import ndimage
from scipy.sparse import coo_matrix, csr_matrix
from scipy.sparse.csgraph import breadth_first_order, dijkstra

from bullet_maze.actions import DIRECTIONS
from bullet_maze.geometry import clearance_mask, segments_clear
from bullet_maze.layout_types import MazeLayout
from bullet_maze.params import MAX_PLANNER_NODES

CLEARANCE_TOLERANCE = 0.01
"""Extra clearance (maze units) that planned paths keep from every surface, above the
simulation's contact tolerance (``world.CONTACT_TOLERANCE``), so that the simulation accepts
them."""

GRID_RESOLUTION = 0.5
"""Cell size in maze units of the planning grid in arenas up to about 316 x 316."""

_NEIGHBOURS = ((-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1))
"""The 8 neighbour offsets (di, dj) of a grid node, in increasing order of the neighbour's index
(``i * ny + j``), as a canonical sparse matrix holds them."""


@dataclass(frozen=True)
class PhysicalLimit:
    """The best any policy can do in a layout, for one robot radius and step size."""

    length: float
    """Euclidean length of the shortest collision-free path from start to goal circle."""
    l1_length: float
    """Length of the shortest collision-free path made of axis-parallel moves."""
    steps: int
    """Least number of 4-direction steps of ``step_size`` covering the L1 geodesic."""
    lattice_steps: int | None
    """Least number of noise-free steps from the exact start; None if the lattice has no path."""
    actions: tuple[int, ...]
    """One sequence of ``lattice_steps`` actions that reaches the goal without noise."""
    waypoints: np.ndarray
    """Corners of the shortest Euclidean path, shape ``(n, 2)``."""
    robot_radius: float
    step_size: float


def goal_reachable(
    layout: MazeLayout,
    robot_radius: float,
    start: tuple[float, float] | None = None,
    goal: tuple[float, float] | None = None,
) -> bool:
    """Whether a disc of ``robot_radius`` can move from ``start`` into the goal circle around
    ``goal`` (by default the layout's own; the circle has the layout's goal radius).

    Decided on the physical limit's grid (``grid_cell``): a gap that leaves the robot's centre
    a band narrower than one cell may be missed (reported unreachable). The grid's connected
    free regions depend only on the layout's solids and the radius and are kept
    (``_free_regions``), so another start or goal in the same layout costs a lookup.
    """
    return goal_test(layout, robot_radius)(
        layout.start if start is None else start, layout.goal if goal is None else goal
    )


def goal_test(
    layout: MazeLayout, robot_radius: float
) -> Callable[[tuple[float, float], tuple[float, float]], bool]:
    """``goal_reachable`` for this layout and radius as a function of the start and the goal, for
    a caller that asks many times (an env's resets): the lookup of the kept free regions hashes
    every solid of the layout (0.5 ms at 1,000 solids), which the function does once."""
    regions = _free_regions(_solids(layout), float(robot_radius))
    return functools.partial(regions.connects, goal_radius=layout.goal_radius)


def _solids(layout: MazeLayout) -> MazeLayout:
    """The layout with everything but its solids, arena and goal radius set to fixed values, as
    the cache key of what depends only on those."""
    return dataclasses.replace(
        layout,
        name="",
        description="",
        start=(0.0, 0.0),
        goal=(0.0, 0.0),
        start_heading=0.0,
        start_size=1.0,
        robot_radius=1.0,
    )


class _Regions:
    """The connected components of a grid's free cells (4-connected)."""

    def __init__(self, grid: _Grid) -> None:
        self.grid = grid
        labels, _ = ndimage.label(grid.free)
        self.labels = labels.ravel()
        # The regions of the last goal circle asked about: resets to new starts keep the goal.
        self._goal: tuple[tuple[float, float], float, frozenset[int]] | None = None

    def connects(
        self, start: tuple[float, float], goal: tuple[float, float], goal_radius: float
    ) -> bool:
        """Whether the start's region holds a free cell of the goal circle."""
        node = self.grid.start_node(start)
        if node is None:
            return False
        kept = self._goal  # read once: the regions are shared by every env of the layout
        if kept is None or kept[:2] != (goal, goal_radius):
            regions = self.labels[self.grid.goal_nodes(goal, goal_radius)]
            kept = self._goal = (goal, goal_radius, frozenset(regions.tolist()))
        return int(self.labels[node]) in kept[2]


@lru_cache(maxsize=8)
def _free_regions(solids: MazeLayout, radius: float) -> _Regions:
    return _Regions(_Grid(solids, radius, grid_cell(solids, radius)))


def coarsest_cell(arena: tuple[float, float]) -> float:
    """The grid cell (maze units) at which the arena's grid has ``MAX_PLANNER_NODES`` nodes;
    robot and goal radii must be at least this (``bullet_maze.validation``)."""
    return math.sqrt(arena[0] * arena[1] / MAX_PLANNER_NODES)


def grid_cell(layout: MazeLayout, robot_radius: float) -> float:
    """The planning grid's cell: 0.5 units, or less for a goal radius under 1 or a robot radius
    under 1, but never finer than ``coarsest_cell``."""
    fine = min(GRID_RESOLUTION, layout.goal_radius / 2.0, robot_radius / 2.0)
    return max(fine, coarsest_cell(layout.arena))


def shortest_path(
    layout: MazeLayout, robot_radius: float | None = None, step_size: float = 5.0
) -> PhysicalLimit:
    """Section V.A's physical limit for a layout (see the module docstring); cached."""
    radius = layout.robot_radius if robot_radius is None else float(robot_radius)
    return _shortest_path(layout, radius, float(step_size))


@lru_cache(maxsize=64)
def _shortest_path(layout: MazeLayout, radius: float, step_size: float) -> PhysicalLimit:
    if radius <= 0 or step_size <= 0:
        raise ValueError(f"robot_radius and step_size must be positive, got {radius}, {step_size}")
    grid = _Grid(layout, radius, grid_cell(layout, radius))
    start = grid.start_node(layout.start)
    goals = grid.goal_nodes(layout.goal, layout.goal_radius)
    if start is None or goals.size == 0:
        raise ValueError(f"{layout.source}: no free start or goal for radius {radius}")
    graph = grid.edges(diagonal=True)
    dist, pred = dijkstra(graph, indices=start, return_predecessors=True)
    del graph
    best = goals[np.argmin(dist[goals])]
    if not np.isfinite(dist[best]):
        raise ValueError(f"{layout.source}: goal unreachable for radius {radius}")
    nodes = [int(best)]
    while nodes[-1] != start:
        nodes.append(int(pred[nodes[-1]]))
    points = grid.points(np.array(nodes[::-1]))
    points[0] = layout.start
    waypoints = _pull_taut(layout, points, radius + CLEARANCE_TOLERANCE)
    length = _length_to_goal(waypoints, np.array(layout.goal), layout.goal_radius)

    l1 = dijkstra(grid.edges(diagonal=False), indices=start)
    l1_length = float(np.min(l1[goals]))
    l1_length += float(np.abs(grid.points(np.array([start]))[0] - layout.start).sum())

    lattice, actions = _lattice_steps(layout, radius, step_size)
    steps = math.ceil(l1_length / step_size - 1e-9)
    return PhysicalLimit(
        length=length,
        l1_length=l1_length,
        steps=steps,
        lattice_steps=lattice,
        actions=actions,
        waypoints=waypoints,
        robot_radius=radius,
        step_size=step_size,
    )


class _Grid:
    """Free cells of a square grid over the arena for a disc of a given radius."""

    def __init__(self, layout: MazeLayout, radius: float, resolution: float) -> None:
        if not resolution * math.sqrt(2.0) < 2.0 * radius:
            # Two free nodes a diagonal apart could then straddle a thin wall.
            raise ValueError(
                f"{layout.source}: a robot of radius {radius:g} is too small for the planning "
                f"grid of cell {resolution:.3g} in a {layout.arena[0]:g} x {layout.arena[1]:g} "
                "arena (bullet_maze.params.MAX_PLANNER_NODES)"
            )
        self.layout = layout
        self.h = resolution
        self.nx = math.floor(layout.arena[0] / resolution) + 1
        self.ny = math.floor(layout.arena[1] / resolution) + 1
        self.xs = np.arange(self.nx) * resolution
        self.ys = np.arange(self.ny) * resolution
        self.limit = radius + CLEARANCE_TOLERANCE
        self.free = clearance_mask(layout, self.xs, self.ys, self.limit)

    def points(self, nodes: np.ndarray) -> np.ndarray:
        i, j = np.divmod(nodes, self.ny)
        return np.stack([i * self.h, j * self.h], axis=-1).astype(float)

    def edges(self, diagonal: bool) -> csr_matrix:
        """The symmetric graph of moves between free neighbours (4- or 8-connected), weighted by
        length, built row by row in canonical order (sorted column indices)."""
        # Neighbours are closer than the robot's diameter (validation bounds the cell by the
        # radius), so two free nodes bound a free edge.
        offsets = [o for o in _NEIGHBOURS if diagonal or 0 in o]
        nx, ny, n = self.nx, self.ny, self.nx * self.ny
        padded = np.zeros((nx + 2, ny + 2), dtype=bool)
        padded[1:-1, 1:-1] = self.free
        valid = np.stack(
            [self.free & padded[1 + di : 1 + di + nx, 1 + dj : 1 + dj + ny] for di, dj in offsets],
            axis=-1,
        ).reshape(n, len(offsets))
        step = np.array([di * ny + dj for di, dj in offsets], dtype=np.int32)
        weight = np.array([self.h * math.hypot(di, dj) for di, dj in offsets])
        rows = np.nonzero(valid)
        indices = (rows[0].astype(np.int32) + step[rows[1]]).astype(np.int32)
        indptr = np.zeros(n + 1, dtype=np.int32)
        np.cumsum(valid.sum(axis=1), out=indptr[1:])
        return csr_matrix((weight[rows[1]], indices, indptr), shape=(n, n))

    def start_node(self, start: tuple[float, float]) -> int | None:
        """The free node nearest ``start`` among the four around it, if any."""
        sx, sy = start
        best: tuple[float, int] | None = None
        for i in (math.floor(sx / self.h), math.ceil(sx / self.h)):
            for j in (math.floor(sy / self.h), math.ceil(sy / self.h)):
                if 0 <= i < self.nx and 0 <= j < self.ny and self.free[i, j]:
                    d = math.hypot(i * self.h - sx, j * self.h - sy)
                    if best is None or d < best[0]:
                        best = (d, i * self.ny + j)
        return None if best is None else best[1]

    def goal_nodes(self, goal: tuple[float, float], radius: float) -> np.ndarray:
        """The free nodes within ``radius`` of ``goal``, in increasing order."""
        gx, gy = goal
        # Only the circle's bounding box (one node wider on each side) is looked at.
        i0 = max(0, math.floor((gx - radius) / self.h) - 1)
        i1 = min(self.nx, math.ceil((gx + radius) / self.h) + 2)
        j0 = max(0, math.floor((gy - radius) / self.h) - 1)
        j1 = min(self.ny, math.ceil((gy + radius) / self.h) + 2)
        if i0 >= i1 or j0 >= j1:
            return np.zeros(0, dtype=np.int64)
        inside = np.hypot(self.xs[i0:i1, None] - gx, self.ys[None, j0:j1] - gy) <= radius
        ii, jj = np.nonzero(inside & self.free[i0:i1, j0:j1])
        return (ii + i0) * self.ny + (jj + j0)


def _pull_taut(layout: MazeLayout, points: np.ndarray, limit: float) -> np.ndarray:
    """Replace runs of grid points by straight segments wherever the robot fits along them."""
    spacing, chunk = 0.1, 64
    kept = [0]
    while kept[-1] < len(points) - 1:
        anchor = kept[-1]
        step = len(points) - 1 - anchor
        for first in range(anchor + 1, len(points), chunk):
            ends = points[first : first + chunk]
            starts = np.broadcast_to(points[anchor], ends.shape)
            # Sampled every 0.1 unit: a segment may dip at most 0.05 below the limit between.
            visible = segments_clear(layout, starts, ends, spacing, limit)
            blocked = np.flatnonzero(~visible)
            if blocked.size:
                step = max(1, first + int(blocked[0]) - 1 - anchor)
                break
        kept.append(anchor + step)
    return points[kept]


def _length_to_goal(points: np.ndarray, goal: np.ndarray, radius: float) -> float:
    """Length of a polyline up to where it first enters the goal circle."""
    total = 0.0
    for a, b in itertools.pairwise(points):
        seg = b - a
        seg_len = float(np.hypot(*seg))
        if np.hypot(*(b - goal)) > radius:
            total += seg_len
            continue
        # Solve |a + t seg - goal| = radius for the entering t in [0, 1].
        f = a - goal
        qa, qb, qc = seg @ seg, 2.0 * (f @ seg), f @ f - radius**2
        disc = max(qb * qb - 4 * qa * qc, 0.0)
        t = (-qb - math.sqrt(disc)) / (2 * qa) if qa > 0 else 0.0
        return total + max(t, 0.0) * seg_len
    return total


def _lattice_steps(
    layout: MazeLayout, radius: float, step_size: float
) -> tuple[int | None, tuple[int, ...]]:
    """Breadth-first search over the lattice of noise-free step positions from the start."""
    sx, sy = layout.start
    w, h = layout.arena
    i_lo, i_hi = -math.floor(sx / step_size), math.floor((w - sx) / step_size)
    j_lo, j_hi = -math.floor(sy / step_size), math.floor((h - sy) / step_size)
    nx, ny = i_hi - i_lo + 1, j_hi - j_lo + 1
    if nx * ny > MAX_PLANNER_NODES:
        return None, ()
    xs = sx + np.arange(i_lo, i_hi + 1) * step_size
    ys = sy + np.arange(j_lo, j_hi + 1) * step_size
    pts = np.stack(np.meshgrid(xs, ys, indexing="ij"), axis=-1)
    index = np.arange(nx * ny).reshape(nx, ny)
    limit = radius + CLEARANCE_TOLERANCE
    spacing = 0.25
    free = clearance_mask(layout, xs, ys, limit)
    rows, cols = [], []
    for di, dj in ((1, 0), (0, 1)):
        a = (slice(0, nx - di), slice(0, ny - dj))
        b = (slice(di, nx), slice(dj, ny))
        ok = free[a] & free[b]
        seg_ok = segments_clear(layout, pts[a][ok], pts[b][ok], spacing, limit + spacing / 2)
        rows.append(index[a][ok][seg_ok])
        cols.append(index[b][ok][seg_ok])
    r, c = np.concatenate(rows), np.concatenate(cols)
    n = nx * ny
    graph = coo_matrix((np.ones(2 * r.size), (np.r_[r, c], np.r_[c, r])), shape=(n, n)).tocsr()
    start = int(index[-i_lo, -j_lo])
    order, pred = breadth_first_order(graph, start, directed=False, return_predecessors=True)
    dist = np.full(n, np.inf)
    for node in order:  # breadth-first order: a node's predecessor is already measured
        dist[node] = 0.0 if node == start else dist[pred[node]] + 1.0
    in_goal = (
        np.hypot(pts[..., 0] - layout.goal[0], pts[..., 1] - layout.goal[1]) <= layout.goal_radius
    ) & free
    goals = np.flatnonzero(in_goal.ravel())
    if goals.size == 0 or not np.isfinite(dist[goals]).any():
        return None, ()
    best = int(goals[np.argmin(dist[goals])])
    nodes = [best]
    while nodes[-1] != start:
        nodes.append(int(pred[nodes[-1]]))
    nodes.reverse()
    actions = []
    for first, second in itertools.pairwise(nodes):
        (ai, aj), (bi, bj) = divmod(first, ny), divmod(second, ny)
        move = np.array([bi - ai, bj - aj], dtype=float)
        actions.append(int(np.flatnonzero((move == DIRECTIONS).all(axis=1))[0]))
    return len(actions), tuple(actions)
