"""Fingerprints of everything a run's numbers depend on, recorded beside them and checked.

A run is a function of its inputs: the layout, the robot, the environment's registration and
arguments, the resolved configuration (every agent field and strategy parameter with its
default filled in, the episodes, the seed) and the code that computes it. Each gets a
fingerprint here, through one function each:

- :func:`layout_fingerprint`: the layout's canonical content, loaded with
  ``bullet_maze.load_layout`` (so named, generated and file layouts all work), not the file's
  bytes: a comment edited in the file leaves it unchanged, a moved goal changes it;
- :func:`robot_fingerprint`: the robot file's validated fields, its URDF's bytes and those of
  the meshes it loads from outside ``pybullet_data``;
- :func:`env_fingerprint`: the id's entry point, registered arguments and every constructor
  argument with its default;
- :func:`resolved_config`: the run's settings with every default filled in, so that a changed
  default shows as a changed setting, not only as changed code;
- :func:`code_fingerprint`: the source of the modules that compute a run (``agent``,
  ``bullet_maze``, the harness's training path and the task's own module) as Python syntax
  trees with docstrings dropped, plus the Python minor version and the versions of numpy,
  scipy, gymnasium and pybullet. A docstring, comment or formatting change leaves it unchanged;
  any change to a statement changes it (``docs/experiments.md`` explains the rule).
"""

from __future__ import annotations

import ast
import dataclasses
import hashlib
import importlib.metadata
import inspect
import json
import sys
from collections.abc import Callable, Mapping
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from experiments.config import EnvSpec, ExperimentConfig, StrategySpec

ROOT = Path(__file__).resolve().parent.parent

RESULT_SOURCES = (
    "agent",
    "bullet_maze",
    "experiments/training.py",
    "experiments/factory.py",
    "experiments/agent_kinds.py",
    "experiments/seeding.py",
    "experiments/evaluation.py",
)
"""What computes a run's numbers (folders are taken whole), relative to the project root."""

LIBRARIES = ("numpy", "scipy", "gymnasium", "pybullet")
"""Installed packages whose versions are part of the code fingerprint."""

LAYOUT_IGNORED = ("name", "description", "source")
"""Layout fields that do not change a run (labels and where it was read from)."""


def digest(data: Any) -> str:
    """SHA-256 of the canonical JSON of ``data`` (sorted keys, exact floats)."""
    text = json.dumps(data, sort_keys=True, separators=(",", ":"), default=repr)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def layout_content(layout: Any) -> dict[str, Any]:
    """A ``MazeLayout``'s fields that matter to a run, as plain data."""
    data = dataclasses.asdict(layout)
    return {key: value for key, value in data.items() if key not in LAYOUT_IGNORED}


def layout_fingerprint(maze: Any) -> str:
    """Fingerprint of a layout (a name, a path, any spelling ``load_layout`` accepts, or a
    ``MazeLayout``); raises what ``load_layout`` raises for a bad one."""
    from bullet_maze import load_layout

    return digest(layout_content(load_layout(maze)))


def robot_content(robot: str) -> dict[str, Any]:
    """A robot's description as plain data: its robot file's validated fields (a built-in name,
    a ``.toml`` file or a bare URDF, through ``bullet_maze.robots.resolve_robot``) with the URDF
    given by the SHA-256 of its bytes instead of its path; raises what ``resolve_robot`` raises
    for a bad one, and ``FileNotFoundError`` for a missing URDF."""
    from bullet_maze.robots import resolve_robot

    spec = resolve_robot(robot)
    urdf = Path(spec.urdf)
    if not urdf.is_file():
        raise FileNotFoundError(f"robot file not found: {urdf}")
    data = dataclasses.asdict(spec)
    data.pop("source", None)
    data["urdf"] = hashlib.sha256(urdf.read_bytes()).hexdigest()
    meshes = _own_meshes(urdf)
    if meshes:  # (absent where there are none, so such robots' fingerprints are as before)
        data["meshes"] = meshes
    return data


def _own_meshes(urdf: Path) -> dict[str, str]:
    """The SHA-256 of each mesh file the URDF loads (collision shapes change the physics),
    keyed by its name as written, so that moving the folder changes nothing. Meshes shipped
    in ``pybullet_data`` are left out: they change only with pybullet itself, and the built-in
    husky's and racecar's fingerprints stay those of the results already stored."""
    import pybullet_data

    from bullet_maze.robots.urdf import read_urdf

    shipped = Path(pybullet_data.getDataPath()).resolve()
    return {
        name: hashlib.sha256(path.read_bytes()).hexdigest()
        for name, path in read_urdf(urdf).meshes
        if not path.resolve().is_relative_to(shipped)
    }


def robot_fingerprint(robot: str) -> str:
    """Fingerprint of the robot: its file's fields, its URDF's bytes and its own meshes'
    (:func:`robot_content`)."""
    return digest(robot_content(robot))


def env_fingerprint(spec: EnvSpec) -> str:
    """Fingerprint of the environment's registration and constructor arguments (defaults in)."""
    from gymnasium.envs.registration import load_env_creator, registry

    registered = registry[spec.id]
    entry = registered.entry_point
    defaults: dict[str, Any] = {}
    if isinstance(entry, str):
        creator = load_env_creator(entry)
        defaults = {
            name: p.default
            for name, p in inspect.signature(creator).parameters.items()
            if p.default is not inspect.Parameter.empty and name != "render_mode"
        }
    arguments = {**defaults, **registered.kwargs, **spec.make_kwargs()}
    arguments.pop("max_episode_steps", None)
    fields: dict[str, Any] = {
        "id": spec.id,
        "entry_point": entry if isinstance(entry, str) else repr(entry),
        "max_episode_steps": spec.max_episode_steps,
        "arguments": arguments,
    }
    module = entry.split(":")[0] if isinstance(entry, str) else getattr(entry, "__module__", "")
    package = str(module).split(".")[0]
    if package not in OWN_PACKAGES:  # a user's env: its code is an input of the run
        fields["source"] = package_fingerprint(package)
    engines = {
        engine: _version(engine)
        for prefix, engine in ENGINES.items()
        if str(module).startswith(prefix)
    }
    if engines:  # (absent for every other env, whose fingerprint stays as it was)
        fields["engines"] = engines
    return digest(fields)


OWN_PACKAGES = frozenset({"gymnasium", "bullet_maze"})
"""Packages whose envs' code the code fingerprint already covers (``bullet_maze``'s sources,
Gymnasium's version); any other env's package is fingerprinted with the env."""

ENGINES = {"gymnasium.envs.mujoco": "mujoco", "gymnasium.envs.box2d": "box2d"}
"""Gymnasium's env modules that step another physics engine, and its package: the engine's
version is an input of their runs (an upgraded MuJoCo is other physics), while Gymnasium's own
version is in the code fingerprint."""


def _version(package: str) -> str:
    try:
        return importlib.metadata.version(package)
    except importlib.metadata.PackageNotFoundError:
        return "not installed"


MAX_PACKAGE_FILES = 2000
"""The most Python files of a user's env package that are read for its fingerprint."""


@cache
def package_fingerprint(package: str) -> str:
    """The source fingerprint of the top-level package (every ``.py`` below its folders, a
    namespace package's too, sorted, at most :data:`MAX_PACKAGE_FILES`) or the single module
    that defines a user's env, so that a change to the env's code changes its runs' inputs
    (``run.py --env-module``). A module without a source file (built in, compiled) is named
    instead."""
    loaded = sys.modules.get(package)
    if loaded is None:
        try:
            loaded = importlib.import_module(package)
        except Exception:
            return f"unreadable: {package}"
    file = getattr(loaded, "__file__", None)
    if hasattr(loaded, "__path__"):  # a package, also a namespace package (which has no file)
        roots = sorted({Path(p).resolve() for p in loaded.__path__})
        files = sorted({f for root in roots for f in root.rglob("*.py")})
    elif file and file.endswith(".py"):
        roots, files = [Path(file).resolve().parent], [Path(file).resolve()]
    else:
        return f"no source: {package}"
    sources = {}
    for source in files[:MAX_PACKAGE_FILES]:
        root = next(r for r in roots if source.is_relative_to(r))
        name = f"{root.name}/{source.relative_to(root)}"
        try:
            sources[name] = source_fingerprint(source)
        except (OSError, SyntaxError, ValueError):
            sources[name] = "unreadable"
    return digest(sources)


def resolved_config(
    experiment: ExperimentConfig, strategy: StrategySpec, env: EnvSpec, seed: int
) -> dict[str, Any]:
    """Every setting of one run, defaults filled in (``TreeConfig`` and the strategy's)."""
    from agent import TreeConfig
    from agent.exploration import exploration_spec, make_exploration
    from experiments.agent_kinds import is_fixed, resolved_agent_params

    if is_fixed(strategy.agent):  # a baseline with its own rule: its arguments, in full
        return _with_evaluation(
            experiment,
            {
                "episodes": experiment.episodes,
                "seed": seed,
                "env": _env_settings(env),
                "agent": strategy.agent,
                "agent_params": resolved_agent_params(strategy.agent, strategy.agent_params),
            },
        )
    config = TreeConfig(**experiment.agent_params(strategy)).to_dict()
    params = exploration_spec(make_exploration(strategy.exploration, **strategy.exploration_params))
    settings = {
        "episodes": experiment.episodes,
        "seed": seed,
        "env": _env_settings(env),
        "agent": strategy.agent,
        "resolution": strategy.resolution,
        "exploration": strategy.exploration,
        "exploration_params": params["params"],
        "agent_config": config,
    }
    return _with_evaluation(experiment, settings)


def _env_settings(env: EnvSpec) -> dict[str, Any]:
    settings = dataclasses.asdict(env)
    for key in ("observation_bounds", "action_bins"):  # settings added later appear only
        if settings.get(key) is None:  # when set: earlier runs keep their fingerprint
            settings.pop(key, None)
    return settings


def _with_evaluation(experiment: ExperimentConfig, settings: dict[str, Any]) -> dict[str, Any]:
    if experiment.eval_episodes:
        settings["eval_episodes"] = experiment.eval_episodes
    if experiment.save_agents:
        settings["save_agents"] = True
    return settings


def _strip_docstrings(tree: ast.AST) -> ast.AST:
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if isinstance(body, list):
            kept = [
                statement
                for statement in body
                if not (
                    isinstance(statement, ast.Expr)
                    and isinstance(statement.value, ast.Constant)
                    and isinstance(statement.value.value, str)
                )
            ]
            node.body = kept or [ast.Pass()]  # type: ignore[attr-defined]
    return tree


def source_fingerprint(path: Path) -> str:
    """SHA-256 of a Python file's syntax tree without docstrings (comments and layout are not
    in the tree)."""
    tree = _strip_docstrings(ast.parse(path.read_bytes(), filename=str(path)))
    return hashlib.sha256(ast.dump(tree).encode("utf-8")).hexdigest()


def _source_files(extra: tuple[str, ...]) -> list[Path]:
    files: set[Path] = set()
    for entry in RESULT_SOURCES:
        path = ROOT / entry
        files |= set(path.rglob("*.py")) if path.is_dir() else {path}
    for module_file in extra:
        files.add(Path(module_file).resolve())
    return sorted(files)


@cache
def _code_fingerprint(extra: tuple[str, ...]) -> dict[str, str]:
    sources = {
        (str(p.relative_to(ROOT)) if p.is_relative_to(ROOT) else p.name): source_fingerprint(p)
        for p in _source_files(extra)
    }
    versions = {name: _version(name) for name in LIBRARIES}
    return {
        "sources": digest(sources),
        "python": f"{sys.version_info.major}.{sys.version_info.minor}",
        **versions,
    }


def code_fingerprint(task: Callable[..., Any] | None = None) -> dict[str, str]:
    """The code version: source fingerprint of :data:`RESULT_SOURCES` (and of ``task``'s
    module file), Python's minor version and the :data:`LIBRARIES` versions. Computed once per
    process."""
    extra: tuple[str, ...] = ()
    if task is not None:
        module = sys.modules.get(task.__module__)
        module_file = getattr(module, "__file__", None)
        if module_file:
            extra = (str(Path(module_file).resolve()),)
    return dict(_code_fingerprint(extra))


def task_name(task: Callable[..., Any]) -> str:
    """``module.function`` of a task."""
    return f"{task.__module__}.{task.__qualname__}"


def normalized(data: Any) -> Any:
    """``data`` as it reads back from JSON (tuples become lists), so that it compares equal to
    what a sidecar recorded."""
    return json.loads(json.dumps(data, default=repr))


def env_inputs(env: EnvSpec, layout: Any = None) -> dict[str, str | None]:
    """The environment's fingerprints: registration and arguments, layout and robot (None for
    an environment that has none). ``layout`` is the layout an environment actually loaded (a
    worker passes it); without it the maze is loaded here."""
    layout_print = None
    if env.maze is not None:
        layout_print = (
            digest(layout_content(layout)) if layout is not None else layout_fingerprint(env.maze)
        )
    return {
        "env": env_fingerprint(env),
        "layout": layout_print,
        "robot": robot_fingerprint(env.robot) if env.robot is not None else None,
    }


def run_inputs(
    experiment: ExperimentConfig,
    strategy: StrategySpec,
    env: EnvSpec,
    seed: int,
    task: Callable[..., Any],
    env_prints: Mapping[str, str | None] | None = None,
) -> dict[str, Any]:
    """Every input of one run, fingerprinted (``env_prints``: :func:`env_inputs`, if known)."""
    return {
        "task": task_name(task),
        "config": normalized(resolved_config(experiment, strategy, env, seed)),
        **(env_prints if env_prints is not None else env_inputs(env)),
        "code": code_fingerprint(task),
    }


INPUT_LABELS = {
    "task": "the task that computes a run",
    "config": "the resolved configuration",
    "env": "the environment's registration, arguments or (a user's env) code",
    "layout": "the maze layout",
    "robot": "the robot's file",
    "code": "the code version",
}


def differences(recorded: Mapping[str, Any], expected: Mapping[str, Any]) -> list[str]:
    """The inputs (and, within the configuration and code, the keys) that differ."""
    found = []
    for key in INPUT_LABELS:
        old, new = recorded.get(key), expected.get(key)
        if old == new:
            continue
        if isinstance(old, dict) and isinstance(new, dict):
            found += [f"{key}.{k}" for k in _differing_keys(old, new)]
        else:
            found.append(key)
    return found


def _differing_keys(old: Mapping[str, Any], new: Mapping[str, Any], prefix: str = "") -> list[str]:
    keys = []
    for key in sorted(set(old) | set(new)):
        a, b = old.get(key), new.get(key)
        if a == b:
            continue
        if isinstance(a, dict) and isinstance(b, dict):
            keys += _differing_keys(a, b, f"{prefix}{key}.")
        else:
            keys.append(f"{prefix}{key}")
    return keys


def only_code_differs(found: list[str]) -> bool:
    """Whether every difference is in the code version."""
    return bool(found) and all(item == "code" or item.startswith("code.") for item in found)
