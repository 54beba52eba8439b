"""Boltzmann (softmax) action selection: P(a) proportional to exp(Q-bar(s, a) / tau).

Sutton and Barto, *Reinforcement Learning: An Introduction* (1998), section 2.3 (the Gibbs
distribution; the rule is Luce's, 1959). The temperature tau is in the units of Q-bar, i.e. in
reward units; with ``TreeConfig(threshold_units="scale")`` it is a multiple of the agent's
measured scale. A published default does not exist (Sutton and Barto: "setting tau requires
knowledge of the likely action values"); 1.0 is the value of their 10-armed testbed, whose
rewards have unit variance.
"""

from __future__ import annotations

import math
from typing import Any

from agent.exploration.base import Exploration, UniformSource, greedy_action
from agent.value_checks import check_arguments


def boltzmann_probabilities(q_row: list[float], temperature: float) -> list[float]:
    """``exp(Q / tau) / sum exp(Q / tau)``, computed from ``Q - max Q`` so it never overflows.

    ``temperature == 0`` is the greedy limit: the mass is shared by the maximal actions.
    """
    best = max(q_row)
    if temperature <= 0.0:
        ties = [1.0 if v == best else 0.0 for v in q_row]
        total = sum(ties)
        return [t / total for t in ties]
    weights = [math.exp((v - best) / temperature) for v in q_row]
    total = sum(weights)
    return [w / total for w in weights]


def sample(probabilities: list[float], u: float) -> int:
    """The action whose cumulative probability first exceeds the uniform draw ``u``."""
    cumulative = 0.0
    for action, p in enumerate(probabilities):
        cumulative += p
        if u < cumulative:
            return action
    return max(a for a, p in enumerate(probabilities) if p > 0.0)  # rounding: u near 1


class Boltzmann(Exploration):
    """Softmax over Q-bar with temperature ``temperature`` (reward units; one draw per choice).

    An action other than a greedy one counts as exploratory (``explored``), so the learner may
    hold it (``TreeConfig.hold_exploration``).
    """

    name = "boltzmann"

    def __init__(self, temperature: float = 1.0) -> None:
        check_arguments(Boltzmann.__init__, self.name, {"temperature": temperature})
        if isinstance(temperature, bool) or not isinstance(temperature, int | float):
            raise TypeError(f"boltzmann: temperature must be a number, got {temperature!r}")
        if not (temperature > 0.0 and math.isfinite(temperature)):
            raise ValueError(f"boltzmann: temperature must be > 0 and finite, got {temperature!r}")
        self.temperature = float(temperature)

    def current_temperature(self) -> float:
        """The temperature in reward units now (times the agent's scale, if it has one)."""
        return self.temperature * self.unit()

    def select(self, leaf: int, q_row: list[float], rng: UniformSource) -> int:
        tau = self.current_temperature()
        if tau <= 0.0:  # no scale measured yet
            self.explored = False
            return greedy_action(q_row, rng)
        action = sample(boltzmann_probabilities(q_row, tau), rng.random())
        self.explored = q_row[action] < max(q_row)
        return action

    def params(self) -> dict[str, Any]:
        return {"temperature": self.temperature}
