"""Epsilon-greedy, greedy, VDBE and the factory."""

from __future__ import annotations

import math
from collections import Counter

import numpy as np
import pytest

from agent.exploration import (
    STRATEGY_NAMES,
    VDBE,
    AdaptiveEpsilon,
    EpsilonGreedy,
    Greedy,
    Tabu,
    exploration_from_spec,
    exploration_spec,
    greedy_action,
    make_exploration,
    vdbe_epsilon,
)


def test_greedy_ties_broken_at_random_among_the_best_only() -> None:
    rng = np.random.default_rng(0)
    picks = Counter(greedy_action([1.0, 0.0, 1.0, 1.0], rng) for _ in range(3000))
    assert set(picks) == {0, 2, 3}
    assert min(picks.values()) > 900
    assert greedy_action([0.0, 2.0, 1.0], rng) == 1


def test_epsilon_greedy_rate() -> None:
    rng = np.random.default_rng(1)
    s = EpsilonGreedy(0.2)
    s.bind(4)
    picks = Counter(s.select(0, [5.0, 0.0, 0.0, 0.0], rng) for _ in range(20000))
    # non-greedy actions with probability 0.2 * 3/4 = 0.15
    assert (20000 - picks[0]) / 20000 == pytest.approx(0.15, abs=0.01)
    assert Greedy().epsilon(0) == 0.0
    with pytest.raises(ValueError, match="epsilon"):
        EpsilonGreedy(1.5)


def test_vdbe_by_hand() -> None:
    # f = (1 - e^-0.5) / (1 + e^-0.5) = 0.244919; 0.25 f + 0.75 * 1
    assert vdbe_epsilon(1.0, -0.5, 1.0, 0.25, "boltzmann") == pytest.approx(0.8112296656009272)
    assert vdbe_epsilon(0.0, 0.5, 1.0, 0.5, "exponential") == pytest.approx(
        0.5 * (1 - math.exp(-0.5))
    )
    s = VDBE(sigma=1.0)
    s.bind(4)
    assert s.epsilon(3) == 1.0
    s.update(3, 0, 0.5)
    assert s.epsilon(3) == pytest.approx(0.8112296656009272)
    for _ in range(200):
        s.update(3, 0, 0.0)
    assert s.epsilon(3) < 1e-20


@pytest.mark.parametrize("name", STRATEGY_NAMES)
def test_factory_builds_every_name_and_round_trips(name: str) -> None:
    s = make_exploration(name)
    s.bind(4)
    s.update(0, 1, 0.3)
    s.on_epoch_end(0, 1)
    s.on_episode_end(True)
    copy = exploration_from_spec(exploration_spec(s))
    copy.bind(4)
    assert repr(copy) == repr(s)
    assert exploration_spec(copy) == exploration_spec(s)
    assert (name == "tabu" or "+tabu" in name) == isinstance(s, Tabu)


def test_factory_routes_parameters_and_rejects_unknown() -> None:
    s = make_exploration("adaptive+tabu", c_n=0.025, c_h=0.001, initial_capacity=7)
    assert isinstance(s, Tabu)
    assert isinstance(s.base, AdaptiveEpsilon)
    assert s.base.c_n == 0.025
    assert s.initial_capacity == 7
    assert "AdaptiveEpsilon(c_n=0.025" in repr(s)
    with pytest.raises(ValueError, match=r"'softmax'.*epsilon-greedy"):
        make_exploration("softmax")
    with pytest.raises(ValueError, match="sigma"):
        make_exploration("adaptive", sigma=1.0)
