"""The report of an experiment over tasks (a layout suite, or ``[[task]]`` tables).

Written into the results folder: ``report.md`` (the aggregate over tasks and runs, one table
per task, definitions), ``summary.csv`` (one row per task and strategy), ``aggregate.csv`` (one
row per group, score and strategy), ``curves.png`` (one panel per task) and one performance
profile per group, ``profile_<group>.png``. Scores and aggregates are defined in
:mod:`experiments.task_scores` and :mod:`experiments.aggregate`; every bootstrap draws from a
generator seeded from the report's seed, so the same runs give the same report.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from experiments import aggregate, plots, store
from experiments.config import ExperimentConfig
from experiments.report import listing, provenance
from experiments.runner import Task, inspect_folder, results_by_task
from experiments.statistics import interval_text
from experiments.task_scores import (
    SCORES,
    Score,
    TaskSummary,
    groups,
    scores_of,
    summarize_task,
)
from experiments.training import train_run

REPORT_FILE = "report.md"
SUMMARY_FILE = "summary.csv"
AGGREGATE_FILE = "aggregate.csv"
CURVES_FILE = "curves.png"
PROFILE_POINTS = 200
"""Thresholds of a performance profile."""


@dataclass(frozen=True)
class AggregateRow:
    """One strategy's aggregate of one score over a group of tasks."""

    group: str
    score: Score
    strategy: str
    tasks: int
    runs: int
    iqm: aggregate.Estimate
    mean: float
    p_improvement: aggregate.Estimate | None
    """Over the baseline (None for the baseline itself, or without it on every task)."""


@dataclass(frozen=True)
class TaskReport:
    """What :func:`write_task_report` produced."""

    markdown: Path
    summary_csv: Path
    aggregate_csv: Path
    figures: tuple[Path, ...]
    tasks: tuple[TaskSummary, ...]
    aggregates: tuple[AggregateRow, ...]
    excluded: tuple[store.RunCheck, ...] = ()
    accepted: tuple[store.RunCheck, ...] = ()
    not_run: tuple[str, ...] = ()
    """Planned runs that have not run yet (``--only``, or a cut experiment), by name."""


def write_task_report(
    config: ExperimentConfig,
    out_dir: Path,
    seed: int = 0,
    task: Task = train_run,
    accept_code_change: bool = False,
) -> TaskReport:
    """Summarise every finished, verified run of an experiment over tasks and write the
    report's files (``ValueError`` if no run has finished)."""
    state = inspect_folder(config, out_dir, task, None, accept_code_change)
    excluded = tuple(check for _, check in state.excluded)
    accepted = tuple(check for _, check in state.code_changed) if accept_code_change else ()
    results = results_by_task(config, state)
    summaries = tuple(
        summarize_task(config, spec, results[spec.name])
        for spec in config.tasks
        if any(results[spec.name].values())
    )
    if not summaries:
        left_out = f"; left out: {listing(excluded)}" if excluded else ""
        raise ValueError(f"{out_dir}: no finished runs to report{left_out}")
    grouped = groups(summaries)
    rows = tuple(_aggregate_rows(config, grouped, seed))
    figures = [_curves(config, summaries, out_dir / CURVES_FILE, seed)]
    figures += [
        _profile(config, group, tasks, out_dir, (seed, index))
        for index, (group, tasks) in enumerate(grouped.items())
    ]
    summary_csv = out_dir / SUMMARY_FILE
    store.atomic_write_text(summary_csv, _summary_csv(summaries))
    aggregate_csv = out_dir / AGGREGATE_FILE
    store.atomic_write_text(aggregate_csv, _aggregate_csv(rows))
    markdown = out_dir / REPORT_FILE
    text = render_markdown(config, summaries, rows, grouped, seed)
    store.atomic_write_text(markdown, text + provenance(state))
    return TaskReport(
        markdown,
        summary_csv,
        aggregate_csv,
        tuple(figures),
        summaries,
        rows,
        excluded,
        accepted,
        tuple(spec.name for spec in state.not_run),
    )


def _aggregate_rows(
    config: ExperimentConfig, grouped: dict[str, list[TaskSummary]], seed: int
) -> list[AggregateRow]:
    rows = []
    baseline = config.baseline_name
    for g, (group, tasks) in enumerate(grouped.items()):
        for k, score in enumerate(SCORES[tasks[0].kind]):
            reference = scores_of(tasks, baseline, score.key)
            for s, strategy in enumerate(config.strategies):
                scores = scores_of(tasks, strategy.name, score.key)
                if scores is None:
                    continue
                improvement = None
                if reference is not None and strategy.name != baseline:
                    improvement = aggregate.probability_of_improvement(
                        scores, reference, score.lower_is_better, (seed, g, k, s, 1)
                    )
                pooled = np.concatenate(scores)
                rows.append(
                    AggregateRow(
                        group,
                        score,
                        strategy.name,
                        len(tasks),
                        int(pooled.size),
                        aggregate.iqm(scores, (seed, g, k, s, 0)),
                        float(pooled.mean()),
                        improvement,
                    )
                )
    return rows


def _thresholds(pooled: np.ndarray, lower_is_better: bool) -> np.ndarray:
    low, high = float(pooled.min()), float(pooled.max())
    if lower_is_better and low > 0:
        return np.geomspace(min(1.0, low), max(high, low * 1.01), PROFILE_POINTS)
    span = max(high - low, 1e-9)
    return np.linspace(low - 0.05 * span, high + 0.05 * span, PROFILE_POINTS)


def _profile_file(group: str) -> str:
    return f"profile_{re.sub(r'[^A-Za-z0-9]+', '_', group).strip('_')}.png"


def _profile(
    config: ExperimentConfig,
    group: str,
    tasks: list[TaskSummary],
    out_dir: Path,
    seed: tuple[int, int],
) -> Path:
    score = SCORES[tasks[0].kind][0]
    per_strategy = {
        s.name: found
        for s in config.strategies
        if (found := scores_of(tasks, s.name, score.key)) is not None
    }
    pooled = np.concatenate([np.concatenate(v) for v in per_strategy.values()])
    taus = _thresholds(pooled, score.lower_is_better)
    profiles = {
        name: aggregate.profile(scores, taus, score.lower_is_better, (*seed, i))
        for i, (name, scores) in enumerate(per_strategy.items())
    }
    return plots.performance_profile(
        taus,
        profiles,
        out_dir / _profile_file(group),
        f"tau ({score.label})",
        score.lower_is_better,
        f"{config.name}: performance profile over {len(tasks)} tasks ({group})",
    )


def _curves(
    config: ExperimentConfig, summaries: Sequence[TaskSummary], path: Path, seed: int
) -> Path:
    panels: list[plots.Panel] = []
    results_column = {"maze": "steps", "return": "return"}
    for summary in summaries:
        column = results_column[summary.kind]
        curves = {entry.strategy: entry.curves[column] for entry in summary.strategies}
        if summary.kind == "maze":
            references: tuple[tuple[str, float], ...] = (
                (f"optimal {summary.optimal_steps:g}", summary.optimal_steps),
            )
        else:
            refs = summary.references
            references = () if refs is None else (("solved", refs.solved_return),)
        ylabel = "steps" if summary.kind == "maze" else "return"
        panels.append((summary.task.name, curves, ylabel, references, summary.kind == "maze"))
    return plots.task_curves(panels, path, config.smoothing_window, seed)


# --- text ---------------------------------------------------------------------------------


def _num(value: float, digits: int = 2) -> str:
    return "n/a" if not math.isfinite(value) else f"{value:.{digits}f}"


def _return_num(value: float) -> str:
    """A mean return with at least three significant digits and one decimal: Blackjack's mean of
    -0.0523 is not "-0.1", and LunarLander's -166.3 stays as it is."""
    if not math.isfinite(value):
        return "n/a"
    magnitude = abs(value)
    digits = 1 if magnitude >= 10 or magnitude == 0 else 2 - math.floor(math.log10(magnitude))
    return f"{value:.{min(max(digits, 1), 6)}f}"


def _estimate(estimate: aggregate.Estimate | None, digits: int = 2) -> str:
    if estimate is None:
        return "-"
    bounds = interval_text(estimate.low, estimate.high, f".{digits}f")
    return f"{_num(estimate.value, digits)} {bounds}"


def _task_heading(summary: TaskSummary, config: ExperimentConfig) -> str:
    task = summary.task
    where = f"`{task.spec_text}`"
    if task.split is not None:
        where += f", {task.split} split"
    cap = task.env.max_episode_steps
    if summary.kind == "maze":
        return f"### {task.name} ({where}, cap {cap}, optimal {_num(summary.optimal_steps, 0)})"
    refs = summary.references
    ends = (
        f"random policy {refs.random_return:g}, solved {refs.solved_return:g}"
        if refs is not None
        else "no reference returns: not in the aggregate"
    )
    return f"### {task.name} ({where}, cap {cap}; {ends})"


def _improvement_on_task(summary: TaskSummary, config: ExperimentConfig, strategy: str) -> str:
    baseline = next((s for s in summary.strategies if s.strategy == config.baseline_name), None)
    entry = next(s for s in summary.strategies if s.strategy == strategy)
    if baseline is None:
        return "n/a"
    if summary.kind == "maze":
        x, y, lower = entry.summary.final_steps, baseline.summary.final_steps, True
    else:
        x, y, lower = entry.score_return, baseline.score_return, False
    return _num(aggregate.probability_of_improvement([x], [y], lower, 0).value)


def _maze_table(summary: TaskSummary, config: ExperimentConfig) -> list[str]:
    evaluated = config.eval_episodes > 0
    optimal = summary.optimal_steps
    head = (
        f"| strategy | runs | final steps (last {config.final_episodes}) | final / optimal | "
        "AUC (mean steps per episode) | AUC / optimal | success rate | "
        "episodes to convergence (median) | runs converged | "
        f"P(improvement) over {config.baseline_name} |"
    )
    rule = "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    if evaluated:
        head += f" greedy success ({config.eval_episodes} episodes) | greedy steps |"
        rule += "---:|---:|"
    lines = [head, rule]
    for entry in summary.strategies:
        s = entry.summary
        final, auc = float(np.mean(s.final_steps)), float(np.mean(s.auc))
        converged = (
            "not converged" if s.median_convergence is None else f"{s.median_convergence:.0f}"
        )
        line = (
            f"| {entry.strategy} | {s.runs} | {final:.1f} | {_num(final / optimal)} | "
            f"{auc:.1f} | {_num(auc / optimal)} | {np.mean(s.success_rate):.3f} | {converged} | "
            f"{s.converged_runs}/{s.runs} | "
            f"{_improvement_on_task(summary, config, entry.strategy)} |"
        )
        if evaluated:
            success = entry.greedy_success
            steps = entry.greedy_steps
            line += (
                f" {'-' if success is None else f'{np.mean(success):.3f}'} |"
                f" {'-' if steps is None else f'{np.mean(steps):.1f}'} |"
            )
        lines.append(line)
    return lines


def _return_table(summary: TaskSummary, config: ExperimentConfig) -> list[str]:
    evaluated = config.eval_episodes > 0
    refs = summary.references
    scored_by = (
        f"greedy return ({config.eval_episodes} episodes)"
        if evaluated
        else (f"training return (last {config.final_episodes})")
    )
    greedy_head = (  # (no column for a greedy evaluation that was not run)
        f"greedy return ({config.eval_episodes} episodes), mean | " if evaluated else ""
    )
    lines = [
        f"| strategy | runs | training return (last {config.final_episodes}), mean | "
        f"{greedy_head}runs solved ({scored_by} >= "
        f"{'n/a' if refs is None else f'{refs.solved_return:g}'}) | normalised score, mean | "
        f"P(improvement) over {config.baseline_name} |",
        "|---|---:|---:|" + ("---:|" if evaluated else "") + "---:|---:|---:|",
    ]
    for entry in summary.strategies:
        greedy = (
            "-" if entry.greedy_return is None else _return_num(float(np.mean(entry.greedy_return)))
        )
        greedy_cell = f"{greedy} | " if evaluated else ""
        solved = (
            "n/a"
            if refs is None
            else f"{int(np.sum(entry.score_return >= refs.solved_return))}/{entry.runs}"
        )
        score = entry.scores.get("normalised_return")
        final = _return_num(float(np.mean(entry.final_return)))
        lines.append(
            f"| {entry.strategy} | {entry.runs} | {final} | {greedy_cell}"
            f"{solved} | {'n/a' if score is None else _num(float(np.mean(score)))} | "
            f"{_improvement_on_task(summary, config, entry.strategy)} |"
        )
    return lines


def render_markdown(
    config: ExperimentConfig,
    summaries: Sequence[TaskSummary],
    rows: Sequence[AggregateRow],
    grouped: dict[str, list[TaskSummary]],
    seed: int = 0,
) -> str:
    """The report's Markdown text."""
    if config.suite is not None:
        what = f"the {len(config.tasks)} layouts of suite `{config.suite}`, split " + (
            " and ".join(config.splits)
        )
    else:
        what = f"{len(config.tasks)} tasks: " + ", ".join(f"`{t.name}`" for t in config.tasks)
    evaluation = (
        f"{config.eval_episodes} greedy episodes per run after training (the first reset seeded "
        "from the run's seed), stored in `runs/<task>/<run>.eval.csv`"
        if config.eval_episodes
        else "none (`[experiment] eval_episodes`)"
    )
    lines = [
        f"# {config.name}",
        "",
        config.description.strip(),
        "",
        f"- tasks: {what}; {len(summaries)} with finished runs",
        f"- {config.episodes} episodes per run; runs per strategy as listed (common random seeds: "
        "run i uses the same environment and agent seeds for every strategy and every task; "
        f"experiment seed {config.seed})",
        f"- greedy evaluation: {evaluation}",
        f"- baseline of the probability of improvement: `{config.baseline_name}`",
        "",
        "## Aggregate over tasks and runs",
        "",
        "Interquartile mean (IQM) of the normalised scores of every run of every task, with a "
        "95% stratified bootstrap interval (runs resampled within each task, "
        f"{aggregate.RESAMPLES:,} resamples, seed {seed}); P(improvement): mean over tasks of "
        "the probability that a run of the strategy scores better than a run of the baseline "
        "on the same task, with a 95% interval (Agarwal et al., NeurIPS 2021)."
        if grouped
        else "None: no task has a normalised score.",
        "",
    ]
    for group, tasks in grouped.items():
        lines += [f"### {group}: {len(tasks)} tasks", ""]
        for score in SCORES[tasks[0].kind]:
            better = "lower is better" if score.lower_is_better else "higher is better"
            lines += [
                f"**{score.label}** ({better})",
                "",
                "| strategy | tasks | runs | IQM [95% CI] | mean | "
                f"P(improvement) over {config.baseline_name} [95% CI] |",
                "|---|---:|---:|---:|---:|---:|",
            ]
            for row in rows:
                if row.group == group and row.score == score:
                    lines.append(
                        f"| {row.strategy} | {row.tasks} | {row.runs} | {_estimate(row.iqm)} | "
                        f"{_num(row.mean)} | {_estimate(row.p_improvement)} |"
                    )
            lines.append("")
        lines += [f"![performance profile, {group}]({_profile_file(group)})", ""]
    missing = [s.task.name for s in summaries if not s.scored]
    if missing:
        lines += [
            "Left out of the aggregate (no normalised score: a maze without an optimum, or a "
            "return task without reference returns; give `random_return` and `solved_return` "
            "in its `[[task]]` table, and write an `[env]` task as one such table to give "
            "them): " + ", ".join(f"`{m}`" for m in missing) + ".",
            "",
        ]
    lines += ["## Per task", "", f"![learning curves per task]({CURVES_FILE})", ""]
    for summary in summaries:
        table = _maze_table if summary.kind == "maze" else _return_table
        lines += [_task_heading(summary, config), "", *table(summary, config), ""]
    lines += _definitions(config, summaries)
    return "\n".join(lines)


def _definitions(config: ExperimentConfig, summaries: Sequence[TaskSummary]) -> list[str]:
    window, final_window = config.smoothing_window, config.final_episodes
    lines = ["## Definitions", ""]
    if any(s.kind == "maze" for s in summaries):
        lines += [
            f"- **final steps**: a run's mean steps over its last {final_window} episodes (a "
            "capped episode counts as the cap); **final / optimal** divides it by the layout's "
            "optimum (`env.unwrapped.optimal_steps`, in compass steps; 1 is optimal; none for "
            "native or continuous actions of a wheeled robot, whose steps it does not bound).",
            "- **AUC**: the area under the steps-per-episode curve divided by the number of "
            "episodes, i.e. mean steps per episode over the whole run (rewards learning fast); "
            "**AUC / optimal** divides it by the optimum.",
            "- **success rate**: fraction of all episodes that reached the goal.",
            f"- **episodes to convergence**: the first episode after which the run's {window}-"
            f"episode moving average stays within {config.convergence_tolerance:.0%} of its "
            "final value; not converged when that happens only in the final window or when "
            "fewer than half of the final episodes reached the goal. **runs converged** counts "
            "the runs that did.",
            "- **P(improvement)** in a task's table: probability that a run of the strategy "
            "ends with fewer final steps than a run of the baseline (ties one half).",
        ]
    if any(s.kind == "return" for s in summaries):
        scored = (
            f"its mean greedy return over its {config.eval_episodes} evaluation episodes"
            if config.eval_episodes
            else f"its mean training return over its last {final_window} episodes"
        )
        lines.append(
            f"- **normalised score** of a return task's run: (R - random) / (solved - random), "
            f"R {scored}; 0 is a uniformly random policy, 1 the solved threshold. "
            "**runs solved**: runs whose R reaches the solved threshold."
        )
        sources = [
            f"`{s.task.name}`: {s.references.source}" for s in summaries if s.references is not None
        ]
        lines.append(
            "- reference returns: " + "; ".join(sources)
            if sources
            else "- reference returns: none (no task gives `random_return` and `solved_return`)"
        )
    lines.append("")
    return lines


# --- tables -------------------------------------------------------------------------------


def _summary_csv(summaries: Sequence[TaskSummary]) -> str:
    columns = (
        "task",
        "split",
        "spec",
        "kind",
        "strategy",
        "runs",
        "optimal_steps",
        "final_steps_mean",
        "final_to_optimal_mean",
        "auc_mean_steps",
        "auc_to_optimal_mean",
        "success_rate",
        "converged_runs",
        "median_convergence_episode",
        "final_return_mean",
        "greedy_return_mean",
        "greedy_success_rate",
        "greedy_steps_mean",
        "normalised_return_mean",
    )
    rows = []
    for summary in summaries:
        for entry in summary.strategies:
            s = entry.summary
            rows.append(
                (
                    summary.task.name,
                    summary.task.split or "",
                    summary.task.spec_text,
                    summary.kind,
                    entry.strategy,
                    s.runs,
                    summary.optimal_steps,
                    float(np.mean(s.final_steps)),
                    _mean(entry.scores.get("final_to_optimal")),
                    float(np.mean(s.auc)),
                    _mean(entry.scores.get("auc_to_optimal")),
                    float(np.mean(s.success_rate)),
                    s.converged_runs,
                    "" if s.median_convergence is None else s.median_convergence,
                    float(np.mean(entry.final_return)),
                    _mean(entry.greedy_return),
                    _mean(entry.greedy_success),
                    _mean(entry.greedy_steps),
                    _mean(entry.scores.get("normalised_return")),
                )
            )
    return store.format_rows(rows, columns)


def _mean(values: np.ndarray | None) -> float | str:
    return "" if values is None else float(np.mean(values))


def _aggregate_csv(rows: Sequence[AggregateRow]) -> str:
    columns = (
        "group",
        "score",
        "strategy",
        "tasks",
        "runs",
        "iqm",
        "iqm_low",
        "iqm_high",
        "mean",
        "p_improvement",
        "p_improvement_low",
        "p_improvement_high",
    )
    table = [
        (
            row.group,
            row.score.key,
            row.strategy,
            row.tasks,
            row.runs,
            row.iqm.value,
            row.iqm.low,
            row.iqm.high,
            row.mean,
            *(
                ("", "", "")
                if row.p_improvement is None
                else (row.p_improvement.value, row.p_improvement.low, row.p_improvement.high)
            ),
        )
        for row in rows
    ]
    return store.format_rows(table, columns)
