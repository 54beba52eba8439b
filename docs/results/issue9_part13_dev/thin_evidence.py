"""Part 13 dev diagnostic: does thin, collided evidence hold the dense forests' routes long?

Trains the general preset on a dev layout (agent seed s, 600 episodes, first reset seed s) and
saves it. Then two arms continue from that file for 200 more episodes (the env reset with seed
s + 1 first):

* ``same``: as it is;
* ``forget``: first, every (leaf, action) whose stored epochs are at most ``MAX_EPOCHS`` and
  whose mean reward is at most -0.5 (mostly collisions; a collision pays -1) loses its epochs,
  and its Q-bar is set to the leaf's V-bar (a tie with the best action), then the model
  sweeps; nothing else changes.

Prints, per arm, the mean steps / optimum of the last 100 episodes and of 5 greedy episodes
(reset seeds 10^6 + i), and how many (leaf, action) pairs were forgotten. A measurement, not
an agent option: if ``forget`` shortens the routes, thin collided evidence is what holds
them::

    PYTHONPATH=. python docs/results/issue9_part13_dev/thin_evidence.py "forest:seed=0" 0
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from agent import preset
from agent.tree_ensemble import tree_agent_class

OUT = Path(__file__).with_name("thin_evidence.jsonl")
MAX_EPOCHS = 8


def forget_thin_collisions(agent: object) -> int:
    """Drop the epochs of every thin, collision-dominated (leaf, action); returns how many."""
    model = agent.model  # type: ignore[attr-defined]
    q = agent.q  # type: ignore[attr-defined]
    n_actions = agent.n_actions  # type: ignore[attr-defined]
    dropped = 0
    for key, records in list(model._records.items()):
        if not records or len(records) > MAX_EPOCHS:
            continue
        if np.mean([r[1] for r in records]) > -0.5:
            continue
        for record in records:
            model._link(record[4], key, -1)
        records.clear()
        model._aggregate(key)
        leaf, action = divmod(key, n_actions)
        q[leaf][action] = max(q[leaf])
        model.push(leaf, 1.0)
        dropped += 1
    return dropped


def finish(agent: object, env: gym.Env, optimum: float, seed: int) -> dict[str, float]:
    history = agent.learn(env, 200, reset_seed=seed + 1)  # type: ignore[attr-defined]
    greedy = []
    for i in range(5):
        obs, _ = env.reset(seed=10**6 + i)
        steps, done = 0, False
        while not done:
            obs, _, terminated, truncated, _ = env.step(agent.predict(obs))  # type: ignore[attr-defined]
            steps, done = steps + 1, terminated or truncated
        greedy.append(steps / optimum)
    last = np.mean([h.steps for h in history[-100:]]) / optimum
    return {"final": round(float(last), 3), "greedy": round(float(np.mean(greedy)), 3)}


def main(maze: str, seed: int) -> None:
    env = gym.make("BulletMaze-v0", maze=maze, max_episode_steps=5000)
    optimum = float(env.unwrapped.optimal_steps)  # type: ignore[attr-defined]
    config = preset("general").config
    agent = preset("general").agent(env.observation_space, env.action_space, seed)
    history = agent.learn(env, 600, reset_seed=seed)
    before = round(float(np.mean([h.steps for h in history[-100:]])) / optimum, 3)
    with tempfile.TemporaryDirectory() as folder:
        path = agent.save(Path(folder) / "agent.npz")
        same = finish(tree_agent_class(config).load(path), env, optimum, seed)
        forgetful = tree_agent_class(config).load(path)
        dropped = forget_thin_collisions(forgetful)
        forget = finish(forgetful, env, optimum, seed)
    record = {"maze": maze, "seed": seed, "final_600": before, "dropped": dropped}
    record |= {"same": same, "forget": forget}
    with OUT.open("a") as f:
        f.write(json.dumps(record) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]))
