"""Probe (part 29, round 4): a temporal vote of the agent's own snapshots.

Today's preset trains as it does; its policy-only file is saved every 50 episodes over the last
half of training (episodes 500, 550, ..., 1,000 of a classic run; 300, 350, ..., 600 of a maze
run's 12 blocks of 50). The greedy action is the one most snapshots' ``predict`` choose, a tie
going to the latest snapshot among the tied actions. Both arms score the same training run:
``today`` (the final agent's ``predict``, part 28's str1) and ``vote``.

    python temporal_vote.py TASK OUT SEED [SEED ...]
    python temporal_vote.py maze:LAYOUT OUT SEED [SEED ...]
"""

from __future__ import annotations

import json
import sys
import tempfile
import time
import warnings
from collections import Counter
from pathlib import Path

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa: F401  (registers the maze)
from agent import adapt_env, preset
from agent.tree_ensemble import tree_agent_class

HERE = Path(__file__).resolve()
sys.path.insert(0, str(HERE.parents[1] / "issue9_part23_dev"))
from supported_greedy import greedy_returns  # noqa: E402

EVERY = 50


def voter(snapshots: list) -> callable:
    """The temporal vote over ``snapshots`` (oldest first)."""

    def choose(obs):
        picks = [int(s.predict(obs)) for s in snapshots]
        counts = Counter(picks)
        top = max(counts.values())
        for pick in reversed(picks):  # the latest snapshot among the tied
            if counts[pick] == top:
                return pick
        raise AssertionError

    return choose


def train(agent, env, episodes: int, blocks: list[tuple[int, int]], folder: Path) -> tuple[list, float, list[int]]:
    """Train in ``blocks`` of (episodes, reset seed); save a snapshot every EVERY episodes over
    the last half. Returns the snapshots (loaded), the CPU seconds and the steps per episode."""
    paths: list[Path] = []
    steps: list[int] = []

    def callback(stats) -> bool:
        done = stats.episode + 1
        if done * 2 >= episodes and done % EVERY == 0:
            paths.append(agent.save(folder / f"snap{done}", policy_only=True))
        return True

    start = time.process_time()
    for count, reset_seed in blocks:
        steps += [h.steps for h in agent.learn(env, count, callback=callback, reset_seed=reset_seed)]
    cpu = time.process_time() - start
    return [type(agent).load(p) for p in paths], cpu, steps


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, out = argv[1], Path(argv[2])
    general = preset("general")
    config = general.config
    for seed in map(int, argv[3:]):
        with tempfile.TemporaryDirectory() as tmp:
            if task.startswith("maze:"):
                maze = task[len("maze:") :]
                env = gym.make("BulletMaze-v0", maze=maze, max_episode_steps=5000)
                agent = tree_agent_class(config)(env.observation_space, env.action_space, general.make_exploration(), seed, config)
                snaps, cpu, steps = train(agent, env, 600, [(50, seed * 1000 + b) for b in range(12)], Path(tmp))
                optimum = env.unwrapped.optimal_steps
                row = {"maze": maze, "seed": seed, "snapshots": len(snaps), "cpu": round(cpu, 1)}
                for label, choose in (("today", agent.predict), ("vote", voter(snaps))):
                    greedy = []
                    for i in range(10):
                        obs, _ = env.reset(seed=10**6 + i)
                        n, done = 0, False
                        while not done:
                            obs, _, term, trunc, _ = env.step(choose(obs))
                            n += 1
                            done = term or trunc
                        greedy.append(n)
                    row[label] = round(float(np.mean(greedy)) / optimum, 3)
                    row[label + "_capped"] = sum(g >= 5000 for g in greedy)
                train_steps = np.asarray(steps, dtype=float)
                row["auc"] = round(float(train_steps.mean()) / optimum, 3)
                row["final"] = round(float(train_steps[-100:].mean()) / optimum, 3)
            else:
                env = adapt_env(gym.make(task))
                agent = tree_agent_class(config)(env.observation_space, env.action_space, general.make_exploration(), seed, config)
                snaps, cpu, _ = train(agent, env, 1000, [(1000, seed)], Path(tmp))
                starts = [1_000_000 + 1000 * seed + i for i in range(20)]
                row = {"task": task, "seed": seed, "snapshots": len(snaps), "cpu": round(cpu, 1)}
                for label, choose in (("today", agent.predict), ("vote", voter(snaps))):
                    row[label] = round(float(np.mean(greedy_returns(agent, env, 0, starts, choose))), 2)
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
