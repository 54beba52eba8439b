"""Epsilon-greedy with an epsilon that decays over the episodes.

``schedule="exponential"``: ``epsilon_k = max(end, start * decay^k)`` after k episodes, the
common schedule of tabular Q-learning (a GLIE schedule in the limit ``end = 0``: Singh,
Jaakkola, Littman and Szepesvari, "Convergence results for single-step on-policy
reinforcement-learning algorithms", Machine Learning 38, 2000). ``schedule="linear"``: from
``start`` to ``end`` in ``horizon`` episodes, then ``end``, as DQN anneals 1.0 to 0.1 (Mnih et
al., Nature 518, 2015; there over the first million frames). Defaults: 1.0 to 0.01 with
decay 0.99 per episode (epsilon is 0.37 after 100 episodes, 0.01 from episode 459 on).
"""

from __future__ import annotations

import math
from typing import Any, Literal

from agent.exploration.base import Exploration
from agent.value_checks import check_arguments

Schedule = Literal["exponential", "linear"]


def decayed_epsilon(
    episodes: int, start: float, end: float, decay: float, schedule: Schedule, horizon: int
) -> float:
    """Epsilon after ``episodes`` finished episodes."""
    if schedule == "linear":
        if episodes >= horizon:
            return end
        return start + (end - start) * episodes / horizon
    return max(end, start * decay**episodes)


class DecayingEpsilon(Exploration):
    """Epsilon-greedy whose epsilon falls with every finished episode (same in every leaf)."""

    name = "decaying-epsilon"

    def __init__(
        self,
        start: float = 1.0,
        end: float = 0.01,
        decay: float = 0.99,
        schedule: Schedule = "exponential",
        horizon: int = 500,
    ) -> None:
        check_arguments(
            DecayingEpsilon.__init__,
            self.name,
            {"start": start, "end": end, "decay": decay, "schedule": schedule, "horizon": horizon},
        )
        for label, value in (("start", start), ("end", end), ("decay", decay)):
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise TypeError(f"decaying-epsilon: {label} must be a number, got {value!r}")
            if not 0.0 <= value <= 1.0 or math.isnan(value):
                raise ValueError(f"decaying-epsilon: {label} must be in [0, 1], got {value!r}")
        if end > start:
            raise ValueError(f"decaying-epsilon: end ({end}) must not exceed start ({start})")
        if schedule not in ("exponential", "linear"):
            raise ValueError(
                f"decaying-epsilon: schedule must be 'exponential' or 'linear', got {schedule!r}"
            )
        if isinstance(horizon, bool) or not isinstance(horizon, int) or horizon < 1:
            raise ValueError(f"decaying-epsilon: horizon must be an int >= 1, got {horizon!r}")
        self.start, self.end, self.decay = float(start), float(end), float(decay)
        self.schedule: Schedule = schedule
        self.horizon = horizon
        self.episodes = 0
        self._epsilon = self.start

    def epsilon(self, leaf: int) -> float:
        return self._epsilon

    def on_episode_end(self, success: bool) -> None:
        self.episodes += 1
        self._epsilon = decayed_epsilon(
            self.episodes, self.start, self.end, self.decay, self.schedule, self.horizon
        )

    def params(self) -> dict[str, Any]:
        return {
            "start": self.start,
            "end": self.end,
            "decay": self.decay,
            "schedule": self.schedule,
            "horizon": self.horizon,
        }

    def state_dict(self) -> dict[str, Any]:
        return {"episodes": self.episodes}

    def load_state_dict(self, state: dict[str, Any]) -> None:
        self.episodes = int(state["episodes"])
        self._epsilon = decayed_epsilon(
            self.episodes, self.start, self.end, self.decay, self.schedule, self.horizon
        )
