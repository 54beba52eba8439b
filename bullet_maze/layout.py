"""Maze layouts as data: TOML files in ``assets/mazes/``, loaded and validated into ``MazeLayout``.

A layout holds the arena size, walls (axis-aligned boxes), obstacles (cylinders), the start
square, the goal circle and the radius of the default disc robot, all in maze units (x right,
y up, origin at the arena's lower-left corner; section V.A's arena is 300 x 300). Every error
is a ``ValueError`` that names the file and the field.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from assets import MAZE_DIR
from bullet_maze.geometry import clearance
from bullet_maze.planning import goal_reachable

DEFAULT_LAYOUT = "paper"
"""The layout of ``BulletMaze-v0``: section V.A's maze as closely as its text allows."""

DEFAULT_ROBOT_RADIUS = 5.0
"""Radius of the disc robot when a layout does not give one (maze units)."""

DEFAULT_START_SIZE = 20.0
"""Side of the drawn start square when a layout does not give one (maze units)."""

_SCHEMA: dict[str, dict[str, bool]] = {
    "": {
        "name": False,
        "description": False,
        "robot_radius": False,
        "arena": True,
        "start": True,
        "goal": True,
        "obstacles": False,
        "walls": False,
    },
    "arena": {"size": True},
    "start": {"position": True, "heading": False, "size": False},
    "goal": {"position": True, "radius": True},
    "obstacles": {"center": True, "radius": True},
    "walls": {"center": True, "size": True},
}
"""Allowed keys of each table and whether each is required."""


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
    """A validated maze; build one with ``load_layout`` or ``MazeLayout.from_dict``."""

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

    @classmethod
    def from_dict(cls, data: dict[str, Any], source: str = "<dict>") -> MazeLayout:
        """Validate a parsed TOML document; ``source`` names it in error messages."""
        _check_keys(data, "", source)
        arena_table = _table(data["arena"], "arena", source)
        _check_keys(arena_table, "arena", source)
        arena = _pair(arena_table["size"], "arena.size", source, positive=True)
        start_table = _table(data["start"], "start", source)
        _check_keys(start_table, "start", source)
        goal_table = _table(data["goal"], "goal", source)
        _check_keys(goal_table, "goal", source)
        obstacles = []
        for i, item in enumerate(_array(data.get("obstacles", []), "obstacles", source)):
            where = f"obstacles[{i}]"
            item = _table(item, where, source)
            _check_keys(item, "obstacles", source, where)
            obstacles.append(
                Obstacle(
                    _pair(item["center"], f"{where}.center", source),
                    _number(item["radius"], f"{where}.radius", source, positive=True),
                )
            )
        walls = []
        for i, item in enumerate(_array(data.get("walls", []), "walls", source)):
            where = f"walls[{i}]"
            item = _table(item, where, source)
            _check_keys(item, "walls", source, where)
            walls.append(
                Wall(
                    _pair(item["center"], f"{where}.center", source),
                    _pair(item["size"], f"{where}.size", source, positive=True),
                )
            )
        name = data.get("name", Path(source).stem)
        description = data.get("description", "")
        for key, value in (("name", name), ("description", description)):
            if not isinstance(value, str):
                raise ValueError(f"{source}: field '{key}' must be a string, got {value!r}")
        layout = cls(
            name=name,
            arena=arena,
            start=_pair(start_table["position"], "start.position", source),
            goal=_pair(goal_table["position"], "goal.position", source),
            goal_radius=_number(goal_table["radius"], "goal.radius", source, positive=True),
            robot_radius=_number(
                data.get("robot_radius", DEFAULT_ROBOT_RADIUS),
                "robot_radius",
                source,
                positive=True,
            ),
            start_heading=_number(start_table.get("heading", math.pi / 2), "start.heading", source),
            start_size=_number(
                start_table.get("size", DEFAULT_START_SIZE), "start.size", source, positive=True
            ),
            obstacles=tuple(obstacles),
            walls=tuple(walls),
            description=description,
            source=source,
        )
        layout.validate()
        return layout

    def validate(self, robot_radius: float | None = None) -> None:
        """Check that start and goal lie in the arena and the goal is reachable.

        ``robot_radius`` defaults to the layout's own; raises ``ValueError`` naming the field.
        """
        radius = self.robot_radius if robot_radius is None else robot_radius
        src = self.source
        for key, (x, y) in (("start.position", self.start), ("goal.position", self.goal)):
            if not (0.0 < x < self.arena[0] and 0.0 < y < self.arena[1]):
                raise ValueError(
                    f"{src}: field '{key}' = ({x}, {y}) lies outside the arena "
                    f"[0, {self.arena[0]}] x [0, {self.arena[1]}]"
                )
        for i, obstacle in enumerate(self.obstacles):
            if math.dist(self.goal, obstacle.center) < obstacle.radius:
                raise ValueError(
                    f"{src}: field 'goal.position' = {self.goal} lies inside obstacles[{i}]"
                )
        for i, wall in enumerate(self.walls):
            if (
                abs(self.goal[0] - wall.center[0]) < wall.size[0] / 2
                and abs(self.goal[1] - wall.center[1]) < wall.size[1] / 2
            ):
                raise ValueError(
                    f"{src}: field 'goal.position' = {self.goal} lies inside walls[{i}]"
                )
        start_clearance = float(clearance(self, np.array(self.start)))
        if start_clearance < radius:
            raise ValueError(
                f"{src}: field 'start.position' = {self.start}: a robot of radius {radius} "
                f"there overlaps a wall or an obstacle (clearance {start_clearance:.2f})"
            )
        if not goal_reachable(self, radius):
            raise ValueError(
                f"{src}: field 'goal' at {self.goal} (radius {self.goal_radius}) "
                f"cannot be reached from the start by a robot of radius {radius}"
            )

    def contains(self, x: float, y: float) -> bool:
        """Whether (x, y) lies strictly inside the arena."""
        return 0.0 < x < self.arena[0] and 0.0 < y < self.arena[1]


def available_layouts() -> list[str]:
    """Names of the layouts shipped in ``assets/mazes/``."""
    return sorted(p.stem for p in MAZE_DIR.glob("*.toml"))


def load_layout(name_or_path: str | Path | MazeLayout) -> MazeLayout:
    """Load a layout by name (``"paper"``, ``"open"``, ...) or from a TOML file path."""
    if isinstance(name_or_path, MazeLayout):
        return name_or_path
    if not isinstance(name_or_path, str | Path):
        raise TypeError(
            f"maze must be a layout name, a path or a MazeLayout, got {type(name_or_path).__name__}"
        )
    text = str(name_or_path)
    path = Path(text)
    if path.suffix != ".toml" and "/" not in text and "\\" not in text:
        path = MAZE_DIR / f"{text}.toml"
        if not path.is_file():
            raise ValueError(
                f"unknown maze {text!r}: choose one of {available_layouts()} "
                f"or give a path to a .toml file"
            )
    if not path.is_file():
        raise FileNotFoundError(f"maze file not found: {path}")
    try:
        with path.open("rb") as handle:
            data = tomllib.load(handle)
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"{path}: not valid TOML: {err}") from err
    return MazeLayout.from_dict(data, source=str(path))


def _check_keys(table: dict[str, Any], kind: str, source: str, where: str | None = None) -> None:
    prefix = f"{where or kind}." if (where or kind) else ""
    allowed = _SCHEMA[kind]
    for key in table:
        if key not in allowed:
            raise ValueError(
                f"{source}: unknown field '{prefix}{key}' (allowed: {', '.join(allowed)})"
            )
    for key, required in allowed.items():
        if required and key not in table:
            raise ValueError(f"{source}: missing field '{prefix}{key}'")


def _table(value: Any, where: str, source: str) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise ValueError(f"{source}: field '{where}' must be a table, got {value!r}")
    return value


def _array(value: Any, where: str, source: str) -> list[Any]:
    if not isinstance(value, list):
        raise ValueError(f"{source}: field '{where}' must be an array of tables, got {value!r}")
    return value


def _number(value: Any, where: str, source: str, positive: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ValueError(f"{source}: field '{where}' must be a finite number, got {value!r}")
    if positive and value <= 0:
        raise ValueError(f"{source}: field '{where}' must be positive, got {value!r}")
    return float(value)


def _pair(value: Any, where: str, source: str, positive: bool = False) -> tuple[float, float]:
    if not isinstance(value, list | tuple) or len(value) != 2:
        raise ValueError(f"{source}: field '{where}' must be a pair [x, y], got {value!r}")
    return (
        _number(value[0], f"{where}[0]", source, positive),
        _number(value[1], f"{where}[1]", source, positive),
    )
