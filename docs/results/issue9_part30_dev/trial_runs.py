"""Part 30's dev runs: the general preset with ``TreeConfig.greedy_tie_trial`` (the library's
build of part 29's round 8, with a start that needs no run length).

Each run trains the candidate once and scores its greedy policy three ways: ``sel`` (``predict``
as the agent stands, at the widths the trial chose), ``z1`` and ``z2`` (``predict`` with the
trial set aside and both tie widths at 1 or 2). Protocols as part 27's str1 rows
(``issue9_part27_dev/ts_*.jsonl``): classic 1,000 episodes, 20 greedy episodes from reset seeds
1,000,000 + 1,000 seed + i; mazes 12 blocks of 50 episodes (reset seeds 1,000 seed + block),
10 greedy episodes from reset seeds 10^6 + i, steps over the optimum.

    python trial_runs.py TASK OUT SEED [SEED ...]
    python trial_runs.py maze:LAYOUT OUT SEED [SEED ...]

``TRIAL_START`` (default 300) sets ``greedy_tie_trial_episodes``, ``TRIAL_EVERY`` (default 2)
``greedy_tie_trial_every``.
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

import bullet_maze  # noqa: F401  (registers the maze)
from agent import adapt_env, preset
from agent.tree_ensemble import tree_agent_class

HERE = Path(__file__).resolve()
sys.path.insert(0, str(HERE.parents[1] / "issue9_part23_dev"))
from supported_greedy import greedy_returns  # noqa: E402

START = int(os.environ.get("TRIAL_START", "300"))
EVERY = int(os.environ.get("TRIAL_EVERY", "2"))


def candidate(env, seed: int):
    general = preset("general")
    config = dataclasses.replace(
        general.config,
        greedy_tie_trial=2.0,
        greedy_tie_trial_episodes=START,
        greedy_tie_trial_every=EVERY,
    )
    return tree_agent_class(config)(
        env.observation_space, env.action_space, general.make_exploration(), seed, config
    )


def scored(agent, width: float | None):
    """``predict`` as it stands (None), or with the trial set aside and both widths at ``width``."""
    if width is None:
        return agent.predict
    trial, config = agent.tie_trial, agent.config
    fixed = dataclasses.replace(  # one object, so predict's per-leaf cache holds between calls
        config, greedy_tie_trial=None, greedy_tie_errors=width, greedy_tie_ancestors=width
    )

    def choose(obs):
        agent.tie_trial, agent.config = None, fixed
        try:
            return agent.predict(obs)
        finally:
            agent.tie_trial, agent.config = trial, config

    return choose


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, out = argv[1], Path(argv[2])
    for seed in map(int, argv[3:]):
        maze = task.startswith("maze:")
        if maze:
            env = gym.make("BulletMaze-v0", maze=task[len("maze:") :], max_episode_steps=5000)
            blocks = [(50, seed * 1000 + b) for b in range(12)]
        else:
            env = adapt_env(gym.make(task))
            blocks = [(1000, seed)]
        agent = candidate(env, seed)
        start = time.process_time()
        for count, reset_seed in blocks:
            agent.learn(env, count, reset_seed=reset_seed)
        cpu = time.process_time() - start
        trial = agent.tie_trial
        diff, se = trial.difference()
        row = {
            "task": task,
            "seed": seed,
            "start": START,
            "every": EVERY,
            "adopted": trial.adopted,
            "diff": round(diff, 4),
            "se": round(se, 4),
            "cpu": round(cpu, 1),
        }
        for label, width in (("sel", None), ("z1", 1.0), ("z2", 2.0)):
            choose = scored(agent, width)
            if maze:
                optimum = env.unwrapped.optimal_steps
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
            else:
                starts = [1_000_000 + 1000 * seed + i for i in range(20)]
                row[label] = round(float(np.mean(greedy_returns(agent, env, 0, starts, choose))), 2)
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
