"""Part 27's held-out rows: each run of today's preset (the tree's ancestors, compared leaf by leaf,
break the greedy choice's ties: ``greedy_tie_errors`` 1, ``greedy_tie_ancestors`` 1) paired with the
run of part 25's preset (``general_as_of(26)``, the neighbours) with the same run seed. Training
must be the same run (the training CSVs' SHA-256 in the sidecars equal; a pair that differs stops
the script), and only the greedy evaluation differs. Prints, per fresh seed set and task, runs at
the target, means and per-run returns (both arms in one folder: 27101's and 27106's three tasks,
27102's to 27105's MountainCar); totals with a sign count and a bootstrap interval; then the maze
suite's test split (seed 14102), today's runs against part 25's stored ones, by geometric-mean
greedy steps over the optimum.

    python pair.py            (from anywhere; reads ../issue9_part2[57]_heldout_*)
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np

RESULTS = Path(__file__).resolve().parent.parent
_SPEC = importlib.util.spec_from_file_location(
    "part25_pair", RESULTS / "issue9_part25_heldout_rows" / "pair.py"
)
assert _SPEC is not None and _SPEC.loader is not None
_PART25 = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(_PART25)
runs, wilson, sign_p, TARGET = _PART25.runs, _PART25.wilson, _PART25.sign_p, _PART25.TARGET
NAMES = ("part 25", "part 27")


def compare(label: str, task: str, new: dict, old: dict) -> tuple[list[float], list[float]]:
    """Part 25's pairing of one set (training equal run by run), with this part's labels."""
    return _PART25.compare(label, task, new, old, NAMES)


def mazes() -> None:
    """The maze suite's test split (seed 14102): part 25's stored runs against part 27's."""
    new_folder = RESULTS / "issue9_part27_heldout_mazes_seed14102"
    if not new_folder.exists():
        print("mazes: not run")
        return
    _PART25.mazes(new_folder, RESULTS / "issue9_part25_heldout_mazes_seed14102")
FRESH = (
    (27101, "issue9_part27_heldout_classic_seed27101", tuple(TARGET)),
    (27102, "issue9_part27_heldout_mountaincar_seed27102", ("MountainCar-v0",)),
    (27103, "issue9_part27_heldout_mountaincar_seed27103", ("MountainCar-v0",)),
    (27104, "issue9_part27_heldout_mountaincar_seed27104", ("MountainCar-v0",)),
    (27105, "issue9_part27_heldout_mountaincar_seed27105", ("MountainCar-v0",)),
    (27106, "issue9_part27_heldout_classic_seed27106", tuple(TARGET)),
)


def main() -> None:
    totals: dict[str, tuple[list[float], list[float]]] = {}
    for seed, folder, tasks in FRESH:
        path = RESULTS / folder
        for task in tasks:
            new = runs(path, task, "general") if path.exists() else {}
            old = runs(path, task, "general-part26") if path.exists() else {}
            if min(len(new), len(old)) < 10:
                print(f"{seed} {task}: not finished")
                continue
            olds, news = compare(str(seed), task, new, old)
            both = totals.setdefault(task, ([], []))
            both[0].extend(olds)
            both[1].extend(news)
    for task, (olds, news) in totals.items():
        target, n = TARGET[task], len(olds)
        diffs = [b - a for a, b in zip(olds, news)]
        higher, lower = sum(d > 0 for d in diffs), sum(d < 0 for d in diffs)
        rng = np.random.default_rng(0)
        means = rng.choice(np.asarray(diffs), size=(10_000, n)).mean(axis=1)
        low, high = np.percentile(means, [2.5, 97.5])
        solved = {k: sum(v >= target for v in vs) for k, vs in (("25", olds), ("27", news))}
        print(
            f"total {task} ({n} runs): part 25 {solved['25']} {wilson(solved['25'], n)}, part 27 "
            f"{solved['27']} {wilson(solved['27'], n)}; mean paired change "
            f"{sum(diffs) / n:+.2f} [{low:+.2f}, {high:+.2f}]; higher {higher}, lower {lower}, "
            f"sign test p = {sign_p(higher, lower):.2g}"
        )
    mazes()


if __name__ == "__main__":
    main()
