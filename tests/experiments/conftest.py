"""Fixtures of the harness tests: a small experiment and the stand-in learner."""

from __future__ import annotations

import copy
import importlib
import sys
from pathlib import Path
from types import ModuleType

import pytest

from experiments.config import ExperimentConfig, parse_config

HERE = Path(__file__).resolve().parent

SMALL = {
    "experiment": {
        "name": "small",
        "seed": 7,
        "runs": 3,
        "episodes": 120,
        "baseline": "eps",
        "smoothing_window": 10,
        "final_window": 20,
    },
    "env": {"maze": "paper", "max_episode_steps": 300},
    "agent": {"alpha": 0.3, "gamma": 0.99},
    "strategy": [
        {"name": "eps", "exploration": "epsilon-greedy", "exploration_params": {"epsilon": 0.015}},
        {"name": "adaptive+tabu", "exploration": "adaptive+tabu"},
    ],
}


@pytest.fixture
def small_data() -> dict:
    """The parsed TOML of a small experiment (a fresh copy to edit)."""
    return copy.deepcopy(SMALL)


@pytest.fixture
def small_config(small_data: dict) -> ExperimentConfig:
    """Two strategies x 3 runs x 120 episodes, validated like a file."""
    return parse_config(small_data, source="small.toml")


@pytest.fixture
def standins(monkeypatch: pytest.MonkeyPatch) -> ModuleType:
    """The stand-in learner, importable as ``standins`` here and in spawned workers."""
    monkeypatch.syspath_prepend(str(HERE))
    monkeypatch.setenv("PYTHONPATH", str(HERE), prepend=":")
    module = importlib.import_module("standins")
    yield module
    sys.modules.pop("standins", None)
