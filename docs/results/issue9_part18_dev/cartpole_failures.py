"""Issue 9, part 18 (development): how the general preset's greedy CartPole episodes end.

Trains ``general_as_of(17)`` on ``CartPole-v1`` through ``adapt_env`` (1,000 episodes, first
reset seed SEED; the agent is saved to MODEL_DIR and reused), then runs 20 greedy episodes
(reset seeds 10^6 + 1000 SEED + i, the dev protocol) and prints, per episode, its length and
why it ended: ``x`` (the cart left |x| > 2.4), ``angle`` (the pole passed 12 degrees) or
``limit`` (500 steps), with the cart's position and velocity at the end::

    python docs/results/issue9_part18_dev/cartpole_failures.py SEED OUT.jsonl [MODEL_DIR]
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from local_greedy import trained  # noqa: E402


def main(seed: int, out: str, model_dir: str) -> None:
    warnings.simplefilter("ignore")
    agent, env = trained("CartPole-v1", seed, model_dir)
    episodes = []
    for i in range(20):
        obs, _ = env.reset(seed=10**6 + 1000 * seed + i)
        steps, done, xs = 0, False, []
        while not done:
            obs, _, terminated, truncated, _ = env.step(agent.predict(obs))
            xs.append(float(obs[0]))
            steps += 1
            done = terminated or truncated
        cause = "limit" if not terminated else ("x" if abs(obs[0]) > 2.4 else "angle")
        episodes.append({"steps": steps, "cause": cause, "x": round(float(obs[0]), 2),
                         "v": round(float(obs[1]), 2), "x_range": [round(min(xs), 2), round(max(xs), 2)]})
    with Path(out).open("a") as f:
        f.write(json.dumps({"seed": seed, "leaves": agent.n_leaves,
                            "greedy": float(np.mean([e["steps"] for e in episodes])),
                            "episodes": episodes}) + "\n")


if __name__ == "__main__":
    main(int(sys.argv[1]), sys.argv[2], sys.argv[3] if len(sys.argv) > 3 else "/tmp/part18_models")
