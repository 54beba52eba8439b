"""The query index against the solid bodies on random, hostile layouts: pieces thin and long
across several index squares, huge and tiny cylinders, arenas that are no multiple of a square,
robots from 0.1 to 20 units, queries on the squares' edges, outside the arena and at the largest
reach the index takes. Every answer must be the solid bodies' own, bit for bit. Queries place the
footprint's collision shape themselves (no probe body is moved): the answers must still be those
of the probe body at that pose, also for a layout of one solid body, at poses a hair apart, far
outside the arena and with the coordinates' sign bits and tiny magnitudes."""

from __future__ import annotations

import numpy as np
import pybullet as pb
import pytest

from bullet_maze.layout_types import MazeLayout, Obstacle, Wall
from bullet_maze.world import (
    CONTACT_TOLERANCE,
    METRES_PER_UNIT,
    REGION,
    SAFE_REACH,
    World,
)


def _random_layout(rng: np.random.Generator, pieces: tuple[int, int] = (17, 160)) -> MazeLayout:
    width, height = (float(v) for v in rng.uniform(120.0, 700.0, 2))
    walls, obstacles = [], []
    for _ in range(int(rng.integers(*pieces))):
        x, y = float(rng.uniform(0.0, width)), float(rng.uniform(0.0, height))
        if rng.random() < 0.5:
            long = float(rng.choice([rng.uniform(0.01, 5.0), rng.uniform(5.0, 1.5 * REGION)]))
            thin = float(rng.uniform(0.01, 3.0))
            size = (long, thin) if rng.random() < 0.5 else (thin, long)
            walls.append(Wall((x, y), size))
        else:
            radius = float(rng.choice([rng.uniform(0.01, 1.0), rng.uniform(1.0, 40.0)]))
            obstacles.append(Obstacle((x, y), radius))
    return MazeLayout(
        name="fuzz",
        arena=(width, height),
        start=(1.0, 1.0),
        goal=(width - 1.0, height - 1.0),
        goal_radius=1.0,
        obstacles=tuple(obstacles),
        walls=tuple(walls),
    )


def _query_points(rng: np.random.Generator, layout: MazeLayout, n: int) -> np.ndarray:
    width, height = layout.arena
    anywhere = rng.uniform((-8.0, -8.0), (width + 8.0, height + 8.0), (n, 2))
    # On a square's edge, a hair to either side, and on the arena's edge.
    edges = np.array([REGION, 2 * REGION, 0.0, width, height])
    snapped = anywhere.copy()
    pick = rng.random((n, 2)) < 0.4
    snapped[pick] = rng.choice(edges, pick.sum()) + rng.choice([0.0, 1e-9, -1e-9], pick.sum())
    return snapped


@pytest.mark.parametrize("seed", range(6))
def test_the_index_answers_as_the_solid_bodies_on_random_layouts(seed: int) -> None:
    rng = np.random.default_rng(seed)
    layout = _random_layout(rng)
    radius = float(rng.choice([0.1, rng.uniform(0.1, 20.0)]))
    client = pb.connect(pb.DIRECT)
    try:
        world = World(client, layout, radius)
        assert world._index is not None
        for x, y in _query_points(rng, layout, 150):
            x, y = float(x), float(y)
            reach = float(rng.choice([0.0, SAFE_REACH, rng.uniform(0.0, SAFE_REACH)]))
            indexed = world._closest(x, y, reach)
            direct = _probe_answers(world, client, x, y, reach)
            assert sorted((p[8], p[7], p[6]) for p in indexed) == sorted(
                (p[8], p[7], p[6]) for p in direct
            ), (seed, x, y, reach)
        world.close()
    finally:
        pb.disconnect(physicsClientId=client)


def _probe_answers(world: World, client: int, x: float, y: float, reach: float) -> list:
    world.place_probe(x, y)
    far = (reach + CONTACT_TOLERANCE) * METRES_PER_UNIT
    return [
        point
        for body in world.solid_ids
        for point in pb.getClosestPoints(world.probe_id, body, far, physicsClientId=client)
    ]


def _hostile_points(
    rng: np.random.Generator, layout: MazeLayout, n: int
) -> list[tuple[float, float]]:
    """Poses a placed probe would not have been moved for (a hair from the last), signed zeros,
    subnormal and tiny coordinates, far outside the arena."""
    width, height = layout.arena
    points: list[tuple[float, float]] = []
    for x, y in _query_points(rng, layout, n):
        x, y = float(x), float(y)
        points.append((x, y))
        points.append((float(np.nextafter(x, np.inf)), y))
        points.append((x, float(np.nextafter(y, -np.inf))))
    points += [(0.0, 0.0), (-0.0, -0.0), (5e-324, 1e-300), (-1e-12, height / 2)]
    points += [(-40.0, -40.0), (width + 60.0, height + 60.0), (width / 2, -REGION)]
    return points


@pytest.mark.parametrize("seed", range(4))
def test_one_solid_body_answers_as_its_probe_at_hostile_poses(seed: int) -> None:
    rng = np.random.default_rng(100 + seed)
    layout = _random_layout(rng, pieces=(0, 13))  # with the arena's 4 walls: one compound
    radius = float(rng.choice([0.1, rng.uniform(0.1, 20.0)]))
    client = pb.connect(pb.DIRECT)
    try:
        world = World(client, layout, radius)
        assert world._index is None
        assert len(world.solid_ids) == 1
        for x, y in _hostile_points(rng, layout, 60):
            reach = float(rng.choice([0.0, 1e-9, SAFE_REACH, rng.uniform(0.0, 3 * SAFE_REACH)]))
            queried = world._closest(x, y, reach)
            direct = _probe_answers(world, client, x, y, reach)
            assert [(p[8], p[7], p[6], p[5]) for p in queried] == [
                (p[8], p[7], p[6], p[5]) for p in direct
            ], (seed, x, y, reach)
        world.close()
    finally:
        pb.disconnect(physicsClientId=client)


@pytest.mark.parametrize("seed", range(3))
def test_the_index_answers_as_the_probe_at_hostile_poses(seed: int) -> None:
    rng = np.random.default_rng(200 + seed)
    layout = _random_layout(rng)
    radius = float(rng.choice([0.1, rng.uniform(0.1, 20.0)]))
    client = pb.connect(pb.DIRECT)
    try:
        world = World(client, layout, radius)
        assert world._index is not None
        for x, y in _hostile_points(rng, layout, 40):
            reach = float(rng.choice([0.0, 1e-9, SAFE_REACH, rng.uniform(0.0, SAFE_REACH)]))
            indexed = world._closest(x, y, reach)
            direct = _probe_answers(world, client, x, y, reach)
            assert sorted((p[8], p[7], p[6], p[5]) for p in indexed) == sorted(
                (p[8], p[7], p[6], p[5]) for p in direct
            ), (seed, x, y, reach)
        world.close()
    finally:
        pb.disconnect(physicsClientId=client)
