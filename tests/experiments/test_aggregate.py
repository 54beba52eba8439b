"""Aggregates over tasks against cases computed by hand; the bootstraps are seeded."""

from __future__ import annotations

import numpy as np
import pytest

from experiments import aggregate
from experiments.references import (
    RANDOM_RETURNS,
    References,
    default_references,
    random_policy_return,
)
from experiments.task_scores import normalised_return


def test_iqm_is_the_mean_of_the_middle_half():
    # 8 scores pooled over two tasks: the two lowest and the two highest are trimmed
    scores = [np.array([8.0, 1.0, 5.0, 3.0]), np.array([2.0, 7.0, 4.0, 6.0])]
    assert aggregate.iqm(scores, 0).value == pytest.approx((3 + 4 + 5 + 6) / 4)


def test_the_stratified_bootstrap_of_a_hand_enumerable_case():
    """Task 1 has one run (always resampled to itself), task 2 runs 2 and 3. The resampled
    pools are {1,2,2}, {1,2,3}, {1,3,2}, {1,3,3} with equal probability; the IQM of three
    values trims nothing, so the IQM is 5/3, 2, 2 or 7/3, and the 95% percentile interval is
    [5/3, 7/3]."""
    estimate = aggregate.iqm([np.array([1.0]), np.array([2.0, 3.0])], seed=0)
    assert estimate.value == pytest.approx(2.0)
    assert (estimate.low, estimate.high) == pytest.approx((5 / 3, 7 / 3))


def test_one_run_per_task_gives_no_interval():
    """With one run in every task nothing is resampled; the interval is NaN, not the value
    twice (a 95% interval of zero width), and the reports print it as n/a."""
    from experiments.task_report import _estimate

    estimate = aggregate.iqm([np.array([1.0]), np.array([2.0]), np.array([4.0])], seed=0)
    assert estimate.value == pytest.approx(7 / 3)  # (the IQM of three values trims nothing)
    assert np.isnan(estimate.low)
    assert np.isnan(estimate.high)
    assert _estimate(estimate) == "2.33 [n/a]"
    from experiments.statistics import interval_text
    from experiments.transfer_report import _ci, _gap

    nan = float("nan")
    assert interval_text(nan, nan) == "[n/a]"
    assert _ci((1.0, nan, nan), True) == "100% [n/a]"
    assert _ci((1.5, nan, nan), False) == "1.50 [n/a]"
    assert _gap((-0.5, nan, nan)) == "-50 [n/a]"
    assert _ci((0.5, 0.25, 0.75), True) == "50% [25, 75]"


def test_probability_of_improvement_by_hand():
    """Task 1: candidate [1, 2] against baseline [2, 3], lower better: the pairs (1,2), (1,3),
    (2,3) are wins and (2,2) a tie, 3.5 / 4. Task 2: candidate 5 against 4, a loss. Mean over
    tasks: 0.4375."""
    candidate = [np.array([1.0, 2.0]), np.array([5.0])]
    baseline = [np.array([2.0, 3.0]), np.array([4.0])]
    lower = aggregate.probability_of_improvement(candidate, baseline, True, 0)
    assert lower.value == pytest.approx(0.4375)
    assert lower.low <= lower.value <= lower.high
    higher = aggregate.probability_of_improvement(candidate, baseline, False, 0)
    assert higher.value == pytest.approx(1 - 0.4375)
    same = aggregate.probability_of_improvement(candidate, candidate, True, 0)
    assert same.value == pytest.approx(0.5)


def test_probability_of_improvement_interval_by_hand():
    """One task, candidate [0, 2] against baseline 1 (one run, fixed): resampled candidates
    {0,0}, {0,2}, {2,0}, {2,2} give P = 1, 0.5, 0.5, 0 (lower better)."""
    estimate = aggregate.probability_of_improvement(
        [np.array([0.0, 2.0])], [np.array([1.0])], True, 0
    )
    assert (estimate.value, estimate.low, estimate.high) == pytest.approx((0.5, 0.0, 1.0))


def test_the_profile_counts_runs_at_least_as_good_as_tau():
    scores = [np.array([1.0, 2.0]), np.array([3.0, 4.0])]
    taus = np.array([0.5, 1.0, 2.5, 4.0])
    lower, low, high = aggregate.profile(scores, taus, True, 0)
    assert lower.tolist() == [0.0, 0.25, 0.5, 1.0]
    assert (low <= lower).all()
    assert (lower <= high).all()
    higher, _, _ = aggregate.profile(scores, taus, False, 0)
    assert higher.tolist() == [1.0, 1.0, 0.5, 0.25]


def test_every_bootstrap_is_seeded():
    rng = np.random.default_rng(3)
    scores = [rng.normal(size=5) for _ in range(4)]
    other = [rng.normal(size=5) for _ in range(4)]
    assert aggregate.iqm(scores, (0, 1)) == aggregate.iqm(scores, (0, 1))
    assert aggregate.iqm(scores, (0, 1)) != aggregate.iqm(scores, (0, 2))
    first = aggregate.probability_of_improvement(scores, other, True, 4)
    assert first == aggregate.probability_of_improvement(scores, other, True, 4)
    taus = np.linspace(-2, 2, 9)
    one, two = aggregate.profile(scores, taus, True, 5), aggregate.profile(scores, taus, True, 5)
    assert all((a == b).all() for a, b in zip(one, two, strict=True))


def test_empty_tasks_are_refused():
    with pytest.raises(ValueError, match="at least one run"):
        aggregate.iqm([np.array([1.0]), np.array([])], 0)
    with pytest.raises(ValueError, match="same tasks"):
        aggregate.probability_of_improvement([np.array([1.0])], [], True, 0)


def test_normalised_return_by_hand():
    references = References(-200.0, -110.0, "test")
    assert normalised_return(np.array([-200.0, -155.0, -110.0, -90.0]), references).tolist() == [
        0.0,
        0.5,
        1.0,
        pytest.approx(110 / 90),
    ]


def test_default_references_hold_at_the_registered_time_limit_only():
    cartpole = default_references("CartPole-v1", 500)
    assert cartpole is not None
    assert (cartpole.random_return, cartpole.solved_return) == (
        RANDOM_RETURNS["CartPole-v1"].mean,
        475.0,
    )
    assert default_references("MountainCar-v0", 200).solved_return == -110.0  # type: ignore[union-attr]
    assert default_references("Acrobot-v1", 500).solved_return == -100.0  # type: ignore[union-attr]
    assert default_references("MountainCar-v0", 300) is None
    assert default_references("Pendulum-v1", 200) is None
    assert default_references("BulletMaze-v0", 5000) is None


@pytest.mark.parametrize(("env_id", "episodes"), [("CartPole-v1", 200), ("MountainCar-v0", 20)])
def test_the_random_returns_agree_with_a_fresh_measurement(env_id: str, episodes: int):
    """The table's 1,000-episode means, within four standard errors of a smaller measurement
    from another seed."""
    mean, error = random_policy_return(env_id, episodes, seed=1)
    recorded = RANDOM_RETURNS[env_id]
    assert abs(mean - recorded.mean) <= 4 * np.hypot(error, recorded.standard_error) + 1e-9
    assert random_policy_return(env_id, 5, seed=2) == random_policy_return(env_id, 5, seed=2)
