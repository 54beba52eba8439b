"""Summaries of part 27's dev probe (``tie_strata.py``; round 1 ``ts_*``, round 2 ``tf_*``), with
part 26's functions: each variant per task (mean greedy return, runs at the target, runs higher /
lower than part 25's choice ``p25``) and per maze run.

    python summarize.py
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "issue9_part26_dev"))
from summarize import classic, mazes  # noqa: E402

if __name__ == "__main__":
    for round_ in ("ts", "tf"):  # round 1, round 2 (the leaf's fallback)
        for name in ("mc", "ac", "cp"):
            if (HERE / f"{round_}_{name}.jsonl").exists():
                classic(HERE / f"{round_}_{name}.jsonl")
        if (HERE / f"{round_}_maze.jsonl").exists():
            mazes(HERE / f"{round_}_maze.jsonl")
