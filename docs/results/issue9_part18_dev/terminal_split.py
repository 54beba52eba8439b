"""Issue 9, part 18 (development): terminal splits, a prototype patched into this process.

Part 14's collision splits cut a leaf where one action's stored epochs that ended on a
collision and those that did not part. This prototype does the same for epochs that ended on a
*terminal* state: after an epoch that ended on a terminal, when no other test split its leaf,
the stored epochs of (leaf, action) are labelled terminal or not, and
``agent.collision_split.choose_collision_split`` picks the cut. MODE ``all`` cuts after every
terminal; ``fail`` only after a *failure*: the terminal step's reward is below the leaf's best
Q-bar before the epoch's update, so that stopping there loses value (CartPole's fall, +1
against a Q-bar of many steps; never a maze's goal, +5 against at most about 5, nor
MountainCar's or Acrobot's, -1 against a Q-bar below -1). The agent's code is not changed: ``TreeAgent._end_epoch`` is wrapped here, which also
turns the compiled maze loop off (its fingerprint no longer matches), so maze jobs run the
reference loop. From ``general_as_of(17)``::

    python docs/results/issue9_part18_dev/terminal_split.py classic TASK SEED LABEL MODE OUT
    python docs/results/issue9_part18_dev/terminal_split.py maze LAYOUT SEED LABEL MODE OUT

MODE ``none`` runs the preset unpatched through the same driver.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "issue9_classic_dev"))
sys.path.insert(0, str(HERE.parent / "issue9_hold_terminals_dev"))

import curves  # noqa: E402
import dev  # noqa: E402

from agent import general_as_of  # noqa: E402
from agent.collision_split import choose_collision_split  # noqa: E402
from agent.tree_agent import TreeAgent  # noqa: E402

COUNTS = {"terminal_epochs": 0, "failures": 0, "splits": 0}


def patch(mode: str) -> None:
    original = TreeAgent._end_epoch

    def end_epoch(self, leaf, action, xs, rs, bootstrap, end_x=None, terminated=False):  # type: ignore[no-untyped-def]
        failure = terminated and rs[-1] < max(self.q[leaf])
        split = original(self, leaf, action, xs, rs, bootstrap, end_x, terminated)
        if not terminated or split or self.model is None:
            return split
        COUNTS["terminal_epochs"] += 1
        if mode == "fail" and not failure:
            return split
        COUNTS["failures"] += 1
        held = self.partition.leaf_of(xs[0])
        partition = self.partition
        if not partition.may_split():
            return split
        records = self.model._records.get(held * self.n_actions + action)
        if not records:
            return split
        firsts = np.asarray([r[0] for r in records], dtype=np.float64)
        ended = np.asarray([r[3] is None for r in records], dtype=np.bool_)
        low, high, _, min_width = partition.split_box(held)
        choice = choose_collision_split(firsts, ended, low, high, min_width)
        if choice is None:
            return split
        self._grow(held, partition.split_with_samples(held, *choice))
        COUNTS["splits"] += 1
        return True

    TreeAgent._end_epoch = end_epoch  # type: ignore[method-assign]


if __name__ == "__main__":
    kind, case, seed, label, mode, out = sys.argv[1:7]
    if mode != "none":
        patch(mode)
    if kind == "classic":
        dev.run(case, label, {}, int(seed), out=Path(out), base=general_as_of(17))
    else:
        curves.run(case, int(seed), label, {}, Path(out), base=general_as_of(17))
    print(label, case, seed, COUNTS, file=sys.stderr)
