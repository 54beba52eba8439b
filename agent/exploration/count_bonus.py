"""A count bonus on the greedy choice: argmax_a Q-bar(s, a) + beta / sqrt(n(s, a)).

The exploration bonus of MBIE-EB (Strehl and Littman, "An analysis of model-based interval
estimation for Markov decision processes", JCSS 74, 2008), ``beta / sqrt(n(s, a))``, applied
here at the choice (as in UCB-style action selection) with n counted in SMDP epochs per
(leaf, action); an action never tried in the leaf is chosen first (ties at random). The
propagated form, where the bonus enters every backup, is ``TreeConfig(planning="sweep",
model_bonus=beta)``. Strehl and Littman tune beta per task (their experiments use values from
0.01 to 10 on rewards in [0, 1]); beta is in reward units, or a multiple of the agent's scale
with ``TreeConfig(threshold_units="scale")``. The default 0.1 is a tenth of the reward range
that paper assumes.
"""

from __future__ import annotations

import math
from typing import Any

from agent.exploration.base import (
    Exploration,
    UniformSource,
    action_counts_from_json,
    greedy_action,
    leaf_table_from_json,
    leaf_table_to_json,
)
from agent.value_checks import check_arguments


def bonus_values(q_row: list[float], counts: list[int], beta: float) -> list[float]:
    """``Q + beta / sqrt(n)`` per action; an untried action (n = 0) gets +inf."""
    return [
        math.inf if n == 0 else v + beta / math.sqrt(n) for v, n in zip(q_row, counts, strict=True)
    ]


class CountBonus(Exploration):
    """Greedy on ``Q-bar + beta / sqrt(n(leaf, a))``.

    A choice that differs from the greedy action of Q-bar alone is exploratory (``explored``,
    held by the learner with ``TreeConfig.hold_exploration``). On a split the children copy
    the parent's counts (``inherit_on_split=True``), so a split does not make every action of
    the new leaves untried again.
    """

    name = "count-bonus"

    def __init__(self, beta: float = 0.1, inherit_on_split: bool = True) -> None:
        check_arguments(
            CountBonus.__init__, self.name, {"beta": beta, "inherit_on_split": inherit_on_split}
        )
        if isinstance(beta, bool) or not isinstance(beta, int | float):
            raise TypeError(f"count-bonus: beta must be a number, got {beta!r}")
        if not (beta >= 0.0 and math.isfinite(beta)):
            raise ValueError(f"count-bonus: beta must be >= 0 and finite, got {beta!r}")
        self.beta = float(beta)
        self.inherit_on_split = bool(inherit_on_split)
        self._counts: dict[int, list[int]] = {}

    def counts(self, leaf: int) -> list[int]:
        """n(leaf, a) for every action."""
        return list(self._counts.get(leaf, [0] * self.n_actions))

    def select(self, leaf: int, q_row: list[float], rng: UniformSource) -> int:
        counts = self._counts.get(leaf)
        if counts is None:
            counts = [0] * len(q_row)
        action = greedy_action(bonus_values(q_row, counts, self.beta * self.unit()), rng)
        self.explored = q_row[action] < max(q_row)
        return action

    def on_epoch_end(self, leaf: int, action: int) -> None:
        counts = self._counts.get(leaf)
        if counts is None:
            counts = self._counts[leaf] = [0] * self.n_actions
        counts[action] += 1

    def on_split(self, parent: int, children: tuple[int, int]) -> None:
        counts = self._counts.pop(parent, None)
        if self.inherit_on_split and counts is not None:
            for child in children:
                self._counts[child] = list(counts)

    def params(self) -> dict[str, Any]:
        return {"beta": self.beta, "inherit_on_split": self.inherit_on_split}

    def state_dict(self) -> dict[str, Any]:
        return {"counts": leaf_table_to_json(self._counts)}

    def load_state_dict(self, state: dict[str, Any]) -> None:
        self._counts = {
            k: action_counts_from_json(k, v, self.n_actions)
            for k, v in leaf_table_from_json(state["counts"]).items()
        }
