"""Part 37: pair a round's Acrobot lines with today's preset's (part 35's round 5, N_th 50).

python pairs.py r2_ac_sweep256.jsonl
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

BASE = Path(__file__).parent.parent / "issue9_part35_dev" / "r5_ac_nth50.jsonl"


def main(path: str) -> None:
    base = {r["seed"]: r for r in map(json.loads, BASE.read_text().splitlines())}
    rows = sorted(map(json.loads, Path(path).read_text().splitlines()), key=lambda r: r["seed"])
    diffs = []
    for r in rows:
        b = base[r["seed"]]
        diffs.append(r["mean"] - b["mean"])
        print(
            f"seed {r['seed']}: {b['mean']:8.2f} -> {r['mean']:8.2f} ({diffs[-1]:+.2f}); "
            f"long {b['long']} -> {r['long']}; cpu {b['cpu']} -> {r['cpu']}"
        )
    n = len(rows)
    print(
        f"{n} pairs: mean change {sum(diffs) / n:+.2f}, higher on {sum(d > 0 for d in diffs)}, "
        f"at -100 {sum(base[r['seed']]['mean'] >= -100 for r in rows)} -> "
        f"{sum(r['mean'] >= -100 for r in rows)}, long "
        f"{sum(base[r['seed']]['long'] for r in rows)} -> {sum(r['long'] for r in rows)}, cpu "
        f"{sum(base[r['seed']]['cpu'] for r in rows):.0f} -> {sum(r['cpu'] for r in rows):.0f}"
    )


if __name__ == "__main__":
    main(sys.argv[1])
