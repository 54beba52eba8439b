"""Experiment files: TOML loaded and validated into frozen dataclasses.

An experiment file has four parts (``docs/experiments.md`` is the full reference)::

    [experiment]            # name, seed, runs, episodes, baseline, smoothing_window, ...
    [env]                   # id, maze, robot, mode, max_episode_steps, [env.params]
    [agent]                 # agent config fields shared by every strategy (alpha, gamma, ...)
    [[strategy]]            # one table per compared strategy: name, agent, exploration, ...

Every unknown key and every value of the wrong type is reported as a :class:`ConfigError`
naming the file and the key (``paper_fig4.toml: [strategy.2] exploration_params: ...``).
Whether agent fields and exploration parameters exist is checked against the agent package
itself by :func:`experiments.factory.check_agent_params`, which this module does not import so
that configs can be read without the simulation or the agent installed.
"""

from __future__ import annotations

import dataclasses
import re
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import tomli_w

from experiments import EXPERIMENT_DIR

AGENT_KINDS = ("tree", "grid")
MODES = ("kinematic", "dynamic")
_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.+-]*$")


class ConfigError(ValueError):
    """A bad experiment file or override; the message names the file and the key."""


@dataclass(frozen=True)
class EnvSpec:
    """Which environment every run of the experiment trains in."""

    id: str = "BulletMaze-v0"
    """Gymnasium id of the environment (registered by ``import bullet_maze``)."""
    maze: str = "paper"
    """Layout name from ``assets/mazes/`` or a path to a layout TOML file."""
    robot: str = "disc"
    """``"disc"``, ``"husky"`` or a path to a URDF file."""
    mode: str = "kinematic"
    """``"kinematic"`` (fast, exact steps) or ``"dynamic"`` (physics)."""
    max_episode_steps: int = 5000
    """Episode cap (section V: 5,000 steps)."""
    params: dict[str, Any] = field(default_factory=dict)
    """Extra keyword arguments for the environment's constructor."""


@dataclass(frozen=True)
class StrategySpec:
    """One compared learner: an agent kind with its exploration strategy and parameters."""

    name: str
    """Unique, file-name safe label; runs are named ``<name>__<seed>``."""
    agent: str = "tree"
    """``"tree"`` (the paper's adaptive tree, ``TreeAgent``) or ``"grid"`` (``GridAgent``)."""
    exploration: str = "adaptive+tabu"
    """Exploration strategy name understood by ``agent.make_exploration``."""
    exploration_params: dict[str, Any] = field(default_factory=dict)
    """Keyword arguments of the exploration strategy (for example ``epsilon``)."""
    config: dict[str, Any] = field(default_factory=dict)
    """Agent config fields for this strategy only, over the experiment's ``[agent]`` table."""
    resolution: int | tuple[int, ...] | None = None
    """Cells per dimension of the uniform grid (``agent = "grid"`` only)."""


@dataclass(frozen=True)
class ExperimentConfig:
    """A whole experiment: strategies x runs x episodes in one environment."""

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
    description: str = ""
    """Free text copied into the report."""
    source: str = ""
    """File the experiment was read from (filled in by :func:`load_config`)."""

    @property
    def baseline_name(self) -> str:
        """The baseline strategy's name (the first strategy when none is set)."""
        return self.baseline if self.baseline is not None else self.strategies[0].name

    def strategy(self, name: str) -> StrategySpec:
        """The strategy called ``name``."""
        for spec in self.strategies:
            if spec.name == name:
                return spec
        known = ", ".join(s.name for s in self.strategies)
        raise ConfigError(f"{self.source}: no strategy named {name!r} (known: {known})")

    def agent_params(self, spec: StrategySpec) -> dict[str, Any]:
        """Agent config fields of one strategy: the shared table overlaid with its own."""
        return {**self.agent, **spec.config}


def resolve_path(name_or_path: str | Path) -> Path:
    """The file of an experiment given as a path or as a name in ``experiments/``."""
    path = Path(name_or_path)
    if path.is_file():
        return path
    for candidate in (EXPERIMENT_DIR / path, EXPERIMENT_DIR / f"{path}.toml"):
        if candidate.is_file():
            return candidate
    known = ", ".join(sorted(p.stem for p in EXPERIMENT_DIR.glob("*.toml")))
    raise ConfigError(f"experiment file {str(name_or_path)!r} not found (shipped: {known})")


def load_config(name_or_path: str | Path) -> ExperimentConfig:
    """Read and validate an experiment file (a path, or a name from ``experiments/``)."""
    path = resolve_path(name_or_path)
    try:
        with path.open("rb") as handle:
            data = tomllib.load(handle)
    except tomllib.TOMLDecodeError as error:
        raise ConfigError(f"{path}: not valid TOML: {error}") from None
    return parse_config(data, source=str(path))


def parse_config(data: Mapping[str, Any], source: str = "<config>") -> ExperimentConfig:
    """Validate the parsed TOML ``data`` of an experiment; ``source`` names it in errors."""
    reader = _Reader(source)
    reader.only(data, "", {"experiment", "env", "agent", "strategy"})
    meta = reader.table(data, "experiment", required=True)
    reader.only(
        meta,
        "experiment",
        {f.name for f in dataclasses.fields(ExperimentConfig)}
        - {"strategies", "env", "agent", "source"},
    )
    env_table = reader.table(data, "env")
    reader.only(env_table, "env", {f.name for f in dataclasses.fields(EnvSpec)})
    env = EnvSpec(
        id=reader.value(env_table, "env", "id", str, EnvSpec.id),
        maze=reader.value(env_table, "env", "maze", str, EnvSpec.maze),
        robot=reader.value(env_table, "env", "robot", str, EnvSpec.robot),
        mode=reader.choice(env_table, "env", "mode", MODES, EnvSpec.mode),
        max_episode_steps=reader.positive(
            env_table, "env", "max_episode_steps", EnvSpec.max_episode_steps
        ),
        params=dict(reader.table(env_table, "env.params")),
    )
    agent = dict(reader.table(data, "agent"))
    raw_strategies = data.get("strategy")
    if not isinstance(raw_strategies, list) or not raw_strategies:
        raise ConfigError(f"{source}: [[strategy]]: at least one strategy table is required")
    strategies = tuple(reader.strategy(raw, i) for i, raw in enumerate(raw_strategies))
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
    tolerance = reader.value(meta, "experiment", "convergence_tolerance", (int, float), 0.1)
    if not 0 < tolerance < 1:
        raise ConfigError(
            f"{source}: [experiment] convergence_tolerance: must be in (0, 1), got {tolerance}"
        )
    budget = reader.value(meta, "experiment", "time_budget_s", (int, float), None)
    if budget is not None and budget <= 0:
        raise ConfigError(f"{source}: [experiment] time_budget_s: must be > 0, got {budget}")
    config = ExperimentConfig(
        name=reader.name(meta, "experiment", "name"),
        strategies=strategies,
        seed=reader.non_negative(meta, "experiment", "seed", 0),
        runs=reader.positive(meta, "experiment", "runs", 30),
        episodes=reader.positive(meta, "experiment", "episodes", 4000),
        env=env,
        agent=agent,
        baseline=baseline,
        smoothing_window=reader.positive(meta, "experiment", "smoothing_window", 50),
        final_window=reader.positive(meta, "experiment", "final_window", 100),
        convergence_tolerance=float(tolerance),
        time_budget_s=None if budget is None else float(budget),
        description=reader.value(meta, "experiment", "description", str, ""),
        source=source,
    )
    return config


def with_overrides(config: ExperimentConfig, **overrides: int | None) -> ExperimentConfig:
    """A copy with ``runs``/``episodes``/``seed``/``max_episode_steps`` replaced (None keeps)."""
    changes = {k: v for k, v in overrides.items() if v is not None}
    env_changes: dict[str, Any] = {}
    if "max_episode_steps" in changes:
        env_changes["max_episode_steps"] = changes.pop("max_episode_steps")
    for key, value in {**changes, **env_changes}.items():
        minimum = 0 if key == "seed" else 1
        if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
            raise ConfigError(
                f"option --{key.replace('_', '-')}: expected an integer >= {minimum}, got {value!r}"
            )
    unknown = set(changes) - {"runs", "episodes", "seed"}
    if unknown:
        raise ConfigError(f"unknown override(s): {', '.join(sorted(unknown))}")
    env = dataclasses.replace(config.env, **env_changes) if env_changes else config.env
    fields: dict[str, Any] = {"env": env, **changes}
    return dataclasses.replace(config, **fields)


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
    env = dataclasses.asdict(config.env)
    strategies = []
    for spec in config.strategies:
        table: dict[str, Any] = {
            "name": spec.name,
            "agent": spec.agent,
            "exploration": spec.exploration,
        }
        if spec.exploration_params:
            table["exploration_params"] = dict(spec.exploration_params)
        if spec.config:
            table["config"] = dict(spec.config)
        if spec.resolution is not None:
            table["resolution"] = (
                spec.resolution if isinstance(spec.resolution, int) else list(spec.resolution)
            )
        strategies.append(table)
    return {"experiment": meta, "env": env, "agent": dict(config.agent), "strategy": strategies}


def dumps(config: ExperimentConfig) -> str:
    """The resolved experiment as TOML text, loadable again with :func:`load_config`."""
    return tomli_w.dumps(to_dict(config))


def same_experiment(a: ExperimentConfig, b: ExperimentConfig) -> list[str]:
    """Keys whose values differ between two experiments, ignoring the number of runs.

    Runs may be added to a results folder (run i's seed does not depend on how many runs
    there are); anything else changes the results, so a folder must not mix them.
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
            differences += [
                f"{section}.{k}" for k in sorted(set(lv) | set(rv)) if lv.get(k) != rv.get(k)
            ]
        else:
            differences.append(section)
    return differences


class _Reader:
    """Typed access to parsed TOML with errors that name the file and the key."""

    def __init__(self, source: str) -> None:
        self.source = source

    def fail(self, where: str, key: str, message: str) -> ConfigError:
        prefix = f"[{where}] " if where else ""
        return ConfigError(f"{self.source}: {prefix}{key}: {message}")

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
        return value

    def positive(self, table: Mapping[str, Any], where: str, key: str, default: int) -> int:
        value = self.value(table, where, key, int, default)
        if value < 1:
            raise self.fail(where, key, f"must be a positive integer, got {value}")
        return value

    def non_negative(self, table: Mapping[str, Any], where: str, key: str, default: int) -> int:
        value = self.value(table, where, key, int, default)
        if value < 0:
            raise self.fail(where, key, f"must be >= 0, got {value}")
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
        if not _NAME.match(value):
            raise self.fail(
                where, key, f"{value!r} must be letters, digits and _ . + - only (it names files)"
            )
        return value

    def strategy(self, raw: Any, index: int) -> StrategySpec:
        where = f"strategy.{index}"
        if not isinstance(raw, dict):
            raise ConfigError(f"{self.source}: [[strategy]] #{index}: expected a table")
        self.only(raw, where, {f.name for f in dataclasses.fields(StrategySpec)})
        agent = self.choice(raw, where, "agent", AGENT_KINDS, "tree")
        resolution = raw.get("resolution")
        if agent == "grid":
            if resolution is None:
                raise self.fail(where, "resolution", 'is required when agent = "grid"')
            ok = (
                isinstance(resolution, int) and not isinstance(resolution, bool) and resolution > 0
            ) or (
                isinstance(resolution, list)
                and resolution
                and all(
                    isinstance(r, int) and not isinstance(r, bool) and r > 0 for r in resolution
                )
            )
            if not ok:
                raise self.fail(
                    where,
                    "resolution",
                    f"expected a positive integer or a list of them, got {resolution!r}",
                )
            if isinstance(resolution, list):
                resolution = tuple(resolution)
        elif resolution is not None:
            raise self.fail(where, "resolution", 'only applies to agent = "grid"')
        params = self.value(raw, where, "exploration_params", dict, {})
        config = self.value(raw, where, "config", dict, {})
        return StrategySpec(
            name=self.name(raw, where, "name"),
            agent=agent,
            exploration=self.value(raw, where, "exploration", str, "adaptive+tabu"),
            exploration_params=dict(params),
            config=dict(config),
            resolution=resolution,
        )


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
