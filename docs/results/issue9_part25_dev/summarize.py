"""Summarise the part-25 probe files: mean greedy return (classic) or the geometric mean of the
greedy steps / optimum (mazes) per (h, z) variant, over the runs present in every variant.

    python summarize.py FILE [FILE ...]
"""

from __future__ import annotations

import json
import math
import sys
from collections import defaultdict

for name in sys.argv[1:]:
    rows = [json.loads(line) for line in open(name)]
    by = defaultdict(dict)
    for r in rows:
        run = (r.get("task") or r.get("maze"), r["seed"])
        by[(r["h"], r.get("z", 0.0))][run] = r
    common = set.intersection(*(set(v) for v in by.values()))
    base = by[(0.0, 0.0)]
    print(name, len(common), "runs")
    for variant, runs in sorted(by.items()):
        vals = [runs[k]["greedy"] for k in sorted(common)]
        if "maze" in rows[0]:
            gm = math.exp(sum(math.log(v) for v in vals) / len(vals))
            capped = sum(runs[k]["capped"] for k in common)
            worse = sum(runs[k]["greedy"] > base[k]["greedy"] + 1e-9 for k in common)
            better = sum(runs[k]["greedy"] < base[k]["greedy"] - 1e-9 for k in common)
            print(f"  h={variant[0]} z={variant[1]}: geo mean {gm:.3f}, capped {capped}, better {better}, worse {worse}")
        else:
            mean = sum(vals) / len(vals)
            task = rows[0]["task"]
            line = {"MountainCar-v0": -110, "CartPole-v1": 475, "Acrobot-v1": -100}.get(task)
            solved = sum(v >= line for v in vals) if line is not None else None
            better = sum(runs[k]["greedy"] > base[k]["greedy"] + 1e-9 for k in common)
            worse = sum(runs[k]["greedy"] < base[k]["greedy"] - 1e-9 for k in common)
            print(f"  h={variant[0]} z={variant[1]}: mean {mean:.2f}, solved {solved}, better {better}, worse {worse}")
