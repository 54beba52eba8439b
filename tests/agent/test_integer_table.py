"""Integer inputs as cells, and ``TreeConfig.table_cells``: a tree that starts as a table of
them (issue 9, part 15; docs/paper-notes.md, "A table for integer inputs")."""

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
from agent.fast_loop import ineligible_reason
from agent.partition_tree import PartitionTree
from agent.spaces import integer_inputs, observation_bounds
from agent.tree_ensemble import tree_agent_class

TABLE = TreeConfig(table_cells=64)


def cell_boxes(tree: PartitionTree) -> list[tuple[list[float], list[float]]]:
    return sorted(tree.leaf_bounds(leaf) for leaf in tree.leaves())


def test_an_integer_box_is_cells_and_a_float_box_is_not() -> None:
    box = spaces.Box(np.array([0, -2]), np.array([4, 2]), dtype=np.int64)
    assert integer_inputs(box)
    assert observation_bounds(box, None) == ([-0.5, -2.5], [4.5, 2.5])
    assert observation_bounds(box, ([0.0, -2.0], [4.0, 2.0])) == ([0.0, -2.0], [4.0, 2.0])
    floats = spaces.Box(0.0, 4.0, (2,))
    assert not integer_inputs(floats)
    assert observation_bounds(floats, None) == ([0.0, 0.0], [4.0, 4.0])


def test_an_integer_dimension_at_its_dtype_extreme_is_unbounded() -> None:
    limits = np.iinfo(np.int32)
    box = spaces.Box(np.array([limits.min, 0]), np.array([limits.max, 3]), dtype=np.int32)
    low, high = observation_bounds(box, None, allow_unbounded=True)
    assert low == [-np.inf, -0.5]
    assert high == [np.inf, 3.5]
    with pytest.raises(ValueError, match="unbounded"):
        observation_bounds(box, None)


def test_small_integer_dtypes_keep_their_extremes_as_bounds() -> None:
    """An image's uint8 box runs from 0 to 255 for real; so does an int8 one's -128..127."""
    image = spaces.Box(0, 255, (2,), dtype=np.uint8)
    assert integer_inputs(image)
    assert observation_bounds(image, None) == ([-0.5, -0.5], [255.5, 255.5])
    small = spaces.Box(-128, 127, (1,), dtype=np.int8)
    assert observation_bounds(small, None) == ([-128.5], [127.5])
    agent = preset("general").agent(spaces.Box(0, 255, (1,), dtype=np.uint8), spaces.Discrete(2))
    assert agent.n_leaves == 256


def test_an_agent_on_an_unsigned_box_saves_and_loads(tmp_path: Path) -> None:
    box = spaces.Box(0, 9, (2,), dtype=np.uint16)
    agent = preset("general").agent(box, spaces.Discrete(3), seed=1)
    again = type(agent).load(agent.save(tmp_path / "grid"))
    assert again.observation_space == box
    assert again.n_leaves == agent.n_leaves == 100


def test_one_dimension_becomes_one_leaf_per_integer() -> None:
    tree = PartitionTree([-0.5], [4.5], TABLE, integer=True)
    assert tree.n_leaves == 5
    assert cell_boxes(tree) == [([k - 0.5], [k + 0.5]) for k in range(5)]
    assert len({tree.leaf_of([float(k)]) for k in range(5)}) == 5
    assert tree.depth == 3  # halved at each level: ceil(log2(5))


def test_several_dimensions_become_their_product_of_cells() -> None:
    """Blackjack's shape in small: 4 x 3 x 2 integers, 24 leaves, one per combination."""
    tree = PartitionTree([-0.5, -0.5, -0.5], [3.5, 2.5, 1.5], TABLE, integer=True)
    assert tree.n_leaves == 24
    cells = {(a, b, c) for a in range(4) for b in range(3) for c in range(2)}
    leaves = {tree.leaf_of([float(v) for v in cell]) for cell in cells}
    assert len(leaves) == 24
    for leaf in tree.leaves():
        low, high = tree.leaf_bounds(leaf)
        assert [h - lo for lo, h in zip(low, high, strict=True)] == [1.0, 1.0, 1.0]


def test_bounds_given_on_the_integers_themselves_cut_between_them() -> None:
    """A user's bounds of [0, 9] (not widened): the cuts are the half-integers inside, so the
    ten integers still get ten leaves (the edge ones half as wide)."""
    tree = PartitionTree([0.0], [9.0], TABLE, integer=True)
    assert tree.n_leaves == 10
    assert len({tree.leaf_of([float(k)]) for k in range(10)}) == 10


def test_more_cells_than_the_budget_or_float_inputs_keep_the_presplit() -> None:
    config = TreeConfig(table_cells=23, presplit_each_dimension=True)
    too_many = PartitionTree([-0.5, -0.5, -0.5], [3.5, 2.5, 1.5], config, integer=True)
    assert too_many.n_leaves == 8  # 24 cells > 23: the presplit, once per dimension
    floats = PartitionTree([-0.5], [4.5], TreeConfig(table_cells=64))
    assert floats.n_leaves == 1
    exact = PartitionTree([-0.5, -0.5], [3.5, 2.5], TreeConfig(table_cells=12), integer=True)
    assert exact.n_leaves == 12  # the budget is inclusive
    unbounded = PartitionTree([-np.inf], [np.inf], TABLE, integer=True)
    assert unbounded.n_leaves == 1


def test_no_child_is_narrower_than_one_integer() -> None:
    """A table leaf holds one integer: the split test, whatever its errors, cannot cut it; a
    leaf of two integers can only be cut between them."""
    tree = PartitionTree([-0.5], [1.5], TreeConfig(split_min_samples=4, min_leaf_fraction=0.01))
    assert tree.split_box(0)[3].tolist() == [0.02]
    integer = PartitionTree(
        [-0.5], [1.5], TreeConfig(split_min_samples=4, min_leaf_fraction=0.01), integer=True
    )
    assert integer.split_box(0)[3].tolist() == [1.0]
    children = integer.record(0, [[0.0], [0.0], [1.0], [1.0]], [-1.0, -1.0, 1.0, 1.0])
    assert children is not None
    assert [integer.leaf_bounds(c) for c in children] == [([-0.5], [0.5]), ([0.5], [1.5])]
    for child in children:
        errors = [-1.0, 1.0, -1.0, 1.0]
        assert integer.record(child, [[0.0]] * 4, errors) is None
    assert integer.n_leaves == 2


def test_the_table_replaces_initial_depth_and_the_presplit() -> None:
    config = TreeConfig(table_cells=64, initial_depth=3, presplit_each_dimension=True)
    tree = PartitionTree([-0.5], [5.5], config, integer=True)
    assert cell_boxes(tree) == [([k - 0.5], [k + 0.5]) for k in range(6)]


def test_a_table_agent_saves_and_continues_identically(tmp_path: Path) -> None:
    env = adapt_env(gym.make("FrozenLake-v1"))
    config = dataclasses.replace(preset("general").config, table_cells=16384)
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, "adaptive+tabu", 3, config
    )
    assert agent.n_leaves == 16
    assert agent.integer_inputs
    agent.learn(env, 30, reset_seed=0)
    path = agent.save(tmp_path / "lake")
    again = type(agent).load(path)
    assert again.partition.integer
    assert again.observation_space == agent.observation_space
    ours = [s.episode_return for s in agent.learn(env, 30, reset_seed=7)]
    theirs = [s.episode_return for s in again.learn(env, 30, reset_seed=7)]
    assert ours == theirs
    assert agent.q == again.q


def test_the_fast_loop_refuses_integer_inputs() -> None:
    box = spaces.Box(np.array([0, 0]), np.array([9, 9]), dtype=np.int64)
    agent = TreeAgent(box, spaces.Discrete(4), "epsilon-greedy", 0)
    assert ineligible_reason(agent, None) == "integer inputs (an integer-typed observation box)"


def test_taxi_is_learnt_as_a_table_and_not_without_one(greedy_return: Callable) -> None:
    """Taxi's 500 encoded states through adapt_env (one integer input), 600 episodes of the
    general preset: with the table the greedy taxi delivers from every one of 10 starts (the
    optimum averages about 8; a start's return is 20 minus its steps), without it (part 14's
    preset, the index split by the tree's tests) it delivers from none within the 200-step
    limit (development cases: Taxi seeds 0-2, docs/results.md, "Part 15")."""
    warnings.simplefilter("ignore")
    env = adapt_env(gym.make("Taxi-v4"))
    returns = {}
    for cells in (16384, None):
        config = dataclasses.replace(preset("general").config, table_cells=cells)
        agent = tree_agent_class(config)(
            env.observation_space, env.action_space, "adaptive+tabu", 0, config
        )
        agent.learn(env, 600, reset_seed=0)
        returns[cells] = [greedy_return(env, agent, 10_000 + i) for i in range(10)]
    assert min(returns[16384]) > 0.0, returns
    assert max(returns[None]) < 0.0, returns
