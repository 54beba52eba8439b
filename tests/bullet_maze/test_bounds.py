"""Every size that could exhaust memory or time has a bound, and breaking it is a ValueError that
names where the value came from, the value and the bound."""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Callable
from pathlib import Path

import gymnasium as gym
import pytest

from bullet_maze import load_layout, shortest_path, validate_layout
from bullet_maze.layout_types import MazeLayout, Obstacle, Wall
from bullet_maze.params import (
    MAX_LAYOUT_FILE_BYTES,
    MAX_PLANNER_NODES,
    MAX_SOLIDS,
    PhysicsParams,
    TaskParams,
)
from bullet_maze.planning import grid_cell
from bullet_maze.rendering import TopDownCamera

from .conftest import SMALL_MAZE

OPEN = MazeLayout("open", (300.0, 300.0), (150.0, 30.0), (150.0, 270.0), 15.0, source="open")


def _layout_error(layout: MazeLayout, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        validate_layout(layout)


@pytest.mark.parametrize(
    ("old", "new", "match"),
    [
        (
            "size = [100.0, 100.0]",
            "size = [2000.5, 100.0]",
            r"'arena\.size\[0\]' = 2000\.5.*2000\]",
        ),
        ("size = [100.0, 100.0]", "size = [1e300, 1e300]", r"'arena\.size\[0\]' = 1e\+300"),
        ("robot_radius = 2.0", "robot_radius = 0.05", r"robot radius 0\.05 is below.*0\.1"),
        ("radius = 5.0", "radius = 0.1", r"'goal\.radius' = 0\.1 is below the least goal radius"),
        ("position = [20.0, 20.0]", "position = [20.0, 20.0]\nsize = 101.0", r"'start\.size'"),
    ],
)
def test_file_bounds_name_the_file_field_and_bound(
    write_maze: Callable[[str], Path], old: str, new: str, match: str
) -> None:
    path = write_maze(SMALL_MAZE.replace(old, new, 1))
    with pytest.raises(ValueError, match=match) as err:
        load_layout(path)
    assert str(path) in str(err.value)


def test_radii_must_be_resolvable_in_large_arenas(write_maze: Callable[[str], Path]) -> None:
    text = SMALL_MAZE.replace("[100.0, 100.0]", "[2000.0, 2000.0]").replace(
        "[80.0, 80.0]", "[1800.0, 1800.0]"
    )
    # The grid's coarsest cell in a 2,000 x 2,000 arena is sqrt(4e6 / 400,000) = 3.16.
    with pytest.raises(ValueError, match=r"robot radius 2 is below the least radius 3\.16"):
        load_layout(write_maze(text))
    text = text.replace("robot_radius = 2.0", "robot_radius = 4.0")
    with pytest.raises(
        ValueError, match=r"'goal\.radius' = 3 is below the least goal radius 3\.16"
    ):
        load_layout(write_maze(text.replace("radius = 5.0", "radius = 3.0")))
    assert load_layout(write_maze(text)).arena == (2000.0, 2000.0)


def test_too_many_solids_is_refused_before_anything_is_built(
    write_maze: Callable[[str], Path],
) -> None:
    walls = "".join(
        f"[[walls]]\ncenter = [{10 + (i % 80)}.5, {30 + i // 80}.5]\nsize = [0.5, 0.5]\n"
        for i in range(MAX_SOLIDS + 1)
    )
    path = write_maze(SMALL_MAZE + walls)
    with pytest.raises(
        ValueError, match=rf"{MAX_SOLIDS + 1:,} solids, more than the {MAX_SOLIDS:,}"
    ):
        load_layout(path)
    many = dataclasses.replace(OPEN, walls=(Wall((100.0, 100.0), (1.0, 1.0)),) * (MAX_SOLIDS + 1))
    _layout_error(many, r"4,001 solids")


def test_solids_may_not_be_thinner_than_a_millimetre() -> None:
    _layout_error(
        dataclasses.replace(OPEN, obstacles=(Obstacle((100.0, 100.0), 0.001),)),
        r"'obstacles\[0\]\.radius' = 0\.001 is below the least solid size 0\.01",
    )
    _layout_error(
        dataclasses.replace(OPEN, walls=(Wall((100.0, 100.0), (5.0, 0.0)),)),
        r"'walls\[0\]\.size\[1\]' = 0 is below",
    )


def test_a_file_larger_than_the_bound_is_not_read(write_maze: Callable[[str], Path]) -> None:
    path = write_maze(SMALL_MAZE + "#" * MAX_LAYOUT_FILE_BYTES)
    with pytest.raises(ValueError, match=r"bytes, more than the 4,000,000 a maze file may have"):
        load_layout(path)


def test_the_planning_grid_is_bounded_whatever_the_arena() -> None:
    layout = load_layout("forest:seed=0,count=200,width=2000,height=2000")
    cell = grid_cell(layout, layout.robot_radius)
    nodes = (math.floor(2000 / cell) + 1) ** 2
    assert nodes <= MAX_PLANNER_NODES * 1.01
    limit = shortest_path(layout)
    assert limit.steps >= math.ceil((1800 - 200 - 15) / 5)
    # A lattice of more than MAX_PLANNER_NODES points is not searched: None, said so.
    assert shortest_path(layout, step_size=2.0).lattice_steps is None


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"render_width": 4096}, r"render_width = 4096 is larger than 2048 pixels"),
        ({"render_height": 100_000}, r"render_height = 100000 is larger than 2048"),
        ({"render_width": 0}, r"render_width = 0"),
        ({"step_size": 1e9}, r"step_size must be at most 100 maze units"),
        ({"noise_variance": 1e6}, r"noise_variance must be at most 100"),
        ({"substeps": 10**8}, r"substeps must be at most 10,000"),
        ({"max_turn_substeps": 10**6}, r"max_turn_substeps must be at most 10,000"),
        ({"max_drive_substeps": 10**6}, r"max_drive_substeps must be at most 10,000"),
        ({"solver_iterations": 5000}, r"solver_iterations must be at most 1,000"),
        ({"time_step": 1e-9}, r"time_step must be in \[0\.0001, 0\.1\] seconds"),
        ({"robot_radius": 0.05}, r"robot radius 0\.05 is below the least radius 0\.474"),
    ],
)
def test_env_arguments_have_bounds(
    make_env: Callable[..., gym.Env], kwargs: dict[str, object], match: str
) -> None:
    with pytest.raises(ValueError, match=match):
        make_env(**kwargs)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"render_width": True}, r"render_width = True: must be an integer number of pixels"),
        ({"render_width": 64.0}, r"render_width = 64\.0: must be an integer"),
        ({"step_size": True}, r"step_size must be a number, got True"),
        ({"time_step": True}, r"time_step must be a number, got True"),
    ],
)
def test_env_arguments_of_the_wrong_type_are_type_errors(
    make_env: Callable[..., gym.Env], kwargs: dict[str, object], match: str
) -> None:
    with pytest.raises(TypeError, match=match):
        make_env(**kwargs)


def test_the_bounds_are_the_dataclasses_own() -> None:
    with pytest.raises(ValueError, match="step_size must be at most"):
        TaskParams(step_size=101.0)
    with pytest.raises(ValueError, match="substeps must be at most"):
        PhysicsParams(substeps=10_001)
    assert TaskParams(step_size=100.0).step_size == 100.0
    with pytest.raises(ValueError, match=re.escape("render_width = 2049")):
        TopDownCamera((300.0, 300.0), 2049, 10)


@pytest.mark.parametrize(
    ("change", "match"),
    [
        ({"obstacles": (Obstacle((310.0, 100.0), 5.0),)}, r"obstacles\[0\].*outside the arena"),
        ({"obstacles": (Obstacle((2.0, 100.0), 5.0),)}, r"spans \[-3, 7\] x \[95, 105\]"),
        ({"walls": (Wall((150.0, -1.0), (20.0, 4.0)),)}, r"walls\[0\].*extends outside"),
        ({"walls": (Wall((150.0, 150.0), (400.0, 4.0)),)}, r"walls\[0\].*\[-50, 350\]"),
        ({"start": (150.0, 260.0)}, r"'start\.position' = \(150\.0, 260\.0\) lies inside the goal"),
        ({"goal_radius": 250.0}, r"inside the goal circle"),
        ({"start": (math.nan, 30.0)}, r"'start\.position' must hold finite numbers"),
        ({"goal_radius": True}, r"'goal\.radius' must hold finite numbers"),
        ({"arena": (300.0,)}, r"'arena\.size' must be a pair"),
    ],
)
def test_a_layout_made_in_python_is_checked_too(change: dict[str, object], match: str) -> None:
    layout = dataclasses.replace(OPEN, **change)  # type: ignore[arg-type]
    _layout_error(layout, match)
    with pytest.raises(ValueError, match=match):
        load_layout(layout)


def test_the_planner_refuses_a_robot_its_grid_cannot_resolve() -> None:
    # The grid's cell in a 300 x 300 arena is at least 0.474: two free nodes a diagonal apart
    # could straddle a thin wall for a robot of radius 0.2.
    layout = load_layout("paper")
    with pytest.raises(ValueError, match=r"radius 0\.2 is too small for the planning grid"):
        shortest_path(layout, robot_radius=0.2)
    assert shortest_path(layout, robot_radius=0.4).steps > 0
