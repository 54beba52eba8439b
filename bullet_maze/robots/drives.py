"""Drives: how a command becomes motion, by an exact kinematic model or by the robot's actuators.

Each drive has the two halves that keep the env's modes comparable:

* ``path(pose, command)``: kinematic mode. The drive's exact model: a holonomic body moves in a
  straight line; a differential robot is a unicycle about its base (it turns in place, then
  drives, or follows an arc); a car is the bicycle model about the middle of its rear axle (it
  cannot turn in place). The returned points are swept with the robot's footprint disc.
* ``run(command, watch, stop_on_touch)``: dynamic mode. The drive turns the command into its
  actuators (the base velocity; wheel velocities; rear-wheel speed and steering angle) and runs
  the physics substeps.

Where the physical parameters live (the places a perturbation would change them): the motors'
limits are ``DriveLimits`` (``Drive.limits``, read at every command), masses and frictions are
the body's (``pybullet.changeDynamics`` on ``Robot.body_id``), and every command goes through
``Robot.execute`` / ``Robot.kinematic_path``.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, replace
from typing import Protocol

import pybullet as pb

from bullet_maze.params import METRES_PER_UNIT, PhysicsParams
from bullet_maze.robots.body import Body
from bullet_maze.robots.commands import Command, Move, Twist
from bullet_maze.world import CONTACT_TOLERANCE, World

_STILL = (0.0, 0.0, 0.0)
"""A zero linear or angular velocity."""

MAX_ARC_CHORDS = 256
"""Most chords an arc is swept as (see ``arc_points``)."""

Point = tuple[float, float]
Pose = tuple[float, float, float]


def wrap_angle(angle: float) -> float:
    """The angle in [-pi, pi)."""
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


def yaw(orientation: tuple[float, float, float, float]) -> float:
    """Rotation about z of a quaternion (x, y, z, w)."""
    qx, qy, qz, qw = orientation
    return math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))


def quaternion(angle: float) -> tuple[float, float, float, float]:
    """The quaternion of a rotation by ``angle`` about z."""
    return (0.0, 0.0, math.sin(angle / 2.0), math.cos(angle / 2.0))


def arc_pose(pose: Pose, pivot: Point, distance: float, turn: float, fraction: float) -> Pose:
    """Pose after ``fraction`` of a constant-curvature motion: the point ``pivot`` (in the
    robot's frame: forward, left) travels ``distance`` along its heading while the robot turns
    by ``turn`` (the unicycle for a pivot at the base; the bicycle model for a car's rear axle).
    """
    x, y, heading = pose
    px, py = pivot
    cos_h, sin_h = math.cos(heading), math.sin(heading)
    # The pivot in the world, then moved along its arc, then the base put back beside it.
    wx, wy = x + px * cos_h - py * sin_h, y + px * sin_h + py * cos_h
    s, theta = distance * fraction, turn * fraction
    if abs(theta) < 1e-12:
        wx, wy = wx + s * cos_h, wy + s * sin_h
    else:
        radius = s / theta
        wx += radius * (math.sin(heading + theta) - sin_h)
        wy += radius * (cos_h - math.cos(heading + theta))
    end = heading + theta
    cos_e, sin_e = math.cos(end), math.sin(end)
    return (wx - px * cos_e + py * sin_e, wy - px * sin_e - py * cos_e, wrap_angle(end))


def arc_points(pose: Pose, pivot: Point, distance: float, turn: float) -> tuple[list[Point], Pose]:
    """The base's path over an ``arc_pose`` motion as chord ends, and the final pose.

    The chords are short enough that the arc lies within half ``CONTACT_TOLERANCE`` of them
    (sagitta r (1 - cos(phi / 2)) for a chord of angle phi on a circle of radius r round the
    instantaneous centre), so sweeping them with the footprint decides a collision as exactly
    as a straight sweep does; at most ``MAX_ARC_CHORDS``.
    """
    end = arc_pose(pose, pivot, distance, turn, 1.0)
    if abs(turn) < 1e-12:
        return [pose[:2], end[:2]], end
    # Radius of the base's circle about the instantaneous centre of rotation.
    radius = math.hypot(end[0] - pose[0], end[1] - pose[1]) / (2.0 * abs(math.sin(turn / 2.0)))
    chords = 1
    if radius > CONTACT_TOLERANCE:
        half_angle = math.acos(max(-1.0, 1.0 - CONTACT_TOLERANCE / 2.0 / radius))
        chords = min(MAX_ARC_CHORDS, max(1, math.ceil(abs(turn) / (2.0 * half_angle))))
    points = [pose[:2]]
    for k in range(1, chords):
        points.append(arc_pose(pose, pivot, distance, turn, k / chords)[:2])
    points.append(end[:2])
    return points, end


DEFAULT_BRAKING = 5.0
"""m/s^2: ``DriveLimits.braking`` of a differential robot whose file does not say (measured
from top speed: rover 5.5; the husky, braked by all four wheels, 10-12)."""


@dataclass(frozen=True)
class DriveLimits:
    """The actuators' limits (SI units at the robot's scale); ``Drive.limits`` is read at every
    command, so replacing it (``Drive.set_limits``) changes the motors from the next step."""

    wheel_speed: float = 0.0
    """rad/s: a driven wheel's velocity target at full command."""
    wheel_torque: float = 0.0
    """N m: each driven wheel's motor force limit."""
    turn_rate: float = 0.0
    """rad/s: differential: the turn rate at full command."""
    steering: float = 0.0
    """rad: ackermann: the largest steering angle of the inner wheel."""
    steering_torque: float = 0.0
    """N m: ackermann: each steering hinge's motor force limit."""
    braking: float = DEFAULT_BRAKING
    """m/s^2: differential: the base's deceleration with its wheels stopped, which the compass
    controller plans its stops with (a robot file's ``limits.braking``; the friction
    perturbations leave it nominal, and a stop they lengthen or shorten is corrected from the
    measured pose)."""


class Drive(ABC):
    """How a robot moves; see the module docstring."""

    kind: str
    has_heading: bool
    turns_in_place: bool
    reach_margin: float
    """Maze units a dynamic step may carry the base beyond its commanded length; within that of
    a solid, contacts are checked every substep."""

    def __init__(self, body: Body, forward: float = 0.0) -> None:
        self.body = body
        self.client = body.client
        self.forward = forward
        """Angle of the robot's forward direction in its base frame (radians)."""
        self.limits = DriveLimits()
        self.physics = PhysicsParams()

    def set_limits(self, **changes: float) -> None:
        """Replace some of ``limits`` (for example a weaker ``wheel_torque``)."""
        self.limits = replace(self.limits, **changes)
        self.stop()

    def configure(self, physics: PhysicsParams) -> None:
        """Keep the settings ``run`` works with."""
        self.physics = physics

    def stop(self) -> None:  # noqa: B027  (a pushed body has no actuators to stop)
        """Command the actuators to rest (after a placement or a restored state)."""

    def pose_metres(self) -> Pose:
        """(x, y, heading) of the base in metres and radians."""
        position, orientation = pb.getBasePositionAndOrientation(self.body.id, self.client)
        return position[0], position[1], wrap_angle(yaw(orientation) + self.forward)

    @property
    def max_speed(self) -> float:
        """Maze units per second at full command (0 for drives without one)."""
        return 0.0

    @abstractmethod
    def path(self, pose: Pose, command: Command) -> tuple[list[Point], Pose]:
        """Kinematic mode: the base's path (points to sweep) and final pose of a command."""

    @abstractmethod
    def run(self, command: Command, watch: World | None, stop_on_touch: bool) -> bool:
        """Dynamic mode: realise the command through physics substeps.

        If ``watch`` is given, contacts with its walls and obstacles are checked after every
        substep (pybullet reports those found at the start of a substep, so the first, which
        sees the pose before the move, is skipped and the final pose is checked explicitly);
        returns whether any occurred. With ``stop_on_touch`` the substeps end at the first
        contact, for a caller that undoes a touching step anyway.
        """

    def reach(self, command: Command) -> float:
        """Maze units the base may travel in a dynamic step of this command."""
        if isinstance(command, Move):
            return math.hypot(command.dx, command.dy) + self.reach_margin
        vx, vy, _ = pb.getBaseVelocity(self.body.id, self.client)[0]
        carried = math.hypot(vx, vy) / METRES_PER_UNIT * command.duration
        return carried + abs(command.distance) + self.reach_margin

    def _substeps(self, watch: World | None, count: int, stop_on_touch: bool) -> bool:
        """``count`` physics steps, contacts watched as ``run`` says."""
        client, body, step = self.client, self.body.id, pb.stepSimulation
        if watch is None:
            for _ in range(count):
                step(client)
            return False
        touched = False
        step(client)
        for _ in range(count - 1):
            step(client)
            if not touched and watch.touching(body):
                if stop_on_touch:
                    return True
                touched = True
        return watch.touching_now(body) or touched


class HolonomicDrive(Drive):
    """A rigid body pushed in the plane, without heading (the disc, a user's URDF without
    wheels).

    Dynamic mode commands the base velocity that covers the move in ``substeps * time_step``
    seconds at the start of the step; then mass, ground friction and contacts act freely through
    the substeps (linear and angular damping are switched off so that only they act).
    """

    kind = "holonomic"
    has_heading = False
    turns_in_place = True
    reach_margin = 0.5  # friction only shortens the commanded move; contacts need proximity

    def __init__(self, body: Body) -> None:
        super().__init__(body)
        self._rate = 0.0
        self._substeps_range = range(0)

    def configure(self, physics: PhysicsParams) -> None:
        super().configure(physics)
        pb.changeDynamics(
            self.body.id, -1, linearDamping=0.0, angularDamping=0.0, physicsClientId=self.client
        )
        self._rate = METRES_PER_UNIT / (physics.substeps * physics.time_step)
        self._substeps_range = range(physics.substeps)

    def path(self, pose: Pose, command: Command) -> tuple[list[Point], Pose]:
        if not isinstance(command, Move):
            raise TypeError("a holonomic robot takes Move commands")
        end = (pose[0] + command.dx, pose[1] + command.dy, pose[2])
        return [pose[:2], end[:2]], end

    def run(self, command: Command, watch: World | None, stop_on_touch: bool) -> bool:
        if not isinstance(command, Move):
            raise TypeError("a holonomic robot takes Move commands")
        client, body, rate = self.client, self.body.id, self._rate
        step = pb.stepSimulation
        pb.resetBaseVelocity(body, (command.dx * rate, command.dy * rate, 0.0), _STILL, client)
        if watch is None:
            for _ in self._substeps_range:
                step(client)
            return False
        touched = False
        step(client)
        for _ in self._substeps_range[1:]:
            step(client)
            if not touched and watch.touching(body):
                if stop_on_touch:
                    return True
                touched = True
        return watch.touching_now(body) or touched


@dataclass(frozen=True)
class Wheel:
    """A wheel joint of the loaded body."""

    index: int
    sign: float
    """+1 if a positive joint velocity rolls the robot forwards, -1 if backwards."""
    lateral: float
    """Metres to the left of the robot's centre line (at its scale)."""


class DifferentialDrive(Drive):
    """Left and right wheels at independent speeds (two-wheeled or skid-steered).

    Kinematic mode: the unicycle about the base. A ``Move`` turns in place to face the target
    (or to face away from it, whichever needs the smaller turn) and drives straight to it; a
    ``Twist`` follows its arc. Dynamic mode: a ``Twist`` holds the wheel speeds of its arc for
    its duration (left ``(v - w t / 2) / r``, right ``(v + w t / 2) / r``); a ``Move`` is the
    same turn and drive, closed-loop on the pose (``CompassController``).
    """

    kind = "differential"
    has_heading = True
    turns_in_place = True

    def __init__(
        self,
        body: Body,
        forward: float,
        left: tuple[Wheel, ...],
        right: tuple[Wheel, ...],
        wheel_radius: float,
        track: float,
        limits: DriveLimits,
    ) -> None:
        super().__init__(body, forward)
        self.left, self.right = left, right
        self.wheel_radius = wheel_radius
        """Metres at the robot's scale."""
        self.track = track
        """Metres between the left and right wheels at the robot's scale."""
        self.limits = limits
        # A skid-steered turn in place may swing the base round a pivot away from it.
        self.reach_margin = body.radius
        self._indices = [w.index for w in left + right]
        self._left_signs = [w.sign for w in left]
        self._right_signs = [w.sign for w in right]
        self._half_track = track / 2.0
        self._sent: tuple[float, float] | None = None
        self.controller = CompassController(self)

    @property
    def max_speed(self) -> float:
        return self.limits.wheel_speed * self.wheel_radius / METRES_PER_UNIT

    @property
    def max_turn_rate(self) -> float:
        """rad/s at full command."""
        return self.limits.turn_rate

    def stop(self) -> None:
        self._sent = None
        self.set_wheels(0.0, 0.0)

    def set_wheels(self, speed: float, turn_rate: float) -> None:
        """Wheel velocity targets for a base speed (m/s) and turn rate (rad/s); a command equal
        to the last one is not sent again."""
        if (speed, turn_rate) != self._sent:
            self.send_wheels(speed, turn_rate)

    def send_wheels(self, speed: float, turn_rate: float) -> None:
        """``set_wheels`` without the check: one ``setJointMotorControlArray`` for every wheel
        (left ``(v - w t / 2) / r``, right ``(v + w t / 2) / r``, each times its sign)."""
        self._sent = (speed, turn_rate)
        r, half = self.wheel_radius, self._half_track
        left, right = (speed - turn_rate * half) / r, (speed + turn_rate * half) / r
        pb.setJointMotorControlArray(
            self.body.id,
            self._indices,
            pb.VELOCITY_CONTROL,
            targetVelocities=[sign * left for sign in self._left_signs]
            + [sign * right for sign in self._right_signs],
            forces=[self.limits.wheel_torque] * len(self._indices),
            physicsClientId=self.client,
        )

    def path(self, pose: Pose, command: Command) -> tuple[list[Point], Pose]:
        if isinstance(command, Twist):
            return arc_points(pose, (0.0, 0.0), command.distance, command.turn)
        end = (pose[0] + command.dx, pose[1] + command.dy)
        if command.dx == 0.0 and command.dy == 0.0:
            return [pose[:2], end], pose
        return [pose[:2], end], (end[0], end[1], facing(pose[2], command.dx, command.dy))

    def run(self, command: Command, watch: World | None, stop_on_touch: bool) -> bool:
        if isinstance(command, Move):
            return self.controller.run(command, watch, stop_on_touch)
        s = METRES_PER_UNIT
        self.set_wheels(command.distance * s / command.duration, command.turn / command.duration)
        count = max(1, round(command.duration / self.physics.time_step))
        return self._substeps(watch, count, stop_on_touch)


def facing(heading: float, dx: float, dy: float) -> float:
    """The heading a differential robot ends a ``Move`` with: the move's bearing, or its
    opposite if that is nearer the current heading (it then drives backwards)."""
    bearing = math.atan2(dy, dx)
    if abs(wrap_angle(bearing - heading)) <= math.pi / 2:
        return bearing
    return wrap_angle(bearing + math.pi)


class CompassController:
    """Dynamic ``Move`` of a differential robot: turn in place to face the target point (or
    face away from it, whichever needs the smaller turn), then drive to it, both by wheel
    velocity commands updated every ``CONTROL_INTERVAL`` seconds (every physics step at 120 Hz
    or coarser); contacts are watched after every physics step.

    Both phases aim at the point itself, not along the move's direction: a skid-steered turn in
    place also moves the base, and aiming along the direction would carry that offset to the end.

    Both phases brake on the measured motion. The turn commands the drive's full turn rate until
    the angle the robot would still cover if its wheels stopped now (its measured yaw rate w
    over the next control update, plus w^2 / (2 ``TURN_BRAKING``)) reaches the remaining
    heading error, then stops the wheels, whose friction brakes the spin; a turn that stopped
    short starts again from the measured state. (A skid-steered robot cannot follow a small
    turn-rate command, its wheels' lateral friction holds it, so a proportional law creeps
    through the last tenths of a radian; a turn that brakes on the measured rate does not.) The
    drive does the same along its axis: it commands the speed from which the wheels can still
    stop in the distance left (``sqrt(2 a d)``, ``a`` the drive's ``limits.braking``; at most
    the top speed) until the distance the robot would still cover if its wheels stopped now
    (its measured speed v over the next update and ``DRIVE_LAG``, plus v^2 / (2 a)) reaches the
    distance left, then stops the wheels; slowed by the cosine of the heading error, steering
    at the heading the measured yaw rate leads to (``STEER_LEAD``). ``max_turn_substeps`` and
    ``max_drive_substeps`` (``PhysicsParams``) bound the phases.

    Chosen on the bench's compass workload (200 seeded random steps in the paper maze, noise
    on) and on 100-step random walks in ``open`` without noise: the husky at 60 Hz with
    ``limits.braking`` 11 takes 55 physics steps per step (the speed profile it replaced, which
    planned with 5 m/s^2 and no stop, took 65) and ends 0.09 units from the target on average;
    the rover at 120 Hz (braking 5) 119 (was 135) and 0.20 units (was 0.30).
    """

    TURN_BRAKING = 25.0
    """rad/s^2: the yaw deceleration assumed when the wheels stop (measured from 1.7 rad/s:
    husky 30, rover 26, at 240 Hz and 60 Hz alike)."""
    DRIVE_LAG = 0.03
    """Seconds the base runs on at its speed after the wheels stop (the contacts' give): the
    husky's speed falls about two physics steps after the command at 60 Hz."""
    STEER_GAIN = 10.0
    """1/s: turn rate command per radian of heading error while driving..."""
    STEER_LEAD = 0.2
    """...of the heading this many seconds ahead at the measured yaw rate (damps the rover's
    weave)."""
    HEADING_TOLERANCE = 0.05
    """Radians: the turn ends when the heading is this close to the facing angle..."""
    SETTLED_SPIN = 0.3
    """...and the yaw rate (rad/s) is below this."""
    DISTANCE_TOLERANCE = 0.1
    """Maze units: the drive ends when the target is this close ahead or behind..."""
    SETTLED_SPEED = 0.1
    """...and the speed (m/s) is below this."""
    AIM_RADIUS = 1.0
    """Maze units: closer than this to the target the robot keeps its last bearing instead of
    re-aiming at a point that is nearly under it."""
    CONTROL_INTERVAL = 1.0 / 120.0
    """Seconds between control updates: 2 physics steps at 240 Hz, every step at 120 Hz or
    coarser."""

    def __init__(self, drive: DifferentialDrive) -> None:
        self.drive = drive

    def run(self, move: Move, watch: World | None, stop_on_touch: bool) -> bool:
        """Turn, then drive; see the class docstring."""
        drive = self.drive
        physics = drive.physics
        client, body = drive.client, drive.body.id
        # Bound once: the loop runs at every control update (about 60 per husky step), where a
        # physics step costs about 25 us and each Python-side microsecond shows.
        step, velocity, place = (
            pb.stepSimulation,
            pb.getBaseVelocity,
            pb.getBasePositionAndOrientation,
        )
        send, touching = drive.send_wheels, None if watch is None else watch.touching
        atan2, cos, sin, hypot, sqrt, copysign = (
            math.atan2,
            math.cos,
            math.sin,
            math.hypot,
            math.sqrt,
            math.copysign,
        )
        pi, tau, half_pi = math.pi, 2.0 * math.pi, math.pi / 2
        offset = drive.forward + pi  # heading = wrap(yaw + forward), as pose_metres
        s = METRES_PER_UNIT
        x0, y0, heading = drive.pose_metres()
        tx, ty = x0 + move.dx * s, y0 + move.dy * s  # metres, like everything below
        reverse = facing(heading, move.dx, move.dy) != math.atan2(move.dy, move.dx)
        flip = pi if reverse else 0.0
        bearing = math.atan2(move.dy, move.dx)
        aim, tolerance = self.AIM_RADIUS * s, self.DISTANCE_TOLERANCE * s
        top_speed, top_spin = drive.max_speed * s, drive.max_turn_rate
        period = max(1, round(self.CONTROL_INTERVAL / physics.time_step))
        ticks = range(period)
        lead = period * physics.time_step  # seconds until the next update
        turn_brake, drive_brake = 2.0 * self.TURN_BRAKING, 2.0 * drive.limits.braking
        drive_lead = lead + self.DRIVE_LAG
        heading_tolerance, settled_spin = self.HEADING_TOLERANCE, self.SETTLED_SPIN
        settled_speed, steer_gain, steer_lead = self.SETTLED_SPEED, self.STEER_GAIN, self.STEER_LEAD
        sent = drive._sent  # the wheels' last command: a command is sent only when it changes
        substep = 0
        touched = False
        for turning, limit in (
            (True, physics.max_turn_substeps),
            (False, physics.max_drive_substeps),
        ):
            end = substep + limit
            while substep < end:
                (x, y, _), (qx, qy, qz, qw) = place(body, client)
                heading = (
                    atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz)) + offset
                ) % tau - pi
                (vx, vy, _), (_, _, spin) = velocity(body, client)
                ex, ey = tx - x, ty - y
                if hypot(ex, ey) > aim:
                    bearing = atan2(ey, ex)
                error = (bearing + flip - heading + pi) % tau - pi
                if turning:
                    if abs(error) < heading_tolerance and abs(spin) < settled_spin:
                        break
                    forward = 0.0
                    coasting = abs(spin) * lead + spin * spin / turn_brake
                    if spin * error > 0.0 and coasting >= abs(error):
                        turn = 0.0
                    else:
                        turn = copysign(top_spin, error)
                else:
                    # Steer the robot's axis at the point, whichever end faces it: past the
                    # point (an overshoot) it backs up instead of turning round.
                    if abs(error) > half_pi:
                        error = (error + pi + pi) % tau - pi  # wrap_angle(error + pi)
                    ch, sh = cos(heading), sin(heading)
                    remaining = ex * ch + ey * sh
                    if abs(remaining) < tolerance and hypot(vx, vy) < settled_speed:
                        break
                    # Stop the wheels once the robot would coast to the point; until then the
                    # speed from which they still stop there.
                    along, left = vx * ch + vy * sh, abs(remaining)
                    if along * remaining > 0.0 and (
                        abs(along) * drive_lead + along * along / drive_brake >= left
                    ):
                        speed = 0.0
                    else:
                        speed = min(top_speed, sqrt(drive_brake * left))
                    forward = copysign(speed, remaining) * max(0.0, cos(error))
                    # Steer at the heading the measured yaw rate leads to (a robot's yaw lags
                    # its wheels' command by about a tenth of a second).
                    ahead = error - steer_lead * spin
                    turn = min(top_spin, max(-top_spin, steer_gain * ahead))
                if (forward, turn) != sent:
                    send(forward, turn)
                    sent = (forward, turn)
                if touching is None or touched:
                    for _ in ticks:
                        step(client)
                    substep += period
                    continue
                for _ in ticks:
                    step(client)
                    substep += 1
                    if substep > 1 and not touched:
                        touched = touching(body)
                        if touched and stop_on_touch:
                            drive.set_wheels(0.0, 0.0)
                            return True
        drive.set_wheels(0.0, 0.0)
        return touched or (watch is not None and watch.touching_now(body))


@dataclass(frozen=True)
class Hinge:
    """A steering hinge of the loaded body."""

    index: int
    sign: float
    """+1 if a positive joint angle steers to the left."""
    lateral: float
    """Metres to the left of the centre line (at the robot's scale)."""


class Manoeuvre(Protocol):
    """How a car realises a displacement (``Move``): ``bullet_maze.robots.car_compass``."""

    def path(self, pose: Pose, move: Move) -> tuple[list[Point], Pose]: ...

    def run(self, move: Move, watch: World | None, stop_on_touch: bool) -> bool: ...

    def reach(self, move: Move) -> float: ...


class AckermannDrive(Drive):
    """A car: driven (rear) wheels, steering hinges in position control, free wheels at motor
    force 0, as in pybullet's ``examples/racecar.py``. It cannot turn in place.

    A ``Move`` (a compass action) is realised by ``manoeuvre`` (a short manoeuvre of arcs that
    keeps the heading, ``bullet_maze.robots.car_compass``), in both modes; without one it is
    an error.

    Kinematic mode: the bicycle model about the middle of the driven axle: a ``Twist`` of
    distance d turns by at most d times the largest curvature ``max_curvature``. Dynamic mode:
    each steering hinge is set to the Ackermann angle of the arc's curvature k for its side,
    ``atan(L k / (1 - k y))`` (wheelbase L, hinge y metres to the left), and each driven wheel
    to the speed of its own circle, ``v (1 - k y) / r`` (an electronic differential), for the
    command's duration.
    """

    kind = "ackermann"
    has_heading = True
    turns_in_place = False

    def __init__(
        self,
        body: Body,
        forward: float,
        driven: tuple[Wheel, ...],
        free: tuple[Wheel, ...],
        hinges: tuple[Hinge, ...],
        axle: Point,
        wheel_radius: float,
        wheelbase: float,
        limits: DriveLimits,
    ) -> None:
        super().__init__(body, forward)
        self.driven, self.free, self.hinges = driven, free, hinges
        self.axle = axle
        """Middle of the driven axle in the robot's frame (forward, left), maze units."""
        self.wheel_radius = wheel_radius
        self.wheelbase = wheelbase
        """Metres from the driven axle to the steered one, at the robot's scale."""
        self.limits = limits
        self.reach_margin = 0.5
        self._sent: tuple[float, float] | None = None
        inner = max((abs(h.lateral) for h in hinges), default=0.0)
        self._inner = inner
        self.manoeuvre: Manoeuvre | None = None
        """Realises ``Move`` commands (set by ``make_robot``)."""

    @property
    def max_speed(self) -> float:
        return self.limits.wheel_speed * self.wheel_radius / METRES_PER_UNIT

    @property
    def max_curvature(self) -> float:
        """1 / maze units: the tightest arc, where the inner hinge reaches ``limits.steering``:
        k = tan(d) / (L + y tan(d))."""
        t = math.tan(self.limits.steering)
        return t / (self.wheelbase + self._inner * t) * METRES_PER_UNIT

    def realisable(self, twist: Twist) -> Twist:
        """The twist with its turn cut to what the curvature limit allows over its distance."""
        most = self.max_curvature * abs(twist.distance)
        return twist._replace(turn=min(most, max(-most, twist.turn)))

    def stop(self) -> None:
        self._sent = None
        self.set_motion(0.0, 0.0)
        client = self.client
        for wheel in self.free:
            pb.setJointMotorControl2(
                self.body.id,
                wheel.index,
                pb.VELOCITY_CONTROL,
                targetVelocity=0.0,
                force=0.0,
                physicsClientId=client,
            )

    def set_motion(self, speed: float, curvature: float) -> None:
        """Steering angles and driven-wheel speeds for a speed (m/s) along an arc of curvature
        (1/m); a command equal to the last one is not sent again."""
        if (speed, curvature) == self._sent:
            return
        self._sent = (speed, curvature)
        client, body, limits = self.client, self.body.id, self.limits
        angles = self.steering_angles(curvature)
        pb.setJointMotorControlArray(
            body,
            [h.index for h in self.hinges],
            pb.POSITION_CONTROL,
            targetPositions=angles,
            forces=[limits.steering_torque] * len(angles),
            physicsClientId=client,
        )
        r = self.wheel_radius
        pb.setJointMotorControlArray(
            body,
            [w.index for w in self.driven],
            pb.VELOCITY_CONTROL,
            targetVelocities=[
                w.sign * speed * (1.0 - curvature * w.lateral) / r for w in self.driven
            ],
            forces=[limits.wheel_torque] * len(self.driven),
            physicsClientId=client,
        )

    def steering_angles(self, curvature: float) -> list[float]:
        """Each hinge's joint angle for an arc of ``curvature`` (1/m), within the limit."""
        top = self.limits.steering
        return [
            h.sign
            * min(
                top, max(-top, math.atan2(self.wheelbase * curvature, 1.0 - curvature * h.lateral))
            )
            for h in self.hinges
        ]

    def _manoeuvre(self) -> Manoeuvre:
        if self.manoeuvre is None:
            raise ValueError(
                "a car without a manoeuvre (AckermannDrive.manoeuvre) cannot realise a "
                "displacement (Move) command"
            )
        return self.manoeuvre

    def reach(self, command: Command) -> float:
        if isinstance(command, Move):
            return self._manoeuvre().reach(command)
        return super().reach(command)

    def path(self, pose: Pose, command: Command) -> tuple[list[Point], Pose]:
        if isinstance(command, Move):
            return self._manoeuvre().path(pose, command)
        twist = self.realisable(command)
        return arc_points(pose, self.axle, twist.distance, twist.turn)

    def run(self, command: Command, watch: World | None, stop_on_touch: bool) -> bool:
        if isinstance(command, Move):
            return self._manoeuvre().run(command, watch, stop_on_touch)
        twist = self.realisable(command)
        curvature = 0.0
        if twist.distance != 0.0:
            curvature = twist.turn / (twist.distance * METRES_PER_UNIT)
        self.set_motion(twist.distance * METRES_PER_UNIT / twist.duration, curvature)
        count = max(1, round(twist.duration / self.physics.time_step))
        return self._substeps(watch, count, stop_on_touch)
