"""Probe (part 28, round 5): offset trees on today's preset.

Part 13 measured four offset trees (``ensemble_trees`` 4, with ``ensemble_decisions="first"``)
on part 12's preset: Acrobot rose by about 17 steps, MountainCar and CartPole fell. Fifteen
parts have changed the preset since, among them part 27's greedy choice, which asks every
tree's ancestors. Does the trade still hold? Today's preset with the overrides in
``OVERRIDES`` (JSON TreeConfig fields), 1,000 episodes, 20 greedy episodes by ``predict``.

    OVERRIDES='{"ensemble_trees": 2, "ensemble_decisions": "first"}' \
        python offset_trees.py TASK OUT LABEL SEED [SEED ...]
        python offset_trees.py maze:LAYOUT OUT LABEL SEED [SEED ...]
"""

from __future__ import annotations

import dataclasses
import json
import os
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

HERE = Path(__file__).resolve()
sys.path.insert(0, str(HERE.parents[1] / "issue9_part23_dev"))
from supported_greedy import greedy_returns  # noqa: E402

from agent import adapt_env, preset  # noqa: E402
from agent.tree_ensemble import tree_agent_class  # noqa: E402


def maze_row(maze: str, seed: int, label: str, config, out: Path) -> None:
    """Part 23's maze protocol (``maze_support.py``): 12 blocks of 50 episodes, first reset of
    block b seeded seed * 1000 + b; 10 greedy episodes from reset seeds 10^6 + i."""
    env = gym.make("BulletMaze-v0", maze=maze, max_episode_steps=5000)
    general = preset("general")
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, general.make_exploration(), seed, config
    )
    start = time.process_time()
    steps = []
    for block in range(12):
        steps += [h.steps for h in agent.learn(env, 50, reset_seed=seed * 1000 + block)]
    cpu = time.process_time() - start
    optimum = env.unwrapped.optimal_steps
    greedy = []
    for i in range(10):
        obs, _ = env.reset(seed=10**6 + i)
        n, done = 0, False
        while not done:
            obs, _, term, trunc, _ = env.step(agent.predict(obs))
            n += 1
            done = term or trunc
        greedy.append(n)
    train = np.asarray(steps, dtype=float)
    row = {"maze": maze, "seed": seed, "variant": label, "greedy": round(float(np.mean(greedy)) / optimum, 3), "capped": sum(g >= 5000 for g in greedy), "auc": round(float(train.mean()) / optimum, 3), "final": round(float(train[-100:].mean()) / optimum, 3), "cpu": round(cpu, 1)}
    with out.open("a") as f:
        f.write(json.dumps(row) + "\n")


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, out, label = argv[1], Path(argv[2]), argv[3]
    overrides = json.loads(os.environ.get("OVERRIDES", "{}"))
    general = preset("general")
    config = dataclasses.replace(general.config, **overrides)
    for seed in map(int, argv[4:]):
        if task.startswith("maze:"):
            maze_row(task[len("maze:") :], seed, label, config, out)
            continue
        env = adapt_env(gym.make(task))
        agent = tree_agent_class(config)(
            env.observation_space, env.action_space, general.make_exploration(), seed, config
        )
        start = time.process_time()
        agent.learn(env, 1000, reset_seed=seed)
        cpu = time.process_time() - start
        starts = [1_000_000 + 1000 * seed + i for i in range(20)]
        returns = greedy_returns(agent, env, 0, starts, agent.predict)
        row = {"task": task, "seed": seed, "variant": label, "overrides": overrides, "greedy": round(float(np.mean(returns)), 2), "leaves": agent.n_leaves, "cpu": round(cpu, 1)}
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
