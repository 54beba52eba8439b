"""Fuzzing the task spelling of experiment files (``[env] suite``/``split``, ``[[task]]``) as an
attacker would: every case's outcome is asserted (refused naming the file and the key, or
accepted and written back unchanged)."""

from __future__ import annotations

import copy
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from experiments.config import ConfigError, dumps, load_config, parse_config, same_experiment

STRATEGIES = [{"name": "a"}, {"name": "b", "exploration": "epsilon-greedy"}]
SUITE: dict[str, Any] = {
    "experiment": {"name": "fuzz", "runs": 2, "episodes": 5, "eval_episodes": 3},
    "env": {"suite": "mazes", "split": "dev", "robot": "disc", "max_episode_steps": 100},
    "strategy": STRATEGIES,
}
TASKS: dict[str, Any] = {
    "experiment": {"name": "fuzz", "runs": 2, "episodes": 5},
    "env": {"max_episode_steps": 100},
    "task": [
        {"id": "MountainCar-v0", "name": "mc", "random_return": -100.0, "solved_return": -50.0},
        {
            "id": "CartPole-v1",
            "max_episode_steps": 500,
            "params": {"sutton_barto_reward": False},
            "observation_bounds": [[-4.8, -3.0, -0.42, -3.5], [4.8, 3.0, 0.42, 3.5]],
        },
        {"id": "BulletMaze-v0", "maze": "open", "robot": "disc", "mode": "kinematic"},
    ],
    "strategy": STRATEGIES,
}


def _with(data: dict[str, Any], path: tuple[Any, ...], value: Any) -> dict[str, Any]:
    edited = copy.deepcopy(data)
    table: Any = edited
    for key in path[:-1]:
        table = table[key]
    table[path[-1]] = value
    return edited


def _without(data: dict[str, Any], path: tuple[Any, ...]) -> dict[str, Any]:
    edited = copy.deepcopy(data)
    table: Any = edited
    for key in path[:-1]:
        table = table[key]
    del table[path[-1]]
    return edited


def _refused(data: dict[str, Any]) -> str:
    with pytest.raises(ConfigError) as error:
        parse_config(data, source="fuzz.toml")
    message = str(error.value)
    assert message.startswith("fuzz.toml: "), message
    return message


def test_the_valid_files_are_valid():
    assert len(parse_config(copy.deepcopy(SUITE), source="fuzz.toml").tasks) == 12
    tasks = parse_config(copy.deepcopy(TASKS), source="fuzz.toml").tasks
    assert [t.name for t in tasks] == ["mc", "CartPole-v1", "open"]


SUITE_CASES = [
    (("env", "suite"), "nosuch", "unknown suite 'nosuch'"),
    (("env", "suite"), "/no/such/suite.toml", "[env] suite"),
    (("env", "suite"), "../../etc/passwd", "[env] suite"),
    (("env", "suite"), "", "[env] suite"),
    (("env", "suite"), 3, "[env] suite: expected a string"),
    (("env", "suite"), True, "[env] suite: expected a string"),
    (("env", "suite"), ["mazes"], "[env] suite: expected a string"),
    (("env", "split"), "val", "unknown split 'val'"),
    (("env", "split"), "Dev", "unknown split 'Dev'"),
    (("env", "split"), [], "[env] split"),
    (("env", "split"), ["dev", "dev"], "once each"),
    (("env", "split"), [1], "[env] split: expected"),
    (("env", "split"), True, "[env] split: expected"),
    (("env", "split"), {"dev": 1}, "[env] split: expected"),
    (("env", "maze"), "open", "[env] maze: cannot be combined with suite"),
    (("env", "id"), "CartPole-v1", "[env] robot: only applies to the maze ids"),
    (("env", "id"), "BulletMaze-open-v0", "[env] suite: needs a maze id"),
    (("env", "id"), "os:system", "[env] id: 'os:system' is an import path"),
    (("env", "max_episode_steps"), "100", "[env] max_episode_steps"),
    (("env", "robot"), 1, "[env] robot"),
    (("experiment", "eval_episodes"), -1, "[experiment] eval_episodes"),
    (("experiment", "eval_episodes"), True, "[experiment] eval_episodes"),
    (("experiment", "eval_episodes"), 10**9, "[experiment] eval_episodes"),
    (("experiment", "eval_episodes"), 2.5, "[experiment] eval_episodes"),
    (("task",), [{"id": "CartPole-v1"}], "[env] suite: cannot be combined with [[task]]"),
]


@pytest.mark.parametrize(("path", "value", "named"), SUITE_CASES, ids=[str(c) for c in SUITE_CASES])
def test_suite_settings_are_refused_by_name(path: tuple[Any, ...], value: Any, named: str):
    assert named in _refused(_with(SUITE, path, value))


def test_a_split_needs_a_suite():
    data = _without(_with(SUITE, ("env", "split"), "test"), ("env", "suite"))
    assert "[env] split: only applies with [env] suite" in _refused(data)


TASK_CASES = [
    (("task",), [], "[[task]]: at least one task"),
    (("task",), {"id": "CartPole-v1"}, "[[task]]: expected an array of tables"),
    (("task",), ["CartPole-v1"], "[[task]]: expected an array of tables"),
    (("task",), [{"id": "CartPole-v1"}] * 1001, "1,001 tasks, at most 1,000"),
    (("task", 0, "id"), "gymnasium.envs.classic_control:CartPoleEnv", "is an import path"),
    (("task", 0, "id"), "NoSuchTask-v9", "[task.0] id: 'NoSuchTask-v9' is not a registered"),
    (("task", 0, "id"), 7, "[task.0] id: expected a string"),
    (("task", 0, "name"), "a/b", "[task.0] name"),
    (("task", 0, "name"), "CartPole-v1", "[task.1] name: 'CartPole-v1' is the name of task 0"),
    (("task", 0, "name"), "", "[task.0] name"),
    (("task", 0, "name"), 5, "[task.0] name: expected a string"),
    (("task", 0, "nam"), "x", "[task.0] nam: unknown key"),
    (("task", 0, "maze"), "open", "[task.0] maze: only applies to the maze ids"),
    (("task", 0, "max_episode_steps"), 0, "[task.0] max_episode_steps"),
    (("task", 0, "max_episode_steps"), True, "[task.0] max_episode_steps"),
    (("task", 0, "max_episode_steps"), 1.5, "[task.0] max_episode_steps"),
    (("task", 0, "random_return"), "low", "[task.0] random_return"),
    (("task", 0, "random_return"), True, "[task.0] random_return"),
    (("task", 0, "solved_return"), -100.0, "[task.0] solved_return: must be above"),
    (("task", 0, "solved_return"), -150.0, "[task.0] solved_return: must be above"),
    (("task", 2, "random_return"), 0.0, "[task.2] random_return: a maze task is scored"),
    (("task", 1, "params"), {"warp": 1}, "CartPole-v1 takes no such argument"),
    (("task", 1, "params"), {"sutton_barto_reward": "yes"}, "expected true or false"),
    (("task", 1, "params"), 3, "params: expected a table"),
    (("task", 1, "observation_bounds"), [[1.0], [0.0]], "[task.1] observation_bounds"),
    (("task", 1, "observation_bounds"), [[0, 1], [1]], "[task.1] observation_bounds"),
    (("task", 1, "observation_bounds"), [["a"], [1]], "[task.1] observation_bounds"),
    (("task", 1, "observation_bounds"), [[True], [2]], "[task.1] observation_bounds"),
    (("task", 1, "observation_bounds"), [[0] * 65, [1] * 65], "[task.1] observation_bounds"),
    (("task", 1, "observation_bounds"), [[], []], "[task.1] observation_bounds"),
    (("task", 1, "observation_bounds"), "wide", "[task.1] observation_bounds"),
    (("task", 1, "observation_bounds"), [[0, 0], [1, 1], [2, 2]], "[task.1] observation_bounds"),
    (("task", 0, "action_bins"), 1, "[task.0] action_bins: must be an integer from 2 to 64"),
    (("task", 0, "action_bins"), 65, "[task.0] action_bins: must be an integer from 2 to 64"),
    (("task", 0, "action_bins"), 0, "[task.0] action_bins"),
    (("task", 0, "action_bins"), -5, "[task.0] action_bins"),
    (("task", 0, "action_bins"), True, "[task.0] action_bins"),
    (("task", 0, "action_bins"), 2.5, "[task.0] action_bins"),
    (("task", 0, "action_bins"), "5", "[task.0] action_bins"),
    (("task", 0, "action_bins"), [5, 5], "[task.0] action_bins"),
    (("task", 2, "mode"), "wobbly", "[task.2] mode"),
    (("task", 2, "robot"), False, "[task.2] robot"),
    (("env", "maze"), "open", "[env] maze: only applies to the maze ids, not 'MountainCar-v0'"),
    (("env", "suite"), "mazes", "[env] suite: cannot be combined with [[task]]"),
    (("env", "params"), [], "env.params: expected a table"),
]


@pytest.mark.parametrize(("path", "value", "named"), TASK_CASES, ids=[str(c) for c in TASK_CASES])
def test_task_settings_are_refused_by_name(path: tuple[Any, ...], value: Any, named: str):
    assert named in _refused(_with(TASKS, path, value))


def test_the_suite_needs_a_maze_id_whose_maze_it_chooses():
    data = _without(_with(SUITE, ("env", "id"), "BulletMaze-open-v0"), ("env", "robot"))
    assert "[env] suite: needs a maze id" in _refused(data)


def test_runs_times_tasks_times_strategies_is_bounded():
    data = _with(TASKS, ("task",), [{"maze": f"rooms:seed={i}"} for i in range(101)])
    data = _with(data, ("experiment", "runs"), 10_000)
    assert "[experiment] runs: 10,000 runs x 101 tasks x 2 strategies" in _refused(data)
    fits = _with(data, ("experiment", "runs"), 9_900)
    assert len(parse_config(fits, source="fuzz.toml").tasks) == 101


def test_one_reference_alone_is_refused():
    data = _without(TASKS, ("task", 0, "solved_return"))
    assert "[task.0] solved_return: is required with random_return" in _refused(data)


def test_a_task_listed_twice_under_two_names_is_refused():
    data = _with(TASKS, ("task", 2), {**TASKS["task"][1], "name": "again"})
    assert "[task.2]: the same task as [task.1]" in _refused(data)


def test_a_non_finite_value_in_a_task_is_refused():
    data = _with(TASKS, ("task", 0, "random_return"), float("nan"))
    assert "[task.0] random_return: must be finite" in _refused(data)


HOSTILE = [True, "1", 0.5, -1, [], {}, None, ["dev", 1], "x" * 5000, "\x00", float("inf")]


def _leaves(table: Any, path: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    if isinstance(table, dict):
        return [leaf for key, value in table.items() for leaf in _leaves(value, (*path, key))]
    if isinstance(table, list) and table and isinstance(table[0], dict):
        return [leaf for i, value in enumerate(table) for leaf in _leaves(value, (*path, i))]
    return [path]


@pytest.mark.parametrize("base", [SUITE, TASKS], ids=["suite", "tasks"])
def test_random_edits_are_refused_by_name_or_round_trip(tmp_path: Path, base: dict[str, Any]):
    if "suite" in base["env"]:  # a small suite of hand-written layouts: fast to load
        suite = tmp_path / "small_suite.toml"
        suite.write_text('dev = ["open", "paper"]\ntest = ["corridors"]\n')
        base = _with(base, ("env", "suite"), str(suite))
    rng = np.random.default_rng(2026)
    refusals: list[str] = []
    accepted = 0
    for _ in range(150):
        data = copy.deepcopy(base)
        for _ in range(1 + int(rng.integers(2))):
            leaves = _leaves(data)
            path = leaves[int(rng.integers(len(leaves)))]
            choice = int(rng.integers(3))
            if choice == 0:
                data = _with(data, path, HOSTILE[int(rng.integers(len(HOSTILE)))])
            elif choice == 1:
                data = _without(data, path)
            else:
                data = _with(data, (*path[:-1], f"{path[-1]}_x"), 1)
        try:
            config = parse_config(data, source="fuzz.toml")
        except ConfigError as error:
            refusals.append(str(error))
            continue
        path = tmp_path / "again.toml"
        path.write_text(dumps(config))
        again = load_config(path)
        assert again.tasks == config.tasks
        assert same_experiment(config, again) == []
        accepted += 1
    assert all(message.startswith("fuzz.toml: ") for message in refusals)
    assert len(refusals) > 50
    assert accepted > 5


def test_references_whose_difference_overflows_are_refused():
    """The normalised score divides by solved_return - random_return: references of
    -1e308 and 1e308, each finite, would make every score 0 (and the profile's axis inf)."""
    data = copy.deepcopy(TASKS)
    data["task"][0].update(random_return=-1e308, solved_return=1e308)
    assert "[task.0] solved_return: 1e+308 is too far from random_return" in _refused(data)
