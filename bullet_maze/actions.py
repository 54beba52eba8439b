"""The discrete actions: section V.A's four compass directions and a wheeled robot's native
commands. What each set asks of a robot, and the noise they share, is ``bullet_maze.action_sets``.
"""

from __future__ import annotations

from enum import IntEnum

import numpy as np


class Action(IntEnum):
    """Section V.A: the robot chooses among up, down, left and right (the compass set)."""

    UP = 0
    DOWN = 1
    LEFT = 2
    RIGHT = 3


DIRECTIONS = np.array([(0.0, 1.0), (0.0, -1.0), (-1.0, 0.0), (1.0, 0.0)])
"""Unit vector of each action, indexed by ``Action``: x to the right, y up."""


class NativeAction(IntEnum):
    """The native commands of a wheeled robot (``actions="native"``)."""

    FORWARD = 0
    BACKWARD = 1
    TURN_LEFT = 2
    TURN_RIGHT = 3
