"""Replay one run of ``lambda_recent_dev`` outside the harness (issue 9, part 7).

The run's agent and environment seeds are those of the harness's first run (experiment seed
7700: agent 1272305970, first reset 4288713310), so an episode's steps equal the stored run's
while nothing is changed. Two uses::

    # the leaf cap raised: AUC, final, goals, leaves and 50-episode blocks, one JSON line
    python docs/results/issue9_recent_dev/replay.py corridors general-64 --max-leaves 16384
    # the model's windows of the four best leaves at every episode from 300 to 318
    python docs/results/issue9_recent_dev/replay.py corridors general-64 --windows 300 318
"""

from __future__ import annotations

import argparse
import dataclasses
import json
from typing import Any

import numpy as np

from agent.tree_ensemble import tree_agent_class
from experiments import factory
from experiments.config import load_config

AGENT_SEED = 1272305970
RESET_SEED = 4288713310


def windows(agent: Any) -> list[tuple[int, int, float, int, int, list[int]]]:
    """Of the four leaves with the highest V-bar: leaf, greedy action, V-bar, epochs in the
    model's window of (leaf, action), how many of them were terminal, and the leaves they
    ended in (-1: terminal)."""
    q = np.array(agent.q)
    leaves = agent.partition.leaves()
    v = q[leaves].max(axis=1)
    out = []
    for j in np.argsort(-v)[:4]:
        leaf = leaves[j]
        action = int(np.argmax(q[leaf]))
        records = agent.model._records.get(leaf * agent.n_actions + action, [])
        terminal = sum(1 for r in records if r[3] is None)
        ends = sorted({r[4] for r in records})
        out.append((leaf, action, round(float(v[j]), 3), len(records), terminal, ends))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("layout")
    parser.add_argument("strategy")
    parser.add_argument("--max-leaves", type=int, default=None)
    parser.add_argument("--windows", type=int, nargs=2, default=None)
    args = parser.parse_args()
    config = load_config("lambda_recent_dev").single_task(args.layout)
    spec = config.strategy(args.strategy)
    env = factory.make_env(config.env)
    bounds = config.env.observation_bounds
    agent = factory.make_agent(config, spec, env, AGENT_SEED, bounds=bounds)
    if args.max_leaves is not None:
        tree = dataclasses.replace(agent.config, max_leaves=args.max_leaves)
        strategy = factory.make_exploration(config, spec)
        agent = tree_agent_class(tree)(
            env.observation_space, env.action_space, strategy, AGENT_SEED, tree, bounds
        )
    last = 600 if args.windows is None else args.windows[1]

    def callback(stats: Any) -> bool:
        if args.windows is not None and stats.episode >= args.windows[0]:
            row = [stats.episode, stats.steps, int(stats.success), windows(agent)]
            print(json.dumps(row), flush=True)
        return stats.episode < last - 1

    history = agent.learn(env, last, callback=callback, reset_seed=RESET_SEED)
    steps = [s.steps for s in history]
    record = {
        "layout": args.layout,
        "strategy": args.strategy,
        "max_leaves": agent.config.max_leaves,
        "episodes": len(steps),
        "auc": round(sum(steps) / len(steps), 1),
        "final": round(sum(steps[-100:]) / len(steps[-100:]), 1),
        "goals": sum(s.success for s in history),
        "leaves": history[-1].leaves,
        "blocks": [round(float(np.mean(steps[b : b + 50]))) for b in range(0, len(steps), 50)],
    }
    print(json.dumps(record))


if __name__ == "__main__":
    main()
