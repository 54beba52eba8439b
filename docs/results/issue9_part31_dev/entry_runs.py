"""Part 31's round 2 dev runs: the general preset (part 30's) against the same preset with
``greedy_tie_trial_on_entry`` on (``ENTRY=1``).

The protocols and greedy scores are part 30's (``issue9_part30_dev/trial_runs.py``: ``sel``,
``z1``, ``z2``). A maze row also keeps the training curve's numbers that the maze rows of the
targets table read: the final (mean steps of the last 100 episodes over the optimum), the
convergence episode (``experiments.statistics.convergence_episode``, None: not converged) and
the training episodes at the 5,000-step cap from episode 300 on (with those of them that were
trial episodes).

    ENTRY=0|1 python entry_runs.py TASK OUT SEED [SEED ...]   (ENTRY=1 only at d885de3)
    ENTRY=0|1 python entry_runs.py maze:LAYOUT OUT SEED [SEED ...]
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
from experiments.statistics import convergence_episode

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "issue9_part30_dev"))
from trial_runs import greedy_returns, scored  # noqa: E402

ENTRY = os.environ.get("ENTRY", "1") == "1"


def make_agent(env, seed: int):
    general = preset("general")
    # the switch existed only at d885de3 (removed since): ENTRY=0 is the preset as it stands
    fields = {"greedy_tie_trial_on_entry": True} if ENTRY else {}
    config = dataclasses.replace(general.config, **fields)
    return tree_agent_class(config)(
        env.observation_space, env.action_space, general.make_exploration(), seed, config
    )


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
        agent = make_agent(env, seed)
        start = time.process_time()
        history = []
        for count, reset_seed in blocks:
            history += agent.learn(env, count, reset_seed=reset_seed)
        cpu = time.process_time() - start
        trial = agent.tie_trial
        diff, se = trial.difference()
        row = {
            "task": task,
            "seed": seed,
            "entry": ENTRY,
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
        if maze:
            steps = np.array([h.steps for h in history], dtype=float)
            success = np.array([h.success for h in history], dtype=float)
            conv = convergence_episode(steps, final_success=float(success[-100:].mean()))
            late = [e for e in range(300, len(history)) if history[e].steps >= 5000]
            row["final"] = round(float(steps[-100:].mean()) / optimum, 3)
            row["converged"] = conv
            row["late_capped"] = len(late)
            row["late_capped_trial"] = sum(trial.start <= e and (e - trial.start) % 4 == 3 for e in late)
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
