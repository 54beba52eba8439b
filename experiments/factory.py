"""Build the environment and the agent of a run from an experiment's specs.

Everything a user gave has been validated by :mod:`experiments.config` already; the checks here
are the ones that need the objects themselves (a layout that loads, a robot file that exists,
an environment that builds, a grid that fits the observation), each reported as a
:class:`ConfigError` naming where the value came from.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from agent.serialization import check_grid_resolution, config_from_data, exploration_from_data
from experiments import fingerprint
from experiments.agent_kinds import FIXED_AGENTS, is_fixed
from experiments.config import ConfigError, EnvSpec, ExperimentConfig, StrategySpec, TaskSpec


def make_env(spec: EnvSpec, render_mode: str | None = None, **changes: Any) -> gym.Env:
    """The run's environment (``gymnasium.make`` with its time limit), through
    :func:`agent.adapt_env`: a task whose observation is not a flat Box or whose actions are
    not Discrete gets the documented wrappers (``spec.action_bins`` values per Box action
    dimension); the mazes and classic control pass unchanged.

    ``changes`` replace fields of ``spec`` (``mode="dynamic"``, ``robot="husky"``). A ValueError
    if ``action_bins`` is set for a task whose actions are not a Box.
    """
    from agent import adapt_env

    spec = dataclasses.replace(spec, **changes) if changes else spec
    env = gym.make(spec.id, render_mode=render_mode, **spec.make_kwargs())
    try:
        return adapt_env(env, spec.action_bins)
    except (TypeError, ValueError):
        env.close()
        raise


def agent_config(config: ExperimentConfig, strategy: StrategySpec) -> Any:
    """The strategy's ``TreeConfig`` (the experiment's ``[agent]`` table under its own)."""
    try:
        return config_from_data(
            config.agent_params(strategy), f"{config.source}: [strategy {strategy.name!r}]"
        )
    except ValueError as error:
        raise ConfigError(str(error)) from None


def make_exploration(config: ExperimentConfig, strategy: StrategySpec) -> Any:
    """The strategy's exploration object (``agent.make_exploration``)."""
    try:
        return exploration_from_data(
            strategy.exploration,
            strategy.exploration_params,
            f"{config.source}: [strategy {strategy.name!r}] exploration",
        )
    except ValueError as error:
        raise ConfigError(str(error)) from None


def make_agent(
    config: ExperimentConfig,
    strategy: StrategySpec,
    env: gym.Env,
    seed: int,
    bounds: tuple[tuple[float, ...], tuple[float, ...]] | None = None,
) -> Any:
    """A fresh agent of the strategy for ``env``, its generator seeded with ``seed``;
    ``bounds`` (an ``EnvSpec``'s ``observation_bounds``) is the box its partition covers."""
    from agent import GridAgent
    from agent.tree_ensemble import tree_agent_class

    where = f"{config.source}: [strategy {strategy.name!r}]"
    if is_fixed(strategy.agent):
        try:
            return FIXED_AGENTS[strategy.agent](
                env.observation_space,
                env.action_space,
                seed,
                bounds=bounds,
                **strategy.agent_params,
            )
        except (TypeError, ValueError) as error:
            raise ConfigError(f"{where} agent_params: {error}") from None
    tree_config = agent_config(config, strategy)
    exploration = make_exploration(config, strategy)
    try:
        if strategy.agent == "grid":
            dims = int(np.prod(env.observation_space.shape or (1,)))
            resolution = check_grid_resolution(strategy.resolution, dims, f"{where} resolution")
            return GridAgent(
                env.observation_space,
                env.action_space,
                exploration=exploration,
                seed=seed,
                config=tree_config,
                resolution=resolution,
                bounds=bounds,
            )
        return tree_agent_class(tree_config)(
            env.observation_space,
            env.action_space,
            exploration=exploration,
            seed=seed,
            config=tree_config,
            bounds=bounds,
        )
    except (TypeError, ValueError) as error:
        message = str(error)
        raise ConfigError(message if message.startswith(where) else f"{where}: {message}") from None


def env_origins(source: str, options: Mapping[str, str] | None = None) -> dict[str, str]:
    """Where each environment setting came from, for error messages: the file's ``[env]``
    table, except the settings an option replaced (``{"maze": "--maze"}``)."""
    origins = {key: f"{source}: [env] {key}" for key in ("id", "maze", "robot", "mode", "params")}
    origins["env"] = f"{source}: [env]"
    for key, option in (options or {}).items():
        origins[key] = f"option {option}"
    if options:
        origins["env"] = f"{source}: [env] with {', '.join(sorted(options.values()))}"
    return origins


def task_origins(source: str, task: TaskSpec) -> dict[str, str]:
    """Where each setting of a task came from, for error messages: the task itself."""
    where = f"{source}: task {task.name!r}"
    if task.split is not None:
        where += f" ([env] suite, split {task.split})"
    return {key: where for key in ("id", "maze", "robot", "mode", "params", "env")}


def check_env(spec: EnvSpec, origins: Mapping[str, str]) -> gym.Env:
    """The environment, built once after its layout and robot were checked on their own, so
    that an error names the setting it came from (``origins``, see :func:`env_origins`).
    The caller closes it."""
    if spec.maze is not None:
        try:
            fingerprint.layout_fingerprint(spec.maze)
        except (TypeError, ValueError, OSError) as error:
            raise ConfigError(f"{origins['maze']}: {error}") from None
    if spec.robot is not None:
        try:
            fingerprint.robot_content(spec.robot)
        except (TypeError, ValueError, OSError) as error:
            raise ConfigError(f"{origins['robot']}: {error}") from None
    try:
        return make_env(spec)
    except (TypeError, ValueError, OSError, gym.error.Error) as error:
        raise ConfigError(f"{origins['env']}: {error}") from None
    except Exception as error:  # e.g. pybullet.error on a robot file it cannot load
        raise ConfigError(
            f"{origins['env']}: cannot build the environment ({type(error).__name__}: {error})"
        ) from None


def check_agents(
    config: ExperimentConfig, env: gym.Env, spec: EnvSpec | None = None, where: str = ""
) -> None:
    """Build every strategy's agent once for ``env`` (made from ``spec``, default the
    experiment's): a grid too fine, a space the agent cannot take is a :class:`ConfigError`
    naming the strategy (and ``where``, the task)."""
    bounds = (spec or config.env).observation_bounds
    for strategy in config.strategies:
        try:
            make_agent(config, strategy, env, seed=0, bounds=bounds)
        except ConfigError as error:
            raise ConfigError(f"{error} ({where})" if where else str(error)) from None


def optimal_steps(env: gym.Env) -> float:
    """``env.unwrapped.optimal_steps``, the least number of compass steps to the goal, where it
    is the env's optimum: NaN when the env does not say, and when its actions are not compass
    steps (a native or continuous step has another length and may go diagonally, so the count
    is no bound on its steps; such a run is reported without an optimum)."""
    from bullet_maze.action_sets import CompassActions

    inner = env.unwrapped
    value = getattr(inner, "optimal_steps", None)
    actions = getattr(inner, "actions", None)
    if value is None or (actions is not None and not isinstance(actions, CompassActions)):
        return float("nan")
    return float(value)


HEADING_INDEX = 2
"""Where a maze observation holds the robot's heading: ``(x, y, heading, lidar ranges...)``
(``bullet_maze.BulletMazeEnv``; a robot without one observes ``(x, y, ranges...)``), in the
Box itself or in a goal-conditioned ``Dict``'s ``"observation"``."""


class DropHeading(gym.ObservationWrapper):
    """The observation without the robot's heading at ``index``, for an agent trained on a robot
    that has none: the other inputs in the places the agent learnt them."""

    def __init__(self, env: gym.Env, index: int) -> None:
        super().__init__(env)
        space = env.observation_space
        if not isinstance(space, gym.spaces.Box) or len(space.shape) != 1:
            raise ValueError(f"cannot drop the heading of observation space {space}")
        self.index = index
        self.keep = np.delete(np.arange(space.shape[0]), index)
        self.observation_space = gym.spaces.Box(
            space.low[self.keep], space.high[self.keep], dtype=space.dtype
        )

    def observation(self, observation: np.ndarray) -> np.ndarray:
        """Every entry but the heading."""
        return np.asarray(observation)[self.keep]


def fitted_to(env: gym.Env, dims: int) -> gym.Env:
    """``env`` as an agent of ``dims`` inputs sees it: itself when it gives ``dims`` values, or
    :class:`DropHeading` of it when it gives one more because its robot has a heading (a
    disc-trained agent on the husky). A ValueError saying what differs otherwise: another
    number of lidar rays, another observation mode or a robot with no heading for an agent
    that used one cannot be fitted by leaving values out."""
    space = env.observation_space
    given = int(np.prod(space.shape)) if isinstance(space, gym.spaces.Box) else None
    if given == dims:
        return env
    heading = heading_index(env)
    if given == dims + 1 and heading is not None:
        return DropHeading(env, heading)
    raise ValueError(
        f"the agent observes {dims} values; this environment gives "
        f"{space if given is None else given}"
        + (" (its robot's heading is one of them)" if heading is not None else "")
    )


def heading_index(env: gym.Env) -> int | None:
    """Where ``env``'s observation, as its wrappers hand it out (a goal-conditioned ``Dict``
    flattened by ``agent.adapt_env``, say), holds the maze robot's heading; None for a robot
    without one or an env that is not the maze. Found by passing a raw observation that is 1 at
    the heading and 0 elsewhere through the wrappers' ``observation`` methods."""
    inner = env.unwrapped
    if not getattr(getattr(inner, "robot", None), "has_heading", False):
        return None
    raw = inner.observation_space
    probe: Any
    if isinstance(raw, gym.spaces.Box) and len(raw.shape) == 1:
        probe = np.zeros(raw.shape, dtype=np.float64)
        probe[HEADING_INDEX] = 1.0
    elif isinstance(raw, gym.spaces.Dict) and "observation" in raw.spaces:
        probe = {key: np.zeros(part.shape, dtype=np.float64) for key, part in raw.spaces.items()}
        probe["observation"][HEADING_INDEX] = 1.0
    else:
        return None
    wrappers = []
    layer: Any = env
    while isinstance(layer, gym.Wrapper):
        if isinstance(layer, gym.ObservationWrapper):
            wrappers.append(layer)
        layer = layer.env
    for wrapper in reversed(wrappers):  # innermost first
        probe = wrapper.observation(probe)
    marked = np.flatnonzero(np.asarray(probe, dtype=np.float64).reshape(-1) == 1.0)
    return int(marked[0]) if marked.size == 1 else None


def load_agent(path: Path) -> Any:
    """A saved agent: a tree or grid, or a baseline (the tile coder, adaptive Q-learning),
    whichever the file holds."""
    from agent import SMDPAgent
    from agent.baseline_files import baseline_kind

    kind = baseline_kind(path)
    if kind is None:
        return SMDPAgent.load(path)
    if kind not in FIXED_AGENTS:
        raise ValueError(f"{path}: holds an agent of unknown kind {kind!r}")
    return FIXED_AGENTS[kind].load(path)  # type: ignore[attr-defined]


def maze_geometry(env: gym.Env) -> tuple[Any, np.ndarray]:
    """The env's maze layout and the unit direction of each action (for drawing)."""
    from bullet_maze import load_layout
    from bullet_maze.actions import DIRECTIONS

    unwrapped = env.unwrapped
    layout = getattr(unwrapped, "layout", None)
    if layout is None:
        kwargs = unwrapped.spec.kwargs if unwrapped.spec is not None else {}
        layout = load_layout(kwargs.get("maze", "paper"))
    return layout, DIRECTIONS
