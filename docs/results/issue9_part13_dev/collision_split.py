"""Part 13 dev prototype (not an agent option): split a leaf where an epoch collided.

The forest diagnostics (``forest_route.py``, ``thin_evidence.py``) point at leaves that span
both the side of a pillar and its shadow: an action collides from one part and passes from
the other, and the tree never learns where. This prototype patches ``SMDPAgent`` so that an
epoch whose last step collided (its last reward at most ``-0.5``: the maze pays -1 for a
collision, -0.01 for a step and +5 at the goal) splits its start leaf at the midpoint of its
widest dimension (relative to the root box), while that width is more than ``1 / FLOOR`` of
the root's, and when neither the paper's test nor the model split has split it. Children
inherit as after any split. Then it runs part 8's maze driver (600 episodes, greedy probes
every 50) and appends to ``maze_collision.jsonl``::

    PYTHONPATH=. python docs/results/issue9_part13_dev/collision_split.py \\
        "forest:seed=2,count=70,radius_max=8,gap=11" 0 csplit32 32
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

from agent.learner import SMDPAgent

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "issue9_hold_terminals_dev"))
import curves  # noqa: E402  (part 8's maze driver, beside this folder)

FLOOR = 32


def patch_collision_splits(choose: Callable[[Any, int, int], Any]) -> None:
    """Patch ``SMDPAgent`` so that after an epoch whose last step collided, when neither the
    paper's test nor the model split has split its start leaf, ``choose(agent, leaf, action)``
    may split it (it returns the children or None). Shared with ``collision_cut.py``."""
    end_epoch = SMDPAgent._end_epoch
    model_split = SMDPAgent._model_split

    def patched_end_epoch(self: Any, leaf: int, action: int, xs: Any, rs: Any, *args: Any) -> bool:
        self._collided_epoch = bool(rs) and rs[-1] <= -0.5
        return end_epoch(self, leaf, action, xs, rs, *args)

    def patched_model_split(self: Any, leaf: int, action: int) -> Any:
        children = model_split(self, leaf, action)
        if children is not None or not getattr(self, "_collided_epoch", False):
            return children
        if not self.partition.may_split():
            return None
        return choose(self, leaf, action)

    SMDPAgent._end_epoch = patched_end_epoch  # type: ignore[method-assign]
    SMDPAgent._model_split = patched_model_split  # type: ignore[method-assign]


def patch(floor: int) -> None:
    """Midpoint splits of the widest dimension while it exceeds ``1 / floor`` of the root's."""

    def midpoint(self: Any, leaf: int, action: int) -> Any:
        partition = self.partition
        low, high = partition.leaf_bounds(leaf)
        roots = zip(low, high, partition.root_low, partition.root_high, strict=True)
        widths = [(h - lo) / (rh - rl) for lo, h, rl, rh in roots]
        dim = max(range(len(widths)), key=widths.__getitem__)
        if widths[dim] <= 1.0 / floor:
            return None
        return partition.split_with_samples(leaf, dim, 0.5 * (low[dim] + high[dim]))

    patch_collision_splits(midpoint)


if __name__ == "__main__":
    maze, seed, label, floor = sys.argv[1], int(sys.argv[2]), sys.argv[3], int(sys.argv[4])
    patch(floor)
    curves.run(maze, seed, label, {}, HERE / "maze_collision.jsonl")
