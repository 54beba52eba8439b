"""The tree's ancestors break the greedy choice's ties (``TreeConfig.greedy_tie_ancestors``;
issue 9, part 27; docs/paper-notes.md, "Ancestors compare leaf by leaf")."""

from __future__ import annotations

import dataclasses
import math
import statistics
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent import GridAgent, TreeAgent, TreeConfig, general_as_of, preset
from agent.ancestor_ties import PairedSums, ancestors_choice
from agent.leaf_model import LeafModel
from agent.serialization import config_from_data
from agent.tree_ensemble import TreeEnsembleAgent

LINE = spaces.Box(low=np.array([0.0]), high=np.array([1.0]), dtype=np.float64)
RULE = {
    "greedy_smoothing": 0.0,
    "greedy_smoothing_links": False,
    "greedy_tie_errors": 1.0,
    "greedy_tie_ancestors": 1.0,
}


def _terminal_epochs(model: LeafModel, leaf: int, action: int, rewards: list[float]) -> None:
    for reward in rewards:  # a terminal epoch's eq. (8) target is its reward part
        model.add(leaf, action, [0.1], reward, 0.9, None, -1)


def _four_leaves(**fields: object) -> tuple[TreeAgent, list[int]]:
    """A 1-D tree cut at 0.5, then at 0.25 and 0.75: leaves [0, .25), [.25, .5), [.5, .75),
    [.75, 1] in that order. The first leaf's two actions are tied (wide spread, close Q-bar)."""
    fields = {"planning": "sweep", "greedy_min_epochs": 1, **RULE, **fields}
    config = TreeConfig(**fields)  # type: ignore[arg-type]
    agent = TreeAgent(LINE, spaces.Discrete(2), "epsilon-greedy", seed=0, config=config)
    left, right = agent.split_leaf(0, 0, 0.5)
    leaves = [*agent.split_leaf(left, 0, 0.25), *agent.split_leaf(right, 0, 0.75)]
    assert agent.model is not None
    _terminal_epochs(agent.model, leaves[0], 0, [1.0, -1.0])
    _terminal_epochs(agent.model, leaves[0], 1, [1.0, -1.0])
    agent.q[leaves[0]] = [0.45, 0.5]  # the leaf alone prefers action 1, within its errors
    return agent, leaves


def test_paired_sums_by_hand() -> None:
    agent, leaves = _four_leaves()
    assert agent.model is not None
    for leaf, row in zip(leaves[1:], ([1.0, 0.0], [2.0, 1.0], [3.0, 2.0]), strict=True):
        agent.q[leaf] = row
        _terminal_epochs(agent.model, leaf, 0, [0.0])
        _terminal_epochs(agent.model, leaf, 1, [0.0])
    sums = PairedSums(2)
    tree = agent.partition
    parent = tree.parent(leaves[0])
    diffs = [-0.05, 1.0]  # Q-bar(0) - Q-bar(1) in the parent's two leaves
    mean, se = sums.difference(sums.at(parent, tree, agent.q, agent.support), 0, 1)
    assert mean == pytest.approx(statistics.mean(diffs))
    assert se == pytest.approx(statistics.stdev(diffs) / math.sqrt(2))
    assert sums.difference(sums.at(parent, tree, agent.q, agent.support), 1, 0) == (-mean, se)
    root = sums.at(0, tree, agent.q, agent.support)
    diffs += [1.0, 1.0]
    assert sums.difference(root, 0, 1)[0] == pytest.approx(statistics.mean(diffs))
    assert sums.difference(root, 0, 1)[1] == pytest.approx(statistics.stdev(diffs) / 2)
    # one shared leaf measures no spread
    assert sums.difference(sums.at(leaves[1], tree, agent.q, agent.support), 0, 1) == (0, math.inf)


def test_the_nearest_ancestor_that_separates_the_actions_decides() -> None:
    agent, leaves = _four_leaves()
    assert agent.model is not None
    state = np.array([0.1])
    assert agent.predict(state) == 1  # no other leaf has both actions: the leaf's best stands
    agent.q[leaves[1]] = [1.0, 0.0]
    _terminal_epochs(agent.model, leaves[1], 0, [0.0])
    _terminal_epochs(agent.model, leaves[1], 1, [0.0])
    # the parent: differences -0.05 and 1, mean 0.475, se 0.525: still tied, and the root has
    # no more shared leaves, so its best among them (action 0, by the mean) is chosen
    agent.forget_greedy_cache()  # Q-bar and the model were edited by hand
    assert agent.predict(state) == 0
    agent.q[leaves[1]] = [0.45, 0.5]
    agent.forget_greedy_cache()  # Q-bar and the model were edited by hand
    assert agent.predict(state) == 1
    for leaf in leaves[2:]:  # the root's other leaves prefer 0 by 1 each
        agent.q[leaf] = [1.0, 0.0]
        _terminal_epochs(agent.model, leaf, 0, [0.0])
        _terminal_epochs(agent.model, leaf, 1, [0.0])
    # parent: two -0.05s, se 0 but mean negative: action 1 leads by 0.05 > 1 * 0: decides 1
    agent.forget_greedy_cache()  # Q-bar and the model were edited by hand
    assert agent.predict(state) == 1
    agent.q[leaves[1]] = [0.5, 0.45]  # the parent now sees -0.05 and +0.05: tied (mean 0)
    # the root: -0.05, 0.05, 1, 1: mean 0.5, se 0.29: action 0 leads by more than one error
    agent.forget_greedy_cache()  # Q-bar and the model were edited by hand
    assert agent.predict(state) == 0
    assert agent.leaf_info(leaves[0]).greedy == 1  # the leaf's own choice is reported unchanged


def test_a_leaf_where_only_one_action_was_tried_is_left_out() -> None:
    agent, leaves = _four_leaves()
    assert agent.model is not None
    agent.q[leaves[1]] = [-5.0, 10.0]  # would decide for action 1 by far ...
    _terminal_epochs(agent.model, leaves[1], 1, [0.0])  # ... but action 0 was never tried there
    for leaf in leaves[2:]:
        agent.q[leaf] = [1.0, 0.0]
        _terminal_epochs(agent.model, leaf, 0, [0.0])
        _terminal_epochs(agent.model, leaf, 1, [0.0])
    # the root: -0.05, 1, 1 (mean 0.65, se 0.35): action 0
    assert agent.predict(np.array([0.1])) == 0


def test_ancestors_choice_by_hand() -> None:
    # two trees; tree 0: leaf 3 -> 1 -> 0, tree 1: leaf 2 -> 0
    parents = [{3: 1, 1: 0, 0: -1}, {2: 0, 0: -1}]
    table = {  # (tree, node) -> {(a, b): (mean of Q(a) - Q(b), se)}
        (0, 1): {(0, 1): (0.3, 1.0), (0, 2): (2.0, 0.1), (1, 2): (1.7, 0.1)},
        (1, 0): {(0, 1): (0.1, 1.0), (0, 2): (1.0, 0.1), (1, 2): (0.9, 0.1)},
        (0, 0): {(0, 1): (-2.0, 0.1), (0, 2): (1.0, 0.1), (1, 2): (3.0, 0.1)},
    }

    def difference(t: int, node: int, a: int, b: int) -> tuple[float, float]:
        mean, se = table[(t, node)][(min(a, b), max(a, b))]
        return (mean if a < b else -mean), se

    def parent(t: int, node: int) -> int:
        return parents[t][node]

    # round 1 (nodes 1 and 0): 0 - 1 = 0.2 +- 0.707, 0 - 2 = 1.5 +- 0.071: action 2 is cut;
    # round 2 (nodes 0 and 0, tree 1 stays at its root): 0 - 1 = -0.95 +- 0.50: action 1
    assert ancestors_choice([2, 0, 1], [3, 2], parent, difference, 1.0) == 1
    # with z 30 nothing separates: the last round's best by summed means (1: 2.9, 0: 0.05)
    assert ancestors_choice([2, 0, 1], [3, 2], parent, difference, 30.0) == 1
    assert ancestors_choice([0], [3, 2], parent, difference, 1.0) == 0  # nothing tied
    assert ancestors_choice([1, 0], [0, 0], parent, difference, 1.0) == 1  # roots: no ancestor


def _trained(config: TreeConfig, episodes: int = 12, seed: int = 3) -> TreeEnsembleAgent:
    env = gym.make("MountainCar-v0")
    agent = TreeEnsembleAgent(
        env.observation_space, env.action_space, preset("general").make_exploration(), seed, config
    )
    agent.learn(env, episodes, reset_seed=seed)
    return agent


def _ancestors_config() -> TreeConfig:
    # part 27's preset, before part 30's trial widths (which need the ancestors)
    return dataclasses.replace(general_as_of(29), **RULE)  # type: ignore[arg-type]


STATES = [np.array([p, v]) for p in np.linspace(-1.2, 0.6, 21) for v in np.linspace(-0.07, 0.07, 9)]


def _reference_choice(agent: TreeAgent, x: np.ndarray, z: float) -> int:
    """The rule written out directly: the leaves below each ancestor gathered by walking the
    tree, the mean and standard error of each pair's differences by ``statistics``."""
    tree = agent.partition
    leaf = tree.leaf_of(list(x))
    tied = agent._tied([agent], [leaf], agent.q[leaf], agent._supported([agent], [leaf]), z)

    def below(node: int) -> list[int]:
        halves = tree.children(node)
        return [node] if halves is None else below(halves[0]) + below(halves[1])

    def diff(node: int, a: int, b: int) -> tuple[float, float]:
        ds = [
            agent.q[leaf][a] - agent.q[leaf][b]
            for leaf in below(node)
            if agent.support(leaf)[a] > 0 and agent.support(leaf)[b] > 0
        ]
        if len(ds) < 2:
            return 0.0, math.inf
        return statistics.fmean(ds), statistics.stdev(ds) / math.sqrt(len(ds))

    node = tree.parent(leaf)
    while node >= 0 and len(tied) > 1:
        score = {a: sum(diff(node, a, b)[0] for b in tied if b != a) for a in tied}
        best = max(tied, key=score.__getitem__)
        leads = {a: diff(node, best, a) for a in tied if a != best}
        tied = [best] + [a for a, (lead, se) in leads.items() if not lead > z * se]
        node = tree.parent(node)
    return tied[0]


def test_a_trained_agent_follows_the_rule_written_out() -> None:
    agent = _trained(_ancestors_config())
    choices = [agent.predict(s) for s in STATES]
    assert choices == [_reference_choice(agent, s, 1.0) for s in STATES]
    leaf_only = dataclasses.replace(agent.config, greedy_tie_ancestors=None, greedy_smoothing=1.0)
    agent.config = leaf_only  # the neighbours instead (part 25's rule, without links)
    assert [agent.predict(s) for s in STATES] != choices  # the ancestors change some choices


def test_training_is_the_same_run_and_the_sums_are_dropped_after_each_episode(
    tmp_path: Path,
) -> None:
    on = _ancestors_config()
    assert on == general_as_of(29)  # part 27's preset
    off = dataclasses.replace(on, greedy_tie_ancestors=None, greedy_smoothing=1.0)
    agents = [_trained(config) for config in (on, off)]
    assert agents[0].q == agents[1].q
    assert agents[0].n_leaves == agents[1].n_leaves
    agent = agents[0]
    [agent.predict(s) for s in STATES]  # fills the sums
    assert agent.paired_sums._sums
    env = gym.make("MountainCar-v0")
    agent.learn(env, 2, callback=lambda _: bool(agent.predict(STATES[0])) or True)
    assert not agent.paired_sums._sums  # dropped after the last episode
    fresh = TreeEnsembleAgent.load(agent.save(tmp_path / "full.npz"))
    assert [agent.predict(s) for s in STATES] == [fresh.predict(s) for s in STATES]


def test_the_leaves_errors_and_choices_are_cached_until_learn_or_a_split() -> None:
    agent = _trained(_ancestors_config())
    cached = [agent.predict(s) for s in STATES]  # fills the caches of errors and choices
    assert agent.leaf_errors
    for leaf, errors in agent.leaf_errors.items():
        assert errors == agent.action_errors(leaf)
    uncached = []
    for s in STATES:  # the same choices when every call computes its errors afresh
        agent.forget_greedy_cache()
        uncached.append(agent.predict(s))
    assert cached == uncached
    [agent.predict(s) for s in STATES]
    assert len(agent.leaf_choices) == len({agent.leaf_of(s) for s in STATES})  # one per leaf
    agent.config = dataclasses.replace(agent.config)  # an equal config, but a new object
    agent.predict(STATES[0])
    assert len(agent.leaf_choices) == 1  # a replaced config starts the choices afresh
    agent.learn(gym.make("MountainCar-v0"), 1)
    assert not agent.leaf_errors  # dropped after the episode
    assert not agent.leaf_choices
    assert not agent.paired_sums._sums
    agent.predict(STATES[0])
    leaf = agent.leaf_of(STATES[0])
    assert leaf in agent.leaf_errors
    agent.split_leaf(leaf, 0, float(np.mean(agent.partition.leaf_bounds(leaf)[0:2], axis=0)[0]))
    assert not agent.leaf_errors  # a split drops them
    assert not agent.leaf_choices


def test_a_hand_edit_needs_forget_greedy_cache() -> None:
    agent, leaves = _four_leaves()
    x = np.array([0.1])
    assert agent.model is not None
    _terminal_epochs(agent.model, leaves[1], 0, [0.0])  # a sibling where action 0 leads
    _terminal_epochs(agent.model, leaves[1], 1, [0.0])
    agent.q[leaves[1]] = [1.0, 0.0]
    assert agent.predict(x) == 0  # tied in the leaf (se 1): the ancestors lean to action 0
    assert agent.leaf_errors[leaves[0]] == [1.0, 1.0]
    _terminal_epochs(agent.model, leaves[0], 1, [0.0] * 200)  # action 1's spread collapses
    _terminal_epochs(agent.model, leaves[0], 0, [0.0] * 200)
    agent.q[leaves[0]] = [0.0, 0.5]
    assert agent.leaf_errors[leaves[0]] == [1.0, 1.0]  # the cache still holds the old errors
    assert agent.predict(x) == 0  # and the old choice
    agent.forget_greedy_cache()
    assert agent.predict(x) == 1  # separated now: the leaf's own best
    assert agent.leaf_errors[leaves[0]] == agent.action_errors(leaves[0])
    assert max(agent.leaf_errors[leaves[0]]) < 0.1


def test_a_policy_only_file_acts_like_the_full_one(tmp_path: Path) -> None:
    agent = _trained(_ancestors_config())
    policy = TreeAgent.load(agent.save(tmp_path / "policy.npz", policy_only=True))
    again = TreeAgent.load(policy.save(tmp_path / "again.npz", policy_only=True))
    want = [agent.predict(s) for s in STATES]
    assert [policy.predict(s) for s in STATES] == want
    assert [again.predict(s) for s in STATES] == want
    assert policy.model is not None  # an empty model: the counts come from the file
    assert not any(any(policy.model.counts(leaf)) for leaf in policy.partition.leaves())
    assert policy.saved_support is not None


def test_a_policy_only_file_keeps_the_counts_without_greedy_min_epochs(tmp_path: Path) -> None:
    agent, leaves = _four_leaves(greedy_min_epochs=0)
    agent.q[leaves[1]] = [1.0, 0.0]
    assert agent.model is not None
    _terminal_epochs(agent.model, leaves[1], 0, [0.0])
    _terminal_epochs(agent.model, leaves[1], 1, [0.0])
    policy = TreeAgent.load(agent.save(tmp_path / "policy.npz", policy_only=True))
    assert policy.saved_support is not None
    states = [np.array([x]) for x in np.linspace(0.0, 1.0, 41)]
    assert [policy.predict(s) for s in states] == [agent.predict(s) for s in states]


def test_an_ensemble_asks_every_trees_ancestors() -> None:
    config = dataclasses.replace(_ancestors_config(), ensemble_trees=2)
    agent = _trained(config, episodes=6)
    assert len(agent.members) == 2
    choices = [agent.predict(s) for s in STATES]
    assert set(choices) <= {0, 1, 2}
    assert all(member.paired_sums._sums for member in agent.members)


@pytest.mark.parametrize(
    ("fields", "defect"),
    [
        ({"greedy_tie_ancestors": 0}, "greedy_tie_ancestors must be a number > 0 or None, got 0"),
        ({"greedy_tie_ancestors": -1.0}, "got -1.0"),
        ({"greedy_tie_ancestors": math.nan}, "got nan"),
        ({"greedy_tie_ancestors": math.inf}, "got inf"),
        ({"greedy_tie_ancestors": True}, "got True"),
        ({"greedy_tie_ancestors": "1"}, "got '1'"),
        (
            {"greedy_tie_errors": None},
            "greedy_tie_ancestors = 1.0 needs greedy_tie_errors",
        ),
        (
            {"greedy_smoothing": 1.0},
            "greedy_tie_ancestors = 1.0 and greedy_smoothing = 1.0 are two ways",
        ),
        (
            {"greedy_tie_ancestors": None},
            "greedy_tie_errors = 1.0 needs greedy_smoothing > 0 or greedy_tie_ancestors",
        ),
        ({"planning": "none"}, "greedy_tie_errors = 1.0 needs planning = 'sweep'"),
    ],
)
def test_bad_settings_are_refused_by_name(fields: dict[str, object], defect: str) -> None:
    with pytest.raises(ValueError, match="TreeConfig") as refused:
        TreeConfig(**{"planning": "sweep", **RULE, **fields})  # type: ignore[arg-type]
    assert defect in str(refused.value)


def test_a_grid_has_no_ancestors() -> None:
    config = TreeConfig(planning="sweep", **RULE)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"greedy_tie_ancestors = 1\.0 needs the adaptive tree"):
        GridAgent(LINE, spaces.Discrete(2), "epsilon-greedy", 0, config, resolution=4)


def test_a_setting_from_a_file_is_checked_strictly() -> None:
    base = {"planning": "sweep", "greedy_tie_errors": 1.0}
    with pytest.raises(ValueError, match=r"where\.toml"):
        config_from_data({**base, "greedy_tie_ancestors": "one"}, "where.toml")
    with pytest.raises(ValueError, match=r"where\.toml"):
        config_from_data({**base, "greedy_tie_ancestors": -2}, "where.toml")
    loaded = config_from_data({**base, "greedy_tie_ancestors": 2}, "x")
    assert loaded.greedy_tie_ancestors == 2


def test_a_policy_only_file_without_its_counts_is_refused_by_name(tmp_path: Path) -> None:
    agent, _ = _four_leaves(greedy_min_epochs=0)
    path = agent.save(tmp_path / "policy.npz", policy_only=True)
    with np.load(path) as data:
        arrays = {k: data[k] for k in data.files if k != "support"}
    np.savez(tmp_path / "bad.npz", **arrays)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"bad\.npz") as refused:
        TreeAgent.load(tmp_path / "bad.npz")
    assert "support" in str(refused.value)
