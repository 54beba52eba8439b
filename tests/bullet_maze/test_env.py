"""Gymnasium conventions: registration, spaces, check_env, determinism, options, bad input and
pybullet client clean-up."""

from __future__ import annotations

import gc
import math
import warnings
from collections.abc import Callable
from pathlib import Path

import gymnasium as gym
import numpy as np
import pybullet as pb
import pytest
from gymnasium.utils.env_checker import check_env

import bullet_maze
from bullet_maze import Action, BulletMazeEnv, available_layouts

from .conftest import SMALL_MAZE


def test_import_registers_the_ids() -> None:
    spec = gym.spec("BulletMaze-v0")
    assert spec.entry_point == "bullet_maze.env:BulletMazeEnv"
    assert spec.max_episode_steps == 5000
    for name in available_layouts():
        assert gym.spec(f"BulletMaze-{name}-v0").kwargs == {"maze": name}
    assert set(bullet_maze.ENV_IDS) >= {"BulletMaze-v0", "BulletMaze-paper_narrow-v0"}


def test_per_layout_id_makes_that_layout(make_env: Callable[..., gym.Env]) -> None:
    env = make_env("BulletMaze-corridors-v0")
    assert env.unwrapped.layout.name == "corridors"
    assert make_env().unwrapped.layout.name == "paper"


def test_spaces(make_env: Callable[..., gym.Env]) -> None:
    disc = make_env()
    assert disc.action_space == gym.spaces.Discrete(4)
    assert disc.observation_space.shape == (2,)
    assert np.array_equal(disc.observation_space.low, [0.0, 0.0])
    assert np.array_equal(disc.observation_space.high, [300.0, 300.0])
    husky = make_env(robot="husky")
    assert husky.observation_space.shape == (3,)
    assert husky.observation_space.low[2] == -math.pi
    obs, _ = husky.reset(seed=0)
    assert husky.observation_space.contains(obs)


@pytest.mark.parametrize(
    "kwargs",
    [{}, {"mode": "dynamic"}, {"robot": "husky"}, {"render_mode": "rgb_array"}],
    ids=["kinematic", "dynamic", "husky", "rgb_array"],
)
def test_check_env_passes_without_warnings(
    make_env: Callable[..., gym.Env],
    kwargs: dict[str, object],
) -> None:
    env = make_env(**kwargs)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env.unwrapped)


def _rollout(seed: int, steps: int, **kwargs: object) -> tuple[np.ndarray, np.ndarray]:
    env = gym.make("BulletMaze-v0", **kwargs)
    obs, _ = env.reset(seed=seed)
    actions = np.random.default_rng(seed).integers(0, 4, steps)
    observations, rewards = [obs], []
    for action in actions:
        obs, reward, terminated, truncated, _ = env.step(action)
        observations.append(obs)
        rewards.append(reward)
        if terminated or truncated:
            obs, _ = env.reset()
    env.close()
    return np.array(observations), np.array(rewards)


@pytest.mark.parametrize(
    ("kwargs", "steps"),
    [
        ({"mode": "kinematic"}, 500),
        ({"mode": "dynamic"}, 500),
        ({"mode": "kinematic", "robot": "husky"}, 500),
        # The husky's dynamic step runs about 260 physics steps: 60 keep the test short.
        ({"mode": "dynamic", "robot": "husky"}, 60),
    ],
    ids=["kinematic-disc", "dynamic-disc", "kinematic-husky", "dynamic-husky"],
)
def test_same_seed_gives_bit_identical_rollouts(kwargs: dict[str, object], steps: int) -> None:
    first = _rollout(7, steps, maze="paper_narrow", **kwargs)
    second = _rollout(7, steps, maze="paper_narrow", **kwargs)
    assert first[0].tobytes() == second[0].tobytes()
    assert first[1].tobytes() == second[1].tobytes()
    other = _rollout(8, steps, maze="paper_narrow", **kwargs)
    assert not np.array_equal(first[0], other[0])


def test_reset_with_the_same_seed_repeats_the_episode(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(mode="dynamic")
    runs = []
    for _ in range(2):
        obs, _ = env.reset(seed=3)
        trace = [obs]
        for action in [0, 0, 3, 3, 2, 1] * 10:
            trace.append(env.step(action)[0])
        runs.append(np.array(trace))
    assert runs[0].tobytes() == runs[1].tobytes()


def test_reset_options_move_start_and_goal(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(maze="open")
    obs, info = env.reset(seed=0, options={"start": (100.0, 100.0), "goal": (100.0, 140.0)})
    assert np.array_equal(obs, [100.0, 100.0])
    assert info["distance_to_goal"] == pytest.approx(40.0)
    assert env.unwrapped.goal == (100.0, 140.0)
    assert env.unwrapped.optimal_steps == 5  # (40 - 15) / 5 units of step
    obs, _ = env.reset(seed=0, options={"start": np.array([100.0, 90.0], dtype=np.float32)})
    assert np.array_equal(obs, [100.0, 90.0])
    husky = make_env(maze="open", robot="husky")
    obs, _ = husky.reset(seed=0, options={"start": (100.0, 100.0, 0.5)})
    assert np.allclose(obs, [100.0, 100.0, 0.5])
    # Without options the layout's own start and goal come back.
    obs, info = env.reset()
    assert np.array_equal(obs, [150.0, 30.0])
    assert info["distance_to_goal"] == pytest.approx(240.0)


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"start": (math.nan, 10.0)}, r"options\['start'\] must be finite"),
        ({"start": (10.0, math.inf)}, r"options\['start'\] must be finite"),
        ({"goal": (math.nan, 10.0)}, r"options\['goal'\] must be finite"),
        ({"start": (-1.0, 10.0)}, r"options\['start'\].*outside the arena"),
        ({"goal": (150.0, 301.0)}, r"options\['goal'\].*outside the arena"),
        ({"start": (150.0, 150.0)}, r"options\['start'\].*overlaps"),
        ({"start": (150.0, 3.0)}, r"options\['start'\].*overlaps"),
        ({"goal": (150.0, 150.0)}, r"options\['goal'\].*inside a wall or an obstacle"),
        ({"start": (150.0, 260.0)}, r"start .* inside the goal circle"),
        ({"start": (1.0, 2.0, 3.0, 4.0)}, r"options\['start'\] must have 2 or 3 numbers"),
        ({"start": "here"}, r"options\['start'\] must be a sequence"),
        ({"speed": 3}, r"unknown reset option\(s\) \['speed'\]"),
        ({"start": "99"}, r"options\['start'\] must be a sequence of 2 or 3 numbers"),
        ({"start": b"99"}, r"options\['start'\] must be a sequence"),
        ({"start": [True, 50.0]}, r"options\['start'\] must be a sequence"),
        ({"goal": ["150", "260"]}, r"options\['goal'\] must be a sequence of 2 numbers"),
        ({"goal": {"x": 1, "y": 2}}, r"options\['goal'\] must be a sequence"),
    ],
)
def test_bad_reset_options(
    make_env: Callable[..., gym.Env],
    options: dict[str, object],
    message: str,
) -> None:
    env = make_env()
    with pytest.raises(ValueError, match=message):
        env.reset(seed=0, options=options)


POCKET = """
[[walls]]
center = [60.0, 18.0]
size = [2.0, 36.0]
[[walls]]
center = [81.5, 40.0]
size = [37.0, 2.0]
"""
"""Walls that close the lower right of ``SMALL_MAZE`` into a pocket, x in (61, 100) and y in
(0, 39), whose only way out is a 3.6-unit gap at (62, 37.5): too narrow for the robot of
radius 2 (4 across), wide enough for one of radius 1."""


def test_reset_refuses_a_goal_or_start_the_robot_cannot_reach(
    make_env: Callable[..., gym.Env],
    write_maze: Callable[[str], Path],
) -> None:
    env = make_env(maze=write_maze(SMALL_MAZE + POCKET))
    with pytest.raises(
        ValueError,
        match=r"options\['goal'\] = \(80\.0, 20\.0\).*cannot be "
        r"reached from the start \(20\.0, 20\.0\).*radius 2",
    ):
        env.reset(seed=0, options={"goal": (80.0, 20.0)})
    with pytest.raises(
        ValueError,
        match=r"options\['start'\] = \(80\.0, 20\.0\): the goal "
        r"circle around \(80\.0, 80\.0\) cannot be reached",
    ):
        env.reset(seed=0, options={"start": (80.0, 20.0, 0.0)})
    with pytest.raises(
        ValueError,
        match=r"options\['goal'\] = \(80\.0, 20\.0\).*from "
        r"options\['start'\] = \(30\.0, 60\.0\)",
    ):
        env.reset(seed=0, options={"start": (30.0, 60.0), "goal": (80.0, 20.0)})
    # Both inside the pocket, or both outside: fine; a refused reset leaves the env usable.
    obs, info = env.reset(seed=0, options={"start": (70.0, 10.0), "goal": (85.0, 25.0)})
    assert np.array_equal(obs, [70.0, 10.0])
    assert info["distance_to_goal"] == pytest.approx(math.dist((70, 10), (85, 25)))
    obs, _ = env.reset(seed=0, options={"start": (30.0, 60.0), "goal": (40.0, 90.0)})
    assert np.array_equal(obs, [30.0, 60.0])
    # A robot of radius 1 fits through the gap, so the same goal is accepted for it.
    small = make_env(maze=write_maze(SMALL_MAZE + POCKET), robot_radius=1.0)
    small.reset(seed=0, options={"goal": (80.0, 20.0)})
    assert small.unwrapped.goal == (80.0, 20.0)


@pytest.mark.parametrize(
    ("action", "error"),
    [
        (4, ValueError),
        (-1, ValueError),
        (1.0, TypeError),
        ("up", TypeError),
        (True, TypeError),
        (None, TypeError),
        (np.array([1, 2]), TypeError),
    ],
)
def test_invalid_actions_are_clear_errors(
    make_env: Callable[..., gym.Env],
    action: object,
    error: type[Exception],
) -> None:
    env = make_env().unwrapped
    env.reset(seed=0)
    with pytest.raises(error, match=r"action"):
        env.step(action)


def test_valid_action_types(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(noise_variance=0.0).unwrapped
    env.reset(seed=0)
    for action in (Action.UP, 0, np.int64(0), np.int32(0), np.array(0), np.uint8(0)):
        obs = env.step(action)[0]
    assert np.array_equal(obs, [150.0, 60.0])


@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        ({"mode": "teleport"}, ValueError, r"mode must be one of \['kinematic', 'dynamic'\]"),
        ({"robot": "tank"}, ValueError, r"unknown robot 'tank'.*'disc', 'husky'"),
        ({"robot": 3}, TypeError, r"robot must be"),
        ({"maze": "nowhere"}, ValueError, r"unknown maze 'nowhere'"),
        ({"render_mode": "ascii"}, ValueError, r"render_mode must be None or one of"),
        ({"step_size": -5.0}, ValueError, r"step_size must be positive"),
        ({"noise_variance": -0.3}, ValueError, r"noise_variance must be >= 0"),
        ({"substeps": 0}, ValueError, r"substeps must be a positive integer"),
        ({"robot_radius": 0.0}, ValueError, r"robot_radius must be a positive number"),
        ({"robot_radius": 45.0}, ValueError, r"'start\.position'.*radius 45"),
        # Issue 12: a bool is not a number, unknown keywords are errors, the time limit is
        # gymnasium.make's.
        ({"robot_radius": True}, TypeError, r"robot_radius must be a number, got True"),
        ({"step_size": True}, TypeError, r"step_size must be a number, got True"),
        ({"substeps": True}, TypeError, r"substeps must be a number, got True"),
        ({"control_period": False}, TypeError, r"control_period must be a number"),
        ({"revert_on_collision": 1}, TypeError, r"revert_on_collision must be a bool, got 1"),
        ({"contact_release": "no"}, TypeError, r"contact_release must be a bool, got 'no'"),
        ({"render_width": True}, TypeError, r"render_width = True: must be an integer"),
        ({"render_height": 100_000}, ValueError, r"render_height = 100000 is larger than 2048"),
        ({"speed": 3}, TypeError, r"unknown keyword argument\(s\) \['speed'\].*'step_size'"),
        ({"max_episode_steps": -1}, TypeError, r"max_episode_steps=-1 is not an env argument"),
        ({"actions": "joystick"}, ValueError, r"actions must be one of"),
        ({"control_period": 0.0}, ValueError, r"control_period must be in \(0, 10\]"),
    ],
)
def test_bad_constructor_arguments(
    kwargs: dict[str, object],
    error: type[Exception],
    message: str,
) -> None:
    with pytest.raises(error, match=message):
        BulletMazeEnv(**kwargs)


def test_parameters_pass_through_gymnasium_make(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(step_size=2.5, substeps=8, noise_variance=0.0)
    assert env.unwrapped.task.step_size == 2.5
    assert env.unwrapped.physics.substeps == 8
    obs, _ = env.reset(seed=0)
    assert np.array_equal(env.step(Action.UP)[0], obs + np.array([0.0, 2.5]))
    # Each parameter's default lives in its dataclass, not in the env's signature.
    assert make_env().unwrapped.task == bullet_maze.TaskParams()


def test_close_disconnects_and_twice_is_harmless() -> None:
    env = gym.make("BulletMaze-v0")
    env.reset(seed=0)
    client = env.unwrapped.client_id
    assert pb.isConnected(physicsClientId=client)
    env.close()
    assert not pb.isConnected(physicsClientId=client)
    assert env.unwrapped.client_id == -1
    env.close()
    with pytest.raises(RuntimeError, match="closed"):
        env.unwrapped.step(0)


def test_failed_construction_leaves_no_client_behind() -> None:
    before = _connected_clients()
    with pytest.raises(FileNotFoundError):
        BulletMazeEnv(robot="/nowhere/robot.urdf")
    assert _connected_clients() == before


def _connected_clients() -> set[int]:
    return {c for c in range(64) if pb.isConnected(physicsClientId=c)}


def test_many_envs_in_one_process_are_independent() -> None:
    envs = [gym.make("BulletMaze-v0", maze=m) for m in ("open", "paper", "open")]
    try:
        assert len({env.unwrapped.client_id for env in envs}) == 3
        starts = [env.reset(seed=0)[0] for env in envs]
        for _ in range(30):
            moved = envs[0].step(Action.UP)[0]
        # Stepping one env leaves the others where they were; the twin env follows its seed.
        assert np.array_equal(envs[2].unwrapped.pose[:2], starts[2])
        envs[1].close()
        for _ in range(30):
            twin = envs[2].step(Action.UP)[0]
        assert np.array_equal(twin, moved)
    finally:
        for env in envs:
            env.close()


def test_an_env_dropped_without_close_disconnects() -> None:
    env = BulletMazeEnv()
    client = env.client_id
    del env
    gc.collect()
    assert not pb.isConnected(physicsClientId=client)
