"""Perturbations of the simulation and domain randomisation (issue 11): what each one changes, in
which units, where it applies, and the levels an evaluation study uses.

Every perturbation is a keyword argument of the env (``gym.make("BulletMaze-v0",
mass_scale=1.5)``, or ``[env.params]`` of an experiment file). Its default is ``None``: not
set, and the env behaves exactly as without it, bit for bit, with the same draws from
``np_random``. A value is either fixed (a number) or a **range** from which every episode draws
its own value at ``reset``:

* ``[low, high]`` or ``(low, high)`` (a TOML array arrives as a list), or a NumPy array of two;
* ``{"low": low, "high": high}`` (a TOML inline table ``{ low = 0.5, high = 2.0 }``).

A range draws uniformly (``uniform(low, high)``; ``integers(low, high + 1)`` for the integer
``latency_steps``), one draw per randomised parameter in the order of ``PERTURBATIONS``, at every
reset and only when a range is given (``low == high`` is a range too, and draws). These draws,
and the observation and lidar noise, come from a generator of their own derived from the env's
``np_random`` without drawing from it (``child_generator``): the same seed gives the same draws,
and the action noise is the same stream with or without perturbations, so that a perturbed and
an unperturbed rollout of one seed can be compared step by step.

Values are strictly checked: a number (a bool is not one, nor a string), finite, within the
parameter's bounds, ``low <= high``, exactly two ends; every error names the parameter and the
value.

``applies(name, ...)`` says whether a perturbation means something for a mode, drive and
observation; the env refuses one that does not (a ``ValueError`` saying why) rather than ignore
it, so that no setting is silently without effect. ``level_settings(level, ...)`` turns a level
(``"none"``, ``"moderate"``, ``"strong"``; ``LEVELS``) into the settings that apply to a
condition. See ``docs/perturbations.md``.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from bullet_maze.params import MODES

DRIVE_KINDS = ("holonomic", "differential", "ackermann")
"""The drives a perturbation may depend on (``bullet_maze.robots.DRIVES``)."""


@dataclass(frozen=True)
class Perturbation:
    """One perturbation: its env keyword, unit, bounds and where it applies."""

    name: str
    unit: str
    low: float
    """Smallest value allowed (fixed or a range's end)."""
    high: float
    """Largest value allowed."""
    null: float
    """The value that perturbs nothing (1 for a scale, 0 otherwise; ``noise_variance``: the
    paper's 0.3)."""
    description: str
    integer: bool = False
    dynamic_only: bool = False
    """Only ``mode="dynamic"`` has it (the kinematic step is the drive's exact model: no mass,
    friction or motors)."""
    needs: str = ""
    """``"motors"`` (a wheeled drive), ``"heading"`` (a robot with a heading), ``"lidar"`` (a
    lidar observation), or nothing."""


MAX_NOISE_VARIANCE = 100.0
"""Largest ``noise_variance`` a range may reach (maze units squared: a standard deviation of 10,
two default steps); it sizes the dynamic substeps, so it is bounded."""

MAX_BIAS = 10.0
"""Largest actuation bias in maze units per step (two default steps)."""

PERTURBATIONS: tuple[Perturbation, ...] = (
    Perturbation(
        "noise_variance",
        "maze units^2",
        0.0,
        MAX_NOISE_VARIANCE,
        0.3,
        "variance of each of the two Gaussian draws of a step's actuation noise (section V.A; "
        "a fixed value is TaskParams' own, a range is drawn per episode)",
    ),
    Perturbation(
        "bias_along",
        "maze units per step",
        -MAX_BIAS,
        MAX_BIAS,
        0.0,
        "systematic over-travel along the commanded motion: a Move's nominal direction, a "
        "Twist's distance (in the sense of its sign); nothing for a motion of length 0",
    ),
    Perturbation(
        "bias_left",
        "maze units per step",
        -MAX_BIAS,
        MAX_BIAS,
        0.0,
        "systematic veer to the left: across a Move's nominal direction, or a turn of the "
        "Twist by bias_left / footprint radius (on the arc its rim travels, like the noise)",
    ),
    Perturbation(
        "floor_friction_scale",
        "factor",
        0.0,
        10.0,
        1.0,
        "the floor's lateral friction coefficient times this (pybullet multiplies the floor's "
        "and the robot's coefficients)",
        dynamic_only=True,
    ),
    Perturbation(
        "wheel_friction_scale",
        "factor",
        0.0,
        10.0,
        1.0,
        "the lateral friction coefficient of the robot's wheels (driven, steered and free; "
        "the whole body of a holonomic robot) times this",
        dynamic_only=True,
    ),
    Perturbation(
        "mass_scale",
        "factor",
        0.01,
        100.0,
        1.0,
        "every link's mass and inertia times this (the same shape, a denser robot); a "
        "holonomic robot's motion depends on it only through contacts that are not undone "
        "(revert_on_collision=False)",
        dynamic_only=True,
    ),
    Perturbation(
        "torque_scale",
        "factor",
        0.0,
        100.0,
        1.0,
        "motor strength: the force limit of every driven wheel and steering hinge times this",
        dynamic_only=True,
        needs="motors",
    ),
    Perturbation(
        "latency_steps",
        "env steps",
        0,
        100,
        0,
        "control latency: the action chosen at step t is executed at step t + k; the first k "
        "steps of an episode execute nothing (the robot stays at rest, no noise is drawn)",
        integer=True,
    ),
    Perturbation(
        "observation_noise",
        "maze units (std)",
        0.0,
        100.0,
        0.0,
        "Gaussian noise on the observed x and y (and achieved_goal), clipped to the arena; "
        "the true pose, the reward and info are unchanged",
    ),
    Perturbation(
        "heading_noise",
        "radians (std)",
        0.0,
        math.pi,
        0.0,
        "Gaussian noise on the observed heading, wrapped to [-pi, pi)",
        needs="heading",
    ),
    Perturbation(
        "lidar_noise",
        "maze units (std)",
        0.0,
        1000.0,
        0.0,
        "Gaussian noise on each lidar reading of a ray that hit something, clipped to "
        "[0, lidar_range]; a ray without a hit still reads lidar_range",
        needs="lidar",
    ),
)
"""Every perturbation, in the order in which a reset draws the randomised ones."""

BY_NAME: dict[str, Perturbation] = {p.name: p for p in PERTURBATIONS}
NAMES = tuple(BY_NAME)
"""The perturbations' env keywords."""

PHYSICAL = ("floor_friction_scale", "wheel_friction_scale", "mass_scale", "torque_scale")
"""The perturbations that change the bodies (applied with ``pybullet.changeDynamics`` and the
motors' limits, at construction if fixed and at every reset if drawn)."""

LEVELS: dict[str, dict[str, float | tuple[float, float]]] = {
    "none": {},
    "moderate": {
        "bias_along": (-0.25, 0.25),
        "bias_left": (-0.25, 0.25),
        "floor_friction_scale": (0.75, 1.25),
        "wheel_friction_scale": (0.75, 1.25),
        "mass_scale": (0.8, 1.25),
        "torque_scale": (0.8, 1.25),
        "latency_steps": (0, 1),
        "observation_noise": 0.5,
        "heading_noise": 0.05,
        "lidar_noise": 0.5,
    },
    "strong": {
        "bias_along": (-0.75, 0.75),
        "bias_left": (-0.75, 0.75),
        "floor_friction_scale": (0.5, 1.5),
        "wheel_friction_scale": (0.5, 1.5),
        "mass_scale": (0.5, 2.0),
        "torque_scale": (0.5, 1.5),
        "latency_steps": (1, 2),
        "observation_noise": 2.0,
        "heading_noise": 0.15,
        "lidar_noise": 2.0,
    },
}
"""Perturbation levels for evaluation and randomised training, chosen a priori (not tuned on any
result): ranges around the robot as built, drawn per episode, so that an evaluation averages
over both directions of a change (lighter and heavier). ``noise_variance`` is the task's own
noise and is left to the task. See ``docs/perturbations.md``."""


@dataclass(frozen=True)
class Range:
    """A domain-randomised value: each episode draws uniformly from [low, high]."""

    low: float
    high: float

    def __str__(self) -> str:
        return f"[{self.low!r}, {self.high!r}]"


Setting = float | int | Range
"""A perturbation's value: fixed, or a range."""


def parse_setting(name: str, value: Any) -> Setting:
    """A perturbation's value checked: a number, or a range ``[low, high]`` /
    ``{"low": ..., "high": ...}``; a ``TypeError`` or ``ValueError`` naming ``name`` and the
    value otherwise."""
    if name not in BY_NAME:
        raise TypeError(f"unknown perturbation {name!r}; the perturbations are {list(NAMES)}")
    spec = BY_NAME[name]
    what = _describe(spec)
    if isinstance(value, Mapping):
        keys = set(value)
        if keys != {"low", "high"}:
            raise ValueError(
                f"{name} = {value!r}: a range given as a table has exactly the keys 'low' and "
                f"'high'; {name} is {what}"
            )
        low = _number(spec, value["low"], f"{name} = {value!r}: 'low'")
        high = _number(spec, value["high"], f"{name} = {value!r}: 'high'")
        return _range(spec, low, high, value)
    if isinstance(value, list | tuple | np.ndarray):
        items = list(value.tolist()) if isinstance(value, np.ndarray) else list(value)
        if isinstance(value, np.ndarray) and value.ndim != 1:
            raise ValueError(f"{name} = {value!r}: a range is [low, high]; {name} is {what}")
        if len(items) != 2:
            raise ValueError(
                f"{name} = {value!r}: a range is [low, high], two numbers, got {len(items)} "
                f"item(s); {name} is {what}"
            )
        low = _number(spec, items[0], f"{name} = {value!r}: low")
        high = _number(spec, items[1], f"{name} = {value!r}: high")
        return _range(spec, low, high, value)
    return _number(spec, value, f"{name} = {value!r}")


def parse_settings(values: Mapping[str, Any]) -> dict[str, Setting]:
    """Every given perturbation checked (``None`` values are left out: not set), in the order
    of ``PERTURBATIONS``."""
    parsed = {
        name: parse_setting(name, value) for name, value in values.items() if value is not None
    }
    return {name: parsed[name] for name in NAMES if name in parsed}


def applies(
    name: str,
    *,
    mode: str,
    drive: str,
    has_heading: bool | None = None,
    lidar: bool = False,
    revert_on_collision: bool = True,
) -> str | None:
    """``None`` if the perturbation ``name`` means something for a robot of this drive in this
    mode with (or without) a heading and a lidar (``has_heading`` defaults to every drive but
    the holonomic one's); else the reason why it does not."""
    if name not in BY_NAME:
        raise ValueError(f"unknown perturbation {name!r}; the perturbations are {list(NAMES)}")
    if mode not in MODES:
        raise ValueError(f"mode must be one of {list(MODES)}, got {mode!r}")
    if drive not in DRIVE_KINDS:
        raise ValueError(f"drive must be one of {list(DRIVE_KINDS)}, got {drive!r}")
    heading = drive != "holonomic" if has_heading is None else has_heading
    spec = BY_NAME[name]
    if spec.dynamic_only and mode != "dynamic":
        return (
            f"{name} needs mode='dynamic': the kinematic step is the drive's exact model, "
            f"which has no masses, frictions or motors"
        )
    if name == "mass_scale" and drive == "holonomic" and revert_on_collision:
        return (
            f"{name} changes nothing for a holonomic robot whose touching steps are undone "
            f"(revert_on_collision=True): its velocity is set at every step and floor friction "
            f"slows any mass alike (measured: bit-identical rollouts); with "
            f"revert_on_collision=False its contacts depend on it"
        )
    if spec.needs == "motors" and drive == "holonomic":
        return (
            f"{name} needs a wheeled robot: a holonomic robot is pushed by setting its "
            f"velocity and has no motors"
        )
    if spec.needs == "heading" and not heading:
        return f"{name} needs a robot with a heading: this robot observes (x, y) only"
    if spec.needs == "lidar" and not lidar:
        return f"{name} needs a lidar: use observation='lidar' or observation='goal+lidar'"
    return None


def level_settings(
    level: str,
    *,
    mode: str,
    drive: str,
    has_heading: bool | None = None,
    lidar: bool = False,
    revert_on_collision: bool = True,
) -> dict[str, float | tuple[float, float]]:
    """The env keywords of a perturbation level (``LEVELS``) for one condition: the level's
    settings that apply to it (``applies``), ready for ``gym.make(..., **settings)``."""
    if not isinstance(level, str) or level not in LEVELS:
        raise ValueError(f"perturbation level must be one of {list(LEVELS)}, got {level!r}")
    return {
        name: value
        for name, value in LEVELS[level].items()
        if applies(
            name,
            mode=mode,
            drive=drive,
            has_heading=has_heading,
            lidar=lidar,
            revert_on_collision=revert_on_collision,
        )
        is None
    }


def draw(settings: Mapping[str, Setting], rng: np.random.Generator) -> dict[str, float | int]:
    """This episode's values: the fixed ones as given, each range drawn from ``rng`` in the order
    of ``PERTURBATIONS`` (uniform; integers inclusive of both ends)."""
    values: dict[str, float | int] = {}
    for name in NAMES:
        if name not in settings:
            continue
        setting = settings[name]
        if not isinstance(setting, Range):
            values[name] = setting
        elif BY_NAME[name].integer:
            values[name] = int(rng.integers(int(setting.low), int(setting.high) + 1))
        else:
            values[name] = float(rng.uniform(setting.low, setting.high))
    return values


def child_generator(rng: np.random.Generator) -> np.random.Generator:
    """A generator of its own for the perturbations' draws, derived from ``rng`` without drawing
    from it: seeded with the first child of ``rng``'s seed sequence (``SeedSequence.spawn``), so
    the same seed gives the same child, and the env's ``np_random`` keeps the action noise's
    stream as without perturbations. A generator without a seed sequence (made from a bare
    state) gives a ``jumped`` copy of its bit generator, or failing that a seed drawn from it."""
    bits = rng.bit_generator
    seed_seq = getattr(bits, "seed_seq", None)
    if isinstance(seed_seq, np.random.SeedSequence):
        return np.random.Generator(type(bits)(seed_seq.spawn(1)[0]))
    jumped = getattr(bits, "jumped", None)
    if jumped is not None:
        return np.random.Generator(jumped())
    return np.random.default_rng(int(rng.integers(2**63)))


def largest(setting: Setting | None, default: float = 0.0) -> float:
    """The largest magnitude a setting can take (a range's farther end)."""
    if setting is None:
        return default
    if isinstance(setting, Range):
        return max(abs(setting.low), abs(setting.high))
    return abs(setting)


def _describe(spec: Perturbation) -> str:
    kind = "an integer" if spec.integer else "a number"
    return f"{kind} ({spec.unit}) in [{spec.low:g}, {spec.high:g}], or a range [low, high]"


def _number(spec: Perturbation, value: Any, where: str) -> float | int:
    what = _describe(spec)
    if isinstance(value, bool | np.bool_):
        raise TypeError(f"{where}: {spec.name} must be {what}; a bool is not a number")
    if not isinstance(value, numbers.Real):
        raise TypeError(f"{where}: {spec.name} must be {what}; got {type(value).__name__}")
    if spec.integer:
        if not isinstance(value, numbers.Integral):
            raise TypeError(f"{where}: {spec.name} must be {what}; got a non-integer")
        number: float | int = int(value)
    else:
        number = float(value)
        if not math.isfinite(number):
            raise ValueError(f"{where}: {spec.name} must be finite ({what})")
    if not spec.low <= number <= spec.high:
        raise ValueError(f"{where}: {spec.name} must be {what}; out of bounds")
    return number


def _range(spec: Perturbation, low: float, high: float, value: Any) -> Range:
    if low > high:
        raise ValueError(
            f"{spec.name} = {value!r}: a range [low, high] needs low <= high, got low {low:g} "
            f"> high {high:g}"
        )
    return Range(low, high)


__all__ = [
    "LEVELS",
    "NAMES",
    "PERTURBATIONS",
    "PHYSICAL",
    "Perturbation",
    "Range",
    "Setting",
    "applies",
    "child_generator",
    "draw",
    "largest",
    "level_settings",
    "parse_setting",
    "parse_settings",
]
