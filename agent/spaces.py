"""Checks of the spaces an agent is built for: a bounded Box observation, Discrete actions."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from gymnasium import spaces


def observation_bounds(
    observation_space: spaces.Space, bounds: tuple[Sequence[float], Sequence[float]] | None
) -> tuple[list[float], list[float]]:
    """The box the partition covers: ``bounds`` if given, else the space's own (finite) bounds.

    Raises TypeError for a non-Box or non-flat observation space and ValueError for infinite or
    empty bounds, naming the offending values.
    """
    if not isinstance(observation_space, spaces.Box):
        raise TypeError(
            "observation_space must be a gymnasium.spaces.Box, "
            f"got {type(observation_space).__name__} ({observation_space!r})"
        )
    if len(observation_space.shape) != 1:
        raise ValueError(
            f"observation_space must be one-dimensional, got shape {observation_space.shape}"
        )
    dims = observation_space.shape[0]
    if bounds is None:
        low = np.asarray(observation_space.low, dtype=np.float64)
        high = np.asarray(observation_space.high, dtype=np.float64)
        source = "observation_space"
    else:
        if len(bounds) != 2:
            raise ValueError(f"bounds must be (low, high), got {bounds!r}")
        low = np.asarray(bounds[0], dtype=np.float64).reshape(-1)
        high = np.asarray(bounds[1], dtype=np.float64).reshape(-1)
        source = "bounds"
        if low.shape != (dims,) or high.shape != (dims,):
            raise ValueError(
                f"bounds must give {dims} lows and {dims} highs, "
                f"got {low.tolist()} and {high.tolist()}"
            )
    if not (np.isfinite(low).all() and np.isfinite(high).all()):
        raise ValueError(
            f"{source} is unbounded (low={low.tolist()}, high={high.tolist()}); "
            "pass finite bounds=(low, high) to the agent"
        )
    if not (low < high).all():
        raise ValueError(
            f"{source} must have low < high, got low={low.tolist()}, high={high.tolist()}"
        )
    return low.tolist(), high.tolist()


def action_count(action_space: spaces.Space) -> int:
    """Number of actions of a Discrete space starting at 0 (TypeError / ValueError otherwise)."""
    if not isinstance(action_space, spaces.Discrete):
        raise TypeError(
            f"action_space must be a gymnasium.spaces.Discrete, got {type(action_space).__name__}"
            f" ({action_space!r})"
        )
    if int(action_space.start) != 0:
        raise ValueError(f"action_space must start at 0, got start={int(action_space.start)}")
    return int(action_space.n)
