"""Run an experiment: every (strategy, run) pair on a backend, stored as it finishes.

The results folder holds ``config.toml`` (the resolved experiment, loadable again),
``runs/<strategy>__<seed>.csv`` (+ ``.json``) for each finished run and, once every run has
finished, ``episodes.csv`` with all of them in a fixed order. Started again on the same folder,
an experiment skips every run whose CSV exists; a folder that holds a different experiment
(anything but the number of runs changed) is refused rather than mixed.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Collection
from dataclasses import dataclass
from pathlib import Path

from experiments import config as config_module
from experiments import store
from experiments.backends import Backend, SerialBackend
from experiments.config import ConfigError, ExperimentConfig, StrategySpec
from experiments.seeding import run_seed

log = logging.getLogger(__name__)

CONFIG_FILE = "config.toml"
RUN_DIR = "runs"
EPISODES_FILE = "episodes.csv"


@dataclass(frozen=True)
class RunSpec:
    """One task: a strategy of an experiment and the index of the run (its seeds)."""

    experiment: ExperimentConfig
    strategy: StrategySpec
    run_index: int
    seed: int

    @property
    def name(self) -> str:
        """``<strategy>__<seed>``."""
        return store.run_name(self.strategy.name, self.seed)


Task = Callable[[RunSpec], store.RunResult]


def plan(config: ExperimentConfig, only: Collection[str] | None = None) -> list[RunSpec]:
    """Every run of the experiment (of the strategies in ``only``, if given), run index first
    so that partial results are balanced."""
    return [
        RunSpec(config, strategy, index, run_seed(config.seed, index))
        for index in range(config.runs)
        for strategy in config.strategies
        if only is None or strategy.name in only
    ]


def prepare_folder(config: ExperimentConfig, out_dir: Path) -> None:
    """Create the results folder and record the resolved experiment, refusing a foreign one."""
    out_dir.mkdir(parents=True, exist_ok=True)
    recorded = out_dir / CONFIG_FILE
    if recorded.is_file():
        previous = config_module.load_config(recorded)
        differences = config_module.same_experiment(previous, config)
        if differences:
            raise ConfigError(
                f"{out_dir} holds results of a different experiment (differs in "
                f"{', '.join(differences)}); choose another --out or delete the folder"
            )
        config = config if config.runs >= previous.runs else previous
    store.atomic_write_text(recorded, config_module.dumps(config))
    store.remove_stale_temporaries(out_dir / RUN_DIR)


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


def pending_runs(
    config: ExperimentConfig, out_dir: Path, only: Collection[str] | None = None
) -> list[RunSpec]:
    """The runs of ``config`` (of the strategies in ``only``, if given) not in ``out_dir`` yet."""
    run_dir = out_dir / RUN_DIR
    return [spec for spec in plan(config, only) if not store.is_finished(run_dir, spec.name)]


def run_experiment(
    config: ExperimentConfig,
    out_dir: Path,
    backend: Backend | None = None,
    task: Task | None = None,
    on_result: Callable[[store.RunResult], None] | None = None,
    only: Collection[str] | None = None,
) -> list[store.RunResult]:
    """Run what is missing of ``config`` in ``out_dir``; returns the runs computed now.

    ``task`` computes one run (default: :func:`experiments.training.train_run`; tests pass a
    stand-in); it must be picklable for the process and Ray backends. ``on_result`` is called
    in this process after each run has been stored. ``only`` restricts the computation to
    some strategies (validated by :func:`select_strategies`); the folder stays the whole
    experiment's, and the rest can be computed later into it.
    """
    if task is None:
        from experiments.training import train_run

        task = train_run
    backend = backend or SerialBackend()
    prepare_folder(config, out_dir)
    only = select_strategies(config, only)
    todo = pending_runs(config, out_dir, only)
    log.info("%s: %d of %d runs to compute", config.name, len(todo), len(plan(config)))
    computed = []
    for result in backend.map_unordered(task, todo):
        store.write_run(out_dir / RUN_DIR, result)
        computed.append(result)
        if on_result is not None:
            on_result(result)
    write_episodes(config, out_dir)
    return computed


def write_episodes(config: ExperimentConfig, out_dir: Path) -> Path | None:
    """Gather every run of ``config`` into ``episodes.csv`` (strategy order, then run index)."""
    run_dir = out_dir / RUN_DIR
    specs = plan(config)
    if not all(store.is_finished(run_dir, spec.name) for spec in specs):
        return None
    ordered = sorted(specs, key=lambda s: (config.strategies.index(s.strategy), s.run_index))
    lines = ["strategy,run,seed," + ",".join(store.COLUMNS)]
    for spec in ordered:
        text = store.run_paths(run_dir, spec.name)[0].read_text(encoding="utf-8")
        prefix = f"{spec.strategy.name},{spec.run_index},{spec.seed},"
        lines += [prefix + line for line in text.splitlines()[1:]]
    path = out_dir / EPISODES_FILE
    store.atomic_write_text(path, "\n".join(lines) + "\n")
    return path


def load_results(config: ExperimentConfig, out_dir: Path) -> dict[str, list[store.RunData]]:
    """The finished runs of each strategy, by run index (missing runs left out)."""
    run_dir = out_dir / RUN_DIR
    results: dict[str, list[store.RunData]] = {s.name: [] for s in config.strategies}
    for spec in sorted(plan(config), key=lambda s: s.run_index):
        if store.is_finished(run_dir, spec.name):
            results[spec.strategy.name].append(store.read_run(run_dir, spec.name))
    return results
