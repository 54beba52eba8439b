"""Stable-Baselines3 on the env, unchanged: its env checker on the goal-conditioned Dict, SAC
and PPO on continuous actions, SAC with HerReplayBuffer on the goal observation."""

from __future__ import annotations

import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import bullet_maze  # noqa: F401  (registers the ids)

sb3 = pytest.importorskip("stable_baselines3")  # in the test extras (see pyproject.toml)
import torch  # noqa: E402
from stable_baselines3 import PPO, SAC, HerReplayBuffer  # noqa: E402
from stable_baselines3.common.env_checker import check_env  # noqa: E402
from stable_baselines3.common.logger import Logger, configure  # noqa: E402

# One thread: on a shared 2-core machine torch's second thread made a short SAC run 14x slower.
torch.set_num_threads(1)


@pytest.fixture
def run_logger(tmp_path: Path) -> Logger:
    """A logger in the test's own folder that writes nothing: without one, SB3's ``learn``
    makes an ``SB3-<time>`` folder in the system's temp folder on every run and leaves it."""
    return configure(str(tmp_path), [])


@pytest.mark.parametrize(
    ("robot", "actions", "observation"),
    [
        ("disc", "continuous", "goal"),
        ("racecar", "continuous", "goal+lidar"),
        ("rover", "native", "goal"),
        ("husky", "compass", "lidar"),
    ],
)
def test_sb3_check_env(robot: str, actions: str, observation: str) -> None:
    env = gym.make(
        "BulletMaze-v0", robot=robot, actions=actions, observation=observation, lidar_rays=8
    )
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            check_env(env.unwrapped)
    finally:
        env.close()


@pytest.mark.parametrize("algorithm", [SAC, PPO])
def test_sac_and_ppo_train_on_continuous_actions(algorithm: type, run_logger: Logger) -> None:
    env = gym.make("BulletMaze-v0", robot="rover", actions="continuous", observation="lidar")
    kwargs = (
        {"learning_starts": 64, "batch_size": 32}
        if algorithm is SAC
        else {"n_steps": 64, "batch_size": 32, "n_epochs": 1}
    )
    model = algorithm("MlpPolicy", env, seed=0, device="cpu", **kwargs)
    model.set_logger(run_logger)
    model.learn(total_timesteps=128)
    obs, _ = env.reset(seed=0)
    action, _ = model.predict(obs, deterministic=True)
    assert env.action_space.contains(action)
    env.step(action)
    env.close()


def test_her_relabels_goals_with_compute_reward(run_logger: Logger) -> None:
    env = gym.make(
        "BulletMaze-v0",
        robot="disc",
        actions="continuous",
        observation="goal",
        max_episode_steps=40,  # HER samples from finished episodes
    )
    model = SAC(
        "MultiInputPolicy",
        env,
        replay_buffer_class=HerReplayBuffer,
        replay_buffer_kwargs={"n_sampled_goal": 4, "goal_selection_strategy": "future"},
        learning_starts=100,
        batch_size=32,
        seed=0,
        device="cpu",
    )
    model.set_logger(run_logger)
    model.learn(total_timesteps=160)
    buffer = model.replay_buffer
    assert isinstance(buffer, HerReplayBuffer)
    samples = buffer.sample(256)
    rewards = samples.rewards.numpy().ravel()
    achieved = samples.next_observations["achieved_goal"].numpy()
    desired = samples.next_observations["desired_goal"].numpy()
    # Relabelled rewards are the env's own, for the relabelled goal: +5 within its circle,
    # -0.01 outside, -1 whatever the goal when the step collided.
    expected = env.unwrapped.compute_reward(achieved, desired, None)
    free = rewards != -1.0
    assert np.allclose(rewards[free], expected[free], atol=1e-6)
    assert np.any(rewards == 5.0)  # "future" goals are reached
    env.close()
