"""The agents a ``[[strategy]]`` can name, and the checked parameters of the fixed baselines.

``agent = "tree"`` (the paper's adaptive tree) and ``"grid"`` (a uniform grid) are SMDP agents
configured by ``TreeConfig`` fields (``[agent]``, ``config``) and an exploration strategy, or by
a named ``preset`` (:mod:`agent.presets`). ``"tile"`` (:class:`agent.TileCodingAgent`, Sutton's
tile coding with linear Sarsa(lambda)) and ``"adaptive-q"`` (:class:`agent.AdaptiveQAgent`,
Sinclair, Banerjee and Yu's adaptive Q-learning) are whole learners with their own exploration;
a strategy gives their constructor arguments in ``agent_params`` (their published defaults
otherwise). The harness supplies the observation and action spaces, the seed and the
observation box, so those are not parameters.
"""

from __future__ import annotations

import dataclasses
import inspect
from collections.abc import Mapping
from functools import cache
from typing import Any, get_type_hints

from gymnasium import spaces

from agent import AdaptiveQAgent, TileCodingAgent
from agent.presets import PRESETS, Preset
from agent.value_checks import check_value

SMDP_AGENTS = ("tree", "grid")
"""Agents configured by ``TreeConfig`` fields and an exploration strategy."""
FIXED_AGENTS: dict[str, type] = {"tile": TileCodingAgent, "adaptive-q": AdaptiveQAgent}
"""Baselines with their own learning rule, configured by ``agent_params`` only."""
AGENT_KINDS = (*SMDP_AGENTS, *FIXED_AGENTS)
"""Every value of a strategy's ``agent``."""
PRESET_NAMES = tuple(sorted(PRESETS))
"""Every value of a strategy's ``preset``."""
HARNESS_ARGUMENTS = ("observation_space", "action_space", "seed", "bounds", "collision_key")
"""Constructor arguments the harness gives, never a strategy."""


def is_fixed(kind: str) -> bool:
    """Whether ``kind`` is a baseline configured by ``agent_params`` alone."""
    return kind in FIXED_AGENTS


@cache
def parameters(kind: str) -> dict[str, tuple[Any, Any]]:
    """The ``agent_params`` of a fixed agent: name -> (annotation, default)."""
    constructor = vars(FIXED_AGENTS[kind])["__init__"]
    hints = get_type_hints(constructor)
    return {
        name: (hints.get(name, Any), p.default)
        for name, p in inspect.signature(constructor).parameters.items()
        if name != "self" and name not in HARNESS_ARGUMENTS
    }


def check_agent_params(kind: str, params: Any, where: str) -> dict[str, Any]:
    """``params`` checked for agent ``kind``: known names, strict types, and values the
    constructor accepts (tried on a one-dimensional box); ``where`` names the source in every
    error (a ValueError)."""
    if not isinstance(params, Mapping):
        raise ValueError(f"{where}: expected a table of parameters, got {params!r}")
    known = parameters(kind)
    for key, value in params.items():
        if key not in known:
            raise ValueError(
                f"{where}: {key!r} is not a parameter of agent = {kind!r}; known: "
                f"{', '.join(sorted(known))}"
            )
        check_value(value, known[key][0], f"{where} {key}")
    try:
        FIXED_AGENTS[kind](spaces.Box(0.0, 1.0, (1,)), spaces.Discrete(2), 0, **params)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{where}: {error}") from None
    return dict(params)


def resolved_agent_params(kind: str, params: Mapping[str, Any]) -> dict[str, Any]:
    """Every constructor argument of a fixed agent, defaults filled in (a run's fingerprint)."""
    return {name: params.get(name, default) for name, (_, default) in parameters(kind).items()}


def preset_config(preset: Preset) -> dict[str, Any]:
    """A preset's ``TreeConfig`` as the fields that differ from ``TreeConfig()`` (the form of
    an ``[agent]`` table)."""
    default = type(preset.config)()
    return {
        f.name: getattr(preset.config, f.name)
        for f in dataclasses.fields(preset.config)
        if getattr(preset.config, f.name) != getattr(default, f.name)
    }
