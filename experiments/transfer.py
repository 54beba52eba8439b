"""The transfer matrix (issue 11): saved agents evaluated greedily in a grid of conditions, robots
x modes x layouts x perturbation levels, behind ``run.py transfer``.

Inputs are agents (an ``agent.npz``/``policy.npz``, a ``run.py train`` folder, or an experiment
folder whose runs saved their agents, ``[experiment] save_agents = true``) and conditions. An
agent trained on layout L is evaluated on L only (a layout of the grid that is not L does not
apply to it), in every robot, mode and level of the grid, and once in its own training
condition (level ``train``: its environment exactly as trained), the reference of its gap. A
level's settings are :func:`bullet_maze.perturbations.level_settings` for the cell's robot and
mode; the training environment's own perturbations are replaced by them, its other arguments
kept. A position-only policy on a robot that also observes its heading sees ``(x, y)`` only
(:func:`experiments.factory.fitted_to`, as ``run.py evaluate`` does). A condition the
agent cannot act in (a base of mass 0 in dynamic mode) is listed with the reason, not run.

Each cell (agent x condition) is ``episodes`` greedy episodes, the first reset seeded from the
agent's run seed and the condition (:func:`cell_seed`): the same whatever the backend, the
worker count or the order. Cells are stored as they finish, like experiment runs
(:mod:`experiments.store`): ``cells/<agent>/<robot>__<mode>__<level>.csv`` with a JSON sidecar
that records the CSV's size and SHA-256, the fingerprints of every input (the agent file's
SHA-256, environment, layout, robot, settings, code) and its own hash. Started again, finished
cells that verify are kept, damaged ones recomputed, and cells computed from other inputs (an
agent retrained, a robot file edited, other episodes) refused by name, never mixed.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import json
import re
import tomllib
from collections.abc import Callable, Collection, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from experiments import config as config_module
from experiments import factory, fingerprint, runner, store
from experiments.backends import Backend, SerialBackend
from experiments.config import MODES, ConfigError, EnvSpec
from experiments.lock import FolderBusyError, FolderLock
from experiments.transfer_cell import (
    Cell,
    CellResult,
    Condition,
    TransferAgent,
    cell_inputs,
    cell_seed,
    evaluate_cell,
    robot_label,
    safe_name,
)
from experiments.transfer_state import (
    TRAIN_LEVEL,
    CellCheck,
    Conditions,
    Skipped,
    TransferSpec,
    TransferState,
)

CELL_DIR = "cells"
SPEC_FILE = "transfer.toml"
SIDECAR_FORMAT = "bullet_maze.transfer_cell"
SIDECAR_VERSION = 1
MAX_AGENTS = 10_000
MAX_CONDITIONS = 1000
MAX_EPISODES = 100_000
_SAFE = re.compile(r"[^A-Za-z0-9_.+-]+")


def _levels() -> tuple[str, ...]:
    from bullet_maze.perturbations import LEVELS

    return tuple(LEVELS)


# --- the spec -----------------------------------------------------------------------------


def load_spec(path: str | Path) -> TransferSpec:
    """A transfer file (a path, or a name from ``experiments/``), checked strictly: every error
    names the file and the key."""
    file = config_module.resolve_path(path)
    try:
        raw = file.read_bytes()
    except OSError as error:
        raise ConfigError(f"{file}: cannot be read ({error.strerror or error})") from None
    if len(raw) > config_module.MAX_CONFIG_BYTES:
        raise ConfigError(f"{file}: {len(raw):,} bytes, at most {config_module.MAX_CONFIG_BYTES:,}")
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, tomllib.TOMLDecodeError) as error:
        raise ConfigError(f"{file}: not a valid TOML file ({error})") from None
    return parse_spec(data, str(file))


def parse_spec(data: Mapping[str, Any], source: str) -> TransferSpec:
    """Validate a parsed transfer file."""
    _only(data, source, "", {"transfer", "conditions"})
    meta = data.get("transfer")
    if not isinstance(meta, dict):
        raise ConfigError(f"{source}: [transfer]: this table is required")
    _only(meta, source, "transfer", {"name", "agents", "episodes", "max_episode_steps"})
    grid = data.get("conditions", {})
    if not isinstance(grid, dict):
        raise ConfigError(f"{source}: [conditions]: expected a table, got {grid!r}")
    _only(grid, source, "conditions", {"robots", "modes", "layouts", "levels"})
    name = meta.get("name", "transfer")
    if not isinstance(name, str) or not _SAFE.sub("", name) == name or not 0 < len(name) <= 100:
        raise ConfigError(
            f"{source}: [transfer] name: {str(name)[:100]!r} must be 1 to 100 letters, digits "
            "and _ . + - (it names the folder)"
        )
    agents = _names(meta.get("agents", []), f"{source}: [transfer] agents", allow_empty=True)
    return TransferSpec(
        name=name,
        agents=agents,
        conditions=check_conditions(
            _names(grid.get("robots", ["disc"]), f"{source}: [conditions] robots"),
            _names(grid.get("modes", ["dynamic"]), f"{source}: [conditions] modes"),
            _names(grid["layouts"], f"{source}: [conditions] layouts")
            if "layouts" in grid
            else None,
            _names(grid.get("levels", ["none"]), f"{source}: [conditions] levels"),
            where=f"{source}: [conditions]",
        ),
        episodes=_bounded(meta, "episodes", 10, 1, MAX_EPISODES, source),
        max_episode_steps=_bounded(
            meta, "max_episode_steps", None, 1, config_module.MAX_EPISODE_CAP, source
        ),
        source=source,
    )


def check_conditions(
    robots: Sequence[str],
    modes: Sequence[str],
    layouts: Sequence[str] | None,
    levels: Sequence[str],
    where: str,
    keys: Mapping[str, str] | None = None,
) -> Conditions:
    """The grid checked: every robot loads, every mode and level exists, every layout loads
    (``keys`` names each list's key or option in errors; default ``<where> robots`` etc.)."""
    named = dict(keys or {})

    def at(key: str) -> str:
        return named.get(key, f"{where} {key}")

    for robot in robots:
        try:
            fingerprint.robot_content(robot)
        except (TypeError, ValueError, OSError) as error:
            raise ConfigError(f"{at('robots')}: robot {robot!r}: {error}") from None
    for mode in modes:
        if mode not in MODES:
            raise ConfigError(f"{at('modes')}: unknown mode {mode!r}; the modes are {list(MODES)}")
    for level in levels:
        if level not in _levels():
            raise ConfigError(
                f"{at('levels')}: unknown perturbation level {level!r}; the levels are "
                f"{list(_levels())}"
            )
    for layout in layouts or ():
        try:
            fingerprint.layout_fingerprint(layout)
        except (TypeError, ValueError, OSError) as error:
            raise ConfigError(f"{at('layouts')}: layout {layout!r}: {error}") from None
    size = len(robots) * len(modes) * len(levels)
    if size > MAX_CONDITIONS:
        raise ConfigError(f"{where}: {size} conditions per agent, at most {MAX_CONDITIONS}")
    for key, items in (("robots", robots), ("modes", modes), ("levels", levels)):
        if len(set(items)) != len(items):
            raise ConfigError(f"{at(key)}: a name is given twice ({list(items)})")
    labels: dict[str, str] = {}
    for robot in robots:  # a cell and a report row are named by the robot's file stem
        label = robot_label(robot)
        if label in labels:
            raise ConfigError(
                f"{at('robots')}: robots {labels[label]!r} and {robot!r} would both be named "
                f"{label!r} in cell names and the report, and their cells would collide; give "
                "one of them a file of another name"
            )
        labels[label] = robot
    return Conditions(
        tuple(robots), tuple(modes), tuple(layouts) if layouts is not None else None, tuple(levels)
    )


def _only(table: Mapping[str, Any], source: str, where: str, allowed: set[str]) -> None:
    for key in table:
        if key not in allowed:
            inside = f"[{where}] " if where else ""
            raise ConfigError(
                f"{source}: {inside}{key}: unknown key (known: {', '.join(sorted(allowed))})"
            )


def _names(value: Any, where: str, allow_empty: bool = False) -> tuple[str, ...]:
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(item, str) for item in value):
        raise ConfigError(f"{where}: expected a list of names, got {str(value)[:200]}")
    if not value and not allow_empty:
        raise ConfigError(f"{where}: at least one name is required")
    for item in value:
        problem = config_module.text_problem(item)
        if problem or not item:
            raise ConfigError(f"{where}: {item[:100]!r}: {problem or 'empty'}")
    return tuple(value)


def _bounded(
    table: Mapping[str, Any], key: str, default: Any, low: int, high: int, source: str
) -> Any:
    if key not in table:
        return default
    value = table[key]
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise ConfigError(
            f"{source}: [transfer] {key}: expected an integer in [{low}, {high:,}], got {value!r}"
        )
    return value


def spec_to_toml(spec: TransferSpec) -> str:
    """The resolved spec as TOML (recorded in the folder)."""
    import tomli_w

    grid: dict[str, Any] = {
        "robots": list(spec.conditions.robots),
        "modes": list(spec.conditions.modes),
        "levels": list(spec.conditions.levels),
    }
    if spec.conditions.layouts is not None:
        grid["layouts"] = list(spec.conditions.layouts)
    meta: dict[str, Any] = {
        "name": spec.name,
        "agents": list(spec.agents),
        "episodes": spec.episodes,
    }
    if spec.max_episode_steps is not None:
        meta["max_episode_steps"] = spec.max_episode_steps
    return tomli_w.dumps({"transfer": meta, "conditions": grid})


# --- the agents ---------------------------------------------------------------------------


def find_agents(
    sources: Sequence[str | Path],
    allowed_env_ids: Collection[str] = (),
    accept_code_change: bool = False,
) -> list[TransferAgent]:
    """Every agent that ``sources`` name, in order (``ConfigError`` naming a source that holds
    none, or an agent whose training condition is unknown)."""
    if not sources:
        raise ConfigError(
            "no agents given: name agent files or folders (--agents or [transfer] agents)"
        )
    agents: list[TransferAgent] = []
    cache: dict[Path, list[TransferAgent]] = {}
    for source in sources:
        config_module.check_option_text(str(source), "agents")
        paths = [Path(source)]
        if any(mark in str(source) for mark in "*?["):
            pattern = Path(source)
            anchor = Path(pattern.anchor) if pattern.is_absolute() else Path()
            paths = sorted(anchor.glob(str(pattern.relative_to(anchor))))
            if not paths:
                raise ConfigError(f"agents: {source!r} matches no file or folder")
        for path in paths:
            agents += _agents_of(path, allowed_env_ids, accept_code_change, cache)
    keys = [a.key for a in agents]
    for key in keys:
        if keys.count(key) > 1:
            raise ConfigError(f"agent {key!r} is given twice (the sources overlap)")
    if len(agents) > MAX_AGENTS:
        raise ConfigError(f"{len(agents)} agents, at most {MAX_AGENTS}")
    return agents


def _agents_of(
    path: Path,
    allowed: Collection[str],
    accept_code_change: bool,
    cache: dict[Path, list[TransferAgent]],
) -> list[TransferAgent]:
    if path.is_dir() and (path / runner.RUN_DIR).is_dir() and (path / runner.CONFIG_FILE).is_file():
        return _experiment_agents(path, allowed, accept_code_change, cache)
    if path.is_dir():
        for name in ("agent.npz", "policy.npz"):
            if (path / name).is_file():
                return [_train_agent(path / name, allowed)]
        raise ConfigError(
            f"{path}: neither an experiment folder (config.toml and runs/) nor a train folder "
            "(agent.npz or policy.npz)"
        )
    if not path.is_file():
        raise ConfigError(f"agent source not found: {path}")
    if path.name.endswith(".agent.npz"):
        root = next((p for p in path.parents if (p / runner.CONFIG_FILE).is_file()), None)
        if root is not None and (root / runner.RUN_DIR).is_dir():
            name = str(path.relative_to(root / runner.RUN_DIR))[: -len(".agent.npz")]
            found = [
                a
                for a in _experiment_agents(root, allowed, accept_code_change, cache)
                if a.path == path
            ]
            if not found:
                raise ConfigError(
                    f"{path}: run {name} of {root} is not finished or does not verify"
                )
            return found
    return [_train_agent(path, allowed)]


def _train_agent(path: Path, allowed: Collection[str]) -> TransferAgent:
    folder = path.parent
    config_file, meta_file = folder / runner.CONFIG_FILE, folder / "meta.json"
    if not config_file.is_file() or not meta_file.is_file():
        raise ConfigError(
            f"{path}: cannot tell what it was trained in: no config.toml and meta.json beside it "
            "(a run.py train folder has both)"
        )
    config = config_module.load_config(config_file, allowed).single_task()
    try:
        seed = json.loads(meta_file.read_text(encoding="utf-8"))["seed"]
    except (OSError, ValueError, KeyError, TypeError) as error:
        raise ConfigError(f"{meta_file}: no run seed ({error})") from None
    if isinstance(seed, bool) or not isinstance(seed, int) or not 0 <= seed <= 2**32 - 1:
        raise ConfigError(f"{meta_file}: seed {seed!r} is not a run seed")
    return _agent(_safe(folder.name), path, config.env, seed, config.strategies[0].name)


def _experiment_agents(
    folder: Path,
    allowed: Collection[str],
    accept_code_change: bool,
    cache: dict[Path, list[TransferAgent]],
) -> list[TransferAgent]:
    if folder.resolve() not in cache:
        cache[folder.resolve()] = _read_experiment_agents(folder, allowed, accept_code_change)
    return cache[folder.resolve()]


def _read_experiment_agents(
    folder: Path, allowed: Collection[str], accept_code_change: bool
) -> list[TransferAgent]:
    config = config_module.load_config(folder / runner.CONFIG_FILE, allowed)
    if not config.save_agents:
        raise ConfigError(
            f"{folder}: its runs did not save their agents; set [experiment] save_agents = true "
            "in the experiment file and run it again"
        )
    state = runner.inspect_folder(config, folder, accept_code_change=accept_code_change)
    if not state.finished:
        statuses = [check.status for check in state.checks.values()]
        why = {
            "code": "computed by another code version (--accept-code-change counts them)",
            "changed": "computed from other inputs",
            "invalid": "whose files do not verify",
            "missing": "not run yet",
        }
        counts = ", ".join(
            f"{statuses.count(status)} {text}" for status, text in why.items() if status in statuses
        )
        raise ConfigError(
            f"{folder}: no finished run that verifies (nothing to evaluate)"
            + (f"; its runs: {counts}" if counts else "")
        )
    agents = []
    for spec, check in state.finished:
        assert check.data is not None
        path = store.agent_path(folder / runner.RUN_DIR, spec.name)
        key = "__".join(part for part in (config.name, spec.task, spec.strategy.name) if part)
        agents.append(
            _agent(_safe(f"{key}__{spec.seed}"), path, spec.env, spec.seed, spec.strategy.name)
        )
    return agents


def _agent(key: str, path: Path, env: EnvSpec, seed: int, strategy: str) -> TransferAgent:
    if not env.is_maze:
        raise ConfigError(f"{path}: trained in {env.id!r}; transfer evaluates maze agents only")
    try:
        digest = hashlib.sha256(path.read_bytes()).hexdigest()
        layout = fingerprint.layout_fingerprint(env.maze)
        saved = factory.load_agent(path)
    except (OSError, TypeError, ValueError) as error:
        raise ConfigError(f"cannot load the agent: {error}") from None
    return TransferAgent(
        key,
        path,
        digest,
        env,
        seed,
        training_group(strategy, env),
        layout,
        int(saved.observation_space.shape[0]),
        int(saved.n_actions),
    )


def training_group(strategy: str, env: EnvSpec) -> str:
    """The training recipe of an agent: strategy, robot, mode, and ``randomised`` (a range
    among its perturbations) or ``perturbed`` (fixed ones)."""
    from bullet_maze.perturbations import NAMES, Range, parse_setting

    settings = {k: v for k, v in env.params.items() if k in NAMES}
    kind = ""
    if settings:
        ranged = any(isinstance(parse_setting(k, v), Range) for k, v in settings.items())
        kind = " randomised" if ranged else " perturbed"
    return f"{strategy} {Path(str(env.robot)).stem} {env.mode}{kind}"


def _safe(text: str) -> str:
    return safe_name(text)


# --- the cells ----------------------------------------------------------------------------


def condition_env(agent: TransferAgent, condition: Condition, cap: int | None) -> EnvSpec:
    """The environment of a cell: the agent's training environment with the condition's robot
    and mode, its perturbations replaced by the level's (``train``: as trained)."""
    from bullet_maze.perturbations import NAMES, level_settings

    env = agent.env
    cap = cap if cap is not None else env.max_episode_steps
    if condition.level == TRAIN_LEVEL:
        return dataclasses.replace(env, max_episode_steps=cap)
    params = {k: v for k, v in env.params.items() if k not in NAMES}
    observation = str(params.get("observation", "pose"))
    settings = level_settings(
        condition.level,
        mode=condition.mode,
        drive=_drive_of(str(condition.robot)),
        lidar=observation.endswith("lidar"),
        revert_on_collision=bool(params.get("revert_on_collision", True)),
    )
    params.update({k: list(v) if isinstance(v, tuple) else v for k, v in settings.items()})
    return dataclasses.replace(
        env, robot=condition.robot, mode=condition.mode, params=params, max_episode_steps=cap
    )


def _drive_of(robot: str) -> str:
    """The drive the perturbation levels depend on (a bare URDF's detected as the env does,
    once per version of the file)."""
    path = Path(robot)
    stamp = path.stat().st_mtime_ns if robot.endswith(".urdf") and path.is_file() else None
    return _detected_drive(robot, stamp)


@functools.cache
def _detected_drive(robot: str, stamp: int | None) -> str:
    from bullet_maze.robots import robot_drive

    return robot_drive(robot)


def plan_cells(
    spec: TransferSpec, agents: Sequence[TransferAgent]
) -> tuple[list[Cell], list[Skipped]]:
    """Every cell of the grid that applies, in a fixed order (agent, robot, mode, level; the
    training condition first), and the conditions that do not, with the reason."""
    grid = spec.conditions
    layouts = (
        None
        if grid.layouts is None
        else {fingerprint.layout_fingerprint(name) for name in grid.layouts}
    )
    cells: list[Cell] = []
    skipped: list[Skipped] = []
    reasons: dict[tuple[str, ...], str | None] = {}
    for agent in agents:
        if layouts is not None and agent.layout not in layouts:
            continue
        own = Condition(str(agent.env.robot), str(agent.env.mode), TRAIN_LEVEL)
        conditions = [own] + [
            Condition(robot, mode, level)
            for robot in grid.robots
            for mode in grid.modes
            for level in grid.levels
        ]
        for condition in conditions:
            env = condition_env(agent, condition, spec.max_episode_steps)
            key = (repr(env), str(agent.observation_dims), str(agent.n_actions))
            if key not in reasons:
                reasons[key] = _applies(agent, env)
            reason = reasons[key]
            if reason is not None:
                skipped.append(Skipped(agent, condition, reason))
                continue
            seed = cell_seed(agent.seed, condition, agent.layout)
            cells.append(Cell(agent, condition, env, spec.episodes, seed))
    return cells, skipped


def _applies(agent: TransferAgent, spec: EnvSpec) -> str | None:
    """None if the agent can act in the environment; else why not."""
    try:
        env = factory.make_env(spec)
    except (TypeError, ValueError) as error:
        return str(error)
    try:
        actions = getattr(env.action_space, "n", None)
        if actions != agent.n_actions:
            return f"the agent has {agent.n_actions} actions; this condition gives {actions}"
        factory.fitted_to(env, agent.observation_dims)
        return None
    except ValueError as error:
        return str(error)
    finally:
        env.close()


# --- storing and checking cells -----------------------------------------------------------


def cell_paths(out: Path, name: str) -> tuple[Path, Path]:
    """The CSV and the sidecar of cell ``name``."""
    return out / CELL_DIR / f"{name}.csv", out / CELL_DIR / f"{name}.json"


def write_cell(out: Path, result: CellResult, inputs: Mapping[str, Any]) -> None:
    """Store a finished cell: its CSV, then the sidecar that vouches for it."""
    csv_path, meta_path = cell_paths(out, result.name)
    text = store.format_rows(result.rows, store.EVAL_COLUMNS)
    data = text.encode("utf-8")
    meta: dict[str, Any] = {
        "format": SIDECAR_FORMAT,
        "version": SIDECAR_VERSION,
        "name": result.name,
        "episodes": len(result.rows),
        "optimal_steps": result.optimal_steps,
        "wall_time_s": result.wall_time_s,
        "env_steps": result.env_steps,
        "projected": result.projected,
        "tipped": result.tipped,
        "data_sha256": hashlib.sha256(data).hexdigest(),
        "data_bytes": len(data),
        "inputs": dict(inputs),
    }
    meta["sidecar_sha256"] = fingerprint.digest(meta)
    with store.deferred_interrupt():  # both files, or a Ctrl-C after them
        store.atomic_write_text(csv_path, text)
        store.atomic_write_text(meta_path, json.dumps(meta, indent=2, sort_keys=True) + "\n")


def check_cell(out: Path, cell: Cell, expected: Mapping[str, Any]) -> CellCheck:
    """Verify a stored cell against its sidecar and the inputs it should have."""
    csv_path, meta_path = cell_paths(out, cell.name)
    if not csv_path.exists() and not meta_path.exists():
        return CellCheck("missing")
    try:
        meta, columns = _read_cell(csv_path, meta_path, cell)
    except ValueError as error:
        return CellCheck("invalid", str(error))
    found = input_differences(meta["inputs"], expected)
    if not found:
        return CellCheck("valid", columns=columns, meta=meta)
    status = "code" if all(item.startswith("code") for item in found) else "changed"
    return CellCheck(status, f"other inputs ({', '.join(found)})", columns, meta)


def input_differences(recorded: Mapping[str, Any], expected: Mapping[str, Any]) -> list[str]:
    """The inputs that differ (the standard ones of :mod:`experiments.fingerprint`, and the
    agent file)."""
    found = fingerprint.differences(recorded, expected)
    if recorded.get("agent") != expected.get("agent"):
        found.insert(0, "agent")
    return found


def _read_cell(
    csv_path: Path, meta_path: Path, cell: Cell
) -> tuple[dict[str, Any], dict[str, np.ndarray]]:
    if not meta_path.is_file():
        raise ValueError(f"{meta_path}: missing (a cell is finished only with its sidecar)")
    if meta_path.stat().st_size > store.MAX_SIDECAR_BYTES:
        raise ValueError(f"{meta_path}: larger than {store.MAX_SIDECAR_BYTES:,} bytes")
    try:
        meta = json.loads(meta_path.read_bytes().decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError) as error:
        raise ValueError(f"{meta_path}: not valid JSON ({error})") from None
    if not isinstance(meta, dict) or meta.get("format") != SIDECAR_FORMAT:
        raise ValueError(f"{meta_path}: not a transfer cell sidecar")
    if meta.get("version") != SIDECAR_VERSION:
        raise ValueError(f"{meta_path}: version {meta.get('version')!r}, not {SIDECAR_VERSION}")
    recorded = meta.pop("sidecar_sha256", None)
    if recorded != fingerprint.digest(meta):
        raise ValueError(f"{meta_path}: differs from its own recorded hash (edited or damaged)")
    if meta.get("name") != cell.name:
        raise ValueError(f"{meta_path}: names cell {meta.get('name')!r}, not {cell.name!r}")
    episodes = meta.get("episodes")
    if isinstance(episodes, bool) or not isinstance(episodes, int) or episodes < 1:
        raise ValueError(f"{meta_path}: episodes is {episodes!r}")
    if not isinstance(meta.get("inputs"), dict):
        raise ValueError(f"{meta_path}: no input fingerprints")
    optimal = meta.get("optimal_steps")
    if isinstance(optimal, bool) or not isinstance(optimal, int | float):
        raise ValueError(f"{meta_path}: optimal_steps is {optimal!r}")
    tipped = meta.get("tipped", 0)  # absent in cells stored before falls were counted
    if isinstance(tipped, bool) or not isinstance(tipped, int) or not 0 <= tipped <= episodes:
        raise ValueError(f"{meta_path}: tipped is {tipped!r} of {episodes} episodes")
    if not csv_path.is_file():
        raise ValueError(f"{csv_path}: missing (its sidecar exists)")
    size = csv_path.stat().st_size
    if size != meta.get("data_bytes") or size > store.MAX_ROW_BYTES * (episodes + 1):
        raise ValueError(f"{csv_path}: differs from its sidecar ({size} bytes; edited or cut)")
    raw = csv_path.read_bytes()
    if hashlib.sha256(raw).hexdigest() != meta.get("data_sha256"):
        raise ValueError(f"{csv_path}: differs from its sidecar (SHA-256 mismatch)")
    recorded_env = meta["inputs"].get("config", {}).get("env", {})
    cap = recorded_env.get("max_episode_steps") if isinstance(recorded_env, dict) else None
    if isinstance(cap, bool) or not isinstance(cap, int) or cap < 1:
        raise ValueError(f"{meta_path}: records no episode cap")
    columns = store.parse_rows(raw, str(csv_path), cap, store.EVAL_COLUMNS)
    if len(columns["steps"]) != episodes:
        raise ValueError(f"{csv_path}: {len(columns['steps'])} rows, its sidecar says {episodes}")
    return meta, columns


# --- the job ------------------------------------------------------------------------------


class _Expected:
    """The expected inputs of each cell; each environment fingerprinted once."""

    def __init__(self) -> None:
        self._env: dict[str, dict[str, str | None]] = {}

    def __call__(self, cell: Cell) -> dict[str, Any]:
        key = repr(cell.env)
        if key not in self._env:
            self._env[key] = fingerprint.env_inputs(cell.env)
        return cell_inputs(cell, self._env[key])


class Transfer:
    """The transfer job: ``status()``, ``run(backend)``, ``report()``; ``run.py transfer`` only
    fills it from the command line and prints from it."""

    def __init__(
        self,
        spec: TransferSpec,
        out: Path,
        allowed_env_ids: Collection[str] = (),
        accept_code_change: bool = False,
    ) -> None:
        runner.check_out_dir(out)
        self.spec = spec
        self.out = out
        self.accept_code_change = accept_code_change
        self.agents = find_agents(spec.agents, allowed_env_ids, accept_code_change)
        self.cells, self.skipped = plan_cells(spec, self.agents)
        if not self.cells:
            raise ConfigError(
                f"{spec.source}: no condition applies to any of the {len(self.agents)} agents "
                "(their layouts are not in [conditions] layouts, or they cannot act there)"
            )

    @classmethod
    def from_options(
        cls,
        config: str | Path | None = None,
        agents: Sequence[str] | None = None,
        robots: Sequence[str] | None = None,
        modes: Sequence[str] | None = None,
        layouts: Sequence[str] | None = None,
        levels: Sequence[str] | None = None,
        episodes: int | None = None,
        max_episode_steps: int | None = None,
        out: Path | None = None,
        allowed_env_ids: Collection[str] = (),
        accept_code_change: bool = False,
        results_dir: Path = Path("results"),
    ) -> Transfer:
        """A transfer file (optional) with the options over it."""
        if config is not None:
            config_module.check_option_text(str(config), "CONFIG")
            try:
                spec = load_spec(config)
            except ConfigError as error:
                if not config_module.resolve_path(config).is_file():
                    raise ConfigError(f"argument CONFIG: {error}") from None
                raise
        else:
            spec = TransferSpec("transfer", (), Conditions(), source="<options>")
        given = {
            "robots": robots,
            "modes": modes,
            "layouts": layouts,
            "levels": levels,
        }
        grid = spec.conditions
        merged = {
            key: tuple(value) if value is not None else getattr(grid, key)
            for key, value in given.items()
        }
        options = {key: f"option --{key}" for key, value in given.items() if value is not None}
        conditions = check_conditions(
            merged["robots"],
            merged["modes"],
            merged["layouts"],
            merged["levels"],
            where=f"{spec.source}: [conditions]",
            keys=options,
        )
        for key, value in (("episodes", episodes), ("max-episode-steps", max_episode_steps)):
            high = MAX_EPISODES if key == "episodes" else config_module.MAX_EPISODE_CAP
            if value is not None and not 1 <= value <= high:
                raise ConfigError(f"option --{key}: expected 1 to {high:,}, got {value}")
        spec = dataclasses.replace(
            spec,
            agents=tuple(agents) if agents else spec.agents,
            conditions=conditions,
            episodes=episodes if episodes is not None else spec.episodes,
            max_episode_steps=max_episode_steps
            if max_episode_steps is not None
            else spec.max_episode_steps,
        )
        if out is not None:
            config_module.check_option_text(str(out), "--out")
        return cls(spec, out or results_dir / spec.name, allowed_env_ids, accept_code_change)

    def status(self) -> TransferState:
        """Every planned cell verified against the folder (reads only)."""
        expected = _Expected()
        checks = {c.name: check_cell(self.out, c, expected(c)) for c in self.cells}
        return TransferState(
            tuple(self.cells), checks, tuple(self.skipped), self.accept_code_change
        )

    def run(
        self,
        backend: Backend | None = None,
        on_start: Callable[[TransferState], None] | None = None,
        on_result: Callable[[CellResult], None] | None = None,
    ) -> list[CellResult]:
        """Compute the pending cells (locked; refusing to mix inputs); returns those computed
        now."""
        backend = backend or SerialBackend()
        try:
            self.out.mkdir(parents=True, exist_ok=True)
        except OSError as error:
            raise ConfigError(
                f"option --out: cannot create {self.out} ({error.strerror})"
            ) from None
        try:
            with FolderLock(self.out):
                return self._run_locked(backend, on_start, on_result)
        except FolderBusyError as error:
            raise ConfigError(str(error)) from None

    def _run_locked(
        self,
        backend: Backend,
        on_start: Callable[[TransferState], None] | None,
        on_result: Callable[[CellResult], None] | None,
    ) -> list[CellResult]:
        store.remove_stale_temporaries(self.out / CELL_DIR, nested=True)
        store.atomic_write_text(self.out / SPEC_FILE, spec_to_toml(self.spec))
        state = self.status()
        refuse_mixing(state, self.out)
        for cell in state.pending:
            for path in cell_paths(self.out, cell.name):
                path.unlink(missing_ok=True)
        if on_start is not None:
            on_start(state)
        expected = _Expected()
        by_name = {cell.name: cell for cell in state.pending}
        computed = []
        for result in backend.map_unordered(evaluate_cell, state.pending):
            wanted = expected(by_name[result.name])
            found = input_differences(fingerprint.normalized(result.inputs), wanted)
            if found:
                raise ConfigError(
                    f"cell {result.name}: its inputs changed while the transfer ran "
                    f"({', '.join(found)}); it was not stored. Finished cells are kept."
                )
            write_cell(self.out, result, fingerprint.normalized(result.inputs))
            computed.append(result)
            if on_result is not None:
                on_result(result)
        return computed

    def report(self, traces: int = 0) -> Any:
        """Write the report of the finished cells (``ConfigError`` if none); with ``traces``,
        also ``failures.png``: that many failing episodes replayed and drawn (the first of
        each recipe and robot in dynamic mode at the moderate level, else at the strong one)."""
        from experiments.transfer_report import write_transfer_report

        state = self.status()
        refuse_mixing(state, self.out)
        if not state.finished:
            raise ConfigError(f"{self.out}: no finished cell (run the transfer first)")
        failures = None
        if traces:
            from experiments.transfer_traces import draw_failures, failing_cells

            picks = failing_cells(state, limit=traces)
            if picks:
                failures = draw_failures(picks, self.out / "failures.png", state)
        return write_transfer_report(self.spec, self.agents, self.out, state, failures)


def refuse_mixing(state: TransferState, out: Path) -> None:
    """``ConfigError`` naming the cells computed from other inputs."""
    refused = state.refused
    if not refused:
        return
    lines = [f"  {c.name}: {state.checks[c.name].reason}" for c in refused[:20]]
    if len(refused) > 20:
        lines.append(f"  ... and {len(refused) - 20} more")
    only_code = all(state.checks[c.name].status == "code" for c in refused)
    advice = (
        "accept them with --accept-code-change if the change cannot alter results, or "
        "compute into another --out"
        if only_code
        else "compute into another --out, or delete those cells to recompute them"
    )
    raise ConfigError(
        f"{out}: {len(refused)} finished cell(s) were computed from other inputs than this "
        "transfer's; they are not mixed with new ones:\n" + "\n".join(lines) + f"\n{advice}"
    )
