"""Layouts with hundreds of solids: built from compounds within pybullet's limits, stepped in both
modes with the same collision answers the geometry gives, rendered, and queried exactly (the
query index answering as the solid bodies do, bit for bit, in one call)."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import gymnasium as gym
import numpy as np
import pybullet as pb
import pytest

from assets import MAZE_DIR
from bullet_maze import BulletMazeEnv, load_layout
from bullet_maze.geometry import clearance, segments_clear
from bullet_maze.world import (
    COMPOUND_CHILDREN,
    CONTACT_TOLERANCE,
    METRES_PER_UNIT,
    SAFE_REACH,
    URDF_CHILDREN,
)

FOREST = "forest:seed=0,count=250,width=700,height=700,gap=11"
MAZE = "maze:seed=0,rows=24,cols=24,cell=30"


def test_thirteen_obstacles_no_longer_crash_the_process(
    write_maze: Callable[[str], Path], make_env: Callable[..., gym.Env]
) -> None:
    # Issue 8's report: open.toml with 13 small obstacles ended in a segmentation fault.
    text = (MAZE_DIR / "open.toml").read_text()
    text += "".join(
        f"\n[[obstacles]]\ncenter = [{30 + 18 * i}.0, 150.0]\nradius = 3.0\n" for i in range(13)
    )
    path = write_maze(text)
    for mode in ("kinematic", "dynamic"):
        env = make_env(maze=str(path), mode=mode)
        env.reset(seed=0)
        for _ in range(50):
            env.step(0)
        assert len(env.unwrapped.world.solid_ids) > 1


@pytest.mark.parametrize("spec", [FOREST, MAZE])
def test_hundreds_of_solids_build_into_compounds_within_pybullets_limits(spec: str) -> None:
    layout = load_layout(spec)
    assert layout.solid_count >= 200
    env = BulletMazeEnv(maze=layout)
    try:
        world, client = env.world, env.client_id
        children = []
        for body in world.solid_ids:
            # One visual piece per collision piece (the collision data of a static rigid body
            # cannot be read back).
            children.append(len(pb.getVisualShapeData(body, physicsClientId=client)))
        assert children[:4] == [1, 1, 1, 1]  # the arena's walls, createCollisionShapeArray's
        assert all(COMPOUND_CHILDREN < n <= URDF_CHILDREN for n in children[4:])
        assert sum(children) == layout.solid_count + 4
        assert len(world.solid_ids) <= 4 + math.ceil(layout.solid_count / URDF_CHILDREN) * 2
    finally:
        env.close()


@pytest.mark.parametrize("spec", [FOREST, MAZE])
def test_kinematic_collisions_agree_with_the_geometry(spec: str) -> None:
    env = BulletMazeEnv(maze=spec, noise_variance=0.0)
    try:
        layout, radius = env.layout, env.robot.radius
        rng = np.random.default_rng(1)
        starts, ends, reported = [], [], []
        env.reset(seed=0)
        for step in range(1200):
            if step % 100 == 0:  # start anew somewhere free, to cover the arena
                while True:
                    point = rng.uniform(radius, np.array(layout.arena) - radius)
                    if clearance(layout, point) > radius + 0.1:
                        break
                if math.dist(point, layout.goal) <= layout.goal_radius:
                    continue
                env.reset(options={"start": tuple(point), "goal": layout.goal})
            x0, y0, _ = env.pose
            action = int(rng.integers(4))
            _, _, terminated, _, info = env.step(action)
            starts.append((x0, y0))
            ends.append(np.add((x0, y0), [(0, 5), (0, -5), (-5, 0), (5, 0)][action]))
            reported.append(info["collision"])
            if terminated:
                env.reset()
        # Sampled every 0.01, the true least clearance is at most 0.005 below the samples'.
        a, b, hit = np.array(starts), np.array(ends), np.array(reported)
        free = segments_clear(layout, a, b, 0.01, radius + CONTACT_TOLERANCE + 0.006)
        into = ~segments_clear(layout, a, b, 0.01, radius + CONTACT_TOLERANCE / 2 - 0.006)
        assert not hit[free].any(), "a free move was reported as a collision"
        assert hit[into].all(), "a move into a solid passed"
        assert free.sum() + into.sum() > 1150
        assert into.sum() > 50  # not vacuous: the walk meets the solids
    finally:
        env.close()


def test_distance_queries_see_every_nearby_solid() -> None:
    env = BulletMazeEnv(maze=FOREST)
    try:
        world, layout, radius = env.world, env.layout, env.robot.radius
        rng = np.random.default_rng(2)
        points = rng.uniform(0.0, layout.arena, (600, 2))
        gaps = clearance(layout, points) - radius
        assert (gaps > 0).sum() > 300
        for (x, y), expected in zip(points[gaps > 0], gaps[gaps > 0], strict=True):
            reach = float(rng.uniform(0.0, 30.0))
            distance = world.distance(float(x), float(y), reach)
            if expected <= reach:
                assert distance == pytest.approx(expected, abs=0.01)
            elif expected > reach + 0.01:
                assert distance == math.inf or distance > reach
    finally:
        env.close()


@pytest.mark.parametrize("mode", ["kinematic", "dynamic"])
@pytest.mark.parametrize("spec", [FOREST, MAZE])
def test_both_modes_step_and_render_hundreds_of_solids(
    make_env: Callable[..., gym.Env], spec: str, mode: str
) -> None:
    env = make_env(maze=spec, mode=mode, render_mode="rgb_array")
    env.reset(seed=0)
    rng = np.random.default_rng(3)
    collided = 0
    for _ in range(300):
        _, _, terminated, truncated, info = env.step(int(rng.integers(4)))
        collided += info["collision"]
        if terminated or truncated:
            env.reset()
    assert collided > 0
    image = env.render()
    layout = env.unwrapped.layout
    camera = env.unwrapped._camera
    assert image.shape == (256, 256, 3)
    solid = layout.obstacles[0].center if layout.obstacles else layout.walls[0].center
    floor = image[camera.pixel(*layout.goal)]
    assert image[camera.pixel(*solid)].mean() < 200
    assert floor[0] > floor[2] + 40  # the red goal marker


@pytest.mark.parametrize("spec", [FOREST, MAZE])
def test_the_query_index_answers_as_the_solid_bodies_in_one_call(spec: str) -> None:
    env = BulletMazeEnv(maze=spec)
    try:
        world, client = env.world, env.client_id
        rng = np.random.default_rng(4)
        calls = [0]
        original = pb.getClosestPoints

        def counted(*args: object, **kwargs: object) -> object:
            calls[0] += 1
            return original(*args, **kwargs)

        for x, y in rng.uniform(-5.0, np.array(env.layout.arena) + 5.0, (400, 2)):
            reach = float(rng.choice([0.0, 5.0, 20.0, SAFE_REACH]))
            pb.getClosestPoints = counted
            try:
                calls[0] = 0
                indexed = world._closest(float(x), float(y), reach)
                assert calls[0] == 1
            finally:
                pb.getClosestPoints = original
            world.place_probe(float(x), float(y))
            far = (reach + CONTACT_TOLERANCE) * METRES_PER_UNIT
            direct = [
                point
                for body in world.solid_ids
                for point in pb.getClosestPoints(world.probe_id, body, far, physicsClientId=client)
            ]
            # Distance, normal and the point on the solid: the same pieces, the same doubles.
            assert sorted((p[8], p[7], p[6]) for p in indexed) == sorted(
                (p[8], p[7], p[6]) for p in direct
            )
        index = world._index
        assert index is not None
        world.close()
        assert not pb.isConnected(physicsClientId=index.client)
        assert world._index is None
    finally:
        env.close()


def test_closing_the_env_disconnects_the_query_index_too() -> None:
    env = BulletMazeEnv(maze=MAZE)
    index = env.world._index
    assert index is not None
    assert pb.isConnected(physicsClientId=index.client)
    env.close()
    assert not pb.isConnected(physicsClientId=index.client)
    env.close()  # a second close does nothing
