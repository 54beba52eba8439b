"""What an agent takes from an env, checked as it arrives.

A user's own env can hand an agent a NaN, an infinity, an observation of the wrong size, a
reward that is not a number, or the old gym API's four values. Unchecked, such a value either
poisons Q-bar silently (a NaN reward is accepted and every backup after it is NaN) or fails deep
inside the learner with a message that names neither the value nor where it came from. Here
each value is checked where it enters:

* :class:`CheckedEnv` wraps a user's env for ``learn``: every ``reset`` and ``step`` result is
  checked (Gymnasium's API: ``(obs, info)`` and ``(obs, reward, terminated, truncated, info)``)
  and passed on unchanged, so a valid env's run is the same, bit for bit;
* :func:`observation_vector` reads ``predict``'s observation.

Every defect is a ValueError naming the value, the call it came from (``env.step`` at step 12 of
the ``learn`` call's episode 3, or ``predict``) and what was expected. Gymnasium's own
``PassiveEnvChecker`` looks at the first ``reset`` and ``step`` only, and only warns.

An observation outside the bounds the agent was built for (its observation space's, or the
``bounds`` it was given) is not refused: envs whose declared box is a little narrower than what
they emit are common, and the agents still act there (the tree files such a point in its edge
leaves). It is not silent either: the first one in a ``learn`` call raises a
:class:`ObservationOutOfBounds` warning naming the input, its value, the bounds, the step and the
episode.

An env that never ends an episode (a user's env made directly, without ``gymnasium.make``'s
``TimeLimit``) would keep ``learn`` in its first episode for ever, silently. An episode that
reaches :data:`LONG_EPISODE_STEPS` steps, in an env that declares no time limit, raises a
:class:`LongEpisode` warning (once per ``learn`` call) naming the episode, the steps and the
remedy; the episode goes on, since an env may end its own episodes late.
"""

from __future__ import annotations

import math
import os
import sys
import warnings
from collections.abc import Sequence
from types import FrameType
from typing import Any

import numpy as np
from gymnasium.wrappers import TimeLimit


class ObservationOutOfBounds(UserWarning):
    """An env handed ``learn`` an observation outside the agent's bounds (module docstring)."""


class LongEpisode(UserWarning):
    """A ``learn`` episode has run :data:`LONG_EPISODE_STEPS` steps in an env that declares no
    time limit (module docstring)."""


LONG_EPISODE_STEPS = 100_000
"""Steps of one ``learn`` episode after which an env that declares no time limit is warned of:
20x the paper's cap of 5,000 and 100x Gymnasium's usual limits (200-1,000); about 10-15 s of
the general agent's steps on a classic task."""


def declared_time_limit(env: Any) -> int | None:
    """The step limit ``env`` declares: its spec's ``max_episode_steps`` or the smallest limit of
    a ``gymnasium.wrappers.TimeLimit`` in its wrapper chain; None when it declares none."""
    limits: list[int] = []
    seen = 0
    while env is not None and seen < 100:  # (a wrapper chain, never a cycle in practice)
        spec = getattr(env, "spec", None)
        spec_limit = getattr(spec, "max_episode_steps", None)
        if isinstance(spec_limit, int) and not isinstance(spec_limit, bool):
            limits.append(spec_limit)
        if isinstance(env, TimeLimit):
            limits.append(int(env._max_episode_steps))
        env = env.__dict__.get("env") if hasattr(env, "__dict__") else None
        seen += 1
    return min(limits) if limits else None


MAX_REWARD_MAGNITUDE = 1e100
"""The largest reward magnitude an agent takes: the learners square rewards (variances, the
measured reward unit), and the square of a larger one overflows a float."""


def observation_vector(obs: Any, n_inputs: int, where: str) -> list[float]:
    """``obs`` as a flat list of ``n_inputs`` finite floats; a ValueError naming the value and
    ``where`` it came from otherwise."""
    try:
        values = np.asarray(obs, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{where}: observation {obs!r} is not numeric ({exc})") from None
    if values.size != n_inputs:
        raise ValueError(
            f"{where}: observation has {values.size} values (shape {values.shape}), but the "
            f"agent's observation space has {n_inputs}"
        )
    flat = values.reshape(-1)
    finite = np.isfinite(flat)
    if not finite.all():
        bad = [int(i) for i in np.flatnonzero(~finite)]
        raise ValueError(
            f"{where}: observation {flat.tolist()} is not finite at input(s) {bad}; an agent "
            "takes finite observations (a diverged simulation, or a sensor with no reading?)"
        )
    return flat.tolist()


def checked_reward(reward: Any, where: str) -> float:
    """``reward`` as a float: a real number (not a bool), finite, at most
    :data:`MAX_REWARD_MAGNITUDE` in magnitude; a ValueError naming it otherwise."""
    if isinstance(reward, bool | np.bool_) or not isinstance(
        reward, int | float | np.integer | np.floating
    ):
        if isinstance(reward, np.ndarray) and reward.shape == ():
            return checked_reward(reward.item(), where)
        raise ValueError(
            f"{where}: reward {reward!r} ({type(reward).__name__}) is not a real number; "
            "an agent takes one scalar reward a step"
        )
    try:
        value = float(reward)
    except OverflowError:  # an int too large for a float
        raise ValueError(
            f"{where}: reward is an integer too large for a float ({len(str(abs(reward)))} "
            "digits); scale the rewards down (a reward wrapper)"
        ) from None
    if not math.isfinite(value):
        raise ValueError(f"{where}: reward {value!r} is not finite")
    if abs(value) > MAX_REWARD_MAGNITUDE:
        raise ValueError(
            f"{where}: reward {reward!r} is beyond +-{MAX_REWARD_MAGNITUDE:g}; scale the rewards "
            "down (a reward wrapper)"
        )
    return value


def deterministic_flag(value: Any) -> bool:
    """``predict``'s ``deterministic`` as a bool: True, False or a numpy bool; anything else
    (``-1``, ``"no"``, ``None``, which would count as true or false by accident) is a
    ValueError naming it."""
    if value is True or value is False:
        return value
    if isinstance(value, np.bool_):
        return bool(value)
    raise ValueError(f"predict: deterministic must be True or False, got {value!r}")


def _check_flag(value: Any, name: str, where: str) -> None:
    if isinstance(value, bool | np.bool_):
        return
    if isinstance(value, int | np.integer) and value in (0, 1):
        return
    raise ValueError(f"{where}: {name} {value!r} ({type(value).__name__}) is not a bool")


class CheckedEnv:
    """``env`` for ``learn``, with every ``reset`` and ``step`` result checked (module
    docstring) and passed on unchanged; any other attribute is ``env``'s own."""

    def __init__(
        self, env: Any, n_inputs: int, bounds: tuple[list[float], list[float]] | None = None
    ) -> None:
        self.env = env
        self.n_inputs = n_inputs
        self.episode = -1
        self.steps = 0
        self.bounds = bounds
        """The box the agent was built for; None once an observation outside it was warned of
        (once per ``learn`` call), or when not given."""
        self.long_episode = LONG_EPISODE_STEPS if declared_time_limit(env) is None else None
        """The step of an episode at which :class:`LongEpisode` is raised; None once it was
        (once per ``learn`` call), or when the env declares a time limit."""

    def __getattr__(self, name: str) -> Any:
        if name == "env":  # not set yet (a copy being built): no recursion
            raise AttributeError(name)
        return getattr(self.env, name)

    def reset(self, **kwargs: Any) -> Any:
        """``env.reset(**kwargs)``, checked: ``(obs, info)`` with a valid observation."""
        self.episode += 1
        self.steps = 0
        result = self.env.reset(**kwargs)
        where = f"env.reset (the learn call's episode {self.episode})"
        _check_shape(result, "(obs, info)", where)
        values = observation_vector(result[0], self.n_inputs, where)
        if self.bounds is not None:
            self._check_bounds(values, where)
        return result

    def step(self, action: Any) -> Any:
        """``env.step(action)``, checked: five values, a valid observation and reward, bool
        ``terminated`` and ``truncated``, a dict ``info``."""
        if self.steps == self.long_episode:  # that many steps taken, none ended the episode
            self._warn_long_episode()
        self.steps += 1
        result = self.env.step(action)
        if type(result) is tuple and len(result) == 5:
            values = _plain_step(*result, self.n_inputs)
            if values is not None:
                bounds = self.bounds
                if bounds is not None:
                    for v, lo, hi in zip(values, bounds[0], bounds[1], strict=True):  # per step
                        if not lo <= v <= hi:
                            self._check_bounds(values, None)
                            break
                return result
        where = self._step_where()
        _check_shape(result, "(obs, reward, terminated, truncated, info)", where)
        obs, reward, terminated, truncated, info = result
        values = observation_vector(obs, self.n_inputs, where)
        checked_reward(reward, where)
        _check_flag(terminated, "terminated", where)
        _check_flag(truncated, "truncated", where)
        if not isinstance(info, dict):
            raise ValueError(f"{where}: info {info!r} ({type(info).__name__}) is not a dict")
        if self.bounds is not None:
            self._check_bounds(values, where)
        return result

    def _warn_long_episode(self) -> None:
        warnings.warn(
            f"env.step (the learn call's episode {self.episode}): the episode has run "
            f"{self.steps:,} steps without ending "
            "(terminated or truncated), and the env declares no time limit; learn returns only "
            "when each of its episodes ends. Give the env a time limit "
            "(gymnasium.wrappers.TimeLimit(env, max_episode_steps=...), or register it with "
            "max_episode_steps and make it with gymnasium.make). Warned once per learn call.",
            LongEpisode,
            stacklevel=_caller_level(),
        )
        self.long_episode = None

    def _step_where(self) -> str:
        return f"env.step (step {self.steps} of the learn call's episode {self.episode})"

    def _check_bounds(self, values: Sequence[float], where: str | None) -> None:
        """Warn (once) if ``values`` leave :attr:`bounds`; then stop looking. ``where`` None:
        this step's (written only when it is needed)."""
        assert self.bounds is not None
        low, high = self.bounds
        for i, (v, lo, hi) in enumerate(zip(values, low, high, strict=True)):  # (first: named)
            if not lo <= v <= hi:
                self.bounds = None
                if where is None:
                    where = self._step_where()
                warnings.warn(
                    f"{where}: observation input {i} = {v!r} lies outside the bounds the agent "
                    f"was built for, [{lo!r}, {hi!r}] (its observation space's, or the bounds "
                    "it was given); the agent acts on it, but its partition or tiling was laid "
                    "out for that box. Declare the range the env's observations take (or give "
                    "the agent bounds=(low, high)). Warned once per learn call.",
                    ObservationOutOfBounds,
                    stacklevel=_caller_level(),
                )
                return


def _caller_level() -> int:
    """The ``stacklevel`` that points a warning at the first frame outside this package (the
    user's ``learn`` call), however deep the agent's loop called it from."""
    package = os.path.dirname(os.path.abspath(__file__))
    frame: FrameType | None = sys._getframe(1)
    level = 1
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(package):
        frame = frame.f_back
        level += 1
    return level


def _plain_step(
    obs: Any, reward: Any, terminated: Any, truncated: Any, info: Any, n_inputs: int
) -> Sequence[float] | None:
    """The observation's values if a step's values are of the common valid kinds (a numeric
    ndarray, or a flat list or tuple of Python or numpy floats and ints, of the right size,
    finite; such a reward within bounds; bools; a dict): ``step``'s quick path, about a
    microsecond. None means "check closely", not "invalid"."""
    if type(terminated) is not bool or type(truncated) is not bool or type(info) is not dict:
        return None
    kind_of_reward = type(reward)
    if kind_of_reward not in _PLAIN_REWARDS:
        return None
    if kind_of_reward is np.float32:  # (compared with the bound, it would cast 1e100 to float32:
        reward = float(reward)  # an overflow warning every step)
    if not -MAX_REWARD_MAGNITUDE <= reward <= MAX_REWARD_MAGNITUDE:  # NaN fails too
        return None
    if type(obs) is np.ndarray:
        if obs.size != n_inputs:
            return None
        kind = obs.dtype.kind
        if kind not in "fiub":
            return None
        values = obs.ravel().tolist()
        if kind == "f" and not all(map(math.isfinite, values)):
            return None
        return values  # (integers and bools are finite)
    if type(obs) is list or type(obs) is tuple:
        if len(obs) != n_inputs or not all(type(v) in _PLAIN_REWARDS for v in obs):
            return None
        return obs if all(map(math.isfinite, obs)) else None
    return None


_PLAIN_REWARDS = (float, int, np.float64, np.float32)
"""The scalar types of the quick path (bool is not among them: a bool reward is refused)."""


def _check_shape(result: Any, api: str, where: str) -> None:
    """A ValueError at ``where`` unless ``result`` is a tuple of as many values as ``api``
    names (Gymnasium's API)."""
    if isinstance(result, tuple) and len(result) == api.count(",") + 1:
        return
    got = (
        f"{len(result)} values"
        if isinstance(result, tuple)
        else (f"a {type(result).__name__}, not a tuple")
    )
    raise ValueError(
        f"{where} returned {got}; Gymnasium's API returns {api} (an env written for the old "
        "gym API needs a compatibility wrapper, such as shimmy's)"
    )
