"""The baseline strategies of issue 9, each against a case computed by hand."""

from __future__ import annotations

import math
import re
from collections import Counter

import numpy as np
import pytest
from gymnasium import spaces

from agent import TreeAgent, TreeConfig
from agent.exploration import (
    Boltzmann,
    CountBonus,
    DecayingEpsilon,
    OptimisticInit,
    VDBESoftmax,
    boltzmann_probabilities,
    bonus_values,
    decayed_epsilon,
    make_exploration,
)
from agent.exploration.boltzmann import sample


class Fixed:
    """A uniform source that returns the given draws in turn."""

    def __init__(self, *draws: float) -> None:
        self.draws = list(draws)

    def random(self) -> float:
        return self.draws.pop(0)


def test_boltzmann_probabilities_by_hand() -> None:
    # exp(1) / (exp(1) + 2) and 1 / (exp(1) + 2)
    p = boltzmann_probabilities([1.0, 0.0, 0.0], 1.0)
    e = math.e
    assert p == pytest.approx([e / (e + 2), 1 / (e + 2), 1 / (e + 2)])
    # tau = 0.5 doubles the gap: exp(2) / (exp(2) + 1)
    assert boltzmann_probabilities([3.0, 2.0], 0.5)[0] == pytest.approx(e**2 / (e**2 + 1))
    # huge values do not overflow (computed from Q - max Q)
    assert boltzmann_probabilities([1e6, 1e6 - 1.0], 1.0)[1] == pytest.approx(1 / (e + 1))
    assert boltzmann_probabilities([2.0, 2.0, 1.0], 0.0) == [0.5, 0.5, 0.0]


def test_boltzmann_select_uses_one_draw_and_marks_exploration() -> None:
    s = Boltzmann(temperature=1.0)
    s.bind(3)
    # cumulative 0.5761, 0.7881, 1.0: u = 0.70 picks action 1 (not greedy: exploratory)
    assert s.select(0, [1.0, 0.0, 0.0], Fixed(0.70)) == 1
    assert s.explored
    assert s.select(0, [1.0, 0.0, 0.0], Fixed(0.10)) == 0
    assert not s.explored
    assert sample([0.2, 0.8], 0.9999999999) == 1
    rng = np.random.default_rng(0)
    picks = Counter(s.select(0, [1.0, 0.0, 0.0], rng) for _ in range(20000))
    assert picks[0] / 20000 == pytest.approx(math.e / (math.e + 2), abs=0.01)


def test_count_bonus_by_hand() -> None:
    # Q + 1 / sqrt(n): 0 + 1/2 = 0.5 against 0.5 + 1/1 = 1.5
    assert bonus_values([0.0, 0.5], [4, 1], 1.0) == [0.5, 1.5]
    s = CountBonus(beta=1.0)
    s.bind(2)
    for _ in range(4):
        s.on_epoch_end(7, 0)
    s.on_epoch_end(7, 1)
    assert s.select(7, [0.0, 0.5], Fixed()) == 1
    assert not s.explored  # 1 is also the greedy action of Q alone
    # an untried action comes first; with a large count the bonus fades
    fresh = CountBonus(beta=1.0)
    fresh.bind(2)
    for _ in range(100):
        fresh.on_epoch_end(3, 0)
    assert fresh.select(3, [1.0, 0.0], Fixed()) == 1
    assert fresh.explored
    fresh.on_epoch_end(3, 1)
    # 1 + 0.1 = 1.1 against 0 + 1 = 1
    assert fresh.select(3, [1.0, 0.0], Fixed()) == 0
    fresh.on_split(3, (8, 9))
    assert fresh.counts(8) == fresh.counts(9) == [100, 1]


def test_decaying_epsilon_schedules_by_hand() -> None:
    assert decayed_epsilon(10, 1.0, 0.0, 0.9, "exponential", 1) == pytest.approx(0.9**10)
    assert decayed_epsilon(1000, 1.0, 0.01, 0.99, "exponential", 1) == 0.01
    # linear from 1 to 0.1 over 10 episodes: 0.55 after 5, 0.1 from 10 on
    assert decayed_epsilon(5, 1.0, 0.1, 0.0, "linear", 10) == pytest.approx(0.55)
    assert decayed_epsilon(12, 1.0, 0.1, 0.0, "linear", 10) == 0.1
    s = DecayingEpsilon(start=1.0, end=0.05, decay=0.5)
    s.bind(4)
    assert s.epsilon(0) == 1.0
    s.on_episode_end(False)
    s.on_episode_end(True)
    assert s.epsilon(5) == 0.25
    copy = make_exploration("decaying-epsilon", **s.params())
    copy.load_state_dict(s.state_dict())
    assert copy.epsilon(0) == 0.25
    with pytest.raises(ValueError, match="end"):
        DecayingEpsilon(start=0.1, end=0.5)


def test_vdbe_softmax_by_hand() -> None:
    s = VDBESoftmax(sigma=1.0, temperature=1.0)
    s.bind(4)
    s.update(2, 0, 1.0)
    # f = (1 - e^-1) / (1 + e^-1); epsilon = f / 4 + 3/4
    f = (1 - math.exp(-1)) / (1 + math.exp(-1))
    assert s.epsilon(2) == pytest.approx(f / 4 + 0.75)
    # first draw 0.5 < epsilon: softmax over [1, 0, 0, 0]; 0.99 falls in the last action
    assert s.select(2, [1.0, 0.0, 0.0, 0.0], Fixed(0.5, 0.99)) == 3
    assert s.explored
    # a draw above epsilon: greedy
    assert s.select(2, [1.0, 0.0, 0.0, 0.0], Fixed(0.99)) == 0
    assert not s.explored


def test_optimistic_initialisation_sets_every_value() -> None:
    s = OptimisticInit(r_max=5.0)
    assert s.initial_value(0.99) == pytest.approx(500.0)
    box = spaces.Box(0.0, 1.0, shape=(2,))
    agent = TreeAgent(box, spaces.Discrete(3), s, config=TreeConfig(inherit_q=False))
    assert agent.q[0] == [pytest.approx(500.0)] * 3
    children = agent.split_leaf(0, 0, 0.5)
    assert agent.q[children[1]] == [pytest.approx(500.0)] * 3
    with pytest.raises(ValueError, match="gamma < 1"):
        s.initial_value(1.0)


@pytest.mark.parametrize(
    ("name", "params", "error"),
    [
        ("boltzmann", {"temperature": 0.0}, ValueError),
        ("boltzmann", {"temperature": float("inf")}, ValueError),
        ("boltzmann", {"temperature": True}, TypeError),
        ("count-bonus", {"beta": -1.0}, ValueError),
        ("count-bonus", {"beta": "1"}, TypeError),
        ("decaying-epsilon", {"decay": 1.5}, ValueError),
        ("decaying-epsilon", {"schedule": "cosine"}, ValueError),
        ("decaying-epsilon", {"horizon": 0}, ValueError),
        ("decaying-epsilon", {"start": float("nan")}, ValueError),
        ("vdbe-softmax", {"temperature": -1.0}, ValueError),
        ("optimistic", {"r_max": float("nan")}, ValueError),
        ("optimistic", {"r_max": None}, TypeError),
    ],
)
def test_bad_parameters_name_the_strategy(name: str, params: dict, error: type) -> None:
    with pytest.raises(error, match=name.split("-")[0]):
        make_exploration(name, **params)


@pytest.mark.parametrize(
    ("counts", "named"),
    [
        ([[7, [4, -1]]], "the counts of leaf 7 are [4, -1]"),
        ([[7, [4]]], "not 2 ints >= 0"),
        ([[7, [4, 1.5]]], "not 2 ints >= 0"),
        ([[7, "x"]], "the counts of leaf 7 are 'x'"),
        ([[-1, [1, 1]]], "[-1, [1, 1]] is not [leaf id >= 0, value]"),
        ([[7, [1, 1]], [7, [2, 2]]], "lists leaf 7 twice"),
        ("x", "must be a list of [leaf, value] pairs"),
    ],
)
def test_a_count_bonus_state_with_bad_counts_is_refused(counts: object, named: str) -> None:
    """Fuzz cases: a negative or short count used to load and fail inside sqrt or indexing."""
    s = CountBonus(beta=1.0)
    s.bind(2)
    with pytest.raises(ValueError, match=re.escape(named)):
        s.load_state_dict({"counts": counts})
    good = CountBonus(beta=1.0)
    good.bind(2)
    good.load_state_dict({"counts": [[7, [4, 1]]]})
    assert good.select(7, [0.0, 0.5], Fixed()) == 1  # the state of the test above, loaded
