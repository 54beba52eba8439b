"""One maze dev job of part 9: ``issue9_hold_terminals_dev/curves.py`` on one layout, agent seed
and set of TreeConfig overrides; with ``MS`` set (a JSON of k, delta, t, m) the prototype
(``proto.py``) runs instead of the committed option::

    python maze.py LAYOUT SEED LABEL OVERRIDES_JSON OUT
"""

from __future__ import annotations

import importlib
import json
import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "issue9_hold_terminals_dev")]
if os.environ.get("MS"):
    importlib.import_module("proto")
curves = importlib.import_module("curves")

if __name__ == "__main__":
    maze, seed, label, overrides, out = sys.argv[1:6]
    curves.run(maze, int(seed), label, json.loads(overrides), Path(out))
