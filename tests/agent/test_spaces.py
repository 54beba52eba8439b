"""Bad input gets a clear error naming the value."""

from __future__ import annotations

import numpy as np
import pytest
from gymnasium import spaces

from agent import GridAgent, TileCodingAgent, TreeAgent, TreeConfig

BOX = spaces.Box(0.0, 1.0, shape=(2,), dtype=np.float32)
ACTIONS = spaces.Discrete(4)


def test_non_box_observation() -> None:
    with pytest.raises(TypeError, match="Box, got Discrete"):
        TreeAgent(spaces.Discrete(5), ACTIONS)


def test_non_discrete_actions() -> None:
    with pytest.raises(TypeError, match="Discrete, got Box"):
        TreeAgent(BOX, spaces.Box(-1.0, 1.0, shape=(1,)))


def test_unbounded_observation_needs_bounds_on_a_grid() -> None:
    unbounded = spaces.Box(-np.inf, np.inf, shape=(2,))
    with pytest.raises(ValueError, match=r"unbounded.*bounds="):
        GridAgent(unbounded, ACTIONS)
    huge = spaces.Box(-np.finfo(np.float32).max, np.finfo(np.float32).max, shape=(2,))
    with pytest.raises(ValueError, match=r"unbounded.*bounds="):
        GridAgent(huge, ACTIONS)
    agent = TreeAgent(unbounded, ACTIONS, bounds=([-1.0, -2.0], [1.0, 2.0]))
    assert agent.leaf_info(0).low == (-1.0, -2.0)
    with pytest.raises(ValueError, match="2 lows and 2 highs"):
        TreeAgent(unbounded, ACTIONS, bounds=([0.0], [1.0]))
    with pytest.raises(ValueError, match=r"low < high .*dimension 1 has low = high = 1\.0"):
        TreeAgent(unbounded, ACTIONS, bounds=([0.0, 1.0], [1.0, 1.0]))
    with pytest.raises(ValueError, match=r"dimension 0 has low 2\.0 > high 1\.0"):
        TreeAgent(unbounded, ACTIONS, bounds=([2.0, 0.0], [1.0, 1.0]))


def test_a_constant_input_is_refused_naming_its_dimension_and_the_remedy() -> None:
    """A Box that declares one input constant (low == high there) is refused by every kind of
    agent with the dimension and what to do, not only "low < high"."""
    constant = spaces.Box(np.array([0.0, 3.0, 0.0]), np.array([1.0, 3.0, 1.0]), dtype=np.float64)
    for make in (
        lambda: TreeAgent(constant, ACTIONS),
        lambda: GridAgent(constant, ACTIONS, resolution=4),
        lambda: TileCodingAgent(constant, ACTIONS),
    ):
        with pytest.raises(ValueError, match=r"dimension 1 has low = high = 3\.0 \(a constant"):
            make()


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("split_min_variance", -0.03),
        ("split_max_abs_mean", -0.5),
        ("split_min_samples", -500),
        ("alpha", 0.0),
        ("gamma", 1.5),
        ("max_epoch_steps", 0),
        ("error_buffer", "ring"),
        ("range_normalization", "leaf"),
        ("split_point", "median"),
        ("max_leaves", 0),
        ("min_leaf_fraction", 0.7),
    ],
)
def test_bad_config_names_field_and_value(field: str, value: object) -> None:
    with pytest.raises(ValueError, match=rf"TreeConfig\.{field}.*{value}"):
        TreeConfig(**{field: value})  # type: ignore[arg-type]


def test_defaults_are_table_one() -> None:
    c = TreeConfig()
    assert (c.alpha, c.gamma) == (0.3, 0.99)
    assert (c.split_min_samples, c.split_max_abs_mean, c.split_min_variance) == (500, 0.5, 0.03)


def test_unknown_strategy_and_bad_arguments() -> None:
    with pytest.raises(ValueError, match=r"'softmaxx'.*adaptive\+tabu"):
        TreeAgent(BOX, ACTIONS, "softmaxx")
    with pytest.raises(TypeError, match="exploration"):
        TreeAgent(BOX, ACTIONS, 3)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="resolution"):
        GridAgent(BOX, ACTIONS, resolution=(3, 0))
    with pytest.raises(TypeError, match="seed"):
        TreeAgent(BOX, ACTIONS, seed=1.5)  # type: ignore[arg-type]


def test_env_with_other_actions_is_refused() -> None:
    class Env:
        action_space = spaces.Discrete(3)

        def reset(self) -> None:
            raise AssertionError("refused before any reset")

        def step(self, action: int) -> None:
            raise AssertionError("refused before any step")

    with pytest.raises(ValueError, match="does not match"):
        TreeAgent(BOX, ACTIONS).learn(Env(), 1)
