"""The harness's front door: one object per job, which ``run.py`` only fills from the command
line and prints from.

- :class:`TrainJob`: one agent, one strategy, one seed (``run.py train`` and the default job);
- :class:`Experiment`: strategies x runs into a results folder, with :meth:`Experiment.pending`,
  :meth:`Experiment.run` and :meth:`Experiment.report`;
- :class:`Playback`: a saved agent in an environment (``run.py evaluate`` and ``render``).

Every value a user gives is checked here or below, and every failure is a :class:`ConfigError`
that names the value and where it came from: the file and key, or the option.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Collection, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from agent.serialization import config_from_data, exploration_from_data
from experiments import config as config_module
from experiments import factory, runner
from experiments.agent_kinds import is_fixed
from experiments.config import ConfigError, EnvSpec, ExperimentConfig
from experiments.evaluation import Episode, Evaluation, evaluate, greedy_episode
from experiments.plan import RunSpec, select_strategies
from experiments.runner import FolderState, Task
from experiments.seeding import run_seed
from experiments.store import EpisodeRow, RunResult
from experiments.training import train_run

if TYPE_CHECKING:  # the modules that draw are imported when a job draws (matplotlib is slow)
    from experiments.backends import Backend
    from experiments.report import Report
    from experiments.single_run import SingleRun
    from experiments.task_report import TaskReport

DEFAULT_CONFIG = "quick"
"""The experiment file of the default job and of ``train`` (``experiments/quick.toml``)."""
RESULTS_DIR = Path("results")
"""Where results folders go by default."""
AGENT_FILES = ("agent.npz", "policy.npz")
"""What ``evaluate``/``render`` look for in a folder, in order."""


@dataclass(frozen=True)
class EnvOptions:
    """Environment settings given on the command line (None: the file's)."""

    maze: str | None = None
    robot: str | None = None
    mode: str | None = None
    max_episode_steps: int | None = None

    def apply(self, config: ExperimentConfig) -> tuple[ExperimentConfig, dict[str, str]]:
        """``config`` with these settings, and where each environment setting came from."""
        given: dict[str, Any] = {
            key: config_module.check_option_text(value, f"--{key}")
            for key, value in (("maze", self.maze), ("robot", self.robot), ("mode", self.mode))
            if value is not None
        }
        if given and not config.env.is_maze:
            option = f"--{next(iter(given))}"
            raise ConfigError(
                f"option {option}: only applies to the maze environments, not {config.env.id!r}"
            )
        modes = config_module.MODES
        if self.mode is not None and self.mode not in modes:
            raise ConfigError(
                f"option --mode: expected one of {', '.join(modes)}, got {self.mode!r}"
            )
        env = dataclasses.replace(config.env, **given)
        config = dataclasses.replace(config, env=env)
        config = config_module.with_overrides(config, max_episode_steps=self.max_episode_steps)
        options = {key: f"--{key}" for key in given}
        return config, factory.env_origins(config.source, options)


def _check_folder(path: Path, option: str) -> Path:
    config_module.check_option_text(str(path), option)
    runner.check_out_dir(path, option)
    return path


def _load(config: str | Path, option: str, allowed_env_ids: Collection[str]) -> ExperimentConfig:
    """An experiment file named by an option (a missing file is the option's error)."""
    config_module.check_option_text(str(config), option)
    try:
        path = config_module.resolve_path(config)
    except ConfigError as error:
        raise ConfigError(f"option {option}: {error}") from None
    return config_module.load_config(path, allowed_env_ids)


MAX_LABEL = 80
"""Longest maze label in a default folder name (a long path would make too long a name)."""


# --- train --------------------------------------------------------------------------------


@dataclass(frozen=True)
class TrainJob:
    """One agent trained, saved and pictured: the one-strategy experiment, resolved."""

    config: ExperimentConfig
    """A one-strategy, one-run experiment (the strategy with the options applied)."""
    seed: int
    """The run seed."""
    out: Path
    """The folder it writes."""
    origins: dict[str, str] = field(default_factory=dict)
    """Where each environment setting came from (for error messages)."""

    @property
    def strategy(self) -> Any:
        """The strategy trained."""
        return self.config.strategies[0]

    @classmethod
    def from_options(
        cls,
        config: str | Path = DEFAULT_CONFIG,
        strategy: str | None = None,
        task: str | None = None,
        exploration: str | None = None,
        params: Sequence[str] = (),
        agent_params: Sequence[str] = (),
        env: EnvOptions | None = None,
        episodes: int | None = None,
        time_budget_s: float | None = None,
        seed: int | None = None,
        out: Path | None = None,
        allowed_env_ids: Collection[str] = (),
        results_dir: Path = RESULTS_DIR,
    ) -> TrainJob:
        """The job the options describe. ``params`` and ``agent_params`` are ``KEY=VALUE``
        texts (values in TOML: ``0.05``, ``true``, ``"text"``; bare text is a string).
        ``time_budget_s`` 0 removes the file's budget; ``task`` chooses a task of an
        experiment over several (default: its first)."""
        if task is not None:
            config_module.check_option_text(task, "--task")
        file_config = _load(config, "--config", allowed_env_ids).single_task(task, "--task")
        spec = (
            file_config.strategy(strategy, "--strategy")
            if strategy is not None
            else file_config.strategies[0]
        )
        if is_fixed(spec.agent):
            raise ConfigError(
                f"{file_config.source}: [strategy {spec.name!r}]: run.py train draws the "
                f'agent\'s partition, which agent = "{spec.agent}" has not; run it with '
                f"run.py experiment {file_config.source} --only {spec.name} (with "
                "[experiment] save_agents = true to keep its agent file)"
            )
        given = config_module.parse_assignments(params or (), "--param")
        if exploration is not None:
            config_module.check_option_text(exploration, "--exploration")
            _checked(lambda: exploration_from_data(exploration, {}, "option --exploration"))
        if exploration is not None or given:
            name = exploration if exploration is not None else spec.exploration
            merged = given if exploration is not None else {**spec.exploration_params, **given}
            _checked(lambda: exploration_from_data(name, merged, "option --param"))
            spec = dataclasses.replace(spec, exploration=name, exploration_params=merged)
            if exploration is not None and strategy is None:
                spec = dataclasses.replace(spec, name=exploration)
        fields = config_module.parse_assignments(agent_params or (), "--agent-param")
        if fields:
            _checked(lambda: config_from_data(fields, "option --agent-param"))
            merged_fields = {**file_config.agent_params(spec), **fields}
            _checked(lambda: config_from_data(merged_fields, "option --agent-param"))
            spec = dataclasses.replace(spec, config={**spec.config, **fields})
        refusal = _checked(lambda: config_module.save_refusal_of(file_config, spec))
        if refusal is not None:
            raise ConfigError(
                f"{file_config.source}: [strategy {spec.name!r}]: run.py train saves the agent, "
                f"and {refusal}; run.py experiment trains it without saving it (unless its "
                "file sets save_agents)"
            )
        budget = file_config.time_budget_s
        if time_budget_s is not None:
            budget = time_budget_s or None
        resolved = dataclasses.replace(
            file_config, strategies=(spec,), baseline=None, runs=1, time_budget_s=budget
        )
        resolved = config_module.with_overrides(resolved, episodes=episodes)
        resolved, origins = (env or EnvOptions()).apply(resolved)
        if seed is not None:
            config_module.check_override("seed", seed)
        run = run_seed(resolved.seed, 0) if seed is None else seed
        label = resolved.env.label[:MAX_LABEL]
        folder = out or results_dir / f"{label}__{spec.name}__{run}"
        return cls(resolved, run, _check_folder(folder, "--out"), origins)

    def run(
        self,
        on_start: Callable[[float], None] | None = None,
        on_episode: Callable[[EpisodeRow], None] | None = None,
    ) -> SingleRun:
        """Train, save and picture the agent (``on_start(optimal_steps)``, ``on_episode(row)``
        for a progress bar)."""
        from experiments.single_run import train_and_save

        try:
            self.out.mkdir(parents=True, exist_ok=True)
        except OSError as error:
            raise ConfigError(
                f"option --out: cannot create {self.out} ({error.strerror})"
            ) from None
        return train_and_save(self.config, self.seed, self.out, on_start, on_episode, self.origins)


def _checked(build: Callable[[], Any]) -> Any:
    try:
        return build()
    except ValueError as error:
        raise ConfigError(str(error)) from None


# --- experiment ---------------------------------------------------------------------------


class Experiment:
    """An experiment into its results folder: what is pending, computing it, its report."""

    def __init__(
        self,
        config: ExperimentConfig,
        out: Path,
        only: Collection[str] | None = None,
        accept_code_change: bool = False,
        allowed_env_ids: Collection[str] = (),
        task: Task = train_run,
    ) -> None:
        self.config = config
        self.out = _check_folder(out, "--out")
        self.only = select_strategies(config, only)
        self.accept_code_change = accept_code_change
        self.allowed_env_ids = tuple(allowed_env_ids)
        self.task = task

    @classmethod
    def from_file(
        cls,
        config: str | Path,
        runs: int | None = None,
        episodes: int | None = None,
        max_episode_steps: int | None = None,
        seed: int | None = None,
        out: Path | None = None,
        only: Collection[str] | None = None,
        accept_code_change: bool = False,
        allowed_env_ids: Collection[str] = (),
        results_dir: Path = RESULTS_DIR,
        splits: Sequence[str] | None = None,
    ) -> Experiment:
        """An experiment file with the command line's overrides; the default folder is
        ``results/<name>`` with ``__<episodes>ep``, ``__cap<N>``, ``__seed<N>``,
        ``__<split>`` for the overrides that change results (runs may be added to a folder).
        ``splits`` replaces a suite experiment's ``[env] split`` (``--split``)."""
        file_config = _load(config, "CONFIG", allowed_env_ids)
        resolved = config_module.with_overrides(
            config_module.with_splits(file_config, splits),
            runs=runs,
            episodes=episodes,
            seed=seed,
            max_episode_steps=max_episode_steps,
        )
        folder = out or results_dir / _folder_name(file_config, resolved)
        return cls(resolved, folder, only, accept_code_change, allowed_env_ids)

    @property
    def planned(self) -> list[RunSpec]:
        """Every run asked for (of the ``only`` strategies, if given)."""
        return runner.plan(self.config, self.only)

    def status(self) -> FolderState:
        """Every planned run verified against the folder (reads only)."""
        return runner.inspect_folder(
            self.config, self.out, self.task, self.only, self.accept_code_change
        )

    def pending(self) -> list[RunSpec]:
        """The runs still to compute: missing, or whose files do not verify."""
        return self.status().pending

    def check(self) -> dict[str | None, float]:
        """Build each task's environment and every strategy's agent once (a bad setting fails
        here, before any run, named); each task's optimal number of steps (NaN where the
        environment does not say), by task name (None: the one environment)."""
        config = self.config
        checks: list[tuple[str | None, EnvSpec, dict[str, str]]] = [
            (t.name, t.env, factory.task_origins(config.source, t)) for t in config.tasks
        ] or [(None, config.env, factory.env_origins(config.source))]
        optimal: dict[str | None, float] = {}
        for name, spec, origins in checks:
            env = factory.check_env(spec, origins)
            try:
                factory.check_agents(config, env, spec, f"task {name!r}" if name else "")
                optimal[name] = factory.optimal_steps(env)
            finally:
                env.close()
        return optimal

    def run(
        self,
        backend: Backend,
        on_start: Callable[[FolderState], None] | None = None,
        on_result: Callable[[RunResult], None] | None = None,
    ) -> list[RunResult]:
        """Compute what is pending (locked, verified, refusing to mix inputs); returns the runs
        computed now. ``on_start(state)`` once the folder is verified, ``on_result(result)``
        after each run is stored."""
        return runner.run_experiment(
            self.config,
            self.out,
            backend,
            self.task,
            on_result=on_result,
            only=self.only,
            on_start=on_start,
            accept_code_change=self.accept_code_change,
            allowed_env_ids=self.allowed_env_ids,
        )

    def report(self) -> Report | TaskReport:
        """Write the report of every finished, verified run (``ConfigError`` if none): a
        :class:`~experiments.task_report.TaskReport` for an experiment over tasks."""
        from experiments.report import write_report
        from experiments.task_report import write_task_report

        if not self.out.is_dir():
            raise ConfigError(f"{self.out}: no such results folder (nothing has run)")
        runner.record_report_config(self.config, self.out, self.allowed_env_ids)
        write = write_task_report if self.config.tasks else write_report
        try:
            return write(
                self.config, self.out, task=self.task, accept_code_change=self.accept_code_change
            )
        except ValueError as error:
            raise ConfigError(str(error)) from None


def _folder_name(file_config: ExperimentConfig, config: ExperimentConfig) -> str:
    name = config.name
    if config.splits != file_config.splits:
        name += f"__{'+'.join(config.splits)}"
    if config.episodes != file_config.episodes:
        name += f"__{config.episodes}ep"
    if config.env.max_episode_steps != file_config.env.max_episode_steps:
        name += f"__cap{config.env.max_episode_steps}"
    if config.seed != file_config.seed:
        name += f"__seed{config.seed}"
    return name


# --- evaluate and render ------------------------------------------------------------------


@dataclass(frozen=True)
class EvaluationResult:
    """What :meth:`Playback.evaluate` measured."""

    evaluation: Evaluation
    optimal_steps: float
    wall_time_s: float
    projected: bool
    """Whether the observation was cut to the agent's dimensions (the husky's heading)."""


def _own_config(path: Path) -> tuple[Path | None, str | None]:
    """The experiment file a saved agent was trained with, and its task's name if the file
    lists tasks: the ``config.toml`` beside it (``run.py train``), or the results folder's for
    an experiment's saved agents (``runs/<run>.agent.npz``, or ``runs/<task>/<run>.agent.npz``);
    (None, None) when there is none."""
    folder = path.parent
    if (folder / runner.CONFIG_FILE).is_file():
        return folder / runner.CONFIG_FILE, None
    if folder.name == runner.RUN_DIR and (folder.parent / runner.CONFIG_FILE).is_file():
        return folder.parent / runner.CONFIG_FILE, None
    root = folder.parent.parent / runner.CONFIG_FILE
    if folder.parent.name == runner.RUN_DIR and root.is_file():
        return root, folder.name
    return None, None


class Playback:
    """A saved agent and the environment to play it in: its own (the ``config.toml`` beside
    it, checked like any experiment file), changed by options."""

    def __init__(self, agent: Any, path: Path, config: ExperimentConfig, origins: dict[str, str]):
        self.agent = agent
        self.path = path
        self.config = config
        self.origins = origins

    @classmethod
    def from_options(
        cls,
        agent: str | Path,
        config: str | Path | None = None,
        env: EnvOptions | None = None,
        allowed_env_ids: Collection[str] = (),
    ) -> Playback:
        """``agent`` is an agent file or a folder holding one (:data:`AGENT_FILES`);
        ``config`` the experiment file of the environment (default: the one beside the agent,
        else :data:`DEFAULT_CONFIG`)."""
        config_module.check_option_text(str(agent), "AGENT")
        path = _agent_file(Path(agent))
        task = None
        if config is not None:
            loaded = _load(config, "--config", allowed_env_ids)
        else:
            own, task = _own_config(path)
            loaded = config_module.load_config(own or DEFAULT_CONFIG, allowed_env_ids)
        loaded, origins = (env or EnvOptions()).apply(loaded.single_task(task, "AGENT"))
        try:
            saved = factory.load_agent(path)
        except (ValueError, OSError) as error:
            raise ConfigError(f"cannot load the agent: {error}") from None
        return cls(saved, path, loaded, origins)

    @property
    def env_spec(self) -> EnvSpec:
        """The environment it plays in."""
        return self.config.env

    def make_env(self) -> Any:
        """The environment as the agent sees it (:func:`experiments.factory.fitted_to`: the
        husky's heading is dropped for a disc-trained agent)."""
        env = factory.check_env(self.config.env, self.origins)
        dims = self.agent.observation_space.shape[0]
        actions = getattr(env.action_space, "n", None)
        try:
            if actions != self.agent.n_actions:
                raise ValueError(
                    f"the agent has {self.agent.n_actions} actions; this environment has {actions}"
                )
            return factory.fitted_to(env, dims)
        except ValueError as error:
            env.close()
            raise ConfigError(
                f"{self.path}: cannot play {self.config.env.label!r} (robot "
                f"{self.config.env.robot!r}): {error}"
            ) from None

    def evaluate(self, episodes: int, seed: int = 0) -> EvaluationResult:
        """``episodes`` greedy episodes, the first reset seeded with ``seed``."""
        config_module.check_override("seed", seed)
        env = self.make_env()
        try:
            optimal = factory.optimal_steps(env)
            start = time.perf_counter()
            result = evaluate(env, self.agent, episodes, seed=seed)
            projected = isinstance(env, factory.DropHeading)
            return EvaluationResult(result, optimal, time.perf_counter() - start, projected)
        finally:
            env.close()

    def render(
        self, out: Path | None = None, seed: int = 0, fps: int = 15, max_frames: int = 150
    ) -> tuple[Path, Episode]:
        """A GIF of one greedy episode over the partition (default: ``episode.gif`` beside the
        agent)."""
        from experiments.animation import render_gif

        config_module.check_override("seed", seed)
        if not self.config.env.is_maze:
            raise ConfigError(f"render draws maze environments only, not {self.config.env.id!r}")
        out = out or self.path.parent / "episode.gif"
        if out.is_dir():
            raise ConfigError(f"option --out: {out} is a folder; give the GIF's file name")
        _check_folder(out.parent, "--out")
        env = self.make_env()
        try:
            episode = greedy_episode(env, self.agent, seed=seed)
            layout, directions = factory.maze_geometry(env)
        finally:
            env.close()
        render_gif(
            self.agent,
            layout,
            directions,
            episode.positions,
            out,
            fps=fps,
            max_frames=max_frames,
            title=f"{self.agent.n_leaves} leaves,",
        )
        return out, episode


def _agent_file(path: Path) -> Path:
    if path.is_dir():
        for name in AGENT_FILES:
            if (path / name).is_file():
                return path / name
        raise ConfigError(f"{path}: holds no agent file ({' or '.join(AGENT_FILES)})")
    if not path.is_file():
        raise ConfigError(f"agent file not found: {path}")
    return path
