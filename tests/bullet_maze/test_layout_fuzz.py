"""Hostile layout files, specs and arguments, each with the outcome it must have: a ValueError
(or TypeError, FileNotFoundError) naming the file and what is wrong, or a valid layout; never a
traceback from deep inside, a crash, a hang or a silently wrong layout."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from bullet_maze import load_layout

from .conftest import SMALL_MAZE

OK = "ok"

EDITS = [
    # (old text of SMALL_MAZE, new text, expected: OK or a regex the error matches)
    # wrong types
    ("size = [100.0, 100.0]", 'size = "100"', r"'arena\.size' must be a pair"),
    ("size = [100.0, 100.0]", 'size = [100.0, "a"]', r"'arena\.size\[1\]' must be a finite number"),
    ("size = [100.0, 100.0]", "size = [100.0, 100.0, 5.0]", r"'arena\.size' must be a pair"),
    ("size = [100.0, 100.0]", "size = [[100.0], 100.0]", r"'arena\.size\[0\]' must be a finite"),
    ("size = [100.0, 100.0]", "size = {x = 1, y = 2}", r"'arena\.size' must be a pair"),
    ("radius = 5.0", 'radius = "5"', r"'goal\.radius' must be a finite number, got '5'"),
    ("radius = 5.0", "radius = 1979-05-27", r"'goal\.radius' must be a finite number"),
    ('name = "small"', "name = 3", r"field 'name' must be a string"),
    ('name = "small"', 'name = "small"\ndescription = ["x"]', r"'description' must be a string"),
    ("[arena]\nsize = [100.0, 100.0]", "arena = 3", r"'arena' must be a table, got 3"),
    ("[goal]", "[goal.sub]", r"unknown field 'goal\.sub'|missing field 'goal\.position'"),
    # bool for a number
    ("robot_radius = 2.0", "robot_radius = true", r"'robot_radius' must be a finite number"),
    ("radius = 5.0", "radius = false", r"'goal\.radius' must be a finite number, got False"),
    ("position = [20.0, 20.0]", "position = [true, 20.0]", r"'start\.position\[0\]'"),
    # NaN and infinities
    ("size = [100.0, 100.0]", "size = [nan, 100.0]", r"'arena\.size\[0\]' must be a finite"),
    ("radius = 5.0", "radius = inf", r"'goal\.radius' must be a finite number, got inf"),
    ("position = [80.0, 80.0]", "position = [-inf, 80.0]", r"'goal\.position\[0\]'"),
    ("robot_radius = 2.0", "robot_radius = -nan", r"'robot_radius' must be a finite number"),
    # huge
    ("size = [100.0, 100.0]", "size = [1e308, 100.0]", r"'arena\.size\[0\]' = 1e\+308 is outside"),
    ("size = [100.0, 100.0]", "size = [1" + "0" * 30 + ", 100]", r"'arena\.size\[0\]' = 1e\+30"),
    ("radius = 5.0", "radius = 1" + "0" * 400, r"'goal\.radius' must be a finite number"),
    ("robot_radius = 2.0", "robot_radius = 1e9", r"overlaps a wall"),
    ("radius = 5.0", "radius = 1e9", r"lies inside the goal circle"),
    ("position = [20.0, 20.0]", "position = [20.0, 20.0]\nsize = 1e9", r"'start\.size' = 1e\+09"),
    # negative, zero, tiny
    ("robot_radius = 2.0", "robot_radius = -5", r"'robot_radius' must be positive"),
    ("robot_radius = 2.0", "robot_radius = 1e-9", r"robot radius 1e-09 is below the least"),
    ("size = [100.0, 100.0]", "size = [-100.0, 100.0]", r"'arena\.size\[0\]' must be positive"),
    ("size = [100.0, 100.0]", "size = [100.0, 0]", r"'arena\.size\[1\]' must be positive"),
    ("radius = 5.0", "radius = -1", r"'goal\.radius' must be positive"),
    ("position = [20.0, 20.0]", "position = [20.0, 20.0]\nsize = -2", r"'start\.size' must be"),
    ("position = [20.0, 20.0]", "position = [-20.0, 20.0]", r"'start\.position'.*outside"),
    # empty
    ('name = "small"', 'name = ""', OK),
    ("[goal]\nposition = [80.0, 80.0]\nradius = 5.0", "", r"missing field 'goal'"),
    ("[arena]\nsize = [100.0, 100.0]", "[arena]", r"missing field 'arena\.size'"),
    ('name = "small"', 'name = "small"\nobstacles = []\nwalls = []', OK),
    ('name = "small"', 'name = "small"\nobstacles = [1, 2]', r"'obstacles\[0\]' must be a table"),
    ('name = "small"', 'name = "small"\nwalls = {}', r"'walls' must be an array of tables"),
    # unknown keys, also deep inside
    ('name = "small"', 'name = "small"\nspeed = 3', r"unknown field 'speed'"),
    ("radius = 5.0", "radius = 5.0\nradius = 6.0", r"not valid TOML"),  # duplicate key
    # the start on the arena's edge, in the goal circle, in a solid
    ("position = [20.0, 20.0]", "position = [0.0, 20.0]", r"'start\.position'.*outside the arena"),
    ("position = [20.0, 20.0]", "position = [78.0, 78.0]", r"inside the goal circle"),
    ("position = [20.0, 20.0]", "position = [1.0, 20.0]", r"overlaps a wall or an obstacle"),
]

APPENDED = [
    # solids appended to SMALL_MAZE, and the outcome
    ("[[obstacles]]\ncenter = [50.0, 50.0]\nradius = 8.0\n" * 2, OK),  # two identical: overlap
    (
        "[[obstacles]]\ncenter = [50.0, 50.0]\nradius = 8.0\n"
        "[[obstacles]]\ncenter = [55.0, 50.0]\nradius = 8.0\n"
        "[[walls]]\ncenter = [50.0, 50.0]\nsize = [30.0, 2.0]\n",
        OK,
    ),
    ("[[obstacles]]\ncenter = [99.0, 50.0]\nradius = 3.0\n", r"obstacles\[0\].*extends outside"),
    ("[[obstacles]]\ncenter = [500.0, 50.0]\nradius = 3.0\n", r"obstacles\[0\].*outside"),
    ("[[walls]]\ncenter = [50.0, 50.0]\nsize = [120.0, 2.0]\n", r"walls\[0\].*\[-10, 110\]"),
    ("[[walls]]\ncenter = [50.0, 50.0]\nsize = [100.0, 2.0]\n", r"'goal\.position'.*cannot be"),
    ("[[walls]]\ncenter = [50.0, 50.0]\nsize = [100.0, 100.0]\n", r"inside walls\[0\]"),
    ("[[walls]]\ncenter = [50.0, 50.0]\nsize = [100.0, 10.0]\n", r"cannot be reached"),
    ("[[walls]]\ncenter = [23.0, 20.0]\nsize = [4.0, 4.0]\n", r"'start\.position'.*overlaps"),
    ("[[walls]]\n", r"missing field 'walls\[0\]\.center'"),
    (
        # a closed box around the goal
        "[[walls]]\ncenter = [80.0, 70.0]\nsize = [22.0, 2.0]\n"
        "[[walls]]\ncenter = [80.0, 90.0]\nsize = [22.0, 2.0]\n"
        "[[walls]]\ncenter = [70.0, 80.0]\nsize = [2.0, 22.0]\n"
        "[[walls]]\ncenter = [90.0, 80.0]\nsize = [2.0, 22.0]\n",
        r"cannot be reached",
    ),
    ("[[obstacles]]\ncenter = [80.0, 80.0]\nradius = 1.0\n", r"'goal\.position'.*inside obstacles"),
    ("[[obstacles]]\ncenter = [50.0, 50.0]\nradius = 0.001\n", r"below the least solid size"),
    (
        "[[obstacles]]\ncenter = [50.0, 50.0]\nradius = 3.0\ncolour = 1\n",
        r"'obstacles\[0\]\.colour",
    ),
]


def _short(value: object) -> str:
    text = repr(value)
    return text if len(text) <= 40 else f"{text[:37]}..."


@pytest.mark.parametrize(("old", "new", "expected"), EDITS, ids=_short)
def test_edited_layout_files(
    write_maze: Callable[[str], Path], old: str, new: str, expected: str
) -> None:
    assert old in SMALL_MAZE
    _check(write_maze(SMALL_MAZE.replace(old, new, 1)), expected)


@pytest.mark.parametrize(("extra", "expected"), APPENDED, ids=_short)
def test_layout_files_with_solids(
    write_maze: Callable[[str], Path], extra: str, expected: str
) -> None:
    _check(write_maze(SMALL_MAZE + extra), expected)


def _check(path: Path, expected: str) -> None:
    if expected == OK:
        assert load_layout(path).arena == (100.0, 100.0)
        return
    with pytest.raises(ValueError, match=expected) as err:
        load_layout(path)
    assert str(path) in str(err.value)
    assert len(str(err.value)) < 600  # huge values are cut, not echoed


@pytest.mark.parametrize(
    ("content", "expected"),
    [
        (b"", r"missing field 'arena'"),
        (b"\xff\xfe\x00garbage\x80", r"not a UTF-8 text file"),
        (b"arena = [", r"not valid TOML"),
        (b"a = " + b"[" * 5000 + b"]" * 5000, r"not valid TOML: nested too deeply"),
        (b"a = " + b"{b = " * 3000 + b"1" + b"}" * 3000, r"not valid TOML"),
        (SMALL_MAZE.replace('"small"', "'" + "x" * 100_000 + "'").encode(), OK),
        (SMALL_MAZE.replace("5.0\n", '"' + "9" * 100_000 + '"\n').encode(), r"got '9999"),
    ],
    ids=_short,
)
def test_hostile_bytes(tmp_path: Path, content: bytes, expected: str) -> None:
    path = tmp_path / "hostile.toml"
    path.write_bytes(content)
    if expected == OK:
        assert len(load_layout(path).name) == 100_000
        return
    with pytest.raises(ValueError, match=expected) as err:
        load_layout(path)
    assert str(path) in str(err.value)
    assert len(str(err.value)) < 600


@pytest.mark.parametrize(
    ("maze", "error", "match"),
    [
        (None, TypeError, r"maze must be a layout name"),
        (3, TypeError, r"got int"),
        (b"paper", TypeError, r"got bytes"),
        (["paper"], TypeError, r"got list"),
        ("", ValueError, r"unknown maze ''"),
        ("paper\x00", ValueError, r"unknown maze"),
        ("pointmaze/../paper", ValueError, r"unknown maze"),
        ("nowhere/umaze", ValueError, r"unknown maze 'nowhere/umaze'"),
        ("x" * 10_000, ValueError, r"maze 'xxxx.*longer than 1,000 characters"),
        ("x" * 10_000 + ".toml", ValueError, r"longer than 1,000 characters"),
        ("missing.toml", FileNotFoundError, r"maze file not found: missing\.toml"),
        (Path("."), FileNotFoundError, r"maze file not found"),
        ("rooms:seed=0,door=1e-300", ValueError, r"'door' = 1e-300 is outside .*\[0\.01, 2000\]"),
        ("rooms:seed=0,door=10.5", ValueError, r"'door' = 10\.5 must be at least 11\.02"),
        ("rooms:seed=" + "9" * 30, ValueError, r"seed must be in \[0, 2\*\*63 - 1\], got 9{30}$"),
        ("rooms:seed=" + "9" * 300, ValueError, r"seed must be in \[0, 2\*\*63 - 1\], got 9{300}$"),
        ("maze:rows=" + "9" * 30, ValueError, r"'rows' = 9{30} is outside its bounds \[2, 100\]"),
        ("rooms:seed=" + "9" * 19, ValueError, r"seed must be in \[0, 2\*\*63 - 1\]"),
        ("maze:rows=" + "9" * 19, ValueError, r"'rows' = 9999999999999999999 is outside"),
        ("forest:count=-1", ValueError, r"'count' = -1 is outside its bounds \[0, 4000\]"),
        ("forest:gap=inf", ValueError, r"'gap' must be a finite number"),
        ("forest:count=1e3", TypeError.__mro__[1], r"'count' must be an integer"),
        ("forest: count = 10 ", ValueError, OK),
        ("serpentine:corridors=200", ValueError, r"'corridors' = 200 is outside"),
    ],
    ids=_short,
)
def test_hostile_maze_arguments(maze: object, error: type[Exception], match: str) -> None:
    if match == OK:
        assert load_layout(maze).solid_count == 10  # type: ignore[arg-type]
        return
    with pytest.raises(error, match=match) as err:
        load_layout(maze)  # type: ignore[arg-type]
    assert len(str(err.value)) < 900
