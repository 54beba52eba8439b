"""VDBE-Softmax (Tokic and Palm, KI 2011): VDBE's epsilon decides *whether* to explore, a
Boltzmann distribution over Q-bar *which* action.

Tokic and Palm, "Value-difference based exploration: adaptive control between epsilon-greedy
and softmax" (KI 2011, LNAI 7006), Algorithm 1: with probability epsilon(s) the action is drawn
from ``softmax(Q-bar(s, .) / tau)``, else the greedy one; epsilon(s) follows VDBE's update
(Tokic 2010; :mod:`agent.exploration.vdbe`) with the Boltzmann form of the value difference
and ``delta = 1 / |A|``. sigma and tau are in reward units (multiples of the agent's scale with
``TreeConfig(threshold_units="scale")``); the defaults are VDBE's sigma = 1 and tau = 1.
"""

from __future__ import annotations

import math
from typing import Any

from agent.exploration.base import UniformSource, greedy_action
from agent.exploration.boltzmann import boltzmann_probabilities, sample
from agent.exploration.vdbe import VDBE
from agent.value_checks import check_arguments


class VDBESoftmax(VDBE):
    """VDBE's per-leaf epsilon, exploring by a softmax over Q-bar instead of uniformly."""

    name = "vdbe-softmax"

    def __init__(
        self,
        sigma: float = 1.0,
        temperature: float = 1.0,
        delta: float | None = None,
        inherit_on_split: bool = False,
    ) -> None:
        check_arguments(
            VDBESoftmax.__init__,
            self.name,
            {
                "sigma": sigma,
                "temperature": temperature,
                "delta": delta,
                "inherit_on_split": inherit_on_split,
            },
        )
        if isinstance(temperature, bool) or not isinstance(temperature, int | float):
            raise TypeError(f"vdbe-softmax: temperature must be a number, got {temperature!r}")
        if not (temperature > 0.0 and math.isfinite(temperature)):
            raise ValueError(
                f"vdbe-softmax: temperature must be > 0 and finite, got {temperature!r}"
            )
        super().__init__(sigma, delta, "boltzmann", inherit_on_split)
        self.temperature = float(temperature)

    def select(self, leaf: int, q_row: list[float], rng: UniformSource) -> int:
        if rng.random() < self.epsilon(leaf):
            tau = self.temperature * self.unit()
            if tau > 0.0:
                action = sample(boltzmann_probabilities(q_row, tau), rng.random())
            else:
                action = int(rng.random() * len(q_row))
            self.explored = True
            return action
        self.explored = False
        return greedy_action(q_row, rng)

    def params(self) -> dict[str, Any]:
        return {
            "sigma": self.sigma,
            "temperature": self.temperature,
            "delta": self.delta,
            "inherit_on_split": self.inherit_on_split,
        }
