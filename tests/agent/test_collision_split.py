"""TreeConfig.collision_splits: a leaf is cut where one action's collided and free epochs part."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent import TreeConfig, general_as_of, preset
from agent.collision_split import choose_collided_only_split, choose_collision_split
from agent.exploration import make_exploration
from agent.leaf_model import LeafModel
from agent.tree_agent import TreeAgent
from agent.tree_ensemble import TreeEnsembleAgent, tree_agent_class

BOX = (np.array([0.0]), np.array([1.0]), np.array([0.01]))


def _cut(xs: list[float], collided: list[bool], box: Any = BOX) -> tuple[int, float] | None:
    firsts = np.array([[x] for x in xs], dtype=np.float64)
    return choose_collision_split(firsts, np.array(collided), *box)


def test_the_cut_between_the_free_and_the_collided_epochs() -> None:
    # free at 0.1, 0.2, 0.3; collided at 0.6, 0.7: the cut lies halfway between 0.3 and 0.6
    cut = _cut([0.6, 0.1, 0.7, 0.2, 0.3], [True, False, True, False, False])
    assert cut == (0, pytest.approx(0.45))


def test_one_label_or_one_epoch_is_no_split() -> None:
    assert _cut([0.1, 0.2, 0.3], [False, False, False]) is None
    assert _cut([0.1, 0.2, 0.3], [True, True, True]) is None
    assert _cut([0.4], [True]) is None


def test_a_cut_must_misplace_fewer_epochs_than_no_cut() -> None:
    # equal first inputs are never cut apart, so nothing can separate these two
    assert _cut([0.5, 0.5], [True, False]) is None
    # F T F T F: no cut misplaces the 2 collided; every cut misplaces 2 as well (after 0.1:
    # 0 + 2; after 0.3: 1 + 1; after 0.5: 1 + 1; after 0.7: 2 + 0), so none is taken
    assert _cut([0.1, 0.3, 0.5, 0.7, 0.9], [False, True, False, True, False]) is None


def test_ties_go_to_the_cut_nearest_the_middle() -> None:
    # F T T F: no cut misplaces 2; the cuts at 0.25 (0 + 1) and 0.7 (1 + 0) misplace 1 each,
    # the one at 0.5 misplaces 2; 0.7 is nearer the leaf's middle (0.5) than 0.25
    assert _cut([0.1, 0.4, 0.6, 0.8], [False, True, True, False]) == (0, pytest.approx(0.7))
    # two dimensions that separate alike: the cut nearer its leaf's middle wins (dimension 1
    # at 0.5 against dimension 0 at 0.55)
    firsts = np.array([[0.1, 0.30], [0.2, 0.35], [0.9, 0.65], [0.95, 0.7]])
    collided = np.array([False, False, True, True])
    box = (np.array([0.0, 0.0]), np.array([1.0, 1.0]), np.array([0.01, 0.01]))
    assert choose_collision_split(firsts, collided, *box) == (1, pytest.approx(0.5))


def test_a_child_narrower_than_the_smallest_leaf_is_not_made() -> None:
    # the only separating cuts lie in (0.2, 0.8); children must be at least 0.55 wide
    wide = (np.array([0.0]), np.array([1.0]), np.array([0.55]))
    assert _cut([0.1, 0.2, 0.8, 0.9], [False, False, True, True], wide) is None
    assert _cut([0.1, 0.2, 0.8, 0.9], [False, False, True, True]) == (0, pytest.approx(0.5))


class Post(gym.Env[np.ndarray, int]):
    """One step from x ~ U(0, 1), cut by a time limit (never terminal). Action 0 moves past a
    post left of 0.5 (+1) and hits it right of 0.5 (-1, ``info["collision"]``); action 1
    pays 0. ``report=False`` keeps the rewards and drops the collision flag."""

    observation_space = spaces.Box(0.0, 1.0, (1,), dtype=np.float64)
    action_space = spaces.Discrete(2)

    def __init__(self, report: bool = True) -> None:
        self.report = report

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        super().reset(seed=seed)
        self.x = float(self.np_random.uniform(0.0, 1.0))
        return np.array([self.x]), {}

    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        hit = action == 0 and self.x >= 0.5
        reward = 0.0 if action == 1 else (-1.0 if hit else 1.0)
        info = {"collision": hit} if self.report else {}
        return np.array([self.x]), reward, False, True, info


POST = TreeConfig(
    split_min_samples=10_000,  # the paper's test never runs: only collisions can split
    planning="sweep",
    presplit_each_dimension=False,
    collision_splits=True,
)


def _train(config: TreeConfig, episodes: int = 40, env: Post | None = None) -> TreeAgent:
    env = env if env is not None else Post()
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, "epsilon-greedy", 3, config
    )
    agent.learn(env, episodes, reset_seed=3)
    return agent


def test_the_post_is_found_from_the_collided_epochs() -> None:
    agent = _train(POST)
    assert isinstance(agent, TreeEnsembleAgent)  # the option runs on the ensemble's loop
    assert agent.n_leaves >= 2
    tree = agent.partition  # the root's cut is the first split
    assert tree._dim[0] == 0
    assert 0.4 < tree._threshold[0] < 0.6
    assert agent.predict(np.array([0.1])) == 0
    assert agent.predict(np.array([0.9])) == 1


def test_every_stored_epoch_is_marked_as_it_ended() -> None:
    agent = _train(POST)
    assert agent.model is not None
    marks = 0
    for leaf in agent.partition.leaves():
        firsts, collided = agent.model.collisions(leaf, 0)
        assert collided == [x[0] >= 0.5 for x in firsts]
        marks += sum(collided)
        assert agent.model.collisions(leaf, 1)[1] == [False] * agent.model.count(leaf, 1)
    assert marks > 0


def test_off_or_without_collisions_nothing_changes() -> None:
    off = _train(dataclasses.replace(POST, collision_splits=False))
    assert off.n_leaves == 1
    # an env that reports no collisions: the option leaves the run as it was, bit for bit
    quiet = _train(POST, env=Post(report=False))
    plain = _train(dataclasses.replace(POST, collision_splits=False), env=Post(report=False))
    assert quiet.n_leaves == plain.n_leaves == 1
    assert quiet.q == plain.q
    assert quiet.model is not None
    assert plain.model is not None
    assert quiet.model.state() == plain.model.state()


def test_the_agent_file_keeps_the_marks(tmp_path: Path) -> None:
    agent = _train(POST, 20)
    loaded = TreeAgent.load(agent.save(tmp_path / "post.npz"))
    assert loaded.config.collision_splits is True
    assert loaded.model is not None
    assert agent.model is not None
    assert loaded.model.state() == agent.model.state()
    assert any(entry[-1] is True for _, rs in loaded.model.state()["records"] for entry in rs)
    env = Post()
    agent.learn(env, 10, reset_seed=9)
    loaded.learn(env, 10, reset_seed=9)
    assert loaded.q == agent.q  # a loaded agent goes on as the saved one does


def test_model_files_without_marks_load_and_bad_marks_are_refused() -> None:
    old = {
        "window": 4,
        "records": [[0, [[[0.2], -1.0, 0.9, [0.3], 0]]]],
        "epochs": [[0, 1]],
        "preds": [[0, [[0, 1]]]],
        "heap": [],
        "priority": [],
    }
    model = LeafModel.from_state(2, old)
    firsts, collided = model.collisions(0, 0)
    assert [list(first) for first in firsts] == [[0.2]]
    assert collided == [False]
    assert model.state()["records"] == old["records"]  # written back as it was read
    for bad in (False, 1, "true", None):
        broken = dict(old, records=[[0, [[[0.2], -1.0, 0.9, [0.3], 0, bad]]]])
        with pytest.raises(ValueError, match="collision mark"):
            LeafModel.from_state(2, broken)
    for bad_entry in ([[0.2], -1.0, 0.9, [0.3]], "epoch", [[0.2], -1.0, 0.9, [0.3], 0, True, 1]):
        broken = dict(old, records=[[0, [bad_entry]]])
        with pytest.raises(ValueError, match="5 or 6 entries"):
            LeafModel.from_state(2, broken)


@pytest.mark.parametrize("bad", [1, 0, "yes", None, 1.0])
def test_bad_values_are_refused_by_name(bad: Any) -> None:
    with pytest.raises(ValueError, match="collision_splits"):
        dataclasses.replace(POST, collision_splits=bad)


def test_it_needs_the_model() -> None:
    with pytest.raises(ValueError, match=r"collision_splits.*planning = 'sweep'"):
        TreeConfig(collision_splits=True)


def test_the_paper_presets_leave_it_off() -> None:
    for name in ("paper", "paper-literal"):
        assert preset(name).config.collision_splits is False


def test_every_tree_of_an_ensemble_cuts_its_own_leaves() -> None:
    # tree 0's presplit lies on the post (0.5); tree 1's is offset from it (0.25), so only
    # tree 1 has a leaf that holds both sides of the post, and it cuts that leaf near 0.5
    config = dataclasses.replace(POST, presplit_each_dimension=True, ensemble_trees=2)
    env = Post()
    explore = make_exploration("epsilon-greedy", epsilon=0.5)  # collide again and again
    agent = TreeEnsembleAgent(env.observation_space, env.action_space, explore, 3, config)
    agent.learn(env, 60, reset_seed=3)
    assert isinstance(agent, TreeEnsembleAgent)
    first, second = agent.members
    assert first.partition.n_leaves == 2
    assert second.partition.n_leaves > 2
    cuts = [second.partition._threshold[i] for i in range(1, second.partition.n_ids)]
    assert any(0.4 < c < 0.6 for c in cuts if c == c)
    assert second.model is not None
    assert any(any(second.model.collisions(leaf, 0)[1]) for leaf in second.partition.leaves())


def test_the_general_preset_runs_classic_control_as_part_13_did() -> None:
    # CartPole reports no collisions: part 14's preset takes part 13's run, bit for bit (part
    # 16's optimism does change CartPole, whose rewards are positive: tests/agent/test_optimism)
    env = gym.make("CartPole-v1")
    runs = []
    for config in (general_as_of(14), general_as_of(13)):
        agent = tree_agent_class(config)(
            env.observation_space, env.action_space, "adaptive+tabu", 5, config
        )
        history = agent.learn(env, 15, reset_seed=5)
        runs.append(([h.episode_return for h in history], agent.q, agent.n_leaves))
    assert general_as_of(14).collision_splits is True
    assert runs[0] == runs[1]


@pytest.mark.parametrize("mark", [False, 1, "yes", None, [True]])
def test_a_tampered_mark_in_an_agent_file_is_refused_naming_the_file(
    tmp_path: Path, mark: Any
) -> None:
    path = _train(POST, 20).save(tmp_path / "post.npz")
    with np.load(path, allow_pickle=False) as data:
        arrays = {name: data[name].copy() for name in data.files}
    meta = json.loads(arrays.pop("metadata").tobytes())
    marked = [
        entry for _, rs in meta["learner"]["model"]["records"] for entry in rs if len(entry) == 6
    ]
    assert marked  # the file holds collision marks to tamper with
    marked[0][5] = mark
    bad = tmp_path / "tampered.npz"
    np.savez(bad, metadata=np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8), **arrays)
    with pytest.raises(ValueError, match=r"tampered\.npz.*collision mark"):
        TreeAgent.load(bad)


def test_no_stored_epochs_is_no_split() -> None:
    empty = choose_collision_split(
        np.asarray([], dtype=np.float64), np.asarray([], dtype=np.bool_), *BOX
    )
    assert empty is None


def _only(xs: list[list[float]], collided: list[bool], box: Any = BOX) -> tuple[int, float] | None:
    firsts = np.array(xs, dtype=np.float64)
    return choose_collided_only_split(firsts, np.array(collided, dtype=np.bool_), *box)


def test_an_action_that_only_collided_is_cut_off_its_part_of_the_leaf() -> None:
    # collided at 0.7 and 0.8 in [0, 1], smallest leaf 0.01: below, cut at 0.69 (0.68 empty);
    # above, cut at 0.81 (0.19 empty): the wider empty part wins
    assert _only([[0.7], [0.8]], [True, True]) == (0, pytest.approx(0.69))
    assert _only([[0.2], [0.25]], [True, True]) == (0, pytest.approx(0.26))
    # two dimensions: dimension 1's part below 0.9 (0.89 wide) beats dimension 0's (0.49)
    box2 = (np.array([0.0, 0.0]), np.array([1.0, 1.0]), np.array([0.01, 0.01]))
    assert _only([[0.5, 0.9], [0.5, 0.95]], [True, True], box2) == (1, pytest.approx(0.89))
    # equal parts: the lower dimension, then the lower side
    assert _only([[0.5, 0.5]], [True], box2) == (0, pytest.approx(0.49))


def test_a_free_epoch_or_a_full_leaf_is_no_collided_only_cut() -> None:
    assert _only([[0.7], [0.8]], [True, False]) is None  # the collision split's case
    assert _only([], []) is None
    # the collided inputs reach both edges less than two smallest leaves away: no child fits
    wide = (np.array([0.0]), np.array([1.0]), np.array([0.3]))
    assert _only([[0.35], [0.65]], [True, True], wide) is None
    assert _only([[0.35], [0.65]], [True, True]) == (0, pytest.approx(0.34))


class HighPost(Post):
    """The post's env started right of the post only: action 0 collides from every start."""

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        super().reset(seed=seed)
        self.x = float(self.np_random.uniform(0.6, 1.0))
        return np.array([self.x]), {}


def test_the_agent_cuts_off_the_part_where_an_action_only_collided() -> None:
    alone = _train(POST, env=HighPost())
    assert alone.n_leaves == 1  # no free epoch of action 0: the collision split finds no cut
    only = dataclasses.replace(POST, collision_splits_collided_only=True)
    agent = _train(only, env=HighPost())
    assert agent.n_leaves >= 2
    tree = agent.partition
    assert tree._dim[0] == 0
    # just below the lowest collided start at that time (every start is at least 0.6)
    assert 0.6 - 1 / 256 <= tree._threshold[0] < 1.0
    assert agent.model is not None
    below = agent.partition.leaf_of([0.1])
    assert agent.model.count(below, 0) == 0  # the part below holds no epoch of action 0
    # an env that reports no collisions: the option changes nothing
    quiet = _train(only, env=HighPost(report=False))
    plain = _train(POST, env=HighPost(report=False))
    assert quiet.q == plain.q


@pytest.mark.parametrize("bad", [1, 0, "yes", None])
def test_the_collided_only_cut_refuses_bad_values_by_name(bad: Any) -> None:
    with pytest.raises(ValueError, match="collision_splits_collided_only must be a bool"):
        dataclasses.replace(POST, collision_splits_collided_only=bad)


def test_the_collided_only_cut_needs_collision_splits() -> None:
    with pytest.raises(ValueError, match="collided_only = True needs collision_splits = True"):
        dataclasses.replace(POST, collision_splits=False, collision_splits_collided_only=True)
    assert preset("general").config.collision_splits_collided_only is False
