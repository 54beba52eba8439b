"""Experiment files: TOML loaded, validated and bounded into frozen dataclasses.

An experiment file has four parts (``docs/experiments.md`` is the full reference)::

    [experiment]            # name, seed, runs, episodes, baseline, smoothing_window, ...
    [env]                   # id, maze, robot, mode, max_episode_steps, observation_bounds,
                            # action_bins, [env.params]
    [agent]                 # agent config fields shared by every strategy (alpha, gamma, ...)
    [[strategy]]            # one table per compared strategy: name, agent, exploration, ...

Everything is checked on load, and every failure is a :class:`ConfigError` naming the file and
the key (``paper_fig4.toml: [strategy.2] exploration_params epsilon: ...``):

- the document: at most :data:`MAX_CONFIG_BYTES`, UTF-8, nested at most :data:`MAX_DEPTH`
  deep, every number finite;
- types strictly (a bool is not a number, a string is not a bool), against this module's
  dataclasses, ``TreeConfig``'s fields and the exploration classes' annotations
  (``agent.serialization``), and the environment constructor's annotations;
- sizes: runs, episodes, the cap, strategies, seeds and names have the bounds below;
- the environment id: one registered by this project or one of Gymnasium's own (their
  registrations import no user code), or an id the caller allows explicitly
  (``run.py --allow-env``, or registered by a module named with ``run.py --env-module``).
  Never an import path (``module:Id``), which would make Gymnasium import that module.
"""

from __future__ import annotations

import dataclasses
import inspect
import math
import re
import tomllib
from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import Any, get_type_hints

import tomli_w
from gymnasium.envs.registration import load_env_creator, registry
from gymnasium.error import DependencyNotInstalled

import bullet_maze
from agent.presets import preset as named_preset
from agent.serialization import config_from_data, exploration_from_data
from agent.spaces import MAX_OBSERVATION_DIMS
from agent.tree_ensemble import save_refusal
from agent.uniform_grid import MAX_GRID_CELLS
from agent.value_checks import check_value
from bullet_maze.params import MAX_EPISODE_STEPS, MODES
from experiments.agent_kinds import (
    AGENT_KINDS,
    PRESET_NAMES,
    check_agent_params,
    is_fixed,
    preset_config,
)

EXPERIMENT_DIR = Path(__file__).resolve().parent
"""Where the shipped experiment files live (``experiments/*.toml``)."""

MAX_CONFIG_BYTES = 1 << 20
"""Largest experiment file (1 MiB)."""
MAX_DEPTH = 16
"""Deepest nesting of tables and arrays in an experiment file."""
MAX_RUNS = 10_000
"""Most runs per strategy (the paper: 30)."""
MAX_EPISODES = 1_000_000
"""Most episodes per run (the paper: 4,000)."""
MAX_EPISODE_CAP = 10_000_000
"""Largest episode cap, ``max_episode_steps`` (the paper: 5,000)."""
MAX_STRATEGIES = 200
"""Most strategies in one experiment."""
MAX_SEED = 2**32 - 1
"""Largest seed (run seeds are 32-bit)."""
MAX_NAME = 100
"""Longest experiment or strategy name (they name files)."""
MAX_TEXT = 20_000
"""Longest description."""
MAX_STRING = 4096
"""Longest other string (a path, a name, an id)."""
MAX_TIME_BUDGET_S = 1e7
"""Longest wall-clock budget of a ``train`` run, in seconds."""
MAX_TASKS = 1000
"""Most tasks in one experiment (a suite split holds at most as many layouts)."""
MAX_PLANNED_RUNS = MAX_RUNS * MAX_STRATEGIES
"""Most runs (runs x tasks x strategies) in one experiment: what one environment allowed."""
MAX_EVAL_EPISODES = 100_000
"""Most greedy evaluation episodes per run."""
MAX_ACTION_BINS = 64
"""Most values per dimension of ``action_bins`` (the grid has at most 4,096 actions in all)."""
SPLITS = ("dev", "test")
"""The splits of a layout suite (``bullet_maze.suites``)."""

DEFAULT_ENV_ID = "BulletMaze-v0"
_MAZE_DEFAULTS = {
    name: p.default for name, p in inspect.signature(bullet_maze.BulletMazeEnv).parameters.items()
}
"""The maze env's own defaults (maze, robot, mode), so that they are written once, there."""
_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.+-]*$")
_OWN_KEYS = ("maze", "robot", "mode")
"""Keyword arguments of the maze env that ``[env]`` sets by name, not in ``[env.params]``."""
_SUITE_KEYS = ("suite", "split")
"""Keys of ``[env]`` that choose a layout suite's tasks (they are not ``EnvSpec`` fields)."""
_REFERENCE_KEYS = ("random_return", "solved_return")
"""Keys of a ``[[task]]`` table that set its normalised score's ends."""


class ConfigError(ValueError):
    """A bad experiment file or option; the message names the file and key, or the option."""


@dataclass(frozen=True)
class EnvSpec:
    """Which environment a run trains in.

    ``maze``, ``robot`` and ``mode`` apply to the maze ids (``BulletMaze-*``) and are None for
    any other environment (a Gymnasium classic-control task, say).
    """

    id: str = DEFAULT_ENV_ID
    """Gymnasium id: a ``BulletMaze-*`` id, a Gymnasium built-in, or one allowed explicitly."""
    maze: str | None = _MAZE_DEFAULTS["maze"]
    """Layout name from ``assets/mazes/`` or a path to a layout TOML file (maze ids only)."""
    robot: str | None = _MAZE_DEFAULTS["robot"]
    """``"disc"``, ``"husky"`` or a path to a URDF file (maze ids only)."""
    mode: str | None = _MAZE_DEFAULTS["mode"]
    """``"kinematic"`` (fast, exact steps) or ``"dynamic"`` (physics) (maze ids only)."""
    max_episode_steps: int = MAX_EPISODE_STEPS
    """Episode cap (section V: 5,000 steps); by default the id's registered limit."""
    params: dict[str, Any] = field(default_factory=dict)
    """Extra keyword arguments for the environment's constructor."""
    observation_bounds: tuple[tuple[float, ...], tuple[float, ...]] | None = None
    """The box ``(low, high)`` the agent's partition covers, for an observation space with
    infinite bounds (CartPole's velocities); None: the space's own bounds. Observations outside
    the box fall into its edge cells."""
    action_bins: int | None = None
    """Values per dimension of a Box action space (``agent.adapt_env``: evenly spaced, both
    bounds included), from 2 to :data:`MAX_ACTION_BINS`; None: 5. Only for a task with Box
    actions."""

    @property
    def is_maze(self) -> bool:
        """Whether this is one of the project's maze environments."""
        return self.maze is not None

    @property
    def label(self) -> str:
        """A short name: the maze's file stem, else the id."""
        return Path(self.maze).stem if self.maze is not None else self.id

    def make_kwargs(self) -> dict[str, Any]:
        """The keyword arguments of ``gymnasium.make`` besides the id."""
        own = {key: getattr(self, key) for key in _OWN_KEYS if getattr(self, key) is not None}
        return {"max_episode_steps": self.max_episode_steps, **own, **self.params}


@dataclass(frozen=True)
class StrategySpec:
    """One compared learner: an agent kind with its exploration strategy and parameters."""

    name: str
    """Unique, file-name safe label; runs are named ``<name>__<seed>``."""
    agent: str = "tree"
    """``"tree"`` (the paper's adaptive tree, ``TreeAgent``), ``"grid"`` (``GridAgent``),
    ``"tile"`` (``TileCodingAgent``) or ``"adaptive-q"`` (``AdaptiveQAgent``)."""
    exploration: str = "adaptive+tabu"
    """Exploration strategy name understood by ``agent.make_exploration`` (tree and grid; with a
    preset, the preset's unless given)."""
    exploration_params: dict[str, Any] = field(default_factory=dict)
    """Keyword arguments of the exploration strategy (for example ``epsilon``); with a preset,
    the preset's with these over them."""
    config: dict[str, Any] = field(default_factory=dict)
    """Agent config fields for this strategy only, over the experiment's ``[agent]`` table, or
    over the preset's fields when it names one."""
    resolution: int | tuple[int, ...] | None = None
    """Cells per dimension of the uniform grid (``agent = "grid"`` only)."""
    preset: str | None = None
    """A named agent of ``agent.presets`` (``"paper"``, ``"paper-literal"``, ``"general"``;
    tree and grid): its ``TreeConfig`` replaces the experiment's ``[agent]`` table."""
    agent_params: dict[str, Any] = field(default_factory=dict)
    """Constructor arguments of ``agent = "tile"`` or ``"adaptive-q"`` (``tilings``, ``alpha``,
    ``bonus_scale``, ...); the other agents take none."""


@dataclass(frozen=True)
class TaskSpec:
    """One task of an experiment over several: a layout of a suite, or a ``[[task]]`` table."""

    name: str
    """File-name safe label, unique in the experiment; its runs are in ``runs/<name>/``."""
    env: EnvSpec
    """The task's environment."""
    split: str | None = None
    """The suite split it comes from (``"dev"`` or ``"test"``; None for a ``[[task]]``)."""
    random_return: float | None = None
    """Return that normalises to 0 (a return task; default: :mod:`experiments.references`)."""
    solved_return: float | None = None
    """Return that normalises to 1 (a return task; default: Gymnasium's ``reward_threshold``)."""

    @property
    def spec_text(self) -> str:
        """How the task reads in a report: the layout spec of a maze, else the id."""
        return self.env.maze if self.env.maze is not None else self.env.id


@dataclass(frozen=True)
class ExperimentConfig:
    """A whole experiment: strategies x tasks x runs x episodes.

    An experiment without tasks (no ``[env] suite``, no ``[[task]]``, and an ``[env]`` maze: an
    ``[env]`` of another id is read as one ``[[task]]``) runs in its one environment,
    :attr:`env`, and its run files keep their names (``runs/<strategy>__<seed>``);
    an experiment over tasks stores each task's runs in ``runs/<task>/``, and :attr:`env` is
    its first task's environment.
    """

    name: str
    """Label of the experiment; the default results folder is ``results/<name>/``."""
    strategies: tuple[StrategySpec, ...]
    """The compared strategies, in the order of the report."""
    seed: int = 0
    """Experiment seed; run i of every strategy uses the seeds derived from (seed, i)."""
    runs: int = 30
    """Independent runs per strategy (section V: 30)."""
    episodes: int = 4000
    """Episodes per run (section V: 4,000)."""
    env: EnvSpec = field(default_factory=EnvSpec)
    """The environment."""
    agent: dict[str, Any] = field(default_factory=dict)
    """Agent config fields shared by every strategy (Table I values by default)."""
    baseline: str | None = None
    """Strategy that probability of improvement is measured against (default: the first)."""
    smoothing_window: int = 50
    """Moving-average window (episodes) of the curves and of the convergence test."""
    final_window: int = 100
    """Episodes at the end of a run that make its final performance."""
    convergence_tolerance: float = 0.1
    """Converged once the moving average stays within this fraction of the final value."""
    time_budget_s: float | None = None
    """Wall-clock cap of one run, for the quick default job only (results then depend on speed)."""
    eval_episodes: int = 0
    """Greedy episodes after each run's training (0: none), the first reset seeded from the
    run's seed; stored beside the run as ``<run>.eval.csv``."""
    save_agents: bool = False
    """Store each run's trained agent (its policy, ``agent.save(policy_only=True)``) as
    ``<run>.agent.npz`` beside its CSV, its hash in the sidecar and verified like the CSV: the
    agents ``run.py transfer`` evaluates."""
    tasks: tuple[TaskSpec, ...] = ()
    """The tasks (empty: the one environment :attr:`env`)."""
    suite: str | None = None
    """The layout suite the tasks come from (``[env] suite``), if any."""
    splits: tuple[str, ...] = ()
    """The suite's splits run, in order (``[env] split``)."""
    description: str = ""
    """Free text copied into the report."""
    source: str = ""
    """File the experiment was read from (filled in by :func:`load_config`)."""

    @property
    def final_episodes(self) -> int:
        """How many episodes a run's final performance is the mean of: :attr:`final_window`,
        or every episode of a run shorter than that (the number the reports name)."""
        return min(self.final_window, self.episodes)

    @property
    def baseline_name(self) -> str:
        """The baseline strategy's name (the first strategy when none is set)."""
        return self.baseline if self.baseline is not None else self.strategies[0].name

    def strategy(self, name: str, option: str | None = None) -> StrategySpec:
        """The strategy called ``name`` (``option`` names where the name came from)."""
        for spec in self.strategies:
            if spec.name == name:
                return spec
        known = ", ".join(s.name for s in self.strategies)
        where = f"option {option}" if option else self.source
        raise ConfigError(f"{where}: no strategy named {name!r} in {self.source} (known: {known})")

    def agent_params(self, spec: StrategySpec) -> dict[str, Any]:
        """``TreeConfig`` fields of one strategy: the shared ``[agent]`` table, or its preset's
        fields when it names one, overlaid with its own ``config``."""
        base = preset_config(named_preset(spec.preset)) if spec.preset else self.agent
        return {**base, **spec.config}

    def task(self, name: str, option: str | None = None) -> TaskSpec:
        """The task called ``name`` (``option`` names where the name came from)."""
        for task in self.tasks:
            if task.name == name:
                return task
        where = f"option {option}" if option else self.source
        known = ", ".join(t.name for t in self.tasks) or "none: it has one environment"
        raise ConfigError(f"{where}: no task named {name!r} in {self.source} (tasks: {known})")

    def single_task(self, name: str | None = None, option: str | None = None) -> ExperimentConfig:
        """This experiment in one environment: the task ``name`` (default the first), or itself
        when it has no tasks."""
        if not self.tasks:
            if name is not None:
                self.task(name, option)
            return self
        task = self.task(name, option) if name is not None else self.tasks[0]
        return dataclasses.replace(self, env=task.env, tasks=(), suite=None, splits=())


# --- environment ids ----------------------------------------------------------------------


@cache
def builtin_env_ids() -> frozenset[str]:
    """Ids that Gymnasium registers itself (their entry points are in ``gymnasium.envs``)."""
    return frozenset(
        env_id
        for env_id, spec in registry.items()
        if isinstance(spec.entry_point, str) and spec.entry_point.startswith("gymnasium.envs.")
    )


def project_env_ids() -> frozenset[str]:
    """Ids that this project registers (``import bullet_maze``)."""
    return frozenset(bullet_maze.ENV_IDS)


def check_env_id(env_id: str, where: str, allowed: Collection[str] = ()) -> None:
    """Refuse an id that is an import path, is not registered, or is neither the project's,
    Gymnasium's own, nor in ``allowed`` (the ids a user passed with ``--allow-env``)."""
    if ":" in env_id:
        raise ConfigError(
            f"{where}: {env_id!r} is an import path (module:Id), which would make Gymnasium "
            "import that module; only registered ids are accepted"
        )
    if env_id not in registry:
        raise ConfigError(
            f"{where}: {env_id!r} is not a registered Gymnasium id (this project registers "
            f"{', '.join(sorted(project_env_ids()))}; Gymnasium's own, such as CartPole-v1, "
            "are accepted too; an env of your own is registered by naming the module that "
            "registers it, run.py --env-module MODULE)"
        )
    if env_id not in project_env_ids() | builtin_env_ids() and env_id not in allowed:
        raise ConfigError(
            f"{where}: {env_id!r} is registered by neither this project nor Gymnasium; "
            f"allow it explicitly with --allow-env {env_id}"
        )


def _is_maze_id(env_id: str) -> bool:
    spec = registry.get(env_id)
    return spec is not None and spec.entry_point == bullet_maze.ENTRY_POINT


class _Checked:
    """A parameter checked by the env's own function (``check(name, value)``), in place of a
    type annotation."""

    def __init__(self, check: Any) -> None:
        self.check = check


def _constructor(env_id: str, where: str) -> tuple[inspect.Signature, dict[str, Any]] | None:
    """The signature and resolved annotations of an id's environment class (None if unknown);
    a ConfigError at ``where`` when the class needs a package that is not installed
    (Gymnasium's ``DependencyNotInstalled``, such as Box2D for LunarLander, or an import that
    fails), since no run of the task could make its env."""
    entry = registry[env_id].entry_point
    if not isinstance(entry, str):
        return None
    try:
        creator = load_env_creator(entry)
    except (DependencyNotInstalled, ImportError) as exc:
        raise ConfigError(
            f"{where}: {env_id!r} cannot be made on this machine, a package it needs is "
            f"missing: {exc}"
        ) from None
    except (AttributeError, TypeError, ValueError):
        return None
    try:
        signature = inspect.signature(creator)
    except (TypeError, ValueError):
        return None
    target: Any = creator.__init__ if isinstance(creator, type) else creator  # type: ignore[misc]
    try:
        hints = get_type_hints(target)
    except (NameError, TypeError):
        hints = {}
    # An env whose constructor takes ``**params`` may name the dataclasses that define them
    # (``BulletMazeEnv.parameter_classes``): their fields become its keyword parameters here.
    # ``parameter_names`` lists the others it takes, left to the env to check.
    classes = getattr(creator, "parameter_classes", ())
    if classes:
        named = [p for p in signature.parameters.values() if p.kind != p.VAR_KEYWORD]
        for cls in classes:
            field_hints = get_type_hints(cls)
            for field in dataclasses.fields(cls):
                named.append(inspect.Parameter(field.name, inspect.Parameter.KEYWORD_ONLY))
                hints[field.name] = field_hints[field.name]
        known = {p.name for p in named}
        check = getattr(creator, "check_parameter", None)
        for name in getattr(creator, "parameter_names", ()):
            # A value or a range: the env's own ``check_parameter`` checks it, else the env.
            hints[name] = _Checked(check) if check is not None else hints.get(name, Any)
            if name not in known:
                named.append(inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY))
        signature = signature.replace(parameters=named)
    return signature, hints


# --- loading ------------------------------------------------------------------------------


def text_problem(value: str, limit: int = MAX_STRING) -> str | None:
    """What is wrong with a string a user gave (None if nothing): too long, or a NUL."""
    if len(value) > limit:
        return f"longer than {limit:,} characters"
    if "\x00" in value:
        return "holds a NUL character"
    return None


def check_option_text(value: str, option: str) -> str:
    """A string given on the command line (``ConfigError`` naming the option otherwise)."""
    problem = text_problem(value)
    if problem:
        raise ConfigError(f"option {option}: the value {value[:40]!r}... {problem}")
    return value


def resolve_path(name_or_path: str | Path) -> Path:
    """The file of an experiment given as a path or as a name in ``experiments/``."""
    path = Path(name_or_path)
    if path.is_file():
        return path
    if path.exists():
        raise ConfigError(f"experiment file {str(name_or_path)!r} is not a file")
    for candidate in (EXPERIMENT_DIR / path, EXPERIMENT_DIR / f"{path}.toml"):
        if candidate.is_file():
            return candidate
    known = ", ".join(sorted(p.stem for p in EXPERIMENT_DIR.glob("*.toml")))
    raise ConfigError(f"experiment file {str(name_or_path)!r} not found (shipped: {known})")


def load_config(
    name_or_path: str | Path, allowed_env_ids: Collection[str] = ()
) -> ExperimentConfig:
    """Read and validate an experiment file (a path, or a name from ``experiments/``)."""
    path = resolve_path(name_or_path)
    try:
        size = path.stat().st_size
        if size > MAX_CONFIG_BYTES:
            raise ConfigError(f"{path}: {size:,} bytes, at most {MAX_CONFIG_BYTES:,}")
        raw = path.read_bytes()
    except OSError as error:
        raise ConfigError(f"{path}: cannot be read ({error.strerror or error})") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as error:
        raise ConfigError(f"{path}: not UTF-8 text (byte {error.start})") from None
    data = parse_toml(text, str(path))
    return parse_config(data, source=str(path), allowed_env_ids=allowed_env_ids)


def parse_toml(text: str, source: str) -> dict[str, Any]:
    """TOML text as data, with errors (bad syntax, too deep) that name ``source``."""
    if len(text) > MAX_CONFIG_BYTES:
        raise ConfigError(f"{source}: {len(text):,} characters, at most {MAX_CONFIG_BYTES:,}")
    if _nesting(text) > 4 * MAX_DEPTH:  # cheap bound before the recursive parser runs
        raise ConfigError(f"{source}: nested more than {MAX_DEPTH} levels deep")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ConfigError(f"{source}: not valid TOML: {error}") from None
    except RecursionError:
        raise ConfigError(f"{source}: nested more than {MAX_DEPTH} levels deep") from None


def _nesting(text: str) -> int:
    """Upper bound of the bracket nesting of TOML text (strings included: only a bound)."""
    depth = deepest = 0
    for char in text:
        if char in "[{":
            depth += 1
            deepest = max(deepest, depth)
        elif char in "]}":
            depth = max(0, depth - 1)
    return deepest


def parse_config(
    data: Mapping[str, Any], source: str = "<config>", allowed_env_ids: Collection[str] = ()
) -> ExperimentConfig:
    """Validate the parsed TOML ``data`` of an experiment; ``source`` names it in errors."""
    reader = _Reader(source)
    reader.document(data)
    reader.only(data, "", {"experiment", "env", "agent", "strategy", "task"})
    meta = reader.table(data, "experiment", required=True)
    reader.only(
        meta,
        "experiment",
        {f.name for f in dataclasses.fields(ExperimentConfig)}
        - {"strategies", "env", "agent", "source", "tasks", "suite", "splits"},
    )
    env_table = reader.table(data, "env")
    suite, splits, tasks = reader.tasks(data, env_table, allowed_env_ids)
    env = tasks[0].env if tasks else reader.env(env_table, allowed_env_ids)
    if not tasks and not env.is_maze:
        # A task other than a maze is scored by its returns, never by a maze's steps and
        # successes (CartPole's terminated is a fall): it is an experiment over that one task.
        tasks = (TaskSpec(task_name(env), env),)
    agent = dict(reader.table(data, "agent"))
    if agent:
        _agent_check(lambda: config_from_data(agent, f"{source}: [agent]"))
    raw_strategies = data.get("strategy")
    if not isinstance(raw_strategies, list) or not raw_strategies:
        raise ConfigError(f"{source}: [[strategy]]: at least one strategy table is required")
    if len(raw_strategies) > MAX_STRATEGIES:
        raise ConfigError(
            f"{source}: [[strategy]]: {len(raw_strategies)} strategies, at most {MAX_STRATEGIES}"
        )
    strategies = tuple(reader.strategy(raw, i, agent) for i, raw in enumerate(raw_strategies))
    names = [s.name for s in strategies]
    for name in names:
        if names.count(name) > 1:
            raise ConfigError(f"{source}: [[strategy]] name: {name!r} is used twice")
    baseline = reader.value(meta, "experiment", "baseline", str, None)
    if baseline is not None and baseline not in names:
        raise ConfigError(
            f"{source}: [experiment] baseline: {baseline!r} is not a strategy "
            f"(known: {', '.join(names)})"
        )
    tolerance = reader.number(meta, "experiment", "convergence_tolerance", 0.1)
    if not 0 < tolerance < 1:
        raise ConfigError(
            f"{source}: [experiment] convergence_tolerance: must be in (0, 1), got {tolerance}"
        )
    budget = reader.number(meta, "experiment", "time_budget_s", None)
    if budget is not None and not 0 < budget <= MAX_TIME_BUDGET_S:
        raise ConfigError(
            f"{source}: [experiment] time_budget_s: must be in (0, {MAX_TIME_BUDGET_S:g}], "
            f"got {budget}"
        )
    description = reader.value(meta, "experiment", "description", str, "")
    if len(description) > MAX_TEXT:
        raise reader.fail("experiment", "description", f"longer than {MAX_TEXT} characters")
    runs = reader.bounded(meta, "experiment", "runs", 30, 1, MAX_RUNS)
    check_planned_runs(runs, max(1, len(tasks)), len(strategies), f"{source}: [experiment] runs")
    config = ExperimentConfig(
        name=reader.name(meta, "experiment", "name"),
        strategies=strategies,
        seed=reader.bounded(meta, "experiment", "seed", 0, 0, MAX_SEED),
        runs=runs,
        episodes=reader.bounded(meta, "experiment", "episodes", 4000, 1, MAX_EPISODES),
        env=env,
        agent=agent,
        baseline=baseline,
        smoothing_window=reader.bounded(
            meta, "experiment", "smoothing_window", 50, 1, MAX_EPISODES
        ),
        final_window=reader.bounded(meta, "experiment", "final_window", 100, 1, MAX_EPISODES),
        convergence_tolerance=float(tolerance),
        time_budget_s=None if budget is None else float(budget),
        eval_episodes=reader.bounded(meta, "experiment", "eval_episodes", 0, 0, MAX_EVAL_EPISODES),
        save_agents=reader.value(meta, "experiment", "save_agents", bool, False),
        tasks=tasks,
        suite=suite,
        splits=splits,
        description=description,
        source=source,
    )
    if config.save_agents:
        for spec in strategies:
            refusal = save_refusal_of(config, spec)
            if refusal is not None:
                raise ConfigError(
                    f"{source}: [experiment] save_agents = true, but strategy {spec.name!r} "
                    f"cannot be saved: {refusal}"
                )
    return config


def save_refusal_of(config: ExperimentConfig, spec: StrategySpec) -> str | None:
    """Why strategy ``spec``'s trained agent cannot be saved (None when it can): checked before
    any run trains an agent that must be saved (``save_agents``, ``run.py train``)."""
    if is_fixed(spec.agent):
        return None
    return save_refusal(config_from_data(config.agent_params(spec), f"strategy {spec.name!r}"))


def check_splits(items: Sequence[str], where: str) -> tuple[str, ...]:
    """Suite splits: each ``"dev"`` or ``"test"``, at least one, none twice (``where`` names
    the file and key, or the option)."""
    for item in items:
        if item not in SPLITS:
            raise ConfigError(f"{where}: unknown split {item[:100]!r} (the splits are dev, test)")
    if not items or len(set(items)) != len(items):
        raise ConfigError(f"{where}: expected dev, test or both once each, got {list(items)}")
    return tuple(items)


def check_planned_runs(runs: int, tasks: int, strategies: int, where: str) -> None:
    """Refuse more than :data:`MAX_PLANNED_RUNS` runs in all (``where`` names the cause)."""
    total = runs * tasks * strategies
    if total > MAX_PLANNED_RUNS:
        raise ConfigError(
            f"{where}: {runs:,} runs x {tasks:,} tasks x {strategies:,} strategies is "
            f"{total:,} runs, at most {MAX_PLANNED_RUNS:,}"
        )


def task_name(spec: EnvSpec) -> str:
    """The default name of a task: its layout spec or id made file-name safe
    (``rooms:seed=1,door=14`` -> ``rooms-seed1-door14``; a layout file by its stem)."""
    if spec.maze is None:
        text = spec.id
    elif spec.maze.endswith(".toml"):
        text = Path(spec.maze).stem
    else:
        text = spec.maze.replace(":", "-").replace(",", "-").replace("=", "")
    return re.sub(r"[^A-Za-z0-9_.+-]", "_", text)


_KEY = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


def parse_assignments(items: Sequence[str], option: str) -> dict[str, Any]:
    """``KEY=VALUE`` options as data; a value is read as TOML (``0.05``, ``true``,
    ``"text"``, ``[1, 2]``), and anything that is not TOML is a string (``cn_exponent``)."""
    values: dict[str, Any] = {}
    for item in items:
        key, sep, raw = item.partition("=")
        key = key.strip()
        if not sep or not _KEY.match(key):
            raise ConfigError(f"option {option}: expected KEY=VALUE, got {item[:200]!r}")
        if key in values:
            raise ConfigError(f"option {option}: {key} is given twice")
        if len(raw) > MAX_NAME * 10 or "\n" in raw or "\r" in raw:
            raise ConfigError(f"option {option}: the value of {key} is too long or has a newline")
        try:
            parsed = parse_toml(f"v = {raw}", f"option {option}")
        except ConfigError:
            values[key] = raw.strip()
            continue
        if set(parsed) != {"v"}:
            raise ConfigError(f"option {option}: {item!r} is not one KEY=VALUE")
        try:
            check_value(parsed["v"], Any, f"option {option} {key}")  # finite, at least
        except ValueError as error:
            raise ConfigError(str(error)) from None
        values[key] = parsed["v"]
    return values


def _agent_check(build: Any) -> Any:
    try:
        return build()
    except ValueError as error:
        raise ConfigError(str(error)) from None


OVERRIDE_BOUNDS = {
    "runs": (1, MAX_RUNS),
    "episodes": (1, MAX_EPISODES),
    "seed": (0, MAX_SEED),
    "max_episode_steps": (1, MAX_EPISODE_CAP),
}
"""The command-line overrides of an experiment and their bounds."""


def check_override(key: str, value: Any) -> int:
    """An integer option within :data:`OVERRIDE_BOUNDS` (the message names ``--key``)."""
    low, high = OVERRIDE_BOUNDS[key]
    option = f"--{key.replace('_', '-')}"
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise ConfigError(
            f"option {option}: expected an integer from {low} to {high:,}, got {value!r}"
        )
    return value


def with_overrides(config: ExperimentConfig, **overrides: int | None) -> ExperimentConfig:
    """A copy with ``runs``/``episodes``/``seed``/``max_episode_steps`` replaced (None keeps)."""
    changes = {k: v for k, v in overrides.items() if v is not None}
    unknown = set(changes) - set(OVERRIDE_BOUNDS)
    if unknown:
        raise ConfigError(f"unknown override(s): {', '.join(sorted(unknown))}")
    for key, value in changes.items():
        check_override(key, value)
    env_changes: dict[str, Any] = {}
    if "max_episode_steps" in changes:
        env_changes["max_episode_steps"] = changes.pop("max_episode_steps")
    env = dataclasses.replace(config.env, **env_changes) if env_changes else config.env
    tasks = tuple(
        dataclasses.replace(task, env=dataclasses.replace(task.env, **env_changes))
        for task in config.tasks
    )
    if "runs" in changes:
        check_planned_runs(
            changes["runs"], max(1, len(tasks)), len(config.strategies), "option --runs"
        )
    fields: dict[str, Any] = {"env": env, "tasks": tasks, **changes}
    return dataclasses.replace(config, **fields)


def with_splits(
    config: ExperimentConfig, splits: Sequence[str] | None, option: str = "--split"
) -> ExperimentConfig:
    """A suite experiment over other splits of its suite (None keeps the file's)."""
    if splits is None:
        return config
    if config.suite is None:
        raise ConfigError(
            f"option {option}: only applies to an experiment over a layout suite ([env] suite); "
            f"{config.source} has none"
        )
    chosen = check_splits([check_option_text(s, option) for s in splits], f"option {option}")
    data = to_dict(config)
    data["env"]["split"] = list(chosen)
    return parse_config(data, config.source)


def to_dict(config: ExperimentConfig) -> dict[str, Any]:
    """The experiment as TOML-ready data (the inverse of :func:`parse_config`)."""
    meta: dict[str, Any] = {
        "name": config.name,
        "description": config.description,
        "seed": config.seed,
        "runs": config.runs,
        "episodes": config.episodes,
        "smoothing_window": config.smoothing_window,
        "final_window": config.final_window,
        "convergence_tolerance": config.convergence_tolerance,
    }
    if config.baseline is not None:
        meta["baseline"] = config.baseline
    if config.time_budget_s is not None:
        meta["time_budget_s"] = config.time_budget_s
    if config.eval_episodes:
        meta["eval_episodes"] = config.eval_episodes
    if config.save_agents:
        meta["save_agents"] = True
    strategies = [strategy_to_dict(spec) for spec in config.strategies]
    data: dict[str, Any] = {"experiment": meta}
    if config.suite is not None:
        env = env_to_dict(config.env)
        env.pop("maze", None)
        env["suite"] = config.suite
        env["split"] = config.splits[0] if len(config.splits) == 1 else list(config.splits)
        data["env"] = env
    elif config.tasks:
        data["task"] = [task_to_dict(task) for task in config.tasks]
    else:
        data["env"] = env_to_dict(config.env)
    return {**data, "agent": dict(config.agent), "strategy": strategies}


def env_to_dict(spec: EnvSpec) -> dict[str, Any]:
    """An ``[env]`` table (its unset fields left out)."""
    env = {k: v for k, v in dataclasses.asdict(spec).items() if v is not None}
    if spec.observation_bounds is not None:
        env["observation_bounds"] = [list(side) for side in spec.observation_bounds]
    return env


def task_to_dict(task: TaskSpec) -> dict[str, Any]:
    """One ``[[task]]`` table, its environment written in full."""
    table: dict[str, Any] = {"name": task.name, **env_to_dict(task.env)}
    if task.random_return is not None:
        table["random_return"] = task.random_return
        table["solved_return"] = task.solved_return
    return table


def strategy_to_dict(spec: StrategySpec) -> dict[str, Any]:
    """One ``[[strategy]]`` table."""
    table: dict[str, Any] = {"name": spec.name, "agent": spec.agent}
    if is_fixed(spec.agent):
        if spec.agent_params:
            table["agent_params"] = dict(spec.agent_params)
        return table
    if spec.preset is not None:
        table["preset"] = spec.preset
    table["exploration"] = spec.exploration
    if spec.exploration_params:
        table["exploration_params"] = dict(spec.exploration_params)
    if spec.config:
        table["config"] = dict(spec.config)
    if spec.resolution is not None:
        table["resolution"] = (
            spec.resolution if isinstance(spec.resolution, int) else list(spec.resolution)
        )
    return table


def dumps(config: ExperimentConfig) -> str:
    """The resolved experiment as TOML text, loadable again with :func:`load_config`."""
    return tomli_w.dumps(to_dict(config))


REPORT_SETTINGS: dict[str, tuple[str, ...]] = {
    "experiment": ("smoothing_window", "final_window", "convergence_tolerance", "baseline"),
    "task": ("random_return", "solved_return"),
}
"""Keys that change only the report, never a run (no run's fingerprint holds them): a folder's
runs stay valid when they change, and its recorded ``config.toml`` follows the report."""


def same_experiment(a: ExperimentConfig, b: ExperimentConfig) -> list[str]:
    """Keys whose values differ between two experiments, ignoring the number of runs and the
    description: ``section.key``, and ``task[name].key`` for a task present in both.

    Runs may be added to a results folder (run i's seed does not depend on how many runs
    there are); a difference in anything else but :data:`REPORT_SETTINGS` changes the
    results, so a folder must not mix them (:func:`run_differences`).
    """
    left, right = to_dict(a), to_dict(b)
    left["experiment"].pop("runs"), right["experiment"].pop("runs")
    for side in (left, right):
        side["experiment"].pop("description", None)
    differences = []
    for section in sorted(set(left) | set(right)):
        lv, rv = left.get(section), right.get(section)
        if lv == rv:
            continue
        if isinstance(lv, dict) and isinstance(rv, dict):
            differences += _dict_differences(section, lv, rv)
        elif section == "task" and isinstance(lv, list) and isinstance(rv, list):
            if not _same_task_names(lv, rv):
                differences.append(section)
                continue
            for lt, rt in zip(lv, rv, strict=True):
                differences += _dict_differences(f"task[{lt['name']}]", lt, rt)
        else:
            differences.append(section)
    return differences


def run_differences(differences: list[str]) -> list[str]:
    """The differences of :func:`same_experiment` that change runs (all but the report's)."""
    return [d for d in differences if not _is_report_setting(d)]


def _is_report_setting(difference: str) -> bool:
    section, _, key = difference.rpartition(".")
    return key in REPORT_SETTINGS.get(section.split("[", 1)[0], ())


def _dict_differences(where: str, left: dict[str, Any], right: dict[str, Any]) -> list[str]:
    keys = sorted(set(left) | set(right))
    return [f"{where}.{k}" for k in keys if left.get(k) != right.get(k)]


def _same_task_names(left: list[Any], right: list[Any]) -> bool:
    if len(left) != len(right):
        return False
    pairs = zip(left, right, strict=True)
    return all(
        isinstance(x, dict) and isinstance(y, dict) and x.get("name") == y.get("name")
        for x, y in pairs
    )


class _Reader:
    """Typed access to parsed TOML with errors that name the file and the key."""

    def __init__(self, source: str) -> None:
        self.source = source

    def fail(self, where: str, key: str, message: str) -> ConfigError:
        prefix = f"[{where}] " if where else ""
        return ConfigError(f"{self.source}: {prefix}{key}: {message}")

    def document(self, data: Any) -> None:
        """Every number finite, nesting bounded, keys strings (walked without recursion)."""
        stack: list[tuple[Any, tuple[Any, ...]]] = [(data, ())]
        while stack:
            value, path = stack.pop()
            if len(path) > MAX_DEPTH:
                raise self.at(path, f"nested more than {MAX_DEPTH} levels")
            if isinstance(value, float) and not math.isfinite(value):
                raise self.at(path, f"must be finite, got {value!r}")
            if isinstance(value, Mapping):
                for key, item in value.items():
                    if not isinstance(key, str):
                        raise self.at(path, f"key {key!r} is not a string")
                    stack.append((item, (*path, key)))
            elif isinstance(value, list | tuple):
                stack += [(item, (*path, i)) for i, item in enumerate(value)]

    def at(self, path: tuple[Any, ...], message: str) -> ConfigError:
        """An error at a key path, written as the rest of this module writes keys
        (``[agent] alpha``, ``[strategy.1] config.max_leaves``)."""
        if len(path) >= 2 and path[0] in ("strategy", "task") and isinstance(path[1], int):
            table, rest = f"{path[0]}.{path[1]}", path[2:]
        else:
            table, rest = (str(path[0]) if path else ""), path[1:]
        key = ".".join(str(k) if not isinstance(k, int) else f"[{k}]" for k in rest)
        key = key.replace(".[", "[")
        return (
            self.fail(table, key or "(table)", message)
            if table
            else ConfigError(f"{self.source}: {message}")
        )

    def only(self, table: Mapping[str, Any], where: str, allowed: set[str]) -> None:
        for key in table:
            if key not in allowed:
                raise self.fail(where, key, f"unknown key (allowed: {', '.join(sorted(allowed))})")

    def table(
        self, parent: Mapping[str, Any], key: str, required: bool = False
    ) -> Mapping[str, Any]:
        name = key.rsplit(".", 1)[-1]
        if name not in parent:
            if required:
                raise ConfigError(f"{self.source}: [{key}]: this table is required")
            return {}
        value = parent[name]
        if not isinstance(value, dict):
            raise ConfigError(f"{self.source}: {key}: expected a table, got {value!r}")
        return value

    def value(
        self,
        table: Mapping[str, Any],
        where: str,
        key: str,
        kind: type | tuple[type, ...],
        default: Any,
    ) -> Any:
        if key not in table:
            return default
        value = table[key]
        kinds = kind if isinstance(kind, tuple) else (kind,)
        if isinstance(value, bool) and bool not in kinds:
            raise self.fail(where, key, f"expected {_kind_name(kinds)}, got {value!r}")
        if not isinstance(value, kinds):
            raise self.fail(where, key, f"expected {_kind_name(kinds)}, got {value!r}")
        if isinstance(value, str):
            problem = text_problem(value, MAX_TEXT if key == "description" else MAX_STRING)
            if problem:
                raise self.fail(where, key, problem)
        return value

    def number(self, table: Mapping[str, Any], where: str, key: str, default: Any) -> Any:
        value = self.value(table, where, key, (int, float), default)
        if value is not None and not math.isfinite(value):
            raise self.fail(where, key, f"must be finite, got {value!r}")
        return value

    def bounded(
        self, table: Mapping[str, Any], where: str, key: str, default: int, low: int, high: int
    ) -> int:
        value = self.value(table, where, key, int, default)
        if not low <= value <= high:
            raise self.fail(where, key, f"must be an integer from {low} to {high:,}, got {value:,}")
        return value

    def choice(
        self, table: Mapping[str, Any], where: str, key: str, choices: tuple[str, ...], default: str
    ) -> str:
        value = self.value(table, where, key, str, default)
        if value not in choices:
            raise self.fail(where, key, f"expected one of {', '.join(choices)}, got {value!r}")
        return value

    def name(self, table: Mapping[str, Any], where: str, key: str) -> str:
        if key not in table:
            raise self.fail(where, key, "is required")
        value = self.value(table, where, key, str, None)
        if not _NAME.match(value) or len(value) > MAX_NAME:
            raise self.fail(
                where,
                key,
                f"{value[:MAX_NAME]!r} must be at most {MAX_NAME} letters, digits and _ . + - "
                "(it names files)",
            )
        return value

    def env(
        self,
        table: Mapping[str, Any],
        allowed_env_ids: Collection[str],
        where: str = "env",
        inherited: Collection[str] = (),
    ) -> EnvSpec:
        """An environment table: ``[env]``, or a task's (``where``) whose ``inherited`` keys
        came from ``[env]`` (their errors name ``[env]``)."""

        def at(key: str) -> str:
            return "env" if key in inherited else where

        self.only(table, where, {f.name for f in dataclasses.fields(EnvSpec)})
        env_id = self.value(table, at("id"), "id", str, DEFAULT_ENV_ID)
        check_env_id(env_id, f"{self.source}: [{at('id')}] id", allowed_env_ids)
        params = dict(self.table(table, f"{at('params')}.params"))
        registered = registry[env_id]
        cap = self.bounded(
            table,
            at("max_episode_steps"),
            "max_episode_steps",
            registered.max_episode_steps or MAX_EPISODE_STEPS,
            1,
            MAX_EPISODE_CAP,
        )
        constructor = _constructor(env_id, f"{self.source}: [{at('id')}] id")
        if constructor is not None:
            self.env_params(params, constructor, env_id, f"{at('params')}.params")
        bounds = self.observation_bounds(table, at("observation_bounds"))
        bins = None
        if "action_bins" in table:
            bins = self.bounded(table, at("action_bins"), "action_bins", 5, 2, MAX_ACTION_BINS)
        if not _is_maze_id(env_id):
            for key in _OWN_KEYS:
                if key in table:
                    whose = f" (the id of [{where}])" if key in inherited else ""
                    raise self.fail(
                        at(key), key, f"only applies to the maze ids, not {env_id!r}{whose}"
                    )
            return EnvSpec(env_id, None, None, None, cap, params, bounds, bins)
        defaults = {**_signature_defaults(constructor), **registered.kwargs}
        return EnvSpec(
            id=env_id,
            maze=self.value(table, at("maze"), "maze", str, defaults.get("maze", EnvSpec.maze)),
            robot=self.value(
                table, at("robot"), "robot", str, defaults.get("robot", EnvSpec.robot)
            ),
            mode=self.choice(table, at("mode"), "mode", MODES, defaults.get("mode", MODES[0])),
            max_episode_steps=cap,
            params=params,
            observation_bounds=bounds,
            action_bins=bins,
        )

    def observation_bounds(
        self, table: Mapping[str, Any], where: str
    ) -> tuple[tuple[float, ...], tuple[float, ...]] | None:
        """``observation_bounds = [[low, ...], [high, ...]]``: finite numbers, low < high."""
        key = "observation_bounds"
        if key not in table:
            return None
        value = table[key]
        expected = (
            f"expected [[low, ...], [high, ...]] with at most {MAX_OBSERVATION_DIMS} finite "
            "numbers each, every low below its high"
        )
        if not (
            isinstance(value, list)
            and len(value) == 2
            and all(isinstance(side, list) for side in value)
            and 1 <= len(value[0]) == len(value[1]) <= MAX_OBSERVATION_DIMS
            and all(
                isinstance(x, int | float) and not isinstance(x, bool) and math.isfinite(x)
                for side in value
                for x in side
            )
        ):
            raise self.fail(where, key, f"{expected}, got {str(value)[:200]}")
        low, high = (tuple(float(x) for x in side) for side in value)
        if not all(a < b for a, b in zip(low, high, strict=True)):
            raise self.fail(where, key, f"{expected}, got {str(value)[:200]}")
        return low, high

    def env_params(
        self,
        params: Mapping[str, Any],
        constructor: tuple[inspect.Signature, dict[str, Any]],
        env_id: str,
        where: str = "env.params",
    ) -> None:
        """``[env.params]`` against the environment constructor's parameters and annotations."""
        signature, hints = constructor
        accepted = {
            name
            for name, p in signature.parameters.items()
            if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)
        }
        open_ended = any(p.kind == p.VAR_KEYWORD for p in signature.parameters.values())
        reserved = {"render_mode", *(_OWN_KEYS if _is_maze_id(env_id) else ())}
        for key, value in params.items():
            if key in reserved:
                raise self.fail(
                    where,
                    key,
                    f"is set by [env] {key}"
                    if key != "render_mode"
                    else "is chosen by the command (render), not by the experiment",
                )
            if key not in accepted and not open_ended:
                raise self.fail(
                    where,
                    key,
                    f"{env_id} takes no such argument (it takes "
                    f"{', '.join(sorted(accepted - reserved))})",
                )
            if key == "end_on_tip" and value is True and _is_maze_id(env_id):
                raise self.fail(
                    where,
                    key,
                    "would cut an episode short where the robot tips over, and the reports "
                    "count a failed episode's steps at the cap; leave it false (info['tipped'] "
                    "still reports a fall, and evaluations count them)",
                )
            if isinstance(hints.get(key), _Checked):
                try:
                    hints[key].check(key, value)
                except (TypeError, ValueError) as error:
                    raise self.fail("env.params", key, str(error)) from None
            elif key in hints and hints[key] is not Any:
                try:
                    check_value(value, hints[key], f"{self.source}: [{where}] {key}")
                except ValueError as error:
                    raise ConfigError(str(error)) from None

    def tasks(
        self, data: Mapping[str, Any], env: Mapping[str, Any], allowed_env_ids: Collection[str]
    ) -> tuple[str | None, tuple[str, ...], tuple[TaskSpec, ...]]:
        """The suite, its splits and the tasks of ``[env] suite`` or of ``[[task]]`` tables
        (None, (), () for an experiment in one environment). A task's table replaces each
        ``[env]`` field it gives (``params`` as a whole) and inherits the others."""
        if "split" in env and "suite" not in env:
            raise self.fail("env", "split", "only applies with [env] suite")
        if "suite" in env:
            if "task" in data:
                raise self.fail(
                    "env",
                    "suite",
                    "cannot be combined with [[task]] tables (give one or the other)",
                )
            return self.suite_tasks(env, allowed_env_ids)
        if "task" not in data:
            return None, (), ()
        raw = data["task"]
        if not isinstance(raw, list) or not all(isinstance(item, dict) for item in raw):
            raise ConfigError(f"{self.source}: [[task]]: expected an array of tables [[task]]")
        if not raw:
            raise ConfigError(f"{self.source}: [[task]]: at least one task table is required")
        if len(raw) > MAX_TASKS:
            raise ConfigError(f"{self.source}: [[task]]: {len(raw):,} tasks, at most {MAX_TASKS:,}")
        env_keys = {f.name for f in dataclasses.fields(EnvSpec)}
        self.only(env, "env", env_keys)
        tasks = []
        for index, table in enumerate(raw):
            where = f"task.{index}"
            self.only(table, where, env_keys | {"name", *_REFERENCE_KEYS})
            merged = {key: value for key, value in env.items() if key in env_keys}
            merged.update({key: value for key, value in table.items() if key in env_keys})
            inherited = {key for key in env if key not in table}
            spec = self.env(merged, allowed_env_ids, where, inherited)
            if "name" in table:
                name = self.name(table, where, "name")
            else:
                name = task_name(spec)
                if not _NAME.match(name) or len(name) > MAX_NAME:
                    raise self.fail(where, "name", f"is required ({spec.label!r} makes no name)")
            random_return, solved_return = self.references(table, where, spec)
            tasks.append(TaskSpec(name, spec, None, random_return, solved_return))
        self.distinct(tasks)
        return None, (), tuple(tasks)

    def references(
        self, table: Mapping[str, Any], where: str, spec: EnvSpec
    ) -> tuple[float | None, float | None]:
        given = [key for key in _REFERENCE_KEYS if key in table]
        if not given:
            return None, None
        if spec.is_maze:
            raise self.fail(where, given[0], "a maze task is scored against its optimum")
        if len(given) == 1:
            missing = next(key for key in _REFERENCE_KEYS if key not in table)
            raise self.fail(where, missing, f"is required with {given[0]}")
        low = float(self.number(table, where, "random_return", None))
        high = float(self.number(table, where, "solved_return", None))
        if not low < high:
            raise self.fail(
                where, "solved_return", f"must be above random_return ({low:g}), got {high:g}"
            )
        if not math.isfinite(high - low):  # (the normalised score divides by it)
            raise self.fail(
                where,
                "solved_return",
                f"{high:g} is too far from random_return ({low:g}): their difference overflows",
            )
        return low, high

    def distinct(self, tasks: Sequence[TaskSpec]) -> None:
        """No two tasks with one name, nor two with one environment."""
        for later, task in enumerate(tasks):
            for earlier in range(later):
                other = tasks[earlier]
                if other.name == task.name:
                    raise self.fail(
                        f"task.{later}",
                        "name",
                        f"{task.name!r} is the name of task {earlier} too (give each a name)",
                    )
                if other.env == task.env:
                    raise ConfigError(
                        f"{self.source}: [task.{later}]: the same task as [task.{earlier}] "
                        f"({task.spec_text!r})"
                    )

    def suite_tasks(
        self, env: Mapping[str, Any], allowed_env_ids: Collection[str]
    ) -> tuple[str, tuple[str, ...], tuple[TaskSpec, ...]]:
        """One task per layout of ``[env] suite``'s ``split`` (``"dev"`` by default)."""
        name = self.value(env, "env", "suite", str, None)
        if "maze" in env:
            raise self.fail(
                "env", "maze", "cannot be combined with suite (each layout of the suite is a task)"
            )
        splits = self.splits(env.get("split", "dev"), "[env] split")
        base = self.env({k: v for k, v in env.items() if k not in _SUITE_KEYS}, allowed_env_ids)
        if not base.is_maze or "maze" in registry[base.id].kwargs:
            raise self.fail(
                "env",
                "suite",
                f"needs a maze id whose maze the experiment chooses ({DEFAULT_ENV_ID}), "
                f"not {base.id!r}",
            )
        try:
            suite = bullet_maze.load_suite(name)
        except (TypeError, ValueError, OSError) as error:
            raise self.fail("env", "suite", str(error)) from None
        tasks = []
        for split in splits:
            for spec in suite.split(split):
                layout_env = dataclasses.replace(base, maze=spec)
                tasks.append(TaskSpec(task_name(layout_env), layout_env, split))
        for task in tasks:
            if not _NAME.match(task.name) or len(task.name) > MAX_NAME:
                raise self.fail("env", "suite", f"layout {task.spec_text!r} makes no task name")
        self.distinct(tasks)
        return name, splits, tuple(tasks)

    def splits(self, value: Any, where: str) -> tuple[str, ...]:
        """``"dev"``, ``"test"`` or a list of them (each at most once)."""
        items = value if isinstance(value, list) else [value]
        if not items or not all(isinstance(item, str) for item in items):
            raise ConfigError(
                f'{self.source}: {where}: expected "dev", "test" or a list of them, got {value!r}'
            )
        return check_splits(items, f"{self.source}: {where}")

    def strategy(self, raw: Any, index: int, agent: Mapping[str, Any]) -> StrategySpec:
        where = f"strategy.{index}"
        if not isinstance(raw, dict):
            raise ConfigError(f"{self.source}: [[strategy]] #{index}: expected a table")
        self.only(raw, where, {f.name for f in dataclasses.fields(StrategySpec)})
        name = self.name(raw, where, "name")
        kind = self.choice(raw, where, "agent", AGENT_KINDS, "tree")
        prefix = f"{self.source}: [{where}]"
        if is_fixed(kind):
            for key in ("preset", "exploration", "exploration_params", "config", "resolution"):
                if key in raw:
                    raise self.fail(
                        where,
                        key,
                        f'does not apply to agent = "{kind}" (it explores by its own rule; '
                        "its parameters go in agent_params)",
                    )
            agent_params = dict(self.value(raw, where, "agent_params", dict, {}))
            _agent_check(lambda: check_agent_params(kind, agent_params, f"{prefix} agent_params"))
            return StrategySpec(name=name, agent=kind, agent_params=agent_params)
        if "agent_params" in raw:
            raise self.fail(
                where,
                "agent_params",
                f'only applies to agent = "tile" or "adaptive-q" (agent = "{kind}" takes '
                "TreeConfig fields in config)",
            )
        resolution = raw.get("resolution")
        if kind == "grid":
            if resolution is None:
                raise self.fail(where, "resolution", 'is required when agent = "grid"')
            resolution = self.resolution(resolution, where)
        elif resolution is not None:
            raise self.fail(where, "resolution", 'only applies to agent = "grid"')
        preset = None
        if "preset" in raw:
            preset = self.choice(raw, where, "preset", PRESET_NAMES, "")
        named = named_preset(preset) if preset is not None else None
        default_exploration = named.exploration if named is not None else "adaptive+tabu"
        exploration = self.value(raw, where, "exploration", str, default_exploration)
        params = dict(self.value(raw, where, "exploration_params", dict, {}))
        if named is not None and exploration == named.exploration:
            params = {**named.exploration_params, **params}
        config = dict(self.value(raw, where, "config", dict, {}))
        _agent_check(lambda: exploration_from_data(exploration, params, f"{prefix} exploration"))
        # the strategy's config is checked on top of its preset or [agent] only: alone, a field
        # that needs another (model_lambda needs the preset's planning = "sweep") is refused
        base = preset_config(named) if named is not None else dict(agent)
        under = f"preset {preset!r}" if named is not None else "[agent]"
        _agent_check(lambda: config_from_data({**base, **config}, f"{prefix} {under} + config"))
        return StrategySpec(
            name=name,
            agent=kind,
            exploration=exploration,
            exploration_params=params,
            config=config,
            resolution=resolution,
            preset=preset,
        )

    def resolution(self, value: Any, where: str) -> int | tuple[int, ...]:
        items = value if isinstance(value, list) else [value]
        ok = (
            bool(items)
            and len(items) <= 64
            and all(isinstance(r, int) and not isinstance(r, bool) and r > 0 for r in items)
        )
        if not ok:
            raise self.fail(
                where, "resolution", f"expected a positive integer or a list of them, got {value!r}"
            )
        cells = math.prod(items)
        if cells > MAX_GRID_CELLS:
            raise self.fail(where, "resolution", f"{cells:,} cells, at most {MAX_GRID_CELLS:,}")
        return tuple(items) if isinstance(value, list) else value


def _signature_defaults(
    constructor: tuple[inspect.Signature, dict[str, Any]] | None,
) -> dict[str, Any]:
    if constructor is None:
        return {}
    return {
        name: p.default
        for name, p in constructor[0].parameters.items()
        if p.default is not inspect.Parameter.empty
    }


def _kind_name(kinds: tuple[type, ...]) -> str:
    names = {
        int: "an integer",
        float: "a number",
        str: "a string",
        dict: "a table",
        bool: "true or false",
        list: "a list",
    }
    return " or ".join(names.get(k, k.__name__) for k in kinds)
