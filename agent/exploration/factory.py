"""Strategies by name: ``make_exploration("adaptive+tabu", c_n=0.001, initial_capacity=20)``.

A name ending in ``+tabu`` wraps the base strategy in :class:`Tabu` (any base composes);
``"tabu"`` alone is epsilon-greedy + tabu. Keyword parameters go to whichever of the two classes
accepts them.
"""

from __future__ import annotations

import inspect
from typing import Any

from agent.exploration.adaptive import AdaptiveEpsilon
from agent.exploration.base import Exploration
from agent.exploration.boltzmann import Boltzmann
from agent.exploration.count_bonus import CountBonus
from agent.exploration.decaying_epsilon import DecayingEpsilon
from agent.exploration.epsilon_greedy import EpsilonGreedy, Greedy
from agent.exploration.optimistic import OptimisticInit
from agent.exploration.tabu import Tabu
from agent.exploration.vdbe import VDBE
from agent.exploration.vdbe_softmax import VDBESoftmax

BASE_STRATEGIES: dict[str, type[Exploration]] = {
    "epsilon-greedy": EpsilonGreedy,
    "greedy": Greedy,
    "adaptive": AdaptiveEpsilon,
    "vdbe": VDBE,
    "boltzmann": Boltzmann,
    "count-bonus": CountBonus,
    "decaying-epsilon": DecayingEpsilon,
    "vdbe-softmax": VDBESoftmax,
    "optimistic": OptimisticInit,
}
STRATEGY_NAMES: tuple[str, ...] = (
    "epsilon-greedy",
    "tabu",
    "adaptive",
    "adaptive+tabu",
    "vdbe",
    "vdbe+tabu",
    "greedy",
    "greedy+tabu",
    "epsilon-greedy+tabu",
    "boltzmann",
    "count-bonus",
    "decaying-epsilon",
    "vdbe-softmax",
    "optimistic",
    "boltzmann+tabu",
    "count-bonus+tabu",
    "decaying-epsilon+tabu",
    "vdbe-softmax+tabu",
    "optimistic+tabu",
)


def _accepted(cls: type) -> set[str]:
    params = inspect.signature(cls).parameters
    return {name for name in params if name != "base"}


def make_exploration(name: str, **params: Any) -> Exploration:
    """Build a strategy from its name (see STRATEGY_NAMES) and keyword parameters."""
    if name not in STRATEGY_NAMES:
        raise ValueError(
            f"unknown exploration strategy {name!r}; choose one of {list(STRATEGY_NAMES)}"
        )
    base_name, tabu = name, False
    if name == "tabu":
        base_name, tabu = "epsilon-greedy", True
    elif name.endswith("+tabu"):
        base_name, tabu = name[: -len("+tabu")], True
    base_cls = BASE_STRATEGIES[base_name]
    base_keys = _accepted(base_cls)
    tabu_keys = _accepted(Tabu) if tabu else set()
    unknown = sorted(set(params) - base_keys - tabu_keys)
    if unknown:
        raise ValueError(
            f"exploration {name!r} has no parameter(s) {unknown}; "
            f"accepted: {sorted(base_keys | tabu_keys)}"
        )
    base = base_cls(**{k: v for k, v in params.items() if k in base_keys})
    if not tabu:
        return base
    return Tabu(base, **{k: v for k, v in params.items() if k in tabu_keys})


def exploration_spec(strategy: Exploration) -> dict[str, Any]:
    """JSON-ready description of a strategy: name, parameters and learned state."""
    if isinstance(strategy, Tabu):
        base_params = strategy.base.params()
        params = {**base_params, **strategy.params()}
        return {"name": strategy.name, "params": params, "state": strategy.state_dict()}
    return {"name": strategy.name, "params": strategy.params(), "state": strategy.state_dict()}


def exploration_from_spec(spec: dict[str, Any]) -> Exploration:
    """Inverse of :func:`exploration_spec` (only for strategies built from these classes)."""
    strategy = make_exploration(spec["name"], **spec["params"])
    strategy.load_state_dict(spec["state"])
    return strategy
