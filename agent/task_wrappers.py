"""Gymnasium wrappers that give any task the spaces the agents take: a flat Box observation
and Discrete actions (beyond the paper, whose maze has both).

The agents partition a box of inputs and choose among ``n`` actions (:mod:`agent.spaces`). A
task with another observation space (FrozenLake's ``Discrete(16)``, Blackjack's ``Tuple``) or a
continuous action (Pendulum's torque) is brought to them by a documented rule, not refused:

* :class:`BoxObservation`: every component becomes coordinates of one flat Box. A
  ``Discrete(n, start)`` is its index, one coordinate; ``MultiDiscrete`` and ``MultiBinary``
  give one index per entry; a ``Box`` of any shape is flattened with its bounds; a ``Tuple``
  or ``Dict`` concatenates its parts (a ``Dict`` in its key order). When every part is
  discrete the Box is integer-typed, ``[start, start + n - 1]`` per index, and the agents read
  each integer as a cell ``[k - 0.5, k + 0.5]`` (:mod:`agent.spaces`), so a tree can start
  as a table of them (``TreeConfig.table_cells``). When a Box part is mixed in, the Box is
  float and an index is one coordinate in ``[start - 0.5, start + n - 0.5]`` (a split halfway
  between two indices separates them). An index keeps the tree's inputs few (one per
  component, where ``gymnasium.wrappers.FlattenObservation`` would one-hot ``Discrete(500)``
  into 500 inputs).
* :class:`DiscreteActions`: ``Discrete(m)`` over a grid of the task's actions. A ``Box`` with
  finite bounds gets ``bins`` evenly spaced values per dimension, both bounds included (with
  an odd ``bins`` the middle one is the centre, 0 for a symmetric torque; a dimension whose
  bounds are equal has its one value), and the grid is the product over dimensions, the first
  dimension varying slowest; ``MultiDiscrete`` and
  ``MultiBinary`` become the product of their choices. At most :data:`MAX_ACTIONS` actions.
* :func:`adapt_env` applies whichever of the two a task needs, and nothing to a task that
  already has a flat Box and a Discrete space (the mazes, classic control), so it is safe to
  call on every task; the experiment harness does (``[env] action_bins``).
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces
from gymnasium.utils import RecordConstructorArgs

MAX_ACTIONS = 4096
"""The largest action grid :class:`DiscreteActions` builds (a tree keeps a value per action in
every leaf)."""
DEFAULT_ACTION_BINS = 5
"""Values per dimension of a Box action when none is given (odd: the centre is one of them)."""


def _box_parts(space: spaces.Space, where: str) -> list[tuple[np.ndarray, np.ndarray]]:
    """Per component of ``space``, the (low, high) of its coordinates, in order."""
    if isinstance(space, spaces.Discrete):
        first = float(space.start)
        return [(np.array([first - 0.5]), np.array([first + float(space.n) - 0.5]))]
    if isinstance(space, spaces.MultiDiscrete):
        nvec = np.asarray(space.nvec, dtype=np.float64).reshape(-1)
        start = np.asarray(space.start, dtype=np.float64).reshape(-1)
        return [(start - 0.5, start + nvec - 0.5)]
    if isinstance(space, spaces.MultiBinary):
        size = int(np.prod(space.shape))
        return [(np.full(size, -0.5), np.full(size, 1.5))]
    if isinstance(space, spaces.Box):
        low = np.asarray(space.low, dtype=np.float64).reshape(-1)
        high = np.asarray(space.high, dtype=np.float64).reshape(-1)
        return [(low, high)]
    if isinstance(space, spaces.Tuple):
        return [
            part for i, sub in enumerate(space.spaces) for part in _box_parts(sub, f"{where}[{i}]")
        ]
    if isinstance(space, spaces.Dict):
        return [
            part
            for key, sub in space.spaces.items()
            for part in _box_parts(sub, f"{where}[{key!r}]")
        ]
    raise TypeError(
        f"BoxObservation: {where} is a {type(space).__name__} ({space!r}); it takes Box, "
        "Discrete, MultiDiscrete, MultiBinary, and Tuple or Dict of those"
    )


def _coordinates(space: spaces.Space, value: Any) -> list[np.ndarray]:
    """The float coordinates of one observation ``value`` of ``space``, per component."""
    if isinstance(space, spaces.Discrete):
        return [np.array([float(value)])]
    if isinstance(space, (spaces.MultiDiscrete, spaces.MultiBinary, spaces.Box)):
        return [np.asarray(value, dtype=np.float64).reshape(-1)]
    if isinstance(space, spaces.Tuple):
        return [c for sub, v in zip(space.spaces, value, strict=True) for c in _coordinates(sub, v)]
    assert isinstance(space, spaces.Dict)
    return [c for key, sub in space.spaces.items() for c in _coordinates(sub, value[key])]


def needs_box_observation(space: spaces.Space) -> bool:
    """Whether ``space`` is not already the flat Box the agents take."""
    return not (isinstance(space, spaces.Box) and len(space.shape) == 1)


def _all_discrete(space: spaces.Space) -> bool:
    """Whether every part of ``space`` is Discrete, MultiDiscrete or MultiBinary."""
    if isinstance(space, spaces.Discrete | spaces.MultiDiscrete | spaces.MultiBinary):
        return True
    if isinstance(space, spaces.Tuple):
        return all(_all_discrete(sub) for sub in space.spaces)
    if isinstance(space, spaces.Dict):
        return all(_all_discrete(sub) for sub in space.spaces.values())
    return False


class BoxObservation(gym.ObservationWrapper[np.ndarray, Any, Any], RecordConstructorArgs):
    """Any observation as the coordinates of one flat Box (module docstring's rule): integer
    indices when every part is discrete, floats otherwise."""

    def __init__(self, env: gym.Env[Any, Any]) -> None:
        RecordConstructorArgs.__init__(self)
        gym.ObservationWrapper.__init__(self, env)
        self._source = env.observation_space
        parts = _box_parts(self._source, "observation_space")
        low = np.concatenate([p[0] for p in parts]) if parts else np.zeros(0)
        high = np.concatenate([p[1] for p in parts]) if parts else np.zeros(0)
        if low.size == 0:
            raise ValueError(f"BoxObservation: observation_space {self._source!r} has no entries")
        self._integer = _all_discrete(self._source)
        if self._integer:
            low, high = (low + 0.5).astype(np.int64), (high - 0.5).astype(np.int64)
            self.observation_space = spaces.Box(low, high, dtype=np.int64)
        else:
            self.observation_space = spaces.Box(low, high, dtype=np.float64)

    def observation(self, observation: Any) -> np.ndarray:
        """The observation's coordinates, concatenated."""
        coordinates = np.concatenate(_coordinates(self._source, observation))
        return coordinates.astype(np.int64) if self._integer else coordinates


def _bins_per_dimension(bins: Any, dims: int) -> list[int]:
    """``bins`` as one count per dimension, checked (ValueError naming the value)."""
    if _is_int(bins):
        counts = [bins] * dims
    elif isinstance(bins, (list, tuple, np.ndarray)):
        counts = list(bins)
    else:
        raise ValueError(
            f"DiscreteActions: bins must be an int >= 2 or one per dimension, got {bins!r}"
        )
    if len(counts) != dims:
        raise ValueError(
            f"DiscreteActions: bins gives {len(counts)} counts for a {dims}-dimensional action, "
            f"got {bins!r}"
        )
    if not all(_is_int(count) and count >= 2 for count in counts):
        raise ValueError(f"DiscreteActions: every bin count must be an int >= 2, got {bins!r}")
    return [int(count) for count in counts]


def _is_int(value: Any) -> bool:
    """An int (Python or NumPy), not a bool."""
    return isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))


class DiscreteActions(gym.ActionWrapper[Any, int, Any], RecordConstructorArgs):
    """``Discrete(m)`` over a grid of the task's actions (module docstring's rule).

    :attr:`actions` lists the task's action of each index.
    """

    def __init__(
        self, env: gym.Env[Any, Any], bins: int | Sequence[int] = DEFAULT_ACTION_BINS
    ) -> None:
        RecordConstructorArgs.__init__(self, bins=bins)
        gym.ActionWrapper.__init__(self, env)
        space = env.action_space
        if isinstance(space, spaces.Box):
            low = np.asarray(space.low, dtype=np.float64).reshape(-1)
            high = np.asarray(space.high, dtype=np.float64).reshape(-1)
            if not (np.isfinite(low).all() and np.isfinite(high).all()):
                raise ValueError(
                    f"DiscreteActions: the action space {space!r} is unbounded "
                    f"(low={low.tolist()}, high={high.tolist()}); give it finite bounds first"
                )
            if low.size == 0:
                raise ValueError(f"DiscreteActions: the action space {space!r} has no entries")
            counts = _bins_per_dimension(bins, low.size)
            # a dimension fixed by its bounds (low == high) has its one value, not repeats
            axes = [
                np.linspace(lo, hi, n if lo < hi else 1)
                for lo, hi, n in zip(low, high, counts, strict=True)
            ]
            shape, dtype = space.shape, space.dtype
            grid = [
                np.asarray(point, dtype=dtype).reshape(shape)
                for point in _product(axes, f"{space!r} with bins={bins!r}")
            ]
        elif isinstance(space, spaces.MultiDiscrete):
            nvec = np.asarray(space.nvec).reshape(-1)
            start = np.asarray(space.start).reshape(-1)
            axes = [np.arange(s, s + n) for s, n in zip(start, nvec, strict=True)]
            shape = space.shape
            grid = [
                np.asarray(point, dtype=space.dtype).reshape(shape)
                for point in _product(axes, repr(space))
            ]
        elif isinstance(space, spaces.MultiBinary):
            size = int(np.prod(space.shape))
            grid = [
                np.asarray(point, dtype=space.dtype).reshape(space.shape)
                for point in _product([np.arange(2)] * size, repr(space))
            ]
        else:
            raise TypeError(
                f"DiscreteActions: the action space is a {type(space).__name__} ({space!r}); it "
                "takes Box (finite bounds), MultiDiscrete and MultiBinary"
            )
        self.actions: list[np.ndarray] = grid
        self.action_space = spaces.Discrete(len(grid))  # type: ignore[assignment]

    def action(self, action: int) -> np.ndarray:
        """The task's action of index ``action``."""
        if not _is_int(action) or not 0 <= int(action) < len(self.actions):
            raise ValueError(
                f"DiscreteActions: action must be an index in [0, {len(self.actions)}), "
                f"got {action!r}"
            )
        return self.actions[int(action)].copy()


def _product(axes: list[np.ndarray], what: str) -> list[tuple[Any, ...]]:
    """Every combination of one value per axis, the first axis slowest; at most MAX_ACTIONS."""
    total = 1
    for axis in axes:
        total *= len(axis)
    if total > MAX_ACTIONS:
        raise ValueError(
            f"DiscreteActions: {what} gives {total:,} actions, more than {MAX_ACTIONS:,}; "
            "use fewer bins"
        )
    return list(itertools.product(*[axis.tolist() for axis in axes]))


def needs_discrete_actions(space: spaces.Space) -> bool:
    """Whether ``space`` is not already a Discrete action space starting at 0."""
    return not (isinstance(space, spaces.Discrete) and int(space.start) == 0)


def adapt_env(
    env: gym.Env[Any, Any], action_bins: int | Sequence[int] | None = None
) -> gym.Env[Any, Any]:
    """``env`` with :class:`BoxObservation` and :class:`DiscreteActions` where its spaces need
    them (``action_bins`` per Box action dimension, None: :data:`DEFAULT_ACTION_BINS`), else
    ``env`` itself. ``action_bins`` given for a task whose actions are not a Box is a
    ValueError naming the task: it would be ignored."""
    space = env.action_space
    if action_bins is not None and not isinstance(space, spaces.Box):
        task = env.spec.id if env.spec is not None else type(env.unwrapped).__name__
        raise ValueError(
            f"action_bins = {action_bins!r} only applies to a task with Box actions; "
            f"{task} has {space}"
        )
    if needs_box_observation(env.observation_space):
        env = BoxObservation(env)
    if isinstance(space, spaces.Discrete) and int(space.start) != 0:
        env = _ShiftedDiscrete(env)
    elif needs_discrete_actions(space):
        env = DiscreteActions(env, DEFAULT_ACTION_BINS if action_bins is None else action_bins)
    return env


class _ShiftedDiscrete(gym.ActionWrapper[Any, int, Any], RecordConstructorArgs):
    """``Discrete(n, start)`` as ``Discrete(n)``: index i is the task's action ``start + i``."""

    def __init__(self, env: gym.Env[Any, Any]) -> None:
        RecordConstructorArgs.__init__(self)
        gym.ActionWrapper.__init__(self, env)
        space = env.action_space
        assert isinstance(space, spaces.Discrete)
        self._start = int(space.start)
        self.action_space = spaces.Discrete(int(space.n))  # type: ignore[assignment]

    def action(self, action: int) -> int:
        """The task's action ``start + action``."""
        return self._start + int(action)
