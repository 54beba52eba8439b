"""Planar geometry of a layout: signed clearance from points and segments to walls and obstacles.

Used to validate layouts and to compute the physical limit; the simulation itself asks pybullet.
``clearance`` is the definition; ``clearance_mask`` and ``segments_clear`` answer the threshold
questions the planner asks ("is the clearance at least ``limit``?") with the same arithmetic,
point for point, but only where a solid can be that close, so that their cost grows with the
number of points near solids rather than with points times solids.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from bullet_maze.layout_types import MazeLayout

_MARGIN = 1e-6
"""Maze units added to every window around a solid, far above rounding: a point outside the
window is farther than the limit from the solid whatever the rounding of its coordinates."""

_BATCH = 512
"""Segments tested together by ``segments_clear`` (grouped by position, so that each group's
bounding box meets few solids)."""


def clearance(layout: MazeLayout, points: np.ndarray) -> np.ndarray:
    """Distance from each point (shape ``(..., 2)``, maze units) to the nearest solid surface.

    Solids are the arena boundary, the walls (axis-aligned boxes) and the obstacles (cylinders).
    Negative inside a solid. A disc of radius r centred at a point is free iff clearance >= r.
    """
    pts = np.asarray(points, dtype=float)
    x, y = pts[..., 0], pts[..., 1]
    width, height = layout.arena
    dist = np.minimum(np.minimum(x, width - x), np.minimum(y, height - y))
    for obstacle in layout.obstacles:
        cx, cy = obstacle.center
        dist = np.minimum(dist, _disc_distance(x, y, cx, cy, obstacle.radius))
    for wall in layout.walls:
        cx, cy = wall.center
        dist = np.minimum(dist, _box_distance(x, y, cx, cy, wall.size[0] / 2.0, wall.size[1] / 2.0))
    return dist


def segment_clearance(
    layout: MazeLayout, starts: np.ndarray, ends: np.ndarray, spacing: float = 0.25
) -> np.ndarray:
    """Least clearance along each straight segment ``starts[i] -> ends[i]`` (shape ``(n, 2)``).

    Sampled every ``spacing`` units; clearance is 1-Lipschitz, so the true minimum is at most
    ``spacing / 2`` below the returned value.
    """
    starts = np.asarray(starts, dtype=float).reshape(-1, 2)
    ends = np.asarray(ends, dtype=float).reshape(-1, 2)
    t = _sample_times(starts, ends, spacing)[None, :, None]
    pts = starts[:, None, :] + t * (ends - starts)[:, None, :]
    return clearance(layout, pts).min(axis=1)


def clearance_mask(layout: MazeLayout, xs: np.ndarray, ys: np.ndarray, limit: float) -> np.ndarray:
    """``clearance(layout, grid) >= limit`` on the grid of points ``(xs[i], ys[j])``, shape
    ``(len(xs), len(ys))``; ``xs`` and ``ys`` increasing. Each solid is only evaluated on the
    points of its bounding box widened by ``limit``: farther points clear it anyway."""
    xs = np.asarray(xs, dtype=float)
    ys = np.asarray(ys, dtype=float)
    width, height = layout.arena
    free = (np.minimum(xs, width - xs) >= limit)[:, None] & (np.minimum(ys, height - ys) >= limit)[
        None, :
    ]
    reach = limit + _MARGIN
    solids = solid_arrays(layout)
    for k in range(solids.count):
        x0, y0, x1, y1 = solids.bounds[k]
        i0, i1 = (int(i) for i in np.searchsorted(xs, (x0 - reach, x1 + reach)))
        j0, j1 = (int(j) for j in np.searchsorted(ys, (y0 - reach, y1 + reach)))
        if i0 >= i1 or j0 >= j1:
            continue
        x, y = xs[i0:i1, None], ys[None, j0:j1]
        free[i0:i1, j0:j1] &= solids.distance(k, x, y) >= limit
    return free


def segments_clear(
    layout: MazeLayout, starts: np.ndarray, ends: np.ndarray, spacing: float, limit: float
) -> np.ndarray:
    """``segment_clearance(layout, starts, ends, spacing) >= limit``, sample for sample.

    The samples are the same (``spacing`` over the longest segment of the call); a solid is only
    evaluated at the samples that fall in its bounding box widened by ``limit``, and the arena's
    boundary at the two end samples (its distance is monotone along a segment).
    """
    starts = np.asarray(starts, dtype=float).reshape(-1, 2)
    ends = np.asarray(ends, dtype=float).reshape(-1, 2)
    n = len(starts)
    if n == 0:
        return np.zeros(0, dtype=bool)
    t = _sample_times(starts, ends, spacing)
    delta = ends - starts
    width, height = layout.arena
    ok = np.ones(n, dtype=bool)
    for tk in (t[0], t[-1]):
        x, y = starts[:, 0] + tk * delta[:, 0], starts[:, 1] + tk * delta[:, 1]
        ok &= np.minimum(np.minimum(x, width - x), np.minimum(y, height - y)) >= limit
    solids = solid_arrays(layout)
    if solids.count == 0:
        return ok
    order = _spatial_order(layout, (starts + ends) / 2.0) if n > _BATCH else np.arange(n)
    for first in range(0, n, _BATCH):
        batch = order[first : first + _BATCH]
        blocked = _blocked(solids, starts[batch], delta[batch], t, limit)
        ok[batch[blocked]] = False
    return ok


@dataclass(frozen=True)
class SolidArrays:
    """A layout's solids as arrays: obstacles first (``kind`` 0: centre, radius), then walls
    (``kind`` 1: centre, half sizes), each with its bounding box ``(x0, y0, x1, y1)``."""

    kind: np.ndarray
    center: np.ndarray
    half: np.ndarray
    bounds: np.ndarray

    @property
    def count(self) -> int:
        return len(self.kind)

    def distance(self, k: int, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """Signed distance from the points (x, y) to solid ``k``, as ``clearance`` computes it."""
        cx, cy = self.center[k]
        if self.kind[k] == 0:
            return _disc_distance(x, y, cx, cy, self.half[k, 0])
        return _box_distance(x, y, cx, cy, self.half[k, 0], self.half[k, 1])


@lru_cache(maxsize=32)
def solid_arrays(layout: MazeLayout) -> SolidArrays:
    """The solids of ``layout`` as ``SolidArrays`` (cached per layout)."""
    kinds = [0] * len(layout.obstacles) + [1] * len(layout.walls)
    centers = [o.center for o in layout.obstacles] + [w.center for w in layout.walls]
    halves = [(o.radius, o.radius) for o in layout.obstacles] + [
        (w.size[0] / 2.0, w.size[1] / 2.0) for w in layout.walls
    ]
    center = np.array(centers, dtype=float).reshape(-1, 2)
    half = np.array(halves, dtype=float).reshape(-1, 2)
    return SolidArrays(
        kind=np.array(kinds, dtype=np.int8),
        center=center,
        half=half,
        bounds=np.concatenate([center - half, center + half], axis=1),
    )


def _disc_distance(x: np.ndarray, y: np.ndarray, cx: float, cy: float, radius: float) -> np.ndarray:
    return np.hypot(x - cx, y - cy) - radius


def _box_distance(
    x: np.ndarray, y: np.ndarray, cx: float, cy: float, hx: float, hy: float
) -> np.ndarray:
    qx, qy = np.abs(x - cx) - hx, np.abs(y - cy) - hy
    outside = np.hypot(np.maximum(qx, 0.0), np.maximum(qy, 0.0))
    inside = np.minimum(np.maximum(qx, qy), 0.0)
    return outside + inside


def _sample_times(starts: np.ndarray, ends: np.ndarray, spacing: float) -> np.ndarray:
    length = float(np.max(np.hypot(*(ends - starts).T), initial=0.0))
    samples = max(2, math.ceil(length / spacing) + 1)
    return np.linspace(0.0, 1.0, samples)


def _spatial_order(layout: MazeLayout, points: np.ndarray) -> np.ndarray:
    """Indices of ``points`` sorted by a 32 x 32 tiling of the arena (row by row)."""
    side = max(layout.arena) / 32.0
    tiles = np.clip((points // side).astype(np.int64), 0, 32)
    return np.argsort(tiles[:, 1] * 64 + tiles[:, 0], kind="stable")


def _point_segment(
    px: np.ndarray, py: np.ndarray, starts: np.ndarray, delta: np.ndarray
) -> np.ndarray:
    """Distance from points (px, py) to the segments ``starts + t * delta``, t in [0, 1]."""
    dx, dy = delta[:, 0], delta[:, 1]
    length2 = dx * dx + dy * dy
    with np.errstate(divide="ignore", invalid="ignore"):
        t = ((px - starts[:, 0]) * dx + (py - starts[:, 1]) * dy) / length2
    t = np.clip(np.where(length2 > 0.0, t, 0.0), 0.0, 1.0)
    return np.hypot(px - (starts[:, 0] + t * dx), py - (starts[:, 1] + t * dy))


def _segment_distance(
    solids: SolidArrays, k: np.ndarray, starts: np.ndarray, delta: np.ndarray
) -> np.ndarray:
    """Exact distance from each segment ``starts[i] + t * delta[i]`` to solid ``k[i]``: to a
    disc, its centre's distance minus the radius; to a box, 0 if the segment meets it, else the
    least of its ends' distances to the box and the box's corners' to the segment (two disjoint
    convex polygons are closest at a vertex of one of them)."""
    cx, cy = solids.center[k, 0], solids.center[k, 1]
    hx, hy = solids.half[k, 0], solids.half[k, 1]
    result = _point_segment(cx, cy, starts, delta) - hx
    box = solids.kind[k] == 1
    if not box.any():
        return result
    cx, cy, hx, hy = cx[box], cy[box], hx[box], hy[box]
    a, d = starts[box], delta[box]
    b = a + d
    ends = np.minimum(
        _box_distance(a[:, 0], a[:, 1], cx, cy, hx, hy),
        _box_distance(b[:, 0], b[:, 1], cx, cy, hx, hy),
    )
    corners = np.min(
        [
            _point_segment(cx + sx * hx, cy + sy * hy, a, d)
            for sx, sy in ((-1, -1), (-1, 1), (1, -1), (1, 1))
        ],
        axis=0,
    )
    # The segment meets the box iff clipping it to the box leaves an interval.
    t0, t1 = np.zeros(len(a)), np.ones(len(a))
    for axis, (c, h) in enumerate(((cx, hx), (cy, hy))):
        p, v = a[:, axis], d[:, axis]
        with np.errstate(divide="ignore", invalid="ignore"):
            ta, tb = (c - h - p) / v, (c + h - p) / v
        inside = np.abs(p - c) <= h
        still = v == 0.0
        t0 = np.maximum(t0, np.where(still, np.where(inside, 0.0, np.inf), np.minimum(ta, tb)))
        t1 = np.minimum(t1, np.where(still, np.where(inside, 1.0, -np.inf), np.maximum(ta, tb)))
    result[box] = np.where(t0 <= t1, -np.inf, np.minimum(ends, corners))
    return result


def _blocked(
    solids: SolidArrays, starts: np.ndarray, delta: np.ndarray, t: np.ndarray, limit: float
) -> np.ndarray:
    """Which segments ``starts + t * delta`` have a sample closer than ``limit`` to a solid."""
    reach = limit + _MARGIN
    ends = starts + delta
    lo = np.minimum(starts, ends).min(axis=0) - reach
    hi = np.maximum(starts, ends).max(axis=0) + reach
    near = np.flatnonzero(
        (solids.bounds[:, 0] <= hi[0])
        & (solids.bounds[:, 2] >= lo[0])
        & (solids.bounds[:, 1] <= hi[1])
        & (solids.bounds[:, 3] >= lo[1])
    )
    blocked = np.zeros(len(starts), dtype=bool)
    if near.size == 0:
        return blocked
    # Every (segment, solid) pair: the interval of t where the segment is inside the solid's
    # widened bounding box (Liang-Barsky clipping); samples outside it clear the solid.
    box = solids.bounds[near]
    t0 = np.zeros((len(starts), near.size))
    t1 = np.ones((len(starts), near.size))
    for axis in (0, 1):
        p, d = starts[:, axis, None], delta[:, axis, None]
        low, high = box[None, :, axis] - reach, box[None, :, 2 + axis] + reach
        with np.errstate(divide="ignore", invalid="ignore"):
            ta, tb = (low - p) / d, (high - p) / d
        still = d == 0.0
        inside = (p >= low) & (p <= high)
        enter = np.where(still, np.where(inside, 0.0, np.inf), np.minimum(ta, tb))
        leave = np.where(still, np.where(inside, 1.0, -np.inf), np.maximum(ta, tb))
        t0, t1 = np.maximum(t0, enter), np.minimum(t1, leave)
    seg, col = np.nonzero(t0 <= t1)
    # A pair whose exact distance clears the limit (with room for rounding) needs no samples.
    close = _segment_distance(solids, near[col], starts[seg], delta[seg]) < reach
    seg, col = seg[close], col[close]
    if seg.size == 0:
        return blocked
    last = len(t) - 1
    first = np.clip(np.floor(t0[seg, col] * last).astype(np.int64) - 1, 0, last)
    stop = np.clip(np.ceil(t1[seg, col] * last).astype(np.int64) + 2, 0, last + 1)
    counts = stop - first
    pair = np.repeat(np.arange(seg.size), counts)
    sample = first[pair] + (np.arange(pair.size) - np.repeat(np.cumsum(counts) - counts, counts))
    segment = seg[pair]
    tk = t[sample]
    x = starts[segment, 0] + tk * delta[segment, 0]
    y = starts[segment, 1] + tk * delta[segment, 1]
    k = near[col[pair]]
    cx, cy = solids.center[k, 0], solids.center[k, 1]
    hx, hy = solids.half[k, 0], solids.half[k, 1]
    disc = solids.kind[k] == 0
    dist = np.empty(pair.size)
    dist[disc] = _disc_distance(x[disc], y[disc], cx[disc], cy[disc], hx[disc])
    box_ = ~disc
    dist[box_] = _box_distance(x[box_], y[box_], cx[box_], cy[box_], hx[box_], hy[box_])
    blocked[segment[dist < limit]] = True
    return blocked
