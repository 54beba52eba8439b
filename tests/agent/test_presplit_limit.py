"""``TreeConfig.presplit_max_dimensions`` and ``presplit_beyond_dimensions``: the presplit of
an input with many dimensions (issue 9, part 17; docs/paper-notes.md, "Inputs with many
dimensions")."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from agent import TreeAgent, TreeConfig, preset
from agent.partition_tree import PartitionTree

PRESPLIT = TreeConfig(presplit_each_dimension=True)


def cut_dimensions(tree: PartitionTree) -> set[int]:
    """The dimensions along which some leaf is narrower than the root."""
    cut: set[int] = set()
    for leaf in tree.leaves():
        low, high = tree.leaf_bounds(leaf)
        for d in range(tree.dims):
            if (low[d], high[d]) != (tree.root_low[d], tree.root_high[d]):
                cut.add(d)
    return cut


def test_without_a_limit_too_many_dimensions_name_the_field_to_set() -> None:
    with pytest.raises(ValueError, match=r"2\^38 leaves.*presplit_max_dimensions"):
        PartitionTree([0.0] * 38, [1.0] * 38, PRESPLIT)


@pytest.mark.parametrize(
    ("beyond", "leaves", "cut"), [(0, 1, set()), (2, 4, {0, 1}), (3, 8, {0, 1, 2})]
)
def test_an_input_beyond_the_limit_splits_only_its_first_dimensions(
    beyond: int, leaves: int, cut: set[int]
) -> None:
    config = dataclasses.replace(
        PRESPLIT, presplit_max_dimensions=3, presplit_beyond_dimensions=beyond
    )
    tree = PartitionTree([0.0] * 5, [1.0] * 5, config)
    assert tree.n_leaves == leaves
    assert cut_dimensions(tree) == cut
    for leaf in tree.leaves():  # each cut at the midpoint
        low, high = tree.leaf_bounds(leaf)
        assert all(high[d] - low[d] == 0.5 for d in cut)


def test_more_dimensions_beyond_than_the_input_has_split_each_once() -> None:
    config = dataclasses.replace(PRESPLIT, presplit_max_dimensions=2, presplit_beyond_dimensions=16)
    assert PartitionTree([0.0] * 3, [1.0] * 3, config).n_leaves == 8


@pytest.mark.parametrize("beyond", [0, 2, 8])
def test_an_input_within_the_limit_is_presplit_as_before(beyond: int) -> None:
    config = dataclasses.replace(
        PRESPLIT, presplit_max_dimensions=6, presplit_beyond_dimensions=beyond
    )
    low, high = [-1.0, 0.0, -math.inf, 2.0, -5.0, 0.0], [1.0, 3.0, math.inf, 4.0, 5.0, 1.0]
    limited, unlimited = PartitionTree(low, high, config), PartitionTree(low, high, PRESPLIT)
    assert limited.n_leaves == unlimited.n_leaves == 64
    bounds = [limited.leaf_bounds(leaf) for leaf in limited.leaves()]
    assert bounds == [unlimited.leaf_bounds(leaf) for leaf in unlimited.leaves()]


def test_the_first_dimensions_split_an_unbounded_one_at_zero() -> None:
    config = dataclasses.replace(PRESPLIT, presplit_max_dimensions=1, presplit_beyond_dimensions=2)
    tree = PartitionTree([-math.inf, 0.0, 0.0], [math.inf, 4.0, 1.0], config)
    assert tree.n_leaves == 4
    assert sorted({tuple(tree.leaf_bounds(leaf)[0][:2]) for leaf in tree.leaves()}) == [
        (-math.inf, 0.0),
        (-math.inf, 2.0),
        (0.0, 0.0),
        (0.0, 2.0),
    ]


def test_initial_depth_still_applies_beyond_the_limit() -> None:
    config = dataclasses.replace(PRESPLIT, initial_depth=2, presplit_max_dimensions=1)
    assert PartitionTree([0.0] * 4, [1.0] * 4, config).n_leaves == 4


@pytest.mark.parametrize(
    ("field", "value", "defect"),
    [
        ("presplit_max_dimensions", -1, "got -1"),
        ("presplit_max_dimensions", 17, "got 17"),
        ("presplit_max_dimensions", 2.5, "got 2.5"),
        ("presplit_max_dimensions", True, "got True"),
        ("presplit_max_dimensions", "8", "got '8'"),
        ("presplit_beyond_dimensions", -1, "got -1"),
        ("presplit_beyond_dimensions", 17, "got 17"),
        ("presplit_beyond_dimensions", None, "got None"),
        ("presplit_beyond_dimensions", False, "got False"),
        ("presplit_beyond_dimensions", "2", "got '2'"),
    ],
)
def test_bad_values_are_refused_by_name(field: str, value: Any, defect: str) -> None:
    with pytest.raises((TypeError, ValueError), match=field) as error:
        TreeConfig(**{field: value})
    assert defect in str(error.value)


def test_the_general_preset_learns_saves_and_loads_on_the_lidar_maze(tmp_path: Path) -> None:
    """The maze seen through its 38-input lidar: refused by the presplit before part 17."""
    general = preset("general")
    env = gym.make("BulletMaze-v0", maze="open", observation="lidar", max_episode_steps=60)
    assert env.observation_space.shape == (38,)
    agent = general.agent(env.observation_space, env.action_space, seed=3)
    assert agent.n_leaves == 2**general.config.presplit_beyond_dimensions == 16
    agent.learn(env, 3, reset_seed=0)
    path = agent.save(tmp_path / "lidar")
    loaded = type(agent).load(path)
    obs, _ = env.reset(seed=9)
    assert loaded.n_leaves == agent.n_leaves
    assert loaded.predict(obs) == agent.predict(obs)
    assert loaded.config == agent.config


def test_a_lidar_of_more_rays_than_an_agent_takes_is_refused_by_name() -> None:
    env = gym.make("BulletMaze-v0", maze="open", observation="lidar", lidar_rays=70)
    with pytest.raises(ValueError, match=r"72 dimensions, at most 64.*lidar_rays"):
        preset("general").agent(env.observation_space, env.action_space, seed=0)


def test_a_wide_box_trains_with_the_general_preset() -> None:
    """Twenty inputs (a user's sensors), the first four presplit; eight keep every split."""
    box = spaces.Box(-1.0, 1.0, (20,), np.float64)
    agent = preset("general").agent(box, spaces.Discrete(3), seed=0)
    assert isinstance(agent, TreeAgent)
    assert agent.n_leaves == 16
    assert agent.predict(np.zeros(20)) in range(3)
    eight = spaces.Box(-1.0, 1.0, (8,), np.float64)
    assert preset("general").agent(eight, spaces.Discrete(3), seed=0).n_leaves == 256
