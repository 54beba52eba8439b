"""A controller that knows the map and prices collisions: how short can a safe route be? (part 22)::

    python careful.py LAYOUT EPISODES WEIGHTS      # e.g. "rooms:seed=3,door=14,loops=0" 20 10,100

Not a learner and not tuned. At each step it scores each compass move by the mean, over 32
noise draws (the env's Gaussian, standard deviation sqrt(noise_variance), from a generator
seeded 123, the same draws every step), of the true geodesic distance to the goal from the
noisy end in steps, plus WEIGHT times the fraction of draws whose straight segment leaves the
free grid nodes (a collision; such a draw counts the distance from where it started). It takes
the lowest score. WEIGHT 100 prices a collision as the task's reward does (-1 against -0.01 a
step); WEIGHT 0 is near ``issue9_horizon_dev/oracle.py``. It runs EPISODES episodes (reset
seeds 0, 1, ...; 2,000-step cap) per weight and prints mean steps (and / optimum), the
longest, collisions per episode and the return, and the same over the episodes that did not
reach the cap: its grid check is coarser than the simulation's, so it can stick at a door,
and those episodes measure the script, not the physics.
"""

from __future__ import annotations

import math
import sys

import gymnasium as gym
import numpy as np
from scipy.sparse.csgraph import dijkstra

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from bullet_maze import planning

MOVES = [(0, 1), (0, -1), (-1, 0), (1, 0)]  # the compass actions' directions, in action order
CAP = 2000

if __name__ == "__main__":
    layout_spec, n = sys.argv[1], int(sys.argv[2])
    weights = [float(w) for w in sys.argv[3].split(",")]
    env = gym.make("BulletMaze-v0", maze=layout_spec, max_episode_steps=CAP)
    env.reset(seed=0)
    maze = env.unwrapped
    layout, radius, step = maze.layout, maze.robot.radius, maze.task.step_size  # type: ignore[attr-defined]
    sigma = math.sqrt(maze.task.noise_variance)  # type: ignore[attr-defined]
    grid = planning._Grid(layout, radius, planning.grid_cell(layout, radius))
    goals = grid.goal_nodes(layout.goal, layout.goal_radius)
    to_goal = dijkstra(grid.edges(diagonal=False), indices=goals, min_only=True)
    to_goal = to_goal.reshape(grid.nx, grid.ny)
    noise = np.random.default_rng(123).normal(0.0, sigma, size=(32, 2))

    def node(x: float, y: float) -> tuple[int, int] | None:
        i, j = round(x / grid.h), round(y / grid.h)
        return (i, j) if 0 <= i < grid.nx and 0 <= j < grid.ny else None

    def distance_after(x: float, y: float, ex: float, ey: float) -> float | None:
        """Geodesic distance from (ex, ey), None if the segment from (x, y) is not free."""
        for t in np.linspace(0.0, 1.0, 12):
            at = node(x + (ex - x) * t, y + (ey - y) * t)
            if at is None or not grid.free[at]:
                return None
        end = node(ex, ey)
        return None if end is None else float(to_goal[end])

    def score(x: float, y: float, dx: int, dy: int, weight: float) -> float:
        start = node(x, y)
        here = float(to_goal[start]) if start is not None and grid.free[start] else 1e6
        total, collided = 0.0, 0
        for nx_, ny_ in noise:
            d = distance_after(x, y, x + step * dx + nx_, y + step * dy + ny_)
            if d is None or not math.isfinite(d):
                collided += 1
                total += here if math.isfinite(here) else 1e6
            else:
                total += d
        return total / len(noise) / step + weight * collided / len(noise)

    optimum = maze.optimal_steps  # type: ignore[attr-defined]
    for weight in weights:
        rows = []
        for episode in range(n):
            env.reset(seed=episode)
            steps = collisions = 0
            total, done = 0.0, False
            while not done:
                x, y, _ = maze.pose  # type: ignore[attr-defined]
                action = int(np.argmin([score(x, y, dx, dy, weight) for dx, dy in MOVES]))
                _, reward, terminated, truncated, info = env.step(action)
                steps, collisions = steps + 1, collisions + int(info["collision"])
                total += float(reward)
                done = terminated or truncated
            rows.append((steps, collisions, total))
        o = np.array(rows, dtype=float)
        ok = o[o[:, 0] < CAP]
        print(f"{layout_spec} weight {weight:g}: steps {o[:, 0].mean():.1f} "
              f"({o[:, 0].mean() / optimum:.2f}x), longest {o[:, 0].max():.0f}, collisions "
              f"{o[:, 1].mean():.2f} an episode, return {o[:, 2].mean():.3f}; below the cap "
              f"{len(ok)} of {len(o)}: steps {ok[:, 0].mean():.1f} "
              f"({ok[:, 0].mean() / optimum:.2f}x), collisions {ok[:, 1].mean():.2f}, "
              f"return {ok[:, 2].mean():.3f}", flush=True)
