"""Robot files: a small TOML file per robot, validated into a ``RobotSpec``.

```toml
name = "husky"                              # optional, default: the file's stem
description = "Clearpath Husky, skid-steered"  # optional
urdf = "pybullet_data:husky/husky.urdf"     # relative to this file, absolute, or in pybullet_data
drive = "differential"                      # "holonomic", "differential" or "ackermann"

[wheels]                # not for holonomic robots; joint names of the URDF
left = ["front_left_wheel", "rear_left_wheel"]      # differential
right = ["front_right_wheel", "rear_right_wheel"]   # differential
# driven = [...]        # ackermann: the wheels the motor turns (rear)
# steering = [...]      # ackermann: the steering hinges, in position control
# free = [...]          # ackermann: wheels that roll freely (motor force 0)
radius = 0.17775        # optional, metres at the URDF's own scale (default: measured)
track = 0.5708          # optional, metres between left and right wheels (default: measured)
# wheelbase = 0.325     # optional, ackermann: rear axle to front axle (default: measured)

[limits]
max_wheel_speed = 12.0  # rad/s of a driven wheel
wheel_torque = 60.0     # N m of each driven wheel's motor
max_turn_rate = 3.0     # optional, rad/s (differential; default: what the wheels allow)
braking = 9.0           # optional, m/s^2 (differential): the base's deceleration with its wheels
                        # stopped, which compass steps plan their stops with (default: 5)
# max_steering = 0.5    # optional, ackermann: radians (default: the hinges' limits)
# steering_torque = 10  # ackermann: N m of each steering hinge's motor

[footprint]
radius = "layout"       # optional: "layout" (the maze's robot radius) or maze units; absent:
                        # the URDF's own size. Used for planning and the kinematic sweep.

[sensors]               # optional defaults of this robot's lidar
lidar_rays = 36
lidar_range = 100.0     # maze units

[physics]               # optional defaults of the dynamic mode for this robot (env arguments win)
time_step = 0.0041667   # seconds per physics step, in [1/2000, 1/30] (default: the env's 1/240)
solver_iterations = 10  # constraint solver iterations per physics step, in [1, 100]

[physics.compass]       # optional: the same keys, with one action set only ("compass",
time_step = 0.0166667   # "native" or "continuous"); they override [physics]
solver_iterations = 5
```

A robot's physics step enters only its own envs; every step of a coarser one is checked
against 240 Hz by ``tests/bullet_maze/test_robot_physics.py`` (the zoo's compass steps end
where the fine step's do, within a stated tolerance).

Every error is a ``ValueError`` (a ``TypeError`` for a wrong type) naming the file and the field.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pybullet_data

from assets import ROBOT_DIR

DRIVES = ("holonomic", "differential", "ackermann")
"""How a robot is driven: a pushed rigid body, left/right wheel speeds, or a car's rear-wheel
speed and steering angle."""

PYBULLET_DATA = "pybullet_data:"
"""Prefix of a URDF path inside the ``pybullet_data`` package."""

MAX_ROBOT_FILE_BYTES = 64 * 1024
"""Largest robot file read (they are a few hundred bytes)."""

MAX_JOINTS_PER_LIST = 16
"""Most joints in one wheel or hinge list."""

_SCHEMA: dict[str, tuple[str, ...]] = {
    "": (
        "name",
        "description",
        "urdf",
        "drive",
        "wheels",
        "limits",
        "footprint",
        "sensors",
        "physics",
    ),
    "wheels": ("left", "right", "driven", "steering", "free", "radius", "track", "wheelbase"),
    "limits": (
        "max_wheel_speed",
        "wheel_torque",
        "max_turn_rate",
        "braking",
        "max_steering",
        "steering_torque",
    ),
    "footprint": ("radius",),
    "sensors": ("lidar_rays", "lidar_range"),
    "physics": ("time_step", "solver_iterations", "compass", "native", "continuous"),
}
"""Allowed keys of each table."""

ACTION_SET_NAMES = ("compass", "native", "continuous")
"""The action sets a ``[physics.<name>]`` table may name (``bullet_maze.action_sets``'s)."""

PHYSICS_KEYS = ("time_step", "solver_iterations")
"""What a ``[physics]`` table sets: the ``PhysicsParams`` fields of that name."""

TIME_STEP_BOUNDS = (1.0 / 2000.0, 1.0 / 30.0)
"""Seconds: a robot file's physics step (2 kHz to 30 Hz; coarser steps would let a wheeled
robot at top speed cross a thin wall's contact margin in one step)."""

MAX_BRAKING = 50.0
"""m/s^2: the largest ``limits.braking`` (about 5 g; a robot braked by its tyres' friction on
the floor, coefficient 1, stops at about 10)."""

SOLVER_ITERATION_BOUNDS = (1, 100)
"""A robot file's constraint solver iterations per physics step."""

_WHEEL_LISTS = {
    "differential": {"left": True, "right": True},
    "ackermann": {"driven": True, "steering": True, "free": False},
}
"""Joint lists each wheeled drive takes, and whether each is required."""


@dataclass(frozen=True)
class RobotSpec:
    """A robot: its body (a URDF), how it is driven and what it senses. Lengths of the body are
    metres at the URDF's own scale (they scale with the robot); the footprint and the lidar
    range are maze units."""

    name: str
    urdf: Path
    drive: str | None
    """One of ``DRIVES``; None for a bare URDF, whose drive is detected when it is loaded."""
    source: str
    """The robot file (or the bare URDF) that errors name."""
    description: str = ""
    left: tuple[str, ...] = ()
    """Differential: joints of the left wheels."""
    right: tuple[str, ...] = ()
    """Differential: joints of the right wheels."""
    driven: tuple[str, ...] = ()
    """Ackermann: joints of the wheels the motor turns."""
    steering: tuple[str, ...] = ()
    """Ackermann: the steering hinges (position control)."""
    free: tuple[str, ...] = ()
    """Ackermann: wheels left to roll (motor force 0)."""
    wheel_radius: float | None = None
    """Metres at the URDF's scale; None: measured from the wheels' collision shapes."""
    track: float | None = None
    """Metres between the left and right wheels; None: measured from the joints."""
    wheelbase: float | None = None
    """Ackermann: metres from the driven axle to the steered one; None: measured."""
    max_wheel_speed: float = 20.0
    """rad/s of a driven wheel: with the wheel radius, the robot's top speed."""
    wheel_torque: float = 20.0
    """N m of each driven wheel's motor (pybullet's motor force limit)."""
    max_turn_rate: float | None = None
    """Differential: rad/s; None: what opposite wheel speeds allow (2 v / track)."""
    braking: float | None = None
    """Differential: m/s^2, the base's deceleration with its wheels stopped (the compass
    controller's stops are planned with it); None: ``drives.DEFAULT_BRAKING``."""
    max_steering: float | None = None
    """Ackermann: radians; None: the smaller hinge limit."""
    steering_torque: float = 10.0
    """Ackermann: N m of each steering hinge's motor."""
    footprint_radius: float | str | None = None
    """Maze units, ``"layout"`` for the maze's robot radius, or None for the URDF's own size."""
    lidar_rays: int | None = None
    """This robot's default number of lidar rays (None: ``LidarParams``'s)."""
    lidar_range: float | None = None
    """This robot's default lidar range in maze units (None: ``LidarParams``'s)."""
    physics: tuple[tuple[str, str, float | int], ...] = ()
    """The ``[physics]`` tables as (action set or "" for every set, key, value)."""

    def physics_defaults(self, actions: str) -> dict[str, float | int]:
        """This robot's dynamic-mode settings with the action set ``actions``: ``[physics]``,
        then ``[physics.<actions>]`` over it."""
        defaults = {key: value for where, key, value in self.physics if where == ""}
        defaults.update({key: value for where, key, value in self.physics if where == actions})
        return defaults

    @property
    def wheels(self) -> tuple[str, ...]:
        """Every wheel joint the drive names."""
        return self.left + self.right + self.driven + self.free


def available_robots() -> list[str]:
    """Names of the robot files shipped in ``assets/robots/``."""
    return sorted(path.stem for path in ROBOT_DIR.glob("*.toml"))


def resolve_robot(robot: str | Path | RobotSpec) -> RobotSpec:
    """A robot name (``available_robots()``), a robot file path (``.toml``), a bare URDF path
    (``.urdf``, its drive detected when loaded) or a ``RobotSpec``."""
    if isinstance(robot, RobotSpec):
        return robot
    if not isinstance(robot, str | Path) or isinstance(robot, bool):
        raise TypeError(
            f"robot must be a robot name, a .toml robot file or a .urdf path, got "
            f"{type(robot).__name__}"
        )
    text = str(robot)
    if text.endswith(".urdf"):
        path = Path(robot)
        return RobotSpec(name=path.stem, urdf=path, drive=None, source=str(path))
    if text.endswith(".toml"):
        return load_robot_spec(Path(robot))
    if isinstance(robot, str) and (ROBOT_DIR / f"{robot}.toml").is_file():
        return load_robot_spec(ROBOT_DIR / f"{robot}.toml")
    raise ValueError(
        f"unknown robot {robot!r}: choose one of {available_robots()} or give a path to a "
        f".toml robot file or a .urdf file"
    )


def load_robot_spec(path: Path) -> RobotSpec:
    """Read and validate a robot file; every error names the file and the field."""
    if not path.is_file():
        raise FileNotFoundError(f"robot file not found: {path}")
    source = str(path)
    raw = path.read_bytes()
    if len(raw) > MAX_ROBOT_FILE_BYTES:
        raise ValueError(f"{source}: {len(raw):,} bytes; a robot file has at most 64 KiB")
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except UnicodeDecodeError as err:
        raise ValueError(f"{source}: not UTF-8 text ({err.reason})") from None
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"{source}: not valid TOML: {err}") from None
    except RecursionError:
        raise ValueError(f"{source}: nested too deeply to be a robot file") from None
    return spec_from_dict(data, source, base=path.parent)


def spec_from_dict(data: dict[str, Any], source: str, base: Path) -> RobotSpec:
    """Validate a parsed robot file; relative URDF paths are relative to ``base``."""
    read = _Reader(source)
    read.keys(data, "")
    tables = {key: read.table(data.get(key, {}), key) for key in _SCHEMA if key}
    for key, table in tables.items():
        read.keys(table, key)
    drive = read.choice(data.get("drive"), "drive", DRIVES)
    urdf = _urdf_path(read.string(data.get("urdf"), "urdf"), base)
    wheels, limits = tables["wheels"], tables["limits"]
    lists = _WHEEL_LISTS.get(drive, {})
    if drive == "holonomic" and wheels:
        raise ValueError(f"{source}: [wheels]: a holonomic robot is pushed as a body, not driven")
    for key in wheels:
        if key not in ("radius", "track", "wheelbase") and key not in lists:
            raise ValueError(f"{source}: wheels.{key}: not used by a {drive} drive")
    if drive != "ackermann":
        for key in ("wheelbase",):
            if key in wheels:
                raise ValueError(f"{source}: wheels.{key}: only an ackermann drive has one")
        for key in ("max_steering", "steering_torque"):
            if key in limits:
                raise ValueError(f"{source}: limits.{key}: only an ackermann drive steers")
    for key in ("max_turn_rate", "braking"):
        if drive != "differential" and key in limits:
            raise ValueError(f"{source}: limits.{key}: only a differential drive has one")
    if drive == "holonomic" and limits:
        raise ValueError(f"{source}: [limits]: a holonomic robot has no motors")
    joints = {
        key: read.joints(wheels.get(key), f"wheels.{key}", required)
        for key, required in lists.items()
    }
    named = [name for names in joints.values() for name in names]
    repeated = sorted({name for name in named if named.count(name) > 1})
    if repeated:
        raise ValueError(f"{source}: [wheels]: joint(s) {repeated} named in more than one list")
    footprint = tables["footprint"].get("radius")
    if footprint is not None and footprint != "layout":
        footprint = read.number(footprint, "footprint.radius", positive=True)
    sensors = tables["sensors"]
    defaults = RobotSpec(name="", urdf=urdf, drive=drive, source=source)
    name = data.get("name", Path(source).stem)
    return RobotSpec(
        name=read.string(name, "name"),
        urdf=urdf,
        drive=drive,
        source=source,
        description=read.string(data.get("description", ""), "description", empty=True),
        left=joints.get("left", ()),
        right=joints.get("right", ()),
        driven=joints.get("driven", ()),
        steering=joints.get("steering", ()),
        free=joints.get("free", ()),
        wheel_radius=read.optional(wheels.get("radius"), "wheels.radius"),
        track=read.optional(wheels.get("track"), "wheels.track"),
        wheelbase=read.optional(wheels.get("wheelbase"), "wheels.wheelbase"),
        max_wheel_speed=read.number(
            limits.get("max_wheel_speed", defaults.max_wheel_speed),
            "limits.max_wheel_speed",
            positive=True,
        ),
        wheel_torque=read.number(
            limits.get("wheel_torque", defaults.wheel_torque), "limits.wheel_torque", positive=True
        ),
        max_turn_rate=read.optional(limits.get("max_turn_rate"), "limits.max_turn_rate"),
        braking=read.optional(limits.get("braking"), "limits.braking", upper=MAX_BRAKING),
        max_steering=read.optional(
            limits.get("max_steering"), "limits.max_steering", upper=math.pi / 2
        ),
        steering_torque=read.number(
            limits.get("steering_torque", defaults.steering_torque),
            "limits.steering_torque",
            positive=True,
        ),
        footprint_radius=footprint,
        lidar_rays=None
        if "lidar_rays" not in sensors
        else read.integer(sensors["lidar_rays"], "sensors.lidar_rays"),
        lidar_range=read.optional(sensors.get("lidar_range"), "sensors.lidar_range"),
        physics=_physics(read, tables["physics"]),
    )


def _physics(read: _Reader, table: dict[str, Any]) -> tuple[tuple[str, str, float | int], ...]:
    """The ``[physics]`` table and its per-action-set tables, checked against their bounds."""
    settings: list[tuple[str, str, float | int]] = []
    for where, values, prefix in [("", table, "physics")] + [
        (name, table[name], f"physics.{name}") for name in ACTION_SET_NAMES if name in table
    ]:
        values = read.table(values, prefix)
        if where:
            unknown = sorted(set(values) - set(PHYSICS_KEYS))
            if unknown:
                raise ValueError(
                    f"{read.source}: unknown key(s) {unknown} at [{prefix}]; allowed: "
                    f"{list(PHYSICS_KEYS)}"
                )
        if "time_step" in values:
            low, high = TIME_STEP_BOUNDS
            step = read.number(values["time_step"], f"{prefix}.time_step", positive=True)
            if not low <= step <= high:
                raise ValueError(
                    f"{read.source}: field '{prefix}.time_step' must be in [{low:g}, {high:g}] "
                    f"seconds (2 kHz to 30 Hz), got {values['time_step']!r}"
                )
            settings.append((where, "time_step", step))
        if "solver_iterations" in values:
            low_i, high_i = SOLVER_ITERATION_BOUNDS
            iterations = read.integer(values["solver_iterations"], f"{prefix}.solver_iterations")
            if iterations > high_i:
                raise ValueError(
                    f"{read.source}: field '{prefix}.solver_iterations' must be in "
                    f"[{low_i}, {high_i}], got {iterations!r}"
                )
            settings.append((where, "solver_iterations", iterations))
    return tuple(settings)


def _urdf_path(text: str, base: Path) -> Path:
    if text.startswith(PYBULLET_DATA):
        return Path(pybullet_data.getDataPath()) / text[len(PYBULLET_DATA) :]
    path = Path(text)
    return path if path.is_absolute() else base / path


class _Reader:
    """Typed field reads whose errors name the file and the field."""

    def __init__(self, source: str) -> None:
        self.source = source

    def _fail(self, field: str, message: str, error: type[Exception] = ValueError) -> Exception:
        return error(f"{self.source}: field '{field}' {message}")

    def keys(self, table: dict[str, Any], name: str) -> None:
        allowed = _SCHEMA[name]
        unknown = sorted(set(table) - set(allowed))
        if unknown:
            where = f"[{name}]" if name else "top level"
            raise ValueError(
                f"{self.source}: unknown key(s) {unknown} at {where}; allowed: {list(allowed)}"
            )

    def table(self, value: Any, field: str) -> dict[str, Any]:
        if not isinstance(value, dict):
            raise self._fail(field, f"must be a table, got {value!r}", TypeError)
        return value

    def string(self, value: Any, field: str, empty: bool = False) -> str:
        if value is None:
            raise self._fail(field, "is required")
        if not isinstance(value, str):
            raise self._fail(field, f"must be a string, got {value!r}", TypeError)
        if not empty and not value.strip():
            raise self._fail(field, "must not be empty")
        if len(value) > 4096:
            raise self._fail(field, "is longer than 4,096 characters")
        return value

    def choice(self, value: Any, field: str, choices: tuple[str, ...]) -> str:
        text = self.string(value, field)
        if text not in choices:
            raise self._fail(field, f"must be one of {list(choices)}, got {text!r}")
        return text

    def number(
        self, value: Any, field: str, positive: bool = False, upper: float = math.inf
    ) -> float:
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self._fail(field, f"must be a number, got {value!r}", TypeError)
        if not math.isfinite(value):
            raise self._fail(field, f"must be finite, got {value!r}")
        if positive and value <= 0:
            raise self._fail(field, f"must be positive, got {value!r}")
        if value > upper:
            raise self._fail(field, f"must be at most {upper:g}, got {value!r}")
        return float(value)

    def optional(self, value: Any, field: str, upper: float = math.inf) -> float | None:
        return None if value is None else self.number(value, field, positive=True, upper=upper)

    def integer(self, value: Any, field: str) -> int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise self._fail(field, f"must be an integer, got {value!r}", TypeError)
        if value < 1:
            raise self._fail(field, f"must be positive, got {value!r}")
        return value

    def joints(self, value: Any, field: str, required: bool) -> tuple[str, ...]:
        if value is None:
            if required:
                raise self._fail(field, "is required (a list of joint names)")
            return ()
        if not isinstance(value, list) or not all(isinstance(v, str) and v for v in value):
            raise self._fail(field, f"must be a list of joint names, got {value!r}", TypeError)
        if required and not value:
            raise self._fail(field, "must name at least one joint")
        if len(value) > MAX_JOINTS_PER_LIST:
            raise self._fail(field, f"names more than {MAX_JOINTS_PER_LIST} joints")
        if len(set(value)) != len(value):
            raise self._fail(field, f"names a joint twice: {value!r}")
        return tuple(value)
