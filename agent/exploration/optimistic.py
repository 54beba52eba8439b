"""Optimistic initialisation: every Q-bar starts at ``r_max / (1 - gamma)``, then greedy.

Even-Dar and Mansour, "Convergence of optimistic and incremental Q-learning" (NIPS 2001):
initialising every Q to ``V_max = R_max / (1 - gamma)``, the largest value any policy can have,
makes greedy Q-learning explore, each action being tried until its value has fallen below the
others'. ``r_max`` is the largest reward of the task (reward units; the maze's goal pays +5,
which is the default; MountainCar, Acrobot and CartPole pay at most 0, 0 and 1). New leaves of
a split copy their parent's values (``TreeConfig.inherit_q``), so the optimism is spent once.
"""

from __future__ import annotations

import math
from typing import Any

from agent.exploration.epsilon_greedy import EpsilonGreedy
from agent.value_checks import check_arguments


class OptimisticInit(EpsilonGreedy):
    """Greedy (or epsilon-greedy with ``epsilon``) over optimistically initialised values."""

    name = "optimistic"

    def __init__(self, r_max: float = 5.0, epsilon: float = 0.0) -> None:
        check_arguments(OptimisticInit.__init__, self.name, {"r_max": r_max, "epsilon": epsilon})
        if isinstance(r_max, bool) or not isinstance(r_max, int | float):
            raise TypeError(f"optimistic: r_max must be a number, got {r_max!r}")
        if not math.isfinite(r_max):
            raise ValueError(f"optimistic: r_max must be finite, got {r_max!r}")
        super().__init__(epsilon)
        self.r_max = float(r_max)

    def initial_value(self, gamma: float) -> float | None:
        """``V_max = r_max / (1 - gamma)`` (``r_max / 1e-12`` is refused: gamma must be < 1)."""
        if gamma >= 1.0:
            raise ValueError(f"optimistic: needs gamma < 1 for r_max / (1 - gamma), got {gamma!r}")
        return self.r_max / (1.0 - gamma)

    def params(self) -> dict[str, Any]:
        return {"r_max": self.r_max, "epsilon": self._epsilon}
