"""Probe (part 28): training's greedy choice breaks its statistical ties the way ``predict``
does since part 27.

Part 27 let the tree's ancestors, compared leaf by leaf, break ``predict``'s ties, and the
greedy routes improved on every classic task and on the mazes. Training still chooses by the
leaf's Q-bar alone. Here, at every decision where the exploration strategy chose the greedy
action (``strategy.explored`` False), and that action has at least ``greedy_min_epochs`` stored
epochs, the choice is remade among the supported actions the tabu list allows: the actions tied
with it within z standard errors (``_tied``) go to the ancestors (``_ancestors_choice``). The
ancestors' per-node sums are kept for the episode (dropped after it and after each split), so a
choice within an episode may read sums a few epochs old. Exploratory choices, and greedy
choices of an untried or once-tried action (optimism), are left as the strategy made them.

Arms (``VARIANTS``): ``base`` (today's training), ``trainZ`` (the rule above with z = Z).
Every arm is scored by today's ``predict`` on the same greedy episodes.

    python train_ties.py TASK OUT SEED [SEED ...]        (classic: 1,000 episodes, 20 greedy)

Only Acrobot was run: the criterion (``decision.md``) stopped the probe there.
"""

from __future__ import annotations

import json
import os
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

HERE = Path(__file__).resolve()
sys.path.insert(0, str(HERE.parents[1] / "issue9_part23_dev"))
from supported_greedy import greedy_returns  # noqa: E402

import bullet_maze  # noqa: E402, F401
from agent import adapt_env, preset  # noqa: E402
from agent.tree_ensemble import tree_agent_class  # noqa: E402

VARIANTS = tuple(os.environ.get("VARIANTS", "base,train1").split(","))


def make(env, seed: int, variant: str):
    general = preset("general")
    agent = tree_agent_class(general.config)(
        env.observation_space, env.action_space, general.make_exploration(), seed, general.config
    )
    counts = {"decisions": 0, "ties": 0, "changed": 0}
    if variant == "base":
        return agent, counts
    z = float(variant.removeprefix("train"))
    strategy = agent.exploration
    original = strategy.select
    k = max(agent.config.greedy_min_epochs, 1)

    def select(leaf, row, rng):
        action = original(leaf, row, rng)
        if strategy.explored:
            return action
        counts["decisions"] += 1
        support = agent.support(leaf)
        if support[action] < k:
            return action
        listed = getattr(strategy, "_by_leaf", {}).get(leaf) or ()
        allowed = [a for a in range(agent.n_actions) if support[a] >= k and a not in listed]
        if action not in allowed or len(allowed) < 2:
            return action
        tied = agent._tied(agent.members, [leaf], row, allowed, z)
        if len(tied) < 2:
            return action
        counts["ties"] += 1
        choice = agent._ancestors_choice(agent.members, [leaf], tied, z)
        counts["changed"] += choice != action
        return choice

    strategy.select = select
    return agent, counts


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, out = argv[1], Path(argv[2])
    for seed in map(int, argv[3:]):
        for variant in VARIANTS:
            env = adapt_env(gym.make(task))
            agent, counts = make(env, seed, variant)
            start = time.process_time()
            agent.learn(env, 1000, reset_seed=seed)
            cpu = time.process_time() - start
            starts = [1_000_000 + 1000 * seed + i for i in range(20)]
            returns = greedy_returns(agent, env, 0, starts, agent.predict)
            row = {"task": task, "seed": seed, "variant": variant, "greedy": round(float(np.mean(returns)), 2), "leaves": agent.n_leaves, "cpu": round(cpu, 1), **counts}
            with out.open("a") as f:
                f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
