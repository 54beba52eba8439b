"""Save and load: a non-executable file after which the agent acts and learns identically."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

from agent import GridAgent, TreeAgent, TreeConfig
from agent.learner import SMDPAgent


def build(kind: str, env: gym.Env, strategy: str) -> SMDPAgent:
    config = TreeConfig(split_min_samples=100, error_buffer="window")
    if kind == "tree":
        return TreeAgent(env.observation_space, env.action_space, strategy, 4, config)
    return GridAgent(env.observation_space, env.action_space, strategy, 4, config, resolution=7)


@pytest.mark.parametrize(
    ("kind", "strategy"),
    [("tree", "adaptive+tabu"), ("tree", "vdbe"), ("tree", "epsilon-greedy"), ("grid", "tabu")],
)
def test_round_trip_acts_and_continues_identically(
    tmp_path: Path, make_corridor: Callable[..., gym.Env], kind: str, strategy: str
) -> None:
    agent = build(kind, make_corridor(), strategy)
    agent.learn(make_corridor(), 25, reset_seed=1)
    path = tmp_path / "agent.npz"
    agent.save(path)
    loaded = type(agent).load(path)

    assert type(loaded) is type(agent)
    assert loaded.q == agent.q
    assert loaded.visits == agent.visits
    assert repr(loaded.exploration) == repr(agent.exploration)
    assert loaded.render() == agent.render()
    probe = np.random.default_rng(0).uniform(0, 1, size=(200, 2))
    assert [loaded.predict(x) for x in probe] == [agent.predict(x) for x in probe]

    later = agent.learn(make_corridor(), 15, reset_seed=9)
    later_loaded = loaded.learn(make_corridor(), 15, reset_seed=9)
    assert later_loaded == later
    assert loaded.q == agent.q
    assert loaded.n_leaves == agent.n_leaves


def test_file_is_plain_arrays_and_json(
    tmp_path: Path, make_corridor: Callable[..., gym.Env]
) -> None:
    agent = build("tree", make_corridor(), "adaptive+tabu")
    agent.learn(make_corridor(), 10)
    agent.save(tmp_path / "a.npz")
    with np.load(tmp_path / "a.npz", allow_pickle=False) as data:
        meta = json.loads(str(data["metadata"]))
        assert data["q"].shape == (agent.partition.n_ids, 4)
    assert meta["kind"] == "tree"
    assert meta["exploration"]["name"] == "adaptive+tabu"
    assert meta["config"]["split_min_samples"] == 100


def test_suffix_is_optional(tmp_path: Path, make_corridor: Callable[..., gym.Env]) -> None:
    agent = build("tree", make_corridor(), "greedy")
    agent.save(tmp_path / "plain")
    assert (tmp_path / "plain.npz").is_file()
    assert TreeAgent.load(tmp_path / "plain").q == agent.q


def test_loading_the_wrong_kind_or_file_fails(
    tmp_path: Path, make_corridor: Callable[..., gym.Env]
) -> None:
    build("grid", make_corridor(), "greedy").save(tmp_path / "grid.npz")
    with pytest.raises(ValueError, match="GridAgent, not a TreeAgent"):
        TreeAgent.load(tmp_path / "grid.npz")
    np.savez(tmp_path / "other.npz", x=np.zeros(2))
    with pytest.raises(ValueError, match="metadata"):
        TreeAgent.load(tmp_path / "other.npz")
