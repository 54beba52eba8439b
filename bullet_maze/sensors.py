"""The lidar: a ring of range readings from the robot's centre, cast with ``rayTestBatch``.

Rays are horizontal, evenly spaced from the robot's heading (from +x for a robot without one),
counter-clockwise. Each starts on the robot's footprint circle, so it never sees the robot
itself, and ends ``lidar_range`` maze units from the centre; a reading is the distance from the
centre to the first solid hit, or ``lidar_range`` if none is. The walls and obstacles are vertical
prisms taller than any robot, so the rays' height (half the walls') does not change a reading.

The rays are cast in the lidar's own scene (``bullet_maze.ray_scene``): the same solids as
triangle meshes in a pybullet client that only answers ray tests, where a cylinder's ray test is
exact to ``MESH_TOLERANCE`` and ten times faster than against the simulation's cylinder shape.

pybullet answers at most 16,384 rays per call (``MAX_RAY_INTERSECTION_BATCH_SIZE``), answers a
list of exactly that many with one result too few, and a NumPy array of exactly that many with
none at all; the rays go in batches of ``RAY_BATCH`` and every answer's length is checked.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from bullet_maze.params import METRES_PER_UNIT, WALL_HEIGHT
from bullet_maze.ray_scene import RayScene
from bullet_maze.world import Piece

RAY_BATCH = 8192
"""Rays per ``rayTestBatch`` call, well below pybullet's limit of 16,384."""

MAX_LIDAR_RAYS = 65536
"""Most rays of one lidar (eight batches)."""

MAX_LIDAR_RANGE = 10000.0
"""Longest lidar range in maze units."""


@dataclass(frozen=True)
class LidarParams:
    """The lidar of ``observation="lidar"``; every field is a keyword argument of the env (a
    robot file's ``[sensors]`` may give its own defaults)."""

    lidar_rays: int = 36
    """Number of range readings, evenly spaced round the robot (every 10 degrees)."""
    lidar_range: float = 100.0
    """Maze units from the robot's centre beyond which nothing is seen (10 m at the default
    scale, a third of the paper's arena)."""

    def __post_init__(self) -> None:
        rays, reach = self.lidar_rays, self.lidar_range
        if isinstance(rays, bool) or not isinstance(rays, int):
            raise TypeError(f"lidar_rays must be an integer, got {rays!r}")
        if not 1 <= rays <= MAX_LIDAR_RAYS:
            raise ValueError(f"lidar_rays must be in [1, {MAX_LIDAR_RAYS}], got {rays}")
        if isinstance(reach, bool) or not isinstance(reach, int | float):
            raise TypeError(f"lidar_range must be a number of maze units, got {reach!r}")
        if not 0.0 < reach <= MAX_LIDAR_RANGE:
            raise ValueError(f"lidar_range must be in (0, {MAX_LIDAR_RANGE:g}], got {reach!r}")


class Lidar:
    """A ring of ``rays`` range readings for a robot of footprint ``radius`` among the solids
    ``pieces`` (``World.pieces``); ``close`` frees its scene's client."""

    def __init__(self, pieces: Sequence[Piece], params: LidarParams, radius: float) -> None:
        if params.lidar_range <= radius:
            raise ValueError(
                f"lidar_range = {params.lidar_range:g} must exceed the robot's footprint "
                f"radius ({radius:g}): the rays start on the footprint"
            )
        self.rays = params.lidar_rays
        self.range = float(params.lidar_range)
        self.radius = radius
        angles = np.linspace(0.0, 2.0 * math.pi, self.rays, endpoint=False)
        self._cos, self._sin = np.cos(angles), np.sin(angles)
        self._starts = np.empty((self.rays, 3))
        self._ends = np.empty((self.rays, 3))
        self._starts[:, 2] = self._ends[:, 2] = WALL_HEIGHT / 2.0 * METRES_PER_UNIT
        self.scene = RayScene(pieces)

    def read(
        self,
        x: float,
        y: float,
        heading: float,
        noise: float = 0.0,
        rng: np.random.Generator | None = None,
    ) -> np.ndarray:
        """The ranges (maze units, float64) seen from (x, y) facing ``heading``.

        With ``noise`` > 0 (a standard deviation in maze units, the env's ``lidar_noise``), each
        reading below the range (a ray that hit something) gets a Gaussian draw from ``rng``
        added, clipped to ``[0, range]``; a ray without a hit still reads the range (no
        return). One draw per ray, hit or not, so the number of draws does not depend on the
        maze.
        """
        s = METRES_PER_UNIT
        c, d = math.cos(heading), math.sin(heading)
        ux = self._cos * c - self._sin * d
        uy = self._sin * c + self._cos * d
        near, far = self.radius * s, self.range * s
        starts, ends = self._starts, self._ends
        starts[:, 0] = x * s + near * ux
        starts[:, 1] = y * s + near * uy
        ends[:, 0] = x * s + far * ux
        ends[:, 1] = y * s + far * uy
        readings = np.empty(self.rays)
        span = self.range - self.radius
        for first in range(0, self.rays, RAY_BATCH):
            last = min(first + RAY_BATCH, self.rays)
            hits = self.scene.cast(starts[first:last], ends[first:last])
            if len(hits) != last - first:
                raise RuntimeError(f"pybullet answered {len(hits)} of {last - first} lidar rays")
            fractions = np.fromiter((hit[2] if hit[0] >= 0 else -1.0 for hit in hits), float)
            readings[first:last] = np.where(
                fractions < 0.0, self.range, self.radius + fractions * span
            )
        if noise > 0.0:
            if rng is None:
                raise ValueError("lidar noise needs a generator (rng)")
            draws = rng.standard_normal(self.rays) * noise
            hit = readings < self.range
            readings[hit] = np.clip(readings[hit] + draws[hit], 0.0, self.range)
        return readings

    def close(self) -> None:
        """Disconnect the lidar's scene; calling it again does nothing."""
        self.scene.close()
