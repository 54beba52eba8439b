"""Fixed-epsilon exploration: epsilon-greedy (the paper's baseline, section III) and greedy."""

from __future__ import annotations

import math
from typing import Any

from agent.exploration.base import Exploration
from agent.value_checks import check_arguments


class EpsilonGreedy(Exploration):
    """Random action with a fixed probability ``epsilon`` (Table I: 0.015), else greedy."""

    name = "epsilon-greedy"

    def __init__(self, epsilon: float = 0.015) -> None:
        check_arguments(EpsilonGreedy.__init__, self.name, {"epsilon": epsilon})
        if not (0.0 <= epsilon <= 1.0) or math.isnan(epsilon):
            raise ValueError(f"{self.name}: epsilon must be in [0, 1], got {epsilon!r}")
        self._epsilon = float(epsilon)

    def epsilon(self, leaf: int) -> float:
        return self._epsilon

    def params(self) -> dict[str, Any]:
        return {"epsilon": self._epsilon}


class Greedy(EpsilonGreedy):
    """Always the greedy action (ties broken at random): epsilon-greedy with epsilon = 0."""

    name = "greedy"

    def __init__(self) -> None:
        super().__init__(0.0)

    def params(self) -> dict[str, Any]:
        return {}
