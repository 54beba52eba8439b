"""Part 23's held-out rows: each run of today's preset (``greedy_min_epochs`` 1) paired with the
stored run of part 22's preset with the same run seed. Training should be the same run (the
training CSVs' SHA-256 in the sidecars equal), and only the greedy evaluation (20 episodes)
differ; a run whose training differs is named (its stored run was made by an earlier preset).
On 11101 and 11104 the stored runs are part 11's preset, and part 12 changed 4 of their 20
MountainCar runs, so part 22's arm was run there too (``--only general-part22``) and is the
baseline wherever the new folder holds it. Prints, per seed set and task, runs at the target, means, and per-run returns.

    python pair.py            (from this folder; reads ../issue9_part*_heldout_*)
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

RESULTS = Path(__file__).resolve().parent.parent
TARGET = {"MountainCar-v0": -110.0, "Acrobot-v1": -100.0, "CartPole-v1": 475.0}

# seed set -> (folder of the stored part 22 runs, their strategy name)
STORED = {
    11101: ("issue9_part11_heldout_classic", "general"),
    11104: ("issue9_part11_heldout_classic_seed11104", "general"),
    12101: ("issue9_part12_heldout_classic", "general"),
    13101: ("issue9_part13_heldout_classic_seed13101", "general"),
    19101: ("issue9_part19_heldout_classic", "general"),
    21101: ("issue9_part21_heldout_classic", "general-part20"),
    21102: ("issue9_part21_heldout_mountaincar_seed21102", "general-part20"),
    21103: ("issue9_part21_heldout_mountaincar_seed21103", "general-part20"),
    22101: ("issue9_part22_heldout_classic_seed22101", "general"),
    22102: ("issue9_part22_heldout_classic_seed22102", "general"),
}


def runs(folder: Path, task: str, strategy: str) -> dict[int, tuple[str, float]]:
    """Run seed -> (training CSV's SHA-256, mean greedy return) of one strategy's runs."""
    out = {}
    for sidecar in sorted((folder / "runs" / task).glob(f"{strategy}__*.json")):
        meta = json.loads(sidecar.read_text())
        if meta["strategy"] != strategy:
            continue
        with sidecar.with_suffix(".eval.csv").open() as f:
            returns = [float(row["return"]) for row in csv.DictReader(f)]
        out[int(meta["seed"])] = (meta["data_sha256"], sum(returns) / len(returns))
    return out


def compare(label: str, task: str, new: dict, old: dict) -> tuple[int, int, int]:
    assert set(new) == set(old) and len(new) == 10, (label, task, len(new), len(old))
    differ = [seed for seed in sorted(new) if new[seed][0] != old[seed][0]]
    if differ:  # the stored run was made by an earlier preset (part 12 changed 2 of 20)
        print(f"{label} {task}: training differs from the stored run on runs {differ}")
    target = TARGET[task]
    olds = [old[s][1] for s in sorted(old)]
    news = [new[s][1] for s in sorted(new)]
    n_old = sum(v >= target for v in olds)
    n_new = sum(v >= target for v in news)
    print(
        f"{label} {task}: part 22 {n_old} of 10, mean {sum(olds) / 10:.1f}; part 23 {n_new} of "
        f"10, mean {sum(news) / 10:.1f}; runs higher / lower "
        f"{sum(b > a for a, b in zip(olds, news))} / {sum(b < a for a, b in zip(olds, news))}"
    )
    print("   part 22:", [round(v, 1) for v in olds])
    print("   part 23:", [round(v, 1) for v in news])
    return n_old, n_new, 10


def maze_runs(folder: Path, layout: str) -> dict[int, tuple[str, float, int, int]]:
    """Run seed -> (training SHA-256, greedy steps / optimum, greedy episodes at the cap,
    greedy episodes) of the "general" runs on one layout."""
    out = {}
    for sidecar in sorted((folder / "runs" / layout).glob("general__*.json")):
        meta = json.loads(sidecar.read_text())
        with sidecar.with_suffix(".eval.csv").open() as f:
            rows = list(csv.DictReader(f))
        steps = [int(row["steps"]) for row in rows]
        capped = sum(row["truncated"] == "1" for row in rows)
        ratio = sum(steps) / len(steps) / float(meta["optimal_steps"])
        out[int(meta["seed"])] = (meta["data_sha256"], ratio, capped, len(rows))
    return out


def mazes() -> None:
    """The maze suite's test split (seed 14102): part 14's stored runs (the same training as
    part 22's preset) against part 23's greedy choice on the same runs."""
    new_folder = RESULTS / "issue9_part23_heldout_mazes_seed14102"
    old_folder = RESULTS / "issue9_part14_heldout_mazes"
    if not new_folder.exists():
        return
    logs = {"old": [], "new": []}
    for layout in sorted(p.name for p in (old_folder / "runs").iterdir()):
        new, old = maze_runs(new_folder, layout), maze_runs(old_folder, layout)
        if len(new) < len(old):
            print(f"mazes {layout}: not finished")
            continue
        for seed in sorted(old):
            same = "same training" if new[seed][0] == old[seed][0] else "TRAINING DIFFERS"
            print(
                f"mazes {layout} run {seed}: greedy {old[seed][1]:.3f}x ({old[seed][2]} of "
                f"{old[seed][3]} capped) -> {new[seed][1]:.3f}x ({new[seed][2]} capped); {same}"
            )
            logs["old"].append(math.log(old[seed][1]))
            logs["new"].append(math.log(new[seed][1]))
    if logs["old"]:
        gm = {k: math.exp(sum(v) / len(v)) for k, v in logs.items()}
        print(f"mazes: geometric-mean greedy steps / optimum {gm['old']:.3f} -> {gm['new']:.3f}")


def main() -> None:
    totals: dict[str, list[int]] = {}
    for seed, (folder, name) in STORED.items():
        new_folder = RESULTS / f"issue9_part23_heldout_mountaincar_seed{seed}"
        if not new_folder.exists():
            print(f"{seed}: not run")
            continue
        task = "MountainCar-v0"
        if len(runs(new_folder, task, "general")) < 10:
            print(f"{seed}: not finished")
            continue
        rerun = runs(new_folder, task, "general-part22")  # part 22's own runs, where made here
        stored = rerun if len(rerun) == 10 else runs(RESULTS / folder, task, name)
        got = compare(str(seed), task, runs(new_folder, task, "general"), stored)
        totals.setdefault(task, [0, 0, 0])
        totals[task] = [a + b for a, b in zip(totals[task], got)]
    fresh = RESULTS / "issue9_part23_heldout_classic"
    if fresh.exists():
        for task in TARGET:
            new, old = runs(fresh, task, "general"), runs(fresh, task, "general-part22")
            if len(new) == len(old) == 10:
                got = compare("23101", task, new, old)
                totals.setdefault(task, [0, 0, 0])
                totals[task] = [a + b for a, b in zip(totals[task], got)]
    for task, (n_old, n_new, n) in totals.items():
        print(f"total {task}: part 22 {n_old} of {n}, part 23 {n_new} of {n}")
    mazes()


if __name__ == "__main__":
    main()
