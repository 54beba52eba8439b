"""Value-difference based exploration, VDBE (Tokic, KI 2010), one epsilon per leaf.

The published reference for the adaptive epsilon of eq. (5): after each update,
``epsilon(s) <- delta f(s) + (1 - delta) epsilon(s)`` with
``f = (1 - exp(-|dQ| / sigma)) / (1 + exp(-|dQ| / sigma))`` (``form="boltzmann"``, Tokic 2010)
or ``f = 1 - exp(-|dQ| / sigma)`` (``form="exponential"``), ``|dQ|`` the change eq. (10) made
and ``delta = 1 / |A|`` by default. Every leaf starts at epsilon = 1.
"""

from __future__ import annotations

import math
from typing import Any, Literal

from agent.exploration.base import (
    Exploration,
    epsilon_from_json,
    leaf_table_from_json,
    leaf_table_to_json,
)
from agent.value_checks import check_arguments

Form = Literal["boltzmann", "exponential"]


def vdbe_epsilon(previous: float, delta_q: float, sigma: float, delta: float, form: Form) -> float:
    """One VDBE step: ``delta f(|dQ|, sigma) + (1 - delta) previous``."""
    decay = math.exp(-abs(delta_q) / sigma)
    f = (1.0 - decay) / (1.0 + decay) if form == "boltzmann" else 1.0 - decay
    return delta * f + (1.0 - delta) * previous


class VDBE(Exploration):
    """Tokic's value-difference based exploration (sigma: inverse sensitivity)."""

    name = "vdbe"

    def __init__(
        self,
        sigma: float = 1.0,
        delta: float | None = None,
        form: Form = "boltzmann",
        inherit_on_split: bool = False,
    ) -> None:
        check_arguments(
            VDBE.__init__,
            self.name,
            {"sigma": sigma, "delta": delta, "form": form, "inherit_on_split": inherit_on_split},
        )
        if not sigma > 0.0:
            raise ValueError(f"vdbe: sigma must be > 0, got {sigma!r}")
        if delta is not None and not 0.0 < delta <= 1.0:
            raise ValueError(f"vdbe: delta must be in (0, 1] or None (1/|A|), got {delta!r}")
        if form not in ("boltzmann", "exponential"):
            raise ValueError(f"vdbe: form must be 'boltzmann' or 'exponential', got {form!r}")
        self.sigma = float(sigma)
        self.delta = delta
        self.form: Form = form
        self.inherit_on_split = bool(inherit_on_split)
        self._epsilon: dict[int, float] = {}

    def epsilon(self, leaf: int) -> float:
        return self._epsilon.get(leaf, 1.0)

    def update(self, leaf: int, action: int, delta_q: float) -> None:
        delta = self.delta if self.delta is not None else 1.0 / self.n_actions
        sigma = self.sigma if self.scale is None else self.sigma * self.scale.value
        if sigma <= 0.0:
            return  # no scale measured yet: no evidence either way
        self._epsilon[leaf] = vdbe_epsilon(
            self._epsilon.get(leaf, 1.0), delta_q, sigma, delta, self.form
        )

    def on_split(self, parent: int, children: tuple[int, int]) -> None:
        eps = self._epsilon.pop(parent, None)
        if self.inherit_on_split and eps is not None:
            for child in children:
                self._epsilon[child] = eps

    def params(self) -> dict[str, Any]:
        return {
            "sigma": self.sigma,
            "delta": self.delta,
            "form": self.form,
            "inherit_on_split": self.inherit_on_split,
        }

    def state_dict(self) -> dict[str, Any]:
        return {"epsilon": leaf_table_to_json(self._epsilon)}

    def load_state_dict(self, state: dict[str, Any]) -> None:
        self._epsilon = {
            k: epsilon_from_json(k, v) for k, v in leaf_table_from_json(state["epsilon"]).items()
        }
