"""Robots the maze can drive: the ``Robot`` interface and its implementations.

* ``HolonomicRobot``: any URDF moved as a rigid body in the plane with no heading, like the
  paper's point robot (section V.A); the default disc (``assets/robots/disc.urdf``) is one.
* ``HuskyRobot``: Clearpath's skid-steered husky from ``pybullet_data``. It reaches the same
  four-direction intent by turning in place towards the step, then driving it, through its
  wheel joints; its observation adds the heading.

A robot's size in the maze is the radius of its footprint: the largest horizontal distance from
its base to its collision geometry, measured with pybullet rays when it is loaded. Kinematic
collision checks sweep a disc of that radius.
"""

from __future__ import annotations

import ctypes
import math
import os
import sys
import tempfile
import xml.etree.ElementTree as ET
from abc import ABC, abstractmethod
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import NamedTuple

import numpy as np
import pybullet as pb
import pybullet_data

from assets import ROBOT_DIR
from bullet_maze.params import METRES_PER_UNIT, PhysicsParams
from bullet_maze.world import World

ROBOT_NAMES = ("disc", "husky")
"""Built-in robots; any other ``robot=`` value must be a path to a URDF file."""

DISC_URDF = ROBOT_DIR / "disc.urdf"
HUSKY_URDF = Path(pybullet_data.getDataPath()) / "husky" / "husky.urdf"

_RAY_ANGLES = 120
_RAY_HEIGHTS = 8


def _yaw(orientation: tuple[float, float, float, float]) -> float:
    qx, qy, qz, qw = orientation
    return math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))


def _quaternion(yaw: float) -> tuple[float, float, float, float]:
    return (0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0))


_STILL = (0.0, 0.0, 0.0)
"""A zero linear or angular velocity."""


class RobotState(NamedTuple):
    """What ``Robot.snapshot`` keeps: pybullet's base pose and the joint positions."""

    position: tuple[float, float, float]
    """Base position in metres."""
    orientation: tuple[float, float, float, float]
    """Base orientation quaternion (x, y, z, w)."""
    joints: tuple[float, ...]
    """Joint positions in joint order."""


def wrap_angle(angle: float) -> float:
    """The angle in [-pi, pi)."""
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


@contextmanager
def _native_output_captured() -> Iterator[list[str]]:
    """Capture what C code writes to the process's stdout and stderr (pybullet's URDF importer
    warns there about every link without inertial data, once per load, and explains its
    failures there). The yielded list receives the text when the block ends."""
    captured: list[str] = []
    try:
        libc = ctypes.CDLL(None)  # the C library already loaded (not available on Windows)
        sys.stdout.flush()
        sys.stderr.flush()
        saved = [os.dup(1), os.dup(2)]
    except (AttributeError, OSError, TypeError, ValueError):  # no C library or no real fds
        yield captured
        return
    with tempfile.TemporaryFile() as sink:
        try:
            os.dup2(sink.fileno(), 1)
            os.dup2(sink.fileno(), 2)
            yield captured
        finally:
            libc.fflush(None)
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            for fd in saved:
                os.close(fd)
            sink.seek(0)
            captured.append(sink.read().decode(errors="replace"))


def load_urdf(client: int, path: Path, scale: float = 1.0) -> int:
    """Load a URDF at the origin; a clear error naming the path instead of a pybullet one."""
    if not path.is_file():
        raise FileNotFoundError(f"robot URDF not found: {path}")
    with _native_output_captured() as output:
        try:
            body = pb.loadURDF(
                str(path), [0.0, 0.0, 0.0], globalScaling=scale, physicsClientId=client
            )
        except pb.error as err:
            failure: pb.error | None = err
        else:
            failure = None
    if failure is not None:
        detail = " ".join("".join(output).split())[-300:]
        raise ValueError(
            f"robot URDF {path} could not be loaded by pybullet: {failure}"
            + (f" ({detail})" if detail else "")
        ) from failure
    return body


def husky_urdf_text() -> str:
    """``husky.urdf`` from ``pybullet_data`` with its frame-only links folded into ``base_link``.

    The IMU mount, top plate, user rail and bumpers are links of their own on fixed joints,
    with no mass or collision shape: their visuals move into ``base_link`` at the joints'
    origins and the links go, which leaves the look and the contacts as they were and makes a
    physics step about a fifth cheaper (five fewer links in pybullet's articulated body). Mesh
    paths become absolute so that the text loads from anywhere.
    """
    robot = ET.parse(HUSKY_URDF).getroot()
    links = {link.get("name"): link for link in robot.findall("link")}
    base = links["base_link"]
    for joint in robot.findall("joint"):
        parent, child = joint.find("parent"), joint.find("child")
        if parent is None or child is None or parent.get("link") != "base_link":
            continue
        link = links[child.get("link", "")]
        visuals = link.findall("visual")
        if (
            joint.get("type") != "fixed"
            or link.find("inertial") is not None
            or link.find("collision") is not None
            or any(_has_offset(visual.find("origin")) for visual in visuals)
        ):
            continue
        origin = joint.find("origin")
        for visual in visuals:
            own_origin = visual.find("origin")
            if own_origin is not None:
                visual.remove(own_origin)
            if origin is not None:
                visual.insert(0, origin)
            base.append(visual)
        robot.remove(link)
        robot.remove(joint)
    for mesh in robot.iter("mesh"):
        mesh.set("filename", str(HUSKY_URDF.parent / mesh.get("filename", "")))
    return ET.tostring(robot, encoding="unicode")


def _has_offset(origin: ET.Element | None) -> bool:
    """Whether a URDF ``<origin>`` moves or turns its element."""
    if origin is None:
        return False
    return any(float(v) != 0.0 for key in ("xyz", "rpy") for v in origin.get(key, "0 0 0").split())


def footprint(client: int, body: int) -> tuple[float, float]:
    """(radius, lowest z) of a body at rest at the origin, in metres.

    The radius is the largest horizontal distance from the base to the body's collision geometry,
    found by casting rays inwards at every angle and height; call it before anything else stands
    near the body.
    """
    lows, highs = [], []
    for link in range(-1, pb.getNumJoints(body, physicsClientId=client)):
        low, high = pb.getAABB(body, link, physicsClientId=client)
        lows.append(low)
        highs.append(high)
    low, high = np.min(lows, axis=0), np.max(highs, axis=0)
    base = np.array(pb.getBasePositionAndOrientation(body, physicsClientId=client)[0])
    reach = 2.0 * float(np.max(np.abs(np.r_[low[:2], high[:2]] - np.r_[base[:2], base[:2]])))
    angles = np.linspace(0.0, 2.0 * math.pi, _RAY_ANGLES, endpoint=False)
    heights = np.linspace(low[2], high[2], _RAY_HEIGHTS + 2)[1:-1]
    a, z = np.meshgrid(angles, heights)
    starts = np.stack([base[0] + reach * np.cos(a), base[1] + reach * np.sin(a), z], -1)
    ends = np.stack([np.full_like(a, base[0]), np.full_like(a, base[1]), z], -1)
    hits = pb.rayTestBatch(
        starts.reshape(-1, 3).tolist(), ends.reshape(-1, 3).tolist(), physicsClientId=client
    )
    radii = [math.hypot(hit[3][0] - base[0], hit[3][1] - base[1]) for hit in hits if hit[0] == body]
    if not radii:
        raise ValueError("robot has no collision geometry to measure its footprint")
    return max(radii), float(low[2])


class Robot(ABC):
    """A body the maze env drives; positions in maze units, heading in radians from +x."""

    name: str
    has_heading: bool
    radius: float
    """Footprint radius in maze units."""
    body_id: int
    reach_margin: float
    """Maze units a dynamic step may carry the robot beyond its commanded length (overshoot);
    within the step's length plus this margin of a solid, contacts are checked every substep."""

    def __init__(self, client: int) -> None:
        self.client = client
        self.scale = 1.0
        """globalScaling applied to the URDF."""
        self._rest_z = 0.0
        self._joints = range(0)
        self._physics = PhysicsParams()

    def _load_scaled(self, path: Path, radius: float | None) -> None:
        """Load the URDF, rescaled so that its footprint has ``radius`` (maze units) if given."""
        body = load_urdf(self.client, path)
        try:
            natural, low = footprint(self.client, body)
        except ValueError as err:
            raise ValueError(f"robot URDF {path}: {err}") from err
        scale = 1.0 if radius is None else radius * METRES_PER_UNIT / natural
        if scale != 1.0:
            pb.removeBody(body, physicsClientId=self.client)
            body = load_urdf(self.client, path, scale)
        self.body_id = body
        self.scale = scale
        self.radius = natural * scale / METRES_PER_UNIT
        self._joints = range(pb.getNumJoints(body, physicsClientId=self.client))
        base_z = pb.getBasePositionAndOrientation(body, physicsClientId=self.client)[0][2]
        self._rest_z = base_z - low * scale

    def place(self, x: float, y: float, heading: float) -> None:
        """Teleport the robot, at rest, to (x, y) facing ``heading``."""
        s = METRES_PER_UNIT
        pb.resetBasePositionAndOrientation(
            self.body_id,
            (x * s, y * s, self._rest_z),
            _quaternion(heading),
            physicsClientId=self.client,
        )
        pb.resetBaseVelocity(
            self.body_id, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), physicsClientId=self.client
        )

    # The calls of the dynamic step name the client positionally: pybullet parses a keyword
    # argument for about 0.25 us, a twentieth of a physics step.

    def position(self) -> tuple[float, float]:
        """(x, y) of the robot's base in maze units."""
        (x, y, _), _ = pb.getBasePositionAndOrientation(self.body_id, self.client)
        return x / METRES_PER_UNIT, y / METRES_PER_UNIT

    def pose(self) -> tuple[float, float, float]:
        """(x, y, heading) of the robot's base in maze units and radians."""
        position, orientation = pb.getBasePositionAndOrientation(self.body_id, self.client)
        s = METRES_PER_UNIT
        return position[0] / s, position[1] / s, _yaw(orientation)

    def joint_states(self) -> tuple[float, ...]:
        """Joint positions (radians or metres, in joint order)."""
        if not self._joints:
            return ()
        states = pb.getJointStates(self.body_id, self._joints, physicsClientId=self.client)
        return tuple(state[0] for state in states)

    def snapshot(self) -> RobotState:
        """The robot's base pose and joint positions, for ``restore``."""
        position, orientation = pb.getBasePositionAndOrientation(self.body_id, self.client)
        return RobotState(position, orientation, self.joint_states())

    def restore(self, state: RobotState) -> None:
        """Put the robot back as ``snapshot`` found it, at rest (undoes a dynamic step)."""
        body, client = self.body_id, self.client
        pb.resetBasePositionAndOrientation(body, state.position, state.orientation, client)
        pb.resetBaseVelocity(body, _STILL, _STILL, client)
        for joint, position in zip(self._joints, state.joints, strict=True):
            pb.resetJointState(body, joint, position, 0.0, physicsClientId=client)

    def configure(self, physics: PhysicsParams) -> None:
        """Keep the settings ``drive`` runs with; subclasses also set their dynamics here."""
        self._physics = physics

    @abstractmethod
    def drive(self, dx: float, dy: float, watch: World | None, stop_on_touch: bool = False) -> bool:
        """Dynamic mode: move by (dx, dy) maze units through physics substeps, with the
        settings given to ``configure``.

        If ``watch`` is given, contacts with its walls and obstacles are checked after every
        substep (pybullet reports those found at the start of the substep, so the first, which
        sees the pose before the move, is skipped and the final pose is checked explicitly);
        returns whether any occurred. With ``stop_on_touch`` the substeps end at the first
        contact, for a caller that undoes a touching step anyway.
        """


class HolonomicRobot(Robot):
    """A URDF moved in the plane as a rigid body without heading (the disc, a user's URDF).

    Dynamic mode commands the base velocity that covers the step in ``substeps * time_step``
    seconds at the start of the step; then mass, ground friction and contacts act freely through
    the substeps (linear and angular damping are switched off so that only they act).
    """

    has_heading = False
    reach_margin = 0.5  # friction only shortens the commanded move; contacts need proximity

    def __init__(
        self, client: int, path: Path, radius: float | None = None, name: str | None = None
    ) -> None:
        super().__init__(client)
        self.name = name or path.stem
        self._load_scaled(path, radius)
        self._rate = 0.0
        self._substeps = range(0)

    def configure(self, physics: PhysicsParams) -> None:
        super().configure(physics)
        pb.changeDynamics(
            self.body_id, -1, linearDamping=0.0, angularDamping=0.0, physicsClientId=self.client
        )
        self._rate = METRES_PER_UNIT / (physics.substeps * physics.time_step)
        self._substeps = range(physics.substeps)

    def drive(self, dx: float, dy: float, watch: World | None, stop_on_touch: bool = False) -> bool:
        client, body, rate = self.client, self.body_id, self._rate
        step = pb.stepSimulation
        pb.resetBaseVelocity(body, (dx * rate, dy * rate, 0.0), _STILL, client)
        if watch is None:
            for _ in self._substeps:
                step(client)
            return False
        touched = False
        step(client)
        for _ in self._substeps[1:]:
            step(client)
            if not touched and watch.touching(body):
                if stop_on_touch:
                    return True
                touched = True
        return watch.touching_now(body) or touched


class HuskyRobot(Robot):
    """Clearpath's husky from ``pybullet_data``, rescaled so that its footprint has the given
    radius (by default the layout's robot radius, so that it fits the same gaps as the disc).

    Dynamic mode: turn in place towards the step's target point, then drive to it, both by
    velocity commands to the four wheel joints (skid steering); see ``drive``. Kinematic mode:
    the turn and the move are teleports.
    """

    has_heading = True
    name = "husky"
    WHEELS = ("front_left_wheel", "rear_left_wheel", "front_right_wheel", "rear_right_wheel")
    WHEEL_RADIUS = 0.17775
    """Metres at the URDF's own scale (``husky.urdf``)."""
    TRACK = 0.5708
    """Distance between left and right wheels in metres at the URDF's own scale."""
    DUMMY_MASS = 0.01
    """kg given to the URDF's links that have no inertial data."""
    MAX_WHEEL_SPEED = 40.0
    """rad/s of a wheel."""
    WHEEL_FORCE = 200.0
    """Newton-metres of each wheel motor."""
    MAX_SPEED = 2.0
    """m/s: forward speed command limit."""
    MAX_SPIN = 8.0
    """rad/s: turn rate command limit."""
    TURN_GAIN = 15.0
    """1/s: turn rate command per radian of heading error while turning in place."""
    STEER_GAIN = 10.0
    """1/s: turn rate command per radian of heading error while driving."""
    DRIVE_DECELERATION = 8.0
    """m/s^2: the forward speed command is at most the speed from which the robot stops in the
    remaining distance at this deceleration (it brakes at about 10 m/s^2 on the floor)..."""
    DRIVE_GAIN = 16.0
    """...and, near the end, this gain (1/s) times the remaining distance in metres."""
    HEADING_TOLERANCE = 0.05
    """Radians: the turn ends when the heading is this close to the bearing of the target..."""
    SETTLED_SPIN = 0.3
    """...and the yaw rate (rad/s) is below this."""
    DISTANCE_TOLERANCE = 0.05
    """Maze units: the drive ends when the target is this close ahead or behind..."""
    SETTLED_SPEED = 0.1
    """...and the speed (m/s) is below this."""
    AIM_RADIUS = 1.0
    """Maze units: closer than this to the target the robot keeps its last bearing instead of
    re-aiming at a point that is nearly under it."""
    CONTROL_PERIOD = 2
    """Physics steps per control update (120 Hz at the default 240 Hz physics); contacts are
    still watched after every physics step."""

    def __init__(self, client: int, radius: float | None = None) -> None:
        super().__init__(client)
        with tempfile.TemporaryDirectory() as folder:
            path = Path(folder) / "husky.urdf"
            path.write_text(husky_urdf_text())
            self._load_scaled(path, radius)
        # A skid-steered turn in place swings the base round a pivot near the rear axle, about
        # half the footprint's radius away: the base may stray the radius from its start.
        self.reach_margin = self.radius
        names = {
            pb.getJointInfo(self.body_id, j, physicsClientId=client)[1].decode(): j
            for j in range(pb.getNumJoints(self.body_id, physicsClientId=client))
        }
        self._wheels = [names[wheel] for wheel in self.WHEELS]
        self._wheel_speeds = (math.nan, math.nan)  # the last command sent: (left, right) rad/s
        # husky.urdf gives no inertial data for its frame-only links (footprint, IMU, plates,
        # bumpers); pybullet then assumes 1 kg and 1 kg m^2 each, which makes the robot turn
        # several times slower than its real inertia allows. Make them near massless.
        for link in [-1, *names.values()]:
            mass, _, inertia = pb.getDynamicsInfo(self.body_id, link, physicsClientId=client)[:3]
            if mass == 1.0 and len(set(inertia)) == 1:
                pb.changeDynamics(
                    self.body_id,
                    link,
                    mass=self.DUMMY_MASS,
                    localInertiaDiagonal=[self.DUMMY_MASS * 1e-3] * 3,
                    physicsClientId=client,
                )

    def configure(self, physics: PhysicsParams) -> None:
        super().configure(physics)
        self._command(0.0, 0.0)

    def place(self, x: float, y: float, heading: float) -> None:
        super().place(x, y, heading)
        self._wheel_speeds = (math.nan, math.nan)  # a restored world may have reset the motors

    def _command(self, forward: float, turn: float) -> None:
        """Wheel speeds for a forward speed (m/s) and a turn rate (rad/s); a command equal to
        the last one is not sent again."""
        r = self.WHEEL_RADIUS * self.scale
        half_track = self.TRACK * self.scale / 2.0
        top = self.MAX_WHEEL_SPEED
        left = min(top, max(-top, (forward - turn * half_track) / r))
        right = min(top, max(-top, (forward + turn * half_track) / r))
        if (left, right) == self._wheel_speeds:
            return
        self._wheel_speeds = (left, right)
        pb.setJointMotorControlArray(
            self.body_id,
            self._wheels,
            pb.VELOCITY_CONTROL,
            targetVelocities=[left, left, right, right],
            forces=[self.WHEEL_FORCE] * 4,
            physicsClientId=self.client,
        )

    def drive(self, dx: float, dy: float, watch: World | None, stop_on_touch: bool = False) -> bool:
        """Turn in place towards the target point, the start plus (dx, dy), then drive to it.

        Both phases aim at the point itself, not along the step's direction: a skid-steered
        turn in place also moves the base (the wheels' pivot is not under it, up to 2 units
        in a half turn), and aiming along the direction would carry that offset to the end.
        The turn is proportional control of the heading; the drive commands the speed that can
        still stop at the point (bounded by ``MAX_SPEED``), steering at it and slowed by the
        cosine of the heading error. ``max_turn_substeps`` and ``max_drive_substeps`` bound the
        phases.
        """
        physics = self._physics
        client, body = self.client, self.body_id
        s = METRES_PER_UNIT
        (x0, y0, _), _ = pb.getBasePositionAndOrientation(body, client)
        tx, ty = x0 + dx * s, y0 + dy * s  # metres, like everything below
        bearing = math.atan2(dy, dx)
        aim, tolerance = self.AIM_RADIUS * s, self.DISTANCE_TOLERANCE * s
        substep = 0
        touched = False
        for turning, limit in (
            (True, physics.max_turn_substeps),
            (False, physics.max_drive_substeps),
        ):
            end = substep + limit
            while substep < end:
                (x, y, _), orientation = pb.getBasePositionAndOrientation(body, client)
                (vx, vy, _), (_, _, spin) = pb.getBaseVelocity(body, client)
                heading = _yaw(orientation)
                ex, ey = tx - x, ty - y
                if math.hypot(ex, ey) > aim:
                    bearing = math.atan2(ey, ex)
                error = wrap_angle(bearing - heading)
                if turning:
                    if abs(error) < self.HEADING_TOLERANCE and abs(spin) < self.SETTLED_SPIN:
                        break
                    forward, gain = 0.0, self.TURN_GAIN
                else:
                    remaining = ex * math.cos(heading) + ey * math.sin(heading)
                    if abs(remaining) < tolerance and math.hypot(vx, vy) < self.SETTLED_SPEED:
                        break
                    speed = min(
                        self.MAX_SPEED,
                        math.sqrt(2.0 * self.DRIVE_DECELERATION * abs(remaining)),
                        self.DRIVE_GAIN * abs(remaining),
                    )
                    forward = math.copysign(speed, remaining) * max(0.0, math.cos(error))
                    gain = self.STEER_GAIN
                self._command(forward, min(self.MAX_SPIN, max(-self.MAX_SPIN, gain * error)))
                for _ in range(self.CONTROL_PERIOD):
                    pb.stepSimulation(client)
                    substep += 1
                    if watch is not None and substep > 1 and not touched:
                        touched = watch.touching(body)
                        if touched and stop_on_touch:
                            self._command(0.0, 0.0)
                            return True
        self._command(0.0, 0.0)
        return touched or (watch is not None and watch.touching_now(body))


def make_robot(spec: str | Path, client: int, radius: float | None) -> Robot:
    """``"disc"``, ``"husky"`` or a path to a URDF file (moved as a holonomic body).

    ``radius`` rescales the robot to that footprint radius in maze units; None keeps a user
    URDF's own size.
    """
    if isinstance(spec, Path) or (isinstance(spec, str) and spec.endswith(".urdf")):
        return HolonomicRobot(client, Path(spec), radius)
    if spec == "disc":
        return HolonomicRobot(client, DISC_URDF, radius, name="disc")
    if spec == "husky":
        return HuskyRobot(client, radius)
    raise ValueError(
        f"unknown robot {spec!r}: choose one of {list(ROBOT_NAMES)} or give a path to a .urdf file"
    )
