"""The SMDP model over the leaves and prioritized sweeping (TreeConfig.planning="sweep")."""

from __future__ import annotations

import json
from array import array

import numpy as np
import pytest
from gymnasium import spaces

from agent import TreeAgent, TreeConfig
from agent.leaf_model import LeafModel
from agent.smdp import epoch_discounts, epoch_returns


def chain() -> tuple[LeafModel, list[list[float]]]:
    """Leaf 0 leads to leaf 1, which ends the episode (one action)."""
    model = LeafModel(n_actions=1, window=2)
    q = [[0.0], [0.0], [0.0], [0.0]]
    model.add(1, 0, [0.8], reward=1.0, discount=0.9, end=None, end_leaf=1)
    model.add(0, 0, [0.2], reward=0.5, discount=0.5, end=[0.85], end_leaf=1)
    return model, q


def test_epoch_discounts_split_the_return() -> None:
    rs, b, gamma = [1.0, -2.0, 0.5], 3.0, 0.9
    full = epoch_returns(rs, b, gamma)
    part = epoch_returns(rs, 0.0, gamma)
    d = epoch_discounts(3, gamma)
    assert d == pytest.approx([0.729, 0.81, 0.9])
    assert full == pytest.approx([p + k * b for p, k in zip(part, d, strict=True)])


def test_model_value_by_hand() -> None:
    model, q = chain()
    assert model.value(1, 0, q) == 1.0  # terminal: R only
    q[1][0] = 1.0
    assert model.value(0, 0, q) == 0.5 + 0.5 * 1.0
    assert model.value(2, 0, q) is None
    model.add(0, 0, [0.3], reward=-1.0, discount=0.25, end=[0.1], end_leaf=0)
    # mean of (0.5 + 0.5 * 1) and (-1 + 0.25 * V(0) = -1 + 0.25 * 0)
    assert model.value(0, 0, q) == pytest.approx((1.0 - 1.0) / 2)
    model.add(0, 0, [0.3], reward=2.0, discount=0.0, end=[0.1], end_leaf=0)
    assert model.count(0, 0) == 2  # window 2: the first epoch was forgotten
    assert model.value(0, 0, q) == pytest.approx((-1.0 + 2.0) / 2)
    assert model.epochs[0] == 3


def test_sweep_pushes_a_change_to_the_predecessors() -> None:
    model, q = chain()
    q[1][0] = 3.0
    model.push(1, 3.0)
    assert model.sweep(q, budget=10, tolerance=1e-9) == 1
    assert q[0][0] == 0.5 + 0.5 * 3.0
    assert model.sweep(q, budget=10, tolerance=1e-9) == 0  # leaf 0 has no predecessors


def test_split_refiles_epochs_by_where_they_began_and_ended() -> None:
    model, q = chain()
    changed = model.split(1, (2, 3), lambda x: 2 if x[0] < 0.82 else 3)
    # (1, 0)'s epoch began at 0.8: child 2; (0, 0)'s epoch ended at 0.85: child 3
    assert changed == [0, 2]
    assert model.count(2, 0) == 1
    assert model.count(3, 0) == 0
    assert model.count(1, 0) == 0
    q[3][0] = 10.0
    assert model.value(0, 0, q) == 0.5 + 0.5 * 10.0
    model.push(3, 1.0)
    model.sweep(q, budget=5, tolerance=0.0)
    assert q[0][0] == 5.5
    state = json.loads(json.dumps(model.state()))
    again = LeafModel.from_state(1, state)
    assert again.value(0, 0, q) == model.value(0, 0, q)
    assert again.epochs == model.epochs


def test_planning_agent_learns_the_mean_target_at_once() -> None:
    class Three:
        observation_space = spaces.Box(0.0, 1.0, shape=(1,))
        action_space = spaces.Discrete(2)

        def reset(self, seed: int | None = None) -> tuple[np.ndarray, dict]:
            self.t = 0
            return np.array([0.5]), {}

        def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict]:
            self.t += 1
            return np.array([0.5]), 1.0, self.t == 3, False, {}

    env = Three()
    agent = TreeAgent(
        env.observation_space,
        env.action_space,
        "greedy",
        config=TreeConfig(alpha=0.5, gamma=0.5, planning="sweep"),
    )
    agent.learn(env, 1)
    acted = int(np.argmax(agent.visits[0]))
    # eq. (10) would give 0.5 * mean(1.75, 1.5, 1); the model gives the mean itself
    assert agent.q[0][acted] == pytest.approx((1.75 + 1.5 + 1.0) / 3)
    assert agent.model is not None
    assert agent.model.count(0, acted) == 1


def test_stored_inputs_are_compact_copies_shared_between_an_end_and_the_next_start() -> None:
    model = LeafModel(n_actions=2, window=4)
    start, middle, end = [0.1, 0.2], [0.3, 0.4], [0.5, 0.6]
    first = model.add(0, 0, start, -1.0, 0.9, middle, 1)
    assert isinstance(first, array)
    assert list(first) == start
    assert first is model.last_added
    second = model.add(1, 1, middle, -1.0, 0.9, end, 0)  # begins where the first ended
    record_first, record_second = model._records[0][0], model._records[3][0]
    assert record_first[0] is first
    assert record_first[3] is second  # one copy for the end and the next start
    assert record_second[3] is not None
    assert list(record_second[3]) == end
    middle[0] = 9.0  # the caller's lists are copied, not kept
    assert list(second) == [0.3, 0.4]
    third = model.add(0, 0, [0.5, 0.6], -1.0, 0.9, None, -1)  # an equal list, not the same one
    assert third is not record_second[3]
    assert model.locate(0, 0, third) == 1
    assert model.locate(0, 0, array("d", [0.5, 0.6])) is None
    reused = [1.0, 2.0]
    model.add(2, 0, [0.0, 0.0], -1.0, 0.9, reused, 0)
    reused[0] = 7.0  # the caller changes the list it passed as the end, then starts there
    fourth = model.add(0, 1, reused, -1.0, 0.9, None, -1)
    assert list(fourth) == [7.0, 2.0]  # a fresh copy, not the stale shared one
    assert list(model._records[4][0][3]) == [1.0, 2.0]


class _KeepsStale(LeafModel):
    """The model with its queue never rebuilt: every stale entry stays in the heap."""

    def _drop_stale(self) -> None:
        pass


def test_dropping_stale_queue_entries_keeps_the_sweeps_and_bounds_the_queue() -> None:
    rng = np.random.default_rng(7)
    models = (LeafModel(n_actions=2, window=4), _KeepsStale(n_actions=2, window=4))
    leaves = 60
    for model in models:  # a random chain of epochs between 60 leaves, the same in both
        draw = np.random.default_rng(1)
        for _ in range(400):
            leaf, end = draw.integers(leaves, size=2).tolist()
            model.add(leaf, int(draw.integers(2)), [0.0], float(draw.normal()), 0.9, [0.0], end)
    tables = [[[0.0, 0.0] for _ in range(leaves)] for _ in models]
    backups: list[list[int]] = [[], []]
    for t in range(300):  # rising priorities, few backups: stale entries pile up
        pushes = [(int(rng.integers(leaves)), t + float(rng.random())) for _ in range(40)]
        for model, q, done in zip(models, tables, backups, strict=True):
            for leaf, priority in pushes:
                model.push(leaf, priority)
            done.append(model.sweep(q, budget=3, tolerance=0.05))
    assert sum(backups[0]) > 500
    assert backups[0] == backups[1]
    assert tables[0] == tables[1]  # the same backups, in the same order
    assert len(models[0]._queue) <= 2 * len(models[0]._priority) + 1024
    assert len(models[1]._queue) > 5_000  # the reference kept its stale entries
