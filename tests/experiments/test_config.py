"""Experiment files: the shipped ones load, errors name the file and the key."""

from __future__ import annotations

from pathlib import Path

import pytest

from experiments.config import (
    ConfigError,
    dumps,
    load_config,
    parse_config,
    same_experiment,
    with_overrides,
)


def _broken(data: dict, **edits: object) -> dict:
    for path, value in edits.items():
        section, key = path.split("__")
        if section == "strategy0":
            data["strategy"][0][key] = value
        else:
            data[section][key] = value
    return data


def test_small_config_values(small_config):
    assert small_config.runs == 3
    assert small_config.env.max_episode_steps == 300
    assert [s.name for s in small_config.strategies] == ["eps", "adaptive+tabu"]
    assert small_config.strategies[0].exploration_params == {"epsilon": 0.015}
    assert small_config.baseline_name == "eps"


@pytest.mark.parametrize(
    ("edits", "named"),
    [
        ({"experiment__runz": 3}, "runz"),
        ({"experiment__runs": 0}, "runs"),
        ({"experiment__episodes": "many"}, "episodes"),
        ({"env__mode": "wobbly"}, "mode"),
        ({"env__max_episode_steps": True}, "max_episode_steps"),
        ({"strategy0__epsilon": 0.1}, "epsilon"),
        ({"strategy0__agent": "forest"}, "agent"),
        ({"strategy0__name": "a/b"}, "name"),
        ({"experiment__baseline": "nope"}, "baseline"),
        ({"strategy0__resolution": 4}, "resolution"),
    ],
)
def test_errors_name_the_key(small_data, edits, named):
    with pytest.raises(ConfigError) as error:
        parse_config(_broken(small_data, **edits), source="bad.toml")
    message = str(error.value)
    assert "bad.toml" in message
    assert named in message


def test_grid_needs_resolution(small_data):
    data = small_data
    data["strategy"].append({"name": "grid", "agent": "grid"})
    with pytest.raises(ConfigError, match="resolution"):
        parse_config(data, source="grid.toml")
    data["strategy"][-1]["resolution"] = [10, 12]
    assert parse_config(data).strategies[-1].resolution == (10, 12)


def test_duplicate_strategy_names_rejected(small_data):
    data = small_data
    data["strategy"][1]["name"] = "eps"
    with pytest.raises(ConfigError, match="used twice"):
        parse_config(data)


def test_bad_toml_names_the_file(tmp_path: Path):
    path = tmp_path / "broken.toml"
    path.write_text("[experiment\nname = 1\n")
    with pytest.raises(ConfigError, match=r"broken\.toml"):
        load_config(path)


def test_missing_file_lists_shipped_ones():
    with pytest.raises(ConfigError, match="paper_fig4"):
        load_config("no_such_experiment")


def test_round_trip_through_toml(small_config, tmp_path: Path):
    path = tmp_path / "resolved.toml"
    path.write_text(dumps(small_config))
    again = load_config(path)
    assert same_experiment(small_config, again) == []
    assert again.strategies == small_config.strategies


def test_overrides_and_differences(small_config):
    more = with_overrides(small_config, runs=10, episodes=None)
    assert more.runs == 10
    assert more.episodes == small_config.episodes
    assert same_experiment(small_config, more) == []
    longer = with_overrides(small_config, episodes=500, max_episode_steps=100)
    assert same_experiment(small_config, longer) == ["env.max_episode_steps", "experiment.episodes"]
    with pytest.raises(ConfigError, match="--runs"):
        with_overrides(small_config, runs=0)


@pytest.mark.parametrize("name", ["paper_fig4", "quick"])
def test_shipped_experiments_load(name):
    config = load_config(name)
    assert config.strategies
    assert config.baseline_name in {s.name for s in config.strategies}


def test_paper_fig4_is_the_papers_setting():
    config = load_config("paper_fig4")
    assert (config.runs, config.episodes, config.env.max_episode_steps) == (30, 4000, 5000)
    assert config.agent["alpha"] == 0.3
    assert config.agent["gamma"] == 0.99
    explorations = {s.exploration for s in config.strategies}
    assert {"epsilon-greedy", "adaptive", "tabu", "adaptive+tabu", "vdbe"} <= explorations
    assert sum(s.agent == "grid" for s in config.strategies) >= 2
    epsilons = {
        s.exploration_params.get("epsilon")
        for s in config.strategies
        if s.exploration == "epsilon-greedy" and s.agent == "tree"
    }
    assert 0.015 in epsilons
    assert len(epsilons) >= 3


@pytest.mark.parametrize(
    ("edit", "named"),
    [
        (lambda d: d["agent"].update(alpah=0.3), "alpah"),
        (lambda d: d["agent"].update(alpha=7.0), "alpha"),
        (lambda d: d["strategy"][0]["exploration_params"].update(epsilonn=0.1), "epsilonn"),
        (lambda d: d["strategy"][1].update(exploration="curiosity"), "curiosity"),
        (lambda d: d["strategy"][1].update(config={"split_min_samples": 1}), "split_min_samples"),
    ],
)
def test_agent_parameters_are_checked_against_the_agent(small_data, edit, named):
    edit(small_data)
    with pytest.raises(ConfigError) as error:
        parse_config(small_data, source="agent.toml")
    assert "agent.toml" in str(error.value)
    assert named in str(error.value)


@pytest.mark.parametrize("name", ["paper_fig4", "quick", "readings_narrow", "readings_split"])
def test_shipped_experiments_pass_every_check(name):
    config = load_config(name)
    assert config.env.is_maze


def test_a_task_whose_package_is_missing_is_refused_by_name(monkeypatch):
    """An env that needs a package this machine lacks (Box2D for LunarLander on the CI machine)
    is refused when the file is read, naming the file, the task and the package, not when a
    worker first makes it."""
    from gymnasium.error import DependencyNotInstalled

    import experiments.config as config_module

    original = config_module.load_env_creator

    def missing(entry_point):
        if "box2d" in entry_point:
            raise DependencyNotInstalled("Box2D is not installed, run `pip install box2d`")
        return original(entry_point)

    monkeypatch.setattr(config_module, "load_env_creator", missing)
    data = {
        "experiment": {"name": "lander", "runs": 1, "episodes": 1},
        "task": [{"id": "CartPole-v1"}, {"id": "LunarLander-v3"}],
        "strategy": [{"name": "general", "preset": "general"}],
    }
    with pytest.raises(ConfigError) as error:
        parse_config(data, source="lander.toml")
    message = str(error.value)
    assert message.startswith("lander.toml: [task.1] id: 'LunarLander-v3' cannot be made"), message
    assert "Box2D is not installed" in message
