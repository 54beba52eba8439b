"""What an action asks a robot to do in one env step: the command a drive realises.

* ``Move``: a displacement intent in maze coordinates (the paper's compass actions, and every
  action of a holonomic robot). Each drive realises it as it can: a holonomic body is pushed
  along it, a differential robot turns in place and drives (forwards or backwards, whichever
  needs the smaller turn); a car cannot (it would need a manoeuvre).
* ``Twist``: a motion in the robot's own frame: drive ``distance`` maze units along the
  heading while turning by ``turn`` radians, at constant curvature, over one control period
  (the native and continuous actions of wheeled robots). In kinematic mode the robot follows
  this arc exactly (the unicycle; for a car, the bicycle model about its rear axle); in dynamic
  mode the drive commands the wheel speeds (and steering angle) of that arc for the period and
  physics does the rest.
"""

from __future__ import annotations

from typing import NamedTuple


class Move(NamedTuple):
    """Displace the robot by (dx, dy) maze units."""

    dx: float
    dy: float


class Twist(NamedTuple):
    """Drive ``distance`` maze units along the heading (negative: backwards) while turning
    ``turn`` radians (positive: to the left), over ``duration`` seconds."""

    distance: float
    turn: float
    duration: float


Command = Move | Twist
"""A command for ``Robot.execute`` / ``Robot.kinematic_path``."""
