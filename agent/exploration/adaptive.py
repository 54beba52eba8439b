"""The entropy-based adaptive epsilon of section III.B, eqs. (2)-(5), one epsilon per leaf.

After each update of eq. (10) in a leaf, that leaf's epsilon is recomputed from its action counts
N(s, a) (one count per epoch that held the action) and the change Delta-Q that eq. (10) made.
A leaf without counts has epsilon = 1 (the paper's initial value). The children of a split
inherit their parent's counts and epsilon (``inherit_on_split=True``): a child is part of a
state whose exploration has already run its course; restarting every new leaf at epsilon = 1
kept the growing tree exploring for ever (docs/paper-notes.md, item 5).
"""

from __future__ import annotations

import math
from typing import Any, Literal

from agent.exploration.base import (
    Exploration,
    action_counts_from_json,
    epsilon_from_json,
    leaf_table_from_json,
    leaf_table_to_json,
)
from agent.value_checks import check_arguments

Variant = Literal["literal", "cn_exponent"]


def action_probabilities(counts: list[int]) -> list[float]:
    """Eq. (2): ``P(s, a_i) = N(s, a_i) / sum_a N(s, a)``, all 0 when the leaf has no counts."""
    total = sum(counts)
    if total == 0:
        return [0.0] * len(counts)
    return [n / total for n in counts]


def entropy(probabilities: list[float]) -> float:
    """Eq. (3): ``H(s) = -sum_i P(s, a_i) ln P(s, a_i)`` with ``0 ln 0 = 0`` (natural log)."""
    return -sum(p * math.log(p) for p in probabilities if p > 0.0)


def normalized_entropy(counts: list[int]) -> float:
    """Eq. (4): ``H-bar(s) = H(s) / ln |A|`` in [0, 1] (0 when there is a single action)."""
    if len(counts) < 2:
        return 0.0
    return entropy(action_probabilities(counts)) / math.log(len(counts))


def adaptive_epsilon(
    counts: list[int],
    delta_q: float,
    c_n: float = 0.001,
    c_h: float = 0.025,
    variant: Variant = "literal",
    unit: float = 1.0,
) -> float:
    """Eq. (5): the leaf's exploration rate from its counts and the last Delta-Q.

    With ``n = sum_a N(s, a)`` and ``h = H-bar(s)``:
    ``epsilon = (1 - h)(1 - exp(-|dQ| / n))`` if ``|dQ| / (n C_n) < C_h``, else ``1 - h``.
    ``variant="cn_exponent"`` reads the exponent as ``-|dQ| / (n C_n)`` (C_n scaling both places).
    A leaf with no counts gets epsilon = 1. ``unit`` (beyond the paper; 1 as printed) is the
    reward unit |dQ| is measured in (the agent's scale with ``threshold_units="scale"``).
    """
    total = sum(counts)
    if total == 0:
        return 1.0
    h = 0.0  # eqs. (2)-(4) inline: this runs once per epoch
    for n in counts:
        if n:
            p = n / total
            h -= p * math.log(p)
    unused = 1.0 - (h / math.log(len(counts)) if len(counts) > 1 else 0.0)
    if unit == 1.0:
        magnitude = abs(delta_q)
    elif unit > 0.0:
        magnitude = abs(delta_q) / unit
    else:  # no scale measured yet (every return so far equal): any change is large
        magnitude = math.inf if delta_q != 0.0 else 0.0
    if magnitude / (total * c_n) < c_h:
        scale = total * c_n if variant == "cn_exponent" else total
        return unused * (1.0 - math.exp(-magnitude / scale))
    return unused


class AdaptiveEpsilon(Exploration):
    """Per-leaf epsilon of eqs. (2)-(5) (Table I: C_n = 0.001, C_h = 0.025)."""

    name = "adaptive"

    def __init__(
        self,
        c_n: float = 0.001,
        c_h: float = 0.025,
        variant: Variant = "literal",
        inherit_on_split: bool = True,
    ) -> None:
        check_arguments(
            AdaptiveEpsilon.__init__,
            self.name,
            {"c_n": c_n, "c_h": c_h, "variant": variant, "inherit_on_split": inherit_on_split},
        )
        if not c_n > 0.0:
            raise ValueError(f"adaptive: c_n must be > 0, got {c_n!r}")
        if not c_h >= 0.0:
            raise ValueError(f"adaptive: c_h must be >= 0, got {c_h!r}")
        if variant not in ("literal", "cn_exponent"):
            raise ValueError(
                f"adaptive: variant must be 'literal' or 'cn_exponent', got {variant!r}"
            )
        self.c_n = float(c_n)
        self.c_h = float(c_h)
        self.variant: Variant = variant
        self.inherit_on_split = bool(inherit_on_split)
        self._counts: dict[int, list[int]] = {}
        self._epsilon: dict[int, float] = {}

    def epsilon(self, leaf: int) -> float:
        return self._epsilon.get(leaf, 1.0)

    def counts(self, leaf: int) -> list[int]:
        """N(leaf, a) for every action (zeros for a leaf never updated)."""
        return list(self._counts.get(leaf, [0] * self.n_actions))

    def update(self, leaf: int, action: int, delta_q: float) -> None:
        counts = self._counts.get(leaf)
        if counts is None:
            counts = self._counts[leaf] = [0] * self.n_actions
        counts[action] += 1
        self._epsilon[leaf] = adaptive_epsilon(
            counts, delta_q, self.c_n, self.c_h, self.variant, self.unit()
        )

    def on_split(self, parent: int, children: tuple[int, int]) -> None:
        counts = self._counts.pop(parent, None)
        eps = self._epsilon.pop(parent, None)
        if self.inherit_on_split and counts is not None and eps is not None:
            for child in children:
                self._counts[child] = list(counts)
                self._epsilon[child] = eps

    def params(self) -> dict[str, Any]:
        return {
            "c_n": self.c_n,
            "c_h": self.c_h,
            "variant": self.variant,
            "inherit_on_split": self.inherit_on_split,
        }

    def state_dict(self) -> dict[str, Any]:
        return {
            "counts": leaf_table_to_json(self._counts),
            "epsilon": leaf_table_to_json(self._epsilon),
        }

    def load_state_dict(self, state: dict[str, Any]) -> None:
        """Inverse of :meth:`state_dict`; a ValueError names a leaf whose counts are not one
        int >= 0 per action (the probabilities are checked by the agent file's loader)."""
        self._counts = {
            leaf: action_counts_from_json(leaf, row, self.n_actions)
            for leaf, row in leaf_table_from_json(state["counts"]).items()
        }
        self._epsilon = {
            k: epsilon_from_json(k, v) for k, v in leaf_table_from_json(state["epsilon"]).items()
        }
