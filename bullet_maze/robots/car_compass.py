"""Compass actions for a car: a displacement intent realised by a short manoeuvre of arcs.

A car cannot turn in place, and turning to face a compass bearing would carry it about one
turning radius sideways and ahead (the racecar's tightest radius is 8.5 maze units against a
``step_size`` of 5), so it cannot realise a compass step by turning and driving as a
differential robot does. Its policy instead **keeps its heading** and displaces its base by
the intent ``(dx, dy)`` (noise included) with bicycle-model segments about the middle of its
driven axle, on arcs of radius ``R`` = ``RADIUS_SCALE`` (1.5) times its tightest (the
racecar: 12.8 units):

* in its own frame the intent is ``a`` ahead and ``b`` to the left;
* ``b = 0``: a straight drive of ``a`` (forwards or backwards);
* a **lane change** (an S of two arcs, turning by ``+phi`` then ``-phi``) moves it ``c``
  sideways and ``A(c) = 2 R sin(phi)`` along its heading, with ``1 - cos(phi) = |c| / (2 R)``,
  and leaves the heading unchanged. If ``|b| <= 2 R`` and ``A(|b|) <= |a|``: one lane change
  of ``b`` in the direction of ``a``, then a straight drive of the rest (``|a| - A``);
* otherwise (a step across the heading, ``|a|`` small): a **zig-zag** of ``m`` lane changes of
  ``b / m`` each, alternately forwards and backwards (the first in the direction of ``a``,
  forwards if ``a = 0``), ``m`` the smallest even number with ``|b| / m <= 2 R``, then a
  straight drive of ``a``. The racecar's step of 5 across its heading: two lane changes of
  2.5, each 11.0 units along the heading and 11.4 units of arc.

It never turns in place: every segment is an arc or a straight of non-zero length.

**Kinematic mode** follows those segments exactly (``arc_pose``); every arc is swept with the
footprint as ``arc_points`` chords, so collisions are found as for every other robot, and the
base ends exactly at the intent (floating-point error only, below 1e-9 units) with the heading
it started with. The swept region reaches ``A`` beyond the start along the heading (11.0 units
for the racecar's cross step), which is where a car meets walls a disc would not.

**Dynamic mode** (``CarCompassController``) drives the same path through the car's own
actuators: the steering hinges in position control, the rear wheels in velocity control, by
pure pursuit of the rear axle along the path, leg by leg (a leg: one driving direction), with
one correction from the measured pose if the base ends more than ``LATERAL_TOLERANCE`` across
or ``ALONG_TOLERANCE`` along its heading from the target. The heading it keeps is the one
measured at the start of each step, so its small errors accumulate over steps as a random
walk (the kinematic mode keeps it exactly). Measured on 60 random steps in ``open`` with the
default noise (120 Hz, the racecar's compass physics): 0.12 units from the target on average,
0.27 at the 90th percentile, at most 0.46; the heading changes by 0.04 rad per step on average
(at most 0.2); about 370 physics steps per compass step (``docs/robots.md``).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import pybullet as pb

from bullet_maze.params import METRES_PER_UNIT
from bullet_maze.robots.commands import Move
from bullet_maze.robots.drives import AckermannDrive, Point, Pose, arc_points, arc_pose
from bullet_maze.world import World

RADIUS_SCALE = 1.5
"""The manoeuvre's arcs' radius over the car's tightest (full lock), in both modes. Chosen on
the racecar in dynamic mode (60 random compass steps in ``open``, noise 0.3): at full lock its
tyres understeer (arc radius 0.95 m at 0.8 m/s against the bicycle model's 0.85 m) and the
pursuit has no steering left to correct, so steps end 0.19 units from their targets on average
(at most 1.14, with heading errors up to 0.36 rad) at 1.3 times full lock's radius, 0.12 (at
most 0.46; heading 0.04 on average) at 1.5, and at 1.7 the 20% longer legs gain nothing."""

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
            return [*segments, Segment(rest, 0.0)] if rest != 0.0 else segments
    count = 2 * math.ceil(abs(left) / (4.0 * radius))
    segments = []
    for k in range(count):
        segments.extend(lane_change(left / count, direction if k % 2 == 0 else -direction, radius))
    return [*segments, Segment(ahead, 0.0)] if ahead != 0.0 else segments


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
        """The manoeuvre's turning radius, maze units (about the driven axle):
        ``RADIUS_SCALE`` times the tightest."""
        return RADIUS_SCALE / self.drive.max_curvature

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
    """Drives a manoeuvre through the steering hinges and the rear wheels by pure pursuit of
    its bicycle-model path; see the module docstring. Every physics step after the first is
    checked for contacts when a ``World`` is watched.

    The plan is split into legs of one driving direction (a zig-zag has one per lane change;
    a lane change and its straight share one). Each leg starts at standstill with the hinges
    set (position control) to the first steering it needs; then, at every control update, the
    rear axle steers along the circle through the leg's point ``LOOKAHEAD`` ahead of the
    nearest point of the path (curvature ``2 y / d^2`` for that point ``d`` away and ``y`` to
    the left; within the steering limit), at up to ``SPEED`` (``ARC_SPEED`` while steering
    hard), braking for the leg's end on the path length left. The leg ends when the axle has
    passed its end point along the path's end tangent. The plan's arcs are ``RADIUS_SCALE``
    wider than full lock, which leaves the pursuit steering in hand.
    """

    SPEED = 1.5
    """m/s: the rear axle's top speed on a straight (the racecar's top speed is 2.45)..."""
    ARC_SPEED = 0.8
    """...and while steering beyond half lock, where faster tyres slip outwards (the
    racecar's arc radius at full lock, measured over 0.6 m at 240 Hz: 0.95-1.01 m at 0.5-0.8
    m/s, 1.48 m at 1.5 m/s, against the bicycle model's 0.85 m)."""
    MIN_SPEED = 0.1
    """m/s: the slowest speed commanded before a leg's end (no creeping)."""
    BRAKING = 4.0
    """m/s^2: the deceleration the speed profile assumes when it slows for a leg's end."""
    LOOKAHEAD = 2.0
    """Maze units ahead of the nearest path point that the pursuit steers at."""
    SAMPLE = 0.25
    """Maze units between the path points the pursuit follows."""
    STEER_TOLERANCE = 0.02
    """Radians: a leg starts when the hinges are within this of their first angles..."""
    STEER_TIMEOUT = 0.5
    """...or after this many seconds of waiting."""
    ALONG_TOLERANCE = 0.3
    """Maze units along the heading from the target that end the step without a correction..."""
    LATERAL_TOLERANCE = 0.5
    """...and across it."""
    MAX_CORRECTIONS = 1
    """Plans from the measured pose after the first."""
    MAX_SECONDS = 12.0
    """Simulated seconds a step may take at most (the racecar's cross step takes about 3)."""
    CONTROL_INTERVAL = 1.0 / 120.0
    """Seconds between control updates (2 physics steps at 240 Hz)."""

    def __init__(self, drive: AckermannDrive) -> None:
        self.drive = drive
        self._budget = 0
        self._substep = 0
        self._period = 1
        self._touched = False
        self._watch: World | None = None
        self._stop_on_touch = False

    def run(self, move: Move, watch: World | None, stop_on_touch: bool) -> bool:
        """Plan from the measured pose, pursue every leg, correct once if needed."""
        drive = self.drive
        physics = drive.physics
        self._period = max(1, round(self.CONTROL_INTERVAL / physics.time_step))
        self._budget = max(1, round(self.MAX_SECONDS / physics.time_step))
        self._substep = 0
        self._touched = False
        self._watch, self._stop_on_touch = watch, stop_on_touch
        s = METRES_PER_UNIT
        x0, y0, heading = drive.pose_metres()
        tx, ty = x0 / s + move.dx, y0 / s + move.dy
        radius = RADIUS_SCALE / drive.max_curvature
        target = move
        for _attempt in range(1 + self.MAX_CORRECTIONS):
            x, y, heading = drive.pose_metres()
            pose = (x / s, y / s, heading)
            for leg in legs(pose, plan(heading, target, radius), drive.axle, self.SAMPLE):
                if self._pursue(leg):
                    drive.set_motion(0.0, 0.0)
                    return True
            x, y, heading = drive.pose_metres()
            ex, ey = tx - x / s, ty - y / s
            along = ex * math.cos(heading) + ey * math.sin(heading)
            across = -ex * math.sin(heading) + ey * math.cos(heading)
            if abs(along) <= self.ALONG_TOLERANCE and abs(across) <= self.LATERAL_TOLERANCE:
                break
            target = Move(ex, ey)
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

    def _axle(self) -> Pose:
        """The driven axle's middle (maze units) and the heading."""
        x, y, heading = self.drive.pose_metres()
        ax, ay = self.drive.axle
        s = METRES_PER_UNIT
        c, n = math.cos(heading), math.sin(heading)
        return x / s + ax * c - ay * n, y / s + ax * n + ay * c, heading

    def _pursue(self, leg: Leg) -> bool:
        """Drive one leg (see the class docstring); whether a contact stopped it."""
        drive = self.drive
        client, body = drive.client, drive.body.id
        s = METRES_PER_UNIT
        points, left_after, sign = leg.points, leg.remaining, leg.direction
        last = len(points) - 1
        ex, ey = points[last]
        end_heading = leg.end_heading
        ux, uy = math.cos(end_heading), math.sin(end_heading)
        # Beyond its end the path goes on along its end tangent, so that the pursuit's last
        # lookahead points line the heading up with it instead of cutting across to the end.
        extend = math.ceil(self.LOOKAHEAD / self.SAMPLE) + 1
        ahead_points = points + [
            (ex + sign * ux * self.SAMPLE * k, ey + sign * uy * self.SAMPLE * k)
            for k in range(1, extend + 1)
        ]
        far = len(ahead_points) - 1
        kmax = drive.max_curvature / s  # 1/m
        lead = self._period * drive.physics.time_step
        nearest = 0
        steered = False
        while self._substep < self._budget:
            x, y, heading = self._axle()
            # The nearest path point, searched forwards from the last one.
            best = (points[nearest][0] - x) ** 2 + (points[nearest][1] - y) ** 2
            for k in range(nearest + 1, min(last + 1, nearest + 40)):
                d2 = (points[k][0] - x) ** 2 + (points[k][1] - y) ** 2
                if d2 < best:
                    best, nearest = d2, k
            past = ((x - ex) * ux + (y - ey) * uy) * sign
            if nearest == last and past >= 0.0:
                break
            look = nearest
            while look < far and (
                math.hypot(ahead_points[look][0] - x, ahead_points[look][1] - y) < self.LOOKAHEAD
            ):
                look += 1
            lx, ly = ahead_points[look][0] - x, ahead_points[look][1] - y
            c, n = math.cos(heading), math.sin(heading)
            ahead, across = lx * c + ly * n, -lx * n + ly * c
            d2 = ahead * ahead + across * across
            curvature = 2.0 * across / d2 / s if d2 > 1e-12 else 0.0
            curvature = min(kmax, max(-kmax, curvature))
            if nearest == last:
                remaining = max(0.0, -past) * s
            else:
                remaining = (left_after[nearest] + math.sqrt(best)) * s
            if not steered:
                if self._steer(curvature):
                    return True
                steered = True
            vx, vy, _ = pb.getBaseVelocity(body, client)[0]
            room = max(0.0, remaining - math.hypot(vx, vy) * lead)
            top = self.ARC_SPEED if abs(curvature) > 0.5 * kmax else self.SPEED
            speed = max(self.MIN_SPEED, min(top, math.sqrt(2.0 * self.BRAKING * room)))
            drive.set_motion(sign * speed, curvature)
            if self._steps(self._period):
                return True
        drive.set_motion(0.0, 0.0)
        return False

    def _steer(self, curvature: float) -> bool:
        """At standstill, set the hinges for ``curvature`` (1/m) and wait until they are
        there; whether a contact stopped it."""
        drive = self.drive
        drive.set_motion(0.0, curvature)
        targets = drive.steering_angles(curvature)
        hinges = [h.index for h in drive.hinges]
        waited, timeout = 0, max(1, round(self.STEER_TIMEOUT / drive.physics.time_step))
        while waited < timeout and self._substep < self._budget:
            states = pb.getJointStates(drive.body.id, hinges, physicsClientId=drive.client)
            if all(
                abs(state[0] - target) <= self.STEER_TOLERANCE
                for state, target in zip(states, targets, strict=True)
            ):
                return False
            if self._steps(self._period):
                return True
            waited += self._period
        return False


class Leg(NamedTuple):
    """Part of a manoeuvre driven in one direction, as the pursuit follows it."""

    points: list[Point]
    """The driven axle's path, maze units, every ``SAMPLE`` or closer."""
    remaining: list[float]
    """Path length from each point to the end."""
    direction: float
    """+1 forwards, -1 backwards."""
    end_heading: float


def legs(pose: Pose, segments: list[Segment], axle: Point, sample: float) -> list[Leg]:
    """The manoeuvre's legs from ``pose`` (see ``CarCompassController``)."""
    out: list[Leg] = []
    points: list[Point] = []
    direction = 0.0

    def axle_of(p: Pose) -> Point:
        c, n = math.cos(p[2]), math.sin(p[2])
        return p[0] + axle[0] * c - axle[1] * n, p[1] + axle[0] * n + axle[1] * c

    def close() -> None:
        if len(points) > 1:
            lengths = [0.0]
            for (x0, y0), (x1, y1) in zip(points[-1:0:-1], points[-2::-1], strict=True):
                lengths.append(lengths[-1] + math.hypot(x1 - x0, y1 - y0))
            out.append(Leg(list(points), lengths[::-1], direction, pose[2]))

    for segment in segments:
        sign = math.copysign(1.0, segment.distance)
        if sign != direction:
            close()
            points, direction = [axle_of(pose)], sign
        count = max(1, math.ceil(abs(segment.distance) / sample))
        for k in range(1, count + 1):
            points.append(axle_of(arc_pose(pose, axle, segment.distance, segment.turn, k / count)))
        pose = arc_pose(pose, axle, segment.distance, segment.turn, 1.0)
    close()
    return out


def end_pose(pose: Pose, segments: list[Segment], pivot: Point) -> Pose:
    """The pose after ``segments`` from ``pose`` by the bicycle model (for tests and docs)."""
    for segment in segments:
        pose = arc_pose(pose, pivot, segment.distance, segment.turn, 1.0)
    return pose
