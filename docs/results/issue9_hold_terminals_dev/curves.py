"""The maze driver of issue 9, part 8 (held exploration until n terminals; development only).

One job: the general preset's config with ``overrides`` on one development layout, agent seed
s, 600 episodes learnt in blocks of 50 (block b's first episode reset with seed 1000 s + b),
and after each block 3 greedy episodes (``predict`` at every step, reset with seeds
10^6 + 100 b + i). Appends one JSON line to ``maze.jsonl`` beside this file (or the file
named by the fifth argument): AUC (mean training steps per episode / optimum), final (the
last 100 episodes' mean / optimum), the episode from which the 50-episode moving average
stays within 10 % of the final value (the report's rule), the greedy steps per block /
optimum, leaves and CPU seconds::

    PYTHONPATH=. python docs/results/issue9_hold_terminals_dev/curves.py \
        paper_narrow 0 holdT20 '{"hold_terminals": 20}'
"""

from __future__ import annotations

import dataclasses
import json
import sys
import time
from pathlib import Path

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from agent import preset
from agent.tree_ensemble import tree_agent_class

OUT = Path(__file__).with_name("maze.jsonl")


def greedy_steps(agent: object, env: gym.Env, seed: int) -> int:
    """Steps of one greedy episode (the env's 5,000-step cap ends a loop)."""
    obs, _ = env.reset(seed=seed)
    steps, done = 0, False
    while not done:
        obs, _, terminated, truncated, _ = env.step(agent.predict(obs))  # type: ignore[attr-defined]
        steps += 1
        done = terminated or truncated
    return steps


def run(
    maze: str,
    seed: int,
    label: str,
    overrides: dict,
    out: Path,
    episodes: int = 600,
    env_kwargs: dict | None = None,
    base: object | None = None,
) -> None:
    """``env_kwargs`` go to ``gym.make`` (part 17: ``{"observation": "lidar"}``); ``base`` is
    the config the overrides apply to (default: today's general preset)."""
    kwargs = env_kwargs or {}
    env = gym.make("BulletMaze-v0", maze=maze, max_episode_steps=5000, **kwargs)
    probe = gym.make("BulletMaze-v0", maze=maze, max_episode_steps=5000, **kwargs)
    optimum = env.unwrapped.optimal_steps  # type: ignore[attr-defined]
    general = preset("general")
    config = dataclasses.replace(base or general.config, **overrides)  # type: ignore[type-var]
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, general.make_exploration(), seed, config
    )
    start = time.process_time()
    train: list[int] = []
    greedy: list[float] = []
    for block in range(episodes // 50):
        history = agent.learn(env, 50, reset_seed=seed * 1000 + block)
        train += [h.steps for h in history]
        runs = [greedy_steps(agent, probe, 10**6 + 100 * block + i) for i in range(3)]
        greedy.append(float(np.mean(runs)))
    steps = np.array(train, dtype=float)
    moving = np.convolve(steps, np.ones(50) / 50, mode="valid")
    final = float(steps[-100:].mean())
    inside = np.abs(moving - final) <= 0.1 * final
    converged = next((i + 50 for i in range(len(moving)) if inside[i:].all()), None)
    record = {
        "maze": maze,
        "seed": seed,
        "label": label,
        "over": overrides,
        **({"env": env_kwargs} if env_kwargs else {}),
        "opt": optimum,
        "auc": round(float(steps.mean()) / optimum, 3),
        "final": round(final / optimum, 3),
        "conv": converged,
        "greedy": [round(v / optimum, 2) for v in greedy],
        "leaves": agent.n_leaves,
        "cpu": round(time.process_time() - start, 1),
        "blocks": [
            round(float(steps[i : i + 50].mean()) / optimum, 2) for i in range(0, len(steps), 50)
        ],
    }
    with out.open("a") as f:
        f.write(json.dumps(record) + "\n")


if __name__ == "__main__":
    target = Path(sys.argv[5]) if len(sys.argv) > 5 else OUT
    run(sys.argv[1], int(sys.argv[2]), sys.argv[3], json.loads(sys.argv[4]), target)
