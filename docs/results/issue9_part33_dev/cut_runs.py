"""Part 33's dev runs: the general preset (part 32's) with or without
``TreeConfig.collision_splits_collided_only`` (``CUT=1`` or ``CUT=0``), through part 32's
``forest_search.py`` (forests; 600 episodes, greedy over 10 episodes) or part 31's
``entry_runs.py`` (the maze rows: final, convergence, late capped episodes, greedy)::

    CUT=0|1|2 python cut_runs.py forests OUT AGENT_SEED LAYOUT [LAYOUT ...]
    CUT=0|1|2 python cut_runs.py mazes maze:LAYOUT OUT SEED [SEED ...]

``CUT=2`` (round 2's prototype): the cut only where at least two stored epochs collided.
"""

from __future__ import annotations

import dataclasses
import os
import sys
from pathlib import Path

import agent.tree_agent as tree_agent
from agent import preset
from agent.collision_split import choose_collided_only_split

HERE = Path(__file__).resolve().parent
CUT = os.environ["CUT"] in ("1", "2")
MIN_COLLIDED = 2 if os.environ["CUT"] == "2" else 1


def collided_at_least(firsts, collided, low, high, min_width):
    """The collided-only cut where at least ``MIN_COLLIDED`` stored epochs collided."""
    if len(collided) < MIN_COLLIDED:
        return None
    return choose_collided_only_split(firsts, collided, low, high, min_width)


def general():
    base = preset("general")
    return dataclasses.replace(
        base, config=dataclasses.replace(base.config, collision_splits_collided_only=CUT)
    )


def make_agent(env, seed: int):
    return general().agent(env.observation_space, env.action_space, seed)


if __name__ == "__main__":
    tree_agent.choose_collided_only_split = collided_at_least
    kind, rest = sys.argv[1], sys.argv[2:]
    if kind == "forests":
        sys.path.insert(0, str(HERE.parent / "issue9_part32_dev"))
        import forest_search

        forest_search.preset = lambda name: general()
        forest_search.main(["forest_search.py", *rest])
    else:
        sys.path.insert(0, str(HERE.parent / "issue9_part31_dev"))
        import entry_runs

        entry_runs.ENTRY = CUT  # the row's "entry" field records the arm
        entry_runs.make_agent = make_agent
        entry_runs.main(["entry_runs.py", *rest])
