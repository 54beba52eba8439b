"""Fuzzing experiment files as an attacker would: every case's outcome is asserted.

Three kinds of cases, all seeded: every key of a valid file given every value of the wrong
kind (each must be refused, naming the file and the key); random edits of the parsed document
(each is refused naming the file, or accepted and then round-trips exactly); random damage to
the bytes of a shipped file (refused naming the file, or accepted). Nothing else may happen:
no other exception, no hang, no silent acceptance of a wrong type.
"""

from __future__ import annotations

import copy
import dataclasses
import datetime
import typing
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from agent import TreeConfig
from experiments.config import (
    EXPERIMENT_DIR,
    ConfigError,
    dumps,
    load_config,
    parse_config,
    same_experiment,
)

VALID: dict[str, Any] = {
    "experiment": {
        "name": "fuzz",
        "description": "fuzzed",
        "seed": 3,
        "runs": 2,
        "episodes": 10,
        "baseline": "eps",
        "smoothing_window": 5,
        "final_window": 5,
        "convergence_tolerance": 0.1,
        "time_budget_s": 10.0,
    },
    "env": {
        "id": "BulletMaze-v0",
        "maze": "paper",
        "robot": "disc",
        "mode": "kinematic",
        "max_episode_steps": 100,
        "params": {
            "step_size": 5.0,
            "noise_variance": 0.3,
            "revert_on_collision": True,
            "contact_release": True,
        },
    },
    "agent": {"alpha": 0.3, "gamma": 0.99, "split_min_samples": 50, "hold_exploration": True},
    "strategy": [
        {"name": "eps", "exploration": "epsilon-greedy", "exploration_params": {"epsilon": 0.1}},
        {
            "name": "tabu",
            "exploration": "adaptive+tabu",
            "exploration_params": {"c_n": 0.001, "deviation_explores": True, "variant": "literal"},
            "config": {"max_leaves": 100},
        },
        {"name": "grid", "agent": "grid", "resolution": [4, 5], "exploration": "greedy"},
        {
            "name": "general",
            "preset": "general",
            "config": {"split_min_samples": 80},
            "exploration_params": {"c_h": 0.02},
        },
        {"name": "tile", "agent": "tile", "agent_params": {"tilings": 4, "alpha": 0.4}},
        {"name": "aq", "agent": "adaptive-q", "agent_params": {"r_max": 0.5, "max_depth": 6}},
    ],
}
"""A file that uses every kind of value: each leaf below is fuzzed."""

NUMBER_HOSTILE = [True, False, "1", "0.5", float("inf"), float("-inf"), float("nan"), [], {}, None]
INTEGER_HOSTILE = [*NUMBER_HOSTILE, 1.5, 10**30, -(10**30), datetime.date(2020, 1, 1)]
STRING_HOSTILE = [True, 1, 0.5, [], {}, ["a"], "x" * 200_000]
BOOL_HOSTILE = ["false", "true", 0, 1, 0.0, [], "yes"]


def _leaves(table: Any, path: tuple[Any, ...] = ()) -> list[tuple[tuple[Any, ...], Any]]:
    if isinstance(table, dict):
        return [leaf for key, value in table.items() for leaf in _leaves(value, (*path, key))]
    if isinstance(table, list) and table and isinstance(table[0], dict):
        return [leaf for i, value in enumerate(table) for leaf in _leaves(value, (*path, i))]
    return [(path, table)]


def _hostile_for(value: Any) -> list[Any]:
    if isinstance(value, bool):
        return BOOL_HOSTILE
    if isinstance(value, int):
        return INTEGER_HOSTILE
    if isinstance(value, float):
        return NUMBER_HOSTILE
    if isinstance(value, str):
        return STRING_HOSTILE
    if isinstance(value, list):
        return [[0, 5], [True, 5], ["4", 5], 0, -4, [], [10**7, 10**7], "4x5"]
    raise AssertionError(value)


def _with(data: dict[str, Any], path: tuple[Any, ...], value: Any) -> dict[str, Any]:
    edited = copy.deepcopy(data)
    table: Any = edited
    for key in path[:-1]:
        table = table[key]
    table[path[-1]] = value
    return edited


def _label(path: tuple[Any, ...]) -> str:
    return str(path[-1])


CASES = [
    (path, hostile)
    for path, value in _leaves(VALID)
    for hostile in _hostile_for(value)
    # a few values are of a valid kind for these keys: the description may be long text,
    # a strategy's string fields accept any name the agent knows (checked in other tests)
    if not (path[-1] == "description" and isinstance(hostile, str))
]


def test_the_valid_file_is_valid():
    config = parse_config(copy.deepcopy(VALID), source="fuzz.toml")
    assert [s.name for s in config.strategies] == ["eps", "tabu", "grid", "general", "tile", "aq"]


@pytest.mark.parametrize(("path", "hostile"), CASES, ids=[f"{p}={h!r:.30}" for p, h in CASES])
def test_every_key_refuses_every_wrong_value(path: tuple[Any, ...], hostile: Any):
    with pytest.raises(ConfigError) as error:
        parse_config(_with(VALID, path, hostile), source="fuzz.toml")
    message = str(error.value)
    assert message.startswith("fuzz.toml: ")
    assert _label(path) in message or str(path[-2]) in message


TREE_HINTS = typing.get_type_hints(TreeConfig)
FIELD_CASES = [
    (field.name, hostile)
    for field in dataclasses.fields(TreeConfig)
    for hostile in (
        BOOL_HOSTILE
        if TREE_HINTS[field.name] is bool
        else STRING_HOSTILE[:-1]
        if field.type in ("str", "ErrorBuffer", "RangeNormalization", "SplitPointRule")
        else [v for v in INTEGER_HOSTILE if v is not None]
        if "int" in str(field.type)
        else NUMBER_HOSTILE[:-1]
    )
]


@pytest.mark.parametrize(
    ("key", "hostile"), FIELD_CASES, ids=[f"{k}={h!r:.20}" for k, h in FIELD_CASES]
)
def test_every_agent_field_refuses_wrong_kinds(key: str, hostile: Any):
    """Every TreeConfig field, in [agent] and in a strategy's config."""
    for where, data in (
        ("[agent]", _with(VALID, ("agent", key), hostile)),
        ("[strategy.1] config", _with(VALID, ("strategy", 1, "config", key), hostile)),
    ):
        with pytest.raises(ConfigError, match=rf"fuzz\.toml: .*{key}") as error:
            parse_config(data, source="fuzz.toml")
        assert where.split()[0] in str(error.value)


HOSTILE_VALUES = [
    *NUMBER_HOSTILE,
    *INTEGER_HOSTILE[-4:],
    *STRING_HOSTILE,
    *BOOL_HOSTILE,
    {"nested": {"deeper": [1, {"x": float("nan")}]}},
    [[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]],
    "os:system",
    "../../../etc/passwd",
    "\x00",
    -1,
    0,
    10**6,
]


def _random_edit(data: dict[str, Any], rng: np.random.Generator) -> dict[str, Any]:
    edited = copy.deepcopy(data)
    leaves = _leaves(edited)
    path, _ = leaves[int(rng.integers(len(leaves)))]
    table: Any = edited
    for key in path[:-1]:
        table = table[key]
    choice = int(rng.integers(4))
    if choice == 0:
        table[path[-1]] = HOSTILE_VALUES[int(rng.integers(len(HOSTILE_VALUES)))]
    elif choice == 1:
        del table[path[-1]]
    elif choice == 2:
        table[f"{path[-1]}_typo"] = table[path[-1]]
    else:
        sections = list(edited)
        section = sections[int(rng.integers(len(sections)))]
        edited[section] = HOSTILE_VALUES[int(rng.integers(len(HOSTILE_VALUES)))]
    return edited


def test_random_edits_are_refused_by_name_or_round_trip(tmp_path: Path):
    rng = np.random.default_rng(12)
    refusals: list[str] = []
    accepted = 0
    for _ in range(400):
        data = _random_edit(VALID, rng)
        if rng.random() < 0.3:
            data = _random_edit(data, rng)
        try:
            config = parse_config(data, source="fuzz.toml")
        except ConfigError as error:
            refusals.append(str(error))
            continue
        path = tmp_path / "again.toml"
        path.write_text(dumps(config))
        again = load_config(path)
        assert same_experiment(config, again) == []
        assert again.strategies == config.strategies
        accepted += 1
    assert all(message.startswith("fuzz.toml: ") for message in refusals)
    assert len(refusals) > 200
    assert accepted > 10


@pytest.mark.parametrize("name", ["paper_fig4", "quick"])
def test_damaged_bytes_are_refused_by_name_or_parse(tmp_path: Path, name: str):
    original = (EXPERIMENT_DIR / f"{name}.toml").read_bytes()
    rng = np.random.default_rng(5)
    path = tmp_path / "damaged.toml"
    refusals: list[str] = []
    for _ in range(150):
        data = bytearray(original)
        kind = int(rng.integers(4))
        position = int(rng.integers(len(data)))
        if kind == 0:
            data = data[:position]
        elif kind == 1:
            data[position] = int(rng.integers(256))
        elif kind == 2:
            data[position:position] = bytes(rng.choice(list(b'[]{}"=\n\\\xff0'), 20))
        else:
            data[position:position] = b"[" * 4000
        path.write_bytes(bytes(data))
        try:
            load_config(path)
        except ConfigError as error:
            refusals.append(str(error))
    assert all(str(path) in message for message in refusals)
    assert len(refusals) > 75


def test_an_oversized_file_is_refused_before_parsing(tmp_path: Path):
    path = tmp_path / "huge.toml"
    path.write_text("# " + "x" * (2 << 20) + "\n")
    with pytest.raises(ConfigError, match=r"huge\.toml: .* bytes, at most"):
        load_config(path)


@pytest.mark.parametrize(
    "env_id",
    ["CartPole-v1", "MountainCar-v0", "Acrobot-v1", "Pendulum-v1", "BulletMaze-open-v0"],
)
def test_builtin_and_project_ids_are_accepted(env_id: str):
    data = _with(VALID, ("env",), {"id": env_id})
    config = parse_config(data, source="fuzz.toml")
    assert config.env.id == env_id
    assert config.env.is_maze == env_id.startswith("BulletMaze")


def test_a_per_layout_id_keeps_its_own_maze():
    config = parse_config(_with(VALID, ("env",), {"id": "BulletMaze-open-v0"}), source="f.toml")
    assert config.env.maze == "open"


@pytest.mark.parametrize(
    ("env", "named"),
    [
        ({"id": "CartPole-v1", "maze": "paper"}, "[env] maze: only applies to the maze ids"),
        ({"id": "gymnasium.envs.classic_control:CartPoleEnv"}, "is an import path"),
        ({"id": "CartPole-v1", "params": {"warp": 1}}, "CartPole-v1 takes no such argument"),
        ({"id": "CartPole-v1", "params": {"sutton_barto_reward": "yes"}}, "expected true or false"),
    ],
)
def test_env_tables_are_checked_against_their_id(env: dict[str, Any], named: str):
    with pytest.raises(ConfigError) as error:
        parse_config(_with(VALID, ("env",), env), source="fuzz.toml")
    assert named in str(error.value)


def test_an_id_registered_by_user_code_needs_the_allow_list():
    """An id that neither this project nor Gymnasium registered (here: by this test) is refused
    unless the user allows it by name, as ``run.py --allow-env ID`` does."""
    import gymnasium as gym
    from gymnasium.envs.registration import registry

    env_id = "UserTask-v0"
    if env_id not in registry:
        gym.register(env_id, entry_point=lambda: gym.make("CartPole-v1").unwrapped)
    data = _with(VALID, ("env",), {"id": env_id})
    with pytest.raises(ConfigError, match=r"allow it explicitly with --allow-env UserTask-v0"):
        parse_config(data, source="fuzz.toml")
    assert parse_config(data, source="fuzz.toml", allowed_env_ids=[env_id]).env.id == env_id
    with pytest.raises(ConfigError, match="is an import path"):
        parse_config(
            _with(VALID, ("env",), {"id": f"os:{env_id}"}),
            source="fuzz.toml",
            allowed_env_ids=[f"os:{env_id}"],
        )
