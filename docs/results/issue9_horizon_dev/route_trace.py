"""Where a trained general agent's greedy route loses steps on a maze (issue 9, part 11; dev only).

Trains the general preset (with optional TreeConfig overrides) for 600 episodes on a layout
(agent seed s, first reset seed s), then runs 5 greedy episodes (reset seeds 10^6 + i) and
counts, per episode, the steps that did not move the robot (blocked), that moved it away from the
goal by more than a unit of geodesic distance (back), and the others that gained less than 3
units (sideways); the geodesic field is the planner's 4-connected grid, as in ``oracle.py``.
Then it prints the first greedy episode's steps that moved away, with the leaf's box, Q-bar and
visits::

    PYTHONPATH=. python docs/results/issue9_horizon_dev/route_trace.py \\
        "rooms:seed=2,door=14,loops=0" 0 '{"gamma": 0.99, "scale_horizon": null}'
"""

from __future__ import annotations

import dataclasses
import json
import math
import sys

import gymnasium as gym
import numpy as np
from scipy.sparse.csgraph import dijkstra

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from agent import preset
from agent.tree_ensemble import tree_agent_class
from bullet_maze import planning


def main(spec: str, seed: int, overrides: dict) -> None:
    env = gym.make("BulletMaze-v0", maze=spec, max_episode_steps=5000)
    maze = env.unwrapped
    general = preset("general")
    config = dataclasses.replace(general.config, **overrides)
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, general.make_exploration(), seed, config
    )
    history = agent.learn(env, 600, reset_seed=seed)
    optimum = maze.optimal_steps
    final = np.mean([h.steps for h in history[-100:]]) / optimum
    print(f"final {final:.3f} of the optimum {optimum}; {agent.n_leaves} leaves")
    layout, radius = maze.layout, maze.robot.radius
    grid = planning._Grid(layout, radius, planning.grid_cell(layout, radius))
    goals = grid.goal_nodes(layout.goal, layout.goal_radius)
    field = dijkstra(grid.edges(diagonal=False), indices=goals, min_only=True)
    field = field.reshape(grid.nx, grid.ny)

    def to_goal(x: float, y: float) -> float:
        return float(field[round(x / grid.h), round(y / grid.h)])

    counts = {"steps": 0, "blocked": 0, "back": 0, "sideways": 0}
    trace = []
    for episode in range(5):
        obs, _ = env.reset(seed=10**6 + episode)
        done = False
        while not done:
            x, y, _ = maze.pose
            action = agent.predict(obs)
            leaf = agent.leaf_info(agent.leaf_of(obs))
            obs, _, terminated, truncated, _ = env.step(action)
            done = terminated or truncated
            x1, y1, _ = maze.pose
            before, after = to_goal(x, y), to_goal(x1, y1)
            counts["steps"] += 1
            if math.hypot(x1 - x, y1 - y) < 2.0:
                counts["blocked"] += 1
            elif after > before + 1.0:
                counts["back"] += 1
                if episode == 0:
                    trace.append((counts["steps"], "UDLR"[action], round(x, 1), round(y, 1), leaf))
            elif after > before - 3.0:
                counts["sideways"] += 1
    print(spec, {k: v / 5 for k, v in counts.items()}, "per greedy episode")
    for step, action, x, y, leaf in trace:
        low = tuple(round(v, 1) for v in leaf.low)
        high = tuple(round(v, 1) for v in leaf.high)
        q = [round(v, 3) for v in leaf.q_values]
        print(step, action, (x, y), "leaf", low, high, "Q", q, "visits", leaf.visits)


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), json.loads(sys.argv[3]) if len(sys.argv) > 3 else {})
