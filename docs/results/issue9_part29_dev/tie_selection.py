"""Probe (part 29, round 5): the agent chooses its tie width by the returns it earns.

Part 27's grid showed Acrobot wanting a wider tie test (z 2) than CartPole and the mazes (z 1).
Here, in the last 10 % of training, training's greedy choices break their ties as ``predict``'s
do (part 28's ``train_ties.py`` rule), with z 1 and z 2 in alternate episodes (z 1 first).
``predict`` then uses z 2 (for the leaf's test and the ancestors', ``greedy_tie_errors`` and
``greedy_tie_ancestors``) only if z 2's mean training return over its episodes exceeds z 1's by
more than two standard errors of the difference; otherwise z 1, today's.

Every run is scored three ways on the same training: ``z1`` and ``z2`` (``predict`` at each
width) and ``sel`` (the width chosen). Round 6 (``SELECT_GREEDY=1``): in the selection episodes
the agent acts by ``predict``'s rule at the episode's z, the strategy not asked (it still
learns from them).

    python tie_selection.py TASK OUT SEED [SEED ...]         (1,000 episodes, 20 greedy)
    python tie_selection.py maze:LAYOUT OUT SEED [SEED ...]  (12 blocks of 50, 10 greedy)
"""

from __future__ import annotations

import dataclasses
import json
import math
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

WIDTHS = (1.0, 2.0)
MARGIN = 2.0  # standard errors of the difference
GREEDY = os.environ.get("SELECT_GREEDY") == "1"
PLAIN_Z1 = os.environ.get("SELECT_Z1_PLAIN") == "1"  # round 8
FRACTION = float(os.environ.get("SELECT_FRACTION", "0.1"))  # round 7: 0.5


def selecting_agent(env, seed: int, start: int):
    """Today's agent whose greedy choices, from episode ``start`` on, break ties with z from
    ``WIDTHS`` in alternate episodes; returns the agent, the callback and the returns by z."""
    general = preset("general")
    agent = tree_agent_class(general.config)(
        env.observation_space, env.action_space, general.make_exploration(), seed, general.config
    )
    state: dict = {"z": None}
    returns: dict[float, list[float]] = {z: [] for z in WIDTHS}
    strategy = agent.exploration
    original = strategy.select
    k = max(agent.config.greedy_min_epochs, 1)

    def select(leaf, row, rng):
        action = original(leaf, row, rng)
        z = state["z"]
        if z is not None and GREEDY:  # round 6: the selection episodes act by predict's rule
            allowed = [a for a in range(agent.n_actions) if agent.support(leaf)[a] >= k]
            if not allowed:
                return max(range(agent.n_actions), key=row.__getitem__)
            tied = agent._tied(agent.members, [leaf], row, allowed, z)
            if len(tied) < 2:
                return tied[0]
            return agent._ancestors_choice(agent.members, [leaf], tied, z)
        if z is None or strategy.explored or (PLAIN_Z1 and z == WIDTHS[0]):
            return action  # (round 8: the z 1 episodes choose as today's training does)
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
        return agent._ancestors_choice(agent.members, [leaf], tied, z)

    strategy.select = select

    def callback(stats) -> bool:
        if state["z"] is not None:
            returns[state["z"]].append(float(stats.episode_return))
        following = stats.episode + 1
        state["z"] = WIDTHS[(following - start) % 2] if following >= start else None
        return True

    if start == 0:
        state["z"] = WIDTHS[0]
    return agent, callback, returns


def chosen_width(returns: dict[float, list[float]]) -> tuple[float, float, float]:
    """z 2 if its mean return beats z 1's by more than MARGIN standard errors; (z, diff, se)."""
    a, b = (np.asarray(returns[z], dtype=float) for z in WIDTHS)
    diff = float(b.mean() - a.mean())
    se = math.sqrt(a.var(ddof=1) / len(a) + b.var(ddof=1) / len(b))
    return (WIDTHS[1] if diff > MARGIN * se else WIDTHS[0]), diff, se


def at_width(agent, z: float):
    """``predict`` with the tie width z for the leaf's test and the ancestors'."""
    config = dataclasses.replace(agent.config, greedy_tie_errors=z, greedy_tie_ancestors=z)

    def choose(obs):
        if agent.config is not config:
            agent.config = config
        return agent.predict(obs)

    return choose


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, out = argv[1], Path(argv[2])
    for seed in map(int, argv[3:]):
        maze = task.startswith("maze:")
        if maze:
            env = gym.make("BulletMaze-v0", maze=task[len("maze:") :], max_episode_steps=5000)
            total, blocks = 600, [(50, seed * 1000 + b) for b in range(12)]
        else:
            env = adapt_env(gym.make(task))
            total, blocks = 1000, [(1000, seed)]
        agent, callback, returns = selecting_agent(env, seed, total - round(total * FRACTION))
        start = time.process_time()
        steps: list[int] = []
        for count, reset_seed in blocks:
            steps += [h.steps for h in agent.learn(env, count, callback=callback, reset_seed=reset_seed)]
        cpu = time.process_time() - start
        z, diff, se = chosen_width(returns)
        row = {"task": task, "seed": seed, "chosen": z, "diff": round(diff, 4), "se": round(se, 4), "cpu": round(cpu, 1)}
        for label, width in (("z1", 1.0), ("z2", 2.0), ("sel", z)):
            choose = at_width(agent, width)
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
