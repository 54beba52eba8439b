"""Gymnasium-Robotics / D4RL maze maps imported as layouts.

A ``maze_map`` is a list of rows, top row first: ``1`` a wall cell, ``0`` a free cell, ``"g"``
the goal, ``"r"`` the reset (start) cell, ``"c"`` a cell that may be either (Gymnasium-Robotics'
``maps.py``); a 2-D numpy array of integers, or of the strings ``np.array`` makes of a map with
letters, is read as the same list. Cell (row i, column j) becomes the square of side
``cell_size`` whose centre is x = (j + 1/2) cell_size, y = (rows - i - 1/2) cell_size, as
Gymnasium-Robotics places it (row 0 at the top). A ring of wall cells around the whole map is
left out: the arena's own walls take its place. Wall cells are merged into as few boxes as
row-by-row runs stacked into rectangles allow.

Gymnasium-Robotics draws a goal and a start among the free cells at every reset; a layout has
one of each: the ``"g"`` cell (else the one ``"c"`` cell, else ``goal_cell``), and the ``"r"``
cell (else a ``"c"`` cell other than the goal, else ``start_cell``, else the free cell farthest
from the goal in cell moves, the first in reading order among equals). The robot's radius and
the goal radius default to PointMaze's proportions: a ball of radius 0.1 and a success distance
of 0.45 in cells of 1.

``STANDARD_MAPS`` holds PointMaze's U, open, medium and large maps with the goal cell of D4RL's
``maze2d`` versions marked; ``assets/mazes/pointmaze/`` ships them imported at the default cell
size (``python -m bullet_maze import-map --standard NAME``).
"""

from __future__ import annotations

from collections import deque
from collections.abc import Sequence
from typing import Any

import numpy as np

from bullet_maze.layout_types import MazeLayout, Wall
from bullet_maze.validation import validate_layout

DEFAULT_CELL_SIZE = 50.0
"""Side of a map cell in maze units: with PointMaze's proportions the robot's radius is then 5,
the default disc's, and the goal radius 22.5."""

MAX_MAP_CELLS = 40_000
"""Most cells of a map (e.g. 200 x 200)."""

ROBOT_RADIUS_PER_CELL = 0.1
"""PointMaze's ball radius (0.1 m) in cells of its default 1 m."""

GOAL_RADIUS_PER_CELL = 0.45
"""PointMaze's success distance (0.45 m) in cells of its default 1 m."""

_W, _G, _R, _C = 1, "g", "r", "c"

STANDARD_MAPS: dict[str, list[list[Any]]] = {
    "umaze": [
        [1, 1, 1, 1, 1],
        [1, _G, 0, 0, 1],
        [1, 1, 1, 0, 1],
        [1, 0, 0, 0, 1],
        [1, 1, 1, 1, 1],
    ],
    "open": [
        [1, 1, 1, 1, 1, 1, 1],
        [1, 0, 0, 0, 0, 0, 1],
        [1, 0, 0, _G, 0, 0, 1],
        [1, 0, 0, 0, 0, 0, 1],
        [1, 1, 1, 1, 1, 1, 1],
    ],
    "medium": [
        [1, 1, 1, 1, 1, 1, 1, 1],
        [1, 0, 0, 1, 1, 0, 0, 1],
        [1, 0, 0, 1, 0, 0, 0, 1],
        [1, 1, 0, 0, 0, 1, 1, 1],
        [1, 0, 0, 1, 0, 0, 0, 1],
        [1, 0, 1, 0, 0, 1, 0, 1],
        [1, 0, 0, 0, 1, 0, _G, 1],
        [1, 1, 1, 1, 1, 1, 1, 1],
    ],
    "large": [
        [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1],
        [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1],
        [1, 0, 1, 1, 0, 1, 0, 1, 0, 1, 0, 1],
        [1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1],
        [1, 0, 1, 1, 1, 1, 0, 1, 1, 1, 0, 1],
        [1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 0, 1],
        [1, 1, 0, 1, 0, 1, 0, 1, 0, 1, 1, 1],
        [1, 0, 0, 1, 0, 0, 0, 1, 0, _G, 0, 1],
        [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1],
    ],
}
"""PointMaze's ``U_MAZE``, ``OPEN``, ``MEDIUM_MAZE`` and ``LARGE_MAZE`` (Gymnasium-Robotics
``envs/maze/maps.py``), with the goal cell of D4RL's ``maze2d-umaze``, ``-open``, ``-medium``
and ``-large`` (``d4rl/pointmaze/maze_model.py``) marked ``"g"``."""


def layout_from_maze_map(
    maze_map: Sequence[Sequence[Any]],
    cell_size: float = DEFAULT_CELL_SIZE,
    *,
    name: str = "maze_map",
    description: str = "",
    robot_radius: float | None = None,
    goal_radius: float | None = None,
    start_cell: tuple[int, int] | None = None,
    goal_cell: tuple[int, int] | None = None,
    source: str = "<maze_map>",
) -> MazeLayout:
    """The layout of a Gymnasium-Robotics ``maze_map`` (see the module docstring), checked by
    ``validate_layout``. ``start_cell`` and ``goal_cell`` are (row, column) of the map as given;
    errors name ``source`` and the cell."""
    grid = _cells(maze_map, source)
    cell = _positive(cell_size, "cell_size", source)
    radius = cell * ROBOT_RADIUS_PER_CELL if robot_radius is None else robot_radius
    goal_r = cell * GOAL_RADIUS_PER_CELL if goal_radius is None else goal_radius
    radius = _positive(radius, "robot_radius", source)
    goal_r = _positive(goal_r, "goal_radius", source)
    rows, cols = len(grid), len(grid[0])
    ring = (
        rows > 2
        and cols > 2
        and all(grid[i][j] == _W for i in (0, rows - 1) for j in range(cols))
        and all(grid[i][j] == _W for i in range(rows) for j in (0, cols - 1))
    )
    first = 1 if ring else 0
    inner = [row[first : cols - first] for row in grid[first : rows - first]]
    n_rows, n_cols = len(inner), len(inner[0])

    def centre(i: int, j: int) -> tuple[float, float]:
        return ((j - first + 0.5) * cell, (rows - first - i - 0.5) * cell)

    goal = _pick(grid, goal_cell, (_G,), (_C,), "goal", source)
    if goal is None:
        raise ValueError(
            f"{source}: the map has no 'g' (or single 'c') cell: give goal_cell=(row, column) "
            "(--goal-cell ROW,COLUMN on the command line)"
        )
    start = _pick(grid, start_cell, (_R,), (_C,), "start", source, exclude=goal)
    if start is None:
        start = _farthest(grid, goal)
        if start == goal:
            raise ValueError(
                f"{source}: no free cell connects to the goal cell {goal}: give "
                "start_cell=(row, column) (--start-cell ROW,COLUMN on the command line)"
            )
    walls = [
        Wall(
            (((j0 + j1 + 1) / 2) * cell, (n_rows - (i0 + i1 + 1) / 2) * cell),
            ((j1 - j0 + 1) * cell, (i1 - i0 + 1) * cell),
        )
        for i0, i1, j0, j1 in _rectangles([[c == _W for c in row] for row in inner])
    ]
    layout = MazeLayout(
        name=name,
        arena=(n_cols * cell, n_rows * cell),
        start=centre(*start),
        goal=centre(*goal),
        goal_radius=goal_r,
        robot_radius=radius,
        start_size=0.4 * cell,
        walls=tuple(walls),
        description=description,
        source=source,
    )
    validate_layout(layout)
    return layout


def _cells(maze_map: Any, source: str) -> list[list[Any]]:
    maze_map = _from_array(maze_map, source)
    if not isinstance(maze_map, list | tuple) or not maze_map:
        raise ValueError(f"{source}: a maze map must be a non-empty list of rows")
    maze_map = [_from_array(row, source) for row in maze_map]
    if not all(isinstance(row, list | tuple) for row in maze_map):
        raise ValueError(f"{source}: every row of a maze map must be a list")
    cols = len(maze_map[0])
    if cols == 0 or any(len(row) != cols for row in maze_map):
        raise ValueError(f"{source}: the rows of a maze map must be non-empty and equally long")
    if len(maze_map) * cols > MAX_MAP_CELLS:
        raise ValueError(
            f"{source}: {len(maze_map)} x {cols} cells, more than the {MAX_MAP_CELLS:,} a map "
            "may have"
        )
    for i, row in enumerate(maze_map):
        for j, value in enumerate(row):
            known = (type(value) is int and value in (0, 1)) or (
                isinstance(value, str) and value in (_G, _R, _C)
            )
            if not known and isinstance(value, np.integer):  # (a row of numpy ints)
                known = bool(value in (0, 1))
            if not known:
                raise ValueError(
                    f"{source}: cell ({i}, {j}) is {value!r}: expected 1 (wall), 0 (free), "
                    "'g' (goal), 'r' (reset) or 'c' (either)"
                )
    if all(value == _W for row in maze_map for value in row):
        raise ValueError(f"{source}: the map has no free cell")
    return [[int(v) if isinstance(v, np.integer) else v for v in row] for row in maze_map]


def _from_array(value: Any, source: str) -> Any:
    """A numpy array of a map (2-D) or a row (1-D) as lists: integers as ints, and the strings
    ``np.array`` makes of a map with letters (``"0"``, ``"1"``, ``"g"``) as the map's cells.
    Anything else is returned as it is, for :func:`_cells` to judge."""
    if not isinstance(value, np.ndarray):
        return value
    if value.ndim not in (1, 2) or value.dtype.kind not in "iuUO":
        raise ValueError(
            f"{source}: a maze map given as an array must be 2-D of integers or strings, got "
            f"shape {value.shape} of {value.dtype}"
        )
    cells = value.tolist()
    if value.dtype.kind == "U":
        digits = {"0": 0, "1": 1}
        if value.ndim == 1:
            return [digits.get(cell, cell) for cell in cells]
        return [[digits.get(cell, cell) for cell in row] for row in cells]
    return cells


def _positive(value: Any, name: str, source: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not value > 0:
        raise ValueError(f"{source}: {name} must be a positive number, got {value!r}")
    if value == float("inf"):
        raise ValueError(f"{source}: {name} must be finite, got {value!r}")
    return float(value)


def _pick(
    grid: list[list[Any]],
    given: tuple[int, int] | None,
    marks: tuple[str, ...],
    shared: tuple[str, ...],
    what: str,
    source: str,
    exclude: tuple[int, int] | None = None,
) -> tuple[int, int] | None:
    """The cell chosen for ``what``: ``given``, else the one cell marked ``marks``, else the one
    ``shared`` cell (other than ``exclude``); None if there is none."""
    if given is not None:
        if (
            not isinstance(given, tuple | list)
            or len(given) != 2
            or not all(isinstance(k, int) and not isinstance(k, bool) for k in given)
        ):
            raise ValueError(f"{source}: {what}_cell must be (row, column), got {given!r}")
        i, j = given
        if not (0 <= i < len(grid) and 0 <= j < len(grid[0])):
            raise ValueError(f"{source}: {what}_cell {tuple(given)} is outside the map")
        if grid[i][j] == _W:
            raise ValueError(f"{source}: {what}_cell {tuple(given)} is a wall cell")
        return (i, j)
    for kinds in (marks, shared):
        found = [
            (i, j)
            for i, row in enumerate(grid)
            for j, value in enumerate(row)
            if value in kinds and (i, j) != exclude
        ]
        if len(found) == 1:
            return found[0]
        if len(found) > 1:
            raise ValueError(
                f"{source}: the map marks {len(found)} cells {' or '.join(map(repr, kinds))} "
                f"for the {what} (a layout has one): give {what}_cell=(row, column)"
            )
    return None


def _farthest(grid: list[list[Any]], goal: tuple[int, int]) -> tuple[int, int]:
    """The free cell farthest from ``goal`` in 4-neighbour moves (first in reading order)."""
    distance = {goal: 0}
    queue = deque([goal])
    while queue:
        i, j = queue.popleft()
        for a, b in ((i + 1, j), (i - 1, j), (i, j + 1), (i, j - 1)):
            if (
                0 <= a < len(grid)
                and 0 <= b < len(grid[0])
                and grid[a][b] != _W
                and (a, b) not in distance
            ):
                distance[(a, b)] = distance[(i, j)] + 1
                queue.append((a, b))
    return min(distance, key=lambda cell: (-distance[cell], cell))


def _rectangles(blocked: list[list[bool]]) -> list[tuple[int, int, int, int]]:
    """Cover the True cells with rectangles ``(first row, last row, first col, last col)``:
    each row's runs, stacked with the same run in the rows below."""
    rows = len(blocked)
    used = [[False] * len(row) for row in blocked]
    found = []
    for i in range(rows):
        j, cols = 0, len(blocked[i])
        while j < cols:
            if not blocked[i][j] or used[i][j]:
                j += 1
                continue
            j1 = j
            while j1 + 1 < cols and blocked[i][j1 + 1] and not used[i][j1 + 1]:
                j1 += 1
            i1 = i
            while i1 + 1 < rows and all(
                blocked[i1 + 1][k] and not used[i1 + 1][k] for k in range(j, j1 + 1)
            ):
                i1 += 1
            for a in range(i, i1 + 1):
                for k in range(j, j1 + 1):
                    used[a][k] = True
            found.append((i, i1, j, j1))
            j = j1 + 1
    return found
