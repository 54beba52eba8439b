"""A robot's own physics step (``[physics]`` of its robot file) is faithful: the zoo's compass
steps at their coarser step end where the same steps at 240 Hz do, and the husky's native and
continuous commands at 120 Hz follow 240 Hz's.

The check is a convergence check, from the same states: each compass step starts with the robot
at rest (where every compass step ends) at the same seeded pose, once at the robot's physics
settings and once at the fine reference, 240 Hz with the env's 10 solver iterations, and their
end poses are compared (``TOLERANCES``). The same steps at 240 Hz with 50 solver iterations
measure the fine reference's own spread. On eight seeds of ten steps (2026-12-02, the compass
controller that stops the wheels on the measured speed): the husky's end poses spread 0.047
units on average there and differ from its 40 Hz / 6-iteration ones by 0.11-0.13 (0.118
overall, at most 0.29; at 60 Hz / 5 it.: 0.079, at most 0.30); the rover, whose casters bounce
at any step, spreads 0.19 at 240 Hz and differs from 120 Hz by 0.11-0.27 (0.18, at most 0.52),
so its mean is also bounded by its own spread. Native and continuous commands are open-loop,
so the poses after five in a row are compared the same way (``COMMAND_TOLERANCES``; 40 states:
0.106 and 0.090 units on average, against 240 Hz's own 0.062 and 0.042).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import gymnasium as gym
import numpy as np
import pytest

from bullet_maze.robots import resolve_robot

FINE = {"time_step": 1.0 / 240.0, "solver_iterations": 10}
"""The fine reference: pybullet's default step with the env's solver iterations."""
FINER = {"time_step": 1.0 / 240.0, "solver_iterations": 50}
"""The fine reference's own spread: the same step, solved to pybullet's default iterations."""
POSES = 10
"""Compass steps compared per robot."""
TOLERANCES = {"husky": (0.2, 0.5, 0.1, 0.3), "rover": (0.5, 1.2, 0.3, 0.8)}
"""Coarse against fine, per robot: mean and largest end-position difference (maze units; the
step is 5), mean and largest heading difference (radians)."""


def _end_poses(
    make_env: Callable[..., gym.Env], robot: str, settings: dict[str, float | int], seed: int
) -> np.ndarray:
    env = make_env(maze="open", robot=robot, mode="dynamic", noise_variance=0.0, **settings)
    env.reset(seed=0)
    base = env.unwrapped
    rng = np.random.default_rng(seed)
    ends = []
    for _ in range(POSES):
        x, y = rng.uniform(100.0, 200.0, 2)
        heading = rng.uniform(-math.pi, math.pi)
        action = int(rng.integers(4))
        base.robot.place(x, y, heading)
        base._x, base._y, base._heading = x, y, heading  # the env's copy of the pose
        obs, _, _, _, info = env.step(action)
        assert not info["collision"]
        ends.append([*obs[:3], x, y])
    return np.array(ends)


def _differences(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    position = np.hypot(*(a[:, :2] - b[:, :2]).T)
    heading = np.abs(np.remainder(a[:, 2] - b[:, 2] + math.pi, 2 * math.pi) - math.pi)
    return position, heading


def test_robot_files_set_their_physics_per_action_set(make_env: Callable[..., gym.Env]) -> None:
    husky = resolve_robot("husky")
    assert husky.physics_defaults("compass") == {
        "time_step": pytest.approx(1 / 40),
        "solver_iterations": 6,
    }
    for actions in ("native", "continuous"):
        assert husky.physics_defaults(actions) == {
            "time_step": pytest.approx(1 / 120),
            "solver_iterations": 5,
        }
    assert resolve_robot("rover").physics_defaults("compass") == {
        "time_step": pytest.approx(1 / 120)
    }
    # The disc (the paper's robot) keeps the env's physics; the racecar's compass manoeuvres
    # run at 120 Hz, its native and continuous commands at the env's.
    assert resolve_robot("disc").physics == ()
    racecar = resolve_robot("racecar")
    assert racecar.physics_defaults("compass") == {"time_step": pytest.approx(1 / 120)}
    assert racecar.physics_defaults("native") == {}
    assert racecar.physics_defaults("continuous") == {}
    env = make_env(robot="husky", mode="dynamic")
    assert env.unwrapped.physics.time_step == pytest.approx(1 / 40)
    assert env.unwrapped.physics.solver_iterations == 6
    native = make_env(robot="husky", mode="dynamic", actions="native")
    assert native.unwrapped.physics.time_step == pytest.approx(1 / 120)
    assert native.unwrapped.physics.solver_iterations == 5
    rover = make_env(robot="rover", mode="dynamic", actions="native")
    assert rover.unwrapped.physics.time_step == pytest.approx(1 / 240)
    assert rover.unwrapped.physics.solver_iterations == 10
    # An env argument wins over the robot file.
    mine = make_env(robot="husky", mode="dynamic", time_step=1 / 120)
    assert mine.unwrapped.physics.time_step == pytest.approx(1 / 120)
    assert mine.unwrapped.physics.solver_iterations == 6


@pytest.mark.parametrize(("robot", "seed"), [("husky", 11), ("rover", 12)])
def test_coarse_compass_steps_end_where_fine_steps_do(
    make_env: Callable[..., gym.Env], robot: str, seed: int
) -> None:
    own = resolve_robot(robot).physics_defaults("compass")
    assert own["time_step"] > FINE["time_step"]  # a coarser step is what is checked
    coarse = _end_poses(make_env, robot, {}, seed)
    fine = _end_poses(make_env, robot, FINE, seed)
    finer = _end_poses(make_env, robot, FINER, seed)
    position, heading = _differences(coarse, fine)
    spread, spread_heading = _differences(finer, fine)
    mean, most, mean_heading, most_heading = TOLERANCES[robot]
    assert position.mean() <= mean
    assert position.max() <= most
    assert heading.mean() <= mean_heading
    assert heading.max() <= most_heading
    # No worse than the fine step's own spread allows (1.5 times it, and 0.1 units).
    assert position.mean() <= max(mean / 2.0, 1.5 * spread.mean() + 0.1)
    assert heading.mean() <= max(mean_heading / 2.0, 1.5 * spread_heading.mean() + 0.05)
    # The coarse steps are steps: they moved their length (5 units) and stopped near it.
    moved = np.hypot(*(coarse[:, :2] - coarse[:, 3:5]).T)
    assert np.all(np.abs(moved - 5.0) < 1.0)


COMMANDS = 5
"""Native or continuous commands in a row from each state at rest (0.5 s of simulated time)."""
COMMAND_TOLERANCES = {"native": (0.2, 1.0, 0.05, 0.3), "continuous": (0.2, 0.8, 0.05, 0.2)}
"""The husky's open-loop commands at 120 Hz against 240 Hz, per action set: mean and largest
pose difference after each command (maze units), mean and largest heading difference (rad)."""


def _command_poses(
    make_env: Callable[..., gym.Env], actions: str, settings: dict[str, float | int], seed: int
) -> np.ndarray:
    env = make_env(
        maze="open",
        robot="husky",
        mode="dynamic",
        actions=actions,
        noise_variance=0.0,
        **settings,
    )
    env.reset(seed=0)
    base = env.unwrapped
    rng = np.random.default_rng(seed)
    poses = []
    for _ in range(POSES):
        x, y = rng.uniform(100.0, 200.0, 2)
        heading = rng.uniform(-math.pi, math.pi)
        base.robot.place(x, y, heading)
        base._x, base._y, base._heading = x, y, heading
        for _ in range(COMMANDS):
            if actions == "native":
                action: object = int(rng.integers(4))
            else:
                action = rng.uniform(-1.0, 1.0, 2).astype(np.float32)
            obs, _, _, _, info = env.step(action)
            assert not info["collision"]
            poses.append(obs[:3])
    return np.array(poses)


@pytest.mark.parametrize(("actions", "seed"), [("native", 21), ("continuous", 22)])
def test_husky_commands_at_120_hz_follow_240_hz(
    make_env: Callable[..., gym.Env], actions: str, seed: int
) -> None:
    # Open-loop wheel speeds, so the poses drift apart over the five commands; the bound is the
    # fine step's own drift (10 against 50 solver iterations) as for the compass steps.
    own = resolve_robot("husky").physics_defaults(actions)
    assert own["time_step"] > FINE["time_step"]
    coarse = _command_poses(make_env, actions, {}, seed)
    fine = _command_poses(make_env, actions, FINE, seed)
    finer = _command_poses(make_env, actions, FINER, seed)
    position, heading = _differences(coarse, fine)
    spread, spread_heading = _differences(finer, fine)
    mean, most, mean_heading, most_heading = COMMAND_TOLERANCES[actions]
    assert position.mean() <= mean
    assert position.max() <= most
    assert heading.mean() <= mean_heading
    assert heading.max() <= most_heading
    assert position.mean() <= 1.5 * spread.mean() + 0.1
    assert heading.mean() <= 1.5 * spread_heading.mean() + 0.05
    # They moved: the husky drove (full speed ahead or astern is 1.87 units per command; the
    # seeded continuous commands average about 0.3 units per command, from rest).
    steps = np.diff(coarse[:, :2].reshape(POSES, COMMANDS, 2), axis=1)
    assert np.hypot(steps[..., 0], steps[..., 1]).mean() > 0.2
