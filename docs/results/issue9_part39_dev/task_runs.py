"""Part 39 dev: the general preset (or an earlier one) with fields overridden, on any task.

    OVERRIDES='{"gamma": 0.99}' AS_OF=7 python task_runs.py TASK EPISODES OUT SEED [SEED ...]

Trains for EPISODES episodes from reset seed = agent seed, then plays 20 greedy episodes (reset
seeds 10^6 + 1,000 seed + i). One JSON line per seed: the mean training return of each tenth of
the run, the mean greedy return, the leaves, whether the failure latch closed, the CPU seconds, and
the steps per epoch over the last tenth.
``AS_OF`` (optional) starts from ``agent.general_as_of(AS_OF)`` instead of today's preset;
``PRESET`` (optional, default ``general``) names another preset (its exploration too).
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
from protocol import greedy_episodes, tenths  # this folder

from agent import adapt_env, general_as_of, preset
from agent.tree_ensemble import tree_agent_class

OVERRIDES = json.loads(os.environ.get("OVERRIDES", "{}"))
AS_OF = os.environ.get("AS_OF")
PRESET = os.environ.get("PRESET", "general")


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, episodes, out = argv[1], int(argv[2]), Path(argv[3])
    general = preset(PRESET)
    base = general.config if AS_OF is None else general_as_of(int(AS_OF))
    config = dataclasses.replace(base, **OVERRIDES)
    for seed in map(int, argv[4:]):
        env = adapt_env(gym.make(task))
        agent = tree_agent_class(config)(
            env.observation_space, env.action_space, general.make_exploration(), seed, config
        )
        start = time.process_time()
        history = agent.learn(env, episodes, reset_seed=seed)
        cpu = round(time.process_time() - start, 1)
        curve = tenths(history, episodes)
        returns, _ = greedy_episodes(env, agent.predict, seed)
        row = {"task": task, "seed": seed, "preset": PRESET, "as_of": AS_OF, "cpu": cpu}
        row["overrides"] = OVERRIDES
        row["leaves"] = agent.n_leaves
        row["latched"] = bool(getattr(agent, "failure_discount", False))
        row["curve"] = curve
        late = history[-max(1, episodes // 10) :]
        row["steps_per_epoch"] = round(
            sum(h.steps for h in late) / max(1, sum(h.epochs for h in late)), 2
        )
        row["greedy"] = round(float(np.mean(returns)), 2)
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
