"""``Robot``: a body and its drive, built from a robot file or a bare URDF (``make_robot``).

A bare URDF gets a drive where the file makes it unambiguous: its continuous joints with
horizontal, parallel axes are wheels; wheels that hang from revolute joints with vertical axes
are steered, and those hinges make it a car (``ackermann``); otherwise the wheels on either side
of the centre line make it ``differential``. Its forward direction is the base's +x axis (its
part across the wheel axes; +y if the axes lie along x), or for a car from the driven axle
towards the steered one. Anything else is moved holonomically as a rigid body, with a logged
warning that names the URDF and the joints it ignores.
"""

from __future__ import annotations

import dataclasses
import logging
import math
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
import pybullet as pb

from bullet_maze.params import METRES_PER_UNIT, PhysicsParams
from bullet_maze.robots.body import Body, JointInfo
from bullet_maze.robots.car_compass import CarCompass
from bullet_maze.robots.commands import Command
from bullet_maze.robots.drives import (
    DEFAULT_BRAKING,
    AckermannDrive,
    DifferentialDrive,
    Drive,
    DriveLimits,
    Hinge,
    HolonomicDrive,
    Point,
    Pose,
    Wheel,
    quaternion,
    wrap_angle,
    yaw,
)
from bullet_maze.robots.spec import RobotSpec, resolve_robot
from bullet_maze.robots.urdf import read_urdf
from bullet_maze.world import World

logger = logging.getLogger(__name__)

_STILL = (0.0, 0.0, 0.0)

HORIZONTAL = 0.1
"""A wheel axis whose vertical component is below this is horizontal..."""
VERTICAL = 0.9
"""...and a steering hinge's axis has at least this much."""
PARALLEL = 0.05
"""Two unit axes are parallel if their cross product is shorter than this."""


class RobotState(NamedTuple):
    """What ``Robot.snapshot`` keeps: pybullet's base pose and the joint positions."""

    position: tuple[float, float, float]
    """Base position in metres."""
    orientation: tuple[float, float, float, float]
    """Base orientation quaternion (x, y, z, w)."""
    joints: tuple[float, ...]
    """Positions of the movable joints."""


@dataclasses.dataclass(frozen=True)
class _Nominal:
    """What ``Robot.scale_dynamics`` scales, as loaded."""

    masses: dict[int, tuple[float, tuple[float, ...]]]
    """Link index (-1: the base) -> (mass in kg, local inertia diagonal in kg m^2)."""
    frictions: dict[int, float]
    """Wheel link index -> lateral friction coefficient."""
    limits: DriveLimits


class Robot:
    """A body the maze env drives; positions in maze units, heading in radians from +x (the
    robot's forward direction, which need not be its base's +x axis)."""

    def __init__(self, spec: RobotSpec, body: Body, drive: Drive) -> None:
        self.spec = spec
        self.body = body
        self.drive = drive
        self.name = spec.name
        self.client = body.client
        self.body_id = body.id
        self.scale = body.scale
        """globalScaling applied to the URDF."""
        self.radius = body.radius
        """Footprint radius in maze units."""
        self.has_heading = drive.has_heading
        self._joints = body.indices
        self._as_loaded: _Nominal | None = None

    @property
    def reach_margin(self) -> float:
        """Maze units a dynamic step may carry the robot beyond its commanded length."""
        return self.drive.reach_margin

    def place(self, x: float, y: float, heading: float) -> None:
        """Teleport the robot, at rest, to (x, y) facing ``heading``."""
        s = METRES_PER_UNIT
        pb.resetBasePositionAndOrientation(
            self.body_id,
            (x * s, y * s, self.body.rest_z),
            quaternion(heading - self.drive.forward),
            physicsClientId=self.client,
        )
        pb.resetBaseVelocity(
            self.body_id, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), physicsClientId=self.client
        )
        self.drive.stop()

    # The calls of the dynamic step name the client positionally: pybullet parses a keyword
    # argument for about 0.25 us, a twentieth of a physics step.

    def position(self) -> tuple[float, float]:
        """(x, y) of the robot's base in maze units."""
        x, y, _, _ = self.placement(False)
        return x, y

    def pose(self) -> tuple[float, float, float]:
        """(x, y, heading) of the robot's base in maze units and radians."""
        x, y, heading, _ = self.placement(True)
        return x, y, heading

    def tilt(self) -> float:
        """Radians between the base's up axis and the vertical: 0 upright, as ``place`` stands
        the robot, pi upside down."""
        up = self.placement(False)[3]
        return math.acos(up if -1.0 <= up <= 1.0 else math.copysign(1.0, up))

    def placement(self, heading: bool) -> tuple[float, float, float, float]:
        """(x, y, heading, up) from one pybullet call: ``pose`` (the heading 0.0 unless asked
        for) and the cosine of ``tilt``, the z component of the base's rotated z axis."""
        position, orientation = pb.getBasePositionAndOrientation(self.body_id, self.client)
        s = METRES_PER_UNIT
        qx, qy = orientation[0], orientation[1]
        up = 1.0 - 2.0 * (qx * qx + qy * qy)
        if not heading:
            return position[0] / s, position[1] / s, 0.0, up
        return (
            position[0] / s,
            position[1] / s,
            wrap_angle(yaw(orientation) + self.drive.forward),
            up,
        )

    def joint_states(self) -> tuple[float, ...]:
        """Positions of the movable joints (radians or metres, in joint order)."""
        if not self._joints:
            return ()
        states = pb.getJointStates(self.body_id, self._joints, physicsClientId=self.client)
        return tuple(state[0] for state in states)

    def wheel_velocities(self) -> tuple[float, ...]:
        """Joint velocities (rad/s) of the driven wheels, signed so that positive rolls the
        robot forwards (empty for a holonomic robot)."""
        wheels: tuple[Wheel, ...] = ()
        if isinstance(self.drive, DifferentialDrive):
            wheels = self.drive.left + self.drive.right
        elif isinstance(self.drive, AckermannDrive):
            wheels = self.drive.driven
        if not wheels:
            return ()
        states = pb.getJointStates(
            self.body_id, [w.index for w in wheels], physicsClientId=self.client
        )
        return tuple(w.sign * state[1] for w, state in zip(wheels, states, strict=True))

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
        """Keep the dynamic mode's settings for the drive."""
        self.drive.configure(physics)

    def scale_dynamics(self, mass: float = 1.0, friction: float = 1.0, torque: float = 1.0) -> None:
        """Scale the robot as it was loaded (the physical perturbations of
        ``bullet_maze.perturbations``): every link's mass and inertia by ``mass``, the lateral
        friction of its wheels (driven, steered and free; every link of a holonomic robot) by
        ``friction``, and its motors' force limits (driven wheels, steering hinges) by
        ``torque``. Every call starts from the values as loaded, so calls do not compound;
        ``restoreState`` does not undo them."""
        nominal = self._nominal()
        client, body = self.client, self.body_id
        for link, (link_mass, inertia) in nominal.masses.items():
            pb.changeDynamics(
                body,
                link,
                mass=link_mass * mass,
                localInertiaDiagonal=[value * mass for value in inertia],
                physicsClientId=client,
            )
        for link, coefficient in nominal.frictions.items():
            pb.changeDynamics(
                body, link, lateralFriction=coefficient * friction, physicsClientId=client
            )
        if self.drive.kind != "holonomic":
            limits = nominal.limits
            self.drive.set_limits(
                wheel_torque=limits.wheel_torque * torque,
                steering_torque=limits.steering_torque * torque,
            )

    def _nominal(self) -> _Nominal:
        """The masses, inertias, wheel frictions and motor limits as loaded (read once)."""
        if self._as_loaded is None:
            client, body = self.client, self.body_id
            links = range(-1, pb.getNumJoints(body, physicsClientId=client))
            info = {link: pb.getDynamicsInfo(body, link, physicsClientId=client) for link in links}
            drive = self.drive
            if isinstance(drive, DifferentialDrive):
                wheels = tuple(w.index for w in drive.left + drive.right)
            elif isinstance(drive, AckermannDrive):
                wheels = tuple(w.index for w in drive.driven + drive.free)
            else:  # a holonomic body slides on whatever touches the floor
                wheels = tuple(links)
            self._as_loaded = _Nominal(
                masses={
                    link: (values[0], tuple(values[2]))
                    for link, values in info.items()
                    if values[0] > 0.0
                },
                frictions={link: info[link][1] for link in wheels},
                limits=drive.limits,
            )
        return self._as_loaded

    def kinematic_path(self, pose: Pose, command: Command) -> tuple[list[Point], Pose]:
        """Kinematic mode: the base's path and final pose under the drive's exact model."""
        return self.drive.path(pose, command)

    def execute(self, command: Command, watch: World | None, stop_on_touch: bool = False) -> bool:
        """Dynamic mode: the drive realises the command (see ``Drive.run``)."""
        return self.drive.run(command, watch, stop_on_touch)


def make_robot(
    robot: str | Path | RobotSpec,
    client: int,
    radius: float | None = None,
    layout_radius: float | None = None,
    dynamic: bool = False,
) -> Robot:
    """The robot named, described by a robot file, or a bare URDF, loaded into ``client``.

    ``radius`` rescales it to that footprint radius in maze units; else a robot file's
    ``footprint.radius`` (``"layout"``: ``layout_radius``), else the URDF's own size. In dynamic
    mode a robot that physics cannot move (a base of mass 0, massless wheels) is refused.
    """
    spec = resolve_robot(robot)
    model = read_urdf(spec.urdf)
    if radius is None:
        wanted = spec.footprint_radius
        radius = layout_radius if wanted == "layout" else wanted  # type: ignore[assignment]
    body = Body(client, model, radius)
    try:
        drive = _drive(spec, body)
        if dynamic:
            _check_movable(spec, body, drive)
    except BaseException:
        pb.removeBody(body.id, physicsClientId=client)
        raise
    return Robot(spec, body, drive)


def robot_drive(robot: str | Path | RobotSpec) -> str:
    """The drive of a robot (``Drive.kind``): a robot file's own, or the one :func:`make_robot`
    detects for a bare URDF, read by loading it once into a throwaway pybullet client."""
    spec = resolve_robot(robot)
    if spec.drive is not None:
        return spec.drive
    client = pb.connect(pb.DIRECT)
    try:
        return make_robot(spec, client).drive.kind
    finally:
        pb.disconnect(physicsClientId=client)


def _check_movable(spec: RobotSpec, body: Body, drive: Drive) -> None:
    if body.mass <= 0.0:
        raise ValueError(
            f"robot {spec.source}: its base link has mass 0, which pybullet treats as fixed "
            f"in place, so physics cannot move it (mode='dynamic'); give the URDF's base link "
            f"an <inertial> with a positive <mass>, or use mode='kinematic'"
        )
    wheels: tuple[Wheel, ...] = ()
    if isinstance(drive, DifferentialDrive):
        wheels = drive.left + drive.right
    elif isinstance(drive, AckermannDrive):
        wheels = drive.driven
    names = {joint.index: name for name, joint in body.joints.items()}
    for wheel in wheels:
        if body.joints[names[wheel.index]].mass <= 0.0:
            raise ValueError(
                f"robot {spec.source}: wheel joint {names[wheel.index]!r} moves a link of mass "
                f"0, which cannot drive the robot (mode='dynamic')"
            )


def _drive(spec: RobotSpec, body: Body) -> Drive:
    if spec.drive is None:
        spec = _detected(spec, body)
    if spec.drive == "holonomic":
        return HolonomicDrive(body)
    if spec.drive == "differential":
        return _differential(spec, body)
    return _ackermann(spec, body)


def _flat(vector: tuple[float, float, float]) -> np.ndarray:
    return np.array(vector[:2])


def _wheel(
    spec: RobotSpec, joint: JointInfo, field: str, forward: np.ndarray, origin: np.ndarray
) -> Wheel:
    axis = np.array(joint.axis)
    if joint.type != pb.JOINT_REVOLUTE or abs(axis[2]) > HORIZONTAL:
        raise ValueError(
            f"{spec.source}: field '{field}': joint {joint.name!r} is not a wheel (a revolute "
            f"or continuous joint with a horizontal axis)"
        )
    rolling = float(axis[1] * forward[0] - axis[0] * forward[1])  # (axis x z) . forward
    if abs(rolling) < 0.5:
        raise ValueError(
            f"{spec.source}: field '{field}': wheel {joint.name!r} has its axis along the "
            f"robot's forward direction, so it cannot roll it forwards"
        )
    left = np.array((-forward[1], forward[0]))
    lateral = float((_flat(joint.position) - origin) @ left)
    return Wheel(joint.index, math.copysign(1.0, rolling), lateral)


def _wheel_radius(spec: RobotSpec, body: Body, joints: list[JointInfo]) -> float:
    """The robot file's, else the wheels' collision cylinders' (or spheres') in the URDF, else
    half the height of their collision boxes (which include pybullet's margin)."""
    if spec.wheel_radius is not None:
        return spec.wheel_radius * body.scale
    model = body.model
    links = [model.joint(joint.name) for joint in joints]
    radii = [model.round_links.get(link.child) for link in links if link is not None]
    if len(radii) == len(joints) and all(r is not None for r in radii):
        return float(np.mean([r for r in radii if r is not None])) * body.scale
    radius = float(np.mean([joint.extent[2] for joint in joints])) / 2.0
    if not radius > 0.0:
        raise ValueError(
            f"{spec.source}: the wheels have no collision shape to measure their radius; give "
            f"wheels.radius"
        )
    return radius


def _differential(spec: RobotSpec, body: Body) -> DifferentialDrive:
    left = [body.joint(name, "wheels.left", spec.source) for name in spec.left]
    right = [body.joint(name, "wheels.right", spec.source) for name in spec.right]
    centre_left = np.mean([_flat(j.position) for j in left], axis=0)
    centre_right = np.mean([_flat(j.position) for j in right], axis=0)
    across = centre_left - centre_right
    width = float(np.hypot(*across))
    if width < 1e-6:
        raise ValueError(
            f"{spec.source}: [wheels]: the left and right wheels stand at the same place"
        )
    unit = across / width
    forward = np.array((unit[1], -unit[0]))  # the left side is to the left of forward
    origin = (centre_left + centre_right) / 2.0
    wheels_left = tuple(_wheel(spec, j, "wheels.left", forward, origin) for j in left)
    wheels_right = tuple(_wheel(spec, j, "wheels.right", forward, origin) for j in right)
    radius = _wheel_radius(spec, body, left + right)
    track = width if spec.track is None else spec.track * body.scale
    speed = spec.max_wheel_speed * radius
    limits = DriveLimits(
        wheel_speed=spec.max_wheel_speed,
        wheel_torque=spec.wheel_torque,
        turn_rate=2.0 * speed / track if spec.max_turn_rate is None else spec.max_turn_rate,
        braking=DEFAULT_BRAKING if spec.braking is None else spec.braking,
    )
    return DifferentialDrive(
        body,
        math.atan2(forward[1], forward[0]),
        wheels_left,
        wheels_right,
        radius,
        track,
        limits,
    )


def _ackermann(spec: RobotSpec, body: Body) -> AckermannDrive:
    driven = [body.joint(name, "wheels.driven", spec.source) for name in spec.driven]
    hinges = [body.joint(name, "wheels.steering", spec.source) for name in spec.steering]
    free = [body.joint(name, "wheels.free", spec.source) for name in spec.free]
    for hinge in hinges:
        if hinge.type != pb.JOINT_REVOLUTE or abs(hinge.axis[2]) < VERTICAL:
            raise ValueError(
                f"{spec.source}: field 'wheels.steering': joint {hinge.name!r} is not a "
                f"steering hinge (a revolute joint with a vertical axis)"
            )
    axle = np.mean([_flat(j.position) for j in driven], axis=0)
    ahead = np.mean([_flat(j.position) for j in hinges], axis=0) - axle
    length = float(np.hypot(*ahead))
    if length < 1e-6:
        raise ValueError(
            f"{spec.source}: [wheels]: the steering hinges stand on the driven axle; a car "
            f"steers the other axle"
        )
    forward = ahead / length
    left_dir = np.array((-forward[1], forward[0]))
    wheels = tuple(_wheel(spec, j, "wheels.driven", forward, axle) for j in driven)
    free_wheels = tuple(_wheel(spec, j, "wheels.free", forward, axle) for j in free)
    steer = tuple(
        Hinge(j.index, math.copysign(1.0, j.axis[2]), float((_flat(j.position) - axle) @ left_dir))
        for j in hinges
    )
    if spec.max_steering is not None:
        steering = spec.max_steering
    else:
        bounded = [min(-j.lower, j.upper) for j in hinges if j.lower < j.upper]
        if len(bounded) < len(hinges) or min(bounded) <= 0.0:
            raise ValueError(
                f"{spec.source}: field 'limits.max_steering' is required: the steering hinges "
                f"have no limits on both sides to take it from"
            )
        steering = min(bounded)
    radius = _wheel_radius(spec, body, driven)
    wheelbase = length if spec.wheelbase is None else spec.wheelbase * body.scale
    base_axle = (
        float(axle @ forward) / METRES_PER_UNIT,
        float(axle @ left_dir) / METRES_PER_UNIT,
    )
    limits = DriveLimits(
        wheel_speed=spec.max_wheel_speed,
        wheel_torque=spec.wheel_torque,
        steering=steering,
        steering_torque=spec.steering_torque,
    )
    drive = AckermannDrive(
        body,
        math.atan2(forward[1], forward[0]),
        wheels,
        free_wheels,
        steer,
        base_axle,
        radius,
        wheelbase,
        limits,
    )
    drive.manoeuvre = CarCompass(drive)
    return drive


def _detected(spec: RobotSpec, body: Body) -> RobotSpec:
    """The drive of a bare URDF, read off its joints (see the module docstring)."""
    path = spec.urdf
    movable = sorted(body.joints)
    wheels = [j for j in body.joints.values() if j.continuous and abs(j.axis[2]) < HORIZONTAL]

    def holonomic(reason: str) -> RobotSpec:
        if movable:
            logger.warning(
                "robot URDF %s: no drive detected (%s); it is moved holonomically as a rigid "
                "body and its joints %s are ignored (a robot file can name its wheels)",
                path,
                reason,
                movable,
            )
        return _replace(spec, drive="holonomic")

    if not wheels:
        return holonomic("no continuous joint with a horizontal axis")
    first = np.array(wheels[0].axis)
    if any(np.linalg.norm(np.cross(first, j.axis)) > PARALLEL for j in wheels):
        return holonomic("its continuous joints' axes are not parallel")
    hinges = {
        j.index: j
        for j in body.joints.values()
        if j.type == pb.JOINT_REVOLUTE and not j.continuous and abs(j.axis[2]) > VERTICAL
    }
    steered = [w for w in wheels if w.parent in hinges]
    if steered:
        driven = [w for w in wheels if w.parent not in hinges]
        if not driven:
            return holonomic("every wheel is steered, none is driven")
        used = {*(w.name for w in wheels), *(hinges[w.parent].name for w in steered)}
        detected = _replace(
            spec,
            drive="ackermann",
            driven=tuple(w.name for w in driven),
            free=tuple(w.name for w in steered),
            steering=tuple(dict.fromkeys(hinges[w.parent].name for w in steered)),
        )
    else:
        along = np.array((1.0, 0.0, 0.0)) - first[0] * first
        forward = along[:2] if np.hypot(*along[:2]) > 1e-6 else np.array((0.0, 1.0))
        forward = forward / np.hypot(*forward)
        left_dir = np.array((-forward[1], forward[0]))
        sides = [float(_flat(w.position) @ left_dir) for w in wheels]
        left = tuple(w.name for w, side in zip(wheels, sides, strict=True) if side > 1e-6)
        right = tuple(w.name for w, side in zip(wheels, sides, strict=True) if side < -1e-6)
        if not left or not right or len(left) + len(right) < len(wheels):
            return holonomic("its wheels do not stand on both sides of the centre line")
        used = set(left + right)
        detected = _replace(spec, drive="differential", left=left, right=right)
    ignored = [name for name in movable if name not in used]
    logger.info(
        "robot URDF %s: detected a %s drive (wheels %s)%s",
        path,
        detected.drive,
        sorted(detected.wheels),
        f"; joints {ignored} are not driven" if ignored else "",
    )
    return detected


def _replace(spec: RobotSpec, **changes: Any) -> RobotSpec:
    return dataclasses.replace(spec, **changes)


__all__ = ["Robot", "RobotState", "make_robot"]
