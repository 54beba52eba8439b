"""Layouts: the shipped files load, and every kind of bad file is a ValueError naming the field."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import pytest

from bullet_maze import available_layouts, load_layout
from bullet_maze.layout import parse_layout

from .conftest import SMALL_MAZE


def test_shipped_layouts_load_with_the_papers_arena() -> None:
    assert {"paper", "paper_narrow", "open", "corridors"} <= set(available_layouts())
    for name in available_layouts():
        layout = load_layout(name)
        assert layout.name == name
        assert layout.arena == (300.0, 300.0)


def test_paper_layout_blocks_the_straight_line_from_start_to_goal() -> None:
    layout = load_layout("paper")
    sx, sy = layout.start
    gx, gy = layout.goal
    assert sx == gx == 150.0
    assert sy < 50.0
    assert gy > 250.0
    blocked = [o for o in layout.obstacles if abs(o.center[0] - sx) < o.radius + 5.0]
    assert blocked, "an obstacle must stand on the straight line"


def test_narrow_layout_matches_the_guide() -> None:
    layout = load_layout("paper_narrow")
    assert layout.start == (150.0, 30.0)
    assert layout.goal == (150.0, 270.0)
    assert layout.goal_radius == 15.0
    assert layout.robot_radius == 5.0
    left = min(o.center[0] - o.radius for o in layout.obstacles)
    right = max(o.center[0] + o.radius for o in layout.obstacles)
    assert math.isclose(left, 40.0)
    assert math.isclose(300.0 - right, 40.0)


def test_load_by_path_and_by_layout(write_maze: Callable[[str], Path]) -> None:
    path = write_maze(SMALL_MAZE)
    layout = load_layout(path)
    assert layout.arena == (100.0, 100.0)
    assert layout.robot_radius == 2.0
    assert load_layout(str(path)) == layout
    assert load_layout(layout) is layout


@pytest.mark.parametrize(
    ("old", "new", "field"),
    [
        ("radius = 5.0", "radius = 5.0\ncolour = 1", "goal.colour"),
        ('name = "small"', 'name = "small"\nspeed = 3', "speed"),
        ("[goal]\nposition = [80.0, 80.0]", "[goal]", "goal.position"),
        ("size = [100.0, 100.0]", "size = [100.0, -100.0]", "arena.size[1]"),
        ("robot_radius = 2.0", "robot_radius = -2.0", "robot_radius"),
        ("radius = 5.0", "radius = 0.0", "goal.radius"),
        ("position = [20.0, 20.0]", "position = [120.0, 20.0]", "start.position"),
        ("position = [80.0, 80.0]", "position = [80.0, 100.0]", "goal.position"),
        ("position = [20.0, 20.0]", 'position = [20.0, "a"]', "start.position[1]"),
        ("position = [20.0, 20.0]", "position = [20.0]", "start.position"),
        ("position = [20.0, 20.0]", "position = [20.0, nan]", "start.position[1]"),
    ],
)
def test_bad_field_names_file_and_field(
    write_maze: Callable[[str], Path], old: str, new: str, field: str
) -> None:
    path = write_maze(SMALL_MAZE.replace(old, new, 1))
    with pytest.raises(ValueError, match=rf"{path}.*'{_escape(field)}'") as err:
        load_layout(path)
    assert str(path) in str(err.value)


def _escape(text: str) -> str:
    return text.replace("[", r"\[").replace("]", r"\]").replace(".", r"\.")


def test_obstacle_radius_must_be_positive(write_maze: Callable[[str], Path]) -> None:
    path = write_maze(SMALL_MAZE + "[[obstacles]]\ncenter = [50.0, 50.0]\nradius = -3.0\n")
    with pytest.raises(ValueError, match=r"'obstacles\[0\]\.radius' must be positive"):
        load_layout(path)


def test_wall_size_must_be_positive(write_maze: Callable[[str], Path]) -> None:
    path = write_maze(SMALL_MAZE + "[[walls]]\ncenter = [50.0, 50.0]\nsize = [10.0, -1.0]\n")
    with pytest.raises(ValueError, match=r"'walls\[0\]\.size\[1\]' must be positive"):
        load_layout(path)


def test_start_inside_an_obstacle(write_maze: Callable[[str], Path]) -> None:
    path = write_maze(SMALL_MAZE + "[[obstacles]]\ncenter = [22.0, 20.0]\nradius = 5.0\n")
    with pytest.raises(ValueError, match=r"'start\.position'.*overlaps"):
        load_layout(path)


def test_goal_inside_an_obstacle(write_maze: Callable[[str], Path]) -> None:
    path = write_maze(SMALL_MAZE + "[[obstacles]]\ncenter = [80.0, 80.0]\nradius = 10.0\n")
    with pytest.raises(ValueError, match=r"'goal\.position'.*inside obstacles\[0\]"):
        load_layout(path)


def test_goal_inside_a_wall(write_maze: Callable[[str], Path]) -> None:
    path = write_maze(SMALL_MAZE + "[[walls]]\ncenter = [80.0, 80.0]\nsize = [4.0, 4.0]\n")
    with pytest.raises(ValueError, match=r"'goal\.position'.*inside walls\[0\]"):
        load_layout(path)


def test_goal_unreachable_for_the_robot_radius(write_maze: Callable[[str], Path]) -> None:
    # A wall across the arena with a 4-unit gap: too narrow for a robot of radius 2.
    wall = "[[walls]]\ncenter = [48.0, 50.0]\nsize = [96.0, 2.0]\n"
    path = write_maze(SMALL_MAZE + wall)
    with pytest.raises(ValueError, match=r"'goal\.position'.*cannot be reached.*radius 2\b"):
        load_layout(path)
    wider = SMALL_MAZE.replace("robot_radius = 2.0", "robot_radius = 1.0")
    assert load_layout(write_maze(wider + wall)).walls  # a radius-1 robot fits through


def test_invalid_toml_names_the_file(write_maze: Callable[[str], Path]) -> None:
    path = write_maze("arena = [")
    with pytest.raises(ValueError, match=rf"{path}: not valid TOML"):
        load_layout(path)


def test_unknown_name_lists_the_choices() -> None:
    with pytest.raises(ValueError, match=r"unknown maze 'nowhere'.*paper"):
        load_layout("nowhere")


def test_missing_file_is_file_not_found(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match=r"missing\.toml"):
        load_layout(tmp_path / "missing.toml")


def test_parse_layout_names_missing_fields() -> None:
    with pytest.raises(ValueError, match=r"<dict>: missing field 'arena'"):
        parse_layout({"start": {}, "goal": {}})
