"""Part 37 diagnostic: does each Acrobot run take up the tie trial's width (z 2), and what does
each width score on the same trained agent?

    python width_uptake.py OUT SEED [SEED ...]

Today's general preset, part 30's classic protocol (1,000 episodes from reset seed = agent seed;
20 greedy episodes from reset seeds 10^6 + 1,000 seed + i), so the run's own score reproduces
part 35's round 5 lines. After training it records the trial's moments (``TieTrial.difference``,
whether z 2 is adopted) and scores the same 20 greedy episodes three times: at the run's widths,
then with ``predict``'s widths forced to (1, 1) and to (2, 2).
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


def score(env: gym.Env, agent, seed: int) -> tuple[float, int]:  # type: ignore[no-untyped-def]
    returns = []
    for i in range(20):
        obs, _ = env.reset(seed=1_000_000 + 1000 * seed + i)
        total, done = 0.0, False
        while not done:
            obs, reward, term, trunc, _ = env.step(agent.predict(obs))
            total += float(reward)
            done = term or trunc
        returns.append(total)
    return round(float(np.mean(returns)), 2), sum(r <= -200 for r in returns)


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    out = Path(argv[1])
    general = preset("general")
    for seed in map(int, argv[2:]):
        env = adapt_env(gym.make("Acrobot-v1"))
        agent = general.agent(env.observation_space, env.action_space, seed=seed)
        start = time.process_time()
        agent.learn(env, 1000, reset_seed=seed)
        trial = agent.tie_trial
        diff, se = trial.difference()
        row = {
            "seed": seed,
            "cpu": round(time.process_time() - start, 1),
            "adopted": trial.adopted,
            "diff": round(diff, 2),
            "se": round(se, 2),
            "episodes": [trial.plain.count, trial.tried.count],
        }
        row["mean"], row["long"] = score(env, agent, seed)
        for z in (1.0, 2.0):
            trial.widths = lambda z=z: (z, z)  # type: ignore[method-assign]
            row[f"z{z:g}"], row[f"z{z:g}_long"] = score(env, agent, seed)
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
