"""Decreasing tabu search (section III.A), wrapping any base strategy.

A FIFO list of (leaf, action) pairs, appended when an epoch ends if not already listed; the
oldest pair is released when the list is full. In the greedy choice a listed action's value is
taken as -inf, so it is not chosen; the base strategy's random choice ignores the list (as the
paper describes the rule; ``random_respects_list=True`` reads the paper's "this action in Tabu
list will not be selected" as covering the random choice too: uniform among the unlisted).
The capacity decreases with the number of successful episodes:
``L_k = max(min_capacity, initial_capacity - floor(k / shrink_every))`` after k successes (the
paper gives no numbers; the defaults shrink the list by one every 10 successes, because with one
per success a few lucky early arrivals emptied it before anything was learnt). When every action
of a leaf is tabu, every value is -inf and the argmax is a tie among all actions, broken at
random (``all_listed="random"``, the default: an exploratory action); ``all_listed="greedy"`` is
classic aspiration, the list ignored for that choice. Aspiration left a cycle over four big
leaves, every action listed and every epsilon near 0, with nothing to explore (docs/results.md,
paper_narrow). An action chosen because the greedy one is listed is reported as exploratory
(``deviation_explores=True``), so the learner holds it like a random one
(``TreeConfig.hold_exploration``). When a leaf splits, its entries are dropped
(``on_split="drop"``) or replaced in place by the same actions of both children
(``on_split="inherit"``).
"""

from __future__ import annotations

from collections import deque
from typing import Any, Literal

from agent.exploration.base import Exploration, RewardUnit, UniformSource, greedy_action
from agent.value_checks import check_arguments

SplitPolicy = Literal["drop", "inherit"]
AllListed = Literal["greedy", "random"]
_NEG_INF = float("-inf")


def tabu_capacity(
    successes: int, initial_capacity: int, shrink_every: int, min_capacity: int
) -> int:
    """The list's capacity after ``successes`` goal arrivals: ``max(L_min, L_0 - floor(k / c))``."""
    return max(min_capacity, initial_capacity - successes // shrink_every)


class Tabu(Exploration):
    """Decreasing tabu list of (leaf, action) pairs in front of a base strategy (section III.A)."""

    def __init__(
        self,
        base: Exploration,
        initial_capacity: int = 20,
        shrink_every: int = 10,
        min_capacity: int = 0,
        on_split: SplitPolicy = "drop",
        random_respects_list: bool = False,
        deviation_explores: bool = True,
        all_listed: AllListed = "random",
    ) -> None:
        check_arguments(
            Tabu.__init__,
            "tabu",
            {
                "base": base,
                "initial_capacity": initial_capacity,
                "shrink_every": shrink_every,
                "min_capacity": min_capacity,
                "on_split": on_split,
                "random_respects_list": random_respects_list,
                "deviation_explores": deviation_explores,
                "all_listed": all_listed,
            },
        )
        if not isinstance(base, Exploration):
            raise TypeError(f"tabu: base must be an Exploration, got {base!r}")
        for label, value, least in (
            ("initial_capacity", initial_capacity, 0),
            ("shrink_every", shrink_every, 1),
            ("min_capacity", min_capacity, 0),
        ):
            if not isinstance(value, int) or value < least:
                raise ValueError(f"tabu: {label} must be an int >= {least}, got {value!r}")
        if on_split not in ("drop", "inherit"):
            raise ValueError(f"tabu: on_split must be 'drop' or 'inherit', got {on_split!r}")
        self.base = base
        self.initial_capacity = initial_capacity
        self.shrink_every = shrink_every
        self.min_capacity = min_capacity
        self.on_split_policy: SplitPolicy = on_split
        self.random_respects_list = bool(random_respects_list)
        self.deviation_explores = bool(deviation_explores)
        if all_listed not in ("greedy", "random"):
            raise ValueError(f"tabu: all_listed must be 'greedy' or 'random', got {all_listed!r}")
        self.all_listed: AllListed = all_listed
        self.successes = 0
        self._capacity = initial_capacity
        self._fifo: deque[tuple[int, int]] = deque()
        self._by_leaf: dict[int, set[int]] = {}  # the same pairs, for an O(1) look-up per leaf

    @property
    def name(self) -> str:  # type: ignore[override]
        return f"{self.base.name}+tabu"

    @property
    def capacity(self) -> int:
        """Current capacity L_k."""
        return self._capacity

    @property
    def entries(self) -> list[tuple[int, int]]:
        """The listed (leaf, action) pairs, oldest first."""
        return list(self._fifo)

    def listed(self, leaf: int) -> frozenset[int]:
        """The actions listed in ``leaf`` now (those :meth:`select` keeps off)."""
        return frozenset(self._by_leaf.get(leaf, ()))

    def bind(self, n_actions: int) -> None:
        super().bind(n_actions)
        self.base.bind(n_actions)

    def use_scale(self, scale: RewardUnit) -> None:
        super().use_scale(scale)
        self.base.use_scale(scale)

    def initial_value(self, gamma: float) -> float | None:
        return self.base.initial_value(gamma)

    def epsilon(self, leaf: int) -> float:
        return self.base.epsilon(leaf)

    def select(self, leaf: int, q_row: list[float], rng: UniformSource) -> int:
        tabu = self._by_leaf.get(leaf)
        if tabu and len(tabu) == len(q_row) and self.all_listed == "random":
            # every value is -inf: the argmax is a tie among all actions, broken at random
            self.explored = True
            return int(rng.random() * len(q_row))
        if not tabu or len(tabu) == len(q_row):  # nothing listed, or aspiration: all listed
            action = self.base.select(leaf, q_row, rng)
            self.explored = self.base.explored
            return action
        masked = [_NEG_INF if a in tabu else v for a, v in enumerate(q_row)]
        if self.random_respects_list:
            if rng.random() < self.base.epsilon(leaf):
                self.explored = True
                allowed = [a for a in range(len(q_row)) if a not in tabu]
                return allowed[int(rng.random() * len(allowed))]
            action = greedy_action(masked, rng)
            explored = False
        else:
            action = self.base.select(leaf, masked, rng)
            explored = self.base.explored
        # The list turned the choice away from the greedy action: an exploratory action too.
        self.explored = explored or (self.deviation_explores and q_row[action] < max(q_row))
        return action

    def update(self, leaf: int, action: int, delta_q: float) -> None:
        self.base.update(leaf, action, delta_q)

    def on_epoch_end(self, leaf: int, action: int) -> None:
        self.base.on_epoch_end(leaf, action)
        tabu = self._by_leaf.get(leaf)
        if tabu is None:
            tabu = self._by_leaf[leaf] = set()
        elif action in tabu:
            return
        tabu.add(action)
        self._fifo.append((leaf, action))
        if len(self._fifo) > self._capacity:
            self._trim()

    def on_episode_end(self, success: bool) -> None:
        self.base.on_episode_end(success)
        if success:
            self.successes += 1
            self._capacity = tabu_capacity(
                self.successes, self.initial_capacity, self.shrink_every, self.min_capacity
            )
            self._trim()

    def on_split(self, parent: int, children: tuple[int, int]) -> None:
        self.base.on_split(parent, children)
        if parent not in self._by_leaf:
            return
        kept: list[tuple[int, int]] = []
        for leaf, action in self._fifo:
            if leaf != parent:
                kept.append((leaf, action))
            elif self.on_split_policy == "inherit":
                kept.extend((child, action) for child in children)
        self._set_entries(kept)
        self._trim()

    def _set_entries(self, pairs: list[tuple[int, int]]) -> None:
        self._fifo = deque(pairs)
        self._by_leaf = {}
        for leaf, action in pairs:
            self._by_leaf.setdefault(leaf, set()).add(action)

    def _trim(self) -> None:
        capacity = self._capacity
        while len(self._fifo) > capacity:
            leaf, action = self._fifo.popleft()
            tabu = self._by_leaf[leaf]
            tabu.discard(action)
            if not tabu:
                del self._by_leaf[leaf]

    def params(self) -> dict[str, Any]:
        return {
            "initial_capacity": self.initial_capacity,
            "shrink_every": self.shrink_every,
            "min_capacity": self.min_capacity,
            "on_split": self.on_split_policy,
            "random_respects_list": self.random_respects_list,
            "deviation_explores": self.deviation_explores,
            "all_listed": self.all_listed,
        }

    def state_dict(self) -> dict[str, Any]:
        return {
            "successes": self.successes,
            "fifo": [list(p) for p in self._fifo],
            "base": self.base.state_dict(),
        }

    def load_state_dict(self, state: dict[str, Any]) -> None:
        """Inverse of :meth:`state_dict`; a ValueError names the first entry that is wrong (a
        count that is not an int >= 0, a listed action outside the bound action count)."""
        successes = state["successes"]
        if isinstance(successes, bool) or not isinstance(successes, int) or successes < 0:
            raise ValueError(f"tabu successes {successes!r} is not an int >= 0")
        fifo = state["fifo"]
        if not isinstance(fifo, list):
            raise ValueError(f"the tabu list {fifo!r} is not a list")
        pairs: list[tuple[int, int]] = []
        n = self.n_actions  # 0 before bind(): no bound to check against
        for entry in fifo:
            ok = isinstance(entry, list) and len(entry) == 2
            ok = ok and all(isinstance(v, int) and not isinstance(v, bool) for v in entry)
            ok = ok and entry[0] >= 0 and entry[1] >= 0 and (n == 0 or entry[1] < n)
            if not ok:
                wanted = "an action >= 0" if n == 0 else f"an action in 0..{n - 1}"
                raise ValueError(f"tabu list entry {entry!r} is not [leaf >= 0, {wanted}]")
            pairs.append((entry[0], entry[1]))
        self.successes = successes
        self._capacity = tabu_capacity(
            self.successes, self.initial_capacity, self.shrink_every, self.min_capacity
        )
        self._set_entries(pairs)
        self.base.load_state_dict(state["base"])

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self.params().items())
        return f"Tabu({self.base!r}, {args})"
