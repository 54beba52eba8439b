"""Part 32's gates (decision.md) read from the raw lines; writes gate.txt.

Round 1: the general preset with ``greedy_tie_trial_avoid_collided`` (``r1_maze_avoid.jsonl``)
against the same preset without it (part 31's round 3, ``r3_maze_release.jsonl``), both with
today's sweep. The comparison is part 31's (``../issue9_part31_dev/gate.py``).

    python gate.py   (from this folder)
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
PART31 = HERE.parent / "issue9_part31_dev"
sys.path.insert(0, str(PART31))
from gate import mazes  # noqa: E402


def main() -> None:
    out = ["# Part 32's gates, read by gate.py", "", "## Round 1: greedy_tie_trial_avoid_collided"]
    mazes(out, HERE / "r1_maze_avoid.jsonl", "option off", PART31 / "r3_maze_release.jsonl")
    (HERE / "gate.txt").write_text("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
