"""Part 35's dev maze runs: today's general preset with TreeConfig fields overridden, through
part 31's ``entry_runs.py`` (12 blocks of 50 episodes, 10 greedy episodes; the maze rows'
final, convergence episode and late capped episodes)::

    OVERRIDES='{"split_min_samples": 50}' python maze_runs.py maze:LAYOUT OUT SEED [SEED ...]

``OVERRIDES='{}'`` is today's preset, which reproduces part 33's ``r1_mazes_cut0.jsonl``. Each
run's leaf count goes to ``OUT`` with ``.leaves`` before its suffix (one line a run).
"""

from __future__ import annotations

import dataclasses
import json
import os
import sys
from pathlib import Path

from agent import preset
from agent.tree_ensemble import tree_agent_class

OVERRIDES = json.loads(os.environ.get("OVERRIDES", "{}"))
HERE = Path(__file__).resolve().parent


MADE: list = []


def make_agent(env, seed: int):
    general = preset("general")
    config = dataclasses.replace(general.config, **OVERRIDES)
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, general.make_exploration(), seed, config
    )
    MADE.append(agent)
    return agent


if __name__ == "__main__":
    sys.path.insert(0, str(HERE.parent / "issue9_part31_dev"))
    import entry_runs

    entry_runs.ENTRY = bool(OVERRIDES)  # the row's "entry" field: True for the overridden arm
    entry_runs.make_agent = make_agent
    task, out, seeds = sys.argv[1], Path(sys.argv[2]), sys.argv[3:]
    for seed in seeds:
        entry_runs.main(["entry_runs.py", task, str(out), seed])
        row = {"task": task, "seed": int(seed), "leaves": MADE[-1].n_leaves}
        with out.with_suffix(".leaves.jsonl").open("a") as f:
            f.write(json.dumps(row) + "\n")
