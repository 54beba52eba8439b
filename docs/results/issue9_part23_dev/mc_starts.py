"""MountainCar: greedy steps of a trained agent (today's preset, ``general_as_of(22)``) from
a grid of start positions, against a near-optimal reference (the best of "push one way for k
steps, then push along the velocity", k = 0..80, both ways).

    python mc_starts.py SEED [SEED ...]  -> one JSON line per seed on stdout
"""

from __future__ import annotations

import json
import sys

import gymnasium as gym
import numpy as np

from agent import general_as_of
from agent.tree_ensemble import tree_agent_class
from agent import preset

GRID = np.linspace(-0.6, -0.4, 41)


def rollout(env: gym.Env, x: float, policy) -> int:
    env.reset(seed=0)
    env.unwrapped.state = np.array([x, 0.0])
    obs = np.array([x, 0.0], dtype=np.float32)
    for t in range(1, 201):
        obs, _, term, trunc, _ = env.step(policy(obs, t))
        if term:
            return t
        if trunc:
            return 200
    return 200


def reference(env: gym.Env, x: float) -> int:
    best = 200
    for first in (0, 2):
        for k in range(0, 81):
            steps = rollout(env, x, lambda o, t: first if t <= k else (2 if o[1] >= 0 else 0))
            best = min(best, steps)
    return best


def main(seeds: list[int]) -> None:
    env = gym.make("MountainCar-v0")
    ref = [reference(env, float(x)) for x in GRID]
    for seed in seeds:
        general = preset("general")
        config = general_as_of(22)
        agent = tree_agent_class(config)(
            env.observation_space, env.action_space, general.make_exploration(), seed, config
        )
        agent.learn(env, 1000, reset_seed=seed)
        steps = [rollout(env, float(x), lambda o, t: agent.predict(o)) for x in GRID]
        print(json.dumps({"seed": seed, "x": [round(float(v), 3) for v in GRID], "agent": steps, "ref": ref,
                          "mean_agent": float(np.mean(steps)), "mean_ref": float(np.mean(ref))}), flush=True)


if __name__ == "__main__":
    main([int(s) for s in sys.argv[1:]])
