"""Probe: ``smoothed_greedy.py``'s smoothing, with a neighbour's row counted only where the
model has an epoch from one of the two leaves that ends in the other (the agent has moved
between them: no wall between them in a maze). h = 0 is part 24's choice.

    python gated_smoothing.py TASK OUT SEED [SEED ...]      (classic: 20 greedy episodes)
    python gated_smoothing.py maze:LAYOUT OUT SEED [SEED ...] (600 episodes as maze_support.py)
"""

from __future__ import annotations

import json
import math
import sys
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "issue9_part23_dev"))
from supported_greedy import greedy_returns  # noqa: E402

import bullet_maze  # noqa: E402, F401
from agent import general_as_of, preset  # noqa: E402
from agent.tree_ensemble import tree_agent_class  # noqa: E402
from float_tasks_support import train  # noqa: E402

HS = (0.0, 0.5, 1.0)


def connected(model, a: int, b: int) -> bool:
    n = model.n_actions
    return any(key // n == a for key in model._preds.get(b, ())) or any(
        key // n == b for key in model._preds.get(a, ())
    )


def gated_action(agent, obs, h: float) -> int:
    x = np.asarray(obs, dtype=np.float64).reshape(-1).tolist()
    part, model = agent.partition, agent.model
    leaf = part.leaf_of(x)
    allowed = [a for a in range(agent.n_actions) if model.count(leaf, a) >= 2] or list(range(agent.n_actions))
    rows = [agent.q[leaf]]
    if h > 0.0:
        low, high = part.leaf_bounds(leaf)
        for j, (lo, hi) in enumerate(zip(low, high)):
            if not (math.isfinite(lo) and math.isfinite(hi)):
                continue
            for sign in (-1.0, 1.0):
                y = list(x)
                y[j] += sign * h * (hi - lo)
                other = part.leaf_of(y)
                if other != leaf and connected(model, leaf, other):
                    rows.append(agent.q[other])
    row = [sum(r[a] for r in rows) / len(rows) for a in range(agent.n_actions)]
    return max(allowed, key=row.__getitem__)


def maze_run(maze: str, seed: int):
    env = gym.make("BulletMaze-v0", maze=maze, max_episode_steps=5000)
    config = general_as_of(22)
    agent = tree_agent_class(config)(env.observation_space, env.action_space, preset("general").make_exploration(), seed, config)
    for block in range(12):
        agent.learn(env, 50, reset_seed=seed * 1000 + block)
    return env, agent


if __name__ == "__main__":
    warnings.simplefilter("ignore")
    task, out = sys.argv[1], Path(sys.argv[2])
    for seed in map(int, sys.argv[3:]):
        if task.startswith("maze:"):
            maze = task[len("maze:"):]
            env, agent = maze_run(maze, seed)
            optimum = env.unwrapped.optimal_steps
            for h in HS:
                steps = []
                for i in range(10):
                    obs, _ = env.reset(seed=10**6 + i)
                    n, done = 0, False
                    while not done:
                        obs, _, term, trunc, _ = env.step(gated_action(agent, obs, h))
                        n += 1
                        done = term or trunc
                    steps.append(n)
                with out.open("a") as f:
                    f.write(json.dumps({"maze": maze, "seed": seed, "h": h, "greedy": round(float(np.mean(steps)) / optimum, 3), "capped": sum(s >= 5000 for s in steps)}) + "\n")
            continue
        env, agent, cpu = train(task, seed)
        starts = [1_000_000 + 1000 * seed + i for i in range(20)]
        for h in HS:
            returns = greedy_returns(agent, env, 0, starts, lambda obs, h=h: gated_action(agent, obs, h))
            with out.open("a") as f:
                f.write(json.dumps({"task": task, "seed": seed, "h": h, "greedy": round(float(np.mean(returns)), 2), "cpu": round(cpu, 1)}) + "\n")
