"""Part 31's gates (decision.md) read from the raw lines; writes gate.txt.

Round 1: ``r1_ac.jsonl`` (``greedy_tie_trial_follow``) against part 30's round 2 rows.
Round 2: ``r2_*.jsonl`` (``greedy_tie_trial_on_entry``); the mazes against part 30's arm run
beside it (``r2_maze_part30.jsonl``), classic control against part 30's round 2 rows.
Round 3: part 30's preset with today's sweep (``r3_maze_release.jsonl``) against the same preset
with the old one (``r2_maze_part30.jsonl``).

    python gate.py   (from this folder)
"""

from __future__ import annotations

import json
import math
import statistics
from pathlib import Path

HERE = Path(__file__).resolve().parent
PART30 = HERE.parent / "issue9_part30_dev"


def rows(path: Path) -> list[dict]:
    if not path.exists():
        return []
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


def classic(out: list[str], label: str, new: Path, old: Path, target: float) -> None:
    base = {r["seed"]: r["sel"] for r in rows(old)}
    got = sorted(rows(new), key=lambda r: r["seed"])
    if not got:
        out.append(f"{label}: not run")
        return
    pairs = [(r["sel"], base[r["seed"]]) for r in got]
    a = [p for p, _ in pairs]
    b = [q for _, q in pairs]
    out.append(
        f"{label}: {len(got)} runs; mean {statistics.mean(a):.2f} (part 30 {statistics.mean(b):.2f}); "
        f"at target {sum(x >= target for x in a)} (part 30 {sum(x >= target for x in b)}); "
        f"higher {sum(x > y for x, y in pairs)}, lower {sum(x < y for x, y in pairs)}; "
        f"z 2 adopted on {sum(bool(r['adopted']) for r in got)}"
    )
    for r, (x, y) in zip(got, pairs, strict=True):
        out.append(f"  seed {r['seed']:>2}: {x:8.2f}  part 30 {y:8.2f}  z1 {r['z1']:8.2f}  z2 {r['z2']:8.2f}")


def geo(values: list[float]) -> float:
    return math.exp(statistics.mean(math.log(v) for v in values))


def mazes(
    out: list[str],
    new_file: str | Path = "r2_maze.jsonl",
    ref: str = "part 30",
    old_file: str | Path = "r2_maze_part30.jsonl",
) -> None:
    new = {(r["task"], r["seed"]): r for r in rows(HERE / new_file)}
    old = {(r["task"], r["seed"]): r for r in rows(HERE / old_file)}
    keys = sorted(set(new) & set(old))
    if not keys:
        out.append("mazes: not run")
        return
    out.append(f"mazes: {len(keys)} runs with both arms")
    for label, key in (("greedy / optimum", "sel"), ("training final / optimum", "final")):
        a, b = geo([new[k][key] for k in keys]), geo([old[k][key] for k in keys])
        out.append(f"  {label}: geometric mean {a:.3f} ({ref} {b:.3f}, {100 * (a / b - 1):+.1f} %)")
    for label, key in (("capped greedy runs", "sel_capped"), ("capped training episodes from 300", "late_capped")):
        out.append(
            f"  {label}: {sum(new[k][key] > 0 if 'greedy' in label else new[k][key] for k in keys)} "
            f"({ref} {sum(old[k][key] > 0 if 'greedy' in label else old[k][key] for k in keys)})"
        )
    conv = sum(new[k]["converged"] is not None for k in keys)
    conv_old = sum(old[k]["converged"] is not None for k in keys)
    out.append(f"  converged runs: {conv} ({ref} {conv_old})")
    same = sum(new[k]["final"] == old[k]["final"] and new[k]["sel"] == old[k]["sel"] for k in keys)
    out.append(f"  runs with the same final and greedy score in both arms: {same}")
    for k in keys:
        n, o = new[k], old[k]
        out.append(
            f"  {k[0][5:]:<45} {k[1]}: greedy {n['sel']:6.3f} / {o['sel']:6.3f}  final {n['final']:6.3f} / "
            f"{o['final']:6.3f}  converged {n['converged']} / {o['converged']}  late capped "
            f"{n['late_capped']} / {o['late_capped']}  adopted {n['adopted']} / {o['adopted']}"
        )


def main() -> None:
    out = ["# Part 31's gates, read by gate.py", "", "## Round 1: greedy_tie_trial_follow"]
    classic(out, "Acrobot", HERE / "r1_ac.jsonl", PART30 / "r2_ac.jsonl", -100)
    out += ["", "## Round 2: greedy_tie_trial_on_entry (candidate / part 30)"]
    mazes(out)
    classic(out, "Acrobot 0-9", HERE / "r2_ac.jsonl", PART30 / "r2_ac.jsonl", -100)
    classic(out, "MountainCar 10-49", HERE / "r2_mc.jsonl", PART30 / "r2_mc.jsonl", -110)
    classic(out, "CartPole 0-9", HERE / "r2_cp.jsonl", PART30 / "r2_cp.jsonl", 475)
    out += ["", "## Round 3: part 30's preset, today's sweep / the old sweep (a measurement)"]
    mazes(out, "r3_maze_release.jsonl", "old sweep")
    (HERE / "gate.txt").write_text("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
