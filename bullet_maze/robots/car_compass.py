"""Compass actions for a car: a displacement intent realised by a short manoeuvre of arcs.

A car cannot turn in place, and turning to face a compass bearing would carry it about one
turning radius ``R`` sideways and ahead (the racecar: ``R`` = 8.5 maze units against a
``step_size`` of 5), so it cannot realise a compass step by turning and driving as a
differential robot does. Its policy instead **keeps its heading** and displaces its base by
the intent ``(dx, dy)`` (noise included) with bicycle-model segments about the middle of its
driven axle (section "Robots" of ``docs/environment.md``):

* in its own frame the intent is ``a`` ahead and ``b`` to the left;
* ``b = 0``: a straight drive of ``a`` (forwards or backwards);
* a **lane change** (an S of two arcs at full lock, turning by ``+phi`` then ``-phi``) moves it
  ``c`` sideways and ``A(c) = 2 R sin(phi)`` along its heading, with ``1 - cos(phi) = |c| /
  (2 R)``, and leaves the heading unchanged. If ``|b| <= 2 R`` and ``A(|b|) <= |a|``, one lane
  change of ``b`` in the direction of ``a`` and a straight drive of the rest (``|a| - A``);
* otherwise (a step across the heading, ``|a|`` small): a **zig-zag** of ``m`` lane changes of
  ``b / m`` each, alternately forwards and backwards (the first in the direction of ``a``,
  forwards if ``a = 0``), ``m`` the smallest even number with ``|b| / m <= 2 R``, then a
  straight drive of ``a``. The racecar's step of 5 across its heading: two lane changes of
  2.5, each 8.9 units along the heading and 9.4 units of arc, then a straight of ``a``.

**Kinematic mode** follows those segments exactly (the bicycle model, ``arc_pose``); every
arc is swept with the footprint as ``arc_points`` chords, so collisions are found as for every
other robot, and the base ends exactly at the intent (floating-point error only, below 1e-9
units) with the heading it started with. The swept region reaches ``A`` beyond the start
along the heading (8.9 units for the racecar's cross step), which is where a car finds walls
a disc would not.

**Dynamic mode** (``CarCompassController``) drives the same segments through the car's own
actuators: for each segment it stops, sets the steering hinges (position control) to the
segment's curvature and waits until they are there, then drives the rear wheels (velocity
control) at up to ``SPEED`` and brakes on the measured progress (the heading turned, for an
arc; the distance along the segment, for a straight). After the plan, if the base is more than
``LATERAL_TOLERANCE`` across or ``ALONG_TOLERANCE`` along its heading from the target, it plans
once more from the measured pose (``MAX_CORRECTIONS``). The heading it keeps is the measured
one at the start of each plan, so the heading's own small errors accumulate over steps (the
kinematic mode keeps it exactly). Measured error bounds: ``docs/environment.md`` and
``tests/bullet_maze/test_car_compass.py``.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import pybullet as pb

from bullet_maze.params import METRES_PER_UNIT
from bullet_maze.robots.commands import Move
from bullet_maze.robots.drives import AckermannDrive, Point, Pose, arc_points, arc_pose, wrap_angle
from bullet_maze.world import World

STRAIGHT_EPSILON = 1e-9
"""Maze units: a sideways part of the intent below this is driven as a straight."""


class Segment(NamedTuple):
    """One bicycle-model motion of the manoeuvre: ``distance`` maze units along the heading
    (negative: backwards) while turning ``turn`` radians (0: a straight)."""

    distance: float
    turn: float


def lane_change_advance(lateral: float, radius: float) -> float:
    """``A(c)``: the distance along the heading that a lane change of ``|lateral|`` sideways
    at turning radius ``radius`` covers (``|lateral| <= 2 radius``)."""
    u = abs(lateral) / (2.0 * radius)
    return 2.0 * radius * math.sqrt(max(0.0, 2.0 * u - u * u))


def lane_change(lateral: float, direction: float, radius: float) -> tuple[Segment, Segment]:
    """The two full-lock arcs that move the car ``lateral`` to its left (negative: right),
    driving forwards (``direction`` +1) or backwards (-1), heading unchanged."""
    phi = math.acos(1.0 - abs(lateral) / (2.0 * radius))
    side = math.copysign(1.0, lateral)
    return (
        Segment(direction * radius * phi, direction * side * phi),
        Segment(direction * radius * phi, -direction * side * phi),
    )


def plan(heading: float, move: Move, radius: float) -> list[Segment]:
    """The manoeuvre (see the module docstring) that displaces a car facing ``heading`` by
    ``move`` with its heading unchanged; ``radius`` is its tightest turning radius (maze
    units)."""
    dx, dy = move
    if not (math.isfinite(dx) and math.isfinite(dy)):
        raise ValueError(f"a car's compass move must be finite, got ({dx!r}, {dy!r})")
    if not (math.isfinite(radius) and radius > 0.0):
        raise ValueError(f"a car's turning radius must be a positive number, got {radius!r}")
    cos_h, sin_h = math.cos(heading), math.sin(heading)
    ahead = dx * cos_h + dy * sin_h
    left = -dx * sin_h + dy * cos_h
    direction = -1.0 if ahead < 0.0 else 1.0
    if abs(ahead) <= STRAIGHT_EPSILON:
        ahead = 0.0
    if abs(left) <= STRAIGHT_EPSILON:
        return [Segment(ahead, 0.0)] if ahead != 0.0 else []
    if abs(left) <= 2.0 * radius:
        advance = lane_change_advance(left, radius)
        if advance <= abs(ahead):
            rest = ahead - direction * advance
            segments = list(lane_change(left, direction, radius))
            return segments + [Segment(rest, 0.0)] if rest != 0.0 else segments
    count = 2 * math.ceil(abs(left) / (4.0 * radius))
    segments = []
    for k in range(count):
        segments.extend(lane_change(left / count, direction if k % 2 == 0 else -direction, radius))
    return segments + [Segment(ahead, 0.0)] if ahead != 0.0 else segments


class CarCompass:
    """A car's compass manoeuvre in both modes (``AckermannDrive.manoeuvre``)."""

    REACH_SLACK = 10.0
    """Maze units beyond the plan's farthest point that a dynamic step is watched for contacts
    (slip, overshoot and the correction pass stay well within it)."""

    def __init__(self, drive: AckermannDrive) -> None:
        self.drive = drive
        self.controller = CarCompassController(drive)

    @property
    def radius(self) -> float:
        """The tightest turning radius, maze units (about the driven axle)."""
        return 1.0 / self.drive.max_curvature

    def segments(self, pose: Pose, move: Move) -> list[Segment]:
        """The manoeuvre from ``pose`` (its heading matters)."""
        return plan(pose[2], move, self.radius)

    def path(self, pose: Pose, move: Move) -> tuple[list[Point], Pose]:
        """Kinematic mode: the chord ends of every arc and straight (to sweep), and the end
        pose (the intent reached exactly, heading kept)."""
        points: list[Point] = [pose[:2]]
        current = pose
        pivot = self.drive.axle
        for segment in self.segments(pose, move):
            chords, current = arc_points(current, pivot, segment.distance, segment.turn)
            points.extend(chords[1:])
        return points, current

    def reach(self, move: Move) -> float:
        """Maze units from the start that a dynamic step may carry the base."""
        points, _ = self.path((0.0, 0.0, self.drive.pose_metres()[2]), move)
        farthest = max((math.hypot(x, y) for x, y in points), default=0.0)
        return farthest + self.drive.reach_margin + self.REACH_SLACK

    def run(self, move: Move, watch: World | None, stop_on_touch: bool) -> bool:
        """Dynamic mode: see ``CarCompassController``."""
        return self.controller.run(move, watch, stop_on_touch)


class CarCompassController:
    """Drives a manoeuvre's segments through the steering hinges and the rear wheels; see the
    module docstring. Every physics step after the first is checked for contacts when a
    ``World`` is watched."""

    SPEED = 1.5
    """m/s: the rear axle's top speed on a straight (the racecar's top speed is 2.45)..."""
    ARC_SPEED = 0.8
    """...and on an arc at full lock, where faster tyres slip outwards (the racecar's arc
    radius, measured over 0.6 m at 240 Hz: 0.95-1.01 m at 0.5-0.8 m/s, 1.48 m at 1.5 m/s,
    against the bicycle model's 0.85 m)."""
    RADIUS_SCALE = 1.12
    """The dynamic plan's turning radius over the bicycle model's: the racecar's measured
    understeer at ``ARC_SPEED`` (0.89-1.01 m forwards and backwards, at 240 Hz and 120 Hz,
    mean 0.95 m against 0.85 m)."""
    MIN_SPEED = 0.1
    """m/s: the slowest speed commanded before a segment's end (no creeping)."""
    BRAKING = 4.0
    """m/s^2: the deceleration the speed profile assumes when it slows for a segment's end."""
    STEER_TOLERANCE = 0.02
    """Radians: the hinges count as set within this of their targets..."""
    STEER_TIMEOUT = 0.5
    """...or after this many seconds of waiting."""
    FIRST_SHARE = 0.37
    """Share of a lane change's sideways move at which its first arc ends (the second arc,
    which ends when the heading is back, then covers the rest: measured on the racecar at
    ``ARC_SPEED``, the second arc of a lane change moves it 1.7 times as far sideways as the
    first, where the bicycle model has them equal)."""
    ALONG_TOLERANCE = 0.2
    """Maze units along the heading from the target that end the step without a correction..."""
    LATERAL_TOLERANCE = 1.0
    """...and across it (a sideways correction costs a lane change, about 6 units of arc)."""
    MAX_CORRECTIONS = 2
    """Plans from the measured pose after the first."""
    MAX_SECONDS = 12.0
    """Simulated seconds a step may take at most (the racecar's cross step takes about 2)."""
    CONTROL_INTERVAL = 1.0 / 120.0
    """Seconds between control updates (2 physics steps at 240 Hz)."""

    def __init__(self, drive: AckermannDrive) -> None:
        self.drive = drive
        self._budget = 0
        self._substep = 0
        self._touched = False
        self._watch: World | None = None
        self._stop_on_touch = False
        self._period = 1
        self._lane_start: Pose = (0.0, 0.0, 0.0)

    def run(self, move: Move, watch: World | None, stop_on_touch: bool) -> bool:
        """Plan from the measured pose, drive every segment, correct once if needed."""
        drive = self.drive
        physics = drive.physics
        self._period = max(1, round(self.CONTROL_INTERVAL / physics.time_step))
        self._budget = max(1, round(self.MAX_SECONDS / physics.time_step))
        self._substep = 0
        self._touched = False
        self._watch, self._stop_on_touch = watch, stop_on_touch
        x0, y0, heading = drive.pose_metres()
        s = METRES_PER_UNIT
        tx, ty = x0 / s + move.dx, y0 / s + move.dy
        radius = self.RADIUS_SCALE / drive.max_curvature
        segments = plan(heading, move, radius)
        for attempt in range(1 + self.MAX_CORRECTIONS):
            arcs = 0
            for segment in segments:
                first = segment.turn != 0.0 and arcs % 2 == 0
                arcs += segment.turn != 0.0
                if self._drive(segment, first, (tx, ty)):
                    drive.set_motion(0.0, 0.0)
                    return True
            x, y, heading = drive.pose_metres()
            ex, ey = tx - x / s, ty - y / s
            along = ex * math.cos(heading) + ey * math.sin(heading)
            across = -ex * math.sin(heading) + ey * math.cos(heading)
            if abs(along) <= self.ALONG_TOLERANCE and abs(across) <= self.LATERAL_TOLERANCE:
                break
            if attempt < self.MAX_CORRECTIONS:
                segments = plan(heading, Move(ex, ey), radius)
        drive.set_motion(0.0, 0.0)
        if self._touched:
            return True
        return watch is not None and watch.touching_now(drive.body.id)

    def _steps(self, count: int) -> bool:
        """``count`` physics steps (within the budget); whether to stop at a contact."""
        client, body, watch = self.drive.client, self.drive.body.id, self._watch
        step = pb.stepSimulation
        for _ in range(count):
            if self._substep >= self._budget:
                return False
            step(client)
            self._substep += 1
            if watch is not None and self._substep > 1 and not self._touched:
                self._touched = watch.touching(body)
                if self._touched and self._stop_on_touch:
                    return True
        return False

    def _drive(self, segment: Segment, first: bool, target: Point) -> bool:
        """One segment: steer at standstill, then drive and brake on the measured progress;
        whether a contact stopped it. The first arc of a lane change ends when the base has
        moved half the lane change sideways, the second when the heading is back where the
        lane change began (so slip changes the distance driven, not the heading kept); a
        straight ends at the step's target seen along the heading."""
        drive = self.drive
        client, body = drive.client, drive.body.id
        s = METRES_PER_UNIT
        arc = segment.turn != 0.0
        curvature = segment.turn / (segment.distance * s) if arc else 0.0
        # Steer at standstill until the hinges reach their angles.
        drive.set_motion(0.0, curvature)
        targets = drive.steering_angles(curvature)
        hinges = [h.index for h in drive.hinges]
        waited, timeout = 0, max(1, round(self.STEER_TIMEOUT / drive.physics.time_step))
        while waited < timeout and self._substep < self._budget:
            states = pb.getJointStates(body, hinges, physicsClientId=client)
            if all(
                abs(state[0] - target) <= self.STEER_TOLERANCE
                for state, target in zip(states, targets, strict=True)
            ):
                break
            if self._steps(self._period):
                return True
            waited += self._period
        x0, y0, h0 = drive.pose_metres()
        if first:
            self._lane_start = (x0, y0, h0)
        lx, ly, lh = self._lane_start
        cos_l, sin_l = math.cos(lh), math.sin(lh)
        sign = math.copysign(1.0, segment.distance)
        turn_sign = math.copysign(1.0, segment.turn)
        length = abs(segment.distance) * s  # metres of axle travel
        # Half a lane change sideways (metres, positive to the side it moves to).
        radius = length / abs(segment.turn) if arc else 0.0
        half = radius * (1.0 - math.cos(segment.turn))
        side = turn_sign * sign
        tx, ty = target[0] * s, target[1] * s
        lead = self._period * drive.physics.time_step
        while self._substep < self._budget:
            x, y, heading = drive.pose_metres()
            if not arc:
                remaining = ((tx - x) * math.cos(heading) + (ty - y) * math.sin(heading)) * sign
            elif first:
                moved = (-(x - lx) * sin_l + (y - ly) * cos_l) * side
                turned = wrap_angle(heading - lh) * turn_sign
                if turned >= 1.5 * abs(segment.turn):  # a safeguard against a stuck slide
                    break
                remaining = length * (1.0 - moved / (2.0 * half * self.FIRST_SHARE))
            else:
                remaining = length * wrap_angle(lh - heading) * turn_sign / abs(segment.turn)
            if remaining <= 0.0:
                break
            vx, vy, _ = pb.getBaseVelocity(body, client)[0]
            room = max(0.0, remaining - math.hypot(vx, vy) * lead)
            top = self.ARC_SPEED if arc else self.SPEED
            speed = max(self.MIN_SPEED, min(top, math.sqrt(2.0 * self.BRAKING * room)))
            drive.set_motion(sign * speed, curvature)
            if self._steps(self._period):
                return True
        drive.set_motion(0.0, curvature)
        return False


def end_pose(pose: Pose, segments: list[Segment], pivot: Point) -> Pose:
    """The pose after ``segments`` from ``pose`` by the bicycle model (for tests and docs)."""
    for segment in segments:
        pose = arc_pose(pose, pivot, segment.distance, segment.turn, 1.0)
    return pose
