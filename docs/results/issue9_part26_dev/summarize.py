"""Summaries of part 26's dev probes: ``tie_ancestor.py``'s variants per task (mean greedy return,
runs at the target, runs higher / lower than part 25's choice ``p25``) and ``longer_runs.py``'s
Acrobot checkpoints.

    python summarize.py
"""

from __future__ import annotations

import json
import math
import statistics
from pathlib import Path

HERE = Path(__file__).resolve().parent
TARGET = {"MountainCar-v0": -110.0, "Acrobot-v1": -100.0, "CartPole-v1": 475.0}


def main() -> None:
    for name in ("ta_mc", "ta_ac", "ta_cp", "tb_mc", "tb_ac"):
        path = HERE / f"{name}.jsonl"
        if path.exists():
            classic(path)
    for path in (HERE / "ta_maze.jsonl", HERE / "tb_maze.jsonl"):
        if path.exists():
            mazes(path)
    acrobot_longer()


def classic(path: Path) -> None:
    """Each variant of one task's file: mean greedy return, runs at the target, and runs higher
    / lower than ``p25`` (part 27's summary reuses it)."""
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


def mazes(path: Path) -> None:
    """Greedy steps over the optimum per variant, against ``p25``, and per run."""
    rows = [json.loads(line) for line in path.open()]
    by: dict[str, dict] = {}
    for r in rows:
        by.setdefault(r["variant"], {})[(r["maze"], r["seed"])] = (r["greedy"], r["capped"])
    runs = sorted(set.intersection(*(set(v) for v in by.values())))
    base = by["p25"]
    for variant, got in by.items():
        log = statistics.mean(math.log(got[k][0]) for k in runs)
        better = sum(got[k][0] < base[k][0] for k in runs)
        worse = sum(got[k][0] > base[k][0] for k in runs)
        print(
            f"mazes ({path.stem}) {variant}: {len(runs)} runs, greedy / optimum {math.exp(log):.3f} "
            f"(geometric mean), runs with a capped episode {sum(got[k][1] > 0 for k in runs)}; "
            f"vs p25 better {better}, worse {worse}"
        )
    for k in runs:
        print("  ", k[0], k[1], {v: got[k][0] for v, got in by.items()})


def acrobot_longer() -> None:
    """``longer_runs.py``'s checkpoints."""
    path = HERE / "acrobot_longer.jsonl"
    if path.exists():
        rows = [json.loads(line) for line in path.open()]
        for episodes in sorted({r["episodes"] for r in rows}):
            at = [r for r in rows if r["episodes"] == episodes]
            print(
                f"Acrobot after {episodes} episodes: mean {statistics.mean(r['greedy'] for r in at):.1f} "
                f"over {len(at)} seeds, best {max(r['greedy'] for r in at)}, "
                f"leaves {min(r['leaves'] for r in at)}-{max(r['leaves'] for r in at)}"
            )


if __name__ == "__main__":
    main()
