"""Planar geometry of a layout: signed clearance from points to walls and obstacles.

Used to validate layouts and to compute the physical limit; the simulation itself asks pybullet.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from bullet_maze.layout import MazeLayout


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
        dist = np.minimum(dist, np.hypot(x - cx, y - cy) - obstacle.radius)
    for wall in layout.walls:
        cx, cy = wall.center
        hx, hy = wall.size[0] / 2.0, wall.size[1] / 2.0
        qx, qy = np.abs(x - cx) - hx, np.abs(y - cy) - hy
        outside = np.hypot(np.maximum(qx, 0.0), np.maximum(qy, 0.0))
        inside = np.minimum(np.maximum(qx, qy), 0.0)
        dist = np.minimum(dist, outside + inside)
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
    length = float(np.max(np.hypot(*(ends - starts).T), initial=0.0))
    samples = max(2, int(np.ceil(length / spacing)) + 1)
    t = np.linspace(0.0, 1.0, samples)[None, :, None]
    pts = starts[:, None, :] + t * (ends - starts)[:, None, :]
    return clearance(layout, pts).min(axis=1)
