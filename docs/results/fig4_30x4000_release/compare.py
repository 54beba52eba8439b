"""Figure 4 at the paper's scale with today's sweep (issue 9, part 32) beside the run recorded
before the simulator fix (``../fig4_30x4000/summary.csv``, code 9fad3a2, old sweep).

    python compare.py RUNS_FOLDER > compare.md

RUNS_FOLDER is the experiment's output folder (its ``summary.csv`` and ``runs/*.csv``). Per
strategy: final steps (mean of the last 100 episodes, mean over runs), converged runs, success
rate, leaves and P(improvement) over eps-greedy 0.015, old and new, from the two summaries;
capped episodes and the mean curve at episode 900 (50-episode moving average) from the new
run files (the old run files were not kept; their figures are in docs/results.md)."""

from __future__ import annotations

import csv
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent


def summary(path: Path) -> dict[str, dict[str, str]]:
    with path.open() as f:
        return {row["strategy"]: row for row in csv.DictReader(f)}


def run_figures(runs: Path, strategy: str, cap: int = 5000) -> tuple[int, float, int]:
    capped, at900 = 0, []
    files = sorted(runs.glob(f"{strategy}__*.csv"))
    for f in files:
        steps = np.loadtxt(f, delimiter=",", skiprows=1, usecols=1)
        capped += int((steps >= cap).sum())
        at900.append(float(steps[850:900].mean()))
    return capped, float(np.mean(at900)), len(files)


def main(folder: Path) -> None:
    old = summary(HERE.parent / "fig4_30x4000" / "summary.csv")
    new = summary(folder / "summary.csv")
    print(
        "| strategy | final steps, old -> new | / optimum 63, new | converged, old -> new "
        "| success rate, old -> new | leaves, old -> new | P(improvement), old -> new "
        "| capped episodes, new | mean curve at 900, new |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, row in new.items():
        was = old[name]
        capped, at900, n = run_figures(folder / "runs", name)
        assert n == int(row["runs"]), (name, n, row["runs"])
        print(
            f"| {name} | {float(was['final_steps_mean']):.1f} -> {float(row['final_steps_mean']):.1f} "
            f"| {float(row['final_to_optimal']):.2f} "
            f"| {was['converged_runs']}/{was['runs']} -> {row['converged_runs']}/{row['runs']} "
            f"| {100 * float(was['success_rate']):.1f}% -> {100 * float(row['success_rate']):.1f}% "
            f"| {float(was['leaves_mean']):.0f} -> {float(row['leaves_mean']):.0f} "
            f"| {float(was['p_improvement']):.2f} -> {float(row['p_improvement']):.2f} "
            f"| {capped:,} | {at900:.1f} |"
        )


if __name__ == "__main__":
    main(Path(sys.argv[1]))
