"""The agent is generic: it runs on Gymnasium's MountainCar-v0 (examples/mountain_car.py)."""

from __future__ import annotations

from collections.abc import Callable
from types import ModuleType


def test_mountain_car_runs(load_example: Callable[[str], ModuleType]) -> None:
    module = load_example("mountain_car")
    result = module.train(episodes=3, exploration="adaptive+tabu", seed=0, eval_episodes=1)
    assert len(result.history) == 3
    assert all(s.steps == 200 or s.success for s in result.history)
    assert result.agent.n_actions == 3
    assert len(result.eval_steps) == 1
