"""Perturbations and domain randomisation (issue 11, items 1, 2 and 4's env side): each one
changes what it should and nothing else, measured in short rollouts against an unperturbed env
of the same seed; ranges draw per episode, reproducibly; none set changes nothing; every bad
value is a clear error naming the parameter and the value."""

from __future__ import annotations

import math
import re
import subprocess
import sys
import tomllib
from collections.abc import Callable
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pybullet as pb
import pytest
from gymnasium.utils.env_checker import check_env

from bullet_maze import perturbations
from bullet_maze.actions import NativeAction
from bullet_maze.perturbations import LEVELS, NAMES, PERTURBATIONS, Range, applies, level_settings

ROOT = Path(__file__).resolve().parents[2]

Rollout = tuple[np.ndarray, np.ndarray, list[Any], list[dict[str, Any]]]


def rollout(env: gym.Env, actions: list[Any], seed: int = 3) -> Rollout:
    """True poses (reset included), rewards, observations and infos of an action sequence."""
    obs, info = env.reset(seed=seed)
    poses, rewards, observations, infos = [env.unwrapped.pose], [], [obs], [info]
    for action in actions:
        obs, reward, terminated, truncated, info = env.step(action)
        poses.append(env.unwrapped.pose)
        rewards.append(reward)
        observations.append(obs)
        infos.append(info)
        assert not terminated
        assert not truncated
    return np.array(poses), np.array(rewards), observations, infos


CYCLE = [0, 3, 1, 2] * 30
"""UP, RIGHT, DOWN, LEFT: a walk that stays near the start in the open arena."""


# -- Defaults and null values -----------------------------------------------------------------


def test_no_perturbation_leaves_info_and_draws_as_they_were(
    make_env: Callable[..., gym.Env],
) -> None:
    env = make_env(maze="open")
    _, _, _, infos = rollout(env, CYCLE)
    assert all("perturbation" not in info for info in infos)
    assert env.unwrapped.perturbation == {}


@pytest.mark.parametrize(
    ("kwargs", "null"),
    [
        (
            {"mode": "dynamic"},
            {
                "bias_along": 0.0,
                "bias_left": 0.0,
                "floor_friction_scale": 1.0,
                "wheel_friction_scale": 1.0,
                "latency_steps": 0,
                "observation_noise": 0.0,
            },
        ),
        (
            {"robot": "rover", "actions": "native"},
            {"bias_along": 0.0, "latency_steps": (0, 0), "heading_noise": 0.0},
        ),
        (
            {"robot": "rover", "actions": "native", "mode": "dynamic"},
            {"mass_scale": 1.0, "torque_scale": (1.0, 1.0), "noise_variance": (0.3, 0.3)},
        ),
    ],
)
def test_null_values_give_the_unperturbed_rollout_and_draws(
    make_env: Callable[..., gym.Env], kwargs: dict[str, Any], null: dict[str, Any]
) -> None:
    """Every perturbation at the value that perturbs nothing (fixed or a degenerate range)
    takes the perturbed path and gives the same poses, rewards and observations bit for bit,
    and leaves np_random where the unperturbed env leaves it."""
    actions = CYCLE[:40] if kwargs.get("actions") != "native" else [0, 2, 0, 3, 1] * 8
    plain, perturbed = make_env(maze="open", **kwargs), make_env(maze="open", **kwargs, **null)
    a, b = rollout(plain, actions), rollout(perturbed, actions)
    np.testing.assert_array_equal(a[0], b[0])
    np.testing.assert_array_equal(a[1], b[1])
    np.testing.assert_array_equal(np.array(a[2]), np.array(b[2]))
    assert (
        plain.unwrapped.np_random.bit_generator.state
        == perturbed.unwrapped.np_random.bit_generator.state
    )
    assert set(b[3][0]["perturbation"]) == set(null)


# -- Actuation bias ---------------------------------------------------------------------------


def test_bias_shifts_every_move_by_the_bias_in_the_commands_frame(
    make_env: Callable[..., gym.Env],
) -> None:
    """Kinematic disc, compass: each realised move is the unbiased one (same seed, same noise)
    plus bias_along along the action's direction and bias_left to its left."""
    plain = make_env(maze="open")
    biased = make_env(maze="open", bias_along=0.7, bias_left=-0.4)
    a, b = rollout(plain, CYCLE), rollout(biased, CYCLE)
    moves_a, moves_b = np.diff(a[0][:, :2], axis=0), np.diff(b[0][:, :2], axis=0)
    directions = {0: (0.0, 1.0), 1: (0.0, -1.0), 2: (-1.0, 0.0), 3: (1.0, 0.0)}
    for action, move_a, move_b in zip(CYCLE, moves_a, moves_b, strict=True):
        ux, uy = directions[action]
        expected = (0.7 * ux + 0.4 * uy, 0.7 * uy - 0.4 * ux)
        np.testing.assert_allclose(move_b - move_a, expected, atol=1e-9)
    np.testing.assert_array_equal(a[1], b[1])  # the same rewards: no collision, no goal


def test_bias_shifts_the_mean_dynamic_move(make_env: Callable[..., gym.Env]) -> None:
    """Dynamic disc: the mean realised UP move grows by bias_along (friction shortens every
    move by 0.02 %)."""
    actions = [0, 1] * 40
    plain, biased = (
        make_env(maze="open", mode="dynamic"),
        make_env(maze="open", mode="dynamic", bias_along=1.0),
    )
    a, b = rollout(plain, actions), rollout(biased, actions)
    up_a = np.diff(a[0][:, 1])[0::2].mean()
    up_b = np.diff(b[0][:, 1])[0::2].mean()
    assert up_b - up_a == pytest.approx(1.0, abs=0.01)


def test_bias_of_velocity_commands_lengthens_the_distance_and_turns_left(
    make_env: Callable[..., gym.Env],
) -> None:
    """Kinematic rover, native actions without noise: FORWARD drives bias_along farther (on an
    arc of bias_left / radius to the left), TURN_LEFT and TURN_RIGHT both turn bias_left /
    radius more to the left."""
    forward = NativeAction.FORWARD
    actions = [forward, NativeAction.TURN_LEFT, forward, NativeAction.TURN_RIGHT] * 5
    kwargs = {"maze": "open", "robot": "rover", "actions": "native", "noise_variance": 0.0}
    plain = make_env(**kwargs)
    biased = make_env(**kwargs, bias_along=0.5, bias_left=0.2)
    a, b = rollout(plain, actions), rollout(biased, actions)
    turn = 0.2 / plain.unwrapped.robot.radius
    for t, action in enumerate(actions):
        turn_a = a[0][t + 1][2] - a[0][t][2]
        turn_b = b[0][t + 1][2] - b[0][t][2]
        assert turn_b - turn_a == pytest.approx(turn, abs=1e-9)
        if action == forward:
            distance = math.dist(a[0][t][:2], a[0][t + 1][:2])  # a straight line
            chord = 2.0 * (distance + 0.5) / turn * math.sin(turn / 2.0)
            assert math.dist(b[0][t][:2], b[0][t + 1][:2]) == pytest.approx(chord, abs=1e-9)


@pytest.mark.parametrize("robot", ["disc", "rover"])
def test_bias_and_latency_apply_to_continuous_actions(
    make_env: Callable[..., gym.Env], robot: str
) -> None:
    """Continuous actions without noise: the disc's move (0.6, 0) * step_size and the rover's
    half-speed drive both travel bias_along farther, one step late."""
    kwargs = {"maze": "open", "robot": robot, "actions": "continuous", "noise_variance": 0.0}
    actions = [np.array([0.6, 0.0], dtype=np.float32)] * 4
    a = rollout(make_env(**kwargs), actions)
    b = rollout(make_env(**kwargs, bias_along=0.3, latency_steps=1), actions)
    np.testing.assert_array_equal(b[0][1], b[0][0])  # the first step holds
    for t in range(3):
        plain = math.dist(a[0][t][:2], a[0][t + 1][:2])
        assert math.dist(b[0][t + 1][:2], b[0][t + 2][:2]) == pytest.approx(plain + 0.3, abs=1e-9)


# -- Physics: friction, mass, motors ----------------------------------------------------------


def _travel(make_env: Callable[..., gym.Env], steps: int, action: int, **kwargs: Any) -> float:
    env = make_env(maze="open", mode="dynamic", noise_variance=0.0, **kwargs)
    env.reset(seed=0)
    x0, y0, _ = env.unwrapped.pose
    for _ in range(steps):
        env.step(action)
    x1, y1, _ = env.unwrapped.pose
    return math.hypot(x1 - x0, y1 - y0)


def test_floor_and_wheel_friction_change_how_far_a_dynamic_step_goes(
    make_env: Callable[..., gym.Env],
) -> None:
    """The disc's noise-free step of 5 units: without friction it covers exactly 5; more
    friction, less distance; floor and wheel coefficients multiply (pybullet), so the same
    factor on either does the same."""
    nominal = _travel(make_env, 1, 0)
    assert 4.99 < nominal < 5.0
    assert _travel(make_env, 1, 0, floor_friction_scale=0.0) == pytest.approx(5.0, abs=1e-9)
    assert _travel(make_env, 1, 0, floor_friction_scale=5.0) < nominal - 0.005
    assert _travel(make_env, 1, 0, wheel_friction_scale=5.0) == _travel(
        make_env, 1, 0, floor_friction_scale=5.0
    )
    # The rover's wheels slip on a slippery floor: two native FORWARD steps from rest.
    rover = {"robot": "rover", "actions": "native"}
    grip = _travel(make_env, 2, NativeAction.FORWARD, **rover)
    assert _travel(make_env, 2, NativeAction.FORWARD, **rover, wheel_friction_scale=0.1) < grip / 3


def test_heavier_robot_and_weaker_motors_change_dynamic_motion(
    make_env: Callable[..., gym.Env],
) -> None:
    """Three native FORWARD steps of the rover from rest (torque-limited acceleration): a
    heavier rover and weaker motors cover less; both are refused in kinematic mode."""
    rover = {"robot": "rover", "actions": "native"}
    nominal = _travel(make_env, 3, NativeAction.FORWARD, **rover)
    assert _travel(make_env, 3, NativeAction.FORWARD, **rover, mass_scale=3.0) < nominal - 0.01
    assert _travel(make_env, 3, NativeAction.FORWARD, **rover, torque_scale=0.2) < nominal - 0.05
    for name in ("mass_scale", "torque_scale", "floor_friction_scale", "wheel_friction_scale"):
        with pytest.raises(ValueError, match=rf"{name} = 2\.0 does not apply.*mode='dynamic'"):
            make_env(robot="rover", actions="native", **{name: 2.0})


def _dynamics(env: gym.Env) -> tuple[dict[int, tuple[float, ...]], dict[int, float], float]:
    unwrapped = env.unwrapped
    client, body = unwrapped.client_id, unwrapped.robot.body_id
    links = range(-1, pb.getNumJoints(body, physicsClientId=client))
    infos = {link: pb.getDynamicsInfo(body, link, physicsClientId=client) for link in links}
    masses = {link: (info[0], *info[2]) for link, info in infos.items()}
    frictions = {link: info[1] for link, info in infos.items()}
    ground = pb.getDynamicsInfo(unwrapped.world.ground_id, -1, physicsClientId=client)[1]
    return masses, frictions, ground


def test_physical_perturbations_change_only_their_own_property(
    make_env: Callable[..., gym.Env],
) -> None:
    """Masses and inertias, wheel frictions (not the body's, not the floor's), the floor's
    friction and the motors' force limits (not their speeds), each alone."""
    kwargs = {"robot": "husky", "actions": "native", "mode": "dynamic"}
    plain = make_env(**kwargs)
    masses, frictions, ground = _dynamics(plain)
    limits = plain.unwrapped.robot.drive.limits
    drive = plain.unwrapped.robot.drive
    wheels = {w.index for w in drive.left + drive.right}

    heavy = make_env(**kwargs, mass_scale=2.5)
    m, f, g = _dynamics(heavy)
    for link, values in masses.items():
        np.testing.assert_allclose(m[link], np.array(values) * 2.5, rtol=1e-12)
    assert (f, g, heavy.unwrapped.robot.drive.limits) == (frictions, ground, limits)

    slippery = make_env(**kwargs, wheel_friction_scale=0.5)
    m, f, g = _dynamics(slippery)
    assert (m, g) == (masses, ground)
    for link, value in frictions.items():
        assert f[link] == pytest.approx(value * 0.5 if link in wheels else value, rel=1e-6)

    floor = make_env(**kwargs, floor_friction_scale=0.25)
    m, f, g = _dynamics(floor)
    assert (m, f) == (masses, frictions)
    assert g == pytest.approx(ground * 0.25)

    weak = make_env(**kwargs, torque_scale=0.5)
    assert _dynamics(weak) == (masses, frictions, ground)
    weak_limits = weak.unwrapped.robot.drive.limits
    assert weak_limits.wheel_torque == limits.wheel_torque * 0.5
    assert weak_limits.wheel_speed == limits.wheel_speed
    assert weak_limits.turn_rate == limits.turn_rate


def test_the_cars_motor_strength_scales_wheels_and_steering(
    make_env: Callable[..., gym.Env],
) -> None:
    plain = make_env(robot="racecar", actions="native", mode="dynamic")
    weak = make_env(robot="racecar", actions="native", mode="dynamic", torque_scale=0.25)
    a, b = plain.unwrapped.robot.drive.limits, weak.unwrapped.robot.drive.limits
    assert (b.wheel_torque, b.steering_torque) == (a.wheel_torque / 4, a.steering_torque / 4)
    assert b.steering == a.steering


# -- Latency ----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("kwargs", "steps", "actions"),
    [
        ({}, 3, CYCLE[:40]),
        ({"mode": "dynamic"}, 2, CYCLE[:40]),
        ({"robot": "rover", "actions": "native", "mode": "dynamic"}, 2, [0, 0, 2, 0, 3, 1] * 3),
    ],
)
def test_latency_delays_every_command_by_exactly_k_steps(
    make_env: Callable[..., gym.Env], kwargs: dict[str, Any], steps: int, actions: list[int]
) -> None:
    """The delayed rollout's poses are the undelayed ones k steps later, bit for bit: the robot
    rests for the first k steps (no physics, no noise drawn), then executes each action with
    the noise the undelayed env gave it."""
    a = rollout(make_env(maze="open", **kwargs), actions)
    b = rollout(make_env(maze="open", latency_steps=steps, **kwargs), actions)
    np.testing.assert_array_equal(b[0][: steps + 1], np.repeat(a[0][:1], steps + 1, axis=0))
    np.testing.assert_array_equal(b[0][steps:], a[0][: len(a[0]) - steps])
    assert all(info["perturbation"]["latency_steps"] == steps for info in b[3])


def test_latency_queue_is_emptied_at_reset(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(maze="open", latency_steps=2)
    env.reset(seed=0)
    env.step(0)
    env.step(0)
    start = env.unwrapped.pose
    env.reset()
    env.step(3)
    assert env.unwrapped.pose == start  # the queued UPs of the last episode are gone


# -- Observation, heading and lidar noise -----------------------------------------------------


def test_observation_noise_changes_the_observation_only(
    make_env: Callable[..., gym.Env],
) -> None:
    """The true poses and the rewards are those of the unperturbed env (same seed); the
    observation is the true position plus noise of the stated spread; the heading too."""
    actions = [0, 2, 1, 3] * 50
    kwargs = {"maze": "open", "robot": "rover", "actions": "native"}
    a = rollout(make_env(**kwargs), actions)
    b = rollout(make_env(**kwargs, observation_noise=0.8, heading_noise=0.05), actions)
    np.testing.assert_array_equal(a[0], b[0])
    np.testing.assert_array_equal(a[1], b[1])
    error = np.array(b[2]) - b[0]
    error[:, 2] = (error[:, 2] + math.pi) % (2 * math.pi) - math.pi
    assert np.std(error[:, 0]) == pytest.approx(0.8, rel=0.2)
    assert np.std(error[:, 1]) == pytest.approx(0.8, rel=0.2)
    assert np.std(error[:, 2]) == pytest.approx(0.05, rel=0.2)
    assert abs(np.mean(error[:, :2])) < 0.15
    assert all(
        info["distance_to_goal"] == ia["distance_to_goal"]
        for info, ia in zip(b[3], a[3], strict=True)
    )


def test_observation_noise_stays_in_the_box_and_reaches_the_goal_observation(
    make_env: Callable[..., gym.Env],
) -> None:
    env = make_env(maze="open", observation="goal", observation_noise=50.0)
    obs, _ = env.reset(seed=1)
    for _ in range(30):
        assert env.observation_space.contains(obs)
        np.testing.assert_array_equal(obs["achieved_goal"], obs["observation"][:2])
        obs, *_ = env.step(0)


def test_lidar_noise_spreads_the_readings_of_rays_that_hit(
    make_env: Callable[..., gym.Env],
) -> None:
    """Same seed and actions: the readings differ from the noise-free lidar's by Gaussians of
    the stated spread on rays that hit a wall, not at all on rays that saw nothing."""
    actions = [0, 1] * 40
    kwargs = {"maze": "open", "observation": "lidar", "lidar_range": 60.0}
    a = rollout(make_env(**kwargs), actions)
    b = rollout(make_env(**kwargs, lidar_noise=1.5), actions)
    np.testing.assert_array_equal(a[0], b[0])
    clean, noisy = np.array(a[2])[:, 2:], np.array(b[2])[:, 2:]
    np.testing.assert_array_equal(np.array(a[2])[:, :2], np.array(b[2])[:, :2])
    hit = clean < 60.0
    assert 500 < hit.sum() < hit.size
    np.testing.assert_array_equal(noisy[~hit], 60.0)
    assert np.std(noisy[hit] - clean[hit]) == pytest.approx(1.5, rel=0.1)
    assert abs(np.mean(noisy[hit] - clean[hit])) < 0.15


# -- Domain randomisation ---------------------------------------------------------------------

RANDOMISED = {
    "robot": "rover",
    "actions": "native",
    "mode": "dynamic",
    "mass_scale": [0.5, 2.0],
    "torque_scale": {"low": 0.5, "high": 1.5},
    "floor_friction_scale": (0.6, 1.4),
    "latency_steps": [0, 2],
    "bias_left": [-0.5, 0.5],
    "observation_noise": 0.3,
    "noise_variance": [0.1, 0.6],
}


def _episodes(env: gym.Env, seed: int, episodes: int, steps: int) -> list[Rollout]:
    out = []
    for i in range(episodes):
        obs, info = env.reset(seed=seed if i == 0 else None)
        poses, rewards, observations, infos = [env.unwrapped.pose], [], [obs], [info]
        for t in range(steps):
            obs, reward, _, _, info = env.step([0, 2, 0, 1][t % 4])
            poses.append(env.unwrapped.pose)
            rewards.append(reward)
            observations.append(obs)
            infos.append(info)
        out.append((np.array(poses), np.array(rewards), observations, infos))
    return out


def test_ranges_draw_per_episode_reproducibly(make_env: Callable[..., gym.Env]) -> None:
    """Same seed, same draws and bit-identical rollouts; every episode its own draws, within
    the ranges, reported at reset and at every step, and applied to the body."""
    first = _episodes(make_env(maze="open", **RANDOMISED), 11, 4, 12)
    env = make_env(maze="open", **RANDOMISED)
    second = _episodes(env, 11, 4, 12)
    for a, b in zip(first, second, strict=True):
        np.testing.assert_array_equal(a[0], b[0])
        np.testing.assert_array_equal(np.array(a[2]), np.array(b[2]))
        assert a[3] == b[3]
    drawn = [episode[3][0]["perturbation"] for episode in first]
    assert all(info["perturbation"] == drawn[i] for i, e in enumerate(first) for info in e[3])
    for name in ("mass_scale", "torque_scale", "floor_friction_scale", "bias_left"):
        assert len({values[name] for values in drawn}) == 4, name
    for values in drawn:
        assert 0.5 <= values["mass_scale"] <= 2.0
        assert 0.5 <= values["torque_scale"] <= 1.5
        assert 0.6 <= values["floor_friction_scale"] <= 1.4
        assert -0.5 <= values["bias_left"] <= 0.5
        assert 0.1 <= values["noise_variance"] <= 0.6
        assert values["latency_steps"] in (0, 1, 2)
        assert isinstance(values["latency_steps"], int)
        assert values["observation_noise"] == 0.3
    # The last episode's draws are on the body now.
    unwrapped = env.unwrapped
    mass = pb.getDynamicsInfo(unwrapped.robot.body_id, -1, physicsClientId=unwrapped.client_id)[0]
    assert mass == pytest.approx(unwrapped.robot.body.mass * drawn[-1]["mass_scale"])
    limits = unwrapped.robot.drive.limits
    assert limits.wheel_torque == pytest.approx(20.0 * drawn[-1]["torque_scale"])
    # reset(seed=s) repeats the first episode, draws included.
    _, info = env.reset(seed=11)
    assert info["perturbation"] == drawn[0]


def test_integer_ranges_reach_both_ends_and_other_seeds_draw_otherwise(
    make_env: Callable[..., gym.Env],
) -> None:
    env = make_env(maze="open", latency_steps=[1, 3], bias_along=(-1.0, 1.0))
    seen, biases = set(), []
    for i in range(40):
        _, info = env.reset(seed=5 if i == 0 else None)
        seen.add(info["perturbation"]["latency_steps"])
        biases.append(info["perturbation"]["bias_along"])
    assert seen == {1, 2, 3}
    _, info = env.reset(seed=6)
    assert info["perturbation"]["bias_along"] != biases[0]


def test_randomisation_leaves_the_action_noise_stream_alone(
    make_env: Callable[..., gym.Env],
) -> None:
    """A degenerate noise-variance range gives the fixed variance's rollout, and ranges of the
    physics or the observation draw nothing from np_random (their own generator)."""
    kwargs = {"maze": "open", "mode": "dynamic"}
    a = rollout(make_env(**kwargs, noise_variance=0.5), CYCLE[:40])
    b = rollout(make_env(**kwargs, noise_variance=[0.5, 0.5]), CYCLE[:40])
    np.testing.assert_array_equal(a[0], b[0])
    plain = make_env(**kwargs)
    randomised = make_env(**kwargs, floor_friction_scale=[0.9, 1.1], observation_noise=[0, 1])
    rollout(plain, CYCLE[:40])
    rollout(randomised, CYCLE[:40])
    assert (
        plain.unwrapped.np_random.bit_generator.state
        == randomised.unwrapped.np_random.bit_generator.state
    )


def test_perturbed_envs_pass_gymnasiums_checker_and_vectorise(
    make_env: Callable[..., gym.Env],
) -> None:
    env = make_env(**RANDOMISED, observation="lidar", lidar_noise=[0.0, 1.0], heading_noise=0.1)
    check_env(env.unwrapped, skip_render_check=True)
    vector = gym.vector.SyncVectorEnv(
        [
            lambda: gym.make(
                "BulletMaze-v0",
                maze="open",
                mass_scale=[1.0, 2.0],
                mode="dynamic",
                revert_on_collision=False,
            )
        ]
        * 2
    )
    try:
        _, infos = vector.reset(seed=0)
        assert infos["perturbation"]["mass_scale"].shape == (2,)
        assert infos["perturbation"]["mass_scale"][0] != infos["perturbation"]["mass_scale"][1]
    finally:
        vector.close()


# -- The perturbation table and levels ---------------------------------------------------------


def test_the_table_lists_every_keyword_with_units_and_bounds() -> None:
    assert [p.name for p in PERTURBATIONS] == list(NAMES)
    for p in PERTURBATIONS:
        assert p.unit
        assert p.description
        assert p.low <= p.null <= p.high
    for level, values in LEVELS.items():
        for name, value in values.items():
            assert isinstance(perturbations.parse_setting(name, value), Range | float), level


@pytest.mark.parametrize(
    ("mode", "drive", "lidar", "absent"),
    [
        (
            "kinematic",
            "holonomic",
            False,
            {
                "floor_friction_scale",
                "wheel_friction_scale",
                "mass_scale",
                "torque_scale",
                "heading_noise",
                "lidar_noise",
            },
        ),
        ("dynamic", "holonomic", True, {"mass_scale", "torque_scale", "heading_noise"}),
        ("dynamic", "differential", False, {"lidar_noise"}),
        (
            "kinematic",
            "ackermann",
            True,
            {"floor_friction_scale", "wheel_friction_scale", "mass_scale", "torque_scale"},
        ),
    ],
)
def test_levels_keep_what_applies_and_every_level_builds_an_env(
    make_env: Callable[..., gym.Env], mode: str, drive: str, lidar: bool, absent: set[str]
) -> None:
    strong = level_settings("strong", mode=mode, drive=drive, lidar=lidar)
    assert set(strong) == set(LEVELS["strong"]) - absent
    assert level_settings("none", mode=mode, drive=drive, lidar=lidar) == {}
    robot = {"holonomic": "disc", "differential": "rover", "ackermann": "racecar"}[drive]
    actions = "native" if drive != "holonomic" else "compass"
    observation = "lidar" if lidar else "pose"
    for level in LEVELS:
        settings = level_settings(level, mode=mode, drive=drive, lidar=lidar)
        env = make_env(robot=robot, mode=mode, actions=actions, observation=observation, **settings)
        _, info = env.reset(seed=0)
        env.step(0)
        assert set(info.get("perturbation", {})) == set(settings)


def test_applies_names_the_reason() -> None:
    assert applies("mass_scale", mode="dynamic", drive="differential") is None
    assert "revert_on_collision" in str(applies("mass_scale", mode="dynamic", drive="holonomic"))
    assert (
        applies("mass_scale", mode="dynamic", drive="holonomic", revert_on_collision=False) is None
    )
    assert "heading" in str(applies("heading_noise", mode="kinematic", drive="holonomic"))
    for bad, message in (
        ({"name": "mass", "mode": "dynamic", "drive": "holonomic"}, "unknown perturbation"),
        ({"name": "mass_scale", "mode": "fast", "drive": "holonomic"}, "mode"),
        ({"name": "mass_scale", "mode": "dynamic", "drive": "legs"}, "drive"),
    ):
        with pytest.raises(ValueError, match=message):
            applies(bad.pop("name"), **bad)
    with pytest.raises(ValueError, match="level must be one of"):
        level_settings("extreme", mode="dynamic", drive="holonomic")


# -- Bad values: every one a clear error naming the parameter and the value --------------------

BAD_VALUES: list[tuple[str, Any, type[Exception], str]] = [
    ("mass_scale", True, TypeError, "a bool is not"),
    ("mass_scale", np.bool_(False), TypeError, ""),
    ("mass_scale", "2.0", TypeError, "got str"),
    ("mass_scale", b"2", TypeError, "got bytes"),
    ("mass_scale", math.nan, ValueError, "finite"),
    ("mass_scale", math.inf, ValueError, "finite"),
    ("mass_scale", -1.0, ValueError, "out of bounds"),
    ("mass_scale", 0.0, ValueError, "out of bounds"),
    ("mass_scale", 1e6, ValueError, "out of bounds"),
    ("mass_scale", [2.0, 1.0], ValueError, "low <= high"),
    ("mass_scale", [1.0, 2.0, 3.0], ValueError, "got 3 item"),
    ("mass_scale", [1.0], ValueError, "got 1 item"),
    ("mass_scale", [], ValueError, "got 0 item"),
    ("mass_scale", [None, 2.0], TypeError, "NoneType"),
    ("mass_scale", [[0.5, 1.0], 2.0], TypeError, "list"),
    ("mass_scale", [True, 2.0], TypeError, "bool"),
    ("mass_scale", [0.5, math.nan], ValueError, "finite"),
    ("mass_scale", [0.5, math.inf], ValueError, "finite"),
    ("mass_scale", np.array([[0.5, 1.0]]), ValueError, "a range is"),
    ("mass_scale", {"low": 1.0}, ValueError, "exactly the keys"),
    ("mass_scale", {"low": 0.5, "high": 1.0, "mean": 0.7}, ValueError, "exactly the keys"),
    ("mass_scale", {"low": {"low": 0.5}, "high": 1.0}, TypeError, "dict"),
    ("mass_scale", {"low": 2.0, "high": 1.0}, ValueError, "low <= high"),
    ("mass_scale", {1, 2}, TypeError, "set"),
    ("mass_scale", object(), TypeError, "object"),
    ("latency_steps", 1.5, TypeError, "non-integer"),
    ("latency_steps", 1.0, TypeError, "non-integer"),
    ("latency_steps", -1, ValueError, "out of bounds"),
    ("latency_steps", 101, ValueError, "out of bounds"),
    ("latency_steps", [0, 1.5], TypeError, "non-integer"),
    ("latency_steps", [3, 1], ValueError, "low <= high"),
    ("latency_steps", True, TypeError, ""),
    ("bias_along", 11.0, ValueError, "out of bounds"),
    ("bias_left", [-20.0, 0.0], ValueError, "out of bounds"),
    ("observation_noise", -0.1, ValueError, "out of bounds"),
    ("heading_noise", 4.0, ValueError, "out of bounds"),
    ("floor_friction_scale", -0.5, ValueError, "out of bounds"),
    ("wheel_friction_scale", "high", TypeError, "str"),
    ("torque_scale", [0.5, 1e9], ValueError, "out of bounds"),
    ("noise_variance", [0.5, 0.1], ValueError, "low <= high"),
    ("noise_variance", [-1.0, 1.0], ValueError, "out of bounds"),
    ("noise_variance", [0.0, 1000.0], ValueError, "out of bounds"),
    ("noise_variance", [0.1, math.nan], ValueError, "finite"),
    ("noise_variance", {"low": 0.1}, ValueError, "exactly the keys"),
    ("noise_variance", [False, 1.0], TypeError, "bool"),
]


@pytest.mark.parametrize(("name", "value", "error", "message"), BAD_VALUES)
def test_bad_values_are_clear_errors_naming_the_parameter_and_value(
    make_env: Callable[..., gym.Env], name: str, value: Any, error: type[Exception], message: str
) -> None:
    robot = {"robot": "rover", "actions": "native", "mode": "dynamic"}
    with pytest.raises(error) as raised:
        make_env(**robot, **{name: value})
    text = str(raised.value)
    assert text.startswith(f"{name} = {value!r}"), text
    assert re.search(re.escape(message), text), text


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"mass_scale": 2.0}, r"mass_scale = 2\.0 does not apply here: .*mode='dynamic'"),
        ({"mode": "dynamic", "torque_scale": 0.5}, "torque_scale = 0.5 does not apply.*motors"),
        ({"mode": "dynamic", "mass_scale": [1, 2]}, "mass_scale .*revert_on_collision"),
        ({"heading_noise": 0.1}, "heading_noise = 0.1 does not apply.*heading"),
        ({"lidar_noise": 1.0}, "lidar_noise = 1.0 does not apply.*observation='lidar'"),
        ({"masss_scale": 2.0}, r"unknown keyword argument\(s\) \['masss_scale'\].*'mass_scale'"),
    ],
)
def test_perturbations_where_they_mean_nothing_are_refused(
    make_env: Callable[..., gym.Env], kwargs: dict[str, Any], message: str
) -> None:
    error = TypeError if "masss" in str(kwargs) else ValueError
    with pytest.raises(error, match=message):
        make_env(**kwargs)


def test_a_none_value_is_not_set(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(mass_scale=None, latency_steps=None)
    _, info = env.reset(seed=0)
    assert "perturbation" not in info


# -- Training in physics through an experiment file's [env] table ------------------------------

EXPERIMENT = """
[experiment]
name = "physics_dr_smoke"
seed = 7
runs = 1
episodes = 2

[env]
maze = "open"
robot = "disc"
mode = "dynamic"
max_episode_steps = 25

[env.params]
floor_friction_scale = [0.5, 1.5]
wheel_friction_scale = { low = 0.8, high = 1.2 }
latency_steps = [0, 1]
bias_along = { low = -0.2, high = 0.2 }
noise_variance = [0.2, 0.4]
observation_noise = 0.1

[[strategy]]
name = "adaptive+tabu"
exploration = "adaptive+tabu"
"""


def test_toml_arrays_and_tables_arrive_as_ranges_and_build_the_env() -> None:
    from experiments import config, factory

    parsed = config.parse_config(tomllib.loads(EXPERIMENT), source="smoke.toml")
    assert parsed.env.params["floor_friction_scale"] == [0.5, 1.5]
    env = factory.make_env(parsed.env)
    try:
        _, info = env.reset(seed=0)
        drawn = info["perturbation"]
        assert set(drawn) == set(tomllib.loads(EXPERIMENT)["env"]["params"])
        assert 0.5 <= drawn["floor_friction_scale"] <= 1.5
        assert 0.8 <= drawn["wheel_friction_scale"] <= 1.2
    finally:
        env.close()
    bad = EXPERIMENT.replace("latency_steps = [0, 1]", "latency_steps = [0, 1, 2]")
    with pytest.raises(config.ConfigError, match=r"smoke\.toml: \[env\.params\] latency_steps"):
        config.parse_config(tomllib.loads(bad), source="smoke.toml")


def test_an_experiment_trains_in_dynamic_mode_with_randomisation(tmp_path: Path) -> None:
    """The front door: ``run.py experiment`` on a file with mode = "dynamic" and ranges in
    [env.params] trains, writes its run CSV and its config (ranges kept), and resumes."""
    path = tmp_path / "physics_dr_smoke.toml"
    path.write_text(EXPERIMENT)
    out = tmp_path / "out"
    command = [
        sys.executable,
        str(ROOT / "run.py"),
        "experiment",
        str(path),
        "--workers",
        "1",
        "--backend",
        "serial",
        "--out",
        str(out),
        "--no-progress",
    ]
    subprocess.run(command, check=True, cwd=ROOT, capture_output=True)
    runs = sorted((out / "runs").glob("*.csv"))
    assert len(runs) == 1
    rows = runs[0].read_text().splitlines()
    assert len(rows) == 3  # a header and two episodes
    saved = (out / "config.toml").read_text()
    assert "floor_friction_scale = [" in saved
    assert "latency_steps = [" in saved
    before = runs[0].read_bytes()
    subprocess.run(command, check=True, cwd=ROOT, capture_output=True)
    assert runs[0].read_bytes() == before
