"""Run an experiment: every (task, strategy, run) on a backend, verified, stored as it finishes.

The results folder holds ``config.toml`` (the resolved experiment, loadable again),
``runs/<strategy>__<seed>.csv`` + ``.json`` for each finished run (``runs/<task>/...`` in an
experiment over tasks; ``.eval.csv`` beside them with a greedy evaluation) and, once every run
has finished, ``episodes.csv`` (and ``evaluation.csv``) with all of them in a fixed order.
While an experiment writes, the folder is locked (:mod:`experiments.lock`): a second writer is
refused and touches nothing.

Started again on the same folder, an experiment first verifies every run it finds
(:func:`inspect_folder`, :func:`experiments.store.check_run`): a run whose files are damaged,
cut, edited or unverifiable is reported by name and recomputed; a run computed from other
inputs (an edited maze, another robot file, other settings) makes the experiment refuse, by
name, rather than mix; a run whose only difference is the code version is refused too unless
the caller accepts code changes (``--accept-code-change``, recorded in the report). A folder
that holds a different experiment (anything but the number of runs or the report's settings
changed) is refused; a change of report settings alone is recorded in ``config.toml``, by a run
or by a report (:func:`record_config`), so the file always describes the folder's report.
"""

from __future__ import annotations

import dataclasses
import logging
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from experiments import config as config_module
from experiments import fingerprint, store
from experiments.backends import Backend, SerialBackend
from experiments.config import ConfigError, ExperimentConfig
from experiments.lock import FolderBusyError, FolderLock
from experiments.plan import RunSpec, plan, select_strategies
from experiments.training import train_run

log = logging.getLogger(__name__)

CONFIG_FILE = "config.toml"
RUN_DIR = "runs"
EPISODES_FILE = "episodes.csv"
EVALUATION_FILE = "evaluation.csv"

Task = Callable[[RunSpec], store.RunResult]


@dataclass(frozen=True)
class FolderState:
    """What a results folder holds of an experiment's runs, each one verified."""

    planned: tuple[RunSpec, ...]
    """The runs asked for (of the selected strategies), in plan order."""
    checks: Mapping[str, store.RunCheck]
    """The verdict on each planned run, by name."""
    accept_code_change: bool = False
    """Whether runs that differ only in the code version count as finished."""

    def _with(self, *statuses: str) -> list[tuple[RunSpec, store.RunCheck]]:
        return [
            (s, self.checks[s.name]) for s in self.planned if self.checks[s.name].status in statuses
        ]

    @property
    def finished(self) -> list[tuple[RunSpec, store.RunCheck]]:
        """Verified runs that count (those that differ only in code, if accepted)."""
        return self._with("valid", "code") if self.accept_code_change else self._with("valid")

    @property
    def pending(self) -> list[RunSpec]:
        """Runs to compute: never computed, or whose files did not verify."""
        return [spec for spec, _ in self._with("missing", "invalid")]

    @property
    def not_run(self) -> list[RunSpec]:
        """Planned runs with no files yet (``--only`` left them, or the experiment was cut)."""
        return [spec for spec, _ in self._with("missing")]

    @property
    def invalid(self) -> list[tuple[RunSpec, store.RunCheck]]:
        """Runs whose files did not verify (damaged, cut, edited): recomputed."""
        return self._with("invalid")

    @property
    def changed(self) -> list[tuple[RunSpec, store.RunCheck]]:
        """Verified runs computed from other inputs: never mixed with these."""
        return self._with("changed")

    @property
    def code_changed(self) -> list[tuple[RunSpec, store.RunCheck]]:
        """Verified runs whose only difference is the code version."""
        return self._with("code")

    @property
    def excluded(self) -> list[tuple[RunSpec, store.RunCheck]]:
        """Runs on disk that do not count, with the reason in their check."""
        kinds = (
            ("invalid", "changed") if self.accept_code_change else ("invalid", "changed", "code")
        )
        return self._with(*kinds)


class _Inputs:
    """The expected inputs of each run; the environment's fingerprints computed once each."""

    def __init__(self, task: Task) -> None:
        self.task = task
        self._env: dict[str, dict[str, str | None]] = {}

    def __call__(self, spec: RunSpec) -> dict[str, Any]:
        key = repr(spec.env)
        if key not in self._env:
            try:
                self._env[key] = fingerprint.env_inputs(spec.env)
            except (TypeError, ValueError, OSError) as error:
                where = "[env]" if spec.task is None else f"task {spec.task!r}"
                raise ConfigError(f"{spec.experiment.source}: {where}: {error}") from None
        return fingerprint.run_inputs(
            spec.experiment, spec.strategy, spec.env, spec.seed, self.task, self._env[key]
        )


def inspect_folder(
    config: ExperimentConfig,
    out_dir: Path,
    task: Task = train_run,
    only: Collection[str] | None = None,
    accept_code_change: bool = False,
) -> FolderState:
    """Verify every planned run in ``out_dir`` (reads only; writes nothing)."""
    run_dir = out_dir / RUN_DIR
    expected = _Inputs(task)
    specs = tuple(plan(config, only))
    checks = {
        spec.name: store.check_run(
            run_dir,
            spec.name,
            config.episodes,
            spec.env.max_episode_steps,
            expected(spec),
            config.eval_episodes,
            config.save_agents,
        )
        for spec in specs
    }
    return FolderState(specs, checks, accept_code_change)


def check_out_dir(out_dir: Path, option: str = "--out") -> None:
    """A results folder must be a folder (or not exist yet)."""
    for path in (out_dir, *out_dir.parents):
        if path.exists() and not path.is_dir():
            where = "is" if path == out_dir else f"lies under {path}, which is"
            raise ConfigError(f"option {option}: {out_dir} {where} a file, not a folder")


def prepare_folder(
    config: ExperimentConfig, out_dir: Path, allowed_env_ids: Collection[str] = ()
) -> None:
    """Create the results folder and record the resolved experiment, refusing a foreign one.
    Call it holding the folder's lock (it removes stale temporaries)."""
    check_out_dir(out_dir)
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise ConfigError(f"option --out: cannot create {out_dir} ({error.strerror})") from None
    record_config(config, out_dir, allowed_env_ids)
    store.remove_stale_temporaries(out_dir / RUN_DIR, nested=True)
    store.remove_stale_temporaries(out_dir)


def refuse_mixing(state: FolderState, out_dir: Path) -> None:
    """Raise :class:`ConfigError` naming the runs computed from other inputs (or other code,
    unless accepted)."""
    problems = state.changed + ([] if state.accept_code_change else state.code_changed)
    if not problems:
        return
    lines = [
        f"  {spec.name}: {check.reason} ({', '.join(check.differences)})"
        for spec, check in problems[:20]
    ]
    if len(problems) > 20:
        lines.append(f"  ... and {len(problems) - 20} more")
    only_code = not state.changed
    advice = (
        "accept them with --accept-code-change (recorded in the report) if the change cannot "
        "alter results, or compute into another --out"
        if only_code
        else "compute into another --out, or delete those runs to recompute them"
    )
    raise ConfigError(
        f"{out_dir}: {len(problems)} finished run(s) were computed from other inputs than this "
        f"experiment's; they are not mixed with new ones:\n" + "\n".join(lines) + f"\n{advice}"
    )


def run_experiment(
    config: ExperimentConfig,
    out_dir: Path,
    backend: Backend | None = None,
    task: Task | None = None,
    on_result: Callable[[store.RunResult], None] | None = None,
    only: Collection[str] | None = None,
    on_start: Callable[[FolderState], None] | None = None,
    accept_code_change: bool = False,
    allowed_env_ids: Collection[str] = (),
) -> list[store.RunResult]:
    """Run what is missing of ``config`` in ``out_dir``; returns the runs computed now.

    ``task`` computes one run (default: :func:`experiments.training.train_run`; tests pass a
    stand-in); it must be picklable for the process and Ray backends. ``on_start(state)`` is
    called once the folder is locked and verified, before anything is computed;
    ``on_result`` in this process after each run has been stored. ``only`` restricts the
    computation to some strategies; the folder stays the whole experiment's, and the rest can
    be computed later into it.
    """
    task = task or train_run
    backend = backend or SerialBackend()
    only = select_strategies(config, only)
    check_out_dir(out_dir)
    try:
        with FolderLock(out_dir):
            return _run_locked(
                config,
                out_dir,
                backend,
                task,
                on_result,
                only,
                on_start,
                accept_code_change,
                allowed_env_ids,
            )
    except FolderBusyError as error:
        raise ConfigError(str(error)) from None
    except OSError as error:
        if error.filename is None or not Path(error.filename).is_relative_to(out_dir):
            raise
        raise ConfigError(f"{out_dir}: cannot write ({error.strerror})") from None


def record_config(
    config: ExperimentConfig, out_dir: Path, allowed_env_ids: Collection[str] = ()
) -> None:
    """Write ``config`` as the folder's ``config.toml``, refusing one that records a different
    experiment (a difference that changes runs, :func:`config_module.run_differences`). A
    change of report settings alone is recorded, so the file always describes the report; the
    recorded number of runs never shrinks. Call it holding the folder's lock."""
    recorded = out_dir / CONFIG_FILE
    if recorded.exists():
        previous = config_module.load_config(recorded, allowed_env_ids)
        differences = config_module.run_differences(config_module.same_experiment(previous, config))
        if differences:
            raise ConfigError(
                f"{out_dir} holds results of a different experiment (differs in "
                f"{', '.join(differences)}); choose another --out or delete the folder"
            )
        if config.runs < previous.runs:
            config = dataclasses.replace(config, runs=previous.runs)
    store.atomic_write_text(recorded, config_module.dumps(config))


def record_report_config(
    config: ExperimentConfig, out_dir: Path, allowed_env_ids: Collection[str] = ()
) -> None:
    """:func:`record_config` under the folder's lock, for a report written without a run
    (``--report-only``): the report's settings become the recorded ones, and a file that
    describes other runs is refused by name. Where nothing but the number of runs differs,
    or where no run has recorded a ``config.toml`` yet, nothing is written and no lock is taken,
    so a report can be read while the runs go on."""
    check_out_dir(out_dir)
    recorded = out_dir / CONFIG_FILE
    if not recorded.exists():
        return  # no run has recorded an experiment here: nothing to describe
    previous = config_module.load_config(recorded, allowed_env_ids)
    unchanged = not config_module.same_experiment(previous, config)
    if unchanged and previous.description == config.description:  # the report copies it
        return
    try:
        with FolderLock(out_dir):
            # read again under the lock: a run may have recorded another file meanwhile
            record_config(config, out_dir, allowed_env_ids)
    except FolderBusyError as error:
        raise ConfigError(str(error)) from None
    except OSError as error:
        raise ConfigError(f"{out_dir}: cannot write ({error.strerror})") from None


def _run_locked(
    config: ExperimentConfig,
    out_dir: Path,
    backend: Backend,
    task: Task,
    on_result: Callable[[store.RunResult], None] | None,
    only: frozenset[str] | None,
    on_start: Callable[[FolderState], None] | None,
    accept_code_change: bool,
    allowed_env_ids: Collection[str],
) -> list[store.RunResult]:
    run_dir = out_dir / RUN_DIR
    prepare_folder(config, out_dir, allowed_env_ids)
    state = inspect_folder(config, out_dir, task, only, accept_code_change)
    refuse_mixing(state, out_dir)
    for spec, check in state.invalid:
        log.warning("%s does not verify and is recomputed: %s", spec.name, check.reason)
        store.remove_run(run_dir, spec.name)
    if on_start is not None:
        on_start(state)
    expected = _Inputs(task)
    log.info("%s: %d of %d runs to compute", config.name, len(state.pending), len(state.planned))
    computed = []
    by_name = {spec.name: spec for spec in state.pending}
    for result in backend.map_unordered(task, state.pending):
        if result.name not in by_name:
            raise ConfigError(
                f"the task returned a run named {result.name!r}, which was not asked for "
                "(a task must copy its RunSpec's strategy, seed and task into its result)"
            )
        wanted = expected(by_name[result.name])
        inputs = fingerprint.normalized(result.inputs) if result.inputs else wanted
        found = fingerprint.differences(inputs, wanted)
        if found:
            raise ConfigError(
                f"run {result.name}: its inputs changed while the experiment ran "
                f"({', '.join(found)}); it was not stored. Finished runs are kept."
            )
        store.write_run(run_dir, result, inputs)
        computed.append(result)
        if on_result is not None:
            on_result(result)
    write_episodes(config, out_dir, task, accept_code_change)
    return computed


def pending_runs(
    config: ExperimentConfig,
    out_dir: Path,
    only: Collection[str] | None = None,
    task: Task = train_run,
) -> list[RunSpec]:
    """The runs of ``config`` (of the strategies in ``only``) that are not finished in
    ``out_dir`` (missing, or not verifying)."""
    return inspect_folder(config, out_dir, task, only).pending


def write_episodes(
    config: ExperimentConfig,
    out_dir: Path,
    task: Task = train_run,
    accept_code_change: bool = False,
) -> Path | None:
    """Gather every run of ``config`` into ``episodes.csv`` (task order, strategy order, then
    run index; a ``task`` column first in an experiment over tasks), and the greedy episodes
    into ``evaluation.csv``, once every run is finished and verified. Until then neither file
    exists: one merged for an earlier plan (fewer runs or strategies) is removed, so a merged
    file always holds exactly the runs the experiment asks for."""
    state = inspect_folder(config, out_dir, task, None, accept_code_change)
    if len(state.finished) != len(state.planned):
        for name in (EPISODES_FILE, EVALUATION_FILE):
            (out_dir / name).unlink(missing_ok=True)
        return None
    tasks = {t.name: i for i, t in enumerate(config.tasks)}
    order = {spec.name: i for i, spec in enumerate(config.strategies)}
    ordered = sorted(
        state.finished,
        key=lambda item: (
            tasks.get(item[0].task or "", 0),
            order[item[0].strategy.name],
            item[0].run_index,
        ),
    )
    head = "task," if config.tasks else ""
    files: list[tuple[str, tuple[str, ...], Callable[[Path, str], tuple[Path, ...]]]] = [
        (EPISODES_FILE, store.COLUMNS, store.run_paths)
    ]
    if config.eval_episodes:
        files.append((EVALUATION_FILE, store.EVAL_COLUMNS, _eval_paths))
    for file_name, columns, paths in files:
        lines = [f"{head}strategy,run,seed," + ",".join(columns)]
        for spec, _ in ordered:
            text = paths(out_dir / RUN_DIR, spec.name)[0].read_text(encoding="utf-8")
            prefix = (f"{spec.task}," if config.tasks else "") + (
                f"{spec.strategy.name},{spec.run_index},{spec.seed},"
            )
            lines += [prefix + line for line in text.splitlines()[1:]]
        store.atomic_write_text(out_dir / file_name, "\n".join(lines) + "\n")
    return out_dir / EPISODES_FILE


def _eval_paths(run_dir: Path, name: str) -> tuple[Path]:
    return (store.eval_path(run_dir, name),)


def load_results(
    config: ExperimentConfig,
    out_dir: Path,
    task: Task = train_run,
    accept_code_change: bool = False,
) -> dict[str, list[store.RunData]]:
    """The finished, verified runs of each strategy, by run index (the rest left out)."""
    state = inspect_folder(config, out_dir, task, None, accept_code_change)
    return results_of(config, state)


def results_of(config: ExperimentConfig, state: FolderState) -> dict[str, list[store.RunData]]:
    """The verified data of a folder's finished runs, by strategy, in run order (an experiment
    with one environment; :func:`results_by_task` for one over tasks)."""
    return results_by_task(config, state).get(None, {s.name: [] for s in config.strategies})


def results_by_task(
    config: ExperimentConfig, state: FolderState
) -> dict[str | None, dict[str, list[store.RunData]]]:
    """The verified data of a folder's finished runs by task (None: the one environment),
    then by strategy, in run order."""
    names: list[str | None] = [t.name for t in config.tasks] or [None]
    results: dict[str | None, dict[str, list[store.RunData]]] = {
        name: {s.name: [] for s in config.strategies} for name in names
    }
    for spec, check in sorted(state.finished, key=lambda item: item[0].run_index):
        assert check.data is not None
        results[spec.task][spec.strategy.name].append(check.data)
    return results
