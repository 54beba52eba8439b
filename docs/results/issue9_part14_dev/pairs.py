"""Pair each dev layout and agent seed's preset line with its collision-split line and print
both, then the geometric means of final and AUC (both / optimum) and the runs with final at
most 1.2x. Preset labels: ``h999`` (part 11's dev lines) and ``preset``; collision-split
labels: ``ccut`` (part 13's prototype) and ``csplit`` (the committed option)::

    python docs/results/issue9_part14_dev/pairs.py \\
        docs/results/issue9_horizon_dev/maze.jsonl \\
        docs/results/issue9_part13_dev/maze_collision.jsonl \\
        docs/results/issue9_part14_dev/maze.jsonl \\
        docs/results/issue9_part14_dev/maze_collision_seeds.jsonl \\
        docs/results/issue9_part14_dev/maze_doors.jsonl
"""

from __future__ import annotations

import collections
import json
import math
import sys
from pathlib import Path

PRESET = {"h999", "preset"}
CUTS = {"ccut", "csplit"}


def geometric_mean(values: list[float]) -> float:
    return math.exp(sum(math.log(v) for v in values) / len(values))


def main(paths: list[str]) -> None:
    pairs: dict[tuple[str, int], dict[str, dict]] = collections.defaultdict(dict)
    for path in paths:
        for line in Path(path).read_text().splitlines():
            row = json.loads(line)
            side = "a" if row["label"] in PRESET else "b" if row["label"] in CUTS else None
            if side is not None:
                pairs[(row["maze"], row["seed"])][side] = row
    finals: dict[str, list[float]] = {"a": [], "b": []}
    aucs: dict[str, list[float]] = {"a": [], "b": []}
    for (maze, seed), both in sorted(pairs.items()):
        if len(both) < 2:
            continue
        a, b = both["a"], both["b"]
        for side, row in both.items():
            finals[side].append(row["final"])
            aucs[side].append(row["auc"])
        print(
            f"{maze[:42]:43s} {seed} final {a['final']:.3f} -> {b['final']:.3f}  "
            f"auc {a['auc']:.2f} -> {b['auc']:.2f}  conv {a['conv']} -> {b['conv']}  "
            f"leaves {a['leaves']} -> {b['leaves']}"
        )
    print(
        f"{len(finals['a'])} pairs; geometric mean final {geometric_mean(finals['a']):.3f} -> "
        f"{geometric_mean(finals['b']):.3f}; AUC {geometric_mean(aucs['a']):.3f} -> "
        f"{geometric_mean(aucs['b']):.3f}; final <= 1.2x: "
        f"{sum(v <= 1.2 for v in finals['a'])} -> {sum(v <= 1.2 for v in finals['b'])}"
    )


if __name__ == "__main__":
    main(sys.argv[1:])
