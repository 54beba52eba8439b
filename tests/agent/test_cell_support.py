"""The greedy choice's count in a single-input leaf (``TreeConfig.greedy_cell_epochs``, issue 9,
part 24; docs/paper-notes.md, "A greedy choice among supported actions")."""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Callable
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent import TreeAgent, TreeConfig, adapt_env, preset
from agent.serialization import config_from_data
from agent.tree_ensemble import TreeEnsembleAgent, tree_agent_class

CELLS = spaces.Box(np.array([0]), np.array([3]), dtype=np.int64)  # four inputs: 0, 1, 2, 3
LINE = spaces.Box(np.array([0.0]), np.array([4.0]), dtype=np.float64)


def _agent(space: spaces.Box, k: int, cell: int | None, **fields: object) -> TreeAgent:
    """Leaf 0's Q-bar ranks action 0 first; only action 1 has a stored epoch there (one)."""
    config = TreeConfig(planning="sweep", greedy_min_epochs=k, greedy_cell_epochs=cell, **fields)  # type: ignore[arg-type]
    agent = TreeAgent(space, spaces.Discrete(2), "epsilon-greedy", seed=0, config=config)
    leaf = agent.leaf_of(np.array([1]))
    agent.q[leaf] = [5.0, 1.0]
    assert agent.model is not None
    agent.model.add(leaf, 1, [1.0], -1.0, 0.9, None, -1)
    return agent


def test_a_leaf_holds_one_input_only_on_integer_cells() -> None:
    table = _agent(CELLS, 2, 1, table_cells=64)
    assert table.n_leaves == 4
    assert all(table.holds_one_input(leaf) for leaf in table.partition.leaves())
    root = _agent(CELLS, 2, 1)  # no table: the root holds all four integers
    assert [root.holds_one_input(leaf) for leaf in root.partition.leaves()] == [False]
    left, right = root.split_leaf(0, 0, 1.7)  # [-0.5, 1.7) holds 0 and 1; [1.7, 3.5) 2 and 3
    assert not root.holds_one_input(left)
    assert not root.holds_one_input(right)
    _, one = root.split_leaf(right, 0, 2.2)  # [2.2, 3.5) holds 3 alone, though 1.3 wide
    assert root.holds_one_input(one)
    floats = _agent(LINE, 2, 1)
    floats.split_leaf(0, 0, 0.5)
    assert not any(floats.holds_one_input(leaf) for leaf in floats.partition.leaves())


def test_an_unbounded_integer_dimension_is_never_one_input() -> None:
    space = spaces.Box(np.array([0]), np.array([np.iinfo(np.int64).max]), dtype=np.int64)
    agent = TreeAgent(space, spaces.Discrete(2), "epsilon-greedy", seed=0, config=TreeConfig())
    assert not agent.holds_one_input(0)


def test_a_cell_asks_its_own_count() -> None:
    assert _agent(CELLS, 2, 1, table_cells=64).predict(np.array([1])) == 1  # one epoch is enough
    assert _agent(CELLS, 2, None, table_cells=64).predict(np.array([1])) == 0  # 2 asked
    assert _agent(CELLS, 1, 0, table_cells=64).predict(np.array([1])) == 0  # 0: no support asked
    assert _agent(CELLS, 2, 1).predict(np.array([1])) == 0  # the root holds four inputs: 2 asked
    assert _agent(LINE, 2, 1).predict(np.array([1.0])) == 0  # a float leaf: 2 asked
    assert _agent(LINE, 1, 3).predict(np.array([1.0])) == 1  # ... and 1 where 1 is asked


def test_partition_pictures_follow_the_cell_rule() -> None:
    agent = _agent(CELLS, 2, 1, table_cells=64)
    leaf = agent.leaf_of(np.array([1]))
    assert agent.leaf_info(leaf).greedy == 1 == agent.predict(np.array([1]))


def _narrow_to_input_one(member: TreeAgent) -> None:
    """Split ``member``'s leaf of input 1 at half-integers until it holds input 1 alone, with
    Q-bar ranking action 0 first and one stored epoch of action 1 there."""
    x = [1.0]
    while not member.holds_one_input(leaf := member.leaf_of(np.array(x))):
        low, _high = member.partition.leaf_bounds(leaf)
        member.split_leaf(leaf, 0, 0.5 if low[0] < 0.5 else 1.5)
    member.q[leaf] = [5.0, 1.0]
    assert member.model is not None
    member.model.add(leaf, 1, x, -1.0, 0.9, None, -1)


def test_an_ensemble_uses_the_cell_count_only_where_every_tree_holds_one_input() -> None:
    config = TreeConfig(
        planning="sweep",
        greedy_min_epochs=2,
        greedy_cell_epochs=1,
        ensemble_trees=2,
        presplit_each_dimension=True,
    )
    agent = TreeEnsembleAgent(CELLS, spaces.Discrete(2), "epsilon-greedy", seed=0, config=config)
    first, second = agent.members
    for member, leaf in zip(agent.members, agent._leaves([1.0]), strict=True):
        assert not member.holds_one_input(leaf)  # each presplit half holds two inputs
        member.q[leaf] = [5.0, 1.0]
        assert member.model is not None
        member.model.add(leaf, 1, [1.0], -1.0, 0.9, None, -1)
    assert agent.predict(np.array([1])) == 0  # 2 asked, 1 stored: all compete
    _narrow_to_input_one(first)
    assert agent.predict(np.array([1])) == 0  # tree 1's leaf still holds two inputs
    _narrow_to_input_one(second)
    assert agent.predict(np.array([1])) == 1  # every tree's leaf is input 1 alone


def test_a_policy_only_file_keeps_the_cell_rule(tmp_path: Path) -> None:
    agent = _agent(CELLS, 2, 1, table_cells=64)
    loaded = TreeAgent.load(agent.save(tmp_path / "policy.npz", policy_only=True))
    assert loaded.config.greedy_cell_epochs == 1
    states = [np.array([i]) for i in range(4)]
    assert [loaded.predict(s) for s in states] == [agent.predict(s) for s in states]
    assert loaded.predict(np.array([1])) == 1


def test_taxi_delivers_from_every_start_with_one_epoch_asked_in_its_cells(
    greedy_return: Callable,
) -> None:
    """The dev case the option was made for (Taxi seed 0, 600 episodes; part 23's Taxi rows):
    two epochs asked in every leaf leave out a good action of one cell that had one, and the
    greedy taxi loops from one start of 10; the preset's one epoch in a cell delivers from all.
    Training is the same run both ways, so one agent is scored under both configs."""
    warnings.simplefilter("ignore")
    env = adapt_env(gym.make("Taxi-v4"))
    config = dataclasses.replace(preset("general").config, greedy_min_epochs=2)
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, "adaptive+tabu", 0, config
    )
    agent.learn(env, 600, reset_seed=0)
    returns = {}
    for cell in (1, None):
        agent.config = dataclasses.replace(config, greedy_cell_epochs=cell)
        returns[cell] = [greedy_return(env, agent, 10_000 + i) for i in range(10)]
    assert min(returns[1]) > 0.0, returns
    assert min(returns[None]) == -200.0, returns  # the 200-step limit, never delivered


@pytest.mark.parametrize(
    ("settings", "named"),
    [
        ({"greedy_cell_epochs": -1}, "must be an int >= 0 or None, got -1"),
        ({"greedy_cell_epochs": True}, "must be an int >= 0 or None, got True"),
        ({"greedy_cell_epochs": 1.0}, "must be an int >= 0 or None, got 1.0"),
        ({"greedy_cell_epochs": "1"}, "must be an int >= 0 or None, got '1'"),
        ({"greedy_cell_epochs": 1, "greedy_min_epochs": 0}, "needs greedy_min_epochs > 0"),
        ({"greedy_cell_epochs": 33}, "more than model_window = 32"),
        ({"greedy_cell_epochs": 5, "model_window": 4, "greedy_min_epochs": 4}, "model_window = 4"),
    ],
)
def test_bad_settings_are_refused_by_name(settings: dict, named: str) -> None:
    fields = {"planning": "sweep", "greedy_min_epochs": 2, **settings}
    with pytest.raises(ValueError, match="greedy_cell_epochs") as refused:
        TreeConfig(**fields)
    assert named in str(refused.value)


def test_a_setting_from_a_file_is_checked_strictly() -> None:
    base = {"planning": "sweep", "greedy_min_epochs": 2}
    with pytest.raises(ValueError, match=r"where\.toml"):
        config_from_data({**base, "greedy_cell_epochs": 1.5}, "where.toml")
    with pytest.raises(ValueError, match=r"where\.toml"):
        config_from_data({**base, "greedy_cell_epochs": "none"}, "where.toml")
    assert config_from_data({**base, "greedy_cell_epochs": 1}, "x").greedy_cell_epochs == 1
