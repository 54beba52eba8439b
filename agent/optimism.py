"""Optimism for untried actions, bounded by what the task has paid (beyond the paper;
``TreeConfig.optimistic_untried``).

Q-bar starts at ``q_init`` (0), which is optimistic only where rewards are at most 0. Where the
task pays a positive reward (FrozenLake's +1 at the goal, Taxi's +20 for a delivery) an action
nobody tried looks as bad as the worst outcome, and once exploration has decayed it is never
tried. R-max (Brafman and Tennenholtz 2002) values what is unknown at the largest return there
is; here that bound is measured: ``best`` is the largest eq. (9) return, without its bootstrap,
of any input of any epoch so far (what the rewards alone have paid inside one epoch).

An action is *untried* in a leaf while no epoch of it started in that leaf or in any leaf it
was split from (a split hands the parent's untried actions to both children). Whenever
``best`` rises, every untried action whose Q-bar is below it is set to it, and the leaves
whose V-bar moved are handed back for the sweeps of ``planning = "sweep"``, so the optimism
reaches the leaves whose epochs end there. Until a positive return is paid nothing changes.
"""

from __future__ import annotations

from typing import Any

MAX_KEYS = 1 << 26
"""Most untried (leaf, action) keys a saved state may list."""


class UntriedOptimism:
    """The untried (leaf, action) pairs of one tree and the bound they are valued at."""

    def __init__(self, n_actions: int, leaves: list[int], best: float) -> None:
        self.n_actions = n_actions
        self.untried: set[int] = {leaf * n_actions + a for leaf in leaves for a in range(n_actions)}
        """Keys ``leaf * n_actions + action`` of the actions no epoch has started with there."""
        self.best = best
        """The largest return paid inside one epoch so far (starts at ``q_init``)."""

    def tried(self, leaf: int, action: int) -> None:
        """An epoch of ``action`` started in ``leaf``."""
        self.untried.discard(leaf * self.n_actions + action)

    def split(self, parent: int, children: tuple[int, int]) -> None:
        """Both children inherit the parent's untried actions."""
        n = self.n_actions
        for action in range(n):
            key = parent * n + action
            if key in self.untried:
                self.untried.discard(key)
                for child in children:
                    self.untried.add(child * n + action)

    def paid(self, value: float, q: list[list[float]]) -> dict[int, float]:
        """An epoch paid ``value``: when it is a new bound, raise every untried Q-bar below it
        to it. Returns each leaf whose V-bar moved, with how far."""
        if not value > self.best:
            return {}
        self.best = value
        moved: dict[int, float] = {}
        for key in sorted(self.untried):
            leaf, action = divmod(key, self.n_actions)
            row = q[leaf]
            if row[action] < value:
                before = max(row)
                row[action] = value
                change = max(row) - before
                if change > 0.0:
                    moved[leaf] = moved.get(leaf, 0.0) + change
        return moved

    def state(self) -> dict[str, Any]:
        """JSON-ready state (:meth:`from_state` restores it)."""
        return {"best": self.best, "untried": sorted(self.untried)}

    @classmethod
    def from_state(cls, n_actions: int, state: Any, leaves: set[int]) -> UntriedOptimism:
        """Inverse of :meth:`state`; ``leaves`` are the tree's leaves (ValueError naming the
        defect otherwise)."""
        if not isinstance(state, dict) or set(state) != {"best", "untried"}:
            raise ValueError(f"optimism state must have keys best and untried, got {state!r:.80}")
        best, keys = state["best"], state["untried"]
        if isinstance(best, bool) or not isinstance(best, int | float) or best != best:
            raise ValueError(f"optimism best {best!r} is not a number")
        if abs(best) == float("inf"):
            raise ValueError(f"optimism best {best!r} is not finite")
        if not isinstance(keys, list) or len(keys) > MAX_KEYS:
            raise ValueError(f"optimism untried must be a list of at most {MAX_KEYS:,} keys")
        for key in keys:
            if isinstance(key, bool) or not isinstance(key, int) or key < 0:
                raise ValueError(f"optimism untried key {key!r} is not an int >= 0")
            if key // n_actions not in leaves:
                raise ValueError(f"optimism untried key {key} is not on a leaf")
        optimism = cls(n_actions, [], float(best))
        optimism.untried = set(keys)
        return optimism
