"""Each robot of the zoo drives as itself, in both modes: straight commands move it along its
heading (its wheels turn), turns change its heading, a car cannot turn in place (its compass
manoeuvre: test_car_compass.py), walls stop it with a collision, and the same seed gives the
same rollout bit for bit."""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable

import gymnasium as gym
import numpy as np
import pytest

from bullet_maze import Action, BulletMazeEnv, NativeAction, available_robots
from bullet_maze.robots.drives import arc_points, arc_pose

WHEELED = ("husky", "rover", "racecar")
MODES = ("kinematic", "dynamic")


def test_the_zoo_is_shipped() -> None:
    assert set(available_robots()) >= {"disc", "husky", "racecar", "rover"}


def test_each_robot_has_its_drive() -> None:
    kinds = {}
    for name in ("disc", *WHEELED):
        env = BulletMazeEnv(robot=name, actions="native")
        kinds[name] = (env.robot.drive.kind, env.robot.has_heading, env.robot.radius)
        env.close()
    assert kinds["disc"][:2] == ("holonomic", False)
    assert kinds["husky"][:2] == ("differential", True)
    assert kinds["rover"][:2] == ("differential", True)
    assert kinds["racecar"][:2] == ("ackermann", True)
    for _, _, radius in kinds.values():  # all scaled to the layout's robot radius
        assert radius == pytest.approx(5.0, abs=0.01)


def test_arc_pose_is_the_exact_unicycle_and_bicycle() -> None:
    # A quarter circle of radius 10 from the origin facing +x ends at (10, 10) facing +y.
    end = arc_pose((0.0, 0.0, 0.0), (0.0, 0.0), 10.0 * math.pi / 2, math.pi / 2, 1.0)
    assert end == pytest.approx((10.0, 10.0, math.pi / 2))
    # About a rear axle 2 behind the base: the axle follows the circle, the base stays 2 ahead.
    end = arc_pose((2.0, 0.0, 0.0), (-2.0, 0.0), 10.0 * math.pi / 2, math.pi / 2, 1.0)
    assert end == pytest.approx((10.0, 12.0, math.pi / 2))
    # A turn in place leaves the base where it is.
    assert arc_pose((3.0, 4.0, 0.5), (0.0, 0.0), 0.0, 1.0, 1.0) == pytest.approx((3.0, 4.0, 1.5))


def test_arc_points_stay_within_the_tolerance_of_the_arc() -> None:
    points, end = arc_points((0.0, 0.0, 0.0), (0.0, 0.0), 10.0 * math.pi / 2, math.pi / 2)
    assert end == pytest.approx((10.0, 10.0, math.pi / 2))
    assert len(points) > 10
    # Chord midpoints lie within half the contact tolerance of the circle round (0, 10).
    for (x0, y0), (x1, y1) in itertools.pairwise(points):
        mid = math.hypot((x0 + x1) / 2, (y0 + y1) / 2 - 10.0)
        assert 10.0 - mid <= 0.0005 + 1e-9
    # A straight command is one segment.
    assert len(arc_points((0.0, 0.0, 0.0), (0.0, 0.0), 5.0, 0.0)[0]) == 2


def _heading_change(before: np.ndarray, after: np.ndarray) -> float:
    return math.remainder(float(after[2] - before[2]), 2 * math.pi)


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("robot", WHEELED)
def test_forward_moves_along_the_heading_and_turns_the_wheels(
    make_env: Callable[..., gym.Env], robot: str, mode: str
) -> None:
    env = make_env(maze="open", robot=robot, mode=mode, actions="native", noise_variance=0.0)
    heading = 0.7
    obs, _ = env.reset(seed=0, options={"start": (150.0, 150.0, heading)})
    drive = env.unwrapped.robot.drive
    expected = drive.max_speed * env.unwrapped.actions.period  # maze units per step
    start = obs
    for _ in range(5):
        obs, reward, _, _, info = env.step(NativeAction.FORWARD)
        assert not info["collision"]
        assert reward == pytest.approx(-0.01)
    moved = obs[:2] - start[:2]
    direction = math.atan2(moved[1], moved[0])
    if mode == "kinematic":
        assert np.hypot(*moved) == pytest.approx(5 * expected)
        assert direction == pytest.approx(heading)
        assert obs[2] == pytest.approx(heading)
    else:
        # Physics: it accelerates from rest, so it covers less than five full steps.
        assert expected < np.hypot(*moved) < 5.5 * expected
        assert abs(math.remainder(direction - heading, 2 * math.pi)) < 0.1
        wheels = env.unwrapped.robot.wheel_velocities()
        assert len(wheels) >= 2
        top = drive.limits.wheel_speed
        assert all(0.5 * top < w < 1.5 * top for w in wheels), wheels  # all roll forwards


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("robot", WHEELED)
def test_backward_moves_against_the_heading(
    make_env: Callable[..., gym.Env], robot: str, mode: str
) -> None:
    env = make_env(maze="open", robot=robot, mode=mode, actions="native", noise_variance=0.0)
    obs, _ = env.reset(seed=0, options={"start": (150.0, 150.0, 0.0)})
    for _ in range(4):
        new, *_ = env.step(NativeAction.BACKWARD)
    assert new[0] < obs[0] - 2.0
    assert abs(new[1] - obs[1]) < 0.5
    if mode == "dynamic":
        assert all(w < 0.0 for w in env.unwrapped.robot.wheel_velocities())


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("robot", WHEELED)
def test_a_turn_changes_the_heading(
    make_env: Callable[..., gym.Env], robot: str, mode: str
) -> None:
    env = make_env(maze="open", robot=robot, mode=mode, actions="native", noise_variance=0.0)
    obs, _ = env.reset(seed=0, options={"start": (150.0, 150.0, 0.0)})
    steps = 2 if mode == "kinematic" else 5  # a car from rest needs speed to turn
    left = obs
    for _ in range(steps):
        left, *_ = env.step(NativeAction.TURN_LEFT)
    assert _heading_change(obs, left) > 0.1
    right = left
    for _ in range(steps):
        right, *_ = env.step(NativeAction.TURN_RIGHT)
    assert _heading_change(left, right) < -0.1
    if mode == "kinematic":
        drive = env.unwrapped.robot.drive
        period = env.unwrapped.actions.period
        if robot == "racecar":
            per_step = drive.max_curvature * drive.max_speed * period
        else:
            per_step = drive.max_turn_rate * period
            assert np.allclose(left[:2], obs[:2])  # a differential robot turns in place
        assert _heading_change(obs, left) == pytest.approx(2 * per_step)


@pytest.mark.parametrize("mode", MODES)
def test_the_car_cannot_turn_in_place(make_env: Callable[..., gym.Env], mode: str) -> None:
    env = make_env(
        maze="open", robot="racecar", mode=mode, actions="continuous", noise_variance=0.0
    )
    obs, _ = env.reset(seed=0, options={"start": (150.0, 150.0, 0.0)})
    # Full steering at zero speed for ten steps: the car stays put.
    for _ in range(10):
        new, *_ = env.step(np.array([0.0, 1.0], dtype=np.float32))
    assert abs(_heading_change(obs, new)) < 0.01
    assert np.hypot(*(new[:2] - obs[:2])) < 0.05
    # Steering while it drives turns it on an arc.
    turned = new
    for _ in range(5):
        turned, *_ = env.step(np.array([1.0, 1.0], dtype=np.float32))
    assert _heading_change(new, turned) > 0.1
    assert np.hypot(*(turned[:2] - new[:2])) > 1.0


def test_the_cars_turn_noise_is_bounded_by_its_curvature(
    make_env: Callable[..., gym.Env],
) -> None:
    env = make_env(maze="open", robot="racecar", actions="continuous")
    curvature = env.unwrapped.robot.drive.max_curvature
    obs, _ = env.reset(seed=1, options={"start": (150.0, 150.0, 0.0)})
    for _ in range(30):  # zero command: only the noise moves it
        new, *_ = env.step(np.array([0.0, 0.0], dtype=np.float32))
        travelled = np.hypot(*(new[:2] - obs[:2]))
        assert abs(_heading_change(obs, new)) <= curvature * travelled * 1.01 + 1e-9
        obs = new


def test_the_car_takes_compass_actions_by_a_manoeuvre() -> None:
    # It cannot turn in place; its compass steps are tested in test_car_compass.py.
    env = BulletMazeEnv(robot="racecar")
    assert not env.robot.drive.turns_in_place
    assert env.robot.drive.manoeuvre is not None
    env.close()


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("robot", ["disc", *WHEELED])
def test_a_wall_stops_the_robot_with_a_collision(
    make_env: Callable[..., gym.Env], robot: str, mode: str
) -> None:
    actions = "compass" if robot == "disc" else "native"
    env = make_env(maze="open", robot=robot, mode=mode, actions=actions, noise_variance=0.0)
    radius = env.unwrapped.robot.radius
    obs, _ = env.reset(seed=0, options={"start": (150.0, radius + 0.5, -math.pi / 2)})
    action = Action.DOWN if robot == "disc" else NativeAction.FORWARD
    collisions = 0
    for _ in range(8):
        new, reward, _, _, info = env.step(action)
        if info["collision"]:
            collisions += 1
            assert reward == -1.0
            assert np.allclose(new, obs, atol=1e-6)  # undone (revert_on_collision)
        assert new[1] > radius / 2  # never through the wall at y = 0
        obs = new
    assert collisions >= 1


@pytest.mark.parametrize(
    ("robot", "actions", "mode"),
    [
        ("husky", "compass", "dynamic"),
        ("rover", "compass", "dynamic"),
        ("husky", "native", "dynamic"),
        ("rover", "continuous", "dynamic"),
        ("racecar", "native", "dynamic"),
        ("racecar", "continuous", "kinematic"),
        ("rover", "native", "kinematic"),
    ],
)
def test_same_seed_gives_bit_identical_rollouts(robot: str, actions: str, mode: str) -> None:
    def rollout(seed: int) -> bytes:
        env = gym.make("BulletMaze-v0", maze="paper", robot=robot, mode=mode, actions=actions)
        env.action_space.seed(seed)
        trace = [env.reset(seed=seed)[0]]
        steps = 10 if actions == "compass" else 60
        for _ in range(steps):
            obs, reward, *_ = env.step(env.action_space.sample())
            trace.append(np.append(obs, reward))
        env.close()
        return np.concatenate(trace).tobytes()

    assert rollout(3) == rollout(3)
    assert rollout(3) != rollout(4)


@pytest.mark.parametrize("robot", ["husky", "rover"])
def test_differential_compass_steps_end_near_their_targets(
    make_env: Callable[..., gym.Env], robot: str
) -> None:
    env = make_env(maze="open", robot=robot, mode="dynamic", noise_variance=0.0)
    obs, _ = env.reset(seed=0, options={"start": (150.0, 150.0, math.pi / 2)})
    errors = []
    for action in np.random.default_rng(2).integers(0, 4, 12):
        new, _, _, _, info = env.step(action)
        assert not info["collision"]
        target = obs[:2] + 5.0 * np.array([(0, 1), (0, -1), (-1, 0), (1, 0)][action])
        errors.append(np.hypot(*(new[:2] - target)))
        obs = new
    assert np.mean(errors) < 0.5
    assert max(errors) < 1.0


@pytest.mark.parametrize("robot", ["husky", "rover"])
def test_a_straight_compass_step_rolls_every_wheel_its_distance(
    make_env: Callable[..., gym.Env], robot: str
) -> None:
    # Dynamic mode at the robot's own physics (the husky's compass steps run at 40 Hz): a step
    # along the heading is driven by the wheels, each turning about distance / radius.
    env = make_env(maze="open", robot=robot, mode="dynamic", noise_variance=0.0)
    obs, _ = env.reset(seed=0, options={"start": (150.0, 150.0, math.pi / 2)})
    robot_ = env.unwrapped.robot
    drive = robot_.drive
    wheels = drive.left + drive.right
    start = dict(zip(robot_._joints, robot_.joint_states(), strict=True))
    before = [start[w.index] for w in wheels]
    new, _, _, _, info = env.step(Action.UP)
    assert not info["collision"]
    after = dict(zip(robot_._joints, robot_.joint_states(), strict=True))
    moved = float(np.hypot(*(new[:2] - obs[:2])))
    assert moved == pytest.approx(5.0, abs=0.5)
    assert abs(_heading_change(obs, new)) < 0.1
    rolled = [w.sign * (after[w.index] - b) for w, b in zip(wheels, before, strict=True)]
    expected = moved * 0.1 / drive.wheel_radius  # METRES_PER_UNIT
    # Every wheel rolled forwards by about the distance (the husky's: 0.98x at 240 Hz, 0.94-1.06x
    # at its 40 Hz with 6 solver iterations; with 5, one wheel 0.88x: the base slid over it).
    assert all(0.9 * expected < r < 1.5 * expected for r in rolled), (rolled, expected)


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("robot", ["husky", "rover"])
def test_a_wall_stops_a_compass_step_with_a_collision(
    make_env: Callable[..., gym.Env], robot: str, mode: str
) -> None:
    # The compass steps of the differential robots (40 Hz and 120 Hz physics in dynamic mode)
    # into the wall at y = 0: reported, undone, never through it.
    env = make_env(maze="open", robot=robot, mode=mode, noise_variance=0.0)
    radius = env.unwrapped.robot.radius
    obs, _ = env.reset(seed=0, options={"start": (150.0, radius + 2.0, -math.pi / 2)})
    new, reward, _, _, info = env.step(Action.DOWN)
    assert info["collision"]
    assert reward == -1.0
    assert np.allclose(new, obs, atol=1e-6)
    body = env.unwrapped.robot
    assert body.position()[1] > radius / 2
