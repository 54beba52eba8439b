"""Part 34 dev diagnostic (d1): today's preset on Acrobot past 1,000 episodes.

Part 26 measured the preset of its day (before part 30's trial) to 4,000 episodes. This trains
today's preset in blocks (1,000, then 500 and 500 episodes; the first reset of each block seeded
1,000 episodes apart from the agent seed, the first block's from the seed itself, so the first
checkpoint is part 30's protocol) and scores the same 20 greedy episodes (reset seeds
10^6 + 1,000 seed + i) at 1,000, 1,500 and 2,000 episodes.

    python longer_acrobot.py OUT SEED [SEED ...]
"""

from __future__ import annotations

import json
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

from agent import adapt_env, preset

BLOCKS = ((1000, 0), (500, 1), (500, 2))


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    out = Path(argv[1])
    for seed in map(int, argv[2:]):
        env = adapt_env(gym.make("Acrobot-v1"))
        agent = preset("general").agent(env.observation_space, env.action_space, seed)
        done_episodes, start = 0, time.process_time()
        row: dict = {"seed": seed}
        for count, block in BLOCKS:
            reset_seed = seed if block == 0 else 1_000_000_000 + 1000 * seed + block
            agent.learn(env, count, reset_seed=reset_seed)
            done_episodes += count
            returns = []
            for i in range(20):
                obs, _ = env.reset(seed=1_000_000 + 1000 * seed + i)
                total, done = 0.0, False
                while not done:
                    obs, reward, term, trunc, _ = env.step(agent.predict(obs))
                    total += float(reward)
                    done = term or trunc
                returns.append(total)
            row[str(done_episodes)] = round(float(np.mean(returns)), 2)
            row[f"{done_episodes}_long"] = sum(r <= -200 for r in returns)
            row[f"{done_episodes}_leaves"] = agent.n_leaves
        row["cpu"] = round(time.process_time() - start, 1)
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
