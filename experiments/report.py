"""The report of an experiment: ``report.md``, ``summary.csv`` and the figures, in its folder.

Metrics (defined in ``docs/experiments.md``): episodes to convergence, final steps (last
``final_window`` episodes) and their ratio to the optimum, area under the curve, success rate
(capped episodes count as failures at the cap), leaves, interquartile mean, probability of
improvement over the baseline, wall time and steps per second.

Only verified runs computed from the experiment's inputs enter it (:func:`runner.inspect_folder`);
every run left out is listed by name with the reason, and runs accepted despite another code
version (``--accept-code-change``) are listed as such.
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from experiments import plots, store
from experiments.config import ExperimentConfig
from experiments.runner import FolderState, Task, inspect_folder, results_of
from experiments.statistics import (
    StrategySummary,
    bootstrap_ci,
    interquartile_mean,
    interval_text,
    summarize,
)
from experiments.training import train_run

REPORT_FILE = "report.md"
SUMMARY_FILE = "summary.csv"
FIGURE4_FILE = "figure4.png"
LEAVES_FILE = "leaves.png"


@dataclass(frozen=True)
class Report:
    """What :func:`write_report` produced."""

    markdown: Path
    summary_csv: Path
    figures: tuple[Path, ...]
    summaries: tuple[StrategySummary, ...]
    optimal_steps: float
    excluded: tuple[store.RunCheck, ...] = ()
    """Runs on disk left out (damaged, or computed from other inputs), with the reasons."""
    accepted: tuple[store.RunCheck, ...] = ()
    """Runs included although their code version differs (``accept_code_change``)."""
    not_run: tuple[str, ...] = ()
    """Planned runs that have not run yet (``--only``, or a cut experiment), by name."""


def write_report(
    config: ExperimentConfig,
    out_dir: Path,
    seed: int = 0,
    task: Task = train_run,
    accept_code_change: bool = False,
) -> Report:
    """Compute the statistics of every finished, verified run in ``out_dir`` and write the
    report (``task`` is the function that computed the runs: part of their inputs)."""
    state = inspect_folder(config, out_dir, task, None, accept_code_change)
    excluded = tuple(check for _, check in state.excluded)
    accepted = tuple(check for _, check in state.code_changed) if accept_code_change else ()
    not_run = tuple(spec.name for spec in state.not_run)
    results = {name: runs for name, runs in results_of(config, state).items() if runs}
    if not results:
        left_out = f"; left out: {listing(excluded)}" if excluded else ""
        raise ValueError(f"{out_dir}: no finished runs to report{left_out}")
    optimal = _optimal_steps(results)
    window, final_window = config.smoothing_window, config.final_episodes
    baseline_runs = results.get(config.baseline_name)
    baseline_final = (
        None
        if baseline_runs is None
        else _stack(baseline_runs, "steps")[:, -final_window:].mean(axis=1)
    )
    summaries = tuple(
        summarize(
            name,
            _stack(runs, "steps"),
            _stack(runs, "success"),
            _stack(runs, "leaves"),
            baseline_final,
            window=window,
            final_window=final_window,
            tolerance=config.convergence_tolerance,
            wall_time_s=np.array([r.meta.get("wall_time_s", np.nan) for r in runs]),
            steps_per_second=np.array([r.meta.get("steps_per_second", np.nan) for r in runs]),
        )
        for name, runs in results.items()
    )
    bands = plots.smoothed_bands(
        {n: _stack(r, "steps") for n, r in results.items()}, window, seed=seed
    )
    runs_count = {name: len(runs) for name, runs in results.items()}
    figures = (
        plots.figure4(
            bands,
            optimal,
            out_dir / FIGURE4_FILE,
            window,
            runs_count,
            cap=config.env.max_episode_steps,
            title=f"{config.name}: average steps to goal "
            f"({window}-episode moving average, 95% bootstrap band)",
        ),
        plots.leaves_figure(
            {n: _stack(r, "leaves") for n, r in results.items()}, out_dir / LEAVES_FILE
        ),
    )
    summary_csv = out_dir / SUMMARY_FILE
    store.atomic_write_text(summary_csv, _summary_csv(summaries, optimal))
    markdown = out_dir / REPORT_FILE
    text = (
        render_markdown(config, summaries, optimal, seed)
        + _evaluation_section(config, results)
        + provenance(state)
    )
    store.atomic_write_text(markdown, text)
    return Report(markdown, summary_csv, figures, summaries, optimal, excluded, accepted, not_run)


def _evaluation_section(config: ExperimentConfig, results: dict[str, list[store.RunData]]) -> str:
    """The greedy evaluation's table (``eval_episodes``), empty without one."""
    if not config.eval_episodes:
        return ""
    lines = [
        "## Greedy evaluation",
        "",
        f"{config.eval_episodes} greedy episodes per run after training, the first reset seeded "
        "from the run's seed (`runs/<run>.eval.csv`); means over runs of each run's mean.",
        "",
        "| strategy | runs | greedy success | greedy steps | greedy return |",
        "|---|---:|---:|---:|---:|",
    ]
    for name, runs in results.items():
        evaluations = [r.evaluation for r in runs if r.evaluation is not None]
        if not evaluations:
            continue
        success, steps, returns = (
            float(np.mean([e[column].mean() for e in evaluations]))
            for column in ("success", "steps", "return")
        )
        lines.append(
            f"| {name} | {len(evaluations)} | {success:.3f} | {steps:.1f} | {returns:.2f} |"
        )
    return "\n".join([*lines, "", ""])


def listing(checks: tuple[store.RunCheck, ...]) -> str:
    return "; ".join(f"{c.name} ({c.reason})" for c in checks)


def provenance(state: FolderState) -> str:
    """The report's sections on planned runs not run yet, runs left out and runs accepted
    under another code version (``--accept-code-change``), all read from the folder's state."""
    excluded = [check for _, check in state.excluded]
    accepted = [check for _, check in state.code_changed] if state.accept_code_change else []
    lines: list[str] = []
    if state.not_run:
        counts = Counter(spec.strategy.name for spec in state.not_run)
        lines += [
            "## Runs not run yet",
            "",
            f"{len(state.not_run)} of the {len(state.planned)} planned runs have not run "
            f"({', '.join(f'`{name}` {n}' for name, n in counts.items())}), so this report covers "
            f"{len(state.finished)} finished runs, and `episodes.csv` and `evaluation.csv`, which "
            "merge every planned run, are not written. Running the experiment again (without "
            "`--only`) computes the rest.",
            "",
        ]
    if accepted:
        lines += [
            "## Runs from another code version (accepted)",
            "",
            "These runs verify but were computed by another version of the code; they are "
            "included because the experiment was run with `--accept-code-change`:",
            "",
            *(f"- `{c.name}`: {', '.join(c.differences)}" for c in accepted),
            "",
        ]
    if excluded:
        lines += [
            "## Runs left out",
            "",
            *(f"- `{c.name}`: {c.status}: {c.reason}" for c in excluded),
            "",
        ]
    return "\n".join(lines)


def _stack(runs: list[store.RunData], column: str) -> np.ndarray:
    """Runs x episodes array of one column (every verified run has the experiment's episodes)."""
    return np.stack([r.columns[column] for r in runs]).astype(float)


def _optimal_steps(results: dict[str, list[store.RunData]]) -> float:
    for runs in results.values():
        for run in runs:
            value = run.meta.get("optimal_steps")
            if value is not None and math.isfinite(value):
                return float(value)
    return float("nan")


def _summary_csv(summaries: tuple[StrategySummary, ...], optimal: float) -> str:
    columns = (
        "strategy",
        "runs",
        "converged_runs",
        "median_convergence_episode",
        "curve_convergence_episode",
        "final_steps_mean",
        "final_steps_iqm",
        "final_to_optimal",
        "auc_mean_steps",
        "success_rate",
        "final_success_rate",
        "leaves_mean",
        "p_improvement",
        "wall_time_s_mean",
        "steps_per_second_mean",
    )
    rows = []
    for s in summaries:
        final = float(np.mean(s.final_steps))
        rows.append(
            (
                s.strategy,
                s.runs,
                s.converged_runs,
                "" if s.median_convergence is None else s.median_convergence,
                "" if s.curve_convergence is None else s.curve_convergence,
                final,
                interquartile_mean(s.final_steps),
                final / optimal if optimal else math.nan,
                float(np.mean(s.auc)),
                float(np.mean(s.success_rate)),
                float(np.mean(s.final_success_rate)),
                float(np.mean(s.leaves)),
                s.p_improvement,
                _nanmean(s.wall_time_s),
                _nanmean(s.steps_per_second),
            )
        )
    return store.format_rows(rows, columns)


def render_markdown(
    config: ExperimentConfig, summaries: tuple[StrategySummary, ...], optimal: float, seed: int = 0
) -> str:
    """The report's Markdown text."""
    cap = config.env.max_episode_steps
    window, final_window = config.smoothing_window, config.final_episodes
    episodes = config.episodes
    lines = [
        f"# {config.name}",
        "",
        config.description.strip() or "",
        "",
        f"- environment: `{config.env.id}`, maze `{config.env.maze}`, robot "
        f"`{config.env.robot}`, mode `{config.env.mode}`, cap {cap} steps",
        f"- {episodes} episodes per run; runs per strategy as listed (common random seeds: run "
        f"i uses the same environment and agent seeds for every strategy; experiment seed "
        f"{config.seed})",
        f"- optimal number of steps: {_num(optimal)}",
        f"- baseline for the probability of improvement: `{config.baseline_name}`",
        f"- curves: each run smoothed by a trailing {window}-episode moving average, then the "
        "mean over runs with a 95% percentile bootstrap band (runs resampled with replacement)",
        "",
        f"![Figure 4 analog]({FIGURE4_FILE})",
        "",
        "| strategy | runs | converged runs | episodes to convergence (median of runs) | "
        "mean curve converges at | final steps, mean [95% CI] | IQM | final / optimal | "
        "AUC (mean steps per episode) | success rate | final success | leaves | "
        f"P(improvement) over {config.baseline_name} | wall time per run (s) | steps/s |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for s in summaries:
        final = float(np.mean(s.final_steps))
        low, high = bootstrap_ci(s.final_steps, seed=seed)
        lines.append(
            f"| {s.strategy} | {s.runs} | {s.converged_runs} | "
            f"{_maybe(s.median_convergence)} | {_maybe(s.curve_convergence)} | "
            f"{final:.1f} {interval_text(low, high)} | {interquartile_mean(s.final_steps):.1f} | "
            f"{_ratio(final, optimal)} | {np.mean(s.auc):.1f} | "
            f"{np.mean(s.success_rate):.3f} | {np.mean(s.final_success_rate):.3f} | "
            f"{np.mean(s.leaves):.0f} | {_num(s.p_improvement, 2)} | "
            f"{_num(_nanmean(s.wall_time_s), 1)} | {_num(_nanmean(s.steps_per_second), 0)} |"
        )
    lines += [
        "",
        f"![Leaves]({LEAVES_FILE})",
        "",
        "## Definitions",
        "",
        f"- **Episodes to convergence**: the first episode after which the run's {window}-episode "
        f"moving average of steps stays within {config.convergence_tolerance:.0%} of its final "
        f"value (the mean of its last "
        f"{final_window} episodes). *Not converged* when that only happens within the last "
        f"{final_window} episodes, or when fewer than half of them reached the goal.",
        f"- **Final steps**: mean steps of the last {final_window} episodes of a run (a capped "
        f"episode counts as {cap} steps); the CI is a 95% percentile bootstrap over runs; "
        "**IQM** is the interquartile mean over runs.",
        "- **AUC**: area under the steps-per-episode curve divided by the number of episodes "
        "(mean steps per episode over the whole run; lower is better).",
        "- **Success rate**: fraction of all episodes that reached the goal; **final success**: "
        f"of the last {final_window}.",
        "- **Leaves**: size of the partition (grid cells for a grid agent) at the end of a run.",
        "- **P(improvement)**: probability that a run of the strategy has fewer final steps than "
        "a run of the baseline, Mann-Whitney U / (n_x n_y), ties counted one half (Agarwal et "
        "al., NeurIPS 2021); 0.5 means no difference.",
        "- **Wall time** and **steps/s** (environment and agent together) depend on the machine "
        "and its load; everything else is determined by the seeds.",
        "",
    ]
    return "\n".join(lines)


def _nanmean(values: np.ndarray) -> float:
    finite = np.asarray(values, dtype=float)
    finite = finite[np.isfinite(finite)]
    return float(finite.mean()) if finite.size else math.nan


def _maybe(value: float | None) -> str:
    return "not converged" if value is None else f"{value:.0f}"


def _num(value: float, digits: int = 1) -> str:
    return "n/a" if not math.isfinite(value) else f"{value:.{digits}f}"


def _ratio(value: float, optimal: float) -> str:
    return "n/a" if not (math.isfinite(optimal) and optimal > 0) else f"{value / optimal:.2f}"
