"""Probe (part 29, round 1): a double estimator for the model's V-bar of an end leaf.

Today's backups value an end leaf l' by max_a Q-bar(l', a), the largest of noisy means (the
maximisation bias; van Hasselt 2010, "Double Q-learning"). Here each (leaf, action)'s stored
epochs are split into two halves by a fixed hash of their first input (CRC-32 of its bytes,
the same in every process). Whenever the model backs (leaf, action) up, it also keeps each
half's mean eq. (8) target, Q_A and Q_B, bootstrapped as the full mean is, and

    V-bar(l') = (Q_B(l', argmax_a Q_A(l', a)) + Q_A(l', argmax_a Q_B(l', a))) / 2,

an action without an epoch in both halves keeping its Q-bar in both. Only the backups change
(``LeafModel.value``, the sweeps, ``backup_all``); the split tests and ``predict``'s errors read
the stored targets as before. Runs part 28's driver (``offset_trees.py``) with the learner's
model class swapped:

    python double_bootstrap.py TASK OUT LABEL SEED [SEED ...]
"""

from __future__ import annotations

import heapq
import os
import sys
import zlib
from pathlib import Path

HERE = Path(__file__).resolve()
sys.path.insert(0, str(HERE.parents[1] / "issue9_part28_dev"))

from offset_trees import main  # noqa: E402

import agent.learner as learner_module  # noqa: E402
from agent.leaf_model import _NOVEL, LeafModel  # noqa: E402

Half = tuple[float, tuple[tuple[int, float], ...], int]


class DoubleLeafModel(LeafModel):
    """:class:`LeafModel` whose backups read an end leaf's V-bar by the double estimator."""

    def __init__(self, n_actions: int, window: int) -> None:
        super().__init__(n_actions, window)
        self._halves: dict[int, tuple[Half, Half]] = {}
        self._half_q: dict[int, tuple[float, float]] = {}

    def _aggregate(self, key: int) -> None:
        super()._aggregate(key)
        parts: list[list] = [[0.0, {}, 0], [0.0, {}, 0]]
        for first, r, d, end, end_leaf, _ in self._records[key]:
            part = parts[zlib.crc32(first.tobytes()) & 1]
            part[0] += r
            part[2] += 1
            if end_leaf == _NOVEL:
                part[0] += d * self.novel_value
            elif end is not None:
                part[1][end_leaf] = part[1].get(end_leaf, 0.0) + d
        if parts[0][2] and parts[1][2]:
            a, b = parts
            self._halves[key] = (
                (a[0], tuple(a[1].items()), a[2]),
                (b[0], tuple(b[1].items()), b[2]),
            )
        else:
            self._halves.pop(key, None)

    def split(self, parent, children, leaf_of):
        changed = super().split(parent, children, leaf_of)
        for action in range(self.n_actions):
            key = parent * self.n_actions + action
            if key not in self._sums:
                self._halves.pop(key, None)
                self._half_q.pop(key, None)
        return changed

    def v_bar(self, leaf: int, q: list[list[float]]) -> float:
        """The double estimator of ``leaf``'s V-bar: each action's two half means as they
        were when (leaf, action) was last backed up, its Q-bar where it has no two halves."""
        row = q[leaf]
        n = self.n_actions
        halves = self._half_q
        base = leaf * n
        qa = list(row)
        qb = list(row)
        for action in range(n):
            pair = halves.get(base + action)
            if pair is not None:
                qa[action], qb[action] = pair
        best_a = max(range(n), key=qa.__getitem__)
        best_b = max(range(n), key=qb.__getitem__)
        return 0.5 * (qb[best_a] + qa[best_b])

    def value(self, leaf: int, action: int, q: list[list[float]]) -> float | None:
        key = leaf * self.n_actions + action
        entry = self._sums.get(key)
        if entry is None:
            self._half_q.pop(key, None)
            return None
        total, ends, count = entry
        values = {}
        for end_leaf, discount in ends:
            v = values[end_leaf] = self.v_bar(end_leaf, q)
            total += discount * v
        pair = self._halves.get(key)
        if pair is None:
            self._half_q.pop(key, None)
        else:
            out = []
            for half_total, half_ends, half_count in pair:
                for end_leaf, discount in half_ends:
                    half_total += discount * values[end_leaf]
                out.append(half_total / half_count)
            self._half_q[key] = (out[0], out[1])
        return total / count

    def sweep(self, q, budget, tolerance, bonus=None) -> int:
        done = 0
        n_actions = self.n_actions
        while self._queue and done < budget:
            negative, leaf = heapq.heappop(self._queue)
            if self._priority.get(leaf) != -negative:
                continue
            del self._priority[leaf]
            for key in list(self._preds.get(leaf, ())):
                pred, action = divmod(key, n_actions)
                value = self.value(pred, action, q)
                if value is None:
                    continue
                row = q[pred]
                before = max(row)
                if bonus is not None:
                    value += bonus(pred, action)
                row[action] = value
                done += 1
                change = abs(max(row) - before)
                if change > tolerance:
                    self.push(pred, change)
        return done


learner_module.LeafModel = DoubleLeafModel  # the learner builds its model by this name

if os.environ.get("DOUBLE_EPOCHS") == "1":  # round 1b: the epoch's own return agrees
    _end_epoch = learner_module.SMDPAgent._end_epoch

    def _double_end_epoch(self, leaf, action, xs, rs, bootstrap, end_x=None, terminated=False):
        model = self.model
        if isinstance(model, DoubleLeafModel) and end_x is not None and not terminated:
            bootstrap = model.v_bar(self.partition.leaf_of(end_x), self.q)
        return _end_epoch(self, leaf, action, xs, rs, bootstrap, end_x, terminated)

    learner_module.SMDPAgent._end_epoch = _double_end_epoch

if __name__ == "__main__":
    main(sys.argv)
