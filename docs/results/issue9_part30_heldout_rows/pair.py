"""Part 30's held-out rows: today's preset (``greedy_tie_trial``) against part 29's
(``general_as_of(29)``, spelt out as ``general-part29``), both arms trained on the same fresh
experiment seeds. Training differs from episode 300 on, so a pair is two runs with the same run
seed (the same agent seed and reset seeds), not the same run.

Classic control (fresh sets 30101 and 30103): per set and task, each arm's runs at the target, mean greedy return (20
greedy episodes a run), the paired change with a bootstrap 95 % interval and a sign test, then the totals over the sets. Mazes
(the suite's test split, seed 30102): per layout, each arm's final (last 100 training episodes)
over the optimum, area under the curve over the optimum, converged runs and their median
episode, and greedy steps, with the best uniform grid's area; and the geometric means over the
layouts.

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
_SPEC = importlib.util.spec_from_file_location(
    "part25_pair", RESULTS / "issue9_part25_heldout_rows" / "pair.py"
)
assert _SPEC is not None and _SPEC.loader is not None
_PART25 = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(_PART25)
wilson, sign_p, TARGET = _PART25.wilson, _PART25.sign_p, _PART25.TARGET
CLASSIC_SETS = (30101, 30103)
MAZES = RESULTS / "issue9_part30_heldout_mazes_seed30102"
ARMS = ("general-part29", "general")


def greedy_means(folder: Path) -> dict[tuple[str, str], dict[int, float]]:
    """Mean greedy return per (task, strategy) and run index, from ``evaluation.csv``."""
    sums: dict[tuple[str, str, int], list[float]] = defaultdict(list)
    with (folder / "evaluation.csv").open() as f:
        for row in csv.DictReader(f):
            sums[(row["task"], row["strategy"], int(row["run"]))].append(float(row["return"]))
    out: dict[tuple[str, str], dict[int, float]] = defaultdict(dict)
    for (task, strategy, run), values in sums.items():
        out[(task, strategy)][run] = sum(values) / len(values)
    return out


def classic(lines: list[str]) -> None:
    totals: dict[str, tuple[list[float], list[float]]] = {}
    for seed in CLASSIC_SETS:
        folder = RESULTS / f"issue9_part30_heldout_classic_seed{seed}"
        if not (folder / "evaluation.csv").exists():
            lines.append(f"classic {seed}: not run")
            continue
        means = greedy_means(folder)
        for task in TARGET:
            old, new = means.get((task, ARMS[0]), {}), means.get((task, ARMS[1]), {})
            runs = sorted(set(old) & set(new))
            if len(runs) < 10:
                lines.append(f"{seed} {task}: {len(runs)} pairs finished")
                continue
            a, b = [old[r] for r in runs], [new[r] for r in runs]
            both = totals.setdefault(task, ([], []))
            both[0].extend(a)
            both[1].extend(b)
            lines.append(f"{seed} " + _pairs(task, a, b))
            lines.append("  part 29: " + ", ".join(f"{v:.2f}" for v in a))
            lines.append("  part 30: " + ", ".join(f"{v:.2f}" for v in b))
    for task, (a, b) in totals.items():
        if len(a) > 10:
            lines.append("all sets " + _pairs(task, a, b, rates=True))


def _pairs(task: str, a: list[float], b: list[float], rates: bool = False) -> str:
    """One line: each arm's runs at the target and mean, and the paired change."""
    target, n = TARGET[task], len(a)
    diffs = np.asarray(b) - np.asarray(a)
    boot = np.random.default_rng(0).choice(diffs, size=(10_000, n)).mean(axis=1)
    low, high = np.percentile(boot, [2.5, 97.5])
    higher, lower = int((diffs > 0).sum()), int((diffs < 0).sum())
    hits = [sum(v >= target for v in arm) for arm in (a, b)]
    rate = [f" {wilson(k, n)}" if rates else "" for k in hits]
    return (
        f"{task}: part 29 {hits[0]} of {n}{rate[0]} at {target:g}, mean {np.mean(a):.2f}; "
        f"part 30 {hits[1]} of {n}{rate[1]}, mean {np.mean(b):.2f}; change {diffs.mean():+.2f} "
        f"[{low:+.2f}, {high:+.2f}], higher {higher}, lower {lower}, sign test p = "
        f"{sign_p(higher, lower):.2g}"
    )


def latest_convergence(arm: str) -> str:
    """The latest per-run convergence episode of ``arm`` over the maze layouts (the report's
    rule, ``experiments.statistics.convergence_episode``), or which runs never converged."""
    from experiments.statistics import convergence_episode

    worst: tuple[int, str] | None = None
    never = []
    for path in sorted((MAZES / "runs").glob(f"*/{arm}__*.csv")):
        if path.name.endswith(".eval.csv"):
            continue
        with path.open() as f:
            rows = list(csv.DictReader(f))
        steps = np.asarray([float(r["steps"]) for r in rows])
        success = float(np.mean([float(r["success"]) for r in rows[-100:]]))
        episode = convergence_episode(steps, 50, 0.1, final_window=100, final_success=success)
        where = f"{path.parent.name} {path.stem.split('__')[1]}"
        if episode is None:
            never.append(where)
        elif worst is None or episode > worst[0]:
            worst = (episode, where)
    text = f"{worst[0]} ({worst[1]})" if worst else "none"
    return text + (f", never converged: {never}" if never else "")


def mazes(lines: list[str]) -> None:
    if not (MAZES / "summary.csv").exists():
        lines.append("mazes: not run")
        return
    rows: dict[tuple[str, str], dict[str, str]] = {}
    with (MAZES / "summary.csv").open() as f:
        for row in csv.DictReader(f):
            rows[(row["task"], row["strategy"])] = row
    layouts = sorted({task for task, _ in rows})
    logs: dict[str, dict[str, list[float]]] = {arm: defaultdict(list) for arm in ARMS}
    lines.append(
        "layout: final / optimum, AUC / optimum, converged (median episode), greedy steps / "
        "optimum; part 29 -> part 30"
    )
    for layout in layouts:
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
    latest = {arm: latest_convergence(arm) for arm in ARMS}
    lines.append(
        "latest run convergence (episode; window 50, tolerance 0.1, the report's rule): "
        + "; ".join(f"{arm} {latest[arm]}" for arm in ARMS)
    )
    for key in ("final", "auc", "greedy"):
        geo = [math.exp(float(np.mean(logs[arm][key]))) for arm in ARMS if logs[arm][key]]
        if len(geo) == 2:
            lines.append(f"geometric mean {key}: {geo[0]:.3f} -> {geo[1]:.3f}")


def main() -> None:
    lines = ["# Part 30's held-out rows (pair.py)", ""]
    classic(lines)
    lines.append("")
    mazes(lines)
    (HERE / "pair.txt").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
