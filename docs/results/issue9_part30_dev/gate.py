"""Part 30's gate (decision.md) read from the raw lines: each case against part 27's str1 rows.

    python gate.py   (from this folder; writes gate.txt)
"""

from __future__ import annotations

import json
import math
import statistics
from pathlib import Path

HERE = Path(__file__).resolve().parent
STR1 = HERE.parent / "issue9_part27_dev"
ROUND8 = HERE.parent / "issue9_part29_dev"


def rows(path: Path) -> list[dict]:
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


def baseline(name: str, key: str) -> dict:
    return {(r[key], r["seed"]): r["greedy"] for r in rows(STR1 / name) if r["variant"] == "str1"}


def classic(out: list[str], label: str, path: Path, ts: str, target: float, score: str) -> None:
    if not path.exists():
        out.append(f"{label}: not run")
        return
    base = baseline(ts, "task")
    got = sorted(rows(path), key=lambda r: r["seed"])
    pairs = [(r[score], base[(r["task"], r["seed"])]) for r in got]
    new = [a for a, _ in pairs]
    old = [b for _, b in pairs]
    adopted = sum(bool(r.get("adopted", r.get("chosen") == 2.0)) for r in got)
    out.append(
        f"{label}: {len(got)} runs; mean {statistics.mean(new):.2f} (str1 {statistics.mean(old):.2f}); "
        f"at target {sum(a >= target for a in new)} (str1 {sum(b >= target for b in old)}); "
        f"higher {sum(a > b for a, b in pairs)}, lower {sum(a < b for a, b in pairs)}; "
        f"z 2 adopted on {adopted}"
    )
    for r, (a, b) in zip(got, pairs, strict=True):
        out.append(
            f"  seed {r['seed']:>2}: {a:8.2f}  str1 {b:8.2f}  z1 {r['z1']:8.2f}  z2 {r['z2']:8.2f}  "
            f"diff {r['diff']:8.3f} se {r['se']:7.3f}"
        )


def mazes(out: list[str], label: str, paths: list[Path], score: str) -> None:
    got = [r for p in paths if p.exists() for r in rows(p)]
    if not got:
        out.append(f"{label}: not run")
        return
    base = baseline("ts_maze.jsonl", "maze")
    pairs = []
    for r in sorted(got, key=lambda r: (r["task"], r["seed"])):
        maze = r["task"][len("maze:") :]
        pairs.append((maze, r["seed"], r[score], r[score + "_capped"], base[(maze, r["seed"])]))
    geo = math.exp(statistics.mean(math.log(p[2]) for p in pairs))
    geo_old = math.exp(statistics.mean(math.log(p[4]) for p in pairs))
    out.append(
        f"{label}: {len(pairs)} runs; geometric mean {geo:.3f} (str1 {geo_old:.3f}, "
        f"{100 * (geo / geo_old - 1):+.1f} %); capped runs {sum(p[3] > 0 for p in pairs)}"
    )
    for maze, seed, a, capped, b in pairs:
        out.append(f"  {maze:<45} {seed}: {a:6.3f}  str1 {b:6.3f}  capped {capped}")


def main() -> None:
    out = ["# Part 30's gate, read by gate.py", ""]
    out.append("## Part 29's round 8 (tie_selection.py, the last half of training)")
    classic(out, "CartPole 0-9", HERE / "r8_cp.jsonl", "ts_cp.jsonl", 475, "sel")
    mazes(out, "mazes", [ROUND8 / "r8_maze.jsonl", HERE / "r8_maze.jsonl"], "sel")
    for n, every in ((1, 2), (2, 4)):
        out += ["", f"## Round {n}: greedy_tie_trial from episode 300, one episode in {every}"]
        if n == 1:
            out.append("(its maze runs are round 8's above; CartPole stopped after one run)")
        classic(out, "Acrobot 0-9", HERE / f"r{n}_ac.jsonl", "ts_ac.jsonl", -100, "sel")
        if n == 2:
            mazes(out, "mazes", [HERE / "r2_maze.jsonl"], "sel")
        classic(out, "MountainCar 10-49", HERE / f"r{n}_mc.jsonl", "ts_mc.jsonl", -110, "sel")
        classic(out, "CartPole 0-9", HERE / f"r{n}_cp.jsonl", "ts_cp.jsonl", 475, "sel")
    (HERE / "gate.txt").write_text("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
