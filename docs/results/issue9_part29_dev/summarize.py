"""Part 29's dev gate for round 7 (``tie_selection.py``, ``SELECT_FRACTION=0.5``) against
today's preset (part 27's ``str1`` rows, the same seeds and protocol).

    python summarize.py
"""

from __future__ import annotations

import json
import math
from pathlib import Path

HERE = Path(__file__).resolve().parent
PART27 = HERE.parent / "issue9_part27_dev"


def rows(path: Path) -> list[dict]:
    return [json.loads(line) for line in path.open()] if path.exists() else []


def str1(name: str, key: str) -> dict:
    return {(r.get(key), r["seed"]): r["greedy"] for r in rows(PART27 / name) if r["variant"] == "str1"}


def classic(task: str, mine: str, base: str, target: float) -> None:
    ours = rows(HERE / mine)
    ref = str1(base, "task")
    pairs = [(r, ref[(task, r["seed"])]) for r in ours if (task, r["seed"]) in ref]
    if not pairs:
        return
    n = len(pairs)
    for arm in ("z1", "z2", "sel"):
        mean = sum(r[arm] for r, _ in pairs) / n
        hit = sum(r[arm] >= target for r, _ in pairs)
        higher = sum(r[arm] > b for r, b in pairs)
        lower = sum(r[arm] < b for r, b in pairs)
        print(f"{task} {arm}: {n} seeds, mean {mean:.2f}, at target {hit}, higher {higher}, lower {lower}")
    base_mean = sum(b for _, b in pairs) / n
    print(f"{task} str1 on the same seeds: mean {base_mean:.2f}, at target {sum(b >= target for _, b in pairs)}")
    print(f"{task} chose z 2 on {sum(r['chosen'] == 2.0 for r, _ in pairs)} of {n}")


def mazes() -> None:
    ours = rows(HERE / "r7_maze.jsonl")
    ref = str1("ts_maze.jsonl", "maze")
    pairs = [(r, ref[(r["task"][len("maze:") :], r["seed"])]) for r in ours]
    if not pairs:
        return
    n = len(pairs)
    base = math.exp(sum(math.log(b) for _, b in pairs) / n)
    print(f"mazes: {n} runs; str1 geometric mean greedy / optimum {base:.3f}")
    for arm in ("z1", "z2", "sel"):
        geo = math.exp(sum(math.log(r[arm]) for r, _ in pairs) / n)
        capped = sum(r[arm + "_capped"] > 0 for r, _ in pairs)
        better = sum(r[arm] < b for r, b in pairs)
        worse = sum(r[arm] > b for r, b in pairs)
        print(f"mazes {arm}: geometric mean {geo:.3f} ({geo / base:.3f} of str1's), runs with a capped episode {capped}, better {better}, worse {worse}")
    print(f"mazes chose z 2 on {sum(r['chosen'] == 2.0 for r, _ in pairs)} of {n}")
    for r, b in pairs:
        print(f"   {r['task'][5:]} {r['seed']}: str1 {b}, z1 {r['z1']}, z2 {r['z2']}, sel {r['sel']} (chose {r['chosen']})")


if __name__ == "__main__":
    classic("Acrobot-v1", "r7_ac.jsonl", "ts_ac.jsonl", -100.0)
    classic("MountainCar-v0", "r7_mc.jsonl", "ts_mc.jsonl", -110.0)
    classic("CartPole-v1", "r7_cp.jsonl", "ts_cp.jsonl", 475.0)
    mazes()
