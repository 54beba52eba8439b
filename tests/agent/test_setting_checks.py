"""Settings given in Python are checked as strictly as settings read from files
(``agent.value_checks``): every ``TreeConfig`` field, every exploration strategy's parameter, the
agents' seeds, bounds and collision keys. A value of the wrong type, or a float that is not
finite, is a ``SettingError`` (both a ``TypeError`` and a ``ValueError``) naming the setting.
Before, ``TreeConfig(hold_exploration="no")`` ran with exploration held (a non-empty string is
true), ``collision_key=None`` and ``alpha=True`` were taken, and ``TreeConfig(alpha=None)``
failed with "'<' not supported between instances of 'float' and 'NoneType'". The hostile
values are kept as a fuzz table, built from the annotations by this file's own reading."""

from __future__ import annotations

import dataclasses
import inspect
import math
import types
import typing
from typing import Any, Literal, get_args, get_origin, get_type_hints

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent import (
    VDBE,
    AdaptiveEpsilon,
    AdaptiveQAgent,
    Boltzmann,
    CountBonus,
    DecayingEpsilon,
    EpsilonGreedy,
    OptimisticInit,
    Tabu,
    TileCodingAgent,
    TreeAgent,
    TreeConfig,
    VDBESoftmax,
)
from agent.value_checks import SettingError

BOX = spaces.Box(-1.0, 1.0, (2,), np.float32)
ACTIONS = spaces.Discrete(3)
STRATEGIES = (
    EpsilonGreedy,
    AdaptiveEpsilon,
    Boltzmann,
    CountBonus,
    DecayingEpsilon,
    VDBE,
    VDBESoftmax,
    OptimisticInit,
)


def _kinds(hint: Any) -> set[str]:
    """What an annotation admits, in this test's own words: "bool", "int", "float", "str",
    "none" and "literal"."""
    origin = get_origin(hint)
    if origin in (typing.Union, types.UnionType):
        return set().union(*(_kinds(option) for option in get_args(hint)))
    if origin is Literal:
        return {"literal"}
    return {
        bool: {"bool"},
        int: {"int"},
        float: {"float", "int"},
        str: {"str"},
        type(None): {"none"},
    }.get(hint, {"other"})


def hostile(hint: Any) -> list[Any]:
    """Values of a type the annotation does not admit, or floats that are not finite."""
    kinds = _kinds(hint)
    values: list[Any] = [[1], {"a": 1}, object(), b"x"]
    if "none" not in kinds:
        values.append(None)
    if "str" not in kinds:
        values.append("x")
    if "bool" not in kinds:
        values.append(True)
    if kinds & {"bool", "literal", "str"} and not kinds & {"int", "float"}:
        values += [1, 0.5]
    if "float" in kinds:
        values += [math.nan, math.inf, -math.inf]
    elif "int" in kinds:
        values += [2.5, math.nan]
    return values


def _config_cases() -> list[tuple[str, Any]]:
    hints = get_type_hints(TreeConfig)
    return [
        (field.name, value)
        for field in dataclasses.fields(TreeConfig)
        for value in hostile(hints[field.name])
    ]


@pytest.mark.parametrize(("name", "value"), _config_cases())
def test_every_tree_config_field_refuses_a_wrong_type_by_name(name: str, value: Any) -> None:
    with pytest.raises((TypeError, ValueError), match=rf"TreeConfig\.{name}\b") as refused:
        TreeConfig(**{name: value})
    assert isinstance(refused.value, TypeError | ValueError)


@pytest.mark.parametrize(
    ("name", "value", "shown"),
    [
        ("hold_exploration", "no", "expected True or False, got 'no'"),
        ("collision_key", None, "expected a string (at most 1000 characters), got None"),
        ("alpha", True, "expected a number, got True"),
        ("alpha", None, "expected a number, got None"),
        ("q_init", "x", "expected a number, got 'x'"),
        ("split_max_abs_mean", math.inf, "must be finite, got inf"),
        ("reset_counts_on_split", "yes", "expected True or False, got 'yes'"),
        ("inherit_q", 1, "expected True or False, got 1"),
    ],
)
def test_a_wrong_type_is_a_setting_error_spelt_as_python(name: str, value: Any, shown: str) -> None:
    with pytest.raises(SettingError) as refused:
        TreeConfig(**{name: value})
    assert str(refused.value) == f"TreeConfig.{name}: {shown}"
    assert isinstance(refused.value, TypeError)
    assert isinstance(refused.value, ValueError)


def test_a_check_of_its_own_still_speaks_first() -> None:
    with pytest.raises(ValueError, match=r"TreeConfig\.alpha must be in \(0\.0, 1\.0\], got 2"):
        TreeConfig(alpha=2.0)
    with pytest.raises(ValueError, match=r"max_epoch_steps must be a positive int or None"):
        TreeConfig(max_epoch_steps=0)


def test_numpy_scalars_are_taken_as_the_python_numbers_they_hold() -> None:
    config = TreeConfig(
        alpha=np.float32(0.5), max_leaves=np.int64(100), split_min_samples=np.int32(40)
    )
    assert (config.alpha, config.max_leaves, config.split_min_samples) == (0.5, 100, 40)
    assert type(config.alpha) is float
    assert type(config.max_leaves) is int
    assert config == TreeConfig(alpha=0.5, max_leaves=100, split_min_samples=40)


def test_valid_settings_are_kept_as_given() -> None:
    config = TreeConfig(alpha=1, q_init=-3, collision_key="hit", hold_exploration=False)
    assert (config.alpha, config.q_init, config.collision_key) == (1, -3, "hit")
    assert config.hold_exploration is False


@dataclasses.dataclass(frozen=True)
class _Extended(TreeConfig):
    extra_flag: bool = False


def test_a_subclass_field_is_checked_by_its_own_annotation() -> None:
    assert _Extended(extra_flag=True).extra_flag is True
    with pytest.raises(SettingError, match=r"_Extended|TreeConfig\.extra_flag"):
        _Extended(extra_flag="yes")  # type: ignore[arg-type]


def _strategy_cases() -> list[tuple[type, str, Any]]:
    cases = []
    for cls in STRATEGIES:
        hints = get_type_hints(cls.__init__)
        for name in inspect.signature(cls).parameters:
            cases += [(cls, name, value) for value in hostile(hints[name])]
    return cases


@pytest.mark.parametrize(("cls", "name", "value"), _strategy_cases())
def test_every_strategy_parameter_refuses_a_wrong_type_by_name(
    cls: type, name: str, value: Any
) -> None:
    with pytest.raises((TypeError, ValueError), match=rf"\b{name}\b"):
        cls(**{name: value})


@pytest.mark.parametrize(
    ("name", "value"),
    [
        (name, value)
        for name, hint in get_type_hints(Tabu.__init__).items()
        if name not in ("base", "return")
        for value in hostile(hint)
    ],
)
def test_every_tabu_parameter_refuses_a_wrong_type_by_name(name: str, value: Any) -> None:
    with pytest.raises((TypeError, ValueError), match=rf"\b{name}\b"):
        Tabu(EpsilonGreedy(), **{name: value})


def test_a_strategy_flag_given_as_text_is_refused() -> None:
    """``inherit_on_split="no"`` used to be stored as ``bool("no")``, which is True."""
    for cls in (AdaptiveEpsilon, CountBonus, VDBE, VDBESoftmax):
        with pytest.raises(SettingError, match="inherit_on_split: expected True or False"):
            cls(inherit_on_split="no")


def _agent(kind: str, **kwargs: Any) -> Any:
    if kind == "tree":
        return TreeAgent(BOX, ACTIONS, **kwargs)
    if kind == "tile":
        return TileCodingAgent(BOX, ACTIONS, **kwargs)
    return AdaptiveQAgent(BOX, ACTIONS, **kwargs)


@pytest.mark.parametrize("kind", ["tree", "tile", "adaptive-q"])
@pytest.mark.parametrize(
    ("seed", "message"),
    [
        (-1, "seed must be an int >= 0, got -1"),
        (np.int64(-5), "seed must be an int >= 0, got -5"),
        (True, "seed must be an int, got True"),
        (2.0, "seed must be an int, got 2.0"),
        ("7", "seed must be an int, got '7'"),
        (None, "seed must be an int, got None"),
    ],
)
def test_a_bad_seed_is_refused_by_name(kind: str, seed: Any, message: str) -> None:
    with pytest.raises(SettingError) as refused:
        _agent(kind, seed=seed)
    assert message in str(refused.value)


@pytest.mark.parametrize("kind", ["tree", "tile", "adaptive-q"])
def test_a_numpy_seed_is_taken_as_an_int(kind: str) -> None:
    agent = _agent(kind, seed=np.int64(3))
    assert agent.seed == 3
    assert type(agent.seed) is int


@pytest.mark.parametrize("kind", ["tree", "tile", "adaptive-q"])
@pytest.mark.parametrize("bounds", [1.0, "ab", ("ab", "cd"), ([0, 0], [1, 1], [2, 2]), {0: 1}])
def test_bounds_that_are_not_two_sequences_of_numbers_are_refused(kind: str, bounds: Any) -> None:
    with pytest.raises(ValueError, match=r"^bounds must be \(low, high\)"):
        _agent(kind, bounds=bounds)


@pytest.mark.parametrize("kind", ["tree", "tile", "adaptive-q"])
@pytest.mark.parametrize("key", [None, 1, ["collision"]])
def test_a_collision_key_that_is_not_text_is_refused(kind: str, key: Any) -> None:
    settings = {"collision_key": key}
    make = (lambda: TreeConfig(**settings)) if kind == "tree" else lambda: _agent(kind, **settings)
    with pytest.raises(SettingError, match="collision_key: expected a string"):
        make()


def test_an_agent_given_checked_settings_still_learns() -> None:
    env = gym.make("CartPole-v1")
    agent = TreeAgent(
        env.observation_space,
        env.action_space,
        EpsilonGreedy(np.float64(0.1)),
        np.int64(1),
        TreeConfig(split_min_samples=np.int64(40)),
    )
    history = agent.learn(env, 3, reset_seed=1)
    assert len(history) == 3
    assert all(h.steps > 0 for h in history)
