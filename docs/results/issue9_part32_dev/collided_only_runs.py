"""Part 32, round 4 (a dev prototype, no library change): a collision split also where every
stored epoch of (leaf, a) collided, cutting off the largest part of the leaf that holds none of
their first inputs (decision.md, round 4). Patches ``agent.tree_agent.choose_collision_split``
and runs round 3's ``forest_search.py`` or part 31's ``entry_runs.py`` (``ENTRY=0``, the preset
as it stands, part 32's):

    python collided_only_runs.py forests OUT AGENT_SEED LAYOUT [LAYOUT ...]
    python collided_only_runs.py mazes maze:LAYOUT OUT SEED [SEED ...]
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

import agent.tree_agent as tree_agent
from agent.collision_split import choose_collision_split

HERE = Path(__file__).resolve().parent


def collided_only_cut(firsts, collided, low, high, min_width):
    """A cut that leaves the largest part of the leaf without any collided first input."""
    n = len(collided)
    if n == 0 or int(collided.sum()) != n:
        return None
    best = None
    for dim in range(firsts.shape[1]):
        lo, hi = float(firsts[:, dim].min()), float(firsts[:, dim].max())
        mw = float(min_width[dim])
        for value, empty in ((lo - mw, lo - mw - low[dim]), (hi + mw, high[dim] - hi - mw)):
            if empty < mw or value - low[dim] < mw or high[dim] - value < mw:
                continue
            if best is None or empty > best[2]:
                best = (dim, float(value), float(empty))
    return None if best is None else (best[0], best[1])


def patched(firsts, collided, low, high, min_width):
    choice = choose_collision_split(firsts, collided, low, high, min_width)
    if choice is None:
        choice = collided_only_cut(np.asarray(firsts), np.asarray(collided), low, high, min_width)
    return choice


if __name__ == "__main__":
    tree_agent.choose_collision_split = patched
    kind, rest = sys.argv[1], sys.argv[2:]
    if kind == "forests":
        sys.path.insert(0, str(HERE))
        import forest_search

        forest_search.main(["forest_search.py", *rest])
    else:
        sys.path.insert(0, str(HERE.parent / "issue9_part31_dev"))
        import entry_runs

        entry_runs.ENTRY = False
        entry_runs.main(["entry_runs.py", *rest])
