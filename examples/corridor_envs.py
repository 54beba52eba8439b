"""Your own env in the harness: a module that registers it when imported (``run.py --env-module``).

    PYTHONPATH=examples python run.py --env-module corridor_envs experiment \
        examples/corridor_tasks.toml

``run.py`` imports this module in its own process and in every worker before a run, so the ids
registered below are accepted by an experiment file like any of Gymnasium's. The env's source is
part of its runs' recorded inputs: edit a statement here and the runs computed before the edit
are named and never mixed with new ones (docs/experiments.md, "Your own envs").

``Corridor`` is a one-dimensional corridor of ``length`` cells: action 1 moves right, 0 left,
every step pays -1, and the last cell ends the episode (the optimum is ``length`` - 1 steps).
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces


class Corridor(gym.Env[np.ndarray, np.int64]):
    """Walk right to the end of a corridor; -1 a step."""

    def __init__(self, length: int = 10, render_mode: str | None = None) -> None:
        if isinstance(length, bool) or not isinstance(length, int) or length < 2:
            raise ValueError(f"Corridor: length must be an int >= 2, got {length!r}")
        self.length = length
        self.render_mode = render_mode
        self.observation_space = spaces.Box(0.0, float(length - 1), (1,), np.float32)
        self.action_space = spaces.Discrete(2)
        self.cell = 0

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        super().reset(seed=seed)
        self.cell = 0
        return np.array([0.0], np.float32), {}

    def step(self, action: np.int64) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        move = 1 if int(action) == 1 else -1
        self.cell = min(self.length - 1, max(0, self.cell + move))
        observation = np.array([float(self.cell)], np.float32)
        return observation, -1.0, self.cell == self.length - 1, False, {}


gym.register("Corridor-v0", entry_point="corridor_envs:Corridor", max_episode_steps=200)
gym.register(
    "LongCorridor-v0",
    entry_point="corridor_envs:Corridor",
    kwargs={"length": 40},
    max_episode_steps=400,
)
