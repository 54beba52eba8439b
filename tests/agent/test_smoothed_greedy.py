"""The greedy choice over a smoothed Q-bar (``TreeConfig.greedy_smoothing``, issue 9, part 24's
probe; docs/paper-notes.md, "A greedy choice over a smoothed Q-bar")."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent import TreeAgent, TreeConfig, general_as_of, preset
from agent.serialization import config_from_data
from agent.tree_ensemble import TreeEnsembleAgent

LINE = spaces.Box(low=np.array([0.0]), high=np.array([1.0]), dtype=np.float64)


def _two_leaves(h: float, **fields: object) -> TreeAgent:
    """A 1-D tree split at 0.5: the left leaf prefers action 0 by 0.1, the right leaf action 1
    by 2."""
    config = TreeConfig(greedy_smoothing=h, **fields)  # type: ignore[arg-type]
    agent = TreeAgent(LINE, spaces.Discrete(2), "epsilon-greedy", seed=0, config=config)
    left, right = agent.split_leaf(0, 0, 0.5)
    agent.q[left] = [1.0, 0.9]
    agent.q[right] = [0.0, 2.0]
    return agent


def test_near_a_face_the_neighbours_row_counts() -> None:
    agent = _two_leaves(0.5)
    # at 0.45 the points 0.2, 0.45 and 0.7: rows [1, 0.9], [1, 0.9], [0, 2] -> action 1
    assert agent.predict(np.array([0.45])) == 1
    # at 0.1 the points -0.15 (the left leaf: the tree sends it there), 0.1 and 0.35
    assert agent.predict(np.array([0.1])) == 0
    assert agent.predict(np.array([0.7])) == 1
    off = _two_leaves(0.0)
    assert off.predict(np.array([0.45])) == 0  # the leaf's own row
    assert agent.leaf_info(agent.leaf_of(np.array([0.45]))).greedy == 0  # the leaf's own


def test_the_allowed_actions_still_bind() -> None:
    agent = _two_leaves(0.5, planning="sweep", greedy_min_epochs=1)
    assert agent.model is not None
    left = agent.leaf_of(np.array([0.45]))
    agent.model.add(left, 0, [0.3], -1.0, 0.9, None, -1)  # only action 0 has an epoch there
    assert agent.predict(np.array([0.45])) == 0


def test_a_single_input_cell_is_not_smoothed() -> None:
    cells = spaces.Box(np.array([0]), np.array([3]), dtype=np.int64)
    config = TreeConfig(greedy_smoothing=1.0, table_cells=64)
    agent = TreeAgent(cells, spaces.Discrete(2), "epsilon-greedy", seed=0, config=config)
    for i in range(4):
        agent.q[agent.leaf_of(np.array([i]))] = [1.0, 0.0] if i == 1 else [0.0, 5.0]
    assert agent.predict(np.array([1])) == 0  # its neighbours' rows are other states'


def test_an_unbounded_edge_is_not_moved_along() -> None:
    space = spaces.Box(np.array([-np.inf, 0.0]), np.array([np.inf, 1.0]), dtype=np.float64)
    config = TreeConfig(greedy_smoothing=1.0)
    agent = TreeAgent(space, spaces.Discrete(2), "epsilon-greedy", seed=0, config=config)
    left, right = agent.split_leaf(0, 1, 0.5)
    agent.q[left] = [1.0, 0.9]
    agent.q[right] = [0.0, 2.0]
    # dimension 0 is unbounded: only 0.4 +- 0.5 along dimension 1 (-0.1 and 0.9) are added
    assert agent.predict(np.array([1e9, 0.4])) == 1
    # the rows [1, 0.9], [1, 0.9] and [0, 2]: means 2 / 3 and 3.8 / 3; without smoothing 0
    assert agent.predict(np.array([-3.0, 0.0])) == 1
    agent.config = dataclasses.replace(config, greedy_smoothing=0.0)
    assert agent.predict(np.array([-3.0, 0.0])) == 0


def test_an_ensemble_smooths_its_mean_row() -> None:
    config = TreeConfig(greedy_smoothing=0.5, ensemble_trees=2, presplit_each_dimension=True)
    agent = TreeEnsembleAgent(LINE, spaces.Discrete(2), "epsilon-greedy", seed=0, config=config)
    for member in agent.members:
        for leaf in member.partition.leaves():
            low, _ = member.partition.leaf_bounds(leaf)
            member.q[leaf] = [1.0, 0.9] if low[0] < 0.3 else [0.0, 2.0]
    smoothed = dataclasses.replace(config, greedy_smoothing=0.0)
    plain = TreeEnsembleAgent(LINE, spaces.Discrete(2), "epsilon-greedy", seed=0, config=smoothed)
    for member, twin in zip(agent.members, plain.members, strict=True):
        twin.q = [list(row) for row in member.q]
    xs = np.linspace(0.0, 1.0, 101)
    with_smoothing = [agent.predict(np.array([x])) for x in xs]
    without = [plain.predict(np.array([x])) for x in xs]
    assert with_smoothing != without  # the smoothed choice moves the switch point
    assert with_smoothing[0] == without[0] == 0
    assert with_smoothing[-1] == without[-1] == 1


def test_training_is_the_same_run() -> None:
    env = gym.make("MountainCar-v0")
    general = preset("general")
    runs = []
    for h in (0.0, 1.0):
        config = dataclasses.replace(
            general_as_of(26),  # part 25's preset: the neighbours break the ties
            greedy_smoothing=h,
            greedy_smoothing_links=h > 0,
            greedy_tie_errors=0.5 if h > 0 else None,
        )
        agent = TreeEnsembleAgent(
            env.observation_space, env.action_space, general.make_exploration(), 1, config
        )
        history = agent.learn(env, 8, reset_seed=1)
        runs.append(([s.steps for s in history], agent.q, agent.n_leaves))
    assert runs[0] == runs[1]


@pytest.mark.parametrize("bad", [-0.1, 1.5, float("nan"), float("inf"), True, "0.5", None])
def test_bad_settings_are_refused_by_name(bad: object) -> None:
    with pytest.raises(ValueError, match="greedy_smoothing must be a number in") as refused:
        TreeConfig(greedy_smoothing=bad)  # type: ignore[arg-type]
    assert repr(bad) in str(refused.value)


def test_a_setting_from_a_file_is_checked_strictly() -> None:
    with pytest.raises(ValueError, match=r"where\.toml"):
        config_from_data({"greedy_smoothing": "half"}, "where.toml")
    assert config_from_data({"greedy_smoothing": 1}, "x").greedy_smoothing == 1


def test_a_policy_only_file_keeps_the_smoothing(tmp_path: Path) -> None:
    agent = _two_leaves(0.5)
    loaded = TreeAgent.load(agent.save(tmp_path / "policy.npz", policy_only=True))
    assert loaded.config.greedy_smoothing == 0.5
    xs = np.linspace(0.0, 1.0, 41)
    assert [loaded.predict(np.array([x])) for x in xs] == [agent.predict(np.array([x])) for x in xs]
