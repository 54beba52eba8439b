"""The world's collision certificates: what cached queries prove free is free."""

from __future__ import annotations

import numpy as np
import pytest

from bullet_maze import BulletMazeEnv
from bullet_maze.geometry import clearance, segment_clearance
from bullet_maze.world import CONTACT_TOLERANCE


@pytest.mark.parametrize("maze", ["paper", "corridors"])
def test_certificates_clear_only_free_footprints(maze: str) -> None:
    env = BulletMazeEnv(maze=maze)
    try:
        world, layout, radius = env.world, env.layout, env.robot.radius
        rng = np.random.default_rng(0)
        points = rng.uniform(0.0, layout.arena, (1500, 2))
        points = points[clearance(layout, points) > radius + CONTACT_TOLERANCE]
        certified_discs = certified_moves = 0
        for x, y in points:
            reach = rng.uniform(0.0, 15.0)
            if world.certified_clear(x, y, reach):
                certified_discs += 1
                # The whole disc of that reach is free: the centre is that much farther away.
                assert clearance(layout, np.array((x, y))) - radius >= reach + CONTACT_TOLERANCE
            angle = rng.uniform(0.0, 2.0 * np.pi)
            end = np.array((x + reach * np.cos(angle), y + reach * np.sin(angle)))
            if world.certified_free(x, y, *end):
                certified_moves += 1
                # Sampled every 0.01: the true minimum is at most 0.005 below.
                free = segment_clearance(layout, np.array((x, y)), end, spacing=0.01)[0]
                assert free - radius >= CONTACT_TOLERANCE - 0.005
        # Not vacuous: most of the arena is open.
        assert certified_discs > len(points) / 3
        assert certified_moves > len(points) / 3
    finally:
        env.close()
