"""Part 34 dev probe: outcome splits (decision.md).

Today's general preset, plus: at the end of every training episode each epoch gets its
lambda-return from its first input to the episode's end (``LAMBDA``, default 1: the Monte
Carlo return; a truncated episode bootstraps from V-bar of its last state), kept per
(leaf, action) in a window of the last ``WINDOW`` (32). Each (leaf, action) the episode touched
with at least ``LEAST`` (8) kept returns is tested with part 9's regression cut
(``choose_model_split``, gap ``model_split_gap`` in threshold units, t at least ``T``, default
6) on those returns, once at least ``LEAST`` returns have been added since its last test. ``OUTCOME=0`` runs today's preset through the same script.

    python outcome_runs.py TASK OUT SEED [SEED ...]
    python outcome_runs.py maze:LAYOUT OUT SEED [SEED ...]

Protocols as part 30's ``trial_runs.py``: classic 1,000 episodes from reset seed = agent seed,
20 greedy episodes from reset seeds 10^6 + 1,000 seed + i (mean return); mazes 12 blocks of 50
episodes (reset seeds 1,000 seed + block), 10 greedy episodes from reset seeds 10^6 + i (mean
steps over the optimum, and how many hit the 5,000-step cap).
"""

from __future__ import annotations

import json
import os
import sys
import time
import warnings
from collections import deque
from pathlib import Path

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa: F401  (registers the maze)
from agent import adapt_env, preset
from agent.model_split import choose_model_split
from agent.smdp import epoch_returns
from agent.tree_ensemble import tree_agent_class

OUTCOME = os.environ.get("OUTCOME", "1") == "1"
LAMBDA = float(os.environ.get("LAMBDA", "1.0"))
WINDOW = int(os.environ.get("WINDOW", "32"))
LEAST = int(os.environ.get("LEAST", "8"))
T = float(os.environ.get("T", "6"))


def outcome_class(base, splits: bool = True):
    """``base`` with the outcome windows kept; with ``splits`` False they are only kept (for
    ``knn_probe.py``), and the run is today's preset's step for step."""

    class OutcomeAgent(base):
        def __init__(self, *args, **kwargs):
            self._otrace = []
            self._outcomes = {}
            self._fresh = {}
            self.outcome_splits = 0
            super().__init__(*args, **kwargs)

        def _end_epoch(self, leaf, action, xs, rs, bootstrap, end_x=None, terminated=False):
            start = epoch_returns(rs, 0.0, self.discount)[0]
            self._otrace.append((tuple(xs[0]), action, start, len(rs), terminated, end_x))
            return super()._end_epoch(leaf, action, xs, rs, bootstrap, end_x, terminated)

        def _grow(self, parent, children):
            super()._grow(parent, children)
            leaf_of = self.partition.leaf_of
            for action in range(self.n_actions):
                entries = self._outcomes.pop((parent, action), None)
                for first, g in entries or ():
                    key = (leaf_of(list(first)), action)
                    self._outcomes.setdefault(key, deque(maxlen=WINDOW)).append((first, g))

        def _run_episode(self, env, obs):
            stats = super()._run_episode(env, obs)
            self._outcome_episode()
            return stats

        def _outcome_episode(self):
            trace, self._otrace = self._otrace, []
            if not trace:
                return
            q, gamma = self.q, self.discount
            leaf_of = self.partition.leaf_of
            last = trace[-1]
            after = 0.0 if last[4] or last[5] is None else max(q[leaf_of(last[5])])
            touched = {}
            for first, action, start, tau, terminal, end_x in reversed(trace):
                if terminal or end_x is None:
                    g = start
                else:
                    v_end = max(q[leaf_of(end_x)])
                    g = start + gamma**tau * ((1.0 - LAMBDA) * v_end + LAMBDA * after)
                key = (leaf_of(list(first)), action)
                self._outcomes.setdefault(key, deque(maxlen=WINDOW)).append((first, g))
                self._fresh[key] = self._fresh.get(key, 0) + 1
                touched[key] = None
                after = g
            if not splits:
                return
            partition = self.partition
            gap = self._in_units(self.config.model_split_gap)
            for key in touched:
                entries = self._outcomes.get(key)
                if entries is None or len(entries) < LEAST or self._fresh.get(key, 0) < LEAST:
                    continue
                self._fresh[key] = 0
                if not partition.may_split():
                    break
                leaf = key[0]
                firsts = np.array([e[0] for e in entries], dtype=np.float64)
                gs = np.array([e[1] for e in entries], dtype=np.float64)
                low, high, _, min_width = partition.split_box(leaf)
                choice = choose_model_split(
                    firsts, gs, low, high, min_width, min_gap=gap, min_t=T
                )
                if choice is None:
                    continue
                children = partition.split_with_samples(leaf, *choice)
                self._grow(leaf, children)
                self.outcome_splits += 1

    return OutcomeAgent


def make_agent(env, seed: int):
    general = preset("general")
    base = tree_agent_class(general.config)
    cls = outcome_class(base) if OUTCOME else base
    return cls(env.observation_space, env.action_space, general.make_exploration(), seed, general.config)


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
        row = {
            "task": task,
            "seed": seed,
            "outcome": OUTCOME,
            "lambda": LAMBDA,
            "window": WINDOW,
            "least": LEAST,
            "t": T,
            "cpu": round(cpu, 1),
            "leaves": agent.n_leaves,
            "outcome_splits": getattr(agent, "outcome_splits", 0),
            "train_last100": round(float(np.mean([h.steps for h in history[-100:]])), 2),
        }
        if maze:
            optimum = env.unwrapped.optimal_steps
            greedy = []
            for i in range(10):
                obs, _ = env.reset(seed=10**6 + i)
                n, done = 0, False
                while not done:
                    obs, _, term, trunc, _ = env.step(agent.predict(obs))
                    n += 1
                    done = term or trunc
                greedy.append(n)
            row["greedy"] = round(float(np.mean(greedy)) / optimum, 3)
            row["capped"] = sum(g >= 5000 for g in greedy)
            row["final"] = round(row["train_last100"] / optimum, 3)
        else:
            returns = []
            for i in range(20):
                obs, _ = env.reset(seed=1_000_000 + 1000 * seed + i)
                total, done = 0.0, False
                while not done:
                    obs, reward, term, trunc, _ = env.step(agent.predict(obs))
                    total += float(reward)
                    done = term or trunc
                returns.append(total)
            row["mean"] = round(float(np.mean(returns)), 2)
            row["long"] = sum(r <= -200 for r in returns)
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
