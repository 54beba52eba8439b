"""Part 17's maze driver (development only): part 8's ``curves.run`` on a layout seen through
the lidar (``observation="lidar"``: x, y and 36 ranges, 38 inputs), from
``general_as_of(16)`` with ``overrides``, 600 episodes, agent seed s::

    python docs/results/issue9_part17_dev/lidar_maze.py LAYOUT SEED LABEL OVERRIDES_JSON OUT \
        [ENV_KWARGS_JSON]

ENV_KWARGS_JSON defaults to ``{"observation": "lidar"}``; ``{}`` runs the pose observation.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "issue9_hold_terminals_dev"))

from curves import run  # noqa: E402

from agent import general_as_of  # noqa: E402

if __name__ == "__main__":
    layout, seed, label, overrides, out = sys.argv[1:6]
    env_kwargs = json.loads(sys.argv[6]) if len(sys.argv) > 6 else {"observation": "lidar"}
    base = general_as_of(16)
    run(layout, int(seed), label, json.loads(overrides), Path(out), env_kwargs=env_kwargs, base=base)
