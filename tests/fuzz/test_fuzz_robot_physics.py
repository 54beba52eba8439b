"""Hostile ``[physics]`` tables in robot files: every value either loads within its bounds or
is a clear error naming the file and the field; none reaches pybullet unchecked.

Seeded random tables (numbers at and beyond the bounds, wrong types, unknown keys and action
sets, nested tables) are kept as a test, and the cases that once mattered are written out.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from bullet_maze import BulletMazeEnv, load_robot_spec
from bullet_maze.robots.spec import (
    ACTION_SET_NAMES,
    PHYSICS_KEYS,
    SOLVER_ITERATION_BOUNDS,
    TIME_STEP_BOUNDS,
)

HEAD = 'urdf = "{urdf}"\ndrive = "holonomic"\n'
DISC = Path(__file__).resolve().parents[2] / "assets" / "robots" / "disc.urdf"

VALUES: list[Any] = [
    0,
    1,
    5,
    100,
    101,
    -1,
    10**30,
    0.0,
    -0.0,
    1e-4,
    1 / 2000,
    1 / 240,
    1 / 60,
    1 / 30,
    0.034,
    1.0,
    math.inf,
    -math.inf,
    math.nan,
    True,
    False,
    "0.01",
    "",
    [0.01],
    {"a": 1},
]
"""What a hostile file puts in a ``[physics]`` field."""


def _toml(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, list):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return "{ " + ", ".join(f"{k} = {_toml(v)}" for k, v in value.items()) + " }"


def _valid(key: str, value: Any) -> bool:
    if key == "time_step":
        low, high = TIME_STEP_BOUNDS
        return (
            isinstance(value, int | float)
            and not isinstance(value, bool)
            and math.isfinite(value)
            and low <= value <= high
        )
    low_i, high_i = SOLVER_ITERATION_BOUNDS
    return isinstance(value, int) and not isinstance(value, bool) and low_i <= value <= high_i


def test_random_physics_tables_load_or_name_the_field(tmp_path: Path) -> None:
    rng = np.random.default_rng(20261202)
    path = tmp_path / "hostile.toml"
    tables = ["physics"] + [f"physics.{name}" for name in ACTION_SET_NAMES] + ["physics.walk"]
    keys = [*PHYSICS_KEYS, "substeps", "compass"]
    for _ in range(300):
        table = tables[rng.integers(len(tables))]
        chosen = {
            keys[i]: VALUES[rng.integers(len(VALUES))]
            for i in rng.choice(len(keys), size=rng.integers(1, 3), replace=False)
        }
        body = "".join(f"{key} = {_toml(value)}\n" for key, value in chosen.items())
        path.write_text(HEAD.format(urdf=DISC) + f"[{table}]\n" + body)
        valid = table != "physics.walk" and all(
            key in PHYSICS_KEYS and _valid(key, value) for key, value in chosen.items()
        )
        if table == "physics" and set(chosen) - set(PHYSICS_KEYS) == {"compass"}:
            valid = False  # a value that is not a table
        if valid:
            spec = load_robot_spec(path)
            where = table.partition(".")[2]
            for key, value in chosen.items():
                assert (where, key, value) in spec.physics
        else:
            with pytest.raises((ValueError, TypeError)) as caught:
                load_robot_spec(path)
            message = str(caught.value)
            assert "hostile.toml" in message
            assert any(name in message for name in (*chosen, "walk", "physics")), message


@pytest.mark.parametrize(
    ("table", "match"),
    [
        # A physics step of 0.1 s (what PhysicsParams allows) lets a robot at 2 m/s cross 20 cm,
        # most of a thin wall's contact margin, in one step: a robot file may not ask for it.
        ("[physics]\ntime_step = 0.1\n", r"'physics.time_step' must be in"),
        # 10**30 iterations would hang every physics step.
        ("[physics]\nsolver_iterations = 1000000000000000000000000000000\n", r"integer|in \[1"),
        # A table for an action set that does not exist is not silently ignored.
        ("[physics.Compass]\ntime_step = 0.01\n", r"\['Compass'\] at \[physics\]"),
    ],
)
def test_physics_cases_that_mattered(tmp_path: Path, table: str, match: str) -> None:
    path = tmp_path / "hostile.toml"
    path.write_text(HEAD.format(urdf=DISC) + table)
    with pytest.raises((ValueError, TypeError), match=match):
        load_robot_spec(path)


def test_a_valid_physics_table_reaches_pybullet(tmp_path: Path) -> None:
    path = tmp_path / "fine.toml"
    path.write_text(
        HEAD.format(urdf=DISC) + "[physics]\ntime_step = 0.002\n[physics.compass]\n"
        "solver_iterations = 3\n[footprint]\nradius = 'layout'\n"
    )
    env = BulletMazeEnv(maze="open", robot=str(path), mode="dynamic")
    try:
        assert (env.physics.time_step, env.physics.solver_iterations) == (0.002, 3)
        env.reset(seed=0)
        env.step(0)
    finally:
        env.close()
