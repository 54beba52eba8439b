"""A plain continuous test task for the agent: a 2-D box with a goal disc (no simulator)."""

from __future__ import annotations

import importlib.util
import sys
from collections.abc import Callable
from pathlib import Path
from types import ModuleType
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent import TreeAgent


class Corridor(gym.Env[np.ndarray, int]):
    """A point in ``[0, 1]^2`` moved by up/down/left/right steps of ``step`` plus Gaussian noise.

    Rewards as in the paper's maze: +5 at the goal disc (terminates), -1 and no move when a step
    would leave the box (``info["collision"]``), -0.01 otherwise; truncated after ``max_steps``.
    """

    moves = ((0.0, 1.0), (0.0, -1.0), (-1.0, 0.0), (1.0, 0.0))

    def __init__(
        self,
        step: float = 0.1,
        noise: float = 0.01,
        start: tuple[float, float] = (0.15, 0.15),
        goal: tuple[float, float] = (0.85, 0.85),
        goal_radius: float = 0.12,
        max_steps: int = 200,
    ) -> None:
        self.observation_space = spaces.Box(0.0, 1.0, shape=(2,), dtype=np.float64)
        self.action_space = spaces.Discrete(4)
        self.step_size, self.noise = step, noise
        self.start, self.goal, self.goal_radius = np.asarray(start), np.asarray(goal), goal_radius
        self.max_steps = max_steps

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        super().reset(seed=seed)
        self.pos = self.start.copy()
        self.t = 0
        return self.pos.copy(), {}

    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        self.t += 1
        move = np.asarray(self.moves[action]) * self.step_size
        new = self.pos + move + self.np_random.normal(0.0, self.noise, size=2)
        collision = bool((new < 0.0).any() or (new > 1.0).any())
        if not collision:
            self.pos = new
        at_goal = bool(np.linalg.norm(self.pos - self.goal) < self.goal_radius)
        reward = 5.0 if at_goal else (-1.0 if collision else -0.01)
        truncated = self.t >= self.max_steps and not at_goal
        info = {"collision": collision, "is_success": at_goal}
        return self.pos.copy(), reward, at_goal, truncated, info


@pytest.fixture
def make_corridor() -> Callable[..., Corridor]:
    """Factory of :class:`Corridor` envs (keyword arguments as its constructor)."""
    return Corridor


@pytest.fixture
def train_corridor(
    make_corridor: Callable[..., Corridor],
) -> Callable[..., tuple[TreeAgent, list[Any]]]:
    """``train(config, episodes, **env)``: a ``TreeAgent`` (epsilon-greedy, seed 0) of ``config``
    trained on a :class:`Corridor` of ``env`` for ``episodes`` (reset seed 0); returns the agent
    and its history."""

    def train(config: Any, episodes: int, **env: Any) -> tuple[TreeAgent, list[Any]]:
        corridor = make_corridor(**env)
        agent = TreeAgent(
            corridor.observation_space, corridor.action_space, "epsilon-greedy", 0, config
        )
        return agent, agent.learn(corridor, episodes, reset_seed=0)

    return train


EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture
def load_example() -> Callable[[str], ModuleType]:
    """``load_example("mountain_car")``: the module ``examples/<name>.py``, loaded by path."""

    def load(name: str) -> ModuleType:
        spec = importlib.util.spec_from_file_location(f"{name}_example", EXAMPLES / f"{name}.py")
        assert spec is not None
        assert spec.loader is not None
        module = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = module  # dataclasses look their module up while made
        spec.loader.exec_module(module)
        return module

    return load


def _greedy_return(env: gym.Env, agent: Any, seed: int) -> float:
    obs, _ = env.reset(seed=seed)
    total, done = 0.0, False
    while not done:
        obs, reward, terminated, truncated, _ = env.step(agent.predict(obs))
        total += float(reward)
        done = terminated or truncated
    return total


@pytest.fixture
def greedy_return() -> Callable[[gym.Env, Any, int], float]:
    """``greedy_return(env, agent, seed)``: the return of one episode of ``agent.predict``
    from ``env.reset(seed=seed)``."""
    return _greedy_return


def _every_agent_kind(observation_space: spaces.Space, action_space: spaces.Space) -> list[Any]:
    from agent import AdaptiveQAgent, TileCodingAgent, preset

    return [
        preset("paper").agent(observation_space, action_space, 0),
        preset("general").agent(observation_space, action_space, 0),
        AdaptiveQAgent(observation_space, action_space, 0),
        TileCodingAgent(observation_space, action_space, 0),
    ]


@pytest.fixture
def every_agent_kind() -> Callable[[spaces.Space, spaces.Space], list[Any]]:
    """One fresh agent of each kind a user's env meets (the paper's tree, the general tree,
    adaptive Q-learning, the tile coder), seed 0, for ``(observation_space, action_space)``."""
    return _every_agent_kind
