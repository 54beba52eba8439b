"""The lidar's scene: a pybullet client of its own holding the layout's solids as static triangle
meshes, which only answers ``rayTestBatch``.

Why a scene of its own: pybullet casts a ray against a convex shape (a box, a cylinder) by an
iterative convex cast, and against a cylinder that is slow and inexact. Measured on this machine
(pybullet 3.2.7, 36 rays across a cylinder of radius 4.5 m): 597 us a batch and up to 1.5 mm from
the true surface; the same rays against a triangle-mesh tube of 2,048 sides took 44 us and were
within 0.015 mm. On the paper's maze, the three cylinders made 175 of the 226 us a 36-ray read
spent in pybullet. A triangle is an exact plane, so a box's mesh is the box itself (its faces cut
into pieces of ``MAX_SEGMENT``, for pybullet's edge tolerance); a cylinder's mesh is a prism of
``cylinder_sides(radius)`` sides whose faces lie within ``MESH_TOLERANCE`` of the cylinder's
surface (their middles inside it, their ends outside).

The meshes are tubes with no caps: the rays are horizontal at half the walls' height (and the
solids are vertical prisms taller than any robot), so they never meet a cap. The scene holds no
robot and no ground: rays start on the robot's footprint and never reach the floor. The solids
never move, so the scene is built once, from the same pieces as the simulation's bodies
(``World.pieces``), and never takes part in the simulation.
"""

from __future__ import annotations

import logging
import math
import weakref
from collections.abc import Sequence

import numpy as np
import pybullet as pb

from bullet_maze.params import METRES_PER_UNIT, WALL_HEIGHT
from bullet_maze.world import Piece, disconnect_client

logger = logging.getLogger(__name__)

MESH_TOLERANCE = 1e-3
"""Maze units (0.1 mm at the default scale): the farthest a cylinder's mesh face lies from the
cylinder's surface, along the radius (a ray meeting the surface at an angle theta from its normal
reads up to this over cos(theta) off; the simulation's own cylinder answers rays up to 0.04 units
off, and misses some)."""

MAX_SEGMENT = 1.0
"""Maze units: the longest horizontal edge of a mesh triangle. pybullet counts a ray as hitting a
triangle when it passes outside an edge by up to about 1e-4 of the triangle's other extent (its
edge tolerance), so a box's faces are cut into pieces of at most this length: a ray that passes a
box's corner by more than ``1e-4 * MAX_SEGMENT`` units misses it (a whole 15 m face let rays
through 1.5 mm beyond its corner count as hits)."""

MAX_SCENE_SIDES = 200_000
"""Most sides (vertical faces of two triangles) of a scene's distinct meshes in all: about 240 MB,
since pybullet keeps about 1.2 KB a side (measured: 1,000 cylinders of distinct radii, 99,653
sides, 120 MB). Equal solids share one mesh. A layout that would need more (thousands of large
cylinders of distinct radii, or long walls) gets coarser meshes, with a logged warning: the
coarsening ``k > 1`` that fits multiplies ``MAX_SEGMENT`` by ``k`` and ``MESH_TOLERANCE`` by
``k ** 2`` (both kinds then need about ``1 / k`` as many sides); ``RayScene.tolerance`` and
``RayScene.segment`` say what the scene holds."""

MIN_SIDES = 16
"""Fewest sides of a cylinder's mesh, for the smallest radii."""

MAX_SIDES = 16384
"""Most sides of a cylinder's mesh (32,768 vertices, within pybullet's mesh limit): only radii
above about 100,000 units, far beyond the largest arena, would have faces farther than
``MESH_TOLERANCE`` from the surface."""


def cylinder_sides(radius: float, tolerance: float = MESH_TOLERANCE) -> int:
    """Sides of the prism standing for a cylinder of ``radius`` maze units: the fewest that keep
    every face within ``tolerance`` of the surface, in ``[MIN_SIDES, MAX_SIDES]``.

    With the vertices at ``R_v = 2 R / (1 + cos(pi / n))`` the faces' midpoints lie at
    ``R_v cos(pi / n)``, so the radial error is at most
    ``R (1 - cos(pi / n)) / (1 + cos(pi / n)) = R tan(pi / (2 n))^2`` (about ``R (pi / n)^2 / 4``).
    """
    sides = math.ceil(math.pi / (2.0 * math.atan(math.sqrt(tolerance / radius))))
    return min(max(sides, MIN_SIDES), MAX_SIDES)


def _key(piece: Piece) -> tuple[str, float, float]:
    """A piece's geometry without its place: pieces with equal keys share one mesh."""
    if piece.radius:
        return ("cylinder", piece.radius, 0.0)
    return ("box", piece.size[0], piece.size[1])


def _section(key: tuple[str, float, float], tolerance: float, segment: float) -> np.ndarray:
    """The horizontal section of a box ``("box", sx, sy)`` or a cylinder ``("cylinder", r, 0)``
    (maze units) as its mesh's corners in order, in metres about its centre, no edge longer than
    ``segment`` units."""
    s = METRES_PER_UNIT
    kind, a, b = key
    if kind == "cylinder":
        n = cylinder_sides(a, tolerance)
        out = 2.0 * a / (1.0 + math.cos(math.pi / n)) * s
        angles = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
        corners = np.column_stack((np.cos(angles), np.sin(angles))) * out
    else:
        hx, hy = a / 2 * s, b / 2 * s
        corners = np.array([(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)])
    return _subdivided(corners, segment * s)


def _subdivided(corners: np.ndarray, longest: float) -> np.ndarray:
    """The closed polygon ``corners`` ((n, 2), in order) with points added along each edge so
    that no edge is longer than ``longest``."""
    edges = np.roll(corners, -1, axis=0) - corners
    pieces = np.maximum(1, np.ceil(np.hypot(edges[:, 0], edges[:, 1]) / longest)).astype(int)
    if np.all(pieces == 1):
        return corners
    edge = np.repeat(np.arange(len(corners)), pieces)
    first = np.cumsum(pieces) - pieces  # each edge's first point in the output
    step = (np.arange(len(edge)) - first[edge]) / pieces[edge]
    return corners[edge] + edges[edge] * step[:, None]


def _tube(corners: np.ndarray, half_height: float) -> tuple[list[list[float]], list[int]]:
    """Vertices and triangle indices of the vertical walls of the prism over ``corners`` (an
    (n, 2) array in order round the section), from ``-half_height`` to ``half_height``."""
    n = len(corners)
    low = np.column_stack((corners, np.full(n, -half_height)))
    high = np.column_stack((corners, np.full(n, half_height)))
    i = np.arange(n)
    j = (i + 1) % n
    triangles = np.column_stack((i, j, n + j, i, n + j, n + i))
    return np.vstack((low, high)).tolist(), triangles.ravel().tolist()


class RayScene:
    """The solids ``pieces`` (each with ``center``, ``size`` and ``radius`` in maze units, as
    ``World.pieces`` gives them) as meshes in a pybullet client of their own; see the module
    docstring. ``cast`` answers a batch of rays in metres."""

    def __init__(self, pieces: Sequence[Piece]) -> None:
        keys = {_key(p): None for p in pieces}  # one mesh per distinct geometry, in order
        coarsening = 1.0
        while True:
            self.tolerance = MESH_TOLERANCE * coarsening**2
            self.segment = MAX_SEGMENT * coarsening
            sections = {key: _section(key, self.tolerance, self.segment) for key in keys}
            self.sides = sum(len(corners) for corners in sections.values())
            if self.sides <= MAX_SCENE_SIDES:
                break
            coarsening *= max(1.1, self.sides / MAX_SCENE_SIDES)
        if coarsening > 1.0:
            logger.warning(
                "lidar: %d distinct solids would need more than %d mesh sides "
                "(bullet_maze.ray_scene.MAX_SCENE_SIDES); their meshes are coarser: cylinder "
                "faces within %.3g units of the surface, wall faces in pieces of %.3g units",
                len(keys),
                MAX_SCENE_SIDES,
                self.tolerance,
                self.segment,
            )
        self.client = pb.connect(pb.DIRECT)
        self._finalizer = weakref.finalize(self, disconnect_client, self.client)
        s, c = METRES_PER_UNIT, self.client
        half_height = WALL_HEIGHT / 2 * s
        shapes: dict[tuple[str, float, float], int] = {}
        try:
            for piece in pieces:
                cx, cy = piece.center
                key = _key(piece)
                if key not in shapes:
                    vertices, indices = _tube(sections[key], half_height)
                    shapes[key] = pb.createCollisionShape(
                        pb.GEOM_MESH, vertices=vertices, indices=indices, physicsClientId=c
                    )
                pb.createMultiBody(
                    0.0,
                    shapes[key],
                    -1,
                    [cx * s, cy * s, half_height],
                    useMaximalCoordinates=True,
                    physicsClientId=c,
                )
        except BaseException:
            self.close()
            raise

    def cast(self, starts: np.ndarray, ends: np.ndarray) -> list:
        """``rayTestBatch`` of the rays from ``starts`` to ``ends`` ((n, 3) arrays in metres,
        n below pybullet's batch limit): one (body, link, fraction, position, normal) a ray."""
        return pb.rayTestBatch(starts, ends, physicsClientId=self.client)

    def close(self) -> None:
        """Disconnect the scene's client; calling it again does nothing."""
        self._finalizer()
