"""A car's compass actions (``bullet_maze.robots.car_compass``): each intent is reached within
the stated error in both modes, by arcs and straights only (never a turn in place), walls stop
it with a collision in both modes, the same seed gives the same rollout bit for bit,
``check_env`` passes, and bad inputs are named."""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable

import gymnasium as gym
import numpy as np
import pybullet as pb
import pytest
from gymnasium.utils.env_checker import check_env

from bullet_maze import Action, BulletMazeEnv
from bullet_maze.robots import Move
from bullet_maze.robots.car_compass import (
    RADIUS_SCALE,
    CarCompassController,
    end_pose,
    lane_change_advance,
    plan,
)

INTENTS = {Action.UP: (0.0, 5.0), Action.DOWN: (0.0, -5.0), Action.LEFT: (-5.0, 0.0)}
INTENTS[Action.RIGHT] = (5.0, 0.0)
R = 12.78  # the racecar's manoeuvre radius, maze units (1.5 x its tightest, 8.52)


@pytest.mark.parametrize("heading", [math.pi / 2, 0.0, -2.0, 0.3])
@pytest.mark.parametrize("move", [(0.0, 5.0), (0.0, -5.0), (-5.0, 0.0), (5.0, 0.0), (0.7, -4.6)])
def test_the_plan_reaches_the_intent_exactly_by_arcs_and_straights(
    heading: float, move: tuple[float, float]
) -> None:
    segments = plan(heading, Move(*move), R)
    start = (100.0, 50.0, heading)
    end = end_pose(start, segments, (-0.1, 0.0))
    assert end[0] == pytest.approx(100.0 + move[0], abs=1e-9)
    assert end[1] == pytest.approx(50.0 + move[1], abs=1e-9)
    assert math.remainder(end[2] - heading, 2 * math.pi) == pytest.approx(0.0, abs=1e-9)
    for segment in segments:  # never a turn in place; no arc tighter than the radius
        assert segment.distance != 0.0
        assert abs(segment.turn) <= abs(segment.distance) / R + 1e-12
    assert len(segments) <= 5


def test_a_step_across_the_heading_is_a_zig_zag_and_along_it_a_drive() -> None:
    across = plan(math.pi / 2, Move(5.0, 0.0), R)
    assert [math.copysign(1, s.distance) for s in across] == [1, 1, -1, -1]
    assert sum(abs(s.distance) for s in across) == pytest.approx(4 * R * math.acos(1 - 2.5 / 2 / R))
    assert plan(math.pi / 2, Move(0.0, 5.0), R) == [(5.0, 0.0)]
    # A little sideways noise on a step along the heading: one lane change and a straight.
    along = plan(math.pi / 2, Move(0.3, 5.0), R)
    assert len(along) == 3
    assert along[2].distance == pytest.approx(5.0 - lane_change_advance(0.3, R))
    assert plan(0.0, Move(0.0, 0.0), R) == []


@pytest.mark.parametrize(
    ("move", "radius", "named"),
    [((math.nan, 1.0), R, "finite"), ((1.0, math.inf), R, "finite"), ((1.0, 0.0), 0.0, "radius")],
)
def test_bad_plan_inputs_are_named(move: tuple[float, float], radius: float, named: str) -> None:
    with pytest.raises(ValueError, match=named):
        plan(0.0, Move(*move), radius)


def test_the_racecar_takes_compass_actions_and_keeps_its_heading_kinematically(
    make_env: Callable[..., gym.Env],
) -> None:
    env = make_env(maze="open", robot="racecar", noise_variance=0.0)
    drive = env.unwrapped.robot.drive
    assert not drive.turns_in_place
    assert 1.0 / drive.max_curvature * RADIUS_SCALE == pytest.approx(R, abs=0.01)
    for action, (dx, dy) in INTENTS.items():
        obs, _ = env.reset(seed=0, options={"start": (150.0, 150.0, math.pi / 2)})
        new, _, _, _, info = env.step(action)
        assert not info["collision"]
        assert new[:2] == pytest.approx(obs[:2] + np.array((dx, dy)), abs=1e-9)
        assert new[2] == pytest.approx(math.pi / 2, abs=1e-12)


def test_each_intent_is_reached_dynamically_through_the_wheels_and_hinges(
    make_env: Callable[..., gym.Env],
) -> None:
    env = make_env(maze="open", robot="racecar", mode="dynamic", noise_variance=0.0)
    robot = env.unwrapped.robot
    drive = robot.drive
    wheels = [w.index for w in drive.driven]
    hinges = [h.index for h in drive.hinges]
    turned: dict[int, list[float]] = {}
    record = CarCompassController._steps

    def watched(self: CarCompassController, count: int) -> bool:
        for j in hinges:
            turned[j].append(pb.getJointState(robot.body_id, j, robot.client)[0])
        return record(self, count)

    for action, (dx, dy) in INTENTS.items():
        obs, _ = env.reset(seed=0, options={"start": (150.0, 150.0, math.pi / 2)})
        turned.update({j: [] for j in hinges})
        rolled_before = [pb.getJointState(robot.body_id, w, robot.client)[0] for w in wheels]
        drive.manoeuvre.controller._steps = watched.__get__(drive.manoeuvre.controller)
        new, _, _, _, info = env.step(action)
        del drive.manoeuvre.controller._steps
        assert not info["collision"]
        # The stated bound: within 0.5 units of the intent, the heading within 0.25 rad.
        assert np.hypot(*(new[:2] - obs[:2] - np.array((dx, dy)))) < 0.5
        assert abs(new[2] - obs[2]) < 0.25
        rolled = [pb.getJointState(robot.body_id, w, robot.client)[0] for w in wheels]
        assert all(abs(a - b) > 1.0 for a, b in zip(rolled, rolled_before, strict=True))
        if action in (Action.LEFT, Action.RIGHT):  # the hinges steered both ways
            for angles in turned.values():
                assert max(angles) > 0.2
                assert min(angles) < -0.2


def test_the_car_never_turns_in_place_dynamically(make_env: Callable[..., gym.Env]) -> None:
    # Between control updates the heading changes by no more than the path driven allows at
    # the steering limit (with slack for the tyres' slip): a turn in place would break this.
    env = make_env(maze="open", robot="racecar", mode="dynamic", noise_variance=0.0)
    robot = env.unwrapped.robot
    env.reset(seed=0, options={"start": (150.0, 150.0, math.pi / 2)})
    poses: list[tuple[float, float, float]] = []
    controller = robot.drive.manoeuvre.controller
    record = CarCompassController._steps

    def watched(self: CarCompassController, count: int) -> bool:
        poses.append(robot.pose())
        return record(self, count)

    controller._steps = watched.__get__(controller)
    env.step(Action.RIGHT)
    del controller._steps
    curvature = robot.drive.max_curvature
    assert len(poses) > 50
    for (x0, y0, h0), (x1, y1, h1) in itertools.pairwise(poses):
        moved = math.hypot(x1 - x0, y1 - y0)
        assert abs(math.remainder(h1 - h0, 2 * math.pi)) <= 1.5 * curvature * moved + 1e-3


@pytest.mark.parametrize("mode", ["kinematic", "dynamic"])
@pytest.mark.parametrize(
    ("start", "action"),
    [
        ((150.0, 5.5), Action.DOWN),  # straight back into the wall below
        ((150.0, 287.0), Action.RIGHT),  # the zig-zag's first lane change meets the wall ahead
    ],
)
def test_a_wall_stops_the_car_with_a_collision(
    make_env: Callable[..., gym.Env], mode: str, start: tuple[float, float], action: Action
) -> None:
    # The kinematic sweep uses the footprint disc (radius 5 about the base); the racecar's
    # body reaches 0.7 units behind its base and 4.5 ahead, so physics may let one more step
    # through before the body itself touches.
    env = make_env(maze="open", robot="racecar", mode=mode, noise_variance=0.0)
    obs, _ = env.reset(seed=0, options={"start": (*start, math.pi / 2)})
    collisions = 0
    for _ in range(3):
        new, reward, _, _, info = env.step(action)
        if info["collision"]:
            collisions += 1
            assert reward == -1.0
            assert new == pytest.approx(obs, abs=1e-6)  # undone (revert_on_collision)
        assert 0.0 < new[1] < 300.0  # never through the wall
        obs = new
    assert collisions >= 1 if mode == "dynamic" else collisions == 3


def test_a_disc_would_not_meet_the_wall_the_cars_manoeuvre_meets(
    make_env: Callable[..., gym.Env],
) -> None:
    env = make_env(maze="open", robot="disc", noise_variance=0.0)
    env.reset(seed=0, options={"start": (150.0, 287.0)})
    assert not env.step(Action.RIGHT)[4]["collision"]


def test_same_seed_gives_bit_identical_car_compass_rollouts() -> None:
    def rollout(seed: int) -> bytes:
        env = gym.make("BulletMaze-v0", maze="paper", robot="racecar", mode="dynamic")
        env.action_space.seed(seed)
        trace = [env.reset(seed=seed)[0]]
        for _ in range(5):
            obs, reward, *_ = env.step(env.action_space.sample())
            trace.append(np.append(obs, reward))
        env.close()
        return np.concatenate(trace).tobytes()

    assert rollout(3) == rollout(3)
    assert rollout(3) != rollout(4)


@pytest.mark.parametrize("mode", ["kinematic", "dynamic"])
def test_check_env_passes_for_the_car_with_compass_actions(mode: str) -> None:
    env = BulletMazeEnv(robot="racecar", mode=mode, actions="compass")
    try:
        check_env(env, skip_render_check=True)
    finally:
        env.close()


def test_a_car_without_a_manoeuvre_is_a_clear_error() -> None:
    env = BulletMazeEnv(robot="racecar", actions="native")
    try:
        drive = env.robot.drive
        drive.manoeuvre = None
        with pytest.raises(ValueError, match=r"without a manoeuvre.*Move"):
            drive.path((150.0, 150.0, 0.0), Move(1.0, 0.0))
        from bullet_maze.action_sets import make_action_set

        with pytest.raises(ValueError, match=r"cannot turn in place.*actions='native'"):
            make_action_set("compass", env.robot, 5.0, 0.1)
    finally:
        env.close()


def test_random_intents_end_exactly_where_they_aim() -> None:
    # Adversarial sizes and headings (a step of up to 10 times the layout's, any direction).
    rng = np.random.default_rng(11)
    for _ in range(300):
        heading = rng.uniform(-math.pi, math.pi)
        move = Move(*rng.normal(0.0, 1.0, 2) * rng.choice([1e-12, 1e-3, 1.0, 5.0, 50.0]))
        segments = plan(heading, move, R)
        end = end_pose((0.0, 0.0, heading), segments, (0.0, 0.0))
        assert end[:2] == pytest.approx(move, abs=1e-8)
        assert all(s.distance != 0.0 for s in segments)
