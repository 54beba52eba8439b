"""Part 14 dev probe (not an agent option): collision splits whose children are at least
``FACTOR`` times the smallest leaf wide, against the door-14 rooms' loss.

The door's free column (4 units on a 300-unit maze) is narrower than a step (5 units), and the
committed rule may cut leaves down to the smallest leaf (1/256 of the box, 1.2 units) beside
it. This probe patches ``agent.tree_agent.choose_collision_split`` so that both children must
be at least ``FACTOR`` x that width, runs part 8's maze driver (600 episodes) with the general
preset, and appends to ``wide_cuts.jsonl`` (label ``wideF``)::

    PYTHONPATH=. python docs/results/issue9_part14_dev/wide_cuts.py "rooms:seed=2,door=14,loops=0" 0 4
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import agent.tree_agent as tree_agent

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "issue9_hold_terminals_dev"))
import curves  # noqa: E402  (part 8's maze driver, beside this folder)


def patch(factor: float) -> None:
    choose = tree_agent.choose_collision_split

    def wider(firsts: Any, collided: Any, low: Any, high: Any, min_width: Any) -> Any:
        return choose(firsts, collided, low, high, min_width * factor)

    tree_agent.choose_collision_split = wider  # type: ignore[assignment]


if __name__ == "__main__":
    maze, seed, factor = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
    patch(factor)
    curves.run(maze, seed, f"wide{factor:g}", {}, HERE / "wide_cuts.jsonl")
