"""Eqs. (2)-(5) of the adaptive epsilon against values computed by hand."""

from __future__ import annotations

import math

import pytest

from agent.exploration import (
    AdaptiveEpsilon,
    action_probabilities,
    adaptive_epsilon,
    entropy,
    normalized_entropy,
)

# counts [3, 1, 0, 0]: P = [0.75, 0.25, 0, 0]
H = 0.5623351446188083  # -(0.75 ln 0.75 + 0.25 ln 0.25)
H_BAR = 0.4056390622295664  # H / ln 4


def test_eq2_probabilities() -> None:
    assert action_probabilities([3, 1, 0, 0]) == [0.75, 0.25, 0.0, 0.0]
    assert action_probabilities([0, 0, 0, 0]) == [0.0, 0.0, 0.0, 0.0]


def test_eq3_entropy_with_zero_log_zero() -> None:
    assert entropy([0.75, 0.25, 0.0, 0.0]) == pytest.approx(H)
    assert entropy([0.0, 0.0]) == 0.0
    assert entropy([0.25] * 4) == pytest.approx(math.log(4))


def test_eq4_normalized_entropy() -> None:
    assert normalized_entropy([3, 1, 0, 0]) == pytest.approx(H_BAR)
    assert normalized_entropy([2, 2, 2, 2]) == pytest.approx(1.0)
    assert normalized_entropy([7, 0, 0, 0]) == 0.0


def test_eq5_zero_counts_gives_one() -> None:
    assert adaptive_epsilon([0, 0, 0, 0], 123.0) == 1.0


def test_eq5_first_branch_small_change() -> None:
    # |dQ| / (n C_n) = 5e-5 / (4 * 0.001) = 0.0125 < C_h = 0.025
    eps = adaptive_epsilon([3, 1, 0, 0], 5e-5, c_n=0.001, c_h=0.025)
    assert eps == pytest.approx((1 - H_BAR) * (1 - math.exp(-5e-5 / 4)))
    assert eps == pytest.approx(7.429465287891954e-06)


def test_eq5_second_branch_large_change() -> None:
    # |dQ| / (n C_n) = 0.5 / 0.004 = 125 >= C_h
    assert adaptive_epsilon([3, 1, 0, 0], -0.5) == pytest.approx(1 - H_BAR)
    assert adaptive_epsilon([3, 1, 0, 0], 0.5) == pytest.approx(0.5943609377704335)


def test_eq5_cn_exponent_variant() -> None:
    eps = adaptive_epsilon([3, 1, 0, 0], 5e-5, variant="cn_exponent")
    assert eps == pytest.approx((1 - H_BAR) * (1 - math.exp(-0.0125)))


def test_strategy_per_leaf_epsilon_and_split() -> None:
    assert AdaptiveEpsilon().inherit_on_split is True  # the default (docs/paper-notes.md, 5)
    s = AdaptiveEpsilon(inherit_on_split=False)
    s.bind(4)
    assert s.epsilon(7) == 1.0
    for action in (0, 0, 0, 1):
        s.update(7, action, 0.5)
    assert s.counts(7) == [3, 1, 0, 0]
    assert s.epsilon(7) == pytest.approx(1 - H_BAR)
    assert s.epsilon(8) == 1.0
    s.on_split(7, (9, 10))
    assert s.epsilon(9) == 1.0
    assert s.counts(9) == [0, 0, 0, 0]
    inherit = AdaptiveEpsilon(inherit_on_split=True)
    inherit.bind(4)
    inherit.update(0, 2, 0.5)
    inherit.update(0, 1, 0.5)
    before = inherit.epsilon(0)
    assert before == pytest.approx(0.5)  # two actions used equally: H-bar = ln 2 / ln 4 = 0.5
    inherit.on_split(0, (1, 2))
    assert inherit.counts(2) == [0, 1, 1, 0]
    assert inherit.epsilon(1) == inherit.epsilon(2) == before


def test_bad_parameters_name_the_value() -> None:
    with pytest.raises(ValueError, match="c_n"):
        AdaptiveEpsilon(c_n=-1.0)
    with pytest.raises(ValueError, match="variant"):
        AdaptiveEpsilon(variant="exp")  # type: ignore[arg-type]
