"""Maze layouts from their sources: shipped names, TOML files and generator specs, each checked.

``load_layout`` takes

* a ``MazeLayout`` (checked, returned as it is);
* a path (a ``Path``, or a string ending in ``.toml``): a TOML layout file;
* a generator spec ``"family:key=value,..."`` such as ``"rooms:seed=3,door=30"``
  (``bullet_maze.generators``; the seed defaults to 0);
* a shipped name: ``"paper"``, ``"open"``, ... (``available_layouts()``), or
  ``"collection/name"`` for a shipped collection such as ``"pointmaze/umaze"``
  (``available_layouts("pointmaze")``).

A layout file holds the arena size, walls (axis-aligned boxes), obstacles (cylinders), the start
square, the goal circle and the radius of the default disc robot, in maze units (x right, y up,
origin at the arena's lower-left corner; section V.A's arena is 300 x 300). ``parse_layout``
reads its fields, ``bullet_maze.validation.validate_layout`` checks the whole, and
``layout_to_toml`` writes one back (loading that text gives an equal layout). Every error is a
``ValueError`` that names the file (or spec) and the field.
"""

from __future__ import annotations

import json
import math
import tomllib
from pathlib import Path
from typing import Any

from assets import MAZE_DIR
from bullet_maze.generators import generate_from_spec, is_generator_spec
from bullet_maze.layout_types import (
    DEFAULT_ROBOT_RADIUS,
    DEFAULT_START_SIZE,
    MazeLayout,
    Obstacle,
    Wall,
)
from bullet_maze.params import MAX_LAYOUT_FILE_BYTES, MAX_SOLIDS
from bullet_maze.validation import validate_layout

DEFAULT_LAYOUT = "paper"
"""The layout of ``BulletMaze-v0``: section V.A's maze as closely as its text allows."""

MAX_SPEC_LENGTH = 1000
"""Longest string ``load_layout`` takes (a name, a path or a generator spec)."""

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

__all__ = [
    "DEFAULT_LAYOUT",
    "DEFAULT_ROBOT_RADIUS",
    "DEFAULT_START_SIZE",
    "MazeLayout",
    "Obstacle",
    "Wall",
    "available_layouts",
    "layout_to_dict",
    "layout_to_toml",
    "load_layout",
    "parse_layout",
    "read_toml",
]


def load_layout(maze: str | Path | MazeLayout) -> MazeLayout:
    """A checked layout from a name, a file, a generator spec or a ``MazeLayout`` (see the
    module docstring)."""
    if isinstance(maze, MazeLayout):
        validate_layout(maze)
        return maze
    if isinstance(maze, Path):
        return _load_file(maze)
    if not isinstance(maze, str):
        raise TypeError(
            "maze must be a layout name, a path, a generator spec or a MazeLayout, "
            f"got {type(maze).__name__}"
        )
    if len(maze) > MAX_SPEC_LENGTH:
        raise ValueError(f"maze {_show(maze)}: longer than {MAX_SPEC_LENGTH:,} characters")
    if maze.endswith(".toml"):
        return _load_file(Path(maze))
    if is_generator_spec(maze):
        return generate_from_spec(maze)
    path = _shipped_path(maze)
    if path is not None:
        return _load_file(path)
    if ("/" in maze or "\\" in maze) and Path(maze).is_file():
        return _load_file(Path(maze))
    collections = sorted(p.name for p in MAZE_DIR.iterdir() if p.is_dir())
    raise ValueError(
        f"unknown maze {_show(maze)}: choose one of {available_layouts()}, a layout of a "
        f"collection ({', '.join(f'{c}/...' for c in collections)}), a generator spec such as "
        "'rooms:seed=3' or a path to a .toml file"
    )


def available_layouts(collection: str | None = None) -> list[str]:
    """Names of the layouts shipped in ``assets/mazes/`` (the hand-written ones, each also
    registered as ``BulletMaze-<name>-v0``), or those of a collection (a subfolder, e.g.
    ``"pointmaze"``), as ``"collection/name"``."""
    if collection is None:
        return sorted(p.stem for p in MAZE_DIR.glob("*.toml"))
    folder = MAZE_DIR / collection
    if not (collection.isidentifier() and folder.is_dir()):
        collections = sorted(p.name for p in MAZE_DIR.iterdir() if p.is_dir())
        raise ValueError(f"unknown layout collection {collection!r}: choose one of {collections}")
    return sorted(f"{collection}/{p.stem}" for p in folder.glob("*.toml"))


def _shipped_path(name: str) -> Path | None:
    parts = name.split("/")
    if not (1 <= len(parts) <= 2 and all(part.isidentifier() for part in parts)):
        return None
    path = MAZE_DIR.joinpath(*parts).with_suffix(".toml")
    return path if path.is_file() else None


def _load_file(path: Path) -> MazeLayout:
    layout = parse_layout(read_toml(path), source=str(path))
    validate_layout(layout)
    return layout


def read_toml(path: Path, what: str = "maze") -> dict[str, Any]:
    """A TOML file's document; every failure a ``ValueError`` or ``FileNotFoundError`` naming
    the file (too large, not UTF-8, not TOML, nested too deeply)."""
    try:
        found = path.is_file()
        size = path.stat().st_size if found else 0
    except OSError as err:  # e.g. a name too long for the file system
        raise ValueError(f"{what} file {_show(str(path))}: {err.strerror}") from None
    if not found:
        raise FileNotFoundError(f"{what} file not found: {path}")
    if size > MAX_LAYOUT_FILE_BYTES:
        raise ValueError(
            f"{path}: {size:,} bytes, more than the {MAX_LAYOUT_FILE_BYTES:,} a {what} file may "
            "have (bullet_maze.params.MAX_LAYOUT_FILE_BYTES)"
        )
    try:
        text = path.read_bytes().decode("utf-8")
    except UnicodeDecodeError as err:
        raise ValueError(f"{path}: not a UTF-8 text file ({err})") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"{path}: not valid TOML: {err}") from None
    except RecursionError:
        raise ValueError(f"{path}: not valid TOML: nested too deeply") from None


def parse_layout(data: dict[str, Any], source: str = "<dict>") -> MazeLayout:
    """The ``MazeLayout`` of a parsed TOML document, its fields checked one by one (keys, types,
    finite numbers, positive sizes, the number of solids); ``source`` names it in errors.
    Whether the whole makes sense is ``validate_layout``'s question."""
    _check_keys(_table(data, "", source), "", source)
    arena_table = _table(data["arena"], "arena", source)
    _check_keys(arena_table, "arena", source)
    arena = _pair(arena_table["size"], "arena.size", source, positive=True)
    start_table = _table(data["start"], "start", source)
    _check_keys(start_table, "start", source)
    goal_table = _table(data["goal"], "goal", source)
    _check_keys(goal_table, "goal", source)
    obstacle_items = _array(data.get("obstacles", []), "obstacles", source)
    wall_items = _array(data.get("walls", []), "walls", source)
    if len(obstacle_items) + len(wall_items) > MAX_SOLIDS:
        raise ValueError(
            f"{source}: {len(wall_items)} walls and {len(obstacle_items)} obstacles make "
            f"{len(obstacle_items) + len(wall_items):,} solids, more than the {MAX_SOLIDS:,} "
            "allowed (bullet_maze.params.MAX_SOLIDS)"
        )
    obstacles = []
    for i, item in enumerate(obstacle_items):
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
    for i, item in enumerate(wall_items):
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
            raise ValueError(f"{source}: field '{key}' must be a string, got {_show(value)}")
    return MazeLayout(
        name=name,
        arena=arena,
        start=_pair(start_table["position"], "start.position", source),
        goal=_pair(goal_table["position"], "goal.position", source),
        goal_radius=_number(goal_table["radius"], "goal.radius", source, positive=True),
        robot_radius=_number(
            data.get("robot_radius", DEFAULT_ROBOT_RADIUS), "robot_radius", source, positive=True
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


def layout_to_dict(layout: MazeLayout) -> dict[str, Any]:
    """The TOML document of ``layout`` (every field written, so nothing depends on defaults)."""
    data: dict[str, Any] = {
        "name": layout.name,
        "description": layout.description,
        "robot_radius": layout.robot_radius,
        "arena": {"size": list(layout.arena)},
        "start": {
            "position": list(layout.start),
            "heading": layout.start_heading,
            "size": layout.start_size,
        },
        "goal": {"position": list(layout.goal), "radius": layout.goal_radius},
    }
    if layout.obstacles:
        data["obstacles"] = [
            {"center": list(o.center), "radius": o.radius} for o in layout.obstacles
        ]
    if layout.walls:
        data["walls"] = [{"center": list(w.center), "size": list(w.size)} for w in layout.walls]
    return data


def layout_to_toml(layout: MazeLayout, header: str = "") -> str:
    """``layout`` as the text of a layout file, one line per field and pairs inline (floats
    written exactly, so loading the text gives an equal layout); ``header`` lines become
    comments on top."""
    lines = [f"# {line}".rstrip() for line in header.splitlines()]
    data = layout_to_dict(layout)
    for key in ("name", "description", "robot_radius"):
        lines.append(f"{key} = {_toml_value(data[key])}")
    for table in ("arena", "start", "goal"):
        lines += ["", f"[{table}]"] + [f"{k} = {_toml_value(v)}" for k, v in data[table].items()]
    for array in ("obstacles", "walls"):
        for item in data.get(array, []):
            lines += ["", f"[[{array}]]"] + [f"{k} = {_toml_value(v)}" for k, v in item.items()]
    return "\n".join(lines) + "\n"


def _toml_value(value: Any) -> str:
    if isinstance(value, str):
        # A JSON string is a TOML basic string, but for DEL, which TOML wants escaped.
        return json.dumps(value, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(value, list):
        return f"[{', '.join(_toml_value(v) for v in value)}]"
    return repr(float(value))


def _check_keys(table: dict[str, Any], kind: str, source: str, where: str | None = None) -> None:
    prefix = f"{where or kind}." if (where or kind) else ""
    allowed = _SCHEMA[kind]
    for key in table:
        if key not in allowed:
            raise ValueError(
                f"{source}: unknown field {_show(prefix + key)} (allowed: {', '.join(allowed)})"
            )
    for key, required in allowed.items():
        if required and key not in table:
            raise ValueError(f"{source}: missing field '{prefix}{key}'")


def _table(value: Any, where: str, source: str) -> dict[str, Any]:
    if not isinstance(value, dict):
        name = f"field '{where}'" if where else "the document"
        raise ValueError(f"{source}: {name} must be a table, got {_show(value)}")
    return value


def _array(value: Any, where: str, source: str) -> list[Any]:
    if not isinstance(value, list):
        raise ValueError(
            f"{source}: field '{where}' must be an array of tables, got {_show(value)}"
        )
    return value


def _number(value: Any, where: str, source: str, positive: bool = False) -> float:
    number = _finite(value)
    if number is None:
        raise ValueError(f"{source}: field '{where}' must be a finite number, got {_show(value)}")
    if positive and number <= 0:
        raise ValueError(f"{source}: field '{where}' must be positive, got {_show(value)}")
    return number


def _finite(value: Any) -> float | None:
    """``value`` as a finite float, or None if it is not a finite real number (a bool is not)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    try:
        number = float(value)
    except OverflowError:  # an integer beyond the floats
        return None
    return number if math.isfinite(number) else None


def _show(value: Any, limit: int = 80) -> str:
    """``repr(value)``, cut to ``limit`` characters (a hostile file may hold huge values)."""
    text = repr(value)
    return text if len(text) <= limit else f"{text[: limit - 5]}...{text[-2:]}"


def _pair(value: Any, where: str, source: str, positive: bool = False) -> tuple[float, float]:
    if not isinstance(value, list | tuple) or len(value) != 2:
        raise ValueError(f"{source}: field '{where}' must be a pair [x, y], got {_show(value)}")
    return (
        _number(value[0], f"{where}[0]", source, positive),
        _number(value[1], f"{where}[1]", source, positive),
    )
