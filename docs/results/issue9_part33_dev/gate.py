"""Part 33's round 1 gate (decision.md) read from the raw lines; writes gate.txt.

    python gate.py   (from this folder)
"""

from __future__ import annotations

import json
import math
from pathlib import Path

HERE = Path(__file__).resolve().parent


def load(name: str, key: str) -> dict:
    rows = {}
    for line in (HERE / name).read_text().splitlines():
        row = json.loads(line)
        rows[(row[key], row["seed"])] = row
    return rows


def gmean(values) -> float:
    values = list(values)
    return math.exp(sum(math.log(v) for v in values) / len(values))


def check(out: list[str], label: str, ok: bool, text: str) -> bool:
    out.append(f"- {label} {'PASS' if ok else 'FAIL'}: {text}")
    return ok


def main() -> None:
    out = ["# Part 33's round 1 gate, read by gate.py", ""]
    f0, f1 = load("r1_forests_cut0.jsonl", "layout"), load("r1_forests_cut1.jsonl", "layout")
    m0, m1 = load("r1_mazes_cut0.jsonl", "task"), load("r1_mazes_cut1.jsonl", "task")
    fk, mk = sorted(set(f0) & set(f1)), sorted(set(m0) & set(m1))
    out.append(f"{len(fk)} paired forest runs, {len(mk)} paired maze runs")
    out.append("")
    out.append("| forest run | final off | final cut | greedy off | greedy cut | leaves off | leaves cut |")
    out.append("| --- | --- | --- | --- | --- | --- | --- |")
    for k in fk:
        a, b = f0[k], f1[k]
        out.append(
            f"| {k[0]} s{k[1]} | {a['final']} | {b['final']} | {a['greedy']} | {b['greedy']} "
            f"| {a['leaves']} | {b['leaves']} |"
        )
    out.append("")
    g0, g1 = gmean(f0[k]["greedy"] for k in fk), gmean(f1[k]["greedy"] for k in fk)
    t0, t1 = gmean(f0[k]["final"] for k in fk), gmean(f1[k]["final"] for k in fk)
    h0 = sum(f0[k]["final"] > 1.4 for k in fk)
    h1 = sum(f1[k]["final"] > 1.4 for k in fk)
    ok = [
        check(out, "A1", g1 <= 0.98 * g0, f"forest greedy {g0:.3f}x -> {g1:.3f}x ({g1 / g0 - 1:+.1%})"),
        check(out, "A2", t1 < t0, f"forest final {t0:.3f}x -> {t1:.3f}x ({t1 / t0 - 1:+.1%})"),
        check(out, "A3", h1 <= h0, f"forest runs above 1.4x {h0} -> {h1}"),
    ]
    c0 = sum(m0[k]["converged"] is not None for k in mk)
    c1 = sum(m1[k]["converged"] is not None for k in mk)
    mf0, mf1 = gmean(m0[k]["final"] for k in mk), gmean(m1[k]["final"] for k in mk)
    l0 = sum(m0[k]["late_capped"] for k in mk)
    l1 = sum(m1[k]["late_capped"] for k in mk)
    ok += [
        check(out, "B1", c1 >= c0, f"maze runs converged {c0} -> {c1} of {len(mk)}"),
        check(out, "B2", mf1 <= 1.01 * mf0, f"maze final {mf0:.3f}x -> {mf1:.3f}x ({mf1 / mf0 - 1:+.1%})"),
        check(out, "B3", l1 <= l0, f"maze capped episodes from 300 on {l0} -> {l1}"),
    ]
    leaves = sum(f1[k]["leaves"] for k in fk) / sum(f0[k]["leaves"] for k in fk)
    fcpu = sum(f1[k]["cpu"] for k in fk) / sum(f0[k]["cpu"] for k in fk)
    mcpu = sum(m1[k]["cpu"] for k in mk) / sum(m0[k]["cpu"] for k in mk)
    ok.append(
        check(
            out,
            "C",
            leaves <= 2.5 and fcpu <= 1.75 and mcpu <= 1.5,
            f"forest leaves {leaves:.2f}x, forest CPU {fcpu:.2f}x, maze CPU {mcpu:.2f}x",
        )
    )
    mg0 = gmean(m0[k]["sel"] for k in mk)
    mg1 = gmean(m1[k]["sel"] for k in mk)
    out.append(f"- (not gated) maze greedy {mg0:.3f}x -> {mg1:.3f}x")
    worse = [(k, m0[k]["final"], m1[k]["final"]) for k in mk if m1[k]["final"] > m0[k]["final"] + 0.05]
    out.append(f"- (not gated) maze runs worse by more than 0.05: {worse}")
    better = [(k, m0[k]["final"], m1[k]["final"]) for k in mk if m1[k]["final"] < m0[k]["final"] - 0.05]
    out.append(f"- (not gated) maze runs better by more than 0.05: {better}")
    out += ["", f"**{'PASS' if all(ok) else 'FAIL'}**"]
    (HERE / "gate.txt").write_text("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
