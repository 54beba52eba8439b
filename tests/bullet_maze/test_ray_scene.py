"""The lidar's ray scene: meshes that answer rays exactly (boxes) or within the stated tolerance
(cylinders), against the exact ray casts computed here, and its client's life."""

from __future__ import annotations

import logging
import math
from collections.abc import Callable
from pathlib import Path

import gymnasium as gym
import numpy as np
import pybullet as pb
import pytest

from bullet_maze import BulletMazeEnv, ray_scene
from bullet_maze.params import METRES_PER_UNIT, WALL_HEIGHT
from bullet_maze.ray_scene import (
    MAX_SIDES,
    MESH_TOLERANCE,
    MIN_SIDES,
    _subdivided,
    cylinder_sides,
)
from bullet_maze.world import Piece

from .conftest import SMALL_MAZE

TREE = "[[obstacles]]\ncenter = [60.0, 20.0]\nradius = 7.5\n"
"""A cylinder whose surface is 32.5 units right of the start (20, 20)."""


def exact_range(
    pieces: list[Piece], x: float, y: float, ux: float, uy: float, near: float, far: float
) -> float:
    """The distance from (x, y) along the unit (ux, uy) to the first solid met beyond ``near``,
    or ``far``: a ray-circle and a slab test per piece."""
    best = far
    for piece in pieces:
        (cx, cy), (sx, sy), radius = piece.center, piece.size, piece.radius
        if radius:
            ox, oy = x - cx, y - cy
            b, c = ox * ux + oy * uy, ox * ox + oy * oy - radius * radius
            if b * b - c >= 0.0:
                t = -b - math.sqrt(b * b - c)
                if near <= t < best:
                    best = t
            continue
        enter, leave = -math.inf, math.inf
        for o, u, low, high in (
            (x, ux, cx - sx / 2, cx + sx / 2),
            (y, uy, cy - sy / 2, cy + sy / 2),
        ):
            if abs(u) < 1e-15:
                if not low <= o <= high:
                    enter, leave = math.inf, -math.inf
            else:
                a, b = (low - o) / u, (high - o) / u
                enter, leave = max(enter, min(a, b)), min(leave, max(a, b))
        if enter <= leave and near <= enter < best:
            best = enter
    return best


def grazes(pieces: list[Piece], x: float, y: float, ux: float, uy: float) -> bool:
    """Whether the line from (x, y) along (ux, uy) passes within ``2 * MESH_TOLERANCE`` of a
    cylinder's tangent: there a mesh may miss what the cylinder has, or the reverse."""
    for piece in pieces:
        if piece.radius:
            ox, oy = piece.center[0] - x, piece.center[1] - y
            if abs(abs(ox * uy - oy * ux) - piece.radius) <= 2 * MESH_TOLERANCE:
                return True
    return False


def clearance(pieces: list[Piece], x: float, y: float) -> float:
    """The distance from (x, y) to the nearest solid (0 inside one)."""
    gaps = []
    for piece in pieces:
        (cx, cy), (sx, sy), radius = piece.center, piece.size, piece.radius
        if radius:
            gaps.append(max(0.0, math.hypot(x - cx, y - cy) - radius))
        else:
            gaps.append(math.hypot(max(abs(x - cx) - sx / 2, 0.0), max(abs(y - cy) - sy / 2, 0.0)))
    return min(gaps)


def test_a_cylinder_reads_within_the_mesh_tolerance(
    make_env: Callable[..., gym.Env], write_maze: Callable[[str], Path]
) -> None:
    env = make_env(maze=write_maze(SMALL_MAZE + TREE), observation="lidar", lidar_rays=4)
    obs, _ = env.reset(seed=0, options={"start": (20.0, 20.0)})
    # Ray 0 (+x) meets the tree's surface at normal incidence: 60 - 7.5 - 20.
    assert abs(obs[2] - 32.5) <= MESH_TOLERANCE + 1e-9
    assert obs[3:] == pytest.approx([80.0, 20.0, 20.0], abs=1e-9)


def test_rays_grazing_a_box_corner_miss_it_and_rays_just_inside_hit_it(
    make_env: Callable[..., gym.Env], write_maze: Callable[[str], Path]
) -> None:
    # A box over [30, 70] x [30, 70]; rays from x = 10 facing +x pass 0.01 below its corner
    # (30, 30), to the arena's wall at x = 100, or 0.01 above it, to its face at x = 30.
    wall = "[[walls]]\ncenter = [50.0, 50.0]\nsize = [40.0, 40.0]\n"
    env = make_env(maze=write_maze(SMALL_MAZE + wall), observation="lidar", lidar_rays=4)
    lidar = env.unwrapped.lidar
    assert lidar.read(10.0, 30.0 - 0.01, 0.0)[0] == pytest.approx(90.0, abs=1e-9)
    assert lidar.read(10.0, 30.0 + 0.01, 0.0)[0] == pytest.approx(20.0, abs=1e-9)
    # The same along y, past the corner (70, 30) on its right.
    assert lidar.read(70.0 + 0.01, 10.0, math.pi / 2)[0] == pytest.approx(90.0, abs=1e-9)
    assert lidar.read(70.0 - 0.01, 10.0, math.pi / 2)[0] == pytest.approx(20.0, abs=1e-9)


@pytest.mark.parametrize("maze", ["paper", "forest:seed=3", "maze:seed=2", "rooms:seed=3,door=30"])
def test_readings_match_exact_ray_casts_on_shipped_and_generated_layouts(maze: str) -> None:
    env = BulletMazeEnv(maze=maze, observation="lidar", lidar_rays=72)
    try:
        lidar, pieces = env.lidar, env.world.pieces()
        assert lidar is not None
        w, h = env.layout.arena
        rng = np.random.default_rng(7)
        errors = []
        poses = 0
        while poses < 40:
            x, y, heading = rng.uniform(1, w - 1), rng.uniform(1, h - 1), rng.uniform(0, 6.3)
            if clearance(pieces, x, y) <= lidar.radius:
                continue  # the footprint would overlap a solid
            poses += 1
            readings = lidar.read(x, y, heading)
            for k, reading in enumerate(readings):
                a = heading + 2 * math.pi * k / lidar.rays
                exact = exact_range(
                    pieces, x, y, math.cos(a), math.sin(a), lidar.radius, lidar.range
                )
                if not grazes(pieces, x, y, math.cos(a), math.sin(a)):
                    errors.append(abs(reading - exact))
        errors_ = np.array(errors)
        # Boxes are exact; a cylinder's faces lie within MESH_TOLERANCE of it, so a ray off by
        # more met the surface at a grazing angle (under a thousandth of the rays here).
        assert np.median(errors_) <= MESH_TOLERANCE
        assert np.quantile(errors_, 0.99) <= 10 * MESH_TOLERANCE
        assert errors_.max() <= 0.5
    finally:
        env.close()


@pytest.mark.parametrize("radius", [1e-3, 0.5, 2.0, 7.5, 45.0, 1000.0, 5000.0])
def test_cylinder_sides_keep_the_faces_within_the_tolerance(radius: float) -> None:
    n = cylinder_sides(radius)
    assert MIN_SIDES <= n <= MAX_SIDES
    error = radius * (1 - math.cos(math.pi / n)) / (1 + math.cos(math.pi / n))
    assert error <= MESH_TOLERANCE
    if n > MIN_SIDES:  # the fewest that do
        fewer = n - 1
        assert radius * (1 - math.cos(math.pi / fewer)) / (1 + math.cos(math.pi / fewer)) > (
            MESH_TOLERANCE * 0.999
        )


def test_subdivided_keeps_the_corners_and_bounds_every_edge() -> None:
    corners = np.array([(0.0, 0.0), (2.5, 0.0), (2.5, 1.0), (0.0, 1.0)])
    points = _subdivided(corners, 1.0)
    edges = np.hypot(*(np.roll(points, -1, axis=0) - points).T)
    assert edges.max() <= 1.0 + 1e-12
    assert len(points) == 3 + 1 + 3 + 1
    for corner in corners:
        assert np.min(np.hypot(*(points - corner).T)) == 0.0
    assert _subdivided(corners, 5.0) is corners


def test_the_scene_client_is_disconnected_on_close() -> None:
    env = BulletMazeEnv(maze="paper", observation="lidar")
    assert env.lidar is not None
    client = env.lidar.scene.client
    assert pb.isConnected(physicsClientId=client)
    env.close()
    assert not pb.isConnected(physicsClientId=client)
    env.close()  # again: nothing


def test_a_scene_beyond_its_side_budget_is_coarsened_with_a_warning(
    monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    monkeypatch.setattr(ray_scene, "MAX_SCENE_SIDES", 2000)
    radii = [40.0 + k for k in range(10)]  # distinct: ten meshes of about 630 sides at 1e-3
    pieces = [
        Piece((100.0 * k + 50.0, 50.0), (0.0, 0.0), r, "obstacle") for k, r in enumerate(radii)
    ]
    pieces.append(Piece((500.0, 200.0), (900.0, 2.0), 0.0, "wall"))  # a long wall: 902 pieces
    with caplog.at_level(logging.WARNING, logger="bullet_maze.ray_scene"):
        scene = ray_scene.RayScene(pieces)
    try:
        assert scene.sides <= 2000
        assert scene.tolerance > MESH_TOLERANCE
        assert scene.segment > ray_scene.MAX_SEGMENT
        assert math.isclose(
            scene.tolerance / MESH_TOLERANCE, (scene.segment / ray_scene.MAX_SEGMENT) ** 2
        )
        assert "MAX_SCENE_SIDES" in caplog.text
        assert "coarser" in caplog.text
        # A ray at normal incidence still reads within the coarser tolerance: from 60 units left
        # of the first tree's centre, its surface lies 20 units away.
        s = METRES_PER_UNIT
        z = 0.5 * WALL_HEIGHT * s
        hit = scene.cast(np.array([[-10.0 * s, 50.0 * s, z]]), np.array([[50.0 * s, 50.0 * s, z]]))
        distance = hit[0][2] * 60.0
        assert abs(distance - 20.0) <= scene.tolerance + 1e-9
    finally:
        scene.close()


def test_a_small_scene_keeps_the_stated_tolerance(caplog: pytest.LogCaptureFixture) -> None:
    with caplog.at_level(logging.WARNING, logger="bullet_maze.ray_scene"):
        scene = ray_scene.RayScene([Piece((0.0, 0.0), (0.0, 0.0), 45.0, "obstacle")])
    try:
        assert scene.tolerance == MESH_TOLERANCE
        assert scene.segment == ray_scene.MAX_SEGMENT
        assert scene.sides == cylinder_sides(45.0)
        assert caplog.text == ""
    finally:
        scene.close()
