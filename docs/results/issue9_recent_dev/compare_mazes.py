"""Print the development maze table of issue 9, part 7, from a results folder of
``lambda_recent_dev``: per layout and strategy, the mean steps per episode over the run (AUC),
the mean of the last 100 episodes (final), the episodes that reached the goal, and the leaves at
the end (a run at its leaf cap, ``max_leaves`` in the run's file, is marked)::

    python docs/results/issue9_recent_dev/compare_mazes.py results/lambda_recent_dev
"""

from __future__ import annotations

import csv
import json
import sys
from pathlib import Path


def main(folder: Path) -> None:
    runs = folder / "runs"
    strategies: list[str] = []
    rows: dict[str, dict[str, str]] = {}
    for layout in sorted(p for p in runs.iterdir() if p.is_dir()):
        for path in sorted(layout.glob("*.csv")):
            if path.name.endswith(".eval.csv"):
                continue
            name = path.name.split("__")[0]
            if name not in strategies:
                strategies.append(name)
            with path.open() as f:
                episodes = list(csv.DictReader(f))
            steps = [int(e["steps"]) for e in episodes]
            goals = sum(int(e["success"]) for e in episodes)
            leaves = int(episodes[-1]["leaves"])
            meta = json.loads(path.with_suffix(".json").read_text())
            limit = meta["inputs"]["config"]["agent_config"]["max_leaves"]
            cap = " (cap)" if leaves >= limit else ""
            auc = sum(steps) / len(steps)
            final = sum(steps[-100:]) / len(steps[-100:])
            cell = f"{auc:.0f} / {final:.0f} / {goals} / {leaves}{cap}"
            rows.setdefault(layout.name, {})[name] = cell
    print("AUC / final / goals / leaves")
    print("| layout | " + " | ".join(strategies) + " |")
    print("| --- |" + " --- |" * len(strategies))
    for layout, cells in rows.items():
        print(f"| {layout} | " + " | ".join(cells.get(s, "-") for s in strategies) + " |")


if __name__ == "__main__":
    main(Path(sys.argv[1]))
