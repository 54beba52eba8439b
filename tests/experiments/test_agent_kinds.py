"""Strategies of every agent of issue 9: a named preset, the tile coder, adaptive Q-learning.

A preset strategy is the preset (its TreeConfig replaces ``[agent]``, its strategy is the
default), spelt out or named it is the same run; the fixed baselines take their constructor
arguments from ``agent_params`` and nothing else; every error names the file and the key.
"""

from __future__ import annotations

import copy
import dataclasses
from pathlib import Path
from typing import Any

import gymnasium as gym
import pytest

import run
from agent import AdaptiveQAgent, TileCodingAgent, TreeAgent, preset
from agent.exploration import exploration_spec
from experiments import factory, fingerprint
from experiments.config import (
    ConfigError,
    dumps,
    load_config,
    parse_config,
    same_experiment,
    to_dict,
)
from experiments.factory import load_agent
from experiments.jobs import TrainJob

BASE: dict[str, Any] = {
    "experiment": {"name": "kinds", "seed": 4, "runs": 1, "episodes": 2},
    "env": {"id": "MountainCar-v0"},
    "agent": {"split_min_samples": 321, "alpha": 0.2},
    "strategy": [{"name": "eps", "exploration": "epsilon-greedy"}],
}


def _with(*strategies: dict[str, Any]) -> dict[str, Any]:
    data = copy.deepcopy(BASE)
    data["strategy"] += list(strategies)
    return data


def _parse(*strategies: dict[str, Any]) -> Any:
    return parse_config(_with(*strategies), source="kinds.toml")


def _refusal(strategy: dict[str, Any]) -> str:
    """The ConfigError of a file holding ``strategy`` alone, which must name the file and the
    strategy's table first."""
    with pytest.raises(ConfigError) as error:
        _parse(strategy)
    message = str(error.value)
    assert message.startswith("kinds.toml: [strategy.1]"), message
    return message


@pytest.fixture(scope="module")
def car() -> gym.Env:
    env = gym.make("MountainCar-v0")
    yield env
    env.close()


@pytest.mark.parametrize("name", ["paper", "paper-literal", "general"])
def test_a_preset_strategy_is_the_preset(name: str, car: gym.Env):
    config = _parse({"name": "p", "preset": name})
    strategy = config.strategies[-1]
    named = preset(name)
    assert factory.agent_config(config, strategy) == named.config  # [agent] does not apply
    assert strategy.exploration == named.exploration
    built = factory.make_exploration(config, strategy)
    assert exploration_spec(built) == exploration_spec(named.make_exploration())
    agent = factory.make_agent(config, strategy, car, seed=3)
    assert isinstance(agent, TreeAgent)
    assert agent.config == named.config


def test_a_preset_strategy_takes_its_own_changes():
    config = _parse(
        {
            "name": "p",
            "preset": "paper-literal",
            "config": {"split_min_samples": 50},
            "exploration_params": {"shrink_every": 3},
        },
        {"name": "q", "preset": "general", "exploration": "epsilon-greedy"},
    )
    literal, other = config.strategies[1:]
    tree = factory.agent_config(config, literal)
    assert tree == dataclasses.replace(preset("paper-literal").config, split_min_samples=50)
    assert literal.exploration_params == {
        **preset("paper-literal").exploration_params,
        "shrink_every": 3,
    }
    assert other.exploration == "epsilon-greedy"
    assert other.exploration_params == {}
    assert factory.agent_config(config, other) == preset("general").config


def test_a_strategy_config_is_checked_on_top_of_its_preset():
    """A field that needs another of the preset's (model_lambda needs planning = "sweep") is
    accepted on the general preset and refused, naming both, on [agent] without sweeping."""
    config = _parse({"name": "lam", "preset": "general", "config": {"model_lambda": 0.5}})
    tree = factory.agent_config(config, config.strategies[-1])
    assert tree == dataclasses.replace(preset("general").config, model_lambda=0.5)
    with pytest.raises(ConfigError) as error:
        _parse({"name": "lam", "config": {"model_lambda": 0.5}})
    message = str(error.value)
    assert message.startswith("kinds.toml: [strategy.1] [agent] + config"), message
    assert "needs planning = 'sweep'" in message, message


def test_named_and_spelt_out_presets_are_the_same_run():
    """``general_paper.toml`` spells the general preset out: naming it gives the same run
    fingerprint (the resolved settings), so either file's runs are the other's."""
    shipped = load_config("general_paper")
    spelt = shipped.strategy("general")
    data = to_dict(shipped)
    data["strategy"] = [{"name": "general", "preset": "general"}]
    data["experiment"].pop("baseline")
    named = parse_config(data, source="named.toml").strategies[0]
    for seed in (0, 12345):
        assert fingerprint.resolved_config(
            shipped, spelt, shipped.env, seed
        ) == fingerprint.resolved_config(shipped, named, shipped.env, seed)


def test_fixed_agents_are_built_with_their_parameters(car: gym.Env):
    config = _parse(
        {"name": "tile", "agent": "tile", "agent_params": {"tilings": 4, "tiles": 6, "alpha": 0.3}},
        {"name": "aq", "agent": "adaptive-q", "agent_params": {"bonus_scale": 0.5, "r_max": 0.0}},
    )
    tile = factory.make_agent(config, config.strategy("tile"), car, seed=9)
    assert isinstance(tile, TileCodingAgent)
    assert (tile.tilings, tile.tiles, tile.alpha, tile.seed) == (4, 6, 0.3, 9)
    assert tile.gamma == 0.99  # its own default: [agent] applies to tree and grid only
    aq = factory.make_agent(config, config.strategy("aq"), car, seed=2)
    assert isinstance(aq, AdaptiveQAgent)
    assert (aq.bonus_scale, aq.r_max, aq.seed) == (0.5, 0.0, 2)


def test_a_fixed_agent_fingerprint_holds_every_argument():
    config = _parse(
        {"name": "tile", "agent": "tile", "agent_params": {"tilings": 4}},
        {"name": "tile2", "agent": "tile", "agent_params": {"tilings": 4, "lam": 0.9}},
        {"name": "tile3", "agent": "tile", "agent_params": {"tilings": 4, "lam": 0.8}},
    )
    settings = [
        fingerprint.resolved_config(config, s, config.env, 1) for s in config.strategies[1:]
    ]
    assert settings[0]["agent_params"]["tilings"] == 4
    assert settings[0]["agent_params"]["alpha"] == 0.5  # defaults filled in
    assert "agent_config" not in settings[0]
    assert "exploration" not in settings[0]
    assert settings[0] == settings[1]  # lam = 0.9 is the default
    assert settings[0] != settings[2]


def test_every_kind_round_trips(tmp_path: Path):
    config = _parse(
        {"name": "p", "preset": "paper-literal", "exploration_params": {"shrink_every": 3}},
        {"name": "tile", "agent": "tile", "agent_params": {"tilings": 4}},
        {"name": "aq", "agent": "adaptive-q"},
    )
    path = tmp_path / "again.toml"
    path.write_text(dumps(config))
    again = load_config(path)
    assert again.strategies == config.strategies
    assert same_experiment(config, again) == []
    assert "exploration" not in path.read_text().split('name = "tile"')[1].split("[[")[0]


@pytest.mark.parametrize(
    ("strategy", "named"),
    [
        ({"name": "x", "preset": "generall"}, "preset: expected one of general, paper"),
        ({"name": "x", "preset": 3}, "preset: expected a string"),
        ({"name": "x", "agent": "tiles"}, "agent: expected one of tree, grid, tile, adaptive-q"),
        ({"name": "x", "agent": "tile", "exploration": "boltzmann"}, "exploration: does not"),
        ({"name": "x", "agent": "tile", "preset": "general"}, "preset: does not apply"),
        ({"name": "x", "agent": "adaptive-q", "config": {"alpha": 0.1}}, "config: does not"),
        ({"name": "x", "agent": "tile", "resolution": 4}, "resolution: does not apply"),
        ({"name": "x", "agent_params": {"tilings": 4}}, "agent_params: only applies"),
        ({"name": "x", "agent": "tile", "agent_params": {"tilngs": 4}}, "'tilngs' is not a"),
        ({"name": "x", "agent": "tile", "agent_params": {"tilings": 0}}, "tilings must be"),
        ({"name": "x", "agent": "tile", "agent_params": {"tilings": 2.0}}, "tilings: expected"),
        ({"name": "x", "agent": "tile", "agent_params": {"alpha": True}}, "alpha: expected"),
        ({"name": "x", "agent": "tile", "agent_params": {"seed": 1}}, "'seed' is not a"),
        ({"name": "x", "agent": "tile", "agent_params": {"bounds": [0, 1]}}, "'bounds' is not"),
        ({"name": "x", "agent": "tile", "agent_params": 4}, "agent_params: expected a table"),
        ({"name": "x", "agent": "adaptive-q", "agent_params": {"gamma": 1.0}}, "gamma must be"),
        ({"name": "x", "agent": "adaptive-q", "agent_params": {"max_depth": -1}}, "max_depth"),
        ({"name": "x", "agent": "adaptive-q", "agent_params": {"horizon": 0.5}}, "horizon"),
        (
            {"name": "x", "preset": "general", "config": {"split_min_samples": 0}},
            "config: TreeConfig",
        ),
        ({"name": "x", "preset": "general", "exploration_params": {"c_h": "a"}}, "c_h"),
    ],
)
def test_errors_name_the_file_the_strategy_and_the_field(strategy: dict[str, Any], named: str):
    message = _refusal(strategy)
    assert named in message, message


def test_train_refuses_a_fixed_agent_and_says_what_to_run(tmp_path: Path):
    path = tmp_path / "kinds.toml"
    data = _with({"name": "tile", "agent": "tile"})
    path.write_text(dumps(parse_config(data, source=str(path))))
    with pytest.raises(ConfigError, match=r"run\.py experiment .* --only tile"):
        TrainJob.from_options(path, strategy="tile", out=tmp_path / "out")
    with pytest.raises(SystemExit) as stop:  # the CLI: a message, no traceback
        run.main(["train", "--config", str(path), "--strategy", "tile"])
    assert stop.value.code == 2


def test_every_kind_runs_in_an_experiment_and_repeats_bit_for_bit(tmp_path: Path, capsys):
    """One run of each new kind in a maze, twice: the same CSVs to the byte. Each saves its
    agent (the baselines too, ``agent.baseline_files``), which the harness loads and
    ``run.py evaluate`` plays."""
    data = {
        "experiment": {
            "name": "kinds",
            "seed": 11,
            "runs": 1,
            "episodes": 2,
            "save_agents": True,
        },
        "env": {"maze": "open", "max_episode_steps": 100},
        "strategy": [
            {"name": "general", "preset": "general"},
            {"name": "tile", "agent": "tile"},
            {"name": "aq", "agent": "adaptive-q"},
        ],
    }
    path = tmp_path / "kinds.toml"
    path.write_text(dumps(parse_config(data, source="kinds.toml")))
    outputs = []
    for name in ("a", "b"):
        out = tmp_path / name
        code = run.main(
            ["experiment", str(path), "--backend", "serial", "--no-progress", "--out", str(out)]
        )
        assert code == 0
        outputs.append({p.name: p.read_bytes() for p in sorted((out / "runs").glob("*.csv"))})
    assert len(outputs[0]) == 3
    assert outputs[0] == outputs[1]
    files = sorted((tmp_path / "a" / "runs").glob("*.agent.npz"))
    assert [f.name.split("__")[0] for f in files] == ["aq", "general", "tile"]
    loaded = [type(load_agent(f)).__name__ for f in files]
    assert loaded[0] == "AdaptiveQAgent"
    assert loaded[2] == "TileCodingAgent"
    capsys.readouterr()
    assert run.main(["evaluate", str(files[2]), "--config", str(path), "--episodes", "1"]) == 0
    assert "1 greedy episodes in maze 'open'" in capsys.readouterr().out
    # without --config: the results folder's own file, not the default job's 'paper' maze
    assert run.main(["evaluate", str(files[1]), "--episodes", "1"]) == 0
    assert "1 greedy episodes in maze 'open'" in capsys.readouterr().out
    damaged = tmp_path / "damaged.agent.npz"
    damaged.write_bytes(files[2].read_bytes()[:-40])
    with pytest.raises(SystemExit) as stop:  # the CLI: a message naming the file, no traceback
        run.main(["evaluate", str(damaged), "--config", str(path)])
    assert stop.value.code == 2
    assert "cannot load the agent: " in capsys.readouterr().err
    for baseline in (files[0], files[2]):  # no partition to draw under the track: the maze
        gif = tmp_path / f"{baseline.stem}.gif"
        assert run.main(["render", str(baseline), "--out", str(gif), "--max-frames", "3"]) == 0
        assert gif.stat().st_size > 0


def test_an_experiment_s_saved_agent_is_played_in_its_own_task(tmp_path: Path, capsys):
    """An agent saved under ``runs/<task>/`` is played in that task of the results folder's
    experiment when no --config is given (it was played in the default job's maze, or refused
    there for its action count)."""
    path = tmp_path / "tasks.toml"
    path.write_text(
        '[experiment]\nname = "t"\nruns = 1\nepisodes = 2\nsave_agents = true\n\n'
        '[[task]]\nid = "CartPole-v1"\n\n[[task]]\nid = "MountainCar-v0"\nname = "mc"\n'
        "max_episode_steps = 30\n\n"
        '[[strategy]]\nname = "tile"\nagent = "tile"\n'
    )
    out = tmp_path / "out"
    assert (
        run.main(
            ["experiment", str(path), "--backend", "serial", "--no-progress", "--out", str(out)]
        )
        == 0
    )
    capsys.readouterr()
    for folder, shown in (
        ("CartPole-v1", "in CartPole-v1 (cap 500)"),
        ("mc", "in MountainCar-v0 (cap 30)"),
    ):
        (agent,) = (out / "runs" / folder).glob("*.agent.npz")
        assert run.main(["evaluate", str(agent), "--episodes", "1"]) == 0
        assert shown in capsys.readouterr().out


ISSUE_9_STRATEGIES = {
    "general",
    "tile",
    "adaptive-q",
    "boltzmann",
    "count-bonus",
    "decaying-epsilon",
    "vdbe-softmax",
    "optimistic",
}


@pytest.mark.parametrize("names", [("maze_suite", "maze_baselines"), ("classic_control",)])
def test_the_shipped_comparisons_hold_every_agent_of_issue_9(names: tuple[str, ...]):
    """The maze comparison is two files (each sized for about 30 minutes), the classic one."""
    configs = [load_config(name) for name in names]
    strategies = [s for config in configs for s in config.strategies]
    assert {s.name for s in strategies} >= ISSUE_9_STRATEGIES
    assert all(c.strategy("general").preset == "general" for c in configs)
    assert {s.agent for s in strategies} >= {"tree", "tile", "adaptive-q"}
    explorations = {s.exploration for s in strategies if s.agent == "tree"}
    assert explorations >= {
        "boltzmann",
        "count-bonus",
        "decaying-epsilon",
        "vdbe-softmax",
        "optimistic",
    }
    for config in configs:  # every agent builds for a task's environment
        task = config.tasks[-1]
        env = factory.make_env(task.env)
        try:
            factory.check_agents(config, env, task.env)
        finally:
            env.close()


@pytest.mark.parametrize(
    ("changes", "defect"),
    [
        ({"hold_terminals": 0}, "hold_terminals must be a positive int or None, got 0"),
        ({"hold_terminals": -3}, "hold_terminals must be a positive int or None, got -3"),
        ({"hold_terminals": True}, "hold_terminals: expected an integer"),
        ({"hold_terminals": "5"}, "hold_terminals: expected an integer"),
        ({"hold_terminals": 2.5}, "hold_terminals: expected an integer"),
        ({"hold_after_truncation": 1}, "hold_after_truncation: expected true or false"),
        (
            {"hold_terminals": None, "hold_after_truncation": True},
            "hold_after_truncation = True needs hold_terminals",
        ),
    ],
)
def test_bad_hold_options_on_the_general_preset_name_the_file_and_field(
    changes: dict[str, Any], defect: str
) -> None:
    """Part 8's options in a strategy table: every bad value is refused by name."""
    config = {k: v for k, v in changes.items() if v is not None}
    if "hold_terminals" in changes and changes["hold_terminals"] is None:
        spelt = {**preset("general").config.to_dict(), **config}
        spelt.pop("hold_terminals")
        strategy = {"name": "held", "exploration": "adaptive+tabu", "config": spelt}
    else:
        strategy = {"name": "held", "preset": "general", "config": config}
    message = _refusal(strategy)
    assert defect in message, message


@pytest.mark.parametrize(
    ("config", "defect"),
    [
        ({"model_split_epochs": 3}, "model_split_epochs must be an int >= 4"),
        ({"model_split_epochs": 40}, "model_split_epochs = 40 is more than model_window = 32"),
        ({"model_split_epochs": True}, "model_split_epochs: expected an integer"),
        ({"model_split_epochs": "8"}, "model_split_epochs: expected an integer"),
        ({"model_split_gap": -1.0}, "model_split_gap must be a finite number >= 0, got -1.0"),
        ({"model_split_gap": "x"}, "model_split_gap: expected a number, got 'x'"),
        ({"model_split_t": float("nan")}, "model_split_t: must be finite, got nan"),
        ({"model_split_t": True}, "model_split_t: expected a number, got true"),
        (
            {"model_split_epochs": 8, "planning": "none"},
            "model_split_epochs = 8 needs planning = 'sweep'",
        ),
    ],
)
def test_bad_model_split_options_name_the_file_and_field(
    config: dict[str, Any], defect: str
) -> None:
    """Part 9's options in a strategy table: every bad value is refused by name."""
    message = _refusal({"name": "split", "preset": "general", "config": config})
    assert defect in message, message


@pytest.mark.parametrize(
    ("config", "defect"),
    [
        ({"novelty_cells": 1}, "novelty_cells must be an int in [2, 2^20] or None, got 1"),
        ({"novelty_cells": 1 << 21}, "novelty_cells must be an int in [2, 2^20]"),
        ({"novelty_cells": True}, "novelty_cells: expected an integer"),
        ({"novelty_cells": 6.5}, "novelty_cells: expected an integer"),
        ({"novelty_cells": "64"}, "novelty_cells: expected an integer"),
        ({"novelty_terminals": 0}, "novelty_terminals must be an int >= 1, got 0"),
        ({"novelty_terminals": -3}, "novelty_terminals must be an int >= 1, got -3"),
        ({"novelty_terminals": "10"}, "novelty_terminals: expected an integer"),
    ],
)
def test_bad_novelty_options_name_the_file_and_field(config: dict[str, Any], defect: str) -> None:
    """Part 10's options in a strategy table: every bad value is refused by name."""
    message = _refusal({"name": "novel", "preset": "general", "config": config})
    assert defect in message, message


@pytest.mark.parametrize(
    ("config", "defect"),
    [
        (
            {"scale_horizon": 0.5},
            "scale_horizon must be None or a number in [1, 1,000,000], got 0.5",
        ),
        ({"scale_horizon": 1e7}, "scale_horizon must be None or a number in [1, 1,000,000]"),
        ({"scale_horizon": float("nan")}, "config.scale_horizon: must be finite, got nan"),
        ({"scale_horizon": True}, "scale_horizon: expected a number or nothing (none), got true"),
        ({"scale_horizon": "100"}, "scale_horizon: expected a number or nothing (none), got '100'"),
    ],
)
def test_bad_scale_horizon_names_the_file_and_field(config: dict[str, Any], defect: str) -> None:
    """The unit's horizon in a strategy table: every bad value is refused by name."""
    message = _refusal({"name": "horizon", "preset": "general", "config": config})
    assert defect in message, message


def test_novel_ends_without_the_model_name_the_file_and_field() -> None:
    # a strategy of its own (no preset): planning keeps its default, "none"
    strategy = {"name": "novel", "exploration": "adaptive+tabu", "config": {"novelty_cells": 64}}
    message = _refusal(strategy)
    assert "novelty_cells = 64 needs planning = 'sweep'" in message, message


@pytest.mark.parametrize(
    ("config", "defect"),
    [
        (
            {"ensemble_decisions": "first"},
            "ensemble_decisions = 'first' needs ensemble_trees >= 2, got 1",
        ),
        (
            {"ensemble_trees": 2, "ensemble_decisions": "each"},
            "ensemble_decisions must be one of ['any', 'first'], got 'each'",
        ),
        ({"ensemble_trees": 2, "ensemble_decisions": 1}, "ensemble_decisions"),
        ({"ensemble_trees": 2, "ensemble_decisions": True}, "ensemble_decisions"),
    ],
)
def test_bad_ensemble_decisions_name_the_file_and_field(
    config: dict[str, Any], defect: str
) -> None:
    """Part 13's option in a strategy table: every bad value is refused by name."""
    message = _refusal({"name": "trees", "preset": "general", "config": config})
    assert defect in message, message


@pytest.mark.parametrize(
    ("strategy", "defect"),
    [
        (
            {"name": "cuts", "config": {"collision_splits": True}},
            "collision_splits = True needs planning = 'sweep'",
        ),
        (
            {"name": "cuts", "preset": "general", "config": {"collision_splits": 1}},
            "collision_splits: expected true or false, got 1",
        ),
        (
            {"name": "cuts", "preset": "general", "config": {"collision_splits": "yes"}},
            "collision_splits: expected true or false, got 'yes'",
        ),
        (
            {"name": "cuts", "preset": "general", "config": {"collision_splits": None}},
            "collision_splits: expected true or false, got None",
        ),
    ],
)
def test_bad_collision_splits_name_the_file_and_field(
    strategy: dict[str, Any], defect: str
) -> None:
    """Part 14's option in a strategy table: every bad value is refused by name."""
    message = _refusal(strategy)
    assert defect in message, message


@pytest.mark.parametrize(
    ("value", "defect"),
    [
        (0, "table_cells must be None or an int in [1, 65,536], got 0"),
        (-3, "got -3"),
        (65537, "got 65537"),
        (2.5, "got 2.5"),
        (True, "got true"),
        ("4096", "got '4096'"),
        ([16], "got [16]"),
    ],
)
def test_bad_table_cells_name_the_file_and_field(value: Any, defect: str) -> None:
    """Part 15's option in a strategy table: every bad value is refused by name."""
    message = _refusal({"name": "table", "preset": "general", "config": {"table_cells": value}})
    assert "table_cells" in message, message
    assert defect in message, message


@pytest.mark.parametrize(
    ("value", "defect"),
    [(1, "got 1"), ("yes", "got 'yes'"), (None, "got None"), ([True], "got [True]")],
)
def test_bad_optimistic_untried_names_the_file_and_field(value: Any, defect: str) -> None:
    """Part 16's option in a strategy table: every bad value is refused by name."""
    strategy = {"name": "opt", "preset": "general", "config": {"optimistic_untried": value}}
    message = _refusal(strategy)
    assert "optimistic_untried" in message, message
    assert defect in message, message


@pytest.mark.parametrize(
    ("field", "value", "defect"),
    [
        ("presplit_max_dimensions", 17, "must be None or an int in [0, 16]"),
        ("presplit_max_dimensions", -2, "got -2"),
        ("presplit_max_dimensions", 8.0, "got 8.0"),
        ("presplit_max_dimensions", "8", "got '8'"),
        ("presplit_max_dimensions", True, "got true"),
        ("presplit_beyond_dimensions", 99, "must be an int in [0, 16]"),
        ("presplit_beyond_dimensions", -1, "got -1"),
        ("presplit_beyond_dimensions", [2], "got [2]"),
        ("presplit_beyond_dimensions", 1.5, "got 1.5"),
    ],
)
def test_bad_presplit_limits_name_the_file_and_field(field: str, value: Any, defect: str) -> None:
    """Part 17's options in a strategy table: every bad value is refused by name."""
    message = _refusal({"name": "wide", "preset": "general", "config": {field: value}})
    assert field in message, message
    assert defect in message, message


@pytest.mark.parametrize(
    ("value", "defect"),
    [
        (1.5, "must be in [0.0, 1.0], got 1.5"),
        (-0.5, "got -0.5"),
        ("0.9995", "got '0.9995'"),
        (True, "got true"),
        ([0.9], "got [0.9]"),
    ],
)
def test_a_bad_failure_discount_names_the_file_and_field(value: Any, defect: str) -> None:
    """Part 19's option in a strategy table: every bad value is refused by name."""
    message = _refusal({"name": "long", "preset": "general", "config": {"failure_gamma": value}})
    assert "failure_gamma" in message, message
    assert defect in message, message


@pytest.mark.parametrize(
    ("value", "defect"),
    [("max", "must be one of ['mean', 'every'], got 'max'"), (3, "got 3"), ([], "got []")],
)
def test_a_bad_failure_measure_names_the_file_and_field(value: Any, defect: str) -> None:
    """Part 20's option in a strategy table: refused by name."""
    config = {"failure_measure": value}
    message = _refusal({"name": "long", "preset": "general", "config": config})
    assert "failure_measure" in message, message
    assert defect in message, message


@pytest.mark.parametrize("name", ["general", "paper"])
def test_an_observation_wider_than_an_agent_takes_names_the_strategy(name: str) -> None:
    """A maze's lidar of 70 rays is 72 inputs: refused when the run's agent is built."""
    import bullet_maze  # noqa: F401  (registers BulletMaze-v0)

    env = gym.make("BulletMaze-v0", maze="open", observation="lidar", lidar_rays=70)
    config = _parse({"name": "wide", "preset": name})
    with pytest.raises(ConfigError, match=r"\[strategy 'wide'\].*72 dimensions, at most 64"):
        factory.make_agent(config, config.strategy("wide"), env, seed=0)
    env.close()


@pytest.mark.parametrize(
    ("strategy", "defect"),
    [
        (
            {"name": "flips", "preset": "general", "config": {"policy_splits": 1}},
            "policy_splits: expected true or false, got 1",
        ),
        (
            {"name": "flips", "preset": "general", "config": {"policy_splits": "no"}},
            "policy_splits: expected true or false, got 'no'",
        ),
        (
            {"name": "flips", "preset": "general", "config": {"policy_splits": [True]}},
            "policy_splits: expected true or false, got [True]",
        ),
        (
            {
                "name": "flips",
                "preset": "general",
                "config": {"model_split_epochs": None, "policy_splits": True},
            },
            "policy_splits = True needs model_split_epochs",
        ),
        (
            {"name": "flips", "config": {"planning": "sweep", "policy_splits": True}},
            "policy_splits = True needs model_split_epochs",
        ),
    ],
)
def test_bad_policy_splits_name_the_file_and_field(strategy: dict[str, Any], defect: str) -> None:
    """Part 21's option in a strategy table: every bad value is refused by name, and without
    model splits the option that needs them is named."""
    message = _refusal(strategy)
    assert defect in message, message
