"""The runs of an experiment: one :class:`RunSpec` per (task, strategy, run index), in a fixed
order.

Each run carries its own environment (:attr:`RunSpec.env`): the experiment's when it has one
environment, else its task's. Run i has the same seed for every strategy and every task
(common random seeds), so a run is named by its task, strategy and seed:
``<task>/<strategy>__<seed>`` (``<strategy>__<seed>`` without tasks).
"""

from __future__ import annotations

from collections.abc import Collection
from dataclasses import dataclass

from experiments import store
from experiments.config import ConfigError, EnvSpec, ExperimentConfig, StrategySpec
from experiments.seeding import run_seed


@dataclass(frozen=True)
class RunSpec:
    """One task: a strategy of an experiment, the index of the run (its seeds), its env."""

    experiment: ExperimentConfig
    strategy: StrategySpec
    run_index: int
    seed: int
    env: EnvSpec
    task: str | None = None
    """The task's name (None in an experiment with one environment)."""

    @property
    def name(self) -> str:
        """``<strategy>__<seed>``, or ``<task>/<strategy>__<seed>``."""
        return store.run_name(self.strategy.name, self.seed, self.task)


def plan(config: ExperimentConfig, only: Collection[str] | None = None) -> list[RunSpec]:
    """Every run of the experiment (of the strategies in ``only``, if given), run index first,
    then task, so that partial results are balanced."""
    tasks: list[tuple[str | None, EnvSpec]] = [(t.name, t.env) for t in config.tasks] or [
        (None, config.env)
    ]
    return [
        RunSpec(config, strategy, index, run_seed(config.seed, index), env, task)
        for index in range(config.runs)
        for task, env in tasks
        for strategy in config.strategies
        if only is None or strategy.name in only
    ]


def select_strategies(
    config: ExperimentConfig, names: Collection[str] | None, option: str = "--only"
) -> frozenset[str] | None:
    """Validate a subset of the experiment's strategy names (None: all of them)."""
    if names is None:
        return None
    known = [spec.name for spec in config.strategies]
    if not names:
        raise ConfigError(
            f"option {option}: no strategy named; experiment {config.name!r} has {', '.join(known)}"
        )
    unknown = [name for name in names if name not in known]
    if unknown:
        raise ConfigError(
            f"option {option}: unknown strategy {', '.join(map(repr, unknown))} "
            f"in experiment {config.name!r}; its strategies are "
            f"{', '.join(known)}"
        )
    return frozenset(names)
