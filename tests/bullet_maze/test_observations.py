"""Observations and action sets: the lidar against known geometry, the goal-conditioned Dict and
its vectorised reward, and Gymnasium's check_env on every action set and observation."""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from bullet_maze import Action, BulletMazeEnv
from bullet_maze.sensors import RAY_BATCH

from .conftest import SMALL_MAZE

WALL = "[[walls]]\ncenter = [40.0, 20.0]\nsize = [2.0, 10.0]\n"
"""A box whose left face is at x = 39, across y in [15, 25]."""


def test_lidar_reads_the_distance_to_known_walls(
    make_env: Callable[..., gym.Env], write_maze: Callable[[str], Path]
) -> None:
    env = make_env(maze=write_maze(SMALL_MAZE + WALL), observation="lidar", lidar_rays=8)
    obs, _ = env.reset(seed=0, options={"start": (20.0, 20.0)})
    assert obs.shape == (2 + 8,)
    ranges = obs[2:]
    # Rays every 45 degrees from +x (the disc has no heading): the box at 19, the arena's walls
    # (faces at 0 and 100) at 80 up, 20 left, 20 down; diagonals 20 sqrt 2 to the lower left.
    assert ranges[0] == pytest.approx(19.0, abs=1e-3)
    assert ranges[2] == pytest.approx(80.0, abs=1e-3)
    assert ranges[4] == pytest.approx(20.0, abs=1e-3)
    assert ranges[6] == pytest.approx(20.0, abs=1e-3)
    assert ranges[5] == pytest.approx(20.0 * math.sqrt(2.0), abs=1e-3)
    assert ranges[1] == pytest.approx(100.0)  # 80 sqrt 2 lies beyond the range (100)
    assert env.observation_space.contains(obs)


def test_lidar_turns_with_the_robot_and_clips_at_its_range(
    make_env: Callable[..., gym.Env], write_maze: Callable[[str], Path]
) -> None:
    env = make_env(
        maze=write_maze(SMALL_MAZE + WALL),
        robot="husky",
        robot_radius=2.0,
        observation="lidar",
        lidar_rays=4,
        lidar_range=50.0,
        noise_variance=0.0,
    )
    obs, _ = env.reset(seed=0, options={"start": (20.0, 20.0, math.pi / 2)})
    # Facing +y: ahead 80 is beyond the range (50), left 20, behind 20, right the box at 19.
    assert obs[3:] == pytest.approx([50.0, 20.0, 20.0, 19.0], abs=1e-3)
    for _ in range(2):
        obs, *_ = env.step(Action.UP)  # 10 units up: past the box (y up to 25)
    assert obs[1] == pytest.approx(30.0)
    assert obs[3:] == pytest.approx([50.0, 20.0, 30.0, 50.0], abs=1e-3)


@pytest.mark.parametrize("rays", [RAY_BATCH * 2, 16384, 20000])
def test_many_lidar_rays_cross_pybullets_batch_limit(rays: int) -> None:
    # pybullet answers a NumPy array of exactly 16,384 rays with nothing at all.
    env = BulletMazeEnv(maze="open", observation="lidar", lidar_rays=rays)
    try:
        obs, _ = env.reset(seed=0, options={"start": (150.0, 100.0)})
    finally:
        env.close()
    ranges = obs[2:]
    assert ranges.shape == (rays,)
    assert ranges[0] == pytest.approx(100.0, abs=1e-3)  # east wall at 300, clipped to 100
    assert ranges[rays * 3 // 4] == pytest.approx(100.0, abs=1e-3)  # 100 down to the floor edge
    assert np.all((ranges > 5.0) & (ranges <= 100.0))


@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        ({"lidar_rays": 0}, ValueError, r"lidar_rays must be in \[1, 65536\]"),
        ({"lidar_rays": True}, TypeError, r"lidar_rays must be"),
        ({"lidar_rays": 3.0}, TypeError, r"lidar_rays must be an integer"),
        ({"lidar_range": 4.0}, ValueError, r"lidar_range = 4 must exceed the robot's footprint"),
        ({"lidar_range": math.nan}, ValueError, r"lidar_range must be in"),
        ({"observation": "camera"}, ValueError, r"observation must be one of"),
    ],
)
def test_bad_observation_arguments(
    kwargs: dict[str, object], error: type[Exception], message: str
) -> None:
    with pytest.raises(error, match=message):
        BulletMazeEnv(observation=kwargs.pop("observation", "lidar"), **kwargs)


def test_the_goal_observation_and_its_vectorised_reward(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(maze="open", observation="goal")
    obs, _ = env.reset(seed=0, options={"goal": (100.0, 200.0)})
    assert set(obs) == {"observation", "achieved_goal", "desired_goal"}
    assert np.array_equal(obs["achieved_goal"], obs["observation"][:2])
    assert np.array_equal(obs["desired_goal"], [100.0, 200.0])
    assert env.observation_space.contains(obs)
    obs, reward, _, _, info = env.step(Action.UP)
    unwrapped = env.unwrapped
    assert unwrapped.compute_reward(obs["achieved_goal"], obs["desired_goal"], info) == reward
    # Relabelled at the achieved position, the same transition reaches the goal.
    assert unwrapped.compute_reward(obs["achieved_goal"], obs["achieved_goal"], info) == 5.0
    achieved = np.array([[0.0, 0.0], [10.0, 0.0], [20.0, 0.0]])
    desired = np.array([[0.0, 14.0], [10.0, 16.0], [20.0, 1.0]])
    infos = np.array([{"collision": False}, {"collision": False}, {"collision": True}])
    rewards = unwrapped.compute_reward(achieved, desired, infos)
    assert rewards.shape == (3,)
    assert rewards.tolist() == [5.0, -0.01, -1.0]  # a collision costs -1 whatever the goal
    assert unwrapped.compute_terminated(achieved, desired, infos).tolist() == [True, False, True]
    assert unwrapped.compute_truncated(achieved, desired, infos).tolist() == [False] * 3
    with pytest.raises(ValueError, match=r"goals must end in an axis of 2"):
        unwrapped.compute_reward(np.zeros(3), np.zeros(3), None)
    # Without the goal observation there is no compute_reward (tools take it for a GoalEnv).
    assert not hasattr(make_env(maze="open").unwrapped, "compute_reward")


CASES = [
    ("disc", "compass", "pose"),
    ("disc", "native", "pose"),
    ("disc", "continuous", "pose"),
    ("disc", "compass", "lidar"),
    ("disc", "continuous", "goal"),
    ("disc", "compass", "goal+lidar"),
    ("husky", "compass", "pose"),
    ("husky", "native", "lidar"),
    ("husky", "continuous", "goal"),
    ("rover", "compass", "goal+lidar"),
    ("rover", "native", "pose"),
    ("rover", "continuous", "lidar"),
    ("racecar", "native", "pose"),
    ("racecar", "native", "lidar"),
    ("racecar", "continuous", "goal"),
    ("racecar", "continuous", "goal+lidar"),
]
"""Every robot with every action set it supports, and every observation."""


@pytest.mark.parametrize(("robot", "actions", "observation"), CASES)
def test_check_env_passes_for_every_action_set_and_observation(
    make_env: Callable[..., gym.Env], robot: str, actions: str, observation: str
) -> None:
    env = make_env(robot=robot, actions=actions, observation=observation, lidar_rays=12)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env.unwrapped)


@pytest.mark.parametrize("robot", ["husky", "rover", "racecar"])
def test_check_env_passes_in_dynamic_mode(make_env: Callable[..., gym.Env], robot: str) -> None:
    env = make_env(robot=robot, mode="dynamic", actions="continuous", observation="goal+lidar")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env.unwrapped)


def test_gymnasium_make_takes_the_issues_example() -> None:
    env = gym.make("BulletMaze-v0", robot="racecar", actions="native", observation="lidar")
    try:
        obs, _ = env.reset(seed=0)
        assert obs.shape == (3 + 36,)
        obs, *_ = env.step(0)
        assert env.observation_space.contains(obs)
    finally:
        env.close()


@pytest.mark.parametrize(
    ("action", "error"),
    [
        (np.array([2.0, 0.0]), ValueError),
        (np.array([math.nan, 0.0]), ValueError),
        (np.array([0.5]), TypeError),
        ("forward", TypeError),
        (None, TypeError),
    ],
)
def test_bad_continuous_actions_are_clear_errors(
    make_env: Callable[..., gym.Env], action: object, error: type[Exception]
) -> None:
    env = make_env(robot="rover", actions="continuous").unwrapped
    env.reset(seed=0)
    with pytest.raises(error, match=r"action"):
        env.step(action)


@pytest.mark.parametrize("robot", ["rover", "racecar"])
def test_velocity_commands_carry_the_papers_noise(
    make_env: Callable[..., gym.Env], robot: str
) -> None:
    # Kinematic straight-ahead commands: the distance noise has the task's variance (0.3).
    env = make_env(maze="open", robot=robot, actions="continuous")
    obs, _ = env.reset(seed=5, options={"start": (150.0, 150.0, 0.0)})
    drive = env.unwrapped.robot.drive
    nominal = 0.5 * drive.max_speed * env.unwrapped.actions.period
    errors = []
    for i in range(600):
        if i % 40 == 0:
            obs, _ = env.reset(options={"start": (150.0, 150.0, 0.0)})
        new, *_ = env.step(np.array([0.5, 0.0], dtype=np.float32))
        dx, dy = new[0] - obs[0], new[1] - obs[1]
        # The base's arc length from its chord and turn (a car's base sits on its rear axle
        # to within 0.1 units, so its circle is the axle's to a part in 10^4).
        sign = math.copysign(1.0, dx * math.cos(obs[2]) + dy * math.sin(obs[2]))
        turn = math.remainder(new[2] - obs[2], 2 * math.pi)
        along = sign * math.hypot(dx, dy)
        if abs(turn) > 1e-12:
            along *= (turn / 2) / math.sin(turn / 2)
        errors.append(along - nominal)
        obs = new
    errors = np.array(errors)
    n = len(errors)
    assert abs(errors.mean()) < 4 * math.sqrt(0.3 / n)
    assert abs(errors.var(ddof=1) - 0.3) < 4 * 0.3 * math.sqrt(2 / (n - 1))
