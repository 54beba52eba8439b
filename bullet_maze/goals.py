"""The goal-conditioned observation (``observation="goal"``) and its vectorised reward.

As Gymnasium-Robotics' mazes give it: a ``Dict`` of ``observation`` (the pose, and the lidar
with ``"goal+lidar"``), ``achieved_goal`` (the robot's x, y) and ``desired_goal`` (the goal
centre), with ``compute_reward(achieved_goal, desired_goal, info)`` that gives the reward the
step would have had for another goal, on one transition or a batch. Stable-Baselines3's
``HerReplayBuffer`` relabels goals with it.

The reward is the env's own (section V.A): ``goal_reward`` within the goal radius, else
``collision_reward`` when the step touched a solid (the ``collision`` entry of ``info``, which
no goal changes), else ``step_reward``; the collision comes first, as in ``step``.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from gymnasium import spaces


def goal_space(observation: spaces.Box, arena: tuple[float, float]) -> spaces.Dict:
    """The ``Dict`` space around an observation ``Box``."""
    low, high = np.zeros(2), np.array(arena, dtype=np.float64)
    return spaces.Dict(
        {
            "observation": observation,
            "achieved_goal": spaces.Box(low, high, dtype=np.float64),
            "desired_goal": spaces.Box(low.copy(), high.copy(), dtype=np.float64),
        }
    )


def goal_distance(achieved_goal: Any, desired_goal: Any) -> np.ndarray:
    """Euclidean distance between goal positions, over the last axis."""
    achieved = np.asarray(achieved_goal, dtype=np.float64)
    desired = np.asarray(desired_goal, dtype=np.float64)
    if achieved.shape[-1:] != (2,) or desired.shape[-1:] != (2,):
        raise ValueError(
            f"goals must end in an axis of 2 (x, y), got shapes {achieved.shape} and "
            f"{desired.shape}"
        )
    return np.linalg.norm(achieved - desired, axis=-1)


def collision_flags(info: Any, shape: tuple[int, ...], key: str = "collision") -> np.ndarray:
    """The ``key`` entries (``collision``, or ``tipped``) of one ``info`` dict or a batch of
    them, as booleans of ``shape`` (False where an info does not say)."""
    if info is None:
        return np.zeros(shape, dtype=bool)
    if isinstance(info, Mapping):
        flag = info.get(key, False)
        if isinstance(flag, np.ndarray):  # a vector env's info: one entry per env
            return np.broadcast_to(flag.astype(bool), shape)
        return np.full(shape, bool(flag))
    infos = np.asarray(info, dtype=object).reshape(-1)
    flags = np.array([bool(i.get(key, False)) if isinstance(i, Mapping) else False for i in infos])
    if flags.size != int(np.prod(shape)):
        raise ValueError(f"{flags.size} infos for {int(np.prod(shape))} goals")
    return flags.reshape(shape)


def goal_reward(
    achieved_goal: Any,
    desired_goal: Any,
    info: Any,
    goal_radius: float,
    rewards: tuple[float, float, float],
) -> np.ndarray:
    """Section V.A's reward for each (achieved, desired) pair; ``rewards`` is (goal,
    collision, step)."""
    distance = goal_distance(achieved_goal, desired_goal)
    at_goal, collision, step = rewards
    reward = np.where(distance <= goal_radius, at_goal, step)
    return np.where(collision_flags(info, distance.shape), collision, reward)
