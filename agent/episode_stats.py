"""Per-episode statistics returned by ``learn``, and the checks and loop every agent's
``learn`` shares."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any


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
    ``env`` has a discrete action space of the agent's ``n_actions`` actions, ``callback`` is
    None or callable and ``reset_seed`` is None or an int >= 0 (Gymnasium's ``reset`` would
    otherwise refuse it without naming it, or a callback of 5 fail after the first episode)."""
    if isinstance(episodes, bool) or not isinstance(episodes, int) or episodes < 0:
        raise ValueError(f"episodes must be an int >= 0, got {episodes!r}")
    if callback is not None and not callable(callback):
        raise ValueError(f"callback must be None or callable, got {callback!r}")
    if reset_seed is not None and (
        isinstance(reset_seed, bool) or not isinstance(reset_seed, int) or reset_seed < 0
    ):
        raise ValueError(f"reset_seed must be None or an int >= 0, got {reset_seed!r}")
    space = getattr(env, "action_space", None)
    env_actions = getattr(space, "n", None)
    if env_actions is None or int(env_actions) != n_actions:
        raise ValueError(
            f"env.action_space {space!r} does not match the agent's {n_actions} actions"
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
