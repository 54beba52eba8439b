"""The agent is generic: it runs on Gymnasium's MountainCar-v0 (examples/mountain_car.py)."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "mountain_car.py"


def test_mountain_car_runs() -> None:
    spec = importlib.util.spec_from_file_location("mountain_car_example", EXAMPLE)
    assert spec is not None
    assert spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up while the class is made
    spec.loader.exec_module(module)
    result = module.train(episodes=3, exploration="adaptive+tabu", seed=0, eval_episodes=1)
    assert len(result.history) == 3
    assert all(s.steps == 200 or s.success for s in result.history)
    assert result.agent.n_actions == 3
    assert len(result.eval_steps) == 1
