"""Part 33 dev diagnostic: the greedy route beside the oracle's, drawn on the layout.

Trains the general preset (part 32's; with ``--cut`` also ``collision_splits_collided_only``)
on a dev layout with one agent seed, 600 episodes in blocks of 50 (reset seeds
seed * 1000 + block, as ``../issue9_part32_dev/forest_search.py``), then walks one greedy
episode and one oracle episode (part 11's controller) from reset seed 10^6 and prints a
character map, 5 units a cell: ``#`` a tree (robot radius added), ``g`` greedy only, ``o``
oracle only, ``*`` both, ``S``/``G`` start and goal::

    PYTHONPATH=. python docs/results/issue9_part33_dev/route_map.py "forest:seed=10" 0 [--cut]
"""

from __future__ import annotations

import dataclasses
import math
import sys
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from agent import preset

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "issue9_horizon_dev"))
from oracle import MOVES, move_scorer  # part 11's oracle

CELL = 5.0


def walk(env, choose) -> list[tuple[float, float]]:
    obs, _ = env.reset(seed=10**6)
    maze = env.unwrapped
    path, done = [tuple(maze.pose[:2])], False
    while not done:
        obs, _, terminated, truncated, _ = env.step(choose(obs))
        path.append(tuple(maze.pose[:2]))
        done = terminated or truncated
    return path


def main(spec: str, seed: int, cut: bool) -> None:
    warnings.simplefilter("ignore")
    env = gym.make("BulletMaze-v0", maze=spec, max_episode_steps=5000)
    base = preset("general")
    config = dataclasses.replace(base.config, collision_splits_collided_only=cut)
    agent = dataclasses.replace(base, config=config).agent(
        env.observation_space, env.action_space, seed
    )
    history = []
    for b in range(12):
        history += agent.learn(env, 50, reset_seed=seed * 1000 + b)
    maze = env.unwrapped
    optimum = maze.optimal_steps
    score = move_scorer(env)
    rng = np.random.default_rng(0)

    def oracle(_obs):
        x, y, _ = maze.pose
        scores = [score(x, y, dx, dy) for dx, dy in MOVES]
        best = min(scores)
        choices = [a for a, s in enumerate(scores) if s == best] if math.isfinite(best) else [0]
        return int(rng.choice(choices))

    greedy = walk(env, agent.predict)
    best = walk(env, oracle)
    layout = maze.layout
    w, h = (int(v / CELL) for v in layout.arena)
    grid = [[" "] * w for _ in range(h)]
    for j in range(h):
        for i in range(w):
            cx, cy = (i + 0.5) * CELL, (j + 0.5) * CELL
            for ob in layout.obstacles:
                if math.dist((cx, cy), ob.center) <= ob.radius + layout.robot_radius:
                    grid[j][i] = "#"
    for path, mark in ((best, "o"), (greedy, "g")):
        for x, y in path:
            i, j = min(w - 1, int(x / CELL)), min(h - 1, int(y / CELL))
            old = grid[j][i]
            grid[j][i] = "*" if old in "og*" and old != mark and old != " " else mark
    for point, mark in ((layout.start, "S"), (layout.goal, "G")):
        grid[min(h - 1, int(point[1] / CELL))][min(w - 1, int(point[0] / CELL))] = mark
    steps = np.array([r.steps for r in history], dtype=float)
    print(
        f"{spec} seed {seed} cut={cut}: optimum {optimum}; training final "
        f"{steps[-100:].mean() / optimum:.2f}x; greedy {len(greedy) - 1} "
        f"({(len(greedy) - 1) / optimum:.2f}x); oracle {len(best) - 1}; leaves {agent.n_leaves}"
    )
    for row in reversed(grid):
        print("".join(row))


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), "--cut" in sys.argv[3:])
