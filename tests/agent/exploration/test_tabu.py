"""Decreasing tabu search: FIFO order, capacity schedule, masking, aspiration, splits."""

from __future__ import annotations

import numpy as np
import pytest

from agent.exploration import EpsilonGreedy, Greedy, Tabu, tabu_capacity


def make(**params: object) -> Tabu:
    tabu = Tabu(Greedy(), **params)  # type: ignore[arg-type]
    tabu.bind(4)
    return tabu


def test_fifo_order_no_duplicates_and_release_of_the_oldest() -> None:
    tabu = make(initial_capacity=3)
    for pair in [(0, 0), (0, 1), (0, 0), (1, 2), (2, 3)]:
        tabu.on_epoch_end(*pair)
    assert tabu.entries == [(0, 1), (1, 2), (2, 3)]


def test_capacity_schedule() -> None:
    expected = [5, 5, 4, 4, 3, 3, 2, 2, 1, 1, 1, 1]
    assert [tabu_capacity(k, 5, 2, 1) for k in range(12)] == expected
    tabu = make(initial_capacity=3, shrink_every=1, min_capacity=0)
    for pair in [(0, 0), (0, 1), (0, 2)]:
        tabu.on_epoch_end(*pair)
    tabu.on_episode_end(False)
    assert tabu.capacity == 3
    tabu.on_episode_end(True)
    assert tabu.capacity == 2
    assert tabu.entries == [(0, 1), (0, 2)]  # the oldest went first
    tabu.on_episode_end(True)
    tabu.on_episode_end(True)
    tabu.on_episode_end(True)
    assert tabu.capacity == 0
    assert tabu.entries == []
    tabu.on_epoch_end(5, 1)
    assert tabu.entries == []


def test_tabu_actions_are_skipped_by_the_greedy_choice() -> None:
    tabu = make(initial_capacity=10)
    rng = np.random.default_rng(0)
    q = [0.0, 3.0, 2.0, 1.0]
    assert tabu.select(0, q, rng) == 1
    tabu.on_epoch_end(0, 1)
    assert tabu.select(0, q, rng) == 2
    assert tabu.select(1, q, rng) == 1  # another leaf is not affected
    tabu.on_epoch_end(0, 2)
    assert tabu.select(0, q, rng) == 3


def test_aspiration_when_every_action_is_tabu() -> None:
    tabu = make(initial_capacity=10, all_listed="greedy")
    for a in range(4):
        tabu.on_epoch_end(0, a)
    assert tabu.select(0, [0.0, 3.0, 2.0, 1.0], np.random.default_rng(0)) == 1
    assert tabu.explored is False


def test_every_action_tabu_is_a_random_tie_by_default() -> None:
    tabu = make(initial_capacity=10)
    assert tabu.all_listed == "random"
    for a in range(4):
        tabu.on_epoch_end(0, a)
    rng = np.random.default_rng(0)
    picks = []
    for _ in range(400):
        picks.append(tabu.select(0, [0.0, 3.0, 2.0, 1.0], rng))
        assert tabu.explored is True
    counts = np.bincount(picks, minlength=4)
    assert counts.min() > 60  # uniform over the four actions (100 expected each)
    with pytest.raises(ValueError, match="all_listed"):
        make(all_listed="first")


def test_random_choice_ignores_the_list() -> None:
    tabu = Tabu(EpsilonGreedy(1.0), initial_capacity=10)
    tabu.bind(4)
    tabu.on_epoch_end(0, 1)
    rng = np.random.default_rng(0)
    chosen = {tabu.select(0, [0.0, 3.0, 2.0, 1.0], rng) for _ in range(200)}
    assert chosen == {0, 1, 2, 3}


def test_random_choice_respects_the_list_when_asked() -> None:
    tabu = Tabu(EpsilonGreedy(1.0), initial_capacity=10, random_respects_list=True)
    tabu.bind(4)
    tabu.on_epoch_end(0, 1)
    tabu.on_epoch_end(0, 3)
    rng = np.random.default_rng(0)
    assert {tabu.select(0, [0.0, 3.0, 2.0, 1.0], rng) for _ in range(200)} == {0, 2}
    assert {tabu.select(1, [0.0, 3.0, 2.0, 1.0], rng) for _ in range(200)} == {0, 1, 2, 3}


def test_split_policy() -> None:
    drop = make(initial_capacity=10)
    keep = make(initial_capacity=10, on_split="inherit")
    for tabu in (drop, keep):
        for pair in [(0, 1), (3, 2), (0, 3)]:
            tabu.on_epoch_end(*pair)
        tabu.on_split(0, (4, 5))
    assert drop.entries == [(3, 2)]
    assert keep.entries == [(4, 1), (5, 1), (3, 2), (4, 3), (5, 3)]


def test_bad_parameters() -> None:
    with pytest.raises(ValueError, match="initial_capacity"):
        Tabu(Greedy(), initial_capacity=-1)
    with pytest.raises(ValueError, match="shrink_every"):
        Tabu(Greedy(), shrink_every=0)
    with pytest.raises(TypeError, match="base"):
        Tabu("greedy")  # type: ignore[arg-type]


@pytest.mark.parametrize("deviation_explores", [True, False])
def test_a_choice_turned_away_from_the_greedy_action_is_exploratory(
    deviation_explores: bool,
) -> None:
    tabu = make(initial_capacity=5, deviation_explores=deviation_explores)
    rng = np.random.default_rng(0)
    q_row = [0.0, 2.0, 1.0, -1.0]
    assert tabu.select(0, q_row, rng) == 1
    assert tabu.explored is False
    tabu.on_epoch_end(0, 1)  # the greedy action becomes tabu
    assert tabu.select(0, q_row, rng) == 2
    assert tabu.explored is deviation_explores
    assert tabu.select(7, q_row, rng) == 1  # another leaf: nothing listed, greedy
    assert tabu.explored is False
