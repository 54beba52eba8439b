"""Swappable robots: the disc, the husky through its wheels, and a user's URDF pushed as a body."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

from bullet_maze import Action, BulletMazeEnv
from bullet_maze.actions import DIRECTIONS

BOX_URDF = """<?xml version="1.0"?>
<robot name="crate">
  <link name="base">
    <inertial><mass value="5.0"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/>
    </inertial>
    <visual><geometry><box size="0.6 0.4 0.3"/></geometry></visual>
    <collision><origin xyz="0 0 0.15"/><geometry><box size="0.6 0.4 0.3"/></geometry></collision>
  </link>
</robot>
"""
"""A 0.6 x 0.4 m box: footprint radius sqrt(0.3^2 + 0.2^2) m = 3.61 maze units."""


@pytest.fixture
def box_urdf(tmp_path: Path) -> Path:
    path = tmp_path / "crate.urdf"
    path.write_text(BOX_URDF)
    return path


def test_disc_radius_matches_the_layout(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(maze="paper_narrow")
    assert env.unwrapped.robot.radius == pytest.approx(5.0, abs=0.01)
    bigger = make_env(maze="open", robot_radius=8.0)
    assert bigger.unwrapped.robot.radius == pytest.approx(8.0, abs=0.01)
    # The wider disc collides sooner: 8 units from the wall it cannot move down.
    bigger.reset(seed=0, options={"start": (150.0, 9.0)})
    assert bigger.step(Action.DOWN)[4]["collision"]


def test_husky_is_scaled_to_the_layouts_robot_radius(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(robot="husky")
    robot = env.unwrapped.robot
    assert robot.radius == pytest.approx(5.0, abs=0.01)
    assert 0.5 < robot.scale < 1.0  # the real husky's footprint radius is about 0.57 m


def test_husky_kinematic_step_faces_the_move_or_backs_up(
    make_env: Callable[..., gym.Env],
) -> None:
    env = make_env(maze="open", robot="husky", noise_variance=0.0)
    obs, _ = env.reset(seed=0)
    assert obs[2] == pytest.approx(math.pi / 2)
    obs, *_ = env.step(Action.RIGHT)  # a quarter turn to face the move, then drive
    assert np.allclose(obs, [155.0, 30.0, 0.0])
    obs, *_ = env.step(Action.LEFT)  # the move lies behind: it backs up, keeping its heading
    assert np.allclose(obs, [150.0, 30.0, 0.0])


def test_husky_dynamic_step_turns_then_drives(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(maze="open", robot="husky", mode="dynamic", noise_variance=0.0)
    obs, _ = env.reset(seed=0, options={"start": (150.0, 150.0, math.pi / 2)})
    wheels = env.unwrapped.robot.joint_states()
    for action, heading in ((Action.RIGHT, 0.0), (Action.DOWN, -math.pi / 2)):
        new, reward, _, _, info = env.step(action)
        assert not info["collision"]
        assert reward == pytest.approx(-0.01)
        # It faces the move or its opposite (a quarter turn either way is a tie that the
        # heading left by the last step decides; then it backs up)...
        assert abs(math.remainder(2.0 * (new[2] - heading), 2 * math.pi)) < 0.6
        # ...and stops at the target.
        target = obs[:2] + 5.0 * DIRECTIONS[action]
        assert np.hypot(*(new[:2] - target)) < 0.3
        obs = new
    assert env.unwrapped.robot.joint_states() != wheels  # the wheels turned


def test_husky_dynamic_steps_end_at_their_targets(make_env: Callable[..., gym.Env]) -> None:
    # A turn in place swings the husky's base round a pivot near its rear axle (up to 5 units
    # in a half turn); the drive aims at the step's target point, so the swing does not stay.
    env = make_env(maze="open", robot="husky", mode="dynamic", noise_variance=0.0)
    obs, _ = env.reset(seed=0, options={"start": (150.0, 150.0, math.pi / 2)})
    errors, lengths = [], []
    for action in np.random.default_rng(1).integers(0, 4, 20):
        new, _, _, _, info = env.step(action)
        assert not info["collision"]
        errors.append(np.hypot(*(new[:2] - obs[:2] - 5.0 * DIRECTIONS[action])))
        lengths.append(np.hypot(*(new[:2] - obs[:2])))
        obs = new
    assert np.mean(lengths) == pytest.approx(5.0, abs=0.1)
    assert np.mean(errors) < 0.2
    assert max(errors) < 0.5


def test_husky_dynamic_collision_reverts(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(maze="open", robot="husky", mode="dynamic")
    obs, _ = env.reset(seed=0, options={"start": (150.0, 8.0, -math.pi / 2)})
    new, reward, _, _, info = env.step(Action.DOWN)
    assert info["collision"]
    assert reward == -1.0
    assert np.allclose(new, obs, atol=1e-6)


def test_user_urdf_is_a_holonomic_body(
    make_env: Callable[..., gym.Env],
    box_urdf: Path,
) -> None:
    env = make_env(maze="open", robot=str(box_urdf), noise_variance=0.0)
    robot = env.unwrapped.robot
    assert robot.radius == pytest.approx(math.hypot(3.0, 2.0), abs=0.05)
    assert env.observation_space.shape == (2,)
    obs, _ = env.reset(seed=0)
    assert np.allclose(env.step(Action.RIGHT)[0], obs + np.array([5.0, 0.0]))
    assert env.unwrapped.optimal_steps <= make_env(maze="open").unwrapped.optimal_steps


def test_user_urdf_in_dynamic_mode(make_env: Callable[..., gym.Env], box_urdf: Path) -> None:
    env = make_env(maze="open", robot=box_urdf, mode="dynamic", noise_variance=0.0)
    obs, _ = env.reset(seed=0)
    new, _, _, _, info = env.step(Action.UP)
    assert not info["collision"]
    assert new[1] - obs[1] == pytest.approx(5.0, rel=0.05)


def test_user_urdf_can_be_rescaled(make_env: Callable[..., gym.Env], box_urdf: Path) -> None:
    env = make_env(robot=str(box_urdf), robot_radius=6.0)
    assert env.unwrapped.robot.radius == pytest.approx(6.0, abs=0.01)


def test_missing_urdf_names_the_path(tmp_path: Path) -> None:
    path = tmp_path / "ghost.urdf"
    with pytest.raises(FileNotFoundError, match=r"ghost\.urdf"):
        BulletMazeEnv(robot=str(path))


def test_malformed_urdf_names_the_path(tmp_path: Path) -> None:
    path = tmp_path / "broken.urdf"
    path.write_text("<robot name='x'><link name='a'>")
    with pytest.raises(ValueError, match=r"broken\.urdf"):
        BulletMazeEnv(robot=str(path))


def test_urdf_without_collision_geometry_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "ghost_shape.urdf"
    path.write_text(
        '<robot name="g"><link name="base"><visual><geometry><box size="1 1 1"/>'
        "</geometry></visual></link></robot>"
    )
    with pytest.raises(ValueError, match=r"ghost_shape\.urdf.*no collision geometry"):
        BulletMazeEnv(robot=str(path))
