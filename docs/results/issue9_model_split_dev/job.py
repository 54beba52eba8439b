"""One dev job of part 9, on the committed code with TreeConfig overrides, or with ``MS`` set
(a JSON of k, delta, t, m) on the prototype (``proto.py``)::

    python job.py maze LAYOUT SEED LABEL OVERRIDES_JSON OUT
    python job.py classic TASK SEED LABEL OVERRIDES_JSON OUT

``maze`` runs ``issue9_hold_terminals_dev/curves.py`` (600 episodes, greedy probes every 50);
``classic`` runs ``issue9_classic_dev/dev.py`` (1,000 episodes, 20 greedy episodes).
"""

from __future__ import annotations

import importlib
import json
import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
DRIVERS = {
    "maze": ("issue9_hold_terminals_dev", "curves"),
    "classic": ("issue9_classic_dev", "dev"),
}


def main(argv: list[str]) -> None:
    kind, case, seed, label, overrides, out = argv
    folder, module = DRIVERS[kind]
    sys.path[:0] = [str(HERE), str(HERE.parent / folder)]
    if os.environ.get("MS"):
        importlib.import_module("proto")
    driver = importlib.import_module(module)
    if kind == "maze":
        driver.run(case, int(seed), label, json.loads(overrides), Path(out))
    else:
        driver.run(case, label, json.loads(overrides), int(seed), 1000, Path(out))


if __name__ == "__main__":
    main(sys.argv[1:])
