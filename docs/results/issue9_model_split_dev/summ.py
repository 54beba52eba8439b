"""Summarise dev JSON lines: per layout AUC / final / convergence episode / leaves per arm, then
per arm the geometric means of AUC and final (both / optimum), the counts of runs with final at
most 1.2x and converged by episode 500, and CPU seconds::

    python summ.py maze.jsonl [more.jsonl ...]
"""

from __future__ import annotations

import collections
import json
import sys
from pathlib import Path

import numpy as np


def main(paths: list[str]) -> None:
    rows = [json.loads(line) for path in paths for line in Path(path).read_text().splitlines()]
    by_case: dict[tuple[str, int], dict[str, dict]] = collections.defaultdict(dict)
    labels: list[str] = []
    for row in rows:
        if row["label"] not in labels:
            labels.append(row["label"])
        by_case[(row["maze"], row["seed"])][row["label"]] = row
    print("layout|seed|" + "|".join(labels))
    per_arm: dict[str, list[dict]] = collections.defaultdict(list)
    for (maze, seed), arms in by_case.items():
        cells = []
        for label in labels:
            row = arms.get(label)
            if row is None:
                cells.append("-")
                continue
            per_arm[label].append(row)
            cells.append(f"{row['auc']:.2f}/{row['final']:.2f}/{row['conv']}/{row['leaves']}")
        print(maze[:32], seed, *cells, sep="|")
    for label in labels:
        arm = per_arm[label]
        auc = np.exp(np.mean(np.log([r["auc"] for r in arm])))
        final = np.exp(np.mean(np.log([r["final"] for r in arm])))
        print(
            f"{label} n {len(arm)} gm auc {auc:.3f} gm final {final:.3f} "
            f"final<=1.2: {sum(r['final'] <= 1.2 for r in arm)} "
            f"conv<=500: {sum((r['conv'] or 9999) <= 500 for r in arm)} "
            f"cpu {sum(r['cpu'] for r in arm):.0f}"
        )


if __name__ == "__main__":
    main(sys.argv[1:])
