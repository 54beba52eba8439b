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
import math
from pathlib import Path

import numpy as np

RESULTS = Path(__file__).resolve().parent.parent
_SPEC = importlib.util.spec_from_file_location(
    "part25_pair", RESULTS / "issue9_part25_heldout_rows" / "pair.py"
)
assert _SPEC is not None and _SPEC.loader is not None
_PART25 = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(_PART25)
runs, maze_runs = _PART25.runs, _PART25.maze_runs
wilson, sign_p, TARGET = _PART25.wilson, _PART25.sign_p, _PART25.TARGET
FRESH = (
    (27101, "issue9_part27_heldout_classic_seed27101", tuple(TARGET)),
    (27102, "issue9_part27_heldout_mountaincar_seed27102", ("MountainCar-v0",)),
    (27103, "issue9_part27_heldout_mountaincar_seed27103", ("MountainCar-v0",)),
    (27104, "issue9_part27_heldout_mountaincar_seed27104", ("MountainCar-v0",)),
    (27105, "issue9_part27_heldout_mountaincar_seed27105", ("MountainCar-v0",)),
    (27106, "issue9_part27_heldout_classic_seed27106", tuple(TARGET)),
)


def compare(label: str, task: str, new: dict, old: dict) -> tuple[list[float], list[float]]:
    """Print one set's pairs; return (part 25's, part 27's) greedy means by run seed."""
    assert set(new) == set(old) and len(new) == 10, (label, task, len(new), len(old))
    differ = [seed for seed in sorted(new) if new[seed][0] != old[seed][0]]
    assert not differ, f"{label} {task}: training differs between the arms on runs {differ}"
    target = TARGET[task]
    olds = [old[s][1] for s in sorted(old)]
    news = [new[s][1] for s in sorted(new)]
    print(
        f"{label} {task}: part 25 {sum(v >= target for v in olds)} of 10, mean "
        f"{sum(olds) / 10:.1f}; part 27 {sum(v >= target for v in news)} of 10, mean "
        f"{sum(news) / 10:.1f}; runs higher / lower "
        f"{sum(b > a for a, b in zip(olds, news))} / {sum(b < a for a, b in zip(olds, news))}"
    )
    print("   part 25:", [round(v, 1) for v in olds])
    print("   part 27:", [round(v, 1) for v in news])
    return olds, news


def mazes() -> None:
    """The maze suite's test split (seed 14102): part 25's runs against part 27's."""
    new_folder = RESULTS / "issue9_part27_heldout_mazes_seed14102"
    old_folder = RESULTS / "issue9_part25_heldout_mazes_seed14102"
    if not new_folder.exists():
        print("mazes: not run")
        return
    logs: dict[str, list[float]] = {"old": [], "new": []}
    for layout in sorted(p.name for p in (old_folder / "runs").iterdir()):
        new, old = maze_runs(new_folder, layout), maze_runs(old_folder, layout)
        if len(new) < len(old):
            print(f"mazes {layout}: not finished")
            continue
        for seed in sorted(old):
            assert new[seed][0] == old[seed][0], f"mazes {layout} run {seed}: training differs"
            print(
                f"mazes {layout} run {seed}: greedy {old[seed][1]:.3f}x ({old[seed][2]} of "
                f"{old[seed][3]} capped) -> {new[seed][1]:.3f}x ({new[seed][2]} capped)"
            )
            logs["old"].append(math.log(old[seed][1]))
            logs["new"].append(math.log(new[seed][1]))
    if logs["old"]:
        gm = {k: math.exp(sum(v) / len(v)) for k, v in logs.items()}
        pairs = list(zip(logs["old"], logs["new"], strict=True))
        better = sum(b < a - 1e-12 for a, b in pairs)
        worse = sum(b > a + 1e-12 for a, b in pairs)
        print(
            f"mazes: geometric-mean greedy steps / optimum {gm['old']:.3f} -> {gm['new']:.3f}; "
            f"runs better {better}, worse {worse}, level {len(pairs) - better - worse}"
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
