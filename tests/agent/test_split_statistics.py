"""Eqs. (12), (13) and the three split conditions against values computed by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

from agent.split_statistics import (
    choose_split,
    density_crossing,
    should_split,
    split_point,
    t_statistics,
)

THRESHOLDS = {"min_samples": 500, "max_abs_mean": 0.5, "min_variance": 0.03}


def test_eq12_t_statistic_by_hand() -> None:
    positive = np.array([[1.0, 0.0], [2.0, 0.0], [3.0, 3.0]])
    negative = np.array([[5.0, 1.0], [6.0, 1.0], [7.0, 1.0], [8.0, 1.0]])
    # dim 0: |2 - 6.5| / sqrt(1/3 + (5/3)/4) = 4.5 / sqrt(0.75) = 5.196152; dim 1: equal means -> 0
    t = t_statistics(positive, negative, np.array([1.0, 1.0]))
    assert t == pytest.approx([5.196152422706632, 0.0])
    weighted = t_statistics(positive, negative, np.array([0.5, 2.0]))
    assert weighted == pytest.approx([2.598076211353316, 0.0])


def test_eq12_constant_groups() -> None:
    positive = np.array([[1.0], [1.0]])
    negative = np.array([[2.0], [2.0]])
    assert t_statistics(positive, negative, np.array([1.0]))[0] == math.inf
    assert t_statistics(positive, positive, np.array([1.0]))[0] == 0.0


def test_eq13_unequal_variances_by_hand() -> None:
    # -3x^2 - 8x + 16 + 8 ln 2 = 0  ->  x = (-8 + sqrt(64 + 12 (16 + 8 ln 2))) / 6 = 1.659910
    x = density_crossing(0.0, 1.0, 1, 4.0, 4.0, 1)
    assert x == pytest.approx(1.6599096559016366)
    left = 1 / math.sqrt(2 * math.pi) * math.exp(-(x**2) / 2)
    right = 1 / math.sqrt(2 * math.pi * 4) * math.exp(-((x - 4) ** 2) / 8)
    assert left == pytest.approx(right)


def test_eq13_equal_variances_linear_by_hand() -> None:
    # x = (m1 + m2)/2 - s^2 ln(n1/n2)/(m1 - m2) = 1 + ln(3)/2
    assert density_crossing(0.0, 1.0, 3, 2.0, 1.0, 1) == pytest.approx(1.549306144334055)
    assert density_crossing(0.0, 1.0, 5, 2.0, 1.0, 5) == pytest.approx(1.0)


def test_eq13_no_real_root_falls_back_to_clipped_midpoint() -> None:
    # group 2 outnumbers group 1 a thousand to one and is wider: its density is above everywhere
    assert density_crossing(0.0, 1.0, 1, 1.0, 4.0, 1000) is None
    assert density_crossing(1.0, 1.0, 1, 1.0, 1.0, 1) is None  # equal means
    pos = np.array([-1.0, 1.0])  # mean 0, sample variance 2
    neg = np.tile([1.0 - 2.0, 1.0 + 2.0], 500)  # mean 1, sample variance ~4, 1000 samples
    assert density_crossing(0.0, 2.0, 2, 1.0, float(neg.var(ddof=1)), 1000) is None
    midpoint = 0.5
    assert split_point(pos, neg, -10.0, 10.0, 0.1) == pytest.approx(midpoint)
    # clipped so that each child keeps the margin
    assert split_point(pos, neg, midpoint - 0.05, 10.0, 0.1) == pytest.approx(midpoint + 0.05)


def test_midpoint_rule_ignores_the_density_crossing() -> None:
    # counts 3:1 and equal variances (1): eq. (13) gives 1 + ln(3) / 2, the midpoint rule 1
    pos = np.array([-1.0, 0.0, 1.0] * 3)  # 9 samples, mean 0, sample variance 0.75
    neg = np.array([1.0, 2.0, 3.0])  # 3 samples, mean 2, sample variance 1
    assert split_point(pos, neg, -10.0, 10.0, 0.1) > 1.2
    assert split_point(pos, neg, -10.0, 10.0, 0.1, "midpoint") == pytest.approx(1.0)
    with pytest.raises(ValueError, match="'median'"):
        split_point(pos, neg, -10.0, 10.0, 0.1, "median")


@pytest.mark.parametrize(
    ("n", "mean", "variance", "expected"),
    [
        (500, 0.0, 0.25, True),
        (499, 0.0, 0.25, False),  # condition 1
        (500, 0.5, 0.25, False),  # condition 2 is strict
        (500, -0.49, 0.25, True),
        (500, 0.6, 0.25, False),
        (500, 0.0, 0.03, False),  # condition 3 is strict
        (500, 0.0, 0.031, True),
        (500, 0.6, 0.01, False),
    ],
)
def test_three_conditions(n: int, mean: float, variance: float, expected: bool) -> None:
    assert should_split(n, mean, variance, **THRESHOLDS) is expected


def test_choose_split_picks_the_informative_dimension() -> None:
    rng = np.random.default_rng(1)
    inputs = rng.uniform(0.0, 1.0, size=(400, 2))
    errors = np.where(inputs[:, 1] < 0.3, 1.0, -1.0) + rng.normal(0, 0.1, 400)
    choice = choose_split(inputs, errors, np.zeros(2), np.ones(2), np.ones(2), np.full(2, 0.01))
    assert choice is not None
    dim, value = choice
    assert dim == 1
    assert 0.2 < value < 0.4


def test_choose_split_needs_two_samples_per_group_and_an_eligible_dimension() -> None:
    inputs = np.array([[0.1], [0.2], [0.3]])
    assert (
        choose_split(
            inputs,
            np.array([1.0, 1.0, -1.0]),
            np.zeros(1),
            np.ones(1),
            np.ones(1),
            np.full(1, 0.01),
        )
        is None
    )
    inputs = np.array([[0.1], [0.2], [0.3], [0.4]])
    errors = np.array([1.0, 1.0, -1.0, -1.0])
    assert (
        choose_split(inputs, errors, np.zeros(1), np.ones(1), np.ones(1), np.full(1, 0.6)) is None
    )
