"""Scores aggregated over tasks and runs, as rliable does (Agarwal et al., "Deep Reinforcement
Learning at the Edge of the Statistical Precipice", NeurIPS 2021).

Each run of each task gives one normalised score (:mod:`experiments.task_scores`). Over a set
of tasks, a strategy gets:

- the **interquartile mean** (IQM) of all its scores (runs x tasks pooled, 25% trimmed from
  each end) with a 95% **stratified bootstrap** confidence interval: each resample draws runs
  with replacement within every task, and the tasks stay fixed;
- a **performance profile**: the fraction of its runs whose score is at least as good as each
  threshold tau, with a stratified-bootstrap band;
- the **probability of improvement** over a baseline: the mean over tasks of
  P(a run of the strategy scores better than a run of the baseline) (ties count one half;
  the Mann-Whitney U statistic over n_x n_y), with a 95% interval from resampling the two
  strategies' runs independently within every task.

The resampling is ``scipy.stats.bootstrap`` (percentile intervals, as rliable's default) with a
``numpy.random.Generator`` made from an explicit seed, never a hand-written loop. rliable
itself is not used: its 1.2.0 release draws its bootstrap indices from numpy's global random
state (``np.random.choice`` in ``StratifiedBootstrap.update_indices``), ignoring the
``random_state`` it is given, and brings arch, pandas, seaborn and absl-py with it.

A task with a single run is a stratum that resamples to itself: it enters every resample
unchanged (scipy needs two observations to resample a sample).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from scipy import stats as scipy_stats

RESAMPLES = 10_000
"""Bootstrap resamples of each interval (rliable's examples use 2,000 to 50,000)."""
BATCH = 500
"""Resamples computed at once (bounds the memory of a profile's runs x thresholds arrays)."""
CONFIDENCE = 0.95
"""Confidence level of every interval."""

Seed = int | Sequence[int]
"""What ``numpy.random.default_rng`` takes: each interval's own seed (an int or a key)."""
Scores = Sequence[np.ndarray]
"""One array of per-run scores for each task (tasks may have different numbers of runs)."""


@dataclass(frozen=True)
class Estimate:
    """A point estimate with its 95% bootstrap interval."""

    value: float
    low: float
    high: float


def interquartile_mean(values: np.ndarray, axis: int = -1) -> np.ndarray:
    """Mean of the middle 50% of ``values`` along ``axis`` (``scipy.stats.trim_mean``, 0.25)."""
    return np.asarray(scipy_stats.trim_mean(values, 0.25, axis=axis))


def _pooled(fixed: list[np.ndarray], samples: tuple[np.ndarray, ...], axis: int) -> np.ndarray:
    """The resampled strata and the fixed (one-run) ones, concatenated along ``axis``."""
    if not samples:
        return np.concatenate(fixed)
    batch = samples[0].shape[:-1]
    constant = [np.broadcast_to(f, (*batch, f.size)) for f in fixed]
    return np.concatenate([*samples, *constant], axis=axis)


def _split(scores: Scores) -> tuple[list[np.ndarray], list[np.ndarray]]:
    arrays = [np.asarray(s, dtype=float).reshape(-1) for s in scores]
    if not arrays or any(a.size == 0 for a in arrays):
        raise ValueError("every task needs at least one run")
    return [a for a in arrays if a.size > 1], [a for a in arrays if a.size == 1]


def stratified_estimate(
    scores: Scores, statistic: Callable[[np.ndarray], np.ndarray], seed: Seed
) -> Estimate:
    """``statistic`` (a function of the pooled scores along the last axis, vectorized) of
    every run of every task, with its 95% stratified bootstrap interval."""
    resampled, fixed = _split(scores)
    value = float(statistic(np.concatenate([*resampled, *fixed])))
    if not resampled:  # one run per task: nothing to resample, so no interval
        return Estimate(value, math.nan, math.nan)

    low, high = _pooled_interval(resampled, fixed, statistic, seed)
    return Estimate(value, float(low), float(high))


def _pooled_interval(
    resampled: list[np.ndarray],
    fixed: list[np.ndarray],
    statistic: Callable[[np.ndarray], np.ndarray],
    seed: Seed,
) -> tuple[np.ndarray, np.ndarray]:
    """The 95% percentile bootstrap interval of ``statistic`` of the pooled scores, each task's
    runs resampled within the task (stratified) and the single-run tasks held fixed."""

    def pooled(*samples: np.ndarray, axis: int = -1) -> np.ndarray:
        return statistic(_pooled(fixed, samples, axis))

    result = scipy_stats.bootstrap(
        tuple(resampled),
        pooled,
        n_resamples=RESAMPLES,
        confidence_level=CONFIDENCE,
        method="percentile",
        vectorized=True,
        batch=BATCH,
        rng=np.random.default_rng(seed),
    )
    interval = result.confidence_interval
    return interval.low, interval.high


def iqm(scores: Scores, seed: Seed) -> Estimate:
    """Interquartile mean of every run of every task, with its stratified bootstrap interval."""
    return stratified_estimate(scores, interquartile_mean, seed)


def profile(
    scores: Scores, thresholds: np.ndarray, lower_is_better: bool, seed: Seed
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The performance profile: for each threshold tau, the fraction of all runs (of all tasks)
    scoring at most tau (``lower_is_better``) or at least tau, with a 95% stratified
    bootstrap band; returns (fraction, low, high), each of the thresholds' length."""
    taus = np.asarray(thresholds, dtype=float)

    def fraction(pooled: np.ndarray) -> np.ndarray:
        data = pooled[..., None, :]
        taus_axis = taus.reshape((1,) * (pooled.ndim - 1) + (-1, 1))
        hits = data <= taus_axis if lower_is_better else data >= taus_axis
        return np.moveaxis(hits.mean(axis=-1), -1, 0)

    resampled, fixed = _split(scores)
    value = fraction(np.concatenate([*resampled, *fixed]))
    if not resampled:
        return value, value.copy(), value.copy()

    low, high = _pooled_interval(resampled, fixed, fraction, seed)
    return value, np.asarray(low), np.asarray(high)


def _improvement(x: np.ndarray, y: np.ndarray, lower_is_better: bool) -> np.ndarray:
    """P(x beats y) along the last axes (every pair of runs; ties one half)."""
    a, b = x[..., :, None], y[..., None, :]
    better = (a < b) if lower_is_better else (a > b)
    return (better + 0.5 * (a == b)).mean(axis=(-2, -1))


def probability_of_improvement(
    candidate: Scores, baseline: Scores, lower_is_better: bool, seed: Seed
) -> Estimate:
    """Mean over tasks of P(a candidate run scores better than a baseline run of the same
    task), with a 95% interval from resampling both strategies' runs within each task."""
    if len(candidate) != len(baseline) or not candidate:
        raise ValueError("the candidate and the baseline need runs of the same tasks")
    xs = [np.asarray(s, dtype=float).reshape(-1) for s in candidate]
    ys = [np.asarray(s, dtype=float).reshape(-1) for s in baseline]
    if any(a.size == 0 for a in (*xs, *ys)):
        raise ValueError("every task needs at least one run of each strategy")
    value = float(
        np.mean([_improvement(x, y, lower_is_better) for x, y in zip(xs, ys, strict=True)])
    )
    arrays = [*xs, *ys]
    movable = [i for i, a in enumerate(arrays) if a.size > 1]
    if not movable:
        return Estimate(value, value, value)
    tasks = len(xs)

    def statistic(*samples: np.ndarray, axis: int = -1) -> np.ndarray:
        batch = samples[0].shape[:-1]
        full = [np.broadcast_to(a, (*batch, a.size)) for a in arrays]
        for index, sample in zip(movable, samples, strict=True):
            full[index] = sample
        per_task = [_improvement(full[i], full[tasks + i], lower_is_better) for i in range(tasks)]
        return np.mean(per_task, axis=0)

    result = scipy_stats.bootstrap(
        tuple(arrays[i] for i in movable),
        statistic,
        n_resamples=RESAMPLES,
        confidence_level=CONFIDENCE,
        method="percentile",
        vectorized=True,
        batch=BATCH,
        rng=np.random.default_rng(seed),
    )
    interval = result.confidence_interval
    return Estimate(value, float(interval.low), float(interval.high))
