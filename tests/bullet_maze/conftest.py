"""Shared helpers of the bullet_maze tests."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path

import gymnasium as gym
import pytest

import bullet_maze  # noqa: F401  (registers the ids)


@pytest.fixture
def make_env() -> Iterator[Callable[..., gym.Env]]:
    """``gymnasium.make("BulletMaze-v0", **kwargs)``; every env made is closed afterwards."""
    made: list[gym.Env] = []

    def make(env_id: str = "BulletMaze-v0", **kwargs: object) -> gym.Env:
        env = gym.make(env_id, **kwargs)
        made.append(env)
        return env

    yield make
    for env in made:
        env.close()


@pytest.fixture
def write_maze(tmp_path: Path) -> Callable[[str], Path]:
    """Write a TOML layout into a temporary file and return its path."""
    count = 0

    def write(text: str) -> Path:
        nonlocal count
        count += 1
        path = tmp_path / f"maze{count}.toml"
        path.write_text(text)
        return path

    return write


SMALL_MAZE = """
name = "small"
robot_radius = 2.0
[arena]
size = [100.0, 100.0]
[start]
position = [20.0, 20.0]
[goal]
position = [80.0, 80.0]
radius = 5.0
"""
"""A valid layout that tests extend or break one field at a time."""
