"""Summarise part 17's held-out frame-stack runs (``runs.jsonl`` beside this file): per task
and arm, the greedy return of each seed, the mean, and the runs at or above a line::

    python docs/results/issue9_part17_heldout_stacked/summary.py
"""

from __future__ import annotations

import json
from collections import defaultdict
from pathlib import Path

LINES = {"CartPole-v1": 475.0, "Pendulum-v1": -150.0}
"""Each task's solved line (Gymnasium's CartPole threshold; Pendulum as in other_tasks.toml)."""

if __name__ == "__main__":
    rows: dict[tuple[str, str], dict[int, dict]] = defaultdict(dict)
    for line in (Path(__file__).with_name("runs.jsonl")).read_text().splitlines():
        record = json.loads(line)
        arm = record["label"].split("-", 1)[1]
        rows[(record["task"], arm)][record["seed"]] = record
    for (task, arm), by_seed in sorted(rows.items()):
        greedy = [by_seed[s]["greedy"] for s in sorted(by_seed)]
        solved = sum(g >= LINES[task] for g in greedy)
        cpu = sum(by_seed[s]["cpu"] for s in by_seed)
        leaves = [by_seed[s]["leaves"] for s in sorted(by_seed)]
        print(
            f"{task} {arm}: seeds {sorted(by_seed)}; greedy {greedy}; mean "
            f"{sum(greedy) / len(greedy):.1f}; {solved} of {len(greedy)} at {LINES[task]:g}; "
            f"leaves {leaves}; {cpu:.0f} CPU-s"
        )
    for task in sorted({t for t, _ in rows}):
        new, old = rows.get((task, "part17"), {}), rows.get((task, "part16"), {})
        both = sorted(set(new) & set(old))
        wins = sum(new[s]["greedy"] > old[s]["greedy"] for s in both)
        ties = sum(new[s]["greedy"] == old[s]["greedy"] for s in both)
        print(f"{task}: part 17 higher on {wins} of {len(both)} seeds, equal on {ties}")
