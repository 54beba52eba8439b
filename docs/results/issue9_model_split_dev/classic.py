"""One classic-control dev job of part 9: ``issue9_classic_dev/dev.py`` (1,000 episodes, 20
greedy episodes) on one task, agent seed and set of TreeConfig overrides; with ``MS`` set the
prototype (``proto.py``) runs instead of the committed option::

    python classic.py TASK SEED LABEL OVERRIDES_JSON OUT
"""

from __future__ import annotations

import importlib
import json
import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "issue9_classic_dev")]
if os.environ.get("MS"):
    importlib.import_module("proto")
dev = importlib.import_module("dev")

if __name__ == "__main__":
    task, seed, label, overrides, out = sys.argv[1:6]
    dev.run(task, label, json.loads(overrides), int(seed), 1000, Path(out))
