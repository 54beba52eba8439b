"""A maze layout as data: the arena, its solids, the start and the goal, in maze units.

Plain frozen dataclasses with no behaviour beyond derived values: reading files is
``bullet_maze.layout``, checking them ``bullet_maze.validation``, geometry
``bullet_maze.geometry``. Maze units: x right, y up, origin at the arena's lower-left corner
(section V.A's arena is 300 x 300).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

DEFAULT_ROBOT_RADIUS = 5.0
"""Radius of the disc robot when a layout does not give one (maze units)."""

DEFAULT_START_SIZE = 20.0
"""Side of the drawn start square when a layout does not give one (maze units)."""


@dataclass(frozen=True)
class Obstacle:
    """A grey cylindrical obstacle (section V.A): centre and radius in maze units."""

    center: tuple[float, float]
    radius: float


@dataclass(frozen=True)
class Wall:
    """An axis-aligned box wall: centre and full size (width, height) in maze units."""

    center: tuple[float, float]
    size: tuple[float, float]


@dataclass(frozen=True)
class MazeLayout:
    """A maze: build a checked one with ``bullet_maze.load_layout`` (a name, a file or a
    generator spec), ``bullet_maze.generate_layout`` or ``bullet_maze.layout_from_maze_map``."""

    name: str
    arena: tuple[float, float]
    start: tuple[float, float]
    goal: tuple[float, float]
    goal_radius: float
    robot_radius: float = DEFAULT_ROBOT_RADIUS
    start_heading: float = math.pi / 2
    start_size: float = DEFAULT_START_SIZE
    obstacles: tuple[Obstacle, ...] = ()
    walls: tuple[Wall, ...] = ()
    description: str = ""
    source: str = field(default="<dict>", compare=False)
    """Where the layout came from (a file, a generator spec), for error messages."""

    @property
    def solid_count(self) -> int:
        """Number of walls and obstacles (the arena's own four walls not counted)."""
        return len(self.walls) + len(self.obstacles)

    def contains(self, x: float, y: float) -> bool:
        """Whether (x, y) lies strictly inside the arena."""
        return 0.0 < x < self.arena[0] and 0.0 < y < self.arena[1]
