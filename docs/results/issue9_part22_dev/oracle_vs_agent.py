"""The step-shortest controller against a trained agent, by the task's reward (part 22)::

    python oracle_vs_agent.py LAYOUT AGENT.npz [EPISODES]

The controller is ``issue9_horizon_dev/oracle.py``'s (it reads the true geodesic distance and
takes the compass move whose noise-free end is nearest the goal). Both run EPISODES episodes
(default 50; reset seeds 0, 1, ...; 2,000-step cap), the agent greedy (``predict``). Prints
each one's mean steps (and / optimum), longest episode, collisions per episode and return.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "issue9_horizon_dev"))

from oracle import MOVES, move_scorer  # noqa: E402

import bullet_maze  # noqa: E402,F401  (registers BulletMaze-v0)
from agent.learner import SMDPAgent  # noqa: E402


def episodes(env: gym.Env, policy, n: int) -> np.ndarray:
    """(steps, collisions, return) of n episodes of ``policy(obs) -> action``."""
    out = []
    for episode in range(n):
        obs, _ = env.reset(seed=episode)
        steps = collisions = 0
        total, done = 0.0, False
        while not done:
            obs, reward, terminated, truncated, info = env.step(policy(obs))
            steps, collisions, total = steps + 1, collisions + int(info["collision"]), total + reward
            done = terminated or truncated
        out.append((steps, collisions, total))
    return np.array(out, dtype=float)


if __name__ == "__main__":
    layout, agent_file = sys.argv[1], sys.argv[2]
    n = int(sys.argv[3]) if len(sys.argv) > 3 else 50
    env = gym.make("BulletMaze-v0", maze=layout, max_episode_steps=2000)
    env.reset(seed=0)
    maze = env.unwrapped
    score = move_scorer(env)
    rng = np.random.default_rng(0)

    def oracle(_obs: object) -> int:
        x, y, _ = maze.pose  # type: ignore[attr-defined]
        scores = [score(x, y, dx, dy) for dx, dy in MOVES]
        best = min(scores)
        if not math.isfinite(best):
            return int(rng.integers(len(MOVES)))
        return int(rng.choice([a for a, s in enumerate(scores) if s == best]))

    agent = SMDPAgent.load(agent_file)
    optimum = maze.optimal_steps  # type: ignore[attr-defined]
    for name, policy in (("step-shortest", oracle), ("agent", agent.predict)):
        o = episodes(env, policy, n)
        print(f"{layout} {name}: steps {o[:, 0].mean():.1f} ({o[:, 0].mean() / optimum:.2f}x), "
              f"longest {o[:, 0].max():.0f}, collisions {o[:, 1].mean():.2f} an episode, "
              f"return {o[:, 2].mean():.3f}")
