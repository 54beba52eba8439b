"""Robots the maze can drive: robot files, bodies, drives.

* ``spec``: robot files (``assets/robots/*.toml``), validated into a ``RobotSpec``;
* ``urdf``: a URDF read and bounded before pybullet sees it;
* ``body``: the pybullet body, scaled to its footprint and measured;
* ``commands``: what one env step asks of a robot (``Move``, ``Twist``);
* ``drives``: holonomic, differential and Ackermann drives, each with its exact kinematic model
  and its dynamic controller;
* ``robot``: ``Robot`` (a body and its drive) and ``make_robot``, which also detects the drive
  of a bare URDF (``robot_drive`` reads it without an env).
"""

from __future__ import annotations

from bullet_maze.robots.commands import Command, Move, Twist
from bullet_maze.robots.drives import (
    AckermannDrive,
    DifferentialDrive,
    Drive,
    DriveLimits,
    HolonomicDrive,
    wrap_angle,
)
from bullet_maze.robots.robot import Robot, RobotState, make_robot, robot_drive
from bullet_maze.robots.spec import (
    DRIVES,
    RobotSpec,
    available_robots,
    load_robot_spec,
    resolve_robot,
)
from bullet_maze.robots.urdf import MAX_LINKS

__all__ = [
    "DRIVES",
    "MAX_LINKS",
    "AckermannDrive",
    "Command",
    "DifferentialDrive",
    "Drive",
    "DriveLimits",
    "HolonomicDrive",
    "Move",
    "Robot",
    "RobotSpec",
    "RobotState",
    "Twist",
    "available_robots",
    "load_robot_spec",
    "make_robot",
    "resolve_robot",
    "robot_drive",
    "wrap_angle",
]
