"""Part 25's held-out rows: each run of today's preset (neighbours break the greedy choice's
ties: ``greedy_smoothing`` 1, ``greedy_smoothing_links``, ``greedy_tie_errors`` 0.5) paired with
the stored run of part 24's preset with the same run seed. Training must be the same run (the
training CSVs' SHA-256 in the sidecars equal; a pair that differs stops the script), and only
the greedy evaluation differs. Prints, per seed set and task, runs at the target, means and
per-run returns; the fresh set 25101, whose folder holds both arms; totals with a sign count;
then the maze suite's test split (seed 14102) by geometric-mean greedy steps over the optimum.

    python pair.py            (from anywhere; reads ../issue9_part2[45]_heldout_*)
"""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import numpy as np

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


def wilson(k: int, n: int, z: float = 1.96) -> str:
    """A Wilson 95 % interval of the rate k / n, as text."""
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return f"{p:.2f} [{centre - half:.2f}, {centre + half:.2f}]"


def sign_p(higher: int, lower: int) -> float:
    """Two-sided sign-test p-value (ties dropped)."""
    n = higher + lower
    tail = sum(math.comb(n, i) for i in range(min(higher, lower) + 1)) / 2**n
    return min(1.0, 2 * tail)


def compare(
    label: str, task: str, new: dict, old: dict, names: tuple[str, str] = ("part 24", "part 25")
) -> tuple[list[float], list[float]]:
    """Print one set's pairs; return (part 24's, part 25's) greedy means by run seed (``names``:
    the two arms' labels; part 27's script reuses it)."""
    assert set(new) == set(old) and len(new) == 10, (label, task, len(new), len(old))
    differ = [seed for seed in sorted(new) if new[seed][0] != old[seed][0]]
    assert not differ, f"{label} {task}: training differs from the stored run on runs {differ}"
    target = TARGET[task]
    olds = [old[s][1] for s in sorted(old)]
    news = [new[s][1] for s in sorted(new)]
    print(
        f"{label} {task}: {names[0]} {sum(v >= target for v in olds)} of 10, mean "
        f"{sum(olds) / 10:.1f}; {names[1]} {sum(v >= target for v in news)} of 10, mean "
        f"{sum(news) / 10:.1f}; runs higher / lower "
        f"{sum(b > a for a, b in zip(olds, news))} / {sum(b < a for a, b in zip(olds, news))}"
    )
    print(f"   {names[0]}:", [round(v, 1) for v in olds])
    print(f"   {names[1]}:", [round(v, 1) for v in news])
    return olds, news


def mazes(
    new_folder: Path = RESULTS / "issue9_part25_heldout_mazes_seed14102",
    old_folder: Path = RESULTS / "issue9_part24_heldout_mazes_seed14102",
) -> None:
    """The maze suite's test split (seed 14102): the old part's runs against the new one's
    (part 24's against part 25's; part 27's script passes its own folders)."""
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
        pairs = list(zip(logs["old"], logs["new"], strict=True))
        better = sum(b < a - 1e-12 for a, b in pairs)
        worse = sum(b > a + 1e-12 for a, b in pairs)
        print(
            f"mazes: geometric-mean greedy steps / optimum {gm['old']:.3f} -> {gm['new']:.3f}; "
            f"runs better {better}, worse {worse}, level {len(pairs) - better - worse}"
        )


def main() -> None:
    totals: dict[str, tuple[list[float], list[float]]] = {}

    def add(task: str, pair: tuple[list[float], list[float]]) -> None:
        olds, news = totals.setdefault(task, ([], []))
        olds.extend(pair[0])
        news.extend(pair[1])

    def stored(label: str, task: str, new_folder: Path, old_folder: Path) -> None:
        new = runs(new_folder, task, "general") if new_folder.exists() else {}
        if len(new) < 10:
            print(f"{label} {task}: not finished")
            return
        add(task, compare(label, task, new, runs(old_folder, task, "general")))

    for seed in MOUNTAINCAR_SETS:
        stored(
            str(seed),
            "MountainCar-v0",
            RESULTS / f"issue9_part25_heldout_mountaincar_seed{seed}",
            RESULTS / f"issue9_part24_heldout_mountaincar_seed{seed}",
        )
    for seed, old in (
        (23101, "issue9_part24_heldout_classic"),
        (24101, "issue9_part24_heldout_classic_seed24101"),
    ):
        for task in TARGET:
            new = RESULTS / f"issue9_part25_heldout_classic_seed{seed}"
            stored(str(seed), task, new, RESULTS / old)
    fresh = RESULTS / "issue9_part25_heldout_classic_seed25101"  # both arms, never used before
    for task in TARGET:
        new = runs(fresh, task, "general") if fresh.exists() else {}
        old = runs(fresh, task, "general-part24") if fresh.exists() else {}
        if min(len(new), len(old)) < 10:
            print(f"25101 {task}: not finished")
            continue
        add(task, compare("25101", task, new, old))
    for task, (olds, news) in totals.items():
        target, n = TARGET[task], len(olds)
        diffs = [b - a for a, b in zip(olds, news)]
        higher, lower = sum(d > 0 for d in diffs), sum(d < 0 for d in diffs)
        rng = np.random.default_rng(0)
        means = rng.choice(np.asarray(diffs), size=(10_000, n)).mean(axis=1)
        low, high = np.percentile(means, [2.5, 97.5])
        solved = {k: sum(v >= target for v in vs) for k, vs in (("24", olds), ("25", news))}
        print(
            f"total {task} ({n} runs): part 24 {solved['24']} {wilson(solved['24'], n)}, part 25 "
            f"{solved['25']} {wilson(solved['25'], n)}; mean paired change "
            f"{sum(diffs) / n:+.2f} [{low:+.2f}, {high:+.2f}]; higher {higher}, lower {lower}, "
            f"sign test p = {sign_p(higher, lower):.2g}"
        )
    mazes()


if __name__ == "__main__":
    main()
