"""Compare two experiment folders run by run, one strategy of each, by the hashes in each run's
sidecar (``docs/results/issue9_part16_same_runs/same_runs.py`` with the strategy named on
both sides)::

    python docs/results/issue9_part20_same_runs/same_arms.py NEW NEW_STRATEGY OLD OLD_STRATEGY

Every run of NEW_STRATEGY in NEW is looked up in OLD under OLD_STRATEGY with the same task and
run seed, and reported ``same`` when its data and evaluation hashes match.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path


def main(new: str, new_strategy: str, old: str, old_strategy: str) -> None:
    same = total = 0
    for sidecar in sorted(Path(new).glob(f"runs/**/{new_strategy}__*.json")):
        relative = sidecar.relative_to(new)
        theirs_path = Path(old) / relative.parent / sidecar.name.replace(
            f"{new_strategy}__", f"{old_strategy}__", 1
        )
        mine = json.loads(sidecar.read_text())
        theirs = json.loads(theirs_path.read_text()) if theirs_path.exists() else {}
        keys = ("data_sha256", "evaluation_sha256")
        match = all(mine.get(k) == theirs.get(k) for k in keys)
        same += match
        total += 1
        print(f"{relative} against {old_strategy}: {'same' if match else 'differs'}")
    print(f"{same} of {total} runs the same")


if __name__ == "__main__":
    main(*sys.argv[1:5])
