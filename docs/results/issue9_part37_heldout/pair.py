"""Part 37's held-out rows: a fifth fresh classic set (37101) and a second maze set (37102)
with both arms of part 36's comparison files (today's preset, N_th 50, against
``general_as_of(35)``, N_th 100), and today's preset pooled over its three classic sets (36101,
36104, 37101). The maze table is part 36's (part 30's), read from 37102's folder.

Per task: each arm's runs at the target and mean greedy return (20 greedy episodes a run), the
paired change with a bootstrap 95 % interval and a sign test (part 30's formatter, as part 36's
``pair.py``); then today's preset's runs at the target over the three sets with a Wilson 95 %
interval. 36104 ran today's preset alone (``--only``), so its runs are read from their own
``.eval.csv`` files.

    python pair.py            (from anywhere; writes pair.txt beside this file)
"""

from __future__ import annotations

import csv
import importlib.util
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
RESULTS = HERE.parent


_SPEC = importlib.util.spec_from_file_location(
    "part36_pair", RESULTS / "issue9_part36_heldout" / "pair.py"
)
assert _SPEC is not None
assert _SPEC.loader is not None
_PART36 = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(_PART36)
_PART30 = _PART36._PART30  # part 30's formatter and targets, as part 36 loaded them
TARGET = _PART30.TARGET
CLASSIC = RESULTS / "issue9_part37_heldout_classic_seed37101"
MAZES = RESULTS / "issue9_part37_heldout_mazes_seed37102"
SETS = {
    36101: RESULTS / "issue9_part36_heldout_classic_seed36101",
    36104: RESULTS / "issue9_part36_heldout_classic_seed36104",
    37101: CLASSIC,
}


def today_means(folder: Path, task: str) -> list[float]:
    """Today's preset's (``general``) mean greedy return per run, from its ``.eval.csv`` files."""
    means = []
    for path in sorted((folder / "runs" / task).glob("general__*.eval.csv")):
        with path.open() as f:
            means.append(float(np.mean([float(r["return"]) for r in csv.DictReader(f)])))
    return means


def pooled(lines: list[str]) -> None:
    for task, target in TARGET.items():
        per_set = {seed: today_means(folder, task) for seed, folder in SETS.items()}
        if any(len(v) != 10 for v in per_set.values()):
            lines.append(f"pooled {task}: a set is unfinished")
            continue
        values = [v for seed in SETS for v in per_set[seed]]
        hits = [sum(v >= target for v in per_set[seed]) for seed in SETS]
        lines.append(
            f"pooled {task}, today's preset on {', '.join(map(str, SETS))}: "
            f"{' + '.join(map(str, hits))} = {sum(hits)} of {len(values)} at {target:g} "
            f"{_PART30.wilson(sum(hits), len(values))}, mean {np.mean(values):.2f}"
        )


def main() -> None:
    lines = ["# Part 37's held-out rows (pair.py)", ""]
    _PART36.CLASSIC = CLASSIC  # its classic() reads this folder
    part36: list[str] = []
    _PART36.classic(part36)
    lines += [line.replace("36101", "37101", 1) for line in part36]
    lines.append("")
    pooled(lines)
    lines.append("")
    _PART36.MAZES = _PART30.MAZES = MAZES  # their mazes() read these
    part36 = []
    _PART36.mazes(part36)
    lines += [line.replace("36102", "37102") for line in part36]
    (HERE / "pair.txt").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
