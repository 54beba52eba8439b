"""Procedural layouts: four families of mazes, each drawn from a seed.

``generate_layout(family, seed, **params)`` returns a checked ``MazeLayout`` (validated, and the
goal reachable for the layout's robot radius); the same family, seed and parameters give the
same layout bit for bit (every draw comes from ``numpy.random.default_rng(seed)``). The same
layout is named by a spec string, ``"family:seed=S,key=value,..."``, which ``load_layout``,
``gymnasium.make("BulletMaze-v0", maze=...)``, experiment files and ``run.py --maze`` accept:

* ``rooms``: a grid of square rooms; the walls between them have doors placed at random along
  them, on a random spanning tree of the rooms (every room reachable) plus, with probability
  ``loops``, on the other walls. ``door`` may go down to a little more than the robot's diameter.
* ``forest``: ``count`` cylinders of radii drawn in ``[radius_min, radius_max]``, at least
  ``gap`` apart, between a start at the bottom middle and a goal at the top middle.
* ``serpentine``: ``corridors`` horizontal corridors joined alternately at the right and the
  left end, with ``stubs`` dead-end stubs per corridor at random places.
* ``maze``: a perfect maze (one path between any two cells) carved by recursive backtracking on
  a ``rows`` x ``cols`` grid of cells, its walls merged into boxes; start and goal at opposite
  corners.

Every family also takes ``robot_radius`` and ``goal_radius``. ``FAMILIES`` lists the parameters
with their defaults and bounds; a bad family, parameter or value is a ``ValueError`` (a
``TypeError`` for a wrong type) that names it and the bound.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from bullet_maze.layout_types import MazeLayout, Obstacle, Wall
from bullet_maze.params import MAX_ARENA_SIDE, MAX_SOLIDS, MIN_ROBOT_RADIUS, MIN_SOLID_SIZE
from bullet_maze.planning import CLEARANCE_TOLERANCE, grid_cell
from bullet_maze.validation import validate_layout

MAX_SEED = 2**63 - 1
"""Largest seed (seeds are integers in [0, 2**63 - 1])."""

MAX_PLACEMENT_TRIES = 200
"""Random positions tried for one tree of a forest before giving up."""


@dataclass(frozen=True)
class Param:
    """One parameter of a family: its default, inclusive bounds and meaning."""

    default: float
    low: float
    high: float
    doc: str
    integer: bool = False


_COMMON = {
    "robot_radius": Param(5.0, MIN_ROBOT_RADIUS, 100.0, "radius of the layout's disc robot"),
    "goal_radius": Param(15.0, MIN_SOLID_SIZE, 500.0, "radius of the goal circle"),
}


@dataclass(frozen=True)
class Family:
    """A layout family: its parameters and the function that draws one layout."""

    name: str
    doc: str
    params: dict[str, Param]
    draw: Callable[[np.random.Generator, dict[str, float], str], MazeLayout]
    draws: int = 1
    """Layouts drawn (from the same generator) until one is valid; 1 when valid by design."""


def generate_layout(family: str, seed: int = 0, **params: Any) -> MazeLayout:
    """A layout of ``family`` drawn from ``seed`` (see the module docstring and ``FAMILIES``)."""
    spec_family, values = _check(family, seed, params)
    seed = int(seed)
    spec = format_spec(family, seed, values)
    rng = np.random.default_rng(seed)
    error: ValueError | None = None
    for _ in range(spec_family.draws):
        layout = spec_family.draw(rng, values, spec)
        layout = replace(layout, name=spec, source=spec)
        try:
            validate_layout(layout)
        except ValueError as err:
            error = err
            continue
        return layout
    raise ValueError(
        f"{spec}: no valid layout in {spec_family.draws} draws (the last: {error}); change the "
        "parameters"
    )


def format_spec(family: str, seed: int, values: dict[str, float]) -> str:
    """The canonical spec of a layout: the family, the seed and every parameter that differs
    from its default, in the family's order (``"rooms:seed=3,door=30"``)."""
    params = FAMILIES[family].params
    items = [f"seed={seed}"] + [
        f"{key}={_format_number(values[key])}"
        for key, param in params.items()
        if values[key] != param.default
    ]
    return f"{family}:{','.join(items)}"


def is_generator_spec(text: str) -> bool:
    """Whether ``text`` has the form of a generator spec (``"word:..."``, no ``.toml``)."""
    head, sep, _ = text.partition(":")
    return bool(sep) and head.isidentifier() and not text.endswith(".toml")


def generate_from_spec(spec: str) -> MazeLayout:
    """The layout a spec string names: ``"family:seed=S,key=value,..."``; errors name the spec."""
    family, _, rest = spec.partition(":")
    params: dict[str, Any] = {}
    for item in rest.split(",") if rest.strip() else []:
        key, sep, raw = (part.strip() for part in item.partition("="))
        if not sep or not key:
            raise ValueError(f"maze spec {spec!r}: expected key=value, got {item.strip()!r}")
        if key in params:
            raise ValueError(f"maze spec {spec!r}: parameter {key!r} given twice")
        params[key] = _parse_number(raw, key, spec)
    seed = params.pop("seed", 0)
    try:
        return generate_layout(family, seed, **params)
    except (TypeError, ValueError) as err:
        raise ValueError(f"maze spec {spec!r}: {err}") from None


def _parse_number(raw: str, key: str, spec: str) -> int | float:
    if re.fullmatch(r"[+-]?\d{1,1000}", raw):  # (a spec has at most 1,000 characters)
        return int(raw)
    if re.fullmatch(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?", raw):
        value = float(raw)
        if math.isfinite(value):
            return value
    raise ValueError(f"maze spec {spec!r}: parameter {key!r} must be a finite number, got {raw!r}")


def _format_number(value: float) -> str:
    if float(value).is_integer() and abs(value) < 1e15:
        return str(int(value))
    return repr(float(value))


def _check(family: Any, seed: Any, params: dict[str, Any]) -> tuple[Family, dict[str, float]]:
    if not isinstance(family, str) or family not in FAMILIES:
        raise ValueError(f"unknown layout family {family!r}: choose one of {', '.join(FAMILIES)}")
    spec_family = FAMILIES[family]
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer):
        raise TypeError(f"{family}: seed must be an integer, got {seed!r}")
    if not 0 <= seed <= MAX_SEED:
        raise ValueError(f"{family}: seed must be in [0, 2**63 - 1], got {seed}")
    values: dict[str, float] = {}
    for key, value in params.items():
        if key not in spec_family.params:
            raise ValueError(
                f"{family}: unknown parameter {key!r} (parameters: "
                f"{', '.join(spec_family.params)}, and seed)"
            )
        param = spec_family.params[key]
        if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
            raise TypeError(f"{family}: parameter {key!r} must be a number, got {value!r}")
        if param.integer and not isinstance(value, int | np.integer):
            raise TypeError(f"{family}: parameter {key!r} must be an integer, got {value!r}")
        number = float(value) if math.isfinite(float(value)) else math.nan
        if not param.low <= number <= param.high:
            raise ValueError(
                f"{family}: parameter {key!r} = {value!r} is outside its bounds "
                f"[{param.low:g}, {param.high:g}]"
            )
        values[key] = int(number) if param.integer else number
    for key, param in spec_family.params.items():
        values.setdefault(key, int(param.default) if param.integer else param.default)
    return spec_family, values


def _passage(values: dict[str, float], arena: tuple[float, float]) -> float:
    """The narrowest gap the robot is sure to get through in this arena: its diameter, the
    planner's tolerance and two cells of the planning grid."""
    probe = MazeLayout("", arena, (0.0, 0.0), (0.0, 0.0), values["goal_radius"])
    radius = values["robot_radius"]
    return 2.0 * (radius + CLEARANCE_TOLERANCE + grid_cell(probe, radius))


def _arena(family: str, width: float, height: float, why: str) -> tuple[float, float]:
    if max(width, height) > MAX_ARENA_SIDE:
        raise ValueError(
            f"{family}: {why} make an arena of {width:g} x {height:g}, larger than "
            f"MAX_ARENA_SIDE {MAX_ARENA_SIDE:g} (bullet_maze.params)"
        )
    return width, height


def _at_least(family: str, key: str, value: float, bound: float, why: str) -> None:
    if value < bound:
        raise ValueError(
            f"{family}: parameter {key!r} = {value:g} must be at least {bound:.4g} ({why})"
        )


def _runs(blocked: list[bool]) -> list[tuple[int, int]]:
    """The maximal runs ``[first, last]`` of True in ``blocked``."""
    runs, first = [], None
    for index, flag in enumerate([*blocked, False]):
        if flag and first is None:
            first = index
        elif not flag and first is not None:
            runs.append((first, index - 1))
            first = None
    return runs


def _spans(total: float, gaps: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """The parts of ``[0, total]`` outside the (disjoint) open ``gaps``."""
    spans, at = [], 0.0
    for lo, hi in sorted(gaps):
        if lo > at:
            spans.append((at, lo))
        at = max(at, hi)
    if at < total:
        spans.append((at, total))
    return spans


def _wall_along(axis: int, line: float, lo: float, hi: float, thickness: float) -> Wall:
    """A wall of ``thickness`` centred on the line ``x = line`` (``axis`` 0, running along y
    from ``lo`` to ``hi``) or ``y = line`` (``axis`` 1, running along x)."""
    middle, length = (lo + hi) / 2.0, hi - lo
    if axis == 0:
        return Wall((float(line), float(middle)), (float(thickness), float(length)))
    return Wall((float(middle), float(line)), (float(length), float(thickness)))


def _draw_rooms(rng: np.random.Generator, v: dict[str, float], spec: str) -> MazeLayout:
    rows, cols, room, door, wall = int(v["rows"]), int(v["cols"]), v["room"], v["door"], v["wall"]
    if rows * cols < 2:
        raise ValueError("rooms: rows * cols must be at least 2 (start and goal rooms)")
    width, height = _arena("rooms", cols * room, rows * room, "cols * room and rows * room")
    passage = _passage(v, (width, height))
    _at_least("rooms", "door", door, passage, "the robot's diameter and two planning cells")
    if door > room - wall:
        raise ValueError(
            f"rooms: parameter 'door' = {door:g} does not fit in a room's side: it must be at "
            f"most room - wall = {room - wall:g}"
        )
    # A random spanning tree of the rooms (randomised depth-first search), then extra doors.
    doors = _spanning_tree(rows, cols, rng)
    adjacent = [frozenset(((r, c), (r, c + 1))) for r in range(rows) for c in range(cols - 1)]
    adjacent += [frozenset(((r, c), (r + 1, c))) for r in range(rows - 1) for c in range(cols)]
    for pair in adjacent:
        if pair not in doors and rng.random() < v["loops"]:
            doors.add(pair)
    walls = []
    # Vertical lines x = c * room between columns c - 1 and c; horizontal lines y = r * room.
    for axis, lines, cells in ((0, cols, rows), (1, rows, cols)):
        for k in range(1, lines):
            gaps = []
            for m in range(cells):
                a, b = ((m, k - 1), (m, k)) if axis == 0 else ((k - 1, m), (k, m))
                if frozenset((a, b)) in doors:
                    lo = m * room + wall / 2.0
                    offset = float(rng.uniform(0.0, room - wall - door))
                    gaps.append((lo + offset, lo + offset + door))
            total = height if axis == 0 else width
            walls += [_wall_along(axis, k * room, lo, hi, wall) for lo, hi in _spans(total, gaps)]
    return MazeLayout(
        name=spec,
        arena=(float(width), float(height)),
        start=(room / 2.0, room / 2.0),
        goal=(width - room / 2.0, height - room / 2.0),
        goal_radius=v["goal_radius"],
        robot_radius=v["robot_radius"],
        walls=tuple(walls),
        description=(
            f"{rows} x {cols} rooms of side {room:g} joined by doors {door:g} wide "
            f"(walls {wall:g} thick); start in the bottom-left room, goal in the top-right one"
        ),
    )


def _draw_forest(rng: np.random.Generator, v: dict[str, float], spec: str) -> MazeLayout:
    width, height = _arena("forest", v["width"], v["height"], "width and height")
    r_lo, r_hi, gap, count = v["radius_min"], v["radius_max"], v["gap"], int(v["count"])
    _at_least("forest", "radius_max", r_hi, r_lo, "radius_min")
    start = (width / 2.0, 0.1 * height)
    goal = (width / 2.0, 0.9 * height)
    start_room = v["robot_radius"] + 10.0  # the drawn start square (side 20) stays clear
    goal_room = v["goal_radius"] + v["robot_radius"]
    cell = 2.0 * r_hi + gap
    buckets: dict[tuple[int, int], list[int]] = {}
    trees: list[Obstacle] = []
    for index in range(count):
        for _ in range(MAX_PLACEMENT_TRIES):
            radius = float(rng.uniform(r_lo, r_hi))
            x = float(rng.uniform(radius, width - radius)) if width > 2 * radius else math.nan
            y = float(rng.uniform(radius, height - radius)) if height > 2 * radius else math.nan
            if not (
                math.dist((x, y), start) >= radius + start_room
                and math.dist((x, y), goal) >= radius + goal_room
            ):
                continue
            bx, by = int(x // cell), int(y // cell)
            near = (
                trees[j]
                for i in (bx - 1, bx, bx + 1)
                for k in (by - 1, by, by + 1)
                for j in buckets.get((i, k), ())
            )
            if all(math.dist((x, y), t.center) >= radius + t.radius + gap for t in near):
                buckets.setdefault((bx, by), []).append(len(trees))
                trees.append(Obstacle((x, y), radius))
                break
        else:
            raise ValueError(
                f"forest: could not place tree {index + 1} of {count} (radii {r_lo:g}-{r_hi:g}, "
                f"gap {gap:g}) in a {width:g} x {height:g} arena in {MAX_PLACEMENT_TRIES} tries: "
                "ask for fewer or smaller trees, a smaller gap or a larger arena"
            )
    return MazeLayout(
        name=spec,
        arena=(float(width), float(height)),
        start=start,
        goal=goal,
        goal_radius=v["goal_radius"],
        robot_radius=v["robot_radius"],
        obstacles=tuple(trees),
        description=(
            f"{count} trees of radius {r_lo:g}-{r_hi:g} at least {gap:g} apart in a "
            f"{width:g} x {height:g} arena; start bottom middle, goal top middle"
        ),
    )


def _draw_serpentine(rng: np.random.Generator, v: dict[str, float], spec: str) -> MazeLayout:
    n, corridor, wall = int(v["corridors"]), v["width"], v["wall"]
    opening, stubs = v["opening"], int(v["stubs"])
    width, height = _arena(
        "serpentine", v["length"], n * corridor + (n - 1) * wall, "length, corridors and width"
    )
    passage = _passage(v, (width, height))
    _at_least("serpentine", "width", corridor, passage, "the robot's diameter and two cells")
    _at_least("serpentine", "opening", opening, passage, "the robot's diameter and two cells")
    _at_least("serpentine", "length", width, 2.0 * opening + wall, "two openings and a wall")
    stub_length = min(v["stub_length"] * corridor, corridor - passage)
    # Stubs stand between the corridor's ends (kept free for turns, start and goal).
    margin = max(opening, corridor) + wall
    room = width - 2.0 * margin
    if stubs and stub_length >= MIN_SOLID_SIZE and room < stubs * (passage + wall):
        raise ValueError(
            f"serpentine: {stubs} stubs per corridor do not fit between the corridor's ends "
            f"({room:g} units long): use fewer stubs, a longer length or a smaller opening"
        )
    right = bool(rng.integers(2))  # whether the first wall is open at the right end
    walls = []
    for k in range(n - 1):
        y = (k + 1) * corridor + k * wall + wall / 2.0
        open_right = right == (k % 2 == 0)
        lo, hi = (0.0, width - opening) if open_right else (opening, width)
        walls.append(_wall_along(1, y, lo, hi, wall))
    if stubs and stub_length >= MIN_SOLID_SIZE:
        # One stub per slot, at least a passage plus a wall from the slot's edges' neighbours.
        slot, keep = room / stubs, (passage + wall) / 2.0
        for k in range(n):
            floor = k * (corridor + wall)
            for m in range(stubs):
                x = margin + slot * m + float(rng.uniform(keep, slot - keep))
                if rng.integers(2):
                    walls.append(_wall_along(0, x, floor, floor + stub_length, wall))
                else:
                    top = floor + corridor
                    walls.append(_wall_along(0, x, top - stub_length, top, wall))
    start_x = corridor / 2.0 if right else width - corridor / 2.0
    last_open_right = right == ((n - 2) % 2 == 0)
    goal_x = corridor / 2.0 if last_open_right else width - corridor / 2.0
    return MazeLayout(
        name=spec,
        arena=(float(width), float(height)),
        start=(start_x, corridor / 2.0),
        goal=(goal_x, height - corridor / 2.0),
        goal_radius=v["goal_radius"],
        robot_radius=v["robot_radius"],
        walls=tuple(walls),
        description=(
            f"{n} corridors {corridor:g} wide and {width:g} long, joined alternately at the "
            f"ends through openings {opening:g} wide, {stubs} dead-end stub(s) per corridor"
        ),
    )


def _draw_maze(rng: np.random.Generator, v: dict[str, float], spec: str) -> MazeLayout:
    rows, cols, cell, wall = int(v["rows"]), int(v["cols"]), v["cell"], v["wall"]
    width, height = _arena("maze", cols * cell, rows * cell, "cols * cell and rows * cell")
    passage = _passage(v, (width, height))
    _at_least("maze", "cell", cell, passage + wall, "the wall, the robot's diameter, two cells")
    # Recursive backtracking: a spanning tree of the cells, each tree edge a carved passage.
    carved = _spanning_tree(rows, cols, rng)
    walls = []
    for axis, lines, cells, total in ((0, cols, rows, height), (1, rows, cols, width)):
        for k in range(1, lines):
            blocked = [
                frozenset(((m, k - 1), (m, k)) if axis == 0 else ((k - 1, m), (k, m))) not in carved
                for m in range(cells)
            ]
            for first, last in _runs(blocked):
                lo = max(0.0, first * cell - wall / 2.0)
                hi = min(total, (last + 1) * cell + wall / 2.0)
                walls.append(_wall_along(axis, k * cell, lo, hi, wall))
    return MazeLayout(
        name=spec,
        arena=(float(width), float(height)),
        start=(cell / 2.0, cell / 2.0),
        goal=(width - cell / 2.0, height - cell / 2.0),
        goal_radius=v["goal_radius"],
        robot_radius=v["robot_radius"],
        walls=tuple(walls),
        description=(
            f"A perfect maze of {rows} x {cols} cells of side {cell:g} (walls {wall:g} thick), "
            "carved by recursive backtracking; start bottom left, goal top right"
        ),
    )


def _side(default: float, doc: str) -> Param:
    return Param(default, MIN_SOLID_SIZE, MAX_ARENA_SIDE, doc)


FAMILIES: dict[str, Family] = {
    "rooms": Family(
        "rooms",
        "square rooms joined by doors on a random spanning tree (plus loops)",
        {
            "rows": Param(3, 1, 40, "rooms from bottom to top", integer=True),
            "cols": Param(3, 1, 40, "rooms from left to right", integer=True),
            "room": _side(100.0, "side of a room (wall centre to wall centre)"),
            "door": _side(30.0, "width of a door (at least the robot's diameter + 2 cells)"),
            "wall": Param(6.0, MIN_SOLID_SIZE, 100.0, "thickness of the walls"),
            "loops": Param(0.25, 0.0, 1.0, "chance of a door in each wall off the tree"),
            **_COMMON,
        },
        _draw_rooms,
    ),
    "forest": Family(
        "forest",
        "cylinders at random, at least a gap apart",
        {
            "count": Param(40, 0, MAX_SOLIDS, "number of trees", integer=True),
            "width": _side(300.0, "arena width"),
            "height": _side(300.0, "arena height"),
            "radius_min": Param(4.0, MIN_SOLID_SIZE, 500.0, "least tree radius"),
            "radius_max": Param(12.0, MIN_SOLID_SIZE, 500.0, "largest tree radius"),
            "gap": Param(12.0, 0.0, 1000.0, "least distance between two trees' surfaces"),
            **_COMMON,
        },
        _draw_forest,
        draws=50,
    ),
    "serpentine": Family(
        "serpentine",
        "corridors joined alternately at their ends, with dead-end stubs",
        {
            "corridors": Param(4, 2, 100, "number of corridors", integer=True),
            "width": _side(60.0, "width of a corridor"),
            "length": _side(300.0, "length of a corridor (the arena's width)"),
            "wall": Param(6.0, MIN_SOLID_SIZE, 100.0, "thickness of the walls"),
            "opening": _side(50.0, "width of the opening at a corridor's end"),
            "stubs": Param(1, 0, 50, "dead-end stubs per corridor", integer=True),
            "stub_length": Param(0.6, 0.0, 1.0, "stub length, a fraction of the width"),
            **_COMMON,
        },
        _draw_serpentine,
    ),
    "maze": Family(
        "maze",
        "a perfect maze carved by recursive backtracking",
        {
            "rows": Param(6, 2, 100, "cells from bottom to top", integer=True),
            "cols": Param(6, 2, 100, "cells from left to right", integer=True),
            "cell": _side(50.0, "side of a cell (wall centre to wall centre)"),
            "wall": Param(4.0, MIN_SOLID_SIZE, 100.0, "thickness of the walls"),
            **_COMMON,
        },
        _draw_maze,
    ),
}
"""The layout families by name."""


def _spanning_tree(
    rows: int, cols: int, rng: np.random.Generator
) -> set[frozenset[tuple[int, int]]]:
    """A random spanning tree of a ``rows`` x ``cols`` grid of cells by recursive backtracking
    with an explicit stack (a random walk that moves into unvisited neighbours and backs up at
    dead ends), as the set of its edges (pairs of adjacent cells); one draw per move."""
    edges: set[frozenset[tuple[int, int]]] = set()
    seen, stack = {(0, 0)}, [(0, 0)]
    while stack:
        r, c = stack[-1]
        around = [
            (r + dr, c + dc)
            for dr, dc in ((1, 0), (-1, 0), (0, 1), (0, -1))
            if 0 <= r + dr < rows and 0 <= c + dc < cols and (r + dr, c + dc) not in seen
        ]
        if not around:
            stack.pop()
            continue
        nxt = around[int(rng.integers(len(around)))]
        edges.add(frozenset(((r, c), nxt)))
        seen.add(nxt)
        stack.append(nxt)
    return edges
