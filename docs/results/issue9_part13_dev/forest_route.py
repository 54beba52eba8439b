"""Part 13 dev diagnostic: where a trained general agent leaves the oracle's route on a forest.

Trains the general preset on a dev layout (agent seed s, 600 episodes, first reset seed s),
then walks the states of one oracle episode (the controller of
``../issue9_horizon_dev/oracle.py``: the compass move whose noise-free segment stays on free
grid nodes and ends nearest the goal by the true geodesic; reset seed 10^6) and, at each,
compares the agent's greedy action with the oracle's: whether they differ, whether the
oracle's action has stored model epochs in that leaf, the Q-bar gap, the mean reward of
those epochs (a collision pays -1, a free step -0.01 a step), and the leaf's width. Prints a
summary and the disagreements; also the greedy episode's length (reset seed 10^6)::

    PYTHONPATH=. python docs/results/issue9_part13_dev/forest_route.py \\
        "forest:seed=2,count=70,radius_max=8,gap=11" 0
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from agent import preset

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "issue9_horizon_dev"))
from oracle import MOVES, move_scorer  # part 11's oracle, beside this folder


def main(spec: str, seed: int) -> None:
    env = gym.make("BulletMaze-v0", maze=spec, max_episode_steps=5000)
    agent = preset("general").agent(env.observation_space, env.action_space, seed)
    agent.learn(env, 600, reset_seed=seed)
    maze = env.unwrapped
    score = move_scorer(env)

    obs, _ = env.reset(seed=10**6)
    greedy_steps, done = 0, False
    while not done:
        obs, _, terminated, truncated, _ = env.step(agent.predict(obs))
        greedy_steps, done = greedy_steps + 1, terminated or truncated

    model = agent.model
    rng = np.random.default_rng(0)
    obs, _ = env.reset(seed=10**6)
    rows, done = [], False
    while not done:
        x, y, _ = maze.pose  # type: ignore[attr-defined]
        scores = [score(x, y, dx, dy) for dx, dy in MOVES]
        best = min(scores)
        choices = [a for a, s in enumerate(scores) if s == best] if math.isfinite(best) else [0]
        oracle = int(rng.choice(choices))
        leaf = agent.leaf_of(obs)
        q = agent.q[leaf]
        greedy = agent.predict(obs)
        records = model._records.get(leaf * agent.n_actions + oracle, ())
        low, high = agent.partition.leaf_bounds(leaf)
        here = np.asarray(obs, dtype=float)[:2]
        near = min(
            (float(np.linalg.norm(np.asarray(r[0])[:2] - here)) for r in records), default=None
        )
        rows.append(
            {
                "xy": (round(x, 1), round(y, 1)),
                "agree": greedy in choices,
                "oracle": oracle,
                "greedy": greedy,
                "gap": q[greedy] - q[oracle],
                "epochs": len(records),
                "reward": float(np.mean([r[1] for r in records])) if records else None,
                "width": (round(high[0] - low[0], 1), round(high[1] - low[1], 1)),
                "nearest": None if near is None else round(near, 1),
            }
        )
        obs, _, terminated, truncated, _ = env.step(oracle)
        done = terminated or truncated
    optimum = maze.optimal_steps  # type: ignore[attr-defined]
    differ = [r for r in rows if not r["agree"]]
    untried = [r for r in differ if r["epochs"] == 0]
    print(
        f"{spec} seed {seed}: optimum {optimum}, greedy {greedy_steps} steps "
        f"({greedy_steps / optimum:.2f}x), oracle {len(rows)}; leaves {agent.n_leaves}"
    )
    print(
        f"oracle states where the greedy action is none of the oracle's best: {len(differ)} of "
        f"{len(rows)}; of those the oracle's action has no epoch in the leaf: {len(untried)}; "
        f"median Q-bar gap {np.median([r['gap'] for r in differ]) if differ else 0:.4f}"
    )
    tried = [r for r in differ if r["epochs"]]
    collided = [r for r in tried if r["reward"] <= -0.5]
    far = [r for r in tried if r["nearest"] > 5.0]
    print(
        f"of the {len(tried)} with epochs: mean reward <= -0.5 (mostly collisions) in "
        f"{len(collided)}; nearest stored start more than one step (5 units) away in {len(far)}"
    )
    for r in differ:
        print(r)


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]))
