"""Gymnasium-Robotics / D4RL maze maps imported as layouts: the four standard maps as shipped,
their walls exactly where the map's wall cells are, and bad maps refused by cell."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from bullet_maze import available_layouts, layout_from_maze_map, load_layout, shortest_path
from bullet_maze.__main__ import main as layout_cli
from bullet_maze.maze_maps import STANDARD_MAPS

OPTIMUM = {"umaze": 46, "open": 24, "medium": 94, "large": 150}
"""Least steps of the shipped standard maps (the README's table)."""


def test_the_shipped_standard_maps_are_the_importers_output() -> None:
    assert available_layouts("pointmaze") == [f"pointmaze/{n}" for n in sorted(STANDARD_MAPS)]
    for name, maze_map in STANDARD_MAPS.items():
        shipped = load_layout(f"pointmaze/{name}")
        imported = layout_from_maze_map(
            maze_map, name=f"pointmaze/{name}", description=shipped.description
        )
        assert shipped == imported
        assert shortest_path(shipped).steps == OPTIMUM[name]


@pytest.mark.parametrize("name", sorted(STANDARD_MAPS))
def test_walls_cover_exactly_the_wall_cells(name: str) -> None:
    maze_map = STANDARD_MAPS[name]
    layout = layout_from_maze_map(maze_map, cell_size=40.0)
    rows, cols = len(maze_map), len(maze_map[0])
    assert layout.arena == ((cols - 2) * 40.0, (rows - 2) * 40.0)  # the wall ring dropped
    for i in range(1, rows - 1):
        for j in range(1, cols - 1):
            x, y = (j - 1 + 0.5) * 40.0, (rows - 2 - i + 0.5) * 40.0
            inside = any(
                abs(x - w.center[0]) < w.size[0] / 2 and abs(y - w.center[1]) < w.size[1] / 2
                for w in layout.walls
            )
            assert inside == (maze_map[i][j] == 1), (i, j)
    assert layout.robot_radius == 4.0  # PointMaze's 0.1 of a cell
    assert layout.goal_radius == pytest.approx(18.0)  # and its 0.45


def test_goal_and_start_cells() -> None:
    umaze = load_layout("pointmaze/umaze")
    assert umaze.goal == (25.0, 125.0)  # D4RL's goal: row 1, column 1 (top left)
    assert umaze.start == (25.0, 25.0)  # the far end of the U
    large = load_layout("pointmaze/large")
    assert large.goal == (425.0, 25.0)  # row 7, column 9
    marked = [[1, 1, 1, 1], [1, "r", 0, 1], [1, 0, "g", 1], [1, 1, 1, 1]]
    layout = layout_from_maze_map(marked, cell_size=50.0)
    assert (layout.start, layout.goal) == ((25.0, 75.0), (75.0, 25.0))
    either = [[1, 1, 1, 1], [1, "c", 0, 1], [1, 0, "g", 1], [1, 1, 1, 1]]
    assert layout_from_maze_map(either).start == (25.0, 75.0)
    chosen = layout_from_maze_map(STANDARD_MAPS["open"], start_cell=(3, 5), goal_cell=(1, 1))
    assert (chosen.start, chosen.goal) == ((225.0, 25.0), (25.0, 125.0))
    open_border = [[0, 0, 0], [0, 1, "g"]]  # no ring of walls: the whole map is the arena
    assert layout_from_maze_map(open_border, cell_size=50.0).arena == (150.0, 100.0)


def test_import_map_command_writes_a_loadable_file(tmp_path: Path) -> None:
    source = tmp_path / "map.json"
    source.write_text(json.dumps([[1, 1, 1, 1, 1], [1, "r", 0, "g", 1], [1, 1, 1, 1, 1]]))
    out = tmp_path / "map.toml"
    assert layout_cli(["import-map", str(source), "--cell-size", "60", "--out", str(out)]) == 0
    layout = load_layout(out)
    assert layout.arena == (180.0, 60.0)
    assert layout.name == "map"
    assert np.allclose(layout.goal, (150.0, 30.0))


def test_import_map_command_takes_the_start_and_goal_cells(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    source = tmp_path / "plain.json"
    source.write_text(json.dumps([[1, 1, 1, 1], [1, 0, 0, 1], [1, 0, 0, 1], [1, 1, 1, 1]]))
    out = tmp_path / "plain.toml"
    with pytest.raises(SystemExit) as stop:  # no goal marked: the message names the option
        layout_cli(["import-map", str(source), "--out", str(out)])
    assert stop.value.code == 2
    assert "--goal-cell ROW,COLUMN" in capsys.readouterr().err
    cells = ["--goal-cell", "1,1", "--start-cell", "2,2"]
    assert layout_cli(["import-map", str(source), *cells, "--out", str(out)]) == 0
    layout = load_layout(out)
    assert (layout.start, layout.goal) == ((75.0, 25.0), (25.0, 75.0))
    assert "--start-cell 2,2 --goal-cell 1,1" in out.read_text().splitlines()[0]
    for bad in ("1", "1,x", "1,2,3", ""):
        with pytest.raises(SystemExit) as stop:
            layout_cli(["import-map", str(source), f"--goal-cell={bad}", "--out", str(out)])
        assert stop.value.code == 2
        assert f"expected ROW,COLUMN (two integers, e.g. 3,4), got {bad!r}" in (
            capsys.readouterr().err
        )
    with pytest.raises(SystemExit):
        layout_cli(["import-map", str(source), "--goal-cell=-2,1", "--out", str(out)])
    assert "goal_cell (-2, 1) is outside the map" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("maze_map", "kwargs", "match"),
    [
        ([], {}, r"non-empty list of rows"),
        ("1010", {}, r"non-empty list of rows"),
        ([[1, 0], [1]], {}, r"equally long"),
        ([[1, 0], 5], {}, r"every row of a maze map must be a list"),
        ([[1, 2]], {}, r"cell \(0, 1\) is 2"),
        ([[1, True]], {}, r"cell \(0, 1\) is True"),
        ([[1, 0.0]], {}, r"cell \(0, 1\) is 0\.0"),
        ([[1, "G"]], {}, r"cell \(0, 1\) is 'G'"),
        ([[1, None]], {}, r"cell \(0, 1\) is None"),
        ([[1, 1]], {}, r"no free cell"),
        ([[0] * 201] * 200, {}, r"200 x 201 cells, more than the 40,000"),
        ([[0, 0, 0]], {}, r"no 'g' \(or single 'c'\) cell: give goal_cell"),
        ([[0, "g", "g"]], {}, r"marks 2 cells 'g' for the goal"),
        ([["r", 0, "g", "r"]], {}, r"marks 2 cells 'r' for the start"),
        ([[0, "g"]], {"cell_size": 0}, r"cell_size must be a positive number"),
        ([[0, "g"]], {"cell_size": float("nan")}, r"cell_size must be a positive number"),
        ([[0, "g"]], {"cell_size": float("inf")}, r"cell_size must be finite"),
        ([[0, "g"]], {"cell_size": True}, r"cell_size must be a positive number"),
        ([[0, "g"]], {"cell_size": 5000.0}, r"'arena\.size\[0\]' = 10000"),
        ([[0, "g"]], {"goal_cell": (0, 5)}, r"goal_cell \(0, 5\) is outside the map"),
        ([[0, 1, "g"]], {"start_cell": (0, 1)}, r"start_cell \(0, 1\) is a wall cell"),
        ([[0, "g"]], {"start_cell": (0, True)}, r"start_cell must be \(row, column\)"),
        ([[0, 1, "g"]], {}, r"no free cell connects to the goal cell \(0, 2\)"),
        ([[0, 1, "g"]], {"start_cell": (0, 0)}, r"cannot be reached"),
        ([["g", 0]], {"robot_radius": 30.0}, r"overlaps a wall"),
        (np.array([[1.0, 0.0]]), {}, r"2-D of integers or strings, got shape \(1, 2\) of float64"),
        (np.zeros((2, 2, 2), int), {}, r"got shape \(2, 2, 2\) of int64"),
        (np.array([[True, False]]), {}, r"got shape \(1, 2\) of bool"),
        (np.array([[1, 2]]), {}, r"cell \(0, 1\) is 2"),
        (np.array([["1", "G"]]), {}, r"cell \(0, 1\) is 'G'"),
        ([[np.int64(0), np.int64(7)]], {}, r"cell \(0, 1\) is np.int64\(7\)"),
    ],
)
def test_bad_maps_are_refused_by_name(maze_map: object, kwargs: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match) as err:
        layout_from_maze_map(maze_map, source="my map", **kwargs)  # type: ignore[arg-type]
    assert "my map" in str(err.value)


def test_a_map_as_a_numpy_array_or_with_numpy_rows_is_the_same_layout() -> None:
    """A map loaded with numpy (``np.loadtxt``, ``np.array`` of a map with letters, whose cells
    become strings) gives the layout of the same map as lists, and the caller's rows are left
    as they were."""
    rows = [[1, 1, 1, 1, 1], [1, "r", 0, "g", 1], [1, 0, 1, 0, 1], [1, 1, 1, 1, 1]]
    expected = layout_from_maze_map(rows)
    assert layout_from_maze_map(np.array(rows)) == expected  # dtype <U21: "1", "r", ...
    numbers = np.array([[1, 1, 1, 1, 1], [1, 0, 0, 0, 1], [1, 0, 1, 0, 1], [1, 1, 1, 1, 1]])
    as_lists = layout_from_maze_map(numbers.tolist(), goal_cell=(1, 3), start_cell=(1, 1))
    assert layout_from_maze_map(numbers, goal_cell=(1, 3), start_cell=(1, 1)) == as_lists
    assert as_lists == expected
    mixed = [list(np.int64(v) if v in (0, 1) else v for v in row) for row in rows]
    copy = [list(row) for row in mixed]
    assert layout_from_maze_map(mixed) == expected
    assert mixed == copy
    assert type(mixed[0][0]) is np.int64
    assert layout_from_maze_map([np.array(row) for row in numbers], goal_cell=(1, 3)) == (
        layout_from_maze_map(numbers.tolist(), goal_cell=(1, 3))
    )
