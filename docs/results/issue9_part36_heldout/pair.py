"""Part 36's held-out rows: today's preset (N_th 50, ``split_min_samples``) against part 35's
(``general_as_of(35)``, spelt out as ``general-part35``), both arms trained on the same fresh
experiment seeds. A pair is two runs with the same run seed (the same agent seed and reset
seeds); every run changes, since the split test's pair count shapes the tree from the start.

Classic control (36101): per task, each arm's runs at the target, mean greedy return (20 greedy
episodes a run), the paired change with a bootstrap 95 % interval and a sign test. Mazes (the
suite's test split, 36102): per layout, each arm's final (last 100 training episodes) over the
optimum, area under the curve over the optimum, converged runs and their median episode, and
greedy steps, with the best uniform grid's area; the latest convergence; the geometric means.
Paper (36103, today's preset only) is read from its own report.md.

    python pair.py            (from anywhere; writes pair.txt beside this file)
"""

from __future__ import annotations

import csv
import importlib.util
import math
from collections import defaultdict
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
RESULTS = HERE.parent


def _load(name: str, path: Path):  # type: ignore[no-untyped-def]
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None
    assert spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_PART30 = _load("part30_pair", RESULTS / "issue9_part30_heldout_rows" / "pair.py")
wilson, sign_p, TARGET = _PART30.wilson, _PART30.sign_p, _PART30.TARGET
greedy_means = _PART30.greedy_means
CLASSIC = RESULTS / "issue9_part36_heldout_classic_seed36101"
MAZES = RESULTS / "issue9_part36_heldout_mazes_seed36102"
ARMS = ("general-part35", "general")
LABELS = ("part 35", "part 36")
_PART30.MAZES = MAZES  # its latest_convergence reads this folder


def classic(lines: list[str]) -> None:
    if not (CLASSIC / "evaluation.csv").exists():
        lines.append("classic 36101: not run")
        return
    means = greedy_means(CLASSIC)
    for task in TARGET:
        old, new = means.get((task, ARMS[0]), {}), means.get((task, ARMS[1]), {})
        runs = sorted(set(old) & set(new))
        if len(runs) < 10:
            lines.append(f"36101 {task}: {len(runs)} pairs finished")
            continue
        a, b = [old[r] for r in runs], [new[r] for r in runs]
        target, n = TARGET[task], len(a)
        diffs = np.asarray(b) - np.asarray(a)
        boot = np.random.default_rng(0).choice(diffs, size=(10_000, n)).mean(axis=1)
        low, high = np.percentile(boot, [2.5, 97.5])
        higher, lower = int((diffs > 0).sum()), int((diffs < 0).sum())
        hits = [sum(v >= target for v in arm) for arm in (a, b)]
        lines.append(
            f"36101 {task}: {LABELS[0]} {hits[0]} of {n} at {target:g}, mean {np.mean(a):.2f}; "
            f"{LABELS[1]} {hits[1]} of {n}, mean {np.mean(b):.2f}; change {diffs.mean():+.2f} "
            f"[{low:+.2f}, {high:+.2f}], higher {higher}, lower {lower}, sign test p = "
            f"{sign_p(higher, lower):.2g}"
        )
        lines.append(f"  {LABELS[0]}: " + ", ".join(f"{v:.2f}" for v in a))
        lines.append(f"  {LABELS[1]}: " + ", ".join(f"{v:.2f}" for v in b))


def mazes(lines: list[str]) -> None:
    if not (MAZES / "summary.csv").exists():
        lines.append("mazes 36102: not run")
        return
    rows: dict[tuple[str, str], dict[str, str]] = {}
    with (MAZES / "summary.csv").open() as f:
        for row in csv.DictReader(f):
            rows[(row["task"], row["strategy"])] = row
    logs: dict[str, dict[str, list[float]]] = {arm: defaultdict(list) for arm in ARMS}
    lines.append(
        "layout: final / optimum, AUC / optimum, converged (median episode), greedy steps / "
        f"optimum; {LABELS[0]} -> {LABELS[1]}"
    )
    for layout in sorted({task for task, _ in rows}):
        cells = []
        for arm in ARMS:
            r = rows.get((layout, arm))
            if r is None:
                cells.append("not run")
                continue
            optimum = float(r["optimal_steps"])
            final, auc = float(r["final_to_optimal_mean"]), float(r["auc_to_optimal_mean"])
            greedy = float(r["greedy_steps_mean"]) / optimum
            for key, value in (("final", final), ("auc", auc), ("greedy", greedy)):
                logs[arm][key].append(math.log(value))
            cells.append(
                f"{final:.3f}, {auc:.3f}, {r['converged_runs']}/{r['runs']} "
                f"({r['median_convergence_episode']}), {greedy:.3f}"
            )
        grids = [
            float(r["auc_to_optimal_mean"])
            for (task, arm), r in rows.items()
            if task == layout and arm.startswith("grid-")
        ]
        best = f"; best grid's AUC {min(grids):.3f}" if grids else ""
        lines.append(f"  {layout}: {cells[0]} -> {cells[1]}{best}")
    latest = {arm: _PART30.latest_convergence(arm) for arm in ARMS}
    lines.append(
        "latest run convergence (episode; window 50, tolerance 0.1, the report's rule): "
        + "; ".join(f"{arm} {latest[arm]}" for arm in ARMS)
    )
    for key in ("final", "auc", "greedy"):
        geo = [math.exp(float(np.mean(logs[arm][key]))) for arm in ARMS if logs[arm][key]]
        if len(geo) == 2:
            lines.append(f"geometric mean {key}: {geo[0]:.3f} -> {geo[1]:.3f}")


def main() -> None:
    lines = ["# Part 36's held-out rows (pair.py)", ""]
    classic(lines)
    lines.append("")
    mazes(lines)
    (HERE / "pair.txt").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
