"""Build the environment and the agent of a run from an experiment's specs.

``bullet_maze`` and ``agent`` are imported inside the functions, so the rest of the harness
(configs, statistics, plots, resume) works and is tested without them.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from experiments.config import ConfigError, EnvSpec, ExperimentConfig, StrategySpec


def make_env(spec: EnvSpec, render_mode: str | None = None, **changes: Any) -> gym.Env:
    """The experiment's environment (``gymnasium.make`` with its time limit).

    ``changes`` replace fields of ``spec`` (``mode="dynamic"``, ``robot="husky"``).
    """
    import bullet_maze  # noqa: F401  (registers the environment ids)

    spec = dataclasses.replace(spec, **changes) if changes else spec
    return gym.make(
        spec.id,
        max_episode_steps=spec.max_episode_steps,
        maze=spec.maze,
        robot=spec.robot,
        mode=spec.mode,
        render_mode=render_mode,
        **spec.params,
    )


def agent_config(config: ExperimentConfig, strategy: StrategySpec) -> Any:
    """The strategy's ``TreeConfig`` (the experiment's ``[agent]`` table under its own)."""
    from agent import TreeConfig

    params = config.agent_params(strategy)
    _check_fields(TreeConfig, params, config.source, strategy)
    try:
        return TreeConfig(**params)
    except (TypeError, ValueError) as error:
        raise ConfigError(
            f"{config.source}: [strategy {strategy.name!r}] agent config: {error}"
        ) from None


def make_exploration(config: ExperimentConfig, strategy: StrategySpec) -> Any:
    """The strategy's exploration object (``agent.make_exploration``)."""
    from agent import make_exploration as build

    try:
        return build(strategy.exploration, **strategy.exploration_params)
    except (TypeError, ValueError) as error:
        raise ConfigError(
            f"{config.source}: [strategy {strategy.name!r}] exploration / "
            f"exploration_params: {error}"
        ) from None


def make_agent(config: ExperimentConfig, strategy: StrategySpec, env: gym.Env, seed: int) -> Any:
    """A fresh agent of the strategy for ``env``, its generator seeded with ``seed``."""
    from agent import GridAgent, TreeAgent

    tree_config = agent_config(config, strategy)
    exploration = make_exploration(config, strategy)
    try:
        if strategy.agent == "grid":
            if strategy.resolution is None:
                raise ValueError('a grid strategy needs "resolution"')
            return GridAgent(
                env.observation_space,
                env.action_space,
                exploration=exploration,
                seed=seed,
                config=tree_config,
                resolution=strategy.resolution,
            )
        return TreeAgent(
            env.observation_space,
            env.action_space,
            exploration=exploration,
            seed=seed,
            config=tree_config,
        )
    except (TypeError, ValueError) as error:
        raise ConfigError(f"{config.source}: [strategy {strategy.name!r}]: {error}") from None


def check_agent_params(config: ExperimentConfig) -> None:
    """Validate every strategy's agent fields and exploration parameters against ``agent``.

    Raises :class:`ConfigError` naming the file, the strategy and the key; builds nothing
    heavier than the config dataclass and the exploration object.
    """
    for strategy in config.strategies:
        agent_config(config, strategy)
        make_exploration(config, strategy)


def make_experiment_env(config: ExperimentConfig, render_mode: str | None = None) -> gym.Env:
    """The experiment's environment; a bad maze, robot or parameter is a :class:`ConfigError`
    naming the file's ``[env]`` table."""
    try:
        return make_env(config.env, render_mode)
    except (TypeError, ValueError, FileNotFoundError, gym.error.Error) as error:
        raise ConfigError(f"{config.source}: [env]: {error}") from None


def check_env(config: ExperimentConfig) -> float:
    """Build the environment once (bad settings fail here, by name); its optimal steps."""
    env = make_experiment_env(config)
    try:
        return optimal_steps(env)
    finally:
        env.close()


def optimal_steps(env: gym.Env) -> float:
    """``env.unwrapped.optimal_steps`` (NaN when the environment does not say)."""
    value = getattr(env.unwrapped, "optimal_steps", None)
    return float("nan") if value is None else float(value)


def _check_fields(
    config_class: type, params: Mapping[str, Any], source: str, strategy: StrategySpec
) -> None:
    known = {f.name for f in dataclasses.fields(config_class)}
    for key in params:
        if key not in known:
            where = "config" if key in strategy.config else "[agent]"
            raise ConfigError(
                f"{source}: {where} key {key!r} (strategy {strategy.name!r}) is not a field of "
                f"{config_class.__name__}; known fields: {', '.join(sorted(known))}"
            )


class ProjectObservation(gym.ObservationWrapper):
    """Keep the first ``dims`` observation entries, for an agent trained on fewer inputs.

    A disc-trained agent sees ``(x, y)``; the husky observes ``(x, y, heading)``. The agent's
    policy is a function of position only, so the heading is dropped.
    """

    def __init__(self, env: gym.Env, dims: int) -> None:
        super().__init__(env)
        space = env.observation_space
        if not isinstance(space, gym.spaces.Box) or space.shape[0] < dims:
            raise ValueError(f"cannot project observation space {space} to {dims} dimensions")
        self.dims = dims
        self.observation_space = gym.spaces.Box(
            space.low[:dims], space.high[:dims], dtype=space.dtype
        )

    def observation(self, observation: np.ndarray) -> np.ndarray:
        """The first ``dims`` entries."""
        return np.asarray(observation)[: self.dims]


def load_agent(path: Path) -> Any:
    """A saved agent (tree or grid, whichever the file holds)."""
    from agent import SMDPAgent

    return SMDPAgent.load(path)


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
