"""Summaries of part 27's dev probe (``tie_strata.py``; round 1 ``ts_*``, round 2 ``tf_*``): each
variant per task (mean greedy
return, runs at the target, runs higher / lower than part 25's choice ``p25``) and per maze run
(part 26's ``mazes`` summary).

    python summarize.py
"""

from __future__ import annotations

import json
import statistics
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "issue9_part26_dev"))
from summarize import TARGET, mazes  # noqa: E402


def classic(path: Path) -> None:
    rows = [json.loads(line) for line in path.open()]
    task = rows[0]["task"]
    by: dict[str, dict[int, float]] = {}
    for r in rows:
        by.setdefault(r["variant"], {})[r["seed"]] = r["greedy"]
    base = by["p25"]
    for variant, runs in by.items():
        seeds = sorted(set(runs) & set(base))
        higher = sum(runs[s] > base[s] for s in seeds)
        lower = sum(runs[s] < base[s] for s in seeds)
        print(
            f"{task} {variant}: {len(seeds)} seeds, mean {statistics.mean(runs[s] for s in seeds):.2f}, "
            f"at target {sum(runs[s] >= TARGET[task] for s in seeds)}; vs p25 higher {higher}, lower {lower}"
        )


if __name__ == "__main__":
    for round_ in ("ts", "tf"):  # round 1, round 2 (the leaf's fallback)
        for name in ("mc", "ac", "cp"):
            if (HERE / f"{round_}_{name}.jsonl").exists():
                classic(HERE / f"{round_}_{name}.jsonl")
        if (HERE / f"{round_}_maze.jsonl").exists():
            mazes(HERE / f"{round_}_maze.jsonl")
