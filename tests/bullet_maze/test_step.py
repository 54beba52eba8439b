"""Step semantics of section V.A: noisy 5-unit moves, -1 and stay put on a hit, +5 and the end
at the goal, -0.01 otherwise, truncation at 5,000 steps; no tunnelling through thin walls."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

from bullet_maze import MAX_EPISODE_STEPS, Action

from .conftest import SMALL_MAZE


def test_displacements_have_the_papers_mean_and_variance(
    make_env: Callable[..., gym.Env],
) -> None:
    env = make_env(maze="open")
    obs, _ = env.reset(seed=1, options={"start": (150.0, 150.0)})
    n = 2000
    moves = []
    actions = [Action.RIGHT, Action.UP, Action.LEFT, Action.DOWN]
    expected = {Action.UP: (0, 5), Action.DOWN: (0, -5), Action.LEFT: (-5, 0), Action.RIGHT: (5, 0)}
    for i in range(n):
        action = actions[i % 4]
        new, reward, terminated, _truncated, info = env.step(action)
        assert not info["collision"]
        assert not terminated
        assert reward == pytest.approx(-0.01)
        moves.append(new - obs - np.array(expected[action]))
        obs = new
    noise = np.array(moves)
    # Mean 0 within 4 standard errors; variance 0.3 within 4 standard errors of a variance.
    assert np.all(np.abs(noise.mean(axis=0)) < 4 * np.sqrt(0.3 / n))
    assert np.all(np.abs(noise.var(axis=0, ddof=1) - 0.3) < 4 * 0.3 * np.sqrt(2 / (n - 1)))
    assert abs(np.corrcoef(noise.T)[0, 1]) < 4 / np.sqrt(n)  # the axes are independent


def test_noise_parameters_are_used(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(maze="open", step_size=2.0, noise_variance=0.0)
    obs, _ = env.reset(seed=0, options={"start": (100.0, 100.0)})
    new, *_ = env.step(Action.LEFT)
    assert np.array_equal(new, obs + np.array([-2.0, 0.0]))


def test_collision_costs_one_and_leaves_the_pose_unchanged(
    make_env: Callable[..., gym.Env],
) -> None:
    env = make_env(maze="open")
    obs, _ = env.reset(seed=0, options={"start": (150.0, 6.0)})  # 1 unit above the wall
    for _ in range(20):
        new, reward, terminated, truncated, info = env.step(Action.DOWN)
        assert info["collision"]
        assert reward == -1.0
        assert not terminated
        assert not truncated
        assert not info["is_success"]
        assert np.array_equal(new, obs)
    new, reward, _, _, info = env.step(Action.UP)
    assert not info["collision"]
    assert reward == pytest.approx(-0.01)
    assert new[1] > obs[1]


def test_obstacle_collision(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(maze="paper")  # cylinder of radius 45 at (150, 150), robot radius 5
    obs, _ = env.reset(seed=0, options={"start": (150.0, 99.0)})
    new, reward, _, _, info = env.step(Action.UP)
    assert info["collision"]
    assert reward == -1.0
    assert np.array_equal(new, obs)


def test_goal_gives_five_and_terminates(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(maze="open")  # goal of radius 15 at (150, 270)
    _obs, info = env.reset(seed=0, options={"start": (150.0, 252.0)})
    assert info["distance_to_goal"] == pytest.approx(18.0)
    assert not info["is_success"]
    new, reward, terminated, truncated, info = env.step(Action.UP)
    assert reward == 5.0
    assert terminated
    assert not truncated
    assert info["is_success"]
    assert not info["collision"]
    assert info["distance_to_goal"] == pytest.approx(np.hypot(*(new - (150.0, 270.0))))
    assert info["distance_to_goal"] <= 15.0


def test_rewards_are_parameters(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(maze="open", goal_reward=10.0, collision_reward=-3.0, step_reward=-0.5)
    env.reset(seed=0, options={"start": (150.0, 6.0)})
    assert env.step(Action.DOWN)[1] == -3.0
    assert env.step(Action.RIGHT)[1] == -0.5
    env.reset(seed=0, options={"start": (150.0, 252.0)})
    assert env.step(Action.UP)[1] == 10.0


def test_truncation_at_the_papers_cap(make_env: Callable[..., gym.Env]) -> None:
    env = make_env("BulletMaze-open-v0")
    assert env.spec is not None
    assert env.spec.max_episode_steps == MAX_EPISODE_STEPS == 5000
    env.reset(seed=0, options={"start": (150.0, 6.0)})
    steps = 0
    truncated = terminated = False
    while not (terminated or truncated):
        _, _, terminated, truncated, _ = env.step(Action.DOWN)  # into the wall for ever
        steps += 1
    assert truncated
    assert not terminated
    assert steps == 5000


def test_no_tunnelling_through_a_wall_thinner_than_a_step(
    make_env: Callable[..., gym.Env],
    write_maze: Callable[[str], Path],
) -> None:
    # A 0.2-unit wall at y = 50 with a gap on the right; the robot (radius 2) sits 10 below it
    # and moves 25 up: both ends of the move are free, the path is not.
    wall = "[[walls]]\ncenter = [40.0, 50.0]\nsize = [80.0, 0.2]\n"
    path = write_maze(SMALL_MAZE + wall)
    for mode in ("kinematic", "dynamic"):
        env = make_env(maze=path, mode=mode, step_size=25.0, noise_variance=0.0)
        obs, _ = env.reset(seed=0, options={"start": (20.0, 40.0)})
        new, reward, _, _, info = env.step(Action.UP)
        assert info["collision"], mode
        assert reward == -1.0, mode
        assert np.array_equal(new, obs), mode
        # Beside the wall's end the same move is free.
        obs, _ = env.reset(seed=0, options={"start": (90.0, 40.0)})
        new, _, _, _, info = env.step(Action.UP)
        assert not info["collision"], mode
        assert new[1] == pytest.approx(65.0, abs=0.5), mode


def test_grazing_a_wall_counts_only_when_touching(
    make_env: Callable[..., gym.Env],
    write_maze: Callable[[str], Path],
) -> None:
    wall = "[[walls]]\ncenter = [50.0, 50.0]\nsize = [10.0, 10.0]\n"  # box x in [45, 55]
    env = make_env(maze=write_maze(SMALL_MAZE + wall), step_size=20.0, noise_variance=0.0)
    # Robot radius 2 passing the box's side 2.01 away: free; 1.99 away: a hit.
    env.reset(seed=0, options={"start": (42.99, 35.0)})
    assert not env.step(Action.UP)[4]["collision"]
    env.reset(seed=0, options={"start": (43.01, 35.0)})
    assert env.step(Action.UP)[4]["collision"]


def test_dynamic_step_moves_about_five_units(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(maze="open", mode="dynamic")
    obs, _ = env.reset(seed=0, options={"start": (150.0, 150.0)})
    lengths = []
    for i in range(40):
        new, reward, _, _, info = env.step(Action.RIGHT if i % 2 == 0 else Action.LEFT)
        assert not info["collision"]
        assert reward == pytest.approx(-0.01)
        lengths.append(abs(new[0] - obs[0]))
        obs = new
    assert np.mean(lengths) == pytest.approx(5.0, rel=0.03)


def test_dynamic_collision_reverts_or_lets_physics_resolve(
    make_env: Callable[..., gym.Env],
) -> None:
    reverting = make_env(maze="open", mode="dynamic")
    obs, _ = reverting.reset(seed=0, options={"start": (150.0, 7.0)})
    new, reward, _, _, info = reverting.step(Action.DOWN)
    assert info["collision"]
    assert reward == -1.0
    assert np.allclose(new, obs, atol=1e-6)

    physical = make_env(maze="open", mode="dynamic", revert_on_collision=False)
    obs, _ = physical.reset(seed=0, options={"start": (150.0, 7.0)})
    new, reward, _, _, info = physical.step(Action.DOWN)
    assert info["collision"]
    assert reward == -1.0
    assert 4.0 < new[1] < obs[1]  # stopped by the wall at y = 0 (radius 5), not through it
