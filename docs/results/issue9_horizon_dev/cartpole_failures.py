"""How a CartPole-v1 dev run's greedy episodes end (issue 9, part 11; development seeds only).

Trains the general preset (with optional TreeConfig overrides) for 1,000 episodes with agent
seed s and first reset seed s, then runs the 20 greedy episodes of the classic dev protocol
(reset with seeds 10^6 + 1000 s + i) and prints, for each, its return, why it ended ("x": the
cart left the track, "th": the pole fell, "ok": the 500-step limit) and the largest |x|::

    PYTHONPATH=. python docs/results/issue9_horizon_dev/cartpole_failures.py 0 '{"gamma": 0.99}'
"""

from __future__ import annotations

import dataclasses
import json
import sys

import gymnasium as gym
import numpy as np

from agent import preset
from agent.tree_ensemble import tree_agent_class


def main(seed: int, overrides: dict) -> None:
    general = preset("general")
    config = dataclasses.replace(general.config, **overrides)
    env = gym.make("CartPole-v1")
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, general.make_exploration(), seed, config
    )
    agent.learn(env, 1000, reset_seed=seed)
    endings = []
    for i in range(20):
        obs, _ = env.reset(seed=1_000_000 + 1000 * seed + i)
        total, done, largest = 0.0, False, 0.0
        while not done:
            obs, reward, terminated, truncated, _ = env.step(agent.predict(obs))
            total += float(reward)
            largest = max(largest, abs(float(obs[0])))
            done = terminated or truncated
        why = "x" if abs(obs[0]) > 2.4 else ("th" if abs(obs[2]) > 0.2095 else "ok")
        endings.append((int(total), why, round(largest, 2)))
    mean = float(np.mean([e[0] for e in endings]))
    print(seed, overrides, agent.n_leaves, mean, endings)


if __name__ == "__main__":
    main(int(sys.argv[1]), json.loads(sys.argv[2]) if len(sys.argv) > 2 else {})
