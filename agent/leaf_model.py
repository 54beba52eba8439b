"""An empirical SMDP model over the leaves, and prioritized sweeping through it (beyond the paper).

Eq. (10) moves Q-bar(leaf, a) a step alpha towards one epoch's target, so a value found at the
goal travels back one epoch per visit. With ``TreeConfig(planning="sweep")`` the learner also
keeps, for every (leaf, action), the last ``model_window`` epochs that held the action there:
each as the mean over the epoch's inputs of the rewards' discounted sum (eq. 9 without its
bootstrap), the mean discount ``gamma^(tau - k)`` that eq. (9) applies to V-bar(s'), and the
state the epoch ended in. Q-bar(leaf, a) is then the average of those epochs' eq. (8) targets
under the *current* values,

    Q-bar(l, a) = (1/m) sum_e [ R_e + D_e V-bar(l'_e) ]      (V-bar = 0 after a terminal state),

and a change of V-bar(l) is pushed back to every (leaf, action) whose stored epochs end in l,
largest change first (prioritized sweeping, Moore and Atkeson 1993), up to ``sweep_backups``
backups per epoch. It is Dyna over the tree with the model's expectation instead of sampled
replays. Each epoch also remembers its first input, so that a split hands every stored epoch to
the child that holds where it began, and re-points the epochs that ended in the split leaf to
the child that holds where they ended: after a split both children have values of their own at
once (value propagation after a split). With ``TreeConfig.novelty_cells`` an epoch may instead
end at a *novel end*, valued ``q_init`` after it, until the agent points it at its end leaf
(:mod:`agent.novelty`).

Keys are ``leaf * n_actions + action``. The state is plain data (:meth:`state`).

Stored inputs are compact copies (:data:`Stored`, ``array('d')``: 8 bytes a value, against about
32 for a list of Python floats), and an epoch's end state and the next epoch's first input share
one copy, so a wide input (38 for the lidar) costs a quarter of the memory a list would. A stored
epoch is found by the identity of its copy, the handle :meth:`LeafModel.add` returns.
"""

from __future__ import annotations

import heapq
import math
from array import array
from collections import deque
from collections.abc import Callable, Iterable, Sequence
from typing import Any

Stored = array
"""A stored input: a compact ``array('d')`` copy of the input list the learner passed."""
Record = tuple[Stored, float, float, Stored | None, int, bool]
"""(first input, mean reward part R, mean discount D, end state or None if terminal, end leaf,
whether the epoch ended on a collision: ``TreeConfig.collision_splits`` marks it)."""
_TERMINAL = -1
_NOVEL = -2
"""The end leaf of a novel end (``TreeConfig.novelty_cells``): V-bar after it is
:attr:`LeafModel.novel_value`."""


class LeafModel:
    """Per-(leaf, action) windows of epochs, their aggregates, and a sweep queue."""

    def __init__(self, n_actions: int, window: int) -> None:
        if window < 1:
            raise ValueError(f"model window must be >= 1, got {window!r}")
        self.n_actions = n_actions
        self.window = window
        self._records: dict[int, deque[Record]] = {}
        self._sums: dict[int, tuple[float, tuple[tuple[int, float], ...], int]] = {}
        """Per key with stored epochs: the sum of their R (with D q_init for each novel end),
        each end leaf with the sum of the D of the epochs that end there (in the order the
        leaves first appear in the window), and how many epochs are stored. One lookup gives
        :meth:`value` all it needs."""
        self._preds: dict[int, dict[int, int]] = {}
        """end leaf -> key -> how many of the key's stored epochs end in that leaf."""
        self.epochs: dict[int, int] = {}
        """Epochs ever recorded per key (a split hands each child the epochs it receives)."""
        self._queue: list[tuple[float, int]] = []
        self._priority: dict[int, float] = {}
        self.terminals = 0
        """Terminal epochs ever recorded (``TreeConfig.model_bonus_terminals`` reads it)."""
        self.novel_value = 0.0
        """V-bar after a novel end (the agent sets its ``q_init``; :mod:`agent.novelty`)."""
        self.seen: dict[tuple[int, ...], int] = {}
        """Inputs counted per novelty-grid cell (``TreeConfig.novelty_cells``)."""
        self.last_added: Stored = array("d")
        """The handle of the epoch :meth:`add` stored last (its first input's copy)."""
        self._last_end: tuple[Sequence[float] | None, Stored | None] = (None, None)
        """The input list the last stored epoch ended at and its copy: the next epoch begins
        there, and shares the copy."""

    def count(self, leaf: int, action: int) -> int:
        """Epochs in the window of (leaf, action)."""
        records = self._records.get(leaf * self.n_actions + action)
        return 0 if records is None else len(records)

    def counts(self, leaf: int) -> list[int]:
        """:meth:`count` of every action of ``leaf``."""
        get, base = self._records.get, leaf * self.n_actions
        return [len(r) if (r := get(base + a)) is not None else 0 for a in range(self.n_actions)]

    def add(
        self,
        leaf: int,
        action: int,
        first: Sequence[float],
        reward: float,
        discount: float,
        end: Sequence[float] | None,
        end_leaf: int,
        novel: bool = False,
    ) -> Stored:
        """Store one epoch; ``end=None`` (and any ``end_leaf``) marks a terminal state, and
        ``novel`` a novel end (V-bar after it is :attr:`novel_value`; :mod:`agent.novelty`).

        The inputs are stored as compact copies (:data:`Stored`); ``first`` shares the copy of
        the last epoch's ``end`` when it is that very list, still holding the same values.
        Returns the stored copy of
        ``first``: the handle :meth:`locate`, :meth:`mark_collided`, :meth:`blend` and
        :meth:`restore` find the epoch by."""
        key = leaf * self.n_actions + action
        records = self._records.get(key)
        if records is None:
            records = self._records[key] = deque()
        source, copy = self._last_end
        stored = array("d", first)
        if first is source and copy == stored:  # (unless the caller changed the list since)
            stored = copy
        stored_end = None if end is None else array("d", end)
        self._last_end = (end, stored_end)
        target = _TERMINAL if end is None else _NOVEL if novel else end_leaf
        records.append((stored, reward, discount, stored_end, target, False))
        self._link(target, key, 1)
        if len(records) > self.window:
            old = records.popleft()
            self._link(old[4], key, -1)
        self.epochs[key] = self.epochs.get(key, 0) + 1
        if end is None:
            self.terminals += 1
        self._aggregate(key)
        self.last_added = stored
        return stored

    def value(self, leaf: int, action: int, q: list[list[float]]) -> float | None:
        """The model's Q-bar(leaf, action) under the values ``q`` (None without epochs)."""
        entry = self._sums.get(leaf * self.n_actions + action)
        if entry is None:
            return None
        total, ends, count = entry
        for end_leaf, discount in ends:
            total += discount * max(q[end_leaf])
        return total / count

    def targets(
        self, leaf: int, action: int, q: list[list[float]]
    ) -> tuple[list[Stored], list[float]]:
        """The first input and the eq. (8) target ``R + D V-bar(l')`` under the values ``q`` of
        every stored epoch of (leaf, action), oldest first (``TreeConfig.model_split_epochs``)."""
        records = self._records.get(leaf * self.n_actions + action)
        if not records:
            return [], []
        return [record[0] for record in records], self._target_values(records, q, {})

    def _target_values(
        self, records: Iterable[Record], q: list[list[float]], v_bar: dict[int, float]
    ) -> list[float]:
        """The eq. (8) target ``R + D V-bar(l')`` of each record under ``q``; ``v_bar`` caches
        each end leaf's ``max q[l']`` across calls that share it (the same values either way)."""
        novel = self.novel_value
        values = []
        for _, reward, discount, end, end_leaf, _ in records:
            if end is None:
                values.append(reward)
                continue
            value = novel if end_leaf == _NOVEL else v_bar.get(end_leaf)
            if value is None:
                value = v_bar[end_leaf] = max(q[end_leaf])
            values.append(reward + discount * value)
        return values

    def errors(self, leaf: int, q: list[list[float]]) -> list[float]:
        """The standard error of each action's Q-bar in ``leaf`` under the values ``q``: the
        sample deviation of its stored epochs' eq. (8) targets (:meth:`targets`) over the root
        of their count; infinite with fewer than two (``TreeConfig.greedy_tie_errors``)."""
        out = []
        v_bar: dict[int, float] = {}  # each end leaf's V-bar, read once for all the actions
        for action in range(self.n_actions):
            records = self._records.get(leaf * self.n_actions + action)
            if records is None or len(records) < 2:
                out.append(math.inf)
                continue
            values = self._target_values(records, q, v_bar)
            n = len(values)
            mean = math.fsum(values) / n
            spread = math.fsum((v - mean) ** 2 for v in values) / (n - 1)
            out.append(math.sqrt(spread) / math.sqrt(n))
        return out

    def linked(self, a: int, b: int) -> bool:
        """Whether an epoch stored from leaf ``a`` ends in leaf ``b`` or one from ``b`` ends in
        ``a`` (``TreeConfig.greedy_smoothing_links``)."""
        n = self.n_actions
        return any(key // n == a for key in self._preds.get(b, ())) or any(
            key // n == b for key in self._preds.get(a, ())
        )

    def links(self) -> list[tuple[int, int]]:
        """Every pair ``(a, b)``, ``a < b``, that :meth:`linked` joins, sorted."""
        n = self.n_actions
        pairs = {
            (min(key // n, end), max(key // n, end))
            for end, keys in self._preds.items()
            if end >= 0
            for key in keys
            if key // n != end
        }
        return sorted(pairs)

    def collisions(self, leaf: int, action: int) -> tuple[list[Stored], list[bool]]:
        """The first input of every stored epoch of (leaf, action), oldest first, and whether
        it ended on a collision (``TreeConfig.collision_splits``)."""
        records = self._records.get(leaf * self.n_actions + action)
        if not records:
            return [], []
        return [record[0] for record in records], [record[5] for record in records]

    def mark_collided(self, leaf: int, action: int, first: Stored) -> bool:
        """Mark the stored epoch of (leaf, action) that began at ``first`` (its handle, from
        :meth:`add`) as ended on a collision; False when it is not stored there."""
        i = self.locate(leaf, action, first)
        if i is None:
            return False
        records = self._records[leaf * self.n_actions + action]
        records[i] = (*records[i][:5], True)
        return True

    def locate(self, leaf: int, action: int, first: Stored) -> int | None:
        """The place in the window of (leaf, action) of the stored epoch that began at
        ``first`` (its handle, from :meth:`add`; an equal input is another epoch), or None
        when it is not stored there."""
        records = self._records.get(leaf * self.n_actions + action)
        if records:
            for i, record in enumerate(records):
                if record[0] is first:
                    return i
        return None

    def first_input(self, key: int, index: int) -> Stored:
        """The first input of the stored epoch at ``index`` in the window of ``key`` (the
        handle :meth:`locate` finds it by); a KeyError or IndexError where there is none."""
        records = self._records[key]
        if not 0 <= index < len(records):
            raise IndexError(f"key {key} holds {len(records)} epochs, not one at {index}")
        return records[index][0]

    def blend(
        self, leaf: int, action: int, first: Stored, lam: float, after: float
    ) -> tuple[float, float] | None:
        """``TreeConfig.model_lambda``: the stored epoch of (leaf, action) that began at
        ``first`` (its handle, from :meth:`add`) keeps ``1 - lam`` of its bootstrap and
        takes ``lam`` of the return ``after`` it instead: R + lam D after, (1 - lam) D.
        Returns the epoch's R and D before the blend (:meth:`restore` puts them back), or None
        when the epoch is no longer stored (out of the window, dropped by a split) or was
        terminal (nothing to blend)."""
        i = self.locate(leaf, action, first)
        if i is None:
            return None
        key = leaf * self.n_actions + action
        records = self._records[key]
        begun, reward, discount, end, end_leaf, collided = records[i]
        if end is None:
            return None
        blended = reward + lam * discount * after
        records[i] = (begun, blended, (1.0 - lam) * discount, end, end_leaf, collided)
        self._aggregate(key)
        return reward, discount

    def restore(
        self, leaf: int, action: int, first: Stored, reward: float, discount: float
    ) -> bool:
        """``TreeConfig.model_lambda_episodes``: the stored epoch of (leaf, action) that began
        at ``first`` takes ``reward`` and ``discount`` (its form before :meth:`blend`) back.
        Returns False when it is no longer stored."""
        i = self.locate(leaf, action, first)
        if i is None:
            return False
        key = leaf * self.n_actions + action
        records = self._records[key]
        begun, _, _, end, end_leaf, collided = records[i]
        records[i] = (begun, reward, discount, end, end_leaf, collided)
        self._aggregate(key)
        return True

    def push(self, leaf: int, priority: float) -> None:
        """Ask for the predecessors of ``leaf`` to be backed up (largest priority first)."""
        if priority > self._priority.get(leaf, 0.0):
            self._priority[leaf] = priority
            queue = self._queue
            heapq.heappush(queue, (-priority, leaf))
            if len(queue) > 2 * len(self._priority) + 1024:
                self._drop_stale()

    def _drop_stale(self) -> None:
        """Rebuild the queue from the live priorities. A stale entry (its leaf queued again
        with a larger priority, or already backed up) is skipped when popped and costs no
        backup, and the live entries pop in the order of their (priority, leaf) values
        whatever the heap's layout, so the sweeps back up the same leaves in the same order."""
        self._queue = [(-priority, leaf) for leaf, priority in self._priority.items()]
        heapq.heapify(self._queue)

    def sweep(
        self,
        q: list[list[float]],
        budget: int,
        tolerance: float,
        bonus: Callable[[int, int], float] | None = None,
    ) -> int:
        """Prioritized sweeping: up to ``budget`` backups of the predecessors of queued leaves.

        A backed-up (leaf, action) whose leaf's V-bar moves by more than ``tolerance`` queues
        that leaf in turn. ``bonus(leaf, action)`` is added to each backup (MBIE-EB). Returns
        the number of backups made.
        """
        done = 0
        n_actions = self.n_actions
        sums = self._sums
        while self._queue and done < budget:
            negative, leaf = heapq.heappop(self._queue)
            if self._priority.get(leaf) != -negative:
                continue  # a stale entry: the leaf was queued again with a larger priority
            del self._priority[leaf]
            for key in list(self._preds.get(leaf, ())):
                entry = sums.get(key)
                if entry is None:
                    continue
                value, ends, count = entry  # :meth:`value`, inlined: the sweeps' hot loop
                for end_leaf, discount in ends:
                    value += discount * max(q[end_leaf])
                value /= count
                pred, action = divmod(key, n_actions)
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

    def backup_all(self, q: list[list[float]]) -> dict[int, float]:
        """Set every modelled Q-bar(leaf, action) to its model value under ``q`` (one pass, in
        the order the keys were stored, each backup seeing the ones before it); returns each
        leaf whose V-bar moved, with how far (the caller queues them for the sweeps)."""
        n_actions = self.n_actions
        changes: dict[int, float] = {}
        for key in list(self._records):
            leaf, action = divmod(key, n_actions)
            value = self.value(leaf, action, q)
            if value is None:
                continue
            row = q[leaf]
            before = max(row)
            row[action] = value
            change = abs(max(row) - before)
            if change > 0.0:
                changes[leaf] = changes.get(leaf, 0.0) + change
        return changes

    def split(
        self, parent: int, children: tuple[int, int], leaf_of: Callable[[Sequence[float]], int]
    ) -> list[int]:
        """Re-file the epochs of ``parent`` and those ending in it; returns the keys changed."""
        n_actions = self.n_actions
        changed: set[int] = set()
        for action in range(n_actions):
            key = parent * n_actions + action
            records = self._records.pop(key, None)
            epochs = self.epochs.pop(key, 0)
            self._sums.pop(key, None)
            if records is None:
                continue
            moved = {child: 0 for child in children}
            for record in records:
                self._link(record[4], key, -1)
                child = leaf_of(record[0])
                if child not in moved:
                    continue  # outside both children (a data-grown box): dropped
                moved[child] += 1
                child_key = child * n_actions + action
                bucket = self._records.get(child_key)
                if bucket is None:
                    bucket = self._records[child_key] = deque()
                bucket.append(record)
                self._link(record[4], child_key, 1)
                changed.add(child_key)
            for child, received in moved.items():
                if received:
                    share = received * epochs // len(records)
                    self.epochs[child * n_actions + action] = max(received, share)
        for key in list(self._preds.pop(parent, {})):
            self._repoint(key, parent, leaf_of)
            changed.add(key)
        for key in changed:
            self._aggregate(key)
        self._priority.pop(parent, None)
        return sorted(changed)

    def end_novelty(self, leaf_of: Callable[[Sequence[float]], int]) -> list[int]:
        """Point every novel end at the leaf that holds its end state (``novelty_terminals``
        reached); returns the keys changed, in order."""
        changed = [
            key
            for key, records in self._records.items()
            if any(record[4] == _NOVEL for record in records)
        ]
        for key in changed:
            self._repoint(key, _NOVEL, leaf_of)
            self._aggregate(key)
        return changed

    def _repoint(self, key: int, old: int, leaf_of: Callable[[Sequence[float]], int]) -> None:
        """The stored epochs of ``key`` that end at ``old`` (a split leaf, or :data:`_NOVEL`)
        end at the leaf ``leaf_of`` gives their end state, and are linked to it (the caller
        re-aggregates ``key``)."""
        refiled: deque[Record] = deque()
        for first, reward, discount, end, end_leaf, collided in self._records[key]:
            if end_leaf == old and end is not None:
                end_leaf = leaf_of(end)
                self._link(end_leaf, key, 1)
            refiled.append((first, reward, discount, end, end_leaf, collided))
        self._records[key] = refiled

    def _link(self, end_leaf: int, key: int, change: int) -> None:
        if end_leaf < 0:  # a terminal state or a novel end: no leaf to link
            return
        links = self._preds.get(end_leaf)
        if links is None:
            links = self._preds[end_leaf] = {}
        count = links.get(key, 0) + change
        if count > 0:
            links[key] = count
        else:
            links.pop(key, None)
            if not links:
                del self._preds[end_leaf]

    def _aggregate(self, key: int) -> None:
        """Recompute the key's sums from its window (exact: no running sums that drift)."""
        reward = 0.0
        discount: dict[int, float] = {}
        for _, r, d, end, end_leaf, _ in self._records[key]:
            reward += r
            if end_leaf == _NOVEL:
                reward += d * self.novel_value
            elif end is not None:
                discount[end_leaf] = discount.get(end_leaf, 0.0) + d
        if self._records[key]:
            self._sums[key] = (reward, tuple(discount.items()), len(self._records[key]))
        else:
            self._sums.pop(key, None)

    def state(self) -> dict[str, Any]:
        """JSON-ready state: every stored epoch, the epoch counts, the predecessor links and the
        sweep queue, each in its order (a sweep visits predecessors in the links' order and
        pops the heap as it lies, so a restored model continues bit for bit). An epoch that
        ended on a collision has a sixth entry, ``True`` (``TreeConfig.collision_splits``);
        the others have five, as before that field."""
        state: dict[str, Any] = {
            "window": self.window,
            "records": [
                [key, [_record_state(record) for record in rs]] for key, rs in self._records.items()
            ],
            "epochs": [[k, n] for k, n in self.epochs.items()],
            "preds": [
                [leaf, [[k, n] for k, n in links.items()]] for leaf, links in self._preds.items()
            ],
            "heap": [[p, leaf] for p, leaf in self._queue],
            "priority": [[leaf, p] for leaf, p in self._priority.items()],
            "terminals": self.terminals,
        }
        if self.seen:  # TreeConfig.novelty_cells
            state["seen"] = [[list(cell), n] for cell, n in self.seen.items()]
        return state

    @classmethod
    def from_state(
        cls,
        n_actions: int,
        state: dict[str, Any],
        novel_value: float = 0.0,
        *,
        dims: int | None = None,
        leaves: set[int] | None = None,
    ) -> LeafModel:
        """Inverse of :meth:`state`; ``novel_value`` is V-bar after a novel end. With ``dims``
        every stored input must have that many values, and with ``leaves`` every key's leaf
        and every end leaf must be one of them (a ValueError names the first that is not)."""
        model = cls(n_actions, _count(state["window"], 1, "window"))
        model.novel_value = novel_value
        for key, records in _pairs(state["records"], "records"):
            _count(key, 0, "key")
            if not isinstance(records, list):
                raise ValueError(f"the model's epochs of key {key} are not a list: {records!r}")
            if leaves is not None and key // n_actions not in leaves:
                raise ValueError(f"the model's key {key} is not a leaf's (leaf {key // n_actions})")
            bucket = model._records[key] = deque()
            for i, entry in enumerate(records):
                try:
                    record = _record_from_state(entry, dims)
                    if leaves is not None and record[4] >= 0 and record[4] not in leaves:
                        raise ValueError(f"its end leaf {record[4]} is not a leaf")
                except ValueError as error:
                    raise ValueError(
                        f"the model's stored epoch {i} of key {key}: {error}"
                    ) from None
                bucket.append(record)
            model._aggregate(key)
        model.epochs = {
            _count(k, 0, "epoch count's key"): _count(n, 0, f"epoch count of key {k}")
            for k, n in _pairs(state["epochs"], "epoch counts")
        }
        model._preds = {
            _count(leaf, 0, "predecessor leaf"): {
                _count(k, 0, f"predecessor of leaf {leaf}"): _count(n, 1, f"link {leaf} <- {k}")
                for k, n in _pairs(links, f"predecessors of leaf {leaf}")
            }
            for leaf, links in _pairs(state["preds"], "predecessor links")
        }
        expected: dict[int, dict[int, int]] = {}
        for key, bucket in model._records.items():
            for record in bucket:
                if record[4] >= 0:
                    links = expected.setdefault(record[4], {})
                    links[key] = links.get(key, 0) + 1
        if {leaf: dict(sorted(v.items())) for leaf, v in model._preds.items()} != {
            leaf: dict(sorted(v.items())) for leaf, v in expected.items()
        }:
            raise ValueError("the model's predecessor links do not match its epochs")
        model._queue = []
        for p, leaf in _pairs(state["heap"], "sweep queue"):  # entries are (-priority, leaf)
            number = isinstance(p, int | float) and not isinstance(p, bool)
            priority = _priority(-p if number else p, f"sweep queue's entry for leaf {leaf!r}")
            model._queue.append((-priority, _count(leaf, 0, "sweep queue's leaf")))
        heapq.heapify(model._queue)
        model._priority = {
            _count(leaf, 0, "queued leaf"): _priority(p, f"queued leaf {leaf}")
            for leaf, p in _pairs(state["priority"], "queued priorities")
        }
        if leaves is not None and not set(model._priority) <= leaves:
            stray = sorted(set(model._priority) - leaves)[:5]
            raise ValueError(f"the model queues leaves that are not leaves: {stray}")
        terminals = state.get("terminals", 0)  # absent in files written before the field
        if isinstance(terminals, bool) or not isinstance(terminals, int) or terminals < 0:
            raise ValueError(f"the model's terminal count {terminals!r} is not an int >= 0")
        model.terminals = terminals
        model.seen = _seen_cells(state.get("seen", []))  # absent in files before the field
        return model


def _count(value: Any, least: int, what: str) -> int:
    """``value`` if it is an int >= ``least`` (a ValueError naming ``what`` otherwise)."""
    if isinstance(value, bool) or not isinstance(value, int) or value < least:
        raise ValueError(f"the model's {what} is {value!r}, not an int >= {least}")
    return value


def _priority(value: Any, what: str) -> float:
    """``value`` as a float if it is a finite number > 0 (a sweep priority)."""
    ok = isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)
    if not ok or value <= 0:
        raise ValueError(f"the model's {what} has priority {value!r}, not a number > 0")
    return float(value)


def _pairs(entries: Any, what: str) -> list[tuple[Any, Any]]:
    """The ``[a, b]`` pairs of a saved list (a ValueError naming ``what`` otherwise)."""
    if not isinstance(entries, list) or not all(
        isinstance(e, list) and len(e) == 2 for e in entries
    ):
        raise ValueError(f"the model's {what} must be a list of pairs, got {entries!r:.120}")
    return [(a, b) for a, b in entries]


def _seen_cells(entries: Any) -> dict[tuple[int, ...], int]:
    """The novelty counts of a saved model (``[[cell, count], ...]``), checked."""
    if not isinstance(entries, list):
        raise ValueError(f"the model's seen cells {entries!r} are not a list")
    seen: dict[tuple[int, ...], int] = {}
    for entry in entries:
        ok = isinstance(entry, list) and len(entry) == 2 and isinstance(entry[0], list)
        if ok:
            cell, count = entry
            ok = all(isinstance(i, int) and not isinstance(i, bool) and i >= 0 for i in cell)
            ok = ok and isinstance(count, int) and not isinstance(count, bool) and count >= 1
        if not ok:
            raise ValueError(
                f"the model's seen cell {entry!r} is not [[index >= 0, ...], count >= 1]"
            )
        if tuple(cell) in seen:
            raise ValueError(f"the model's seen cell {cell!r} is listed twice")
        seen[tuple(cell)] = count
    return seen


def _record_state(record: Record) -> list[Any]:
    """One stored epoch as JSON-ready data (:meth:`LeafModel.state`)."""
    first, reward, discount, end, end_leaf, collided = record
    entry = [list(first), reward, discount, None if end is None else list(end), end_leaf]
    return [*entry, True] if collided else entry


def _record_from_state(entry: Any, dims: int | None = None) -> Record:
    """Inverse of :func:`_record_state`; a sixth entry must be ``True``. With ``dims`` the
    inputs must have that many values. A ValueError says what is wrong."""
    if not isinstance(entry, list | tuple) or len(entry) not in (5, 6):
        raise ValueError(f"a stored epoch of the model must have 5 or 6 entries, got {entry!r}")
    if len(entry) == 6 and entry[5] is not True:
        raise ValueError(f"a stored epoch's collision mark must be true, got {entry[5]!r}")
    first, reward, discount, end, end_leaf = entry[:5]
    for name, value in (("R", reward), ("D", discount)):
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise ValueError(f"its {name} {value!r} is not a number")
    if not 0.0 <= discount <= 1.0:  # a mean of gamma^k (a blend keeps a share of one)
        raise ValueError(f"its D {discount!r} is not in [0, 1]")
    if isinstance(end_leaf, bool) or not isinstance(end_leaf, int) or end_leaf < _NOVEL:
        raise ValueError(f"its end leaf {end_leaf!r} is not an int >= {_NOVEL}")
    if (end is None) != (end_leaf == _TERMINAL):
        raise ValueError(f"its end state {end!r} and end leaf {end_leaf} disagree on terminal")
    return (
        _input_from_state("first input", first, dims),
        float(reward),
        float(discount),
        None if end is None else _input_from_state("end state", end, dims),
        end_leaf,
        len(entry) == 6,
    )


def _input_from_state(name: str, values: Any, dims: int | None) -> Stored:
    """A stored input from its saved list, checked (a list of numbers, ``dims`` of them)."""
    ok = isinstance(values, list) and all(
        isinstance(v, int | float) and not isinstance(v, bool) for v in values
    )
    if not ok or (dims is not None and len(values) != dims):
        wanted = "numbers" if dims is None else f"{dims} numbers"
        raise ValueError(f"its {name} must be a list of {wanted}, got {values!r}")
    return array("d", values)
