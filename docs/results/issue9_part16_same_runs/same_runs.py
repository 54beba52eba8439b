"""Compare two experiment folders run by run, by the hashes in each run's sidecar.

    python docs/results/issue9_part16_same_runs/same_runs.py NEW OLD STRATEGY > OUT.txt

NEW and OLD are experiment folders (``runs/`` inside); every run of STRATEGY in NEW is looked
up in OLD by its path, and reported ``same`` when its data and evaluation hashes match.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path


def main(new: str, old: str, strategy: str) -> None:
    same = total = 0
    for sidecar in sorted(Path(new).glob(f"runs/**/{strategy}__*.json")):
        relative = sidecar.relative_to(new)
        mine = json.loads(sidecar.read_text())
        theirs_path = Path(old) / relative
        theirs = json.loads(theirs_path.read_text()) if theirs_path.exists() else {}
        keys = ("data_sha256", "evaluation_sha256")
        match = all(mine.get(k) == theirs.get(k) for k in keys)
        same += match
        total += 1
        print(f"{relative}: {'same' if match else 'differs'}")
    print(f"{same} of {total} runs the same")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], sys.argv[3])
