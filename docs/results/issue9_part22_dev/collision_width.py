"""Part 22's dev probe (prototype, not in the library): collision splits may cut below the
smallest leaf, to ``min_leaf_fraction`` / FACTOR, while every other split keeps the limit::

    python collision_width.py LAYOUT SEED LABEL FACTOR OUT

FACTOR 1 is today's preset. The prototype replaces ``TreeAgent._collision_split`` in this
process with a copy whose ``min_width`` is divided by FACTOR, then runs
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
from agent.collision_split import choose_collision_split  # noqa: E402
from agent.tree_agent import TreeAgent  # noqa: E402


def patch(factor: float) -> None:
    def collision_split(self: TreeAgent, leaf: int, action: int) -> bool:
        partition = self.partition
        if not partition.may_split():
            return False
        firsts, collided = self.model.collisions(leaf, action)  # type: ignore[union-attr]
        low, high, _, min_width = partition.split_box(leaf)
        choice = choose_collision_split(
            np.asarray(firsts, dtype=np.float64),
            np.asarray(collided, dtype=np.bool_),
            low,
            high,
            min_width / factor,
        )
        if choice is None:
            return False
        self._grow(leaf, partition.split_with_samples(leaf, *choice))
        return True

    TreeAgent._collision_split = collision_split  # type: ignore[method-assign]


if __name__ == "__main__":
    layout, seed, label, factor, out = sys.argv[1:6]
    patch(float(factor))
    run(layout, int(seed), label, {}, Path(out), base=general_as_of(20))
