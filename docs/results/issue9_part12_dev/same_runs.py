"""Which runs of a held-out comparison are the same to the bit in its two arms (issue 9, part 12:
where the 10th terminal comes within 100 episodes, ``novelty_episodes`` changes nothing). Two
runs with the same seed are the same when their per-episode CSVs and their greedy evaluations
(``.eval.csv``) are equal byte for byte::

    python docs/results/issue9_part12_dev/same_runs.py RESULTS_FOLDER general general-part11
"""

from __future__ import annotations

import sys
from pathlib import Path


def main(folder: str, a: str, b: str) -> None:
    same, differ = 0, []
    for first in sorted(Path(folder, "runs").rglob(f"{a}__*.csv")):
        if first.name.endswith(".eval.csv"):
            continue
        seed = first.name.split("__")[1]
        second = first.with_name(f"{b}__{seed}")
        evals = [p.with_name(p.name.replace(".csv", ".eval.csv")) for p in (first, second)]
        equal = first.read_bytes() == second.read_bytes()
        if evals[0].exists() or evals[1].exists():
            equal = equal and evals[0].read_bytes() == evals[1].read_bytes()
        if equal:
            same += 1
        else:
            differ.append(f"{first.parent.name}/{seed}")
    print(f"{same} of {same + len(differ)} runs the same to the byte in {a} and {b}")
    for run in differ:
        print("differs:", run)


if __name__ == "__main__":
    main(*sys.argv[1:4])
