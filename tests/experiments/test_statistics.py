"""Statistics checked against values computed by hand."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats as scipy_stats

from experiments import statistics as st


def test_moving_average_by_hand():
    np.testing.assert_allclose(st.moving_average(np.array([2.0, 4, 6, 8]), 2), [2, 3, 5, 7])
    runs = np.array([[1.0, 2, 3], [3, 3, 3]])
    np.testing.assert_allclose(st.moving_average(runs, 3), [[1, 1.5, 2], [3, 3, 3]])


def test_convergence_of_a_step_curve():
    steps = np.r_[np.full(80, 100.0), np.full(220, 20.0)]
    # The 10-episode average first holds only 20s at episode 90 and stays there.
    assert st.convergence_episode(steps, window=10, final_window=100) == 90


def test_no_convergence_when_still_falling_or_stuck():
    falling = np.linspace(1000, 10, 300)
    assert st.convergence_episode(falling, window=10, final_window=100) is None
    stuck = np.full(300, 5000.0)
    assert st.convergence_episode(stuck, window=10, final_window=100, final_success=0.0) is None
    assert st.convergence_episode(stuck, window=10, final_window=100, final_success=1.0) == 1


def test_probability_of_improvement_by_hand():
    assert st.probability_of_improvement(np.array([1.0, 2]), np.array([2.0, 3])) == 0.875
    assert st.probability_of_improvement(np.array([1.0, 3]), np.array([2.0])) == 0.5
    assert st.probability_of_improvement(np.array([5.0]), np.array([5.0])) == 0.5
    assert st.probability_of_improvement(np.array([1.0, 1]), np.array([9.0, 8])) == 1.0


def test_interquartile_mean_by_hand():
    assert st.interquartile_mean(np.array([1.0, 2, 3, 4, 5, 6, 7, 100])) == 4.5


def test_bootstrap_band_is_seeded_and_brackets_the_mean():
    rng = np.random.default_rng(0)
    runs = rng.normal(10, 2, size=(20, 50))
    mean, low, high = st.bootstrap_mean_band(runs, seed=3)
    np.testing.assert_allclose(mean, runs.mean(axis=0))
    assert np.all(low <= mean)
    assert np.all(mean <= high)
    again = st.bootstrap_mean_band(runs, seed=3)
    np.testing.assert_array_equal(again[1], low)
    # Roughly a 95% interval of a mean of 20 normal draws: +-1.96 * 2 / sqrt(20).
    assert np.mean(high - low) == pytest.approx(2 * 1.96 * 2 / np.sqrt(20), rel=0.2)
    single = st.bootstrap_mean_band(runs[:1])
    np.testing.assert_array_equal(single[1], runs[0])


def test_bootstrap_ci_agrees_with_the_normal_interval():
    scores = np.random.default_rng(1).normal(50, 5, 40)
    low, high = st.bootstrap_ci(scores, seed=0)
    half = scipy_stats.t.ppf(0.975, 39) * scores.std(ddof=1) / np.sqrt(40)
    assert low == pytest.approx(scores.mean() - half, abs=0.6)
    assert high == pytest.approx(scores.mean() + half, abs=0.6)


def test_one_run_gives_no_interval_and_equal_runs_a_point():
    """A 95% interval from one score would claim a spread of zero: it is NaN ("n/a" in the
    reports). Equal scores resample only to themselves, so their interval is the value."""
    low, high = st.bootstrap_ci(np.array([42.0]))
    assert np.isnan(low)
    assert np.isnan(high)
    assert st.bootstrap_ci(np.array([3.0, 3.0, 3.0])) == (3.0, 3.0)


def test_summarize_rows():
    steps = np.array([[100.0] * 50 + [10.0] * 150, [5000.0] * 200])
    success = (steps < 5000).astype(float)
    leaves = np.tile(np.arange(200.0), (2, 1))
    row = st.summarize(
        "s",
        steps,
        success,
        leaves,
        baseline_final=np.array([20.0, 20.0]),
        window=10,
        final_window=100,
    )
    np.testing.assert_allclose(row.final_steps, [10, 5000])
    np.testing.assert_allclose(row.success_rate, [1, 0])
    assert row.convergence == [60, None]
    assert row.converged_runs == 1
    assert row.p_improvement == 0.5
    np.testing.assert_allclose(row.auc, [(50 * 100 + 150 * 10) / 200, 5000])
    np.testing.assert_allclose(row.leaves, [199, 199])
