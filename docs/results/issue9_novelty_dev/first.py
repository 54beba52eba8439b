"""Episodes to the first goal on one layout, for variants of the general preset (dev only)::

    python first.py LAYOUT AGENT_SEED VARIANT CAP OUT

VARIANT is ``preset``; ``random`` (the preset, but every decision a uniformly random, held
action until the first terminal); ``novNN`` (the preset with ``novelty_cells`` NN);
``grid30`` (a 30 x 30 grid, Table I, adaptive + tabu); ``grid30g`` / ``grid60g`` (30 x 30 /
60 x 60 grids with the preset's model and sweeps; no holds until terminals, no model splits).
Learns up to CAP episodes (cap 5,000 steps, first reset seed 1000 x AGENT_SEED), stopping at
the first goal, and appends one JSON line to OUT.
"""

from __future__ import annotations

import dataclasses
import json
import sys
import time
from typing import Any

import gymnasium as gym

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from agent import GridAgent, TreeConfig, preset
from agent.tree_ensemble import tree_agent_class


def main(maze: str, seed: int, variant: str, cap: int, out: str) -> None:
    env = gym.make("BulletMaze-v0", maze=maze, max_episode_steps=5000)
    general = preset("general")
    over = {"novelty_cells": int(variant[3:])} if variant.startswith("nov") else {}
    config = dataclasses.replace(general.config, **over)
    strategy = general.make_exploration()
    agent: Any
    if variant.startswith("grid"):
        grid_config = TreeConfig()
        if variant.endswith("g"):
            grid_config = dataclasses.replace(config, hold_terminals=None, model_split_epochs=None)
        agent = GridAgent(
            env.observation_space,
            env.action_space,
            strategy,
            seed,
            grid_config,
            resolution=int(variant[4:6]),
        )
    else:
        agent = tree_agent_class(config)(
            env.observation_space, env.action_space, strategy, seed, config
        )
    if variant == "random":  # every decision random (and so held) until the first terminal
        base = getattr(strategy, "base", strategy)
        own = base.epsilon
        base.epsilon = lambda leaf: 1.0 if agent.terminals_seen == 0 else own(leaf)
    state: dict[str, Any] = {"first": None, "n": 0}

    def stop_at_goal(stats: Any) -> bool | None:
        state["n"] += 1
        if stats.steps < 5000:
            state["first"] = state["n"] - 1
            return False
        return None

    start = time.process_time()
    agent.learn(env, cap, reset_seed=seed * 1000, callback=stop_at_goal)
    record = {
        "maze": maze,
        "seed": seed,
        "variant": variant,
        "first": state["first"],
        "episodes": state["n"],
        "leaves": agent.n_leaves,
        "cpu": round(time.process_time() - start, 1),
    }
    with open(out, "a") as f:
        f.write(json.dumps(record) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), sys.argv[3], int(sys.argv[4]), sys.argv[5])
