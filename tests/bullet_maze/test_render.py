"""Rendering: a top-down TinyRenderer image with the robot, start and goal, no display needed."""

from __future__ import annotations

import logging
from collections.abc import Callable

import gymnasium as gym
import numpy as np
import pytest

from bullet_maze.world import COLOURS


def _is_red(pixel: np.ndarray) -> bool:
    r, g, b = (int(v) for v in pixel)
    return r > 100 and r > g + 60 and r > b + 60


def _is_grey(pixel: np.ndarray, low: int, high: int) -> bool:
    return bool(np.ptp(pixel.astype(int)) < 20 and low <= pixel.mean() <= high)


def _is_robot_blue(pixel: np.ndarray) -> bool:
    r, g, b = (int(v) for v in pixel)
    return b > 120 and b > r + 60 and b > g + 40


def test_rgb_array_shape_and_content(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(render_mode="rgb_array", render_width=160, render_height=120)
    env.reset(seed=0)
    image = env.render()
    assert image.shape == (120, 160, 3)
    assert image.dtype == np.uint8
    camera = env.unwrapped._camera
    layout = env.unwrapped.layout
    assert _is_robot_blue(image[camera.pixel(*layout.start)])
    assert _is_red(image[camera.pixel(*layout.goal)])
    floor = image[camera.pixel(20.0, 280.0)]
    obstacle = image[camera.pixel(150.0, 150.0)]  # the big cylinder
    assert _is_grey(floor, 180, 255)
    assert _is_grey(obstacle, 40, 170)
    assert floor.mean() - obstacle.mean() > 40
    # Shading darkens, never reverses, the order of the configured brightnesses.
    assert COLOURS["ground"][0] > COLOURS["obstacle"][0] > COLOURS["wall"][0]


def test_the_robot_moves_in_the_image(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(maze="open", render_mode="rgb_array", noise_variance=0.0)
    env.reset(seed=0, options={"start": (60.0, 150.0)})
    before = env.render()
    for _ in range(12):
        env.step(3)  # 60 units to the right
    after = env.render()
    camera = env.unwrapped._camera
    old, new = camera.pixel(60.0, 150.0), camera.pixel(120.0, 150.0)
    assert _is_robot_blue(before[old])
    assert not _is_robot_blue(before[new])
    assert _is_robot_blue(after[new])
    assert not _is_robot_blue(after[old])
    changed = np.any(before != after, axis=-1)
    assert 0 < changed.mean() < 0.05  # only the robot's neighbourhood changed


def test_husky_is_visible(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(robot="husky", render_mode="rgb_array")
    env.reset(seed=0, options={"start": (60.0, 250.0)})
    image = env.render()
    empty = make_env(render_mode="rgb_array")
    empty.reset(seed=0, options={"start": (240.0, 40.0)})
    row, column = env.unwrapped._camera.pixel(60.0, 250.0)
    patch = (slice(row - 3, row + 4), slice(column - 3, column + 4))
    assert np.abs(image[patch].astype(int) - empty.render()[patch].astype(int)).max() > 60


def test_render_without_a_mode_returns_none(make_env: Callable[..., gym.Env]) -> None:
    env = make_env()
    env.reset(seed=0)
    with pytest.warns(UserWarning, match="render_mode"):
        assert env.unwrapped.render() is None


def test_human_mode_without_a_display_runs_headless(
    make_env: Callable[..., gym.Env],
    monkeypatch: pytest.MonkeyPatch,
    caplog: pytest.LogCaptureFixture,
) -> None:
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    with caplog.at_level(logging.WARNING, logger="bullet_maze.env"):
        env = make_env(render_mode="human")
    assert "needs a display" in caplog.text
    env.reset(seed=0)
    assert env.step(0)[0].shape == (2,)
    assert env.render() is None
