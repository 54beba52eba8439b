"""Part 24's held-out rows: each run of today's preset (``greedy_min_epochs`` 2,
``greedy_cell_epochs`` 1) paired with the stored run of part 23's preset (``greedy_min_epochs``
1) with the same run seed. Training must be the same run (the training CSVs' SHA-256 in the
sidecars equal; a pair that differs stops the script), and only the greedy evaluation differs.
Prints, per seed set and task, runs at the target, means and per-run returns; the fresh set
24101, whose folder holds both arms (and whose MountainCar runs the MountainCar-only file made
again, which must be the same runs); then the maze suite's test split (seed 14102) by
geometric-mean greedy steps over the optimum.

    python pair.py            (from anywhere; reads ../issue9_part2[34]_heldout_*)
"""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path

RESULTS = Path(__file__).resolve().parent.parent
_SPEC = importlib.util.spec_from_file_location(
    "part23_pair", RESULTS / "issue9_part23_heldout_rows" / "pair.py"
)
assert _SPEC is not None and _SPEC.loader is not None
_PART23 = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(_PART23)
runs = _PART23.runs  # run seed -> (training SHA-256, mean greedy return)
maze_runs = _PART23.maze_runs  # run seed -> (training SHA-256, greedy / optimum, capped, episodes)
TARGET = {"MountainCar-v0": -110.0, "Acrobot-v1": -100.0, "CartPole-v1": 475.0}
MOUNTAINCAR_SETS = (11101, 11104, 12101, 13101, 19101, 21101, 21102, 21103, 22101, 22102)


def compare(label: str, task: str, new: dict, old: dict) -> tuple[list[float], list[float]]:
    """Print one set's pairs; return (part 23's, part 24's) greedy means by run seed."""
    assert set(new) == set(old) and len(new) == 10, (label, task, len(new), len(old))
    differ = [seed for seed in sorted(new) if new[seed][0] != old[seed][0]]
    assert not differ, f"{label} {task}: training differs from the stored run on runs {differ}"
    target = TARGET[task]
    olds = [old[s][1] for s in sorted(old)]
    news = [new[s][1] for s in sorted(new)]
    print(
        f"{label} {task}: part 23 {sum(v >= target for v in olds)} of 10, mean "
        f"{sum(olds) / 10:.1f}; part 24 {sum(v >= target for v in news)} of 10, mean "
        f"{sum(news) / 10:.1f}; runs higher / lower "
        f"{sum(b > a for a, b in zip(olds, news))} / {sum(b < a for a, b in zip(olds, news))}"
    )
    print("   part 23:", [round(v, 1) for v in olds])
    print("   part 24:", [round(v, 1) for v in news])
    return olds, news


def mazes() -> None:
    """The maze suite's test split (seed 14102): part 23's runs against part 24's."""
    new_folder = RESULTS / "issue9_part24_heldout_mazes_seed14102"
    old_folder = RESULTS / "issue9_part23_heldout_mazes_seed14102"
    if not new_folder.exists():
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
        print(f"mazes: geometric-mean greedy steps / optimum {gm['old']:.3f} -> {gm['new']:.3f}")


def main() -> None:
    totals: dict[str, tuple[list[float], list[float]]] = {}

    def add(task: str, pair: tuple[list[float], list[float]]) -> None:
        olds, news = totals.setdefault(task, ([], []))
        olds.extend(pair[0])
        news.extend(pair[1])

    task = "MountainCar-v0"
    for seed in MOUNTAINCAR_SETS:
        new_folder = RESULTS / f"issue9_part24_heldout_mountaincar_seed{seed}"
        old_folder = RESULTS / f"issue9_part23_heldout_mountaincar_seed{seed}"
        new = runs(new_folder, task, "general") if new_folder.exists() else {}
        if len(new) < 10:
            print(f"{seed}: not finished")
            continue
        add(task, compare(str(seed), task, new, runs(old_folder, task, "general")))
    fresh_new = RESULTS / "issue9_part24_heldout_classic"
    fresh_old = RESULTS / "issue9_part23_heldout_classic"
    for task in TARGET:
        new = runs(fresh_new, task, "general") if fresh_new.exists() else {}
        if len(new) < 10:
            print(f"23101 {task}: not finished")
            continue
        add(task, compare("23101", task, new, runs(fresh_old, task, "general")))
    fresh = RESULTS / "issue9_part24_heldout_classic_seed24101"  # both arms, never used before
    for task in TARGET:
        new = runs(fresh, task, "general") if fresh.exists() else {}
        old = runs(fresh, task, "general-part23") if fresh.exists() else {}
        if min(len(new), len(old)) < 10:
            print(f"24101 {task}: not finished")
            continue
        add(task, compare("24101", task, new, old))
    alone = RESULTS / "issue9_part24_heldout_mountaincar_seed24101"  # the same seed, MountainCar's file
    if fresh.exists() and alone.exists():
        for name in ("general", "general-part23"):
            here, there = runs(alone, "MountainCar-v0", name), runs(fresh, "MountainCar-v0", name)
            same = here == there and len(here) == 10
            print(f"24101 MountainCar-v0 {name}: the two files' runs are {'the same' if same else 'NOT the same'}")
    for task, (olds, news) in totals.items():
        target, n = TARGET[task], len(olds)
        diffs = [b - a for a, b in zip(olds, news)]
        print(
            f"total {task} ({n} runs): part 23 {sum(v >= target for v in olds)}, part 24 "
            f"{sum(v >= target for v in news)}; mean paired change {sum(diffs) / n:+.2f}; "
            f"higher {sum(d > 0 for d in diffs)}, lower {sum(d < 0 for d in diffs)}"
        )
    mazes()


if __name__ == "__main__":
    main()
