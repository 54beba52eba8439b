"""Part 35, round 3's gate for `split_min_samples` 50 (decision.md), read from the raw lines:
MountainCar seeds 10-49 and CartPole seeds 0-9 against part 30's `r2_mc.jsonl` and
`r2_cp.jsonl` (today's preset), the 17 dev mazes x agent seeds 10-11 against part 33's
`r1_mazes_cut0.jsonl` (today's preset), with CPU seconds of training beside each.

    python gate.py > gate.txt
"""

import json
import math
from pathlib import Path

HERE = Path(__file__).resolve().parent
RESULTS = HERE.parent


def lines(path):
    return [json.loads(line) for line in path.open()]


def classic(name, new_file, base_file, threshold, sign):
    new = {r["seed"]: r for r in lines(HERE / new_file)}
    base = {r["seed"]: r for r in lines(RESULTS / "issue9_part30_dev" / base_file)}
    seeds = sorted(new)
    b = [base[s]["sel"] for s in seeds]
    n = [new[s]["mean"] for s in seeds]
    solved = lambda xs: sum(sign * x >= sign * threshold for x in xs)  # noqa: E731
    print(f"{name}, seeds {seeds[0]}-{seeds[-1]} ({len(seeds)}):")
    print(f"  today {sum(b) / len(b):.2f} ({solved(b)} solved); N_th 50 {sum(n) / len(n):.2f} "
          f"({solved(n)} solved); higher on {sum(y > x for x, y in zip(b, n))}, lower on "
          f"{sum(y < x for x, y in zip(b, n))}")
    print(f"  CPU {sum(base[s]['cpu'] for s in seeds):.0f} s -> "
          f"{sum(new[s]['cpu'] for s in seeds):.0f} s")


def mazes():
    base = {(r["task"], r["seed"]): r for r in lines(RESULTS / "issue9_part33_dev" / "r1_mazes_cut0.jsonl")}
    new = {(r["task"], r["seed"]): r for r in lines(HERE / "r3_mazes.jsonl")}
    leaves = {(r["task"], r["seed"]): r["leaves"] for r in lines(HERE / "r3_mazes.leaves.jsonl")}
    keys = sorted(new)
    geo = lambda rows, f: math.exp(sum(math.log(r[f]) for r in rows) / len(rows))  # noqa: E731
    b = [base[k] for k in keys]
    n = [new[k] for k in keys]
    print(f"dev mazes ({len(keys)} runs):")
    for f in ("sel", "final"):
        print(f"  {f}: geometric mean {geo(b, f):.3f}x -> {geo(n, f):.3f}x "
              f"({100 * (geo(n, f) / geo(b, f) - 1):+.1f} %); better on "
              f"{sum(y[f] < x[f] for x, y in zip(b, n))}, worse on {sum(y[f] > x[f] for x, y in zip(b, n))}")
    print(f"  capped greedy episodes {sum(r['sel_capped'] for r in b)} -> {sum(r['sel_capped'] for r in n)}; "
          f"capped training episodes from 300 on {sum(r['late_capped'] for r in b)} -> {sum(r['late_capped'] for r in n)}")
    conv = lambda rows: sum(r["converged"] is not None for r in rows)  # noqa: E731
    late = [max(r["converged"] for r in rows if r["converged"] is not None) for rows in (b, n)]
    print(f"  converged {conv(b)} -> {conv(n)} of {len(keys)}, the latest at {late[0]} -> {late[1]}; "
          f"converged later on {sum((y['converged'] or 10**9) > (x['converged'] or 10**9) for x, y in zip(b, n))}, "
          f"sooner on {sum((y['converged'] or 10**9) < (x['converged'] or 10**9) for x, y in zip(b, n))}")
    print(f"  leaves (N_th 50) {min(leaves.values())}-{max(leaves.values())}, the cap 16,384")
    print(f"  CPU {sum(r['cpu'] for r in b):.0f} s -> {sum(r['cpu'] for r in n):.0f} s")
    for k in keys:
        print(f"    {k[0]} {k[1]}: greedy {base[k]['sel']:.3f} -> {new[k]['sel']:.3f}, "
              f"final {base[k]['final']:.3f} -> {new[k]['final']:.3f}")


classic("MountainCar-v0", "r3_mc.jsonl", "r2_mc.jsonl", -110, 1)
classic("CartPole-v1", "r3_cp.jsonl", "r2_cp.jsonl", 475, 1)
mazes()
