"""Checks of the spaces an agent is built for: a Box observation, Discrete actions.

An integer-typed Box (:func:`integer_inputs`) holds cells: the integer k covers
``[k - 0.5, k + 0.5]``, so its box is the declared bounds widened by a half on each side, and a
split halfway between two integers separates them.

A dimension whose bound is infinite, or beyond :data:`UNBOUNDED_MAGNITUDE` in magnitude (some
envs write ``float32`` max for "unbounded"), or at the extreme of a 32- or 64-bit integer dtype,
is unbounded (an 8- or 16-bit one's extremes are real bounds: an image's 0 and 255).
Agents whose partition can grow its bounds from the data (the tree, ``allow_unbounded=True``)
get ``-inf`` / ``inf`` there; the others refuse it with a message that says to pass ``bounds``.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from gymnasium import spaces

UNBOUNDED_MAGNITUDE = 1e30
"""A declared bound at least this large in magnitude is read as unbounded."""

MAX_OBSERVATION_DIMS = 64
"""Most observation dimensions an agent takes (and an agent file may declare): the model keeps
each stored epoch's input, so its memory grows with them. The maze's lidar with its default 36
rays has 38."""


def observation_bounds(
    observation_space: spaces.Space,
    bounds: tuple[Sequence[float], Sequence[float]] | None,
    allow_unbounded: bool = False,
) -> tuple[list[float], list[float]]:
    """The box the partition covers: ``bounds`` if given, else the space's own bounds.

    With ``allow_unbounded`` an unbounded dimension comes back as ``-inf`` / ``inf``; without it
    it is a ValueError. Raises TypeError for a non-Box observation space and ValueError for a
    non-flat one, NaN or empty bounds, naming the offending values.
    """
    if not isinstance(observation_space, spaces.Box):
        raise TypeError(
            "observation_space must be a gymnasium.spaces.Box, "
            f"got {type(observation_space).__name__} ({observation_space!r}); "
            "agent.adapt_env(env) maps it to one"
        )
    if len(observation_space.shape) != 1:
        raise ValueError(
            f"observation_space must be one-dimensional, got shape {observation_space.shape}; "
            "agent.adapt_env(env) flattens it"
        )
    dims = observation_space.shape[0]
    if dims == 0:
        raise ValueError(
            f"observation_space has no dimensions ({observation_space!r}); an agent needs at "
            "least one input"
        )
    if dims > MAX_OBSERVATION_DIMS:
        raise ValueError(
            f"observation_space has {dims} dimensions, at most {MAX_OBSERVATION_DIMS}: give the "
            "agent fewer inputs (a maze's lidar_rays, a smaller frame stack)"
        )
    if bounds is None:
        low = np.asarray(observation_space.low, dtype=np.float64)
        high = np.asarray(observation_space.high, dtype=np.float64)
        source = "observation_space"
        if integer_inputs(observation_space):
            low, high = low - 0.5, high + 0.5
            limits = np.iinfo(observation_space.dtype)
            if limits.bits >= 32:  # a 32- or 64-bit extreme stands for "no bound"
                low = np.where(low + 0.5 <= limits.min, -np.inf, low)
                high = np.where(high - 0.5 >= limits.max, np.inf, high)
    else:
        if isinstance(bounds, str | bytes) or not isinstance(bounds, Sequence | np.ndarray):
            raise ValueError(f"bounds must be (low, high), got {bounds!r}")
        if len(bounds) != 2:
            raise ValueError(f"bounds must be (low, high), got {bounds!r}")
        try:
            low = np.asarray(bounds[0], dtype=np.float64).reshape(-1)
            high = np.asarray(bounds[1], dtype=np.float64).reshape(-1)
        except (TypeError, ValueError):
            raise ValueError(
                f"bounds must be (low, high), two sequences of numbers, got {bounds!r}"
            ) from None
        source = "bounds"
        if low.shape != (dims,) or high.shape != (dims,):
            raise ValueError(
                f"bounds must give {dims} lows and {dims} highs, "
                f"got {low.tolist()} and {high.tolist()}"
            )
    if np.isnan(low).any() or np.isnan(high).any():
        raise ValueError(f"{source} has NaN bounds (low={low.tolist()}, high={high.tolist()})")
    low = np.where(low <= -UNBOUNDED_MAGNITUDE, -np.inf, low)
    high = np.where(high >= UNBOUNDED_MAGNITUDE, np.inf, high)
    if not allow_unbounded and not (np.isfinite(low).all() and np.isfinite(high).all()):
        raise ValueError(
            f"{source} is unbounded (low={low.tolist()}, high={high.tolist()}); "
            "pass finite bounds=(low, high) to the agent"
        )
    if not (low < high).all():
        d = int(np.flatnonzero(~(low < high))[0])
        lo, hi = float(low[d]), float(high[d])
        what = (
            f"low = high = {lo!r} (a constant input: drop it from the observation, or give "
            "the agent bounds=(low, high) that are wider there)"
            if lo == hi
            else f"low {lo!r} > high {hi!r}"
        )
        raise ValueError(
            f"{source} must have low < high in every dimension; dimension {d} has {what} "
            f"(low={low.tolist()}, high={high.tolist()})"
        )
    return low.tolist(), high.tolist()


def integer_inputs(observation_space: spaces.Space) -> bool:
    """Whether the observation is a Box of an integer dtype: its coordinates are cells
    (module docstring), as :func:`agent.adapt_env` gives a Discrete, MultiDiscrete or
    MultiBinary observation, or a Tuple or Dict of those."""
    return isinstance(observation_space, spaces.Box) and bool(
        np.issubdtype(observation_space.dtype, np.integer)
    )


def squash(value: float) -> float:
    """``x / (1 + |x|)``: an unbounded input mapped onto (-1, 1), monotone, 0 at 0 (the rule of
    the fixed-representation baselines for unbounded dimensions; it assumes inputs of order 1)."""
    return value / (1.0 + abs(value))


def action_count(action_space: spaces.Space) -> int:
    """Number of actions of a Discrete space starting at 0 (TypeError / ValueError otherwise)."""
    if not isinstance(action_space, spaces.Discrete):
        raise TypeError(
            f"action_space must be a gymnasium.spaces.Discrete, got {type(action_space).__name__}"
            f" ({action_space!r}); agent.adapt_env(env, action_bins=5) gives a grid of its actions"
        )
    if int(action_space.start) != 0:
        raise ValueError(
            f"action_space must start at 0, got start={int(action_space.start)}; "
            "agent.adapt_env(env) renumbers it"
        )
    return int(action_space.n)
