"""Statistics of learning curves, as recommended by Agarwal et al. (NeurIPS 2021).

All functions take per-run arrays (runs x episodes, or one score per run) and are pure;
every resampling draws from a ``numpy.random.Generator`` made from an explicit seed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import stats as scipy_stats


def moving_average(values: np.ndarray, window: int) -> np.ndarray:
    """Trailing moving average along the last axis; the first ``window - 1`` use what exists.

    Entry t is the mean of episodes ``max(0, t - window + 1) .. t``, so the curve has as many
    points as episodes and never looks ahead.
    """
    if window < 1:
        raise ValueError(f"window must be >= 1, got {window}")
    data = np.asarray(values, dtype=float)
    cumulative = np.cumsum(data, axis=-1)
    result = cumulative.copy()
    result[..., window:] = cumulative[..., window:] - cumulative[..., :-window]
    counts = np.minimum(np.arange(1, data.shape[-1] + 1), window)
    return result / counts


def bootstrap_mean_band(
    runs: np.ndarray, confidence: float = 0.95, resamples: int = 2000, seed: int = 0
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mean over runs (axis 0) with a percentile bootstrap confidence band, per column.

    Every resample draws runs with replacement (the same draw for every column, so the band
    is that of whole curves). Computed as multinomial weights times the data, which needs
    memory for ``resamples x columns`` only. With one run the band is the curve itself.
    """
    data = np.atleast_2d(np.asarray(runs, dtype=float))
    n = data.shape[0]
    mean = data.mean(axis=0)
    if n < 2:
        return mean, mean.copy(), mean.copy()
    rng = np.random.default_rng(seed)
    weights = rng.multinomial(n, np.full(n, 1.0 / n), size=resamples) / n
    means = weights @ data
    tail = (1.0 - confidence) / 2.0 * 100.0
    low, high = np.percentile(means, [tail, 100.0 - tail], axis=0)
    return mean, low, high


def bootstrap_ci(
    scores: np.ndarray, statistic: str = "mean", confidence: float = 0.95, seed: int = 0
) -> tuple[float, float]:
    """Percentile bootstrap interval of the mean or IQM of per-run scores (scipy.stats); NaN
    for fewer than two scores (one run says nothing about the spread), and the value itself
    when every score is equal (every resample is)."""
    data = np.asarray(scores, dtype=float)
    if data.size < 2:
        return float("nan"), float("nan")
    if np.all(data == data[0]):
        return float(data[0]), float(data[0])
    function = np.mean if statistic == "mean" else interquartile_mean
    result = scipy_stats.bootstrap(
        (data,),
        function,
        confidence_level=confidence,
        n_resamples=2000,
        method="percentile",
        rng=np.random.default_rng(seed),
        vectorized=False,
    )
    return float(result.confidence_interval.low), float(result.confidence_interval.high)


def interval_text(low: float, high: float, form: str = ".1f") -> str:
    """An interval as the reports print it: ``[low, high]`` in the format ``form``, or ``[n/a]``
    where there is none (one run or one agent: :func:`bootstrap_ci`'s NaN)."""
    if not (math.isfinite(low) and math.isfinite(high)):
        return "[n/a]"
    return f"[{low:{form}}, {high:{form}}]"


def interquartile_mean(scores: np.ndarray) -> float:
    """Mean of the middle 50% of the scores (25% trimmed from each end)."""
    data = np.asarray(scores, dtype=float)
    return float(scipy_stats.trim_mean(data, 0.25)) if data.size else float("nan")


def probability_of_improvement(candidate: np.ndarray, baseline: np.ndarray) -> float:
    """P(a candidate run scores fewer steps than a baseline run); ties count one half.

    The Mann-Whitney U statistic divided by ``n_x n_y`` (Agarwal et al. 2021), with "better"
    meaning fewer steps, so 0.5 is no difference and 1 is "every candidate run beats every
    baseline run".
    """
    x = np.asarray(candidate, dtype=float)
    y = np.asarray(baseline, dtype=float)
    if x.size == 0 or y.size == 0:
        return float("nan")
    statistic = scipy_stats.mannwhitneyu(y, x, alternative="two-sided").statistic
    return float(statistic) / (x.size * y.size)


def convergence_episode(
    steps: np.ndarray,
    window: int = 50,
    tolerance: float = 0.1,
    final_window: int = 100,
    final_success: float | None = None,
    min_final_success: float = 0.5,
) -> int | None:
    """Episode (1-based) after which the moving average stays within ``tolerance`` of the end.

    The end value is the mean of the last ``final_window`` episodes. The run has converged at
    the first episode t such that the ``window``-episode moving average at every episode from
    t on lies within ``tolerance`` x end value of it. ``None`` ("not converged") when that
    stretch starts inside the final window itself (it was never stable before the end), or
    when fewer than ``min_final_success`` of the final episodes reached the goal (a run stuck
    at the cap is "stable" at failure); ``final_success`` is that fraction, when known.
    """
    data = np.asarray(steps, dtype=float)
    episodes = data.size
    if episodes <= final_window:
        return None
    final = data[-final_window:]
    if final_success is not None and final_success < min_final_success:
        return None
    end = float(final.mean())
    smooth = moving_average(data, window)
    outside = np.abs(smooth - end) > tolerance * end
    if not outside.any():
        return 1
    last_outside = int(np.flatnonzero(outside)[-1])
    first_stable = last_outside + 1
    if first_stable >= episodes - final_window:
        return None
    return first_stable + 1


@dataclass(frozen=True)
class StrategySummary:
    """The report's row for one strategy (scores are per-run values, lower steps better)."""

    strategy: str
    runs: int
    final_steps: np.ndarray
    """Mean steps of each run's last ``final_window`` episodes."""
    auc: np.ndarray
    """Each run's area under the steps curve: mean steps per episode over the whole run."""
    success_rate: np.ndarray
    """Each run's fraction of episodes that reached the goal (capped ones did not)."""
    final_success_rate: np.ndarray
    """Each run's fraction of its last ``final_window`` episodes that reached the goal."""
    leaves: np.ndarray
    """Leaves (or cells) of each run at its last episode."""
    convergence: list[int | None]
    """Each run's convergence episode (None: not converged)."""
    curve_convergence: int | None
    """Convergence episode of the mean curve over runs."""
    wall_time_s: np.ndarray
    steps_per_second: np.ndarray
    p_improvement: float
    """Probability of improvement of the final steps over the baseline's."""

    @property
    def converged_runs(self) -> int:
        """How many runs converged."""
        return sum(c is not None for c in self.convergence)

    @property
    def median_convergence(self) -> float | None:
        """Median convergence episode of the runs that converged."""
        done = [c for c in self.convergence if c is not None]
        return float(np.median(done)) if done else None


def summarize(
    strategy: str,
    steps: np.ndarray,
    successes: np.ndarray,
    leaves: np.ndarray,
    baseline_final: np.ndarray | None,
    window: int = 50,
    final_window: int = 100,
    tolerance: float = 0.1,
    wall_time_s: np.ndarray | None = None,
    steps_per_second: np.ndarray | None = None,
) -> StrategySummary:
    """Compute a strategy's row from its runs x episodes arrays."""
    steps = np.atleast_2d(np.asarray(steps, dtype=float))
    successes = np.atleast_2d(np.asarray(successes, dtype=float))
    leaves = np.atleast_2d(np.asarray(leaves, dtype=float))
    final_window = min(final_window, steps.shape[1])
    final = steps[:, -final_window:].mean(axis=1)
    final_success = successes[:, -final_window:].mean(axis=1)
    nan = np.full(steps.shape[0], np.nan)
    return StrategySummary(
        strategy=strategy,
        runs=steps.shape[0],
        final_steps=final,
        auc=steps.mean(axis=1),
        success_rate=successes.mean(axis=1),
        final_success_rate=final_success,
        leaves=leaves[:, -1],
        convergence=[
            convergence_episode(
                run, window, tolerance, final_window=final_window, final_success=rate
            )
            for run, rate in zip(steps, final_success, strict=True)
        ],
        curve_convergence=convergence_episode(
            steps.mean(axis=0),
            window,
            tolerance,
            final_window=final_window,
            final_success=float(final_success.mean()),
        ),
        wall_time_s=nan if wall_time_s is None else np.asarray(wall_time_s, dtype=float),
        steps_per_second=(
            nan if steps_per_second is None else np.asarray(steps_per_second, dtype=float)
        ),
        p_improvement=(
            float("nan")
            if baseline_final is None
            else probability_of_improvement(final, baseline_final)
        ),
    )
