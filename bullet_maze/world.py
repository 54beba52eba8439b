"""The maze built as pybullet bodies in one client, and the collision queries made on it.

Units: pybullet works in metres at ``params.METRES_PER_UNIT`` (0.1 m per maze unit); maze x and
y map to world x and y, z is up. The world holds

* the ground, a plane (collision) under a light floor (visual);
* static bodies for the solids: the four arena walls, the layout's walls (boxes) and obstacles
  (grey cylinders, section V.A). When they fit, one compound shape holds them all, so that one
  query covers them; ``createCollisionShapeArray``'s compounds hold at most
  ``COMPOUND_CHILDREN`` pieces (pybullet crashes beyond 16), so a larger layout has the four arena
  walls one body each and the rest in compounds of up to ``URDF_CHILDREN`` nearby pieces, each
  loaded from a URDF of one link with many collision and visual elements (pybullet's physics step
  costs about the same per static body whatever its size: 1,000 walls in 8 bodies step 2.5 times
  faster than in 132 compounds of 16);
* visual-only markers: the green start square and the red goal circle (section V.A);
* a collision probe: a cylinder of the robot's footprint radius with no visual shape. A query
  (``sweep_collides``) passes its collision shape and the footprint's pose to
  ``getClosestPoints``, which places it there itself: the probe body's own answers at that pose,
  bit for bit, without the cost of moving a body (a broadphase update); the body is moved only
  for the long queries of a layout of several solid bodies. It is filtered out of the physics
  simulation; cameras would draw its collision shape, so it is parked under the floor before
  rendering.

Queries in a layout of several solid bodies go to a query index instead (``_RegionIndex``): a
second pybullet client that only answers distance queries, holding the footprint's shape and, for
each ``REGION``-unit square of the arena that a query has visited, one body whose compound shape
holds every piece that can lie within ``SAFE_REACH`` of a footprint centred in the square (pieces
are copied into every square they are near). A query of that reach is then one ``getClosestPoints``
call against one body whatever the number of solids; its answers are the same pieces' answers,
bit for bit, as those of the bodies above (the same shapes at the same places). Longer reaches ask
the bodies above. The index never takes part in the simulation or in pictures.
"""

from __future__ import annotations

import contextlib
import math
import os
import tempfile
import weakref
from typing import NamedTuple

import numpy as np
import pybullet as pb

from bullet_maze.layout_types import MazeLayout
from bullet_maze.params import BOUNDARY_THICKNESS, METRES_PER_UNIT, WALL_HEIGHT, PhysicsParams

CONTACT_TOLERANCE = 1e-3
"""Maze units: a robot closer than this to a solid surface touches it (a collision). A move
that only grazes a solid between half this and this distance may pass as free."""

GROUND_FRICTION = 1.0
"""Lateral friction coefficient of the floor (rubber on concrete); pybullet multiplies it with
each robot link's own coefficient."""

SAFE_REACH = 50.0
"""Maze units: each sweep's first distance query looks this far, and the free disc it certifies
(the "safe ball") lets the following moves that stay inside it skip pybullet altogether."""

CELL = 5.0
"""Maze units: side of the square cells of the arena that each keep one pybullet query made at
their centre (see ``World.sweep_collides``). The solids never move, so it stays valid."""

CELL_REACH = 20.0
"""Maze units: how far a cell's query looks; a certificate covers moves within this of the
cell's centre (a cell's corner plus a step and its noise is less than 10)."""

COMPOUND_CHILDREN = 16
"""Most pieces in one compound of ``createCollisionShapeArray``: pybullet's limit (a layout with 13
obstacles and the four arena walls crashed the process before the solids were split)."""

URDF_CHILDREN = 256
"""Most pieces in one solid body loaded from a URDF (a link's collision elements make one compound,
which has no such limit: 8,000 load and answer queries). Measured on a maze of 1,128 walls in
dynamic mode: compounds of 16, 64, 256 and all pieces in one body ran 9,700, 20,500, 24,000 and
23,400 steps/s (bit-identical rollouts); pybullet visits every child of a compound a body meets."""

REGION = 200.0
"""Maze units: side of the squares of the query index (``_RegionIndex``): each holds a compound of
the pieces within about ``SAFE_REACH`` of it (in a forest of 1,000 trees in 1,000 x 1,000, about
100), so a query's cost depends on the solids near it, not on their number. A square's body costs
about 0.5 ms to build (at most 121 squares in the largest arena); a piece in it costs a query about
4 ns (pybullet's compound test visits every child)."""

REGION_MARGIN = 1.0
"""Maze units added to the reach of a region's body, far above pybullet's collision margins (0.001
m): a piece left out of a square's body is farther than ``SAFE_REACH`` plus this from every
footprint centred in the square."""

MAX_SWEEP_QUERIES = 256
"""Bound on the distance queries of one sweep; a sweep that needs more counts as a collision."""

COLOURS = {
    "ground": (0.93, 0.93, 0.90, 1.0),
    "wall": (0.30, 0.30, 0.32, 1.0),
    "obstacle": (0.55, 0.55, 0.58, 1.0),
    "start": (0.15, 0.70, 0.25, 1.0),
    "goal": (0.85, 0.12, 0.12, 1.0),
}
"""RGBA colours of the maze, after section V.A: green start, red goal, grey obstacles."""

_IDENTITY = (0.0, 0.0, 0.0, 1.0)


class Piece(NamedTuple):
    """One solid's shape: a box (``radius`` 0) or a cylinder (``size`` 0), in maze units."""

    center: tuple[float, float]
    size: tuple[float, float]
    radius: float
    colour: str


class World:
    """A layout's bodies in the pybullet client ``client``; see the module docstring."""

    def __init__(
        self,
        client: int,
        layout: MazeLayout,
        robot_radius: float,
        contact_release: bool = PhysicsParams.contact_release,
    ) -> None:
        self.client = client
        self.layout = layout
        self.robot_radius = robot_radius
        self.contact_release = contact_release
        """``PhysicsParams.contact_release``: a piece within the tolerance stops only a move
        towards it (False: every move, the sweep before 2026-12-07)."""
        self.solid_ids = self._build_solids()
        self._solid_set = frozenset(self.solid_ids)
        self._single = self.solid_ids[0] if len(self.solid_ids) == 1 else None
        self.ground_id = self._build_ground()
        self._build_markers()
        self.probe_id = self._build_probe(robot_radius)
        self._probe_xy = (math.nan, math.nan)
        self._safe = (math.nan, math.nan, -math.inf)  # centre x, y and radius of the safe ball
        self._disc = self._safe  # the cell's free disc that last certified a move
        self._cells: dict[tuple[int, int], _CellBounds | None] = {}
        self._index = (
            None
            if self._single is not None
            else _RegionIndex(self.pieces(), robot_radius, layout.arena)
        )

    def _build_ground(self) -> int:
        s, c = METRES_PER_UNIT, self.client
        w, h = self.layout.arena
        margin = BOUNDARY_THICKNESS
        shape = pb.createCollisionShape(pb.GEOM_PLANE, physicsClientId=c)
        visual = pb.createVisualShape(
            pb.GEOM_BOX,
            halfExtents=[(w / 2 + margin) * s, (h / 2 + margin) * s, 0.005],
            visualFramePosition=[w / 2 * s, h / 2 * s, -0.005],
            rgbaColor=COLOURS["ground"],
            physicsClientId=c,
        )
        ground = pb.createMultiBody(0.0, shape, visual, physicsClientId=c)
        pb.changeDynamics(ground, -1, lateralFriction=GROUND_FRICTION, physicsClientId=c)
        return ground

    def pieces(self) -> list[Piece]:
        """The solids in maze units, what the bodies are built from: the four arena walls
        (outside ``[0, w] x [0, h]``), then the layout's walls and its obstacles in file order."""
        w, h = self.layout.arena
        t = BOUNDARY_THICKNESS
        arena = [  # outside [0, w] x [0, h]
            Piece((w / 2, -t / 2), (w + 2 * t, t), 0.0, "wall"),
            Piece((w / 2, h + t / 2), (w + 2 * t, t), 0.0, "wall"),
            Piece((-t / 2, h / 2), (t, h), 0.0, "wall"),
            Piece((w + t / 2, h / 2), (t, h), 0.0, "wall"),
        ]
        walls = [Piece(wall.center, wall.size, 0.0, "wall") for wall in self.layout.walls]
        obstacles = [
            Piece(obstacle.center, (0.0, 0.0), obstacle.radius, "obstacle")
            for obstacle in self.layout.obstacles
        ]
        return arena + walls + obstacles

    def _build_solids(self) -> list[int]:
        """The solid bodies: one compound when every piece fits in one (boxes first, as
        ``_pieces`` orders them), else the four arena walls one body each and the rest in
        URDF compounds of nearby pieces."""
        pieces = self.pieces()
        if len(pieces) <= COMPOUND_CHILDREN:
            return [self._build_compound(pieces)]
        arena = [self._build_compound([piece]) for piece in pieces[:4]]
        bodies = [
            _load_urdf(self.client, group, visual=True)
            for group in _nearby_groups(pieces[4:], URDF_CHILDREN)
        ]
        for body in bodies:
            # The importer gives the compound itself (not its pieces) a margin of 1 mm, which
            # widens its bounding box; createMultiBody's compounds have none.
            pb.changeDynamics(body, -1, collisionMargin=0.0, physicsClientId=self.client)
        return arena + bodies

    def _build_compound(self, pieces: list[Piece]) -> int:
        s, c = METRES_PER_UNIT, self.client
        z = WALL_HEIGHT / 2
        types, extents, radii, lengths, positions, colours = [], [], [], [], [], []
        for piece in sorted(pieces, key=lambda p: p.radius > 0):  # boxes first
            (cx, cy), (sx, sy) = piece.center, piece.size
            if piece.radius:
                types.append(pb.GEOM_CYLINDER)
                extents.append([0.0, 0.0, 0.0])
                radii.append(piece.radius * s)
                lengths.append(WALL_HEIGHT * s)
            else:
                types.append(pb.GEOM_BOX)
                extents.append([sx / 2 * s, sy / 2 * s, z * s])
                radii.append(0.0)
                lengths.append(0.0)
            positions.append([cx * s, cy * s, z * s])
            colours.append(COLOURS[piece.colour])
        shape = pb.createCollisionShapeArray(
            shapeTypes=types,
            halfExtents=extents,
            radii=radii,
            lengths=lengths,
            collisionFramePositions=positions,
            physicsClientId=c,
        )
        visual = pb.createVisualShapeArray(
            shapeTypes=types,
            halfExtents=extents,
            radii=radii,
            lengths=lengths,
            rgbaColors=colours,
            visualFramePositions=positions,
            physicsClientId=c,
        )
        # A static rigid body, not a fixed-base multibody: pybullet then leaves it out of every
        # physics step's multibody updates (the dynamic step with 68 compounds runs 2.5x faster;
        # with one compound the rollouts are bit-identical either way).
        return pb.createMultiBody(0.0, shape, visual, useMaximalCoordinates=True, physicsClientId=c)

    def _build_markers(self) -> None:
        s, c, layout = METRES_PER_UNIT, self.client, self.layout
        half = layout.start_size / 2 * s
        square = pb.createVisualShape(
            pb.GEOM_BOX,
            halfExtents=[half, half, 0.002],
            rgbaColor=COLOURS["start"],
            physicsClientId=c,
        )
        self.start_marker_id = pb.createMultiBody(
            0.0, -1, square, [layout.start[0] * s, layout.start[1] * s, 0.002], physicsClientId=c
        )
        circle = pb.createVisualShape(
            pb.GEOM_CYLINDER,
            radius=layout.goal_radius * s,
            length=0.004,
            rgbaColor=COLOURS["goal"],
            physicsClientId=c,
        )
        self.goal_marker_id = pb.createMultiBody(
            0.0, -1, circle, [layout.goal[0] * s, layout.goal[1] * s, 0.002], physicsClientId=c
        )

    def _build_probe(self, radius: float) -> int:
        s, c = METRES_PER_UNIT, self.client
        shape = pb.createCollisionShape(
            pb.GEOM_CYLINDER, radius=radius * s, height=WALL_HEIGHT / 2 * s, physicsClientId=c
        )
        self._probe_shape = shape  # queried where the probe would be, without moving it
        probe = pb.createMultiBody(0.0, shape, -1, [0.0, 0.0, -WALL_HEIGHT * s], physicsClientId=c)
        # The probe only answers distance queries; it never touches anything in the simulation.
        pb.setCollisionFilterGroupMask(probe, -1, 0, 0, physicsClientId=c)
        return probe

    def move_markers(self, start: tuple[float, float], goal: tuple[float, float]) -> None:
        """Show the start square and the goal circle at these centres (maze units)."""
        s = METRES_PER_UNIT
        for marker, (x, y) in ((self.start_marker_id, start), (self.goal_marker_id, goal)):
            pb.resetBasePositionAndOrientation(
                marker, [x * s, y * s, 0.002], _IDENTITY, physicsClientId=self.client
            )

    def restore(self, state_id: int) -> None:
        """``pybullet.restoreState``: bodies, the probe included, go back to a saved state."""
        pb.restoreState(state_id, physicsClientId=self.client)
        self._probe_xy = (math.nan, math.nan)

    def park_probe(self) -> None:
        """Move the probe under the floor, out of sight of cameras (pybullet draws the collision
        shape of a body that has no visual shape)."""
        below = (0.0, 0.0, -WALL_HEIGHT * METRES_PER_UNIT)
        pb.resetBasePositionAndOrientation(
            self.probe_id, below, _IDENTITY, physicsClientId=self.client
        )
        self._probe_xy = (math.nan, math.nan)

    def place_probe(self, x: float, y: float) -> None:
        """Put the probe's centre at (x, y) in maze units."""
        if (x, y) != self._probe_xy:
            s = METRES_PER_UNIT
            pb.resetBasePositionAndOrientation(
                self.probe_id,
                (x * s, y * s, WALL_HEIGHT / 4 * s),
                _IDENTITY,
                physicsClientId=self.client,
            )
            self._probe_xy = (x, y)

    def distance(self, x: float, y: float, reach: float) -> float:
        """Distance (maze units) from a robot footprint at (x, y) to the nearest solid, or
        ``math.inf`` if nothing is within ``reach``."""
        points = self._closest(x, y, reach)
        if not points:
            return math.inf
        return min(point[8] for point in points) / METRES_PER_UNIT

    def certified_clear(self, x: float, y: float, reach: float) -> bool:
        """Whether what earlier queries left proves a footprint centred anywhere within
        ``reach`` of (x, y) free: the free disc around the centre of (x, y)'s cell (see
        ``sweep_collides``) or the safe ball covers that disc. Makes no query except the first
        one of a cell. False means "not proved", not "collides"."""
        cx, cy, free = self._disc  # the disc that answered last: often still covers the move
        if math.hypot(x - cx, y - cy) + reach <= free:
            return True
        cell = (int(x // CELL), int(y // CELL))
        bounds = self._cells.get(cell, _UNSEEN)
        if bounds is _UNSEEN:
            bounds = self._cells[cell] = self._cell_bounds(cell)
        if bounds is not None and math.hypot(x - bounds.cx, y - bounds.cy) + reach <= bounds.free:
            self._disc = (bounds.cx, bounds.cy, bounds.free)
            return True
        cx, cy, safe = self._safe
        return math.hypot(x - cx, y - cy) + reach <= safe

    def clear_within(self, x: float, y: float, reach: float) -> bool:
        """Whether a footprint centred anywhere within ``reach`` of (x, y) is free; answered
        by ``certified_clear`` when it can, else by a distance query that renews the safe
        ball."""
        if self.certified_clear(x, y, reach):
            return True
        look = max(reach, SAFE_REACH)
        gap = self.distance(x, y, look)
        self._safe = (x, y, min(gap, look) - CONTACT_TOLERANCE)
        return reach <= self._safe[2]

    def certified_free(self, x0: float, y0: float, x1: float, y1: float) -> bool:
        """Whether what earlier queries left proves the move from (x0, y0) to (x1, y1) free:
        the safe ball holds both ends, or the bounds of (x0, y0)'s cell clear it (see
        ``sweep_collides``). Makes no query except the first one of a cell. False means "not
        proved", not "collides"."""
        cx, cy, safe = self._safe
        if math.hypot(x1 - cx, y1 - cy) <= safe and math.hypot(x0 - cx, y0 - cy) <= safe:
            return True  # both ends, hence the whole segment, inside a certified free disc
        cell = (int(x0 // CELL), int(y0 // CELL))
        bounds = self._cells.get(cell, _UNSEEN)
        if bounds is _UNSEEN:
            bounds = self._cells[cell] = self._cell_bounds(cell)
        return bounds is not None and bounds.clear(x0, y0, x1, y1)

    def sweep_collides(self, x0: float, y0: float, x1: float, y1: float) -> bool:
        """Whether the robot's footprint comes within ``CONTACT_TOLERANCE`` of a solid anywhere
        on the straight move from (x0, y0) to (x1, y1).

        Conservative advancement with pybullet closest-point queries: each returned point gives
        the distance d to one convex piece (a box or a cylinder) and the normal n pointing away
        from it. The distance to a convex piece is a convex function of the travelled length t,
        so d(t) >= d + t (u . n) along the move direction u: the footprint may advance until the
        smallest such bound reaches the tolerance. A flat wall is passed or hit in one query, a
        move far from everything is cleared by the first, and no wall is skipped however thin.
        Most moves need no query at all. The latest first query's free disc (the "safe ball")
        is remembered, and each 5-unit cell of the arena keeps one query made at its centre c:
        the same convexity bound, d(q) >= d + n . (q - c) for every piece it saw, and d(q) >
        tolerance for the pieces it did not see while q is within ``CELL_REACH`` of c, clears
        any move whose two ends satisfy them (the bound is linear along the move, so its ends
        decide). A move the cached bounds cannot clear gets the queries above.

        A piece already within the tolerance stops only a move towards it (u . n < 0): the
        advance aims half-way into the band, so a move may end inside it, and a robot resting
        against a wall must still be able to leave it. With ``contact_release`` False, such a
        piece stops every move, as before 2026-12-07: a robot that ended a move inside the band
        was held there for the rest of the episode, every action a collision (issue 9, part 31).
        """
        if self.certified_free(x0, y0, x1, y1):
            return False
        length = math.hypot(x1 - x0, y1 - y0)
        if length == 0.0:
            return not self.clear_within(x0, y0, 0.0)
        ux, uy = (x1 - x0) / length, (y1 - y0) / length
        look = max(length, SAFE_REACH)
        points = self._closest(x0, y0, look)
        gap = min((p[8] for p in points), default=math.inf) / METRES_PER_UNIT
        self._safe = (x0, y0, min(gap, look) - CONTACT_TOLERANCE)
        travelled = 0.0
        for _ in range(MAX_SWEEP_QUERIES):
            advance = math.inf
            for point in points:
                distance = point[8] / METRES_PER_UNIT
                normal = point[7]
                rate = ux * normal[0] + uy * normal[1]
                if distance < CONTACT_TOLERANCE and (rate < 0.0 or not self.contact_release):
                    return True
                if rate < 0.0:
                    # Aim half-way into the tolerance band, so that a move into a wall ends
                    # with one more query instead of creeping up to the band's edge.
                    advance = min(advance, (distance - CONTACT_TOLERANCE / 2) / -rate)
            travelled += advance
            if travelled >= length:
                return False
            points = self._closest(x0 + travelled * ux, y0 + travelled * uy, length - travelled)
        return True

    def _cell_bounds(self, cell: tuple[int, int]) -> _CellBounds | None:
        """One query at the cell's centre; None if the centre is too close to a solid for its
        bounds to clear anything."""
        cx, cy = (cell[0] + 0.5) * CELL, (cell[1] + 0.5) * CELL
        pieces = []
        for point in self._closest(cx, cy, CELL_REACH):
            distance = point[8] / METRES_PER_UNIT
            if distance < CONTACT_TOLERANCE:
                return None
            pieces.append((distance, point[7][0], point[7][1]))
        return _CellBounds(cx, cy, tuple(pieces))

    def _closest(self, x: float, y: float, reach: float) -> list[tuple]:
        """pybullet's closest points between the footprint at (x, y) and every solid piece
        within ``reach`` (plus the tolerance). With several solid bodies, a reach up to
        ``SAFE_REACH`` asks the body of (x, y)'s square in the query index, which holds every
        piece that close; a longer one asks the solid bodies whose broadphase bounding box
        (which holds the body) meets the square of that reach around the footprint: the others
        are farther."""
        s, c = METRES_PER_UNIT, self.client
        far = (reach + CONTACT_TOLERANCE) * s
        if self._single is not None:
            # The probe's shape at the probe's pose (``place_probe``), placed by the query itself:
            # the same answers as the probe body's, bit for bit, without a move of its own.
            return pb.getClosestPoints(
                -1,
                self._single,
                far,
                collisionShapeA=self._probe_shape,
                collisionShapePositionA=(x * s, y * s, WALL_HEIGHT / 4 * s),
                physicsClientId=c,
            )
        if reach <= SAFE_REACH and self._index is not None:
            return self._index.closest(x, y, far)
        self.place_probe(x, y)
        e = (reach + self.robot_radius + 2 * CONTACT_TOLERANCE) * s
        top = WALL_HEIGHT * s
        near = pb.getOverlappingObjects(
            (x * s - e, y * s - e, -top), (x * s + e, y * s + e, 2 * top), physicsClientId=c
        )
        points: list[tuple] = []
        solids = self._solid_set
        for body, _ in near or ():
            if body in solids:
                points.extend(pb.getClosestPoints(self.probe_id, body, far, physicsClientId=c))
        return points

    def close(self) -> None:
        """Disconnect the query index's client (the world's own client is its owner's)."""
        if self._index is not None:
            self._index.close()
            self._index = None

    def touching(self, body_id: int) -> bool:
        """Whether a simulated body is in contact with a wall or an obstacle."""
        limit = CONTACT_TOLERANCE * METRES_PER_UNIT
        if self._single is not None:
            contacts = pb.getContactPoints(body_id, self._single, physicsClientId=self.client)
            return any(point[8] < limit for point in contacts)
        solids = self._solid_set
        return any(
            point[8] < limit and point[2] in solids
            for point in pb.getContactPoints(body_id, physicsClientId=self.client)
        )

    def touching_now(self, body_id: int) -> bool:
        """``touching`` after a fresh collision detection of the current poses."""
        pb.performCollisionDetection(physicsClientId=self.client)
        return self.touching(body_id)


class _CellBounds:
    """Lower bounds on the footprint's distance to every solid around a cell's centre."""

    __slots__ = ("cx", "cy", "free", "pieces")

    def __init__(
        self, cx: float, cy: float, pieces: tuple[tuple[float, float, float], ...]
    ) -> None:
        self.cx, self.cy = cx, cy
        self.pieces = pieces  # (distance at the centre, normal x, normal y) per convex piece
        # Radius of the disc around the centre where a footprint is free: pieces the query did
        # not return lie farther than its reach plus the tolerance.
        nearest = min((piece[0] for piece in pieces), default=CELL_REACH + CONTACT_TOLERANCE)
        self.free = min(nearest, CELL_REACH + CONTACT_TOLERANCE) - CONTACT_TOLERANCE

    def clear(self, x0: float, y0: float, x1: float, y1: float) -> bool:
        """Whether the bounds prove the move from (x0, y0) to (x1, y1) free."""
        ax, ay, bx, by = x0 - self.cx, y0 - self.cy, x1 - self.cx, y1 - self.cy
        if math.hypot(ax, ay) > CELL_REACH or math.hypot(bx, by) > CELL_REACH:
            return False
        for distance, nx, ny in self.pieces:
            if (
                distance + nx * ax + ny * ay < CONTACT_TOLERANCE
                or distance + nx * bx + ny * by < CONTACT_TOLERANCE
            ):
                return False
        return True


class _RegionIndex:
    """The query index of a layout of several solid bodies: a pybullet client of its own with the
    footprint's collision shape and one static body per ``REGION`` square of the arena (those
    outside it, which a move through the arena's wall may visit, when first asked; see the module
    docstring)."""

    def __init__(
        self, pieces: list[Piece], robot_radius: float, arena: tuple[float, float]
    ) -> None:
        self.pieces = pieces
        half = np.array(
            [(p.size[0] / 2, p.size[1] / 2) if not p.radius else (p.radius,) * 2 for p in pieces]
        )
        centres = np.array([p.center for p in pieces])
        self._low, self._high = centres - half, centres + half  # bounding boxes
        # A footprint centred in the square is farther than SAFE_REACH + REGION_MARGIN from a
        # piece whose bounding box is farther than this from the square.
        self._margin = SAFE_REACH + CONTACT_TOLERANCE + robot_radius + REGION_MARGIN
        self.client = pb.connect(pb.DIRECT)
        self._finalizer = weakref.finalize(self, disconnect_client, self.client)
        s, c = METRES_PER_UNIT, self.client
        # The footprint is a collision shape, not a body: a query places it itself. Moving a probe
        # body costs a broadphase update that grows with the bodies in the client (0.9 us alone,
        # 1.7 us among the 100 squares of a 1,880 x 1,880 maze) and a command of its own.
        self._shape = pb.createCollisionShape(
            pb.GEOM_CYLINDER, radius=robot_radius * s, height=WALL_HEIGHT / 2 * s, physicsClientId=c
        )
        self._bodies: dict[tuple[int, int], int | None] = {}
        for i in range(int(arena[0] // REGION) + 1):
            for j in range(int(arena[1] // REGION) + 1):
                self._bodies[i, j] = self._build((i, j))

    def closest(self, x: float, y: float, far: float) -> list[tuple]:
        """``getClosestPoints`` within ``far`` (metres, at most ``SAFE_REACH`` units plus the
        tolerance) between the footprint at (x, y) and the body of (x, y)'s square."""
        square = (int(x // REGION), int(y // REGION))
        body = self._bodies.get(square, -1)
        if body == -1:
            body = self._bodies[square] = self._build(square)
        if body is None:
            return []
        s = METRES_PER_UNIT
        # The footprint's shape at the pose a probe body would have (World.place_probe): the same
        # transform, hence the same answers bit for bit (tests compare them with the probe's).
        return pb.getClosestPoints(
            -1,
            body,
            far,
            collisionShapeA=self._shape,
            collisionShapePositionA=(x * s, y * s, WALL_HEIGHT / 4 * s),
            physicsClientId=self.client,
        )

    def _build(self, square: tuple[int, int]) -> int | None:
        """The square's body: the pieces whose bounding box comes within the margin of it, as one
        compound (a URDF link of many collision elements, where pybullet's compounds of
        ``createCollisionShapeArray`` stop at 16 pieces); None if there are none."""
        low = np.array(square, dtype=float) * REGION - self._margin
        high = low + REGION + 2 * self._margin
        near = np.flatnonzero(np.all((self._high >= low) & (self._low <= high), axis=1))
        if near.size == 0:
            return None
        return _load_urdf(self.client, [self.pieces[i] for i in near], visual=False)

    def close(self) -> None:
        self._finalizer()


def disconnect_client(client: int) -> None:
    """Disconnect a client of this package's own (a query index, a ray scene), if still there."""
    with contextlib.suppress(pb.error):  # already gone with its server
        pb.disconnect(physicsClientId=client)


def _load_urdf(client: int, pieces: list[Piece], visual: bool) -> int:
    """A static rigid body of one link whose compound holds the pieces (``_urdf``)."""
    fd, path = tempfile.mkstemp(suffix=".urdf")
    try:
        with os.fdopen(fd, "w") as file:
            file.write(_urdf(pieces, visual))
        return pb.loadURDF(
            path,
            useMaximalCoordinates=True,
            useFixedBase=True,
            flags=pb.URDF_USE_IMPLICIT_CYLINDER,
            physicsClientId=client,
        )
    finally:
        os.unlink(path)


def _urdf(pieces: list[Piece], visual: bool) -> str:
    """A URDF of one static link whose collision elements are the pieces, exactly as
    ``World._build_compound`` makes them (boxes first; the same sizes in metres, written so that
    they read back to the same doubles: queries answer bit for bit as on that compound), with a
    visual element of the piece's colour each if ``visual``; one element a line (pybullet's reader
    fails on very long lines). Without ``visual`` a tiny box stands for the link's looks: without
    any, pybullet would tessellate every cylinder for its renderer (25 times slower to load)."""
    s = METRES_PER_UNIT
    z = WALL_HEIGHT / 2
    lines = ['<?xml version="1.0"?>', '<robot name="solids">']
    lines += [
        f'<material name="{name}"><color rgba="{" ".join(repr(float(v)) for v in COLOURS[name])}"/>'
        "</material>"
        for name in ("wall", "obstacle")
    ]
    lines += [
        '<link name="solids">',
        '<inertial><mass value="0"/>'
        '<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>',
    ]
    if not visual:
        lines.append('<visual><geometry><box size="0.001 0.001 0.001"/></geometry></visual>')
    for piece in sorted(pieces, key=lambda p: p.radius > 0):
        (cx, cy), (sx, sy) = piece.center, piece.size
        if piece.radius:
            radius, length = float(piece.radius * s), float(WALL_HEIGHT * s)
            geometry = f'<cylinder radius="{radius!r}" length="{length!r}"/>'
        else:
            # The importer halves the sizes: twice _build_compound's half extents (exact).
            size = (float(2 * (sx / 2 * s)), float(2 * (sy / 2 * s)), float(2 * (z * s)))
            geometry = f'<box size="{size[0]!r} {size[1]!r} {size[2]!r}"/>'
        x, y, h = float(cx * s), float(cy * s), float(z * s)
        element = f'<origin xyz="{x!r} {y!r} {h!r}"/><geometry>{geometry}</geometry>'
        lines.append(f"<collision>{element}</collision>")
        if visual:
            lines.append(f'<visual>{element}<material name="{piece.colour}"/></visual>')
    lines.append("</link></robot>")
    return "\n".join(lines) + "\n"


def _nearby_groups(pieces: list[Piece], most: int) -> list[list[Piece]]:
    """Split pieces into groups of at most ``most`` by halving along the longer side of their
    centres' spread, so that each group's bounding box is small."""
    if len(pieces) <= most:
        return [pieces]
    centres = np.array([piece.center for piece in pieces])
    axis = int(np.argmax(np.ptp(centres, axis=0)))
    order = np.argsort(centres[:, axis], kind="stable")
    half = len(pieces) // 2
    first = [pieces[i] for i in order[:half]]
    second = [pieces[i] for i in order[half:]]
    return _nearby_groups(first, most) + _nearby_groups(second, most)


_UNSEEN = _CellBounds(math.nan, math.nan, ())
"""Marks a cell not queried yet (distinct from None, a cell whose bounds are useless)."""
