"""Per-run numbers of a maze experiment's folder, for the tables of docs/results.md.

One line per layout and strategy: "AUC / final / converged" of each run in index order (AUC:
mean steps per episode; final: the last 100 episodes' mean over the optimum; converged: the
harness's 10 % rule, ``experiments.statistics.convergence_episode``), then each run's success
rate::

    cd docs/results/issue9_part10_heldout_mazes && python per_run.py .
"""

from __future__ import annotations

import collections
import csv
import json
import sys
from pathlib import Path

import numpy as np

from experiments.statistics import convergence_episode


def main(root: Path) -> None:
    rows: dict[tuple[str, str], list[tuple[int, float, float, int | None, float, float]]] = (
        collections.defaultdict(list)
    )
    for sidecar in sorted(root.glob("runs/*/*.json")):
        meta = json.loads(sidecar.read_text())
        with sidecar.with_suffix(".csv").open() as handle:
            data = list(csv.DictReader(handle))
        steps = np.array([float(r["steps"]) for r in data])
        success = np.array([float(r["success"]) for r in data])
        optimum = float(meta["optimal_steps"])
        converged = convergence_episode(steps, 50, 0.1, 100, float(success[-100:].mean()))
        rows[(meta["task"], meta["strategy"])].append(
            (
                meta["run_index"],
                float(steps.mean()),
                float(steps[-100:].mean()) / optimum,
                converged,
                float(success.mean()),
                optimum,
            )
        )
    for (task, strategy), runs in sorted(rows.items()):
        runs.sort()
        cells = " ; ".join(f"{a:.0f} / {f:.2f}x / {c or 'not'}" for _, a, f, c, _, _ in runs)
        rates = ", ".join(f"{s:.2f}" for _, _, _, _, s, _ in runs)
        print(f"{task} ({runs[0][5]:.0f}) | {strategy} | {cells} | success {rates}")


if __name__ == "__main__":
    main(Path(sys.argv[1]))
