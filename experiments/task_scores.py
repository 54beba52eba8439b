"""Per-task summaries and normalised scores of an experiment over tasks.

Two kinds of task:

- a **maze** task (a ``BulletMaze`` id) is scored against its layout's optimum
  (``env.unwrapped.optimal_steps``): **final / optimal** is a run's mean steps over its last
  ``final_window`` episodes divided by the optimum, **AUC / optimal** its mean steps per episode
  over the whole run divided by the optimum (1 is the optimum; lower is better; a capped
  episode counts as the cap);
- a **return** task (any other id, a Gymnasium classic-control task say) is scored by its
  **normalised return** ``(R - random) / (solved - random)`` (:mod:`experiments.references`;
  0 is a random policy, 1 the solved threshold; higher is better), where R is the run's mean
  greedy return over its evaluation episodes when the experiment has them
  (``eval_episodes``), else its mean training return over the last ``final_window`` episodes.

Tasks are aggregated in groups of one kind and one suite split (:func:`groups`): the
development and the test layouts of a suite are never pooled.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from experiments import store
from experiments.config import ExperimentConfig, TaskSpec
from experiments.references import References, default_references
from experiments.statistics import StrategySummary, summarize

Kind = Literal["maze", "return"]


@dataclass(frozen=True)
class Score:
    """A normalised score of every run."""

    key: str
    """Column name (``final_to_optimal``, ``auc_to_optimal``, ``normalised_return``)."""
    label: str
    """How the report writes it."""
    kind: Kind
    lower_is_better: bool


SCORES: dict[Kind, tuple[Score, ...]] = {
    "maze": (
        Score("final_to_optimal", "final steps / optimal", "maze", True),
        Score("auc_to_optimal", "AUC / optimal", "maze", True),
    ),
    "return": (Score("normalised_return", "normalised return", "return", False),),
}
"""The scores of each kind of task; the first is the primary one (profiles use it)."""


@dataclass(frozen=True)
class StrategyOnTask:
    """One strategy's runs on one task."""

    strategy: str
    summary: StrategySummary
    """Steps, success and convergence of its runs (:func:`experiments.statistics.summarize`)."""
    final_return: np.ndarray
    """Each run's mean return over its last ``final_window`` episodes."""
    greedy_return: np.ndarray | None
    """Each run's mean greedy return over its evaluation episodes (None: no evaluation)."""
    greedy_success: np.ndarray | None
    greedy_steps: np.ndarray | None
    scores: dict[str, np.ndarray]
    """Each run's normalised scores by :attr:`Score.key` (empty: the task has no reference)."""
    curves: dict[str, np.ndarray]
    """Runs x episodes arrays of ``steps`` and ``return`` (for the learning curves)."""

    @property
    def runs(self) -> int:
        """How many runs."""
        return self.summary.runs

    @property
    def score_return(self) -> np.ndarray:
        """The return a return task is scored by: greedy when evaluated, else training."""
        return self.greedy_return if self.greedy_return is not None else self.final_return


@dataclass(frozen=True)
class TaskSummary:
    """One task: what it is, its reference values, and each strategy's runs on it."""

    task: TaskSpec
    kind: Kind
    optimal_steps: float
    """The layout's optimum (maze tasks; NaN otherwise)."""
    references: References | None
    """The ends of the normalised return (return tasks; None if unknown)."""
    strategies: tuple[StrategyOnTask, ...]
    """The strategies with at least one finished run, in the experiment's order."""

    @property
    def scored(self) -> bool:
        """Whether its runs have normalised scores (a maze with an optimum, a return task with
        references)."""
        if self.kind == "maze":
            return math.isfinite(self.optimal_steps) and self.optimal_steps > 0
        return self.references is not None

    @property
    def group(self) -> str:
        """The aggregate it belongs to: its kind, and its suite split if any."""
        return self.kind if self.task.split is None else f"{self.kind}, {self.task.split} split"


def task_kind(task: TaskSpec) -> Kind:
    """``"maze"`` for the project's maze ids, else ``"return"``."""
    return "maze" if task.env.is_maze else "return"


def task_references(task: TaskSpec) -> References | None:
    """The task's own reference returns, else the defaults of its id at its cap."""
    if task.random_return is not None and task.solved_return is not None:
        return References(task.random_return, task.solved_return, "given in the experiment file")
    return default_references(task.env.id, task.env.max_episode_steps)


def normalised_return(returns: np.ndarray, references: References) -> np.ndarray:
    """``(R - random) / (solved - random)``: 0 a random policy, 1 the solved threshold."""
    span = references.solved_return - references.random_return
    return (np.asarray(returns, dtype=float) - references.random_return) / span


def _stack(runs: Sequence[store.RunData], column: str) -> np.ndarray:
    return np.stack([r.columns[column] for r in runs]).astype(float)


def _optimal(runs: Sequence[store.RunData]) -> float:
    for run in runs:
        value = run.meta.get("optimal_steps")
        if isinstance(value, int | float) and math.isfinite(value):
            return float(value)
    return math.nan


def summarize_task(
    config: ExperimentConfig,
    task: TaskSpec,
    results: Mapping[str, Sequence[store.RunData]],
) -> TaskSummary:
    """A task's summary from the verified runs of each strategy on it."""
    kind = task_kind(task)
    present = {name: runs for name, runs in results.items() if runs}
    optimal = (
        next((_optimal(runs) for runs in present.values()), math.nan)
        if kind == "maze"
        else math.nan
    )
    references = task_references(task) if kind == "return" else None
    final_window = config.final_window
    baseline = present.get(config.baseline_name)
    baseline_final = None if baseline is None else _stack(baseline, "steps")[:, -final_window:]
    strategies = []
    for name, runs in present.items():
        steps = _stack(runs, "steps")
        summary = summarize(
            name,
            steps,
            _stack(runs, "success"),
            _stack(runs, "leaves"),
            None if baseline_final is None else baseline_final.mean(axis=1),
            window=config.smoothing_window,
            final_window=final_window,
            tolerance=config.convergence_tolerance,
            wall_time_s=np.array([r.meta.get("wall_time_s", np.nan) for r in runs]),
            steps_per_second=np.array([r.meta.get("steps_per_second", np.nan) for r in runs]),
        )
        final_return = _stack(runs, "return")[:, -final_window:].mean(axis=1)
        greedy = [r.evaluation for r in runs if r.evaluation is not None]
        evaluated = len(greedy) == len(runs)
        greedy_return = np.array([e["return"].mean() for e in greedy]) if evaluated else None
        greedy_success = np.array([e["success"].mean() for e in greedy]) if evaluated else None
        greedy_steps = np.array([e["steps"].mean() for e in greedy]) if evaluated else None
        scores: dict[str, np.ndarray] = {}
        if kind == "maze" and math.isfinite(optimal) and optimal > 0:
            scores = {
                "final_to_optimal": summary.final_steps / optimal,
                "auc_to_optimal": summary.auc / optimal,
            }
        elif kind == "return" and references is not None:
            scored_return = greedy_return if greedy_return is not None else final_return
            scores = {"normalised_return": normalised_return(scored_return, references)}
        strategies.append(
            StrategyOnTask(
                name,
                summary,
                final_return,
                greedy_return,
                greedy_success,
                greedy_steps,
                scores,
                {"steps": steps, "return": _stack(runs, "return")},
            )
        )
    return TaskSummary(task, kind, optimal, references, tuple(strategies))


def groups(summaries: Sequence[TaskSummary]) -> dict[str, list[TaskSummary]]:
    """The scored tasks by aggregate group (kind and split), in the order they first appear."""
    found: dict[str, list[TaskSummary]] = {}
    for summary in summaries:
        if summary.scored:
            found.setdefault(summary.group, []).append(summary)
    return found


def scores_of(tasks: Sequence[TaskSummary], strategy: str, key: str) -> list[np.ndarray] | None:
    """A strategy's per-run scores on each task of a group (None unless it ran on all)."""
    found = []
    for summary in tasks:
        entry = next((s for s in summary.strategies if s.strategy == strategy), None)
        if entry is None or key not in entry.scores:
            return None
        found.append(entry.scores[key])
    return found
