"""Part 22's dev probe (prototype, not in the library): collision splits may cut below the
smallest leaf, to ``min_leaf_fraction`` / FACTOR, while every other split keeps the limit::

    python collision_width.py LAYOUT SEED LABEL FACTOR OUT

FACTOR 1 is today's preset. The prototype wraps ``TreeAgent._collision_split`` in this
process so that it sees the leaf's smallest child width divided by FACTOR, then runs
``issue9_hold_terminals_dev/curves.py`` (600 episodes) from ``general_as_of(20)``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "issue9_hold_terminals_dev"))

from curves import run  # noqa: E402

from agent import general_as_of  # noqa: E402
from agent.tree_agent import TreeAgent  # noqa: E402


def patch(factor: float) -> None:
    """``TreeAgent._collision_split`` sees the leaf's box with ``min_width`` / ``factor``."""
    original = TreeAgent._collision_split

    def collision_split(self: TreeAgent, leaf: int, action: int) -> bool:
        partition = self.partition
        box = partition.split_box

        def finer(node: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
            low, high, root_width, min_width = box(node)
            return low, high, root_width, min_width / factor

        partition.split_box = finer  # an instance attribute shadows the method for this call
        try:
            return original(self, leaf, action)
        finally:
            del partition.split_box

    TreeAgent._collision_split = collision_split  # type: ignore[method-assign]


if __name__ == "__main__":
    layout, seed, label, factor, out = sys.argv[1:6]
    patch(float(factor))
    run(layout, int(seed), label, {}, Path(out), base=general_as_of(20))
