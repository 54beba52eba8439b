"""Neighbours break the greedy choice's statistical ties (``TreeConfig.greedy_tie_errors`` and
``greedy_smoothing_links`` with ``greedy_smoothing``; issue 9, part 25; docs/paper-notes.md,
"Neighbours break the ties")."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent import TreeAgent, TreeConfig, general_as_of, preset
from agent.leaf_model import LeafModel
from agent.serialization import config_from_data
from agent.tree_ensemble import TreeEnsembleAgent

LINE = spaces.Box(low=np.array([0.0]), high=np.array([1.0]), dtype=np.float64)
RULE = {"greedy_smoothing": 1.0, "greedy_smoothing_links": True, "greedy_tie_errors": 0.5}


def _split_line(**fields: object) -> tuple[TreeAgent, int, int]:
    """A 1-D tree split at 0.5 with the model on: the left leaf prefers action 0 by 0.05, the
    right leaf action 1 by 2. No epochs are stored yet."""
    config = TreeConfig(planning="sweep", **{**RULE, **fields})  # type: ignore[arg-type]
    agent = TreeAgent(LINE, spaces.Discrete(2), "epsilon-greedy", seed=0, config=config)
    left, right = agent.split_leaf(0, 0, 0.5)
    agent.q[left] = [0.5, 0.45]
    agent.q[right] = [0.0, 2.0]
    return agent, left, right


def _terminal_epochs(model: LeafModel, leaf: int, action: int, rewards: list[float]) -> None:
    for reward in rewards:  # a terminal epoch's eq. (8) target is its reward part
        model.add(leaf, action, [0.25], reward, 0.9, None, -1)


def test_standard_errors_by_hand() -> None:
    model = LeafModel(n_actions=3, window=8)
    q = [[0.0, 0.0, 0.0], [4.0, 1.0, 0.0]]
    _terminal_epochs(model, 0, 0, [1.0, 0.0])  # sd 0.7071, se 0.5
    model.add(0, 1, [0.1], 0.0, 0.5, [0.9], 1)  # targets 0 + 0.5 * 4 = 2 ...
    model.add(0, 1, [0.2], 1.0, 0.5, [0.9], 1)  # ... and 1 + 2 = 3: se 0.5
    model.add(0, 1, [0.3], 2.0, 0.5, [0.9], 1)  # and 4: sd 1, se 1 / sqrt(3)
    _terminal_epochs(model, 0, 2, [7.0])  # one epoch: no spread measured
    errors = model.errors(0, q)
    assert errors[0] == pytest.approx(0.5)
    assert errors[1] == pytest.approx(1 / math.sqrt(3))
    assert errors[2] == math.inf
    assert model.errors(1, q) == [math.inf] * 3  # no epochs at all


def test_links_are_the_moves_the_model_stored() -> None:
    model = LeafModel(n_actions=2, window=2)
    model.add(3, 1, [0.1], 0.0, 0.9, [0.2], 5)  # from 3 to 5
    model.add(5, 0, [0.2], 0.0, 0.9, [0.3], 5)  # 5 to itself: not a link
    _terminal_epochs(model, 7, 0, [1.0])  # a terminal: no end leaf
    assert model.linked(3, 5)
    assert model.linked(5, 3)
    assert not model.linked(3, 7)
    assert not model.linked(5, 7)
    assert model.links() == [(3, 5)]
    model.add(3, 1, [0.1], 0.0, 0.9, [0.2], 4)
    model.add(3, 1, [0.1], 0.0, 0.9, [0.2], 4)  # the window of 2 drops the move to 5
    assert not model.linked(3, 5)
    assert model.links() == [(3, 4)]


def test_a_tie_goes_to_the_linked_neighbours() -> None:
    agent, left, right = _split_line()
    assert agent.model is not None
    _terminal_epochs(agent.model, left, 0, [1.0, 0.0])  # se 0.5
    _terminal_epochs(agent.model, left, 1, [0.9, 0.1])  # se 0.4: gap 0.05 <= 0.5 * 0.64
    # without a link the moved points (-0.05: the left leaf itself; 0.95) are left out
    assert agent.predict(np.array([0.45])) == 0
    agent.model.add(right, 0, [0.7], 0.0, 0.9, [0.4], left)  # the agent moved right -> left
    # rows [0.5, 0.45] and [0, 2]: means 0.25 and 1.225
    assert agent.predict(np.array([0.45])) == 1
    assert agent.leaf_info(left).greedy == 0  # the leaf's own choice is reported unchanged


def test_actions_the_evidence_separates_keep_the_leafs_choice() -> None:
    agent, left, right = _split_line()
    assert agent.model is not None
    _terminal_epochs(agent.model, left, 0, [0.5, 0.5])  # se 0: nothing is tied
    _terminal_epochs(agent.model, left, 1, [0.45, 0.45])
    agent.model.add(right, 0, [0.7], 0.0, 0.9, [0.4], left)
    assert agent.predict(np.array([0.45])) == 0
    # the same leaf with the tie rule off: every action competes on the smoothed row
    agent.config = dataclasses.replace(agent.config, greedy_tie_errors=None)
    assert agent.predict(np.array([0.45])) == 1


def test_without_links_every_moved_point_counts() -> None:
    agent, left, _ = _split_line(greedy_smoothing_links=False)
    assert agent.model is not None
    _terminal_epochs(agent.model, left, 0, [1.0, 0.0])
    _terminal_epochs(agent.model, left, 1, [0.9, 0.1])
    # rows [0.5, 0.45] twice (the state and -0.05) and [0, 2]: 1/3 against 2.9/3
    assert agent.predict(np.array([0.45])) == 1


def test_the_tie_rule_reads_only_the_allowed_actions() -> None:
    agent, left, right = _split_line(greedy_min_epochs=2)
    assert agent.model is not None
    _terminal_epochs(agent.model, left, 0, [1.0, 0.0])
    _terminal_epochs(agent.model, left, 1, [0.9])  # one epoch: action 1 is not allowed
    agent.model.add(right, 0, [0.7], 0.0, 0.9, [0.4], left)
    agent.q[left] = [0.45, 0.5]
    assert agent.predict(np.array([0.45])) == 0  # the only allowed action


def test_an_ensemble_needs_every_changed_tree_to_link() -> None:
    config = TreeConfig(planning="sweep", ensemble_trees=2, presplit_each_dimension=True, **RULE)  # type: ignore[arg-type]
    agent = TreeEnsembleAgent(LINE, spaces.Discrete(2), "epsilon-greedy", seed=0, config=config)
    for member in agent.members:
        for leaf in member.partition.leaves():
            low, _ = member.partition.leaf_bounds(leaf)
            member.q[leaf] = [1.0, 0.9] if low[0] < 0.3 else [0.0, 2.0]
    xs = np.linspace(0.0, 1.0, 101)
    unlinked = [agent.predict(np.array([x])) for x in xs]
    agent.config = dataclasses.replace(
        config, greedy_smoothing=0.0, greedy_smoothing_links=False, greedy_tie_errors=None
    )
    own = [agent.predict(np.array([x])) for x in xs]
    agent.config = config
    assert unlinked == own  # no stored epochs: every action ties, but no neighbour is linked
    first = agent.members[0]
    pairs = {(a, b) for a in first.partition.leaves() for b in first.partition.leaves() if a < b}
    first.saved_links = pairs  # tree 0 links everything, tree 1 nothing
    partial = [agent.predict(np.array([x])) for x in xs]
    for x, choice, alone in zip(xs, partial, own, strict=True):
        if choice == alone:
            continue
        # a neighbour counted: a moved point whose leaf only tree 0 changes (tree 1 keeps its)
        low, high = first.partition.leaf_bounds(first.leaf_of(np.array([x])))
        moved = [x - (high[0] - low[0]), x + (high[0] - low[0])]
        second = agent.members[1]
        assert any(
            second.leaf_of(np.array([m])) == second.leaf_of(np.array([x]))
            and first.leaf_of(np.array([m])) != first.leaf_of(np.array([x]))
            for m in moved
        )
    for member in agent.members:
        leaves = member.partition.leaves()
        member.saved_links = {(a, b) for a in leaves for b in leaves if a < b}
    linked = [agent.predict(np.array([x])) for x in xs]
    assert linked != own  # the neighbours move the switch point
    # at 0 the point one width right lies in both trees' right leaves: rows [1, 0.9], [0, 2]
    assert (own[0], linked[0]) == (0, 1)
    assert linked[-1] == own[-1] == 1  # at 1 no moved point leaves the leaves


def test_training_is_the_same_run_and_the_rule_is_part_25s_preset() -> None:
    general = preset("general")
    part25 = general_as_of(25)  # part 27 put the ancestors in its place
    assert {name: getattr(part25, name) for name in RULE} == RULE
    env = gym.make("MountainCar-v0")
    runs, choices = [], []
    off = dataclasses.replace(
        part25, greedy_smoothing=0.0, greedy_smoothing_links=False, greedy_tie_errors=None
    )
    grid = [(p, v) for p in np.linspace(-1.2, 0.6, 30) for v in np.linspace(-0.07, 0.07, 30)]
    states = [np.array(point) for point in grid]
    for config in (part25, off):
        agent = TreeEnsembleAgent(
            env.observation_space, env.action_space, general.make_exploration(), 1, config
        )
        history = agent.learn(env, 10, reset_seed=1)
        runs.append(([s.steps for s in history], agent.q, agent.n_leaves))
        choices.append([agent.predict(s) for s in states])
    assert runs[0] == runs[1]
    assert choices[0] != choices[1]  # the rule acts on a trained tree


def test_a_policy_only_file_acts_like_the_full_one(tmp_path: Path) -> None:
    env = gym.make("MountainCar-v0")
    general = preset("general")
    agent = TreeEnsembleAgent(
        env.observation_space, env.action_space, general.make_exploration(), 2, general_as_of(25)
    )
    agent.learn(env, 10, reset_seed=2)
    policy = TreeAgent.load(agent.save(tmp_path / "policy.npz", policy_only=True))
    full = TreeAgent.load(agent.save(tmp_path / "full.npz"))
    again = TreeAgent.load(policy.save(tmp_path / "again.npz", policy_only=True))
    states = [np.array([p, v]) for p in np.linspace(-1.2, 0.6, 25) for v in (-0.06, 0.0, 0.06)]
    want = [agent.predict(s) for s in states]
    assert [policy.predict(s) for s in states] == want
    assert [full.predict(s) for s in states] == want
    assert [again.predict(s) for s in states] == want
    assert policy.saved_links is not None
    assert policy.saved_errors is not None
    assert agent.model is not None
    assert policy.saved_links == set(agent.model.links())


def _rewrite(path: Path, out: Path, name: str, array: np.ndarray) -> Path:
    with np.load(path) as data:
        arrays = {k: data[k] for k in data.files}
    arrays[name] = array
    np.savez(out, **arrays)  # type: ignore[arg-type]
    return out


@pytest.mark.parametrize(
    ("entry", "make", "defect"),
    [
        ("errors", lambda e, _: -e - 1.0, "negative or not a number"),
        ("errors", lambda e, _: np.full_like(e, np.nan), "negative or not a number"),
        ("errors", lambda e, _: e[:, :1], "entry 'errors' has shape"),
        ("errors", lambda e, _: e.astype(np.float32), "entry 'errors' has dtype"),
        ("links", lambda _, n: np.array([[0, n]], dtype=np.int64), "not leaf ids a < b below"),
        ("links", lambda _, n: np.array([[1, 1]], dtype=np.int64), "not leaf ids a < b below"),
        ("links", lambda _, n: np.array([[2, 1]], dtype=np.int64), "not leaf ids a < b below"),
        ("links", lambda _, n: np.array([[-1, 1]], dtype=np.int64), "not leaf ids a < b below"),
        ("links", lambda _, n: np.zeros((2, 3), dtype=np.int64), "expected (pairs, 2)"),
        ("links", lambda _, n: np.zeros(4, dtype=np.int64), "entry 'links' has 1 dimensions"),
    ],
)
def test_a_damaged_policy_only_file_is_refused_by_name(
    tmp_path: Path, entry: str, make: object, defect: str
) -> None:
    agent, left, right = _split_line()
    assert agent.model is not None
    _terminal_epochs(agent.model, left, 0, [1.0, 0.0])
    agent.model.add(right, 0, [0.7], 0.0, 0.9, [0.4], left)
    path = agent.save(tmp_path / "policy.npz", policy_only=True)
    with np.load(path) as data:
        errors = data["errors"]
    bad = _rewrite(path, tmp_path / "bad.npz", entry, make(errors, len(agent.q)))  # type: ignore[operator]
    with pytest.raises(ValueError, match=r"bad\.npz") as refused:
        TreeAgent.load(bad)
    assert defect in str(refused.value)


@pytest.mark.parametrize(
    ("fields", "defect"),
    [
        ({"greedy_tie_errors": 0}, "greedy_tie_errors must be a number > 0 or None, got 0"),
        ({"greedy_tie_errors": -1.0}, "got -1.0"),
        ({"greedy_tie_errors": math.nan}, "got nan"),
        ({"greedy_tie_errors": math.inf}, "got inf"),
        ({"greedy_tie_errors": True}, "got True"),
        ({"greedy_tie_errors": "0.5"}, "got '0.5'"),
        ({"greedy_smoothing_links": 1}, "greedy_smoothing_links must be a bool, got 1"),
        (
            {"greedy_tie_errors": 0.5, "greedy_smoothing": 0.0, "greedy_smoothing_links": False},
            "greedy_tie_errors = 0.5 needs greedy_smoothing > 0",
        ),
        (
            {"greedy_smoothing_links": True, "greedy_smoothing": 0.0},
            "greedy_smoothing_links = True needs greedy_smoothing > 0",
        ),
        (
            {"greedy_tie_errors": 0.5, "planning": "none", "greedy_smoothing_links": False},
            "greedy_tie_errors = 0.5 needs planning = 'sweep'",
        ),
        (
            {"greedy_smoothing_links": True, "planning": "none"},
            "greedy_smoothing_links = True needs planning = 'sweep'",
        ),
    ],
)
def test_bad_settings_are_refused_by_name(fields: dict[str, object], defect: str) -> None:
    with pytest.raises(ValueError, match="TreeConfig") as refused:
        TreeConfig(**{"planning": "sweep", **RULE, **fields})  # type: ignore[arg-type]
    assert defect in str(refused.value)


def test_a_setting_from_a_file_is_checked_strictly() -> None:
    base = {"planning": "sweep", "greedy_smoothing": 1.0}
    with pytest.raises(ValueError, match=r"where\.toml"):
        config_from_data({**base, "greedy_tie_errors": "half"}, "where.toml")
    with pytest.raises(ValueError, match=r"where\.toml"):
        config_from_data({**base, "greedy_smoothing_links": "yes"}, "where.toml")
    loaded = config_from_data({**base, "greedy_tie_errors": 1, "greedy_smoothing_links": True}, "x")
    assert (loaded.greedy_tie_errors, loaded.greedy_smoothing_links) == (1, True)
