"""Action sets (the env's ``actions=``): what an action asks of the robot, and the noise they
all share.

* ``"compass"`` (default, section V.A): ``Action`` UP, DOWN, LEFT, RIGHT, a displacement of
  ``step_size`` in that direction. Each drive realises it as it can: a holonomic body is pushed
  along it; a differential robot turns in place to face the target (or to face away from it,
  whichever needs the smaller turn: it may drive backwards) and drives there. A car cannot turn
  in place: it keeps its heading and reaches the target by a short manoeuvre of full-lock arcs
  (``bullet_maze.robots.car_compass``). A drive with neither ability is an error that names the
  other sets.
* ``"native"``: the drive's own commands. ``NativeAction`` FORWARD, BACKWARD, TURN_LEFT,
  TURN_RIGHT for differential robots (full speed ahead or astern, or a turn in place at the
  full turn rate) and cars (full speed ahead or astern, or full speed ahead at full lock to
  either side); a holonomic robot's native actions are the compass ones.
* ``"continuous"``: ``Box([-1, 1]^2, float32)`` of normalised velocity commands: (vx, vy) times
  ``step_size`` per step for a holonomic robot; (speed, turn rate) times the drive's top speed
  and turn rate for a differential robot; (speed, steering) for a car, the steering a fraction
  of its tightest curvature.

Native and continuous commands of wheeled robots last ``control_period`` seconds (both modes:
the kinematic mode follows the drive's exact model for that long, the dynamic mode holds the
motors' targets for that long).

**Noise, the same in every set.** Each step draws two independent Gaussians of mean 0 and
variance ``noise_variance`` (0.3, section V.A; maze units squared) from the env's seeded
``np_random``. A displacement (compass actions; every holonomic action) gets them on its x and
y. A velocity command of a robot with a heading gets the first on the distance its base
travels and the second on the arc the rim of its footprint travels (a turn of the second
divided by the footprint radius), so that both perturb the step by the same length. A car
realises only the turn its curvature limit allows over the distance.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any

import numpy as np
from gymnasium import spaces

from bullet_maze.actions import DIRECTIONS, NativeAction
from bullet_maze.robots import AckermannDrive, Command, DifferentialDrive, Move, Robot, Twist

ACTION_SETS = ("compass", "native", "continuous")
"""The values of the env's ``actions`` argument."""


@dataclass(frozen=True)
class ActionParams:
    """Settings of the native and continuous action sets; every field is a keyword argument of
    the env."""

    control_period: float = 0.1
    """Seconds one native or continuous command of a wheeled robot lasts (10 Hz control, a
    common rate for mobile robots; 24 physics steps at 240 Hz)."""

    def __post_init__(self) -> None:
        value = self.control_period
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise TypeError(f"control_period must be a number of seconds, got {value!r}")
        if not 0.0 < value <= 10.0:
            raise ValueError(f"control_period must be in (0, 10] seconds, got {value!r}")


class ActionSet(ABC):
    """Turns an action and the step's two noise draws into a command for the robot."""

    name: str
    space: spaces.Space[Any]

    @abstractmethod
    def command(self, action: Any, noise_a: float, noise_b: float) -> Command:
        """The command of a (checked) action, with the step's noise."""

    @abstractmethod
    def check(self, action: Any) -> Any:
        """The action in the form ``command`` takes, or a clear TypeError / ValueError."""


class CompassActions(ActionSet):
    """Displacements of ``step_size`` up, down, left or right (``Action``)."""

    name = "compass"

    def __init__(self, step_size: float) -> None:
        self.space = spaces.Discrete(len(DIRECTIONS))
        self.moves = [(float(mx), float(my)) for mx, my in DIRECTIONS * step_size]

    def command(self, action: int, noise_a: float, noise_b: float) -> Command:
        mx, my = self.moves[action]
        return Move(mx + noise_a, my + noise_b)

    def check(self, action: Any) -> int:
        return _discrete(action, "UP, DOWN, LEFT, RIGHT (bullet_maze.Action)")


class NativeActions(ActionSet):
    """``NativeAction`` for a wheeled robot: full speed ahead or astern, or a full turn."""

    name = "native"

    def __init__(self, robot: Robot, period: float) -> None:
        self.space = spaces.Discrete(len(NativeAction))
        drive = robot.drive
        distance = drive.max_speed * period
        if isinstance(drive, AckermannDrive):
            turn = drive.max_curvature * distance
            self.twists = [(distance, 0.0), (-distance, 0.0), (distance, turn), (distance, -turn)]
        else:
            assert isinstance(drive, DifferentialDrive)
            turn = drive.max_turn_rate * period
            self.twists = [(distance, 0.0), (-distance, 0.0), (0.0, turn), (0.0, -turn)]
        self.period = period
        self.rim = robot.radius

    def command(self, action: int, noise_a: float, noise_b: float) -> Command:
        distance, turn = self.twists[action]
        return Twist(distance + noise_a, turn + noise_b / self.rim, self.period)

    def check(self, action: Any) -> int:
        return _discrete(action, "FORWARD, BACKWARD, TURN_LEFT, TURN_RIGHT (NativeAction)")


class ContinuousActions(ActionSet):
    """Normalised velocity commands in ``[-1, 1]^2``; see the module docstring."""

    name = "continuous"

    def __init__(self, robot: Robot, period: float, step_size: float) -> None:
        self.space = spaces.Box(-1.0, 1.0, (2,), dtype=np.float32)
        drive = robot.drive
        self.period = period
        self.rim = robot.radius
        self.step_size = step_size
        self.kind = drive.kind
        self.speed = drive.max_speed * period
        self.turn = 0.0
        if isinstance(drive, DifferentialDrive):
            self.turn = drive.max_turn_rate * period
        elif isinstance(drive, AckermannDrive):
            self.turn = drive.max_curvature * self.speed

    def command(self, action: tuple[float, float], noise_a: float, noise_b: float) -> Command:
        a, b = action
        if self.kind == "holonomic":
            return Move(a * self.step_size + noise_a, b * self.step_size + noise_b)
        # A car's steering is a share of its curvature, times the distance it drives.
        turn = b * self.turn * a if self.kind == "ackermann" else b * self.turn
        return Twist(a * self.speed + noise_a, turn + noise_b / self.rim, self.period)

    def check(self, action: Any) -> tuple[float, float]:
        try:
            values = np.asarray(action, dtype=np.float64)
        except (TypeError, ValueError):
            values = np.array([math.nan])
        if values.shape != (2,) or isinstance(action, str | bytes):
            raise TypeError(f"action must be 2 numbers in [-1, 1], got {action!r}")
        if not np.all(np.isfinite(values)):
            raise ValueError(f"action must be finite, got {action!r}")
        if np.any(np.abs(values) > 1.0 + 1e-6):
            raise ValueError(f"action {action!r} lies outside the action space [-1, 1]^2")
        return float(values[0]), float(values[1])


def make_action_set(name: Any, robot: Robot, step_size: float, period: float) -> ActionSet:
    """The action set ``name`` for ``robot``; a clear error if the robot cannot realise it."""
    if not isinstance(name, str) or name not in ACTION_SETS:
        raise ValueError(f"actions must be one of {list(ACTION_SETS)}, got {name!r}")
    kind = robot.drive.kind
    if name == "compass" or (name == "native" and kind == "holonomic"):
        drive = robot.drive
        if not drive.turns_in_place and not (
            isinstance(drive, AckermannDrive) and drive.manoeuvre is not None
        ):
            raise ValueError(
                f"robot {robot.name!r} ({kind} drive) cannot turn in place, so it cannot "
                f"realise the compass actions (a step of step_size up, down, left or right); "
                f"use actions='native' or actions='continuous'"
            )
        return CompassActions(step_size)
    if name == "native":
        return NativeActions(robot, period)
    return ContinuousActions(robot, period, step_size)


def _discrete(action: Any, names: str) -> int:
    if isinstance(action, np.ndarray) and action.shape == ():
        action = action.item()
    if isinstance(action, bool) or not isinstance(action, int | np.integer):
        raise TypeError(f"action must be an integer in [0, 4) ({names}), got {action!r}")
    if not 0 <= action < 4:
        raise ValueError(f"action {action} is not in [0, 4) ({names})")
    return int(action)
