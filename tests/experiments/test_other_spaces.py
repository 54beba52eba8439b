"""Experiments on tasks whose spaces are not a flat Box and Discrete actions: every env is built
through agent.adapt_env, with ``action_bins`` for a Box action (experiments/factory.py)."""

from __future__ import annotations

import copy
import tomllib
from pathlib import Path
from typing import Any

import pytest

import run
from experiments import Experiment
from experiments.config import ConfigError, dumps, parse_config
from experiments.factory import make_env
from experiments.fingerprint import resolved_config

BASE: dict[str, Any] = {
    "experiment": {"name": "spaces", "runs": 1, "episodes": 2, "eval_episodes": 2},
    "task": [
        {"id": "Pendulum-v1", "action_bins": 3, "random_return": -1200.0, "solved_return": -150.0},
        {"id": "FrozenLake-v1", "random_return": 0.0, "solved_return": 0.7},
    ],
    "strategy": [{"name": "general", "preset": "general"}],
}


def test_the_tasks_are_adapted_with_their_action_bins() -> None:
    config = parse_config(copy.deepcopy(BASE), "spaces.toml")
    pendulum, lake = (make_env(task.env) for task in config.tasks)
    assert pendulum.action_space.n == 3  # type: ignore[attr-defined]
    assert [a.tolist() for a in pendulum.actions] == [[-2.0], [0.0], [2.0]]  # type: ignore[attr-defined]
    assert lake.observation_space.shape == (1,)
    assert config.tasks[1].env.action_bins is None  # default: 5, only for a Box action


def test_action_bins_for_discrete_actions_is_refused_naming_the_task(tmp_path: Path) -> None:
    data = copy.deepcopy(BASE)
    data["task"][1]["action_bins"] = 4
    config = parse_config(data, "spaces.toml")
    with pytest.raises(
        ConfigError,
        match=r"spaces.toml: task 'FrozenLake-v1': action_bins = 4 "
        r"only applies to a task with Box actions; FrozenLake-v1 has Discrete\(4\)",
    ):
        Experiment(config, tmp_path / "out").check()


def test_action_bins_round_trips_and_is_part_of_the_run_identity() -> None:
    config = parse_config(copy.deepcopy(BASE), "spaces.toml")
    again = parse_config(tomllib.loads(dumps(config)), "spaces.toml")
    assert again == config
    five = copy.deepcopy(BASE)
    five["task"][0]["action_bins"] = 5
    other = parse_config(five, "spaces.toml")
    strategy = config.strategies[0]
    assert resolved_config(config, strategy, config.tasks[0].env, 0) != resolved_config(
        other, strategy, other.tasks[0].env, 0
    )
    # a task without it keeps the fingerprint it had before the setting existed
    assert "action_bins" not in resolved_config(config, strategy, config.tasks[1].env, 0)["env"]


def test_an_experiment_runs_on_adapted_tasks_end_to_end(tmp_path: Path) -> None:
    config = parse_config(copy.deepcopy(BASE), "spaces.toml")
    path = tmp_path / "spaces.toml"
    path.write_text(dumps(config))
    out = tmp_path / "out"
    assert run.main(["experiment", str(path), "--out", str(out), "--no-progress"]) == 0
    report = (out / "report.md").read_text()
    assert "Pendulum-v1" in report
    assert "FrozenLake-v1" in report
    assert len(list((out / "runs").rglob("*.eval.csv"))) == 2


def test_random_references_run_as_the_harness_runs_the_task() -> None:
    from experiments.references import random_policy_return

    mean, _ = random_policy_return("Pendulum-v1", 2, seed=0)  # a Box action: the 5-value grid
    assert -16.3 * 200 <= mean < 0.0
    # CliffWalking registers no limit; at 10 steps each step costs 1, or 100 off the cliff
    mean, error = random_policy_return("CliffWalking-v1", 3, seed=0, max_episode_steps=10)
    assert -1000.0 <= mean <= -10.0
    assert error >= 0.0
