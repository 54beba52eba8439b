"""Driver of the within-leaf gradient prototype (within_leaf_gradient.py): GP=1 applies it::

GP=1 python within_leaf_gradient_job.py classic Acrobot-v1 0 gp OUT.jsonl
"""

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
sys.path[:0] = [
    str(HERE),
    str(ROOT),
    str(ROOT / "docs/results/issue9_classic_dev"),
    str(ROOT / "docs/results/issue9_hold_terminals_dev"),
]
kind, case, seed, label, out = sys.argv[1:6]
if os.environ.get("GP"):
    import within_leaf_gradient  # noqa: F401
if kind == "classic":
    import dev

    dev.run(case, label, {}, int(seed), 1000, Path(out))
else:
    import curves

    curves.run(case, int(seed), label, {}, Path(out))
