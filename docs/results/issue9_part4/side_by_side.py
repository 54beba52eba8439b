"""The maze suite's test split, old and new held-out runs side by side (issue 9, part 4):

    python docs/results/issue9_part4/side_by_side.py OLD/summary.csv NEW/summary.csv

Per layout: final / optimum and AUC (mean steps per episode) of each strategy in both; then the
IQM over the layouts of final / optimum and AUC / optimum with a 95 % percentile bootstrap over
the layouts (10,000 resamples, seed 0), as in docs/results.md's held-out section.
"""

from __future__ import annotations

import csv
import sys
from pathlib import Path

import numpy as np
from scipy import stats


def load(path: str) -> dict[tuple[str, str], dict[str, str]]:
    rows = csv.DictReader(Path(path).read_text().splitlines())
    return {(r["task"], r["strategy"]): r for r in rows}


def iqm(values: np.ndarray) -> float:
    return float(stats.trim_mean(values, 0.25))


def band(values: list[float]) -> str:
    data = np.asarray(values)
    rng = np.random.default_rng(0)
    boots = [iqm(rng.choice(data, size=data.size, replace=True)) for _ in range(10_000)]
    low, high = np.percentile(boots, [2.5, 97.5])
    return f"{iqm(data):.2f} [{low:.2f}, {high:.2f}]"


def main() -> None:
    old, new = load(sys.argv[1]), load(sys.argv[2])
    tasks = sorted({t for t, _ in new})
    strategies = sorted({s for _, s in new})
    header = "| layout | optimum | strategy | old: final / opt | old: AUC | old: conv. "
    print(header + "| new: final / opt | new: AUC | new: conv. |")
    print("|---|---:|---|---:|---:|---:|---:|---:|---:|")
    for task in tasks:
        for strategy in strategies:
            a, b = old.get((task, strategy)), new.get((task, strategy))
            if b is None:
                continue
            cells = []
            for row in (a, b):
                if row is None:
                    cells += ["-", "-", "-"]
                else:
                    conv = row["median_convergence_episode"] or "not"
                    cells += [
                        f"{float(row['final_to_optimal_mean']):.2f}",
                        f"{float(row['auc_mean_steps']):.0f}",
                        conv.removesuffix(".0"),
                    ]
            print(
                f"| `{task}` | {float(b['optimal_steps']):.0f} | {strategy} | "
                + " | ".join(cells)
                + " |"
            )
    print()
    print("| strategy | old: IQM final / optimum | new | old: IQM AUC / optimum | new |")
    print("|---|---:|---:|---:|---:|")
    for strategy in strategies:
        line = [strategy]
        for key in ("final_to_optimal_mean", "auc_to_optimal_mean"):
            for table in (old, new):
                values = [float(table[(t, strategy)][key]) for t in tasks if (t, strategy) in table]
                line.append(band(values) if len(values) == len(tasks) else "-")
        print("| " + " | ".join(line) + " |")


if __name__ == "__main__":
    main()
