"""Per-episode statistics returned by ``learn``, and the checks and loop every agent's
``learn`` shares."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TypeGuard

import numpy as np


@dataclass(frozen=True)
class EpisodeStats:
    """What happened in one training episode."""

    episode: int
    """Index of the episode over the agent's life (continues across ``learn`` calls)."""
    steps: int
    """Environment steps taken."""
    episode_return: float
    """Undiscounted sum of rewards."""
    success: bool
    """``info["is_success"]`` at the last step if the env reports it, else ``terminated``."""
    truncated: bool
    """The episode was cut by a time limit."""
    leaves: int
    """Leaves of the partition at the end of the episode."""
    collisions: int
    """Steps whose ``info[collision_key]`` was true."""
    epochs: int = 0
    """SMDP epochs (decision points) in the episode (section IV.A)."""
    mean_epsilon: float = 0.0
    """Mean exploration rate at the episode's decision points."""


Callback = Callable[[EpisodeStats], bool | None]
"""Called after each episode of ``learn``; returning ``False`` stops learning."""


def check_learn_arguments(
    env: Any,
    episodes: object,
    n_actions: int,
    callback: object = None,
    reset_seed: object = None,
) -> None:
    """A ValueError naming the argument unless ``episodes`` is an int >= 0 (not a bool),
    ``env`` is one Gymnasium env (not an id, a class or a vector env) whose action space is
    ``Discrete(n_actions)`` starting at 0 (the agent's actions are ``0 .. n_actions - 1``; an env
    numbered from 1 would take them as other actions), ``callback`` is None or callable and
    ``reset_seed`` is None or an int >= 0 (Gymnasium's ``reset`` would otherwise refuse it
    without naming it, or a callback of 5 fail after the first episode)."""
    if isinstance(episodes, bool) or not isinstance(episodes, int) or episodes < 0:
        raise ValueError(f"episodes must be an int >= 0, got {episodes!r}")
    if callback is not None and not callable(callback):
        raise ValueError(f"callback must be None or callable, got {callback!r}")
    if reset_seed is not None and (
        isinstance(reset_seed, bool) or not isinstance(reset_seed, int) or reset_seed < 0
    ):
        raise ValueError(f"reset_seed must be None or an int >= 0, got {reset_seed!r}")
    _check_one_env(env)
    space = getattr(env, "action_space", None)
    env_actions = getattr(space, "n", None)
    start = getattr(space, "start", 0)
    if not _whole(env_actions) or int(env_actions) != n_actions:
        raise ValueError(
            f"env.action_space {space!r} does not match the agent's {n_actions} actions"
        )
    if not _whole(start) or int(start) != 0:
        raise ValueError(
            f"env.action_space {space!r} starts at {start}, but the agent's actions are "
            f"0 .. {n_actions - 1}: the env would take them as other actions; "
            "agent.adapt_env(env) renumbers it"
        )


def _whole(value: object) -> TypeGuard[int | np.integer[Any]]:
    """An int or a numpy integer, not a bool."""
    return isinstance(value, int | np.integer) and not isinstance(value, bool)


def _check_one_env(env: Any) -> None:
    """A ValueError unless ``env`` is one env: an object with ``reset`` and ``step`` that is not
    a class and not a vector env (``num_envs`` copies stepped as one)."""
    if isinstance(env, str):
        raise ValueError(
            f"env must be a Gymnasium env, got the string {env!r}; make it first, "
            f"gymnasium.make({env!r})"
        )
    if isinstance(env, type):
        raise ValueError(
            f"env must be a Gymnasium env, got the class {env.__name__}; pass an instance"
        )
    if not (callable(getattr(env, "reset", None)) and callable(getattr(env, "step", None))):
        raise ValueError(
            f"env must be a Gymnasium env with reset() and step(), got {env!r} "
            f"({type(env).__name__})"
        )
    copies = getattr(env, "num_envs", None)
    if _whole(copies):
        raise ValueError(
            f"env is a vector env of {copies} copies ({type(env).__name__}); learn steps one "
            "env: pass one made with gymnasium.make"
        )


def run_episodes(
    env: Any,
    episodes: int,
    run_episode: Callable[[Any, Any], EpisodeStats],
    callback: Callback | None = None,
    reset_seed: int | None = None,
) -> list[EpisodeStats]:
    """``episodes`` episodes of ``run_episode(env, obs)``, the first reset with ``reset_seed``
    and the rest unseeded; ``callback(stats)`` after each, ``False`` stops."""
    history: list[EpisodeStats] = []
    for i in range(episodes):
        obs, _ = env.reset(seed=reset_seed if i == 0 else None)
        stats = run_episode(env, obs)
        history.append(stats)
        if callback is not None and callback(stats) is False:
            break
    return history
