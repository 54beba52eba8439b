"""The world's collision certificates: what cached queries prove free is free; and contact:
a robot against a solid can always leave it."""

from __future__ import annotations

import numpy as np
import pytest

from bullet_maze import BulletMazeEnv
from bullet_maze.geometry import clearance, segment_clearance
from bullet_maze.params import METRES_PER_UNIT
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


def _nearest(world: object, x: float, y: float) -> tuple[float, float, float]:
    """The distance to the nearest solid piece and the normal pointing away from it."""
    points = world._closest(x, y, 500.0)  # type: ignore[attr-defined]
    best = min(points, key=lambda p: p[8])
    return best[8] / METRES_PER_UNIT, best[7][0], best[7][1]


def _into_band(world: object, x: float, y: float) -> tuple[float, float]:
    """The point a straight move from (x, y) towards its nearest solid reaches when it stops
    three quarters of the way into the contact band."""
    distance, nx, ny = _nearest(world, x, y)
    travel = distance - 0.75 * CONTACT_TOLERANCE
    return x - travel * nx, y - travel * ny


@pytest.mark.parametrize("maze", ["paper", "rooms:seed=2,door=14,loops=0", "forest:seed=0"])
def test_a_robot_resting_inside_the_contact_band_can_leave_it(maze: str) -> None:
    """A move may end inside the tolerance band (the advance aims half-way into it). From
    there a move towards the solid is a collision and a move away or along it is not: the
    robot is never held against a wall for the rest of an episode (issue 9, part 31)."""
    env = BulletMazeEnv(maze=maze)
    try:
        world, layout, radius = env.world, env.layout, env.robot.radius
        rng = np.random.default_rng(3)
        points = rng.uniform(0.0, layout.arena, (400, 2))
        points = points[clearance(layout, points) > radius + 1.0]
        checked = 0
        for x, y in points[:40]:
            if _nearest(world, x, y)[0] > 60.0:
                continue
            x1, y1 = _into_band(world, x, y)
            if world.sweep_collides(x, y, x1, y1):
                continue  # another solid in the way
            end, mx, my = _nearest(world, x1, y1)
            assert CONTACT_TOLERANCE / 2 <= end < CONTACT_TOLERANCE  # inside the band
            assert world.sweep_collides(x1, y1, x1 - 2.0 * mx, y1 - 2.0 * my)  # into it
            assert not world.sweep_collides(x1, y1, x1 + 2.0 * mx, y1 + 2.0 * my)  # away
            along = [
                world.sweep_collides(x1, y1, x1 + 0.5 * s * my, y1 - 0.5 * s * mx)
                for s in (1.0, -1.0)
            ]
            assert not all(along)  # a wall's corner may stop one way, never both
            checked += 1
        assert checked >= 10
    finally:
        env.close()


def test_a_step_from_inside_the_band_moves_away_from_the_wall() -> None:
    """``step``'s compass move, from a pose a move can reach inside the band: the move away from
    the wall is taken and is no collision; the move into it stays put and is one."""
    env = BulletMazeEnv(maze="paper", noise_variance=0.0)
    try:
        env.reset(seed=0)
        x, y = env._x, env._y
        _, nx, ny = _nearest(env.world, x, y)
        assert (abs(nx), abs(ny)) == pytest.approx((0.0, 1.0), abs=1e-9)  # a wall below or above
        env._x, env._y = _into_band(env.world, x, y)
        moves = {a: env._moves[a] for a in range(4)}
        into = next(a for a, (dx, dy) in moves.items() if dy * ny < 0 and dx == 0)
        away = next(a for a, (dx, dy) in moves.items() if dy * ny > 0 and dx == 0)
        start = (env._x, env._y)
        _, reward, _, _, info = env.step(into)
        assert info["collision"]
        assert reward == env.task.collision_reward
        assert (env._x, env._y) == start
        _, _, _, _, info = env.step(away)
        assert not info["collision"]
        assert env._y != start[1]
    finally:
        env.close()


def test_the_sweep_before_the_fix_stays_available_and_the_switch_is_checked() -> None:
    """``contact_release=False`` is the sweep of the results recorded before 2026-12-07: from
    inside the band every move is a collision, away from the wall too."""
    env = BulletMazeEnv(maze="paper", noise_variance=0.0, contact_release=False)
    try:
        env.reset(seed=0)
        x, y = env._x, env._y
        _, nx, ny = _nearest(env.world, x, y)
        x1, y1 = _into_band(env.world, x, y)
        assert not env.world.sweep_collides(x, y, x1, y1)
        for dx, dy in ((nx, ny), (-ny, nx), (ny, -nx), (-nx, -ny)):
            assert env.world.sweep_collides(x1, y1, x1 + 2.0 * dx, y1 + 2.0 * dy)
    finally:
        env.close()
    for bad in ("yes", 1, None):
        with pytest.raises(TypeError, match="contact_release must be a bool"):
            BulletMazeEnv(maze="paper", contact_release=bad)
