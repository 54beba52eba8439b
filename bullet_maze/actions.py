"""The four actions of section V.A and their unit directions in maze coordinates (y up)."""

from __future__ import annotations

from enum import IntEnum

import numpy as np


class Action(IntEnum):
    """Section V.A: the robot chooses among up, down, left and right."""

    UP = 0
    DOWN = 1
    LEFT = 2
    RIGHT = 3


DIRECTIONS = np.array([(0.0, 1.0), (0.0, -1.0), (-1.0, 0.0), (1.0, 0.0)])
"""Unit vector of each action, indexed by ``Action``: x to the right, y up."""
