"""Experiments over tasks: the spelling of [env] suite / split and [[task]] tables."""

from __future__ import annotations

import copy
from pathlib import Path
from typing import Any

import pytest

import bullet_maze
from experiments.config import (
    ConfigError,
    dumps,
    load_config,
    parse_config,
    same_experiment,
    task_name,
    with_overrides,
    with_splits,
)
from experiments.plan import plan

BASE: dict[str, Any] = {
    "experiment": {"name": "t", "runs": 2, "episodes": 5},
    "strategy": [{"name": "a"}, {"name": "b", "exploration": "epsilon-greedy"}],
}


def _with(**sections: Any) -> dict[str, Any]:
    data = copy.deepcopy(BASE)
    data.update(copy.deepcopy(sections))
    return data


def test_a_suite_gives_one_task_per_layout_of_its_dev_split():
    config = parse_config(_with(env={"suite": "mazes", "max_episode_steps": 900}))
    suite = bullet_maze.load_suite("mazes")
    assert [t.env.maze for t in config.tasks] == list(suite.dev)
    assert {t.split for t in config.tasks} == {"dev"}
    assert all(t.env.max_episode_steps == 900 for t in config.tasks)
    assert config.tasks[5].name == "rooms-seed1-door14-loops0"
    assert config.env == config.tasks[0].env
    assert config.suite == "mazes"
    assert config.splits == ("dev",)


@pytest.mark.parametrize(
    ("split", "expected"),
    [("test", ("test",)), (["dev", "test"], ("dev", "test")), (["test", "dev"], ("test", "dev"))],
)
def test_the_split_chooses_dev_test_or_both(split: Any, expected: tuple[str, ...]):
    config = parse_config(_with(env={"suite": "mazes", "split": split}))
    suite = bullet_maze.load_suite("mazes")
    assert config.splits == expected
    assert [t.env.maze for t in config.tasks] == [m for s in expected for m in suite.split(s)]
    assert [t.split for t in config.tasks] == [s for s in expected for _ in suite.split(s)]


def test_split_option_replaces_the_files_split():
    config = parse_config(_with(env={"suite": "mazes"}), source="s.toml")
    both = with_splits(config, ["dev", "test"])
    assert both.splits == ("dev", "test")
    assert len(both.tasks) == 20
    assert with_splits(config, None) is config
    with pytest.raises(ConfigError, match=r"option --split: unknown split 'val'"):
        with_splits(config, ["val"])
    with pytest.raises(ConfigError, match=r"option --split: expected dev, test or both once"):
        with_splits(config, ["dev", "dev"])
    single = parse_config(_with(env={"maze": "open"}), source="one.toml")
    with pytest.raises(ConfigError, match=r"option --split: only applies .* one\.toml has none"):
        with_splits(single, ["test"])


def test_tasks_inherit_env_and_override_it():
    config = parse_config(
        _with(
            env={"max_episode_steps": 300, "params": {"sutton_barto_reward": False}},
            task=[
                {"id": "CartPole-v1"},
                {"id": "CartPole-v1", "name": "cp-long", "max_episode_steps": 500},
                {"id": "BulletMaze-v0", "maze": "open", "params": {}},
            ],
        )
    )
    first, second, maze = config.tasks
    assert (first.name, first.env.max_episode_steps) == ("CartPole-v1", 300)
    assert first.env.params == {"sutton_barto_reward": False}
    assert (second.name, second.env.max_episode_steps) == ("cp-long", 500)
    assert maze.name == "open"
    assert maze.env.is_maze
    assert maze.env.max_episode_steps == 300
    assert config.env == first.env


def test_runs_of_tasks_are_named_by_task_and_share_seeds():
    config = parse_config(_with(task=[{"id": "CartPole-v1"}, {"id": "Acrobot-v1"}]))
    runs = plan(config)
    assert len(runs) == 2 * 2 * 2
    assert [r.name.split("/")[0] for r in runs[:4]] == ["CartPole-v1"] * 2 + ["Acrobot-v1"] * 2
    seeds = {(r.task, r.strategy.name, r.run_index): r.seed for r in runs}
    assert seeds[("CartPole-v1", "a", 1)] == seeds[("Acrobot-v1", "b", 1)]
    assert seeds[("CartPole-v1", "a", 0)] != seeds[("CartPole-v1", "a", 1)]
    assert runs[0].name == f"CartPole-v1/a__{runs[0].seed}"


def test_single_environment_experiments_keep_their_run_names(small_config):
    assert small_config.tasks == ()
    assert all("/" not in r.name and r.task is None for r in plan(small_config))


@pytest.mark.parametrize(
    "sections",
    [
        {"env": {"suite": "mazes", "split": ["dev", "test"], "robot": "disc"}},
        {"task": [{"id": "CartPole-v1", "random_return": 20.0, "solved_return": 475.0}]},
        {
            "task": [
                {
                    "id": "CartPole-v1",
                    "observation_bounds": [[-4.8, -3, -0.42, -3.5], [4.8, 3, 0.42, 3.5]],
                },
                {"maze": "rooms:seed=3", "name": "r3"},
            ]
        },
    ],
)
def test_task_experiments_round_trip(tmp_path: Path, sections: dict[str, Any]):
    config = parse_config(_with(**sections), source="t.toml")
    path = tmp_path / "again.toml"
    path.write_text(dumps(config))
    again = load_config(path)
    assert again.tasks == config.tasks
    assert same_experiment(config, again) == []


def test_a_changed_split_or_task_is_another_experiment():
    dev = parse_config(_with(env={"suite": "mazes"}))
    test = parse_config(_with(env={"suite": "mazes", "split": "test"}))
    assert same_experiment(dev, test) == ["env.split"]
    one = parse_config(_with(task=[{"id": "CartPole-v1"}]))
    two = parse_config(_with(task=[{"id": "CartPole-v1"}, {"id": "Acrobot-v1"}]))
    assert same_experiment(one, two) == ["task"]


def test_the_cap_override_reaches_every_task():
    config = parse_config(_with(task=[{"id": "CartPole-v1"}, {"id": "MountainCar-v0"}]))
    capped = with_overrides(config, max_episode_steps=77)
    assert [t.env.max_episode_steps for t in capped.tasks] == [77, 77]
    assert capped.env.max_episode_steps == 77


def test_single_task_is_a_one_environment_experiment():
    config = parse_config(_with(task=[{"id": "CartPole-v1"}, {"id": "Acrobot-v1"}]), "t.toml")
    one = config.single_task("Acrobot-v1", "--task")
    assert one.tasks == ()
    assert one.env.id == "Acrobot-v1"
    assert config.single_task().env.id == "CartPole-v1"
    with pytest.raises(ConfigError, match=r"option --task: no task named 'x' .*CartPole-v1"):
        config.single_task("x", "--task")


@pytest.mark.parametrize(
    ("maze", "name"),
    [
        ("rooms:seed=1,door=14,loops=0", "rooms-seed1-door14-loops0"),
        ("maze:seed=1,rows=8,cols=8,cell=37.5", "maze-seed1-rows8-cols8-cell37.5"),
        ("/some/where/my maze.toml", "my_maze"),
        ("paper", "paper"),
    ],
)
def test_task_names_are_file_name_safe(maze: str, name: str):
    from experiments.config import EnvSpec

    assert task_name(EnvSpec(maze=maze)) == name


def test_the_shipped_comparisons_load():
    suite = load_config("maze_suite")
    assert suite.splits == ("dev",)
    assert len(suite.tasks) == 12
    assert {"adaptive+tabu", "eps-greedy-0.015", "grid-10x10", "grid-30x30"} <= {
        s.name for s in suite.strategies
    }
    assert len(with_splits(suite, ["test"]).tasks) == 8
    classic = load_config("classic_control")
    assert [(t.name, t.env.max_episode_steps) for t in classic.tasks] == [
        ("MountainCar-v0", 200),
        ("Acrobot-v1", 500),
        ("CartPole-v1", 500),
    ]
    assert classic.eval_episodes == 20
    assert classic.tasks[2].env.observation_bounds is not None


def test_an_env_other_than_a_maze_is_an_experiment_over_that_one_task():
    """Its runs are scored by their returns (the task report), never by a maze's steps and
    successes: CartPole's ``terminated`` is a fall, which the maze report counted as a success."""
    config = parse_config(_with(env={"id": "CartPole-v1", "max_episode_steps": 200}))
    assert [(t.name, t.env.id, t.env.max_episode_steps) for t in config.tasks] == [
        ("CartPole-v1", "CartPole-v1", 200)
    ]
    assert config.env == config.tasks[0].env
    as_table = parse_config(_with(task=[{"id": "CartPole-v1", "max_episode_steps": 200}]))
    assert config.tasks == as_table.tasks
    maze = parse_config(_with(env={"maze": "open"}))
    assert maze.tasks == ()
    assert maze.env.is_maze
