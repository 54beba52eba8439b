"""TreeConfig.leaves_per_terminal: a leaf budget that grows with the terminal transitions seen."""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

import bullet_maze  # noqa: F401 (registers the env)
from agent import TreeAgent, TreeConfig, preset
from agent.fast_loop import ineligible_reason
from agent.partition_tree import GatedPartitionTree, PartitionTree
from agent.tree_ensemble import tree_agent_class

FINE = TreeConfig(split_min_samples=20, split_min_variance=0.0, max_epoch_steps=10)


def test_the_default_keeps_the_papers_tree() -> None:
    agent = TreeAgent(*_spaces(), "epsilon-greedy", 0, TreeConfig())
    assert type(agent.partition) is PartitionTree
    assert TreeConfig().leaves_per_terminal == 0


@pytest.mark.parametrize("bad", [-1, 1.5, True, "8"])
def test_a_bad_budget_is_refused_by_name(bad: Any) -> None:
    with pytest.raises((ValueError, TypeError), match="leaves_per_terminal"):
        TreeConfig(leaves_per_terminal=bad)


def test_no_split_before_the_first_terminal_transition(train_corridor: Callable[..., Any]) -> None:
    # the goal is out of reach in 200 steps: no episode terminates
    config = dataclasses.replace(FINE, leaves_per_terminal=8)
    agent, history = train_corridor(config, 5, goal=(0.95, 0.95), goal_radius=0.01)
    assert not any(s.success for s in history)
    assert agent.n_leaves == 1
    ungated, _ = train_corridor(FINE, 5, goal=(0.95, 0.95), goal_radius=0.01)
    assert ungated.n_leaves > 1  # the same run without the gate splits


def test_the_budget_grows_by_its_step_per_terminal(train_corridor: Callable[..., Any]) -> None:
    config = dataclasses.replace(FINE, leaves_per_terminal=2)
    agent, history = train_corridor(config, 40)
    partition = agent.partition
    assert isinstance(partition, GatedPartitionTree)
    goals = sum(s.success for s in history)
    assert partition.terminals == goals > 0
    assert partition.leaf_budget == min(1 + 2 * goals, config.max_leaves)
    assert 1 < agent.n_leaves <= partition.leaf_budget


def test_the_presplit_is_the_budgets_base() -> None:
    config = TreeConfig(presplit_each_dimension=True, leaves_per_terminal=3)
    agent = TreeAgent(*_spaces(), "epsilon-greedy", 0, config)
    assert isinstance(agent.partition, GatedPartitionTree)
    assert agent.partition.initial_leaves == agent.n_leaves == 4
    assert agent.partition.leaf_budget == 4


def test_the_count_is_saved_and_learning_continues_the_same(
    make_corridor: Callable[..., Any], train_corridor: Callable[..., Any], tmp_path: Path
) -> None:
    config = dataclasses.replace(FINE, leaves_per_terminal=2)
    agent, _ = train_corridor(config, 20)
    loaded = TreeAgent.load(agent.save(tmp_path / "gated"))
    assert isinstance(loaded.partition, GatedPartitionTree)
    assert loaded.partition.terminals == agent.partition.terminals  # type: ignore[attr-defined]
    env_a, env_b = make_corridor(), make_corridor()
    a = [s.steps for s in agent.learn(env_a, 10, reset_seed=5)]
    b = [s.steps for s in loaded.learn(env_b, 10, reset_seed=5)]
    assert a == b
    assert agent.n_leaves == loaded.n_leaves


def test_the_fast_loop_leaves_a_gated_tree_to_the_reference() -> None:
    env = gym.make("BulletMaze-v0", mode="kinematic")
    config = TreeConfig(leaves_per_terminal=4)
    agent = TreeAgent(env.observation_space, env.action_space, "epsilon-greedy", 0, config)
    assert ineligible_reason(agent, env) is not None
    env.close()


def test_the_general_preset_with_a_budget_builds() -> None:
    config = dataclasses.replace(preset("general").config, leaves_per_terminal=16)
    agent = tree_agent_class(config)(*_spaces(), "adaptive+tabu", 0, config)
    assert isinstance(agent.partition, GatedPartitionTree)


def _spaces() -> tuple[Any, Any]:
    return spaces.Box(0.0, 1.0, shape=(2,), dtype=np.float64), spaces.Discrete(4)


@pytest.mark.parametrize("bad", [-1, 2.5, True, "3", None])
def test_a_tampered_terminal_count_is_refused_by_name(
    train_corridor: Callable[..., Any], tmp_path: Path, bad: Any
) -> None:
    config = dataclasses.replace(FINE, leaves_per_terminal=2)
    agent, _ = train_corridor(config, 5)
    path = agent.save(tmp_path / "gated")
    with np.load(path, allow_pickle=False) as data:
        arrays = {name: data[name].copy() for name in data.files}
    meta = json.loads(arrays.pop("metadata").tobytes())
    meta["learner"]["gate"]["terminals"] = bad
    target = tmp_path / "tampered.npz"
    np.savez(target, metadata=np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8), **arrays)
    with pytest.raises(ValueError, match=r"tampered.*terminals"):
        TreeAgent.load(target)
