"""bullet_maze: the robot maze of section V.A of Hwang, Li and Jiang, "Adaptive Exploration
Strategies for Reinforcement Learning", as a Gymnasium environment in headless pybullet.

Importing the package registers ``BulletMaze-v0`` (keyword arguments ``maze``, ``robot``,
``mode``, ...) and one id per shipped layout, ``BulletMaze-<layout>-v0``; each is capped at
5,000 steps by its ``max_episode_steps`` (section V.A).

Layouts: ``load_layout`` (a name, a TOML file or a generator spec such as
``"rooms:seed=3,door=30"``), ``generate_layout`` (the procedural families),
``layout_from_maze_map`` (a Gymnasium-Robotics / D4RL ``maze_map``), ``load_suite`` (named sets
of layouts with a development and a test split).
"""

from __future__ import annotations

from gymnasium.envs.registration import register, registry

from bullet_maze.action_sets import ActionParams
from bullet_maze.actions import Action, NativeAction
from bullet_maze.env import BulletMazeEnv
from bullet_maze.generators import FAMILIES, generate_layout
from bullet_maze.layout import (
    MazeLayout,
    Obstacle,
    Wall,
    available_layouts,
    layout_to_toml,
    load_layout,
)
from bullet_maze.maze_maps import layout_from_maze_map
from bullet_maze.params import MAX_EPISODE_STEPS, METRES_PER_UNIT, PhysicsParams, TaskParams
from bullet_maze.planning import PhysicalLimit, shortest_path
from bullet_maze.robots import Robot, RobotSpec, available_robots, load_robot_spec
from bullet_maze.sensors import LidarParams
from bullet_maze.suites import LayoutSuite, available_suites, load_suite
from bullet_maze.validation import validate_layout

ENTRY_POINT = "bullet_maze.env:BulletMazeEnv"


def _register_ids() -> list[str]:
    ids: dict[str, dict[str, str]] = {"BulletMaze-v0": {}}
    ids.update({f"BulletMaze-{name}-v0": {"maze": name} for name in available_layouts()})
    for env_id, kwargs in ids.items():
        if env_id not in registry:
            register(
                id=env_id,
                entry_point=ENTRY_POINT,
                max_episode_steps=MAX_EPISODE_STEPS,
                kwargs=kwargs,
            )
    return list(ids)


ENV_IDS = _register_ids()
"""The registered ids."""

__all__ = [
    "ENV_IDS",
    "FAMILIES",
    "MAX_EPISODE_STEPS",
    "METRES_PER_UNIT",
    "Action",
    "ActionParams",
    "BulletMazeEnv",
    "LayoutSuite",
    "LidarParams",
    "MazeLayout",
    "NativeAction",
    "Obstacle",
    "PhysicalLimit",
    "PhysicsParams",
    "Robot",
    "RobotSpec",
    "TaskParams",
    "Wall",
    "available_layouts",
    "available_robots",
    "available_suites",
    "generate_layout",
    "layout_from_maze_map",
    "layout_to_toml",
    "load_layout",
    "load_robot_spec",
    "load_suite",
    "shortest_path",
    "validate_layout",
]
