"""A controller that knows the layout: how close can steps with noise get to the optimum?

The maze's optimum (``optimal_steps``) is the L1 geodesic over the step, a bound for noise-free
steps. This controller reads the true geodesic distance to the goal (Dijkstra from the goal's
free nodes on the planner's 4-connected grid, ``bullet_maze.planning``) and at every step takes
the compass move whose noise-free end is nearest the goal among those whose straight segment
stays on free grid nodes (ties and dead ends at random, from a generator seeded 0). It runs
``EPISODES`` episodes (reset seeds 0, 1, ...; 2,000-step cap) and prints the optimum, the
lattice steps, its mean steps and their ratio to the optimum, and its longest episode. Not a
learner and not tuned; it uses the planner's private grid, so it is a measurement script::

    PYTHONPATH=. python docs/results/issue9_horizon_dev/oracle.py "rooms:seed=2,door=14,loops=0" 50

Its grid check is coarser than the simulation's collision test, so on some layouts it gets stuck
at a door or a pillar until the cap (its longest episode then reads 2,000); its mean there
measures the script, not the physics. Only the layouts where it never hit the cap say what the
noise costs.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable

import gymnasium as gym
import numpy as np
from scipy.sparse.csgraph import dijkstra

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from bullet_maze import planning

MOVES = [(0, 1), (0, -1), (-1, 0), (1, 0)]  # the compass actions' directions, in action order


def move_scorer(env: gym.Env) -> Callable[[float, float, int, int], float]:
    """``score(x, y, dx, dy)``: the true geodesic distance to the goal from the noise-free end
    of the compass move (dx, dy) from (x, y), inf where its straight segment leaves the free
    grid nodes (the planner's 4-connected grid of ``env``'s maze)."""
    maze = env.unwrapped
    layout, radius, step = maze.layout, maze.robot.radius, maze.task.step_size
    grid = planning._Grid(layout, radius, planning.grid_cell(layout, radius))
    goals = grid.goal_nodes(layout.goal, layout.goal_radius)
    to_goal = dijkstra(grid.edges(diagonal=False), indices=goals, min_only=True)
    to_goal = to_goal.reshape(grid.nx, grid.ny)

    def node(x: float, y: float) -> tuple[int, int] | None:
        i, j = round(x / grid.h), round(y / grid.h)
        return (i, j) if 0 <= i < grid.nx and 0 <= j < grid.ny else None

    def score(x: float, y: float, dx: int, dy: int) -> float:
        for t in np.linspace(0.0, 1.0, 12):
            at = node(x + step * dx * t, y + step * dy * t)
            if at is None or not grid.free[at]:
                return math.inf
        end = node(x + step * dx, y + step * dy)
        return math.inf if end is None else float(to_goal[end])

    return score


def main(spec: str, episodes: int) -> None:
    env = gym.make("BulletMaze-v0", maze=spec, max_episode_steps=2000)
    env.reset(seed=0)
    maze = env.unwrapped
    score = move_scorer(env)
    rng = np.random.default_rng(0)
    lengths = []
    for episode in range(episodes):
        env.reset(seed=episode)
        steps, done = 0, False
        while not done:
            x, y, _ = maze.pose
            scores = [score(x, y, dx, dy) for dx, dy in MOVES]
            best = min(scores)
            if math.isfinite(best):
                action = int(rng.choice([a for a, s in enumerate(scores) if s == best]))
            else:
                action = int(rng.integers(len(MOVES)))
            _, _, terminated, truncated, _ = env.step(action)
            steps, done = steps + 1, terminated or truncated
        lengths.append(steps)
    optimum = maze.optimal_steps
    mean = float(np.mean(lengths))
    print(
        spec[:45].ljust(45),
        optimum,
        maze.physical_limit.lattice_steps,
        "oracle mean",
        round(mean, 1),
        "ratio",
        round(mean / optimum, 3),
        "max",
        max(lengths),
    )


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 50)
