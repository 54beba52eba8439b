"""One dev job of part 21: today's general preset (``general_as_of(20)``) with TreeConfig
overrides, with the policy-split prototype (``proto_policy.py``) when ``PROTO`` is ``policy``::

    python job.py maze LAYOUT SEED LABEL PROTO OVERRIDES_JSON OUT
    python job.py classic TASK SEED LABEL PROTO OVERRIDES_JSON OUT

``maze`` runs ``issue9_hold_terminals_dev/curves.py`` (600 episodes, greedy probes every 50);
``classic`` runs ``issue9_classic_dev/dev.py`` (1,000 episodes, 20 greedy episodes). The
prototype's settings come from the environment (``PS_T``, ``PS_MIN``).
"""

from __future__ import annotations

import importlib
import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent

if __name__ == "__main__":
    kind, case, seed, label, proto, overrides, out = sys.argv[1:8]
    sys.path[:0] = [str(HERE), str(HERE.parent / "issue9_hold_terminals_dev"), str(HERE.parent / "issue9_classic_dev")]
    if proto == "policy":
        importlib.import_module("proto_policy")
    from agent import general_as_of

    base = general_as_of(20)
    if kind == "maze":
        import curves

        curves.run(case, int(seed), label, json.loads(overrides), Path(out), base=base)
    else:
        import dev

        dev.run(case, label, json.loads(overrides), int(seed), 1000, Path(out), base=base)
