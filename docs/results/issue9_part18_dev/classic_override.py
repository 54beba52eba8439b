"""Issue 9, part 18 (development): part 4's classic driver from ``general_as_of(17)`` with
TreeConfig overrides (today's general preset, whatever later parts change)::

    python docs/results/issue9_part18_dev/classic_override.py TASK SEED LABEL OVERRIDES_JSON OUT
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "issue9_classic_dev"))

from dev import run  # noqa: E402

from agent import general_as_of  # noqa: E402

if __name__ == "__main__":
    task, seed, label, overrides, out = sys.argv[1:6]
    run(task, label, json.loads(overrides), int(seed), out=Path(out), base=general_as_of(17))
