"""The greedy choice among supported actions (``TreeConfig.greedy_min_epochs``)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent import TreeAgent, TreeConfig, general_as_of, preset
from agent.smdp import greedy_among
from agent.tree_ensemble import TreeEnsembleAgent

LINE = spaces.Box(low=np.array([0.0]), high=np.array([1.0]), dtype=np.float64)


def _split_agent(k: int) -> tuple[TreeAgent, int, int]:
    """A 1-D tree split at 0.5 whose right child has one stored epoch of action 1 and an
    inherited Q-bar that ranks action 0 first."""
    config = TreeConfig(planning="sweep", greedy_min_epochs=k)
    agent = TreeAgent(LINE, spaces.Discrete(2), "epsilon-greedy", seed=0, config=config)
    agent.q[0] = [5.0, 1.0]
    left, right = agent.split_leaf(0, 0, 0.5)
    assert agent.q[right] == [5.0, 1.0]  # inherited from the root
    assert agent.model is not None
    agent.model.add(right, 1, [0.7], -1.0, 0.9, None, -1)  # one terminal epoch of action 1
    return agent, left, right


def test_greedy_among_breaks_ties_low_and_keeps_to_the_allowed() -> None:
    assert greedy_among([1.0, 3.0, 3.0]) == 1
    assert greedy_among([1.0, 3.0, 3.0], [0, 2]) == 2
    assert greedy_among([1.0, 3.0, 3.0], [0]) == 0


def test_an_unsupported_inherited_value_does_not_lead() -> None:
    agent, _, right = _split_agent(1)
    assert agent.support(right) == [0, 1]
    assert agent.predict(np.array([0.7])) == 1  # only action 1 has an epoch there
    assert agent.predict(np.array([0.2])) == 0  # no action has one: all compete
    off, _, _ = _split_agent(0)
    assert off.predict(np.array([0.7])) == 0  # the paper's greedy choice
    assert (agent.leaf_info(right).greedy, off.leaf_info(right).greedy) == (1, 0)  # as predict


def test_the_count_must_reach_k() -> None:
    agent, _, right = _split_agent(2)
    assert agent.predict(np.array([0.7])) == 0  # one epoch is short of 2: all compete
    assert agent.model is not None
    agent.model.add(right, 1, [0.8], -1.0, 0.9, None, -1)
    assert agent.predict(np.array([0.7])) == 1


def test_exploration_still_sees_every_action() -> None:
    agent, _, _ = _split_agent(1)
    picks = {agent.predict(np.array([0.7]), deterministic=False) for _ in range(200)}
    assert picks == {0, 1}  # epsilon-greedy's own greedy part and its random draws


def test_an_ensemble_needs_the_support_in_every_tree() -> None:
    config = TreeConfig(
        planning="sweep", greedy_min_epochs=1, ensemble_trees=2, presplit_each_dimension=True
    )
    agent = TreeEnsembleAgent(LINE, spaces.Discrete(2), "epsilon-greedy", seed=0, config=config)
    x = [0.7]
    leaves = agent._leaves(x)
    for member, leaf in zip(agent.members, leaves, strict=True):
        member.q[leaf] = [5.0, 1.0]
    first = agent.members[0].model
    assert first is not None
    first.add(leaves[0], 1, x, -1.0, 0.9, None, -1)
    assert agent.predict(np.array(x)) == 0  # tree 1 holds no epoch of action 1
    second = agent.members[1].model
    assert second is not None
    second.add(leaves[1], 1, x, -1.0, 0.9, None, -1)
    assert agent.predict(np.array(x)) == 1


def test_training_is_the_same_run(tmp_path: Path) -> None:
    """The option changes what ``predict`` reports, never a training step."""
    env = gym.make("MountainCar-v0")
    general = preset("general")
    runs = []
    for k in (0, 2):
        config = dataclasses.replace(general.config, greedy_min_epochs=k, greedy_cell_epochs=None)
        agent = TreeEnsembleAgent(
            env.observation_space, env.action_space, general.make_exploration(), 1, config
        )
        history = agent.learn(env, 8, reset_seed=1)
        runs.append(([h.steps for h in history], agent.q, agent.n_leaves))
    assert runs[0] == runs[1]


def _trained(k: int) -> TreeEnsembleAgent:
    env = gym.make("MountainCar-v0")
    general = preset("general")  # part 24's rule alone: no tie-break reads the counts
    config = dataclasses.replace(general_as_of(24), greedy_min_epochs=k, greedy_cell_epochs=None)
    agent = TreeEnsembleAgent(
        env.observation_space, env.action_space, general.make_exploration(), 3, config
    )
    agent.learn(env, 12, reset_seed=3)
    return agent


def test_a_policy_only_file_acts_like_the_full_one(tmp_path: Path) -> None:
    agent = _trained(2)
    full = TreeAgent.load(agent.save(tmp_path / "full.npz"))
    policy = TreeAgent.load(agent.save(tmp_path / "policy.npz", policy_only=True))
    assert policy.saved_support is not None
    states = np.random.default_rng(0).uniform([-1.2, -0.07], [0.6, 0.07], size=(2000, 2))
    acts = [agent.predict(s) for s in states]
    assert acts == [full.predict(s) for s in states] == [policy.predict(s) for s in states]
    plain = [max(range(3), key=agent.q[agent.leaf_of(s)].__getitem__) for s in states]
    assert acts != plain  # the option changed some choices of this agent


def _damaged_support(tmp_path: Path, change: object) -> str:
    agent = _trained(2)
    path = agent.save(tmp_path / "policy.npz", policy_only=True)
    arrays = dict(np.load(path, allow_pickle=False))
    if change is None:
        del arrays["support"]
    else:
        arrays["support"] = change(arrays["support"])  # type: ignore[operator]
    np.savez(tmp_path / "damaged.npz", **arrays)
    with pytest.raises(ValueError, match=r"damaged\.npz") as refused:
        TreeAgent.load(tmp_path / "damaged.npz")
    return str(refused.value)


@pytest.mark.parametrize(
    ("change", "named"),
    [
        (None, "missing entries ['support']"),
        (lambda a: a[:-1], "entry 'support' has shape"),
        (lambda a: a[:, :2], "entry 'support' has shape"),
        (lambda a: a - 1, "counts outside [0, model_window = 32]"),
        (lambda a: a + 33, "counts outside [0, model_window = 32]"),
        (lambda a: a.astype(np.float64), "entry 'support' has dtype float64"),
        (lambda a: a.reshape(-1), "entry 'support' has 1 dimensions"),
    ],
)
def test_a_damaged_support_entry_is_refused(tmp_path: Path, change: object, named: str) -> None:
    assert named in _damaged_support(tmp_path, change)


def test_a_support_entry_the_config_does_not_ask_for_is_refused(tmp_path: Path) -> None:
    agent = _trained(0)
    path = agent.save(tmp_path / "policy.npz", policy_only=True)
    arrays = dict(np.load(path, allow_pickle=False))
    assert "support" not in arrays
    arrays["support"] = np.zeros_like(arrays["visits"])
    np.savez(tmp_path / "damaged.npz", **arrays)
    with pytest.raises(ValueError, match=r"unknown entries \['support'\]"):
        TreeAgent.load(tmp_path / "damaged.npz")


@pytest.mark.parametrize(
    ("settings", "named"),
    [
        ({"greedy_min_epochs": -1, "planning": "sweep"}, "must be an int >= 0, got -1"),
        ({"greedy_min_epochs": True, "planning": "sweep"}, "must be an int >= 0, got True"),
        ({"greedy_min_epochs": 2.0, "planning": "sweep"}, "must be an int >= 0, got 2.0"),
        ({"greedy_min_epochs": "2", "planning": "sweep"}, "must be an int >= 0, got '2'"),
        ({"greedy_min_epochs": 2}, "needs planning = 'sweep'"),
        ({"greedy_min_epochs": 33, "planning": "sweep"}, "more than model_window = 32"),
        ({"greedy_min_epochs": 5, "planning": "sweep", "model_window": 4}, "model_window = 4"),
    ],
)
def test_bad_settings_are_refused_by_name(settings: dict, named: str) -> None:
    with pytest.raises(ValueError, match="greedy_min_epochs") as refused:
        TreeConfig(**settings)
    assert named in str(refused.value)


def test_a_setting_from_a_file_is_checked_strictly() -> None:
    from agent.serialization import config_from_data

    with pytest.raises(ValueError, match=r"where\.toml"):
        config_from_data({"greedy_min_epochs": 1.5, "planning": "sweep"}, "where.toml")
    config = config_from_data({"greedy_min_epochs": 3, "planning": "sweep"}, "x")
    assert config.greedy_min_epochs == 3
