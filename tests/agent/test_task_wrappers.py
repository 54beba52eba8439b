"""agent.adapt_env: any task's spaces as the flat Box and Discrete actions the agents take."""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Callable
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces
from gymnasium.utils.env_checker import check_env

from agent import BoxObservation, DiscreteActions, TreeAgent, adapt_env, preset
from agent.spaces import observation_bounds
from agent.task_wrappers import MAX_ACTIONS
from agent.tree_ensemble import tree_agent_class


class SpaceEnv(gym.Env[Any, Any]):
    """An env with given spaces that records the actions it receives and returns fixed
    observations; episodes end after ``length`` steps with reward 1 on the last."""

    def __init__(
        self, observation_space: spaces.Space, action_space: spaces.Space, length: int = 3
    ) -> None:
        self.observation_space = observation_space
        self.action_space = action_space
        self.length = length
        self.received: list[Any] = []
        self._t = 0

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None) -> Any:
        super().reset(seed=seed)
        self._t = 0
        return self.observation_space.sample(), {}

    def step(self, action: Any) -> Any:
        self.received.append(action)
        self._t += 1
        done = self._t >= self.length
        return self.observation_space.sample(), float(done), done, False, {}


def test_discrete_observation_is_its_index_in_an_integer_box() -> None:
    env = BoxObservation(SpaceEnv(spaces.Discrete(5, start=2), spaces.Discrete(2)))
    assert env.observation_space.dtype == np.int64
    assert env.observation_space.low.tolist() == [2]
    assert env.observation_space.high.tolist() == [6]
    value = env.observation(4)
    assert value.tolist() == [4]
    assert value.dtype == np.int64
    assert env.observation_space.contains(value)
    # the agents read each integer as the cell [k - 0.5, k + 0.5]
    assert observation_bounds(env.observation_space, None) == ([1.5], [6.5])


def test_discrete_parts_only_give_an_integer_box_and_a_box_part_a_float_one() -> None:
    parts = spaces.Tuple((spaces.Discrete(32), spaces.Discrete(11), spaces.MultiBinary(1)))
    env = BoxObservation(SpaceEnv(parts, spaces.Discrete(2)))
    assert env.observation_space.dtype == np.int64
    assert env.observation_space.high.tolist() == [31, 10, 1]
    assert env.observation((31, 0, np.array([1]))).tolist() == [31, 0, 1]
    mixed = spaces.Tuple((spaces.Discrete(3), spaces.Box(-1.0, 1.0, (1,))))
    env = BoxObservation(SpaceEnv(mixed, spaces.Discrete(2)))
    assert env.observation_space.dtype == np.float64
    assert env.observation_space.low.tolist() == [-0.5, -1.0]


def test_tuple_and_dict_observations_concatenate_in_order() -> None:
    tuple_space = spaces.Tuple(
        (spaces.Discrete(32), spaces.MultiDiscrete([3, 4]), spaces.Box(-1.0, 1.0, (2, 2)))
    )
    env = BoxObservation(SpaceEnv(tuple_space, spaces.Discrete(2)))
    assert env.observation_space.shape == (7,)
    assert env.observation_space.low.tolist() == [-0.5, -0.5, -0.5, -1.0, -1.0, -1.0, -1.0]
    assert env.observation_space.high.tolist() == [31.5, 2.5, 3.5, 1.0, 1.0, 1.0, 1.0]
    value = (7, np.array([2, 0]), np.array([[0.5, -0.5], [0.25, 0.0]]))
    assert env.observation(value).tolist() == [7.0, 2.0, 0.0, 0.5, -0.5, 0.25, 0.0]
    dict_space = spaces.Dict({"b": spaces.MultiBinary(2), "a": spaces.Discrete(3)})
    env = BoxObservation(SpaceEnv(dict_space, spaces.Discrete(2)))
    keys = list(dict_space.spaces)  # gymnasium sorts a dict's keys: a, then b
    assert keys == ["a", "b"]
    assert env.observation({"a": 2, "b": np.array([1, 0])}).tolist() == [2, 1, 0]
    assert env.observation_space.high.tolist() == [2, 1, 1]


def test_box_actions_become_a_grid_with_both_bounds_and_the_centre() -> None:
    env = DiscreteActions(SpaceEnv(spaces.Box(0, 1, (1,)), spaces.Box(-2.0, 2.0, (1,))), bins=5)
    assert env.action_space == spaces.Discrete(5)
    assert [a.tolist() for a in env.actions] == [[-2.0], [-1.0], [0.0], [1.0], [2.0]]
    env.reset(seed=0)
    env.step(3)
    assert env.unwrapped.received[-1].tolist() == [1.0]  # type: ignore[attr-defined]


def test_two_dimensional_grid_varies_the_first_dimension_slowest() -> None:
    box = spaces.Box(np.array([0.0, -1.0]), np.array([1.0, 1.0]))
    env = DiscreteActions(SpaceEnv(spaces.Box(0, 1, (1,)), box), bins=(2, 3))
    assert env.action_space.n == 6  # type: ignore[attr-defined]
    expected = [[0, -1], [0, 0], [0, 1], [1, -1], [1, 0], [1, 1]]
    assert [a.tolist() for a in env.actions] == expected


def test_a_dimension_fixed_by_its_bounds_has_one_value() -> None:
    box = spaces.Box(np.array([-1.0, 0.5]), np.array([1.0, 0.5]))
    env = DiscreteActions(SpaceEnv(spaces.Box(0, 1, (1,)), box), bins=3)
    assert [a.tolist() for a in env.actions] == [[-1.0, 0.5], [0.0, 0.5], [1.0, 0.5]]


def test_multidiscrete_and_multibinary_actions_are_their_products() -> None:
    env = DiscreteActions(SpaceEnv(spaces.Box(0, 1, (1,)), spaces.MultiDiscrete([2, 3])))
    assert [a.tolist() for a in env.actions] == [[0, 0], [0, 1], [0, 2], [1, 0], [1, 1], [1, 2]]
    env = DiscreteActions(SpaceEnv(spaces.Box(0, 1, (1,)), spaces.MultiBinary(2)))
    assert [a.tolist() for a in env.actions] == [[0, 0], [0, 1], [1, 0], [1, 1]]


def test_action_bins_for_actions_that_are_not_a_box_is_refused_naming_the_task() -> None:
    with pytest.raises(ValueError, match=r"action_bins = 3 only applies .* CliffWalking-v1 has"):
        adapt_env(gym.make("CliffWalking-v1"), 3)
    with pytest.raises(ValueError, match=r"action_bins = 2 only applies .* SpaceEnv has"):
        adapt_env(SpaceEnv(spaces.Box(0, 1, (1,)), spaces.MultiBinary(2)), 2)
    assert adapt_env(gym.make("Pendulum-v1"), 3).action_space == spaces.Discrete(3)


def test_adapt_env_leaves_a_fitting_task_alone_and_renumbers_a_shifted_discrete() -> None:
    fitting = SpaceEnv(spaces.Box(0, 1, (2,)), spaces.Discrete(3))
    assert adapt_env(fitting) is fitting
    shifted = adapt_env(SpaceEnv(spaces.Box(0, 1, (2,)), spaces.Discrete(3, start=-1)))
    assert shifted.action_space == spaces.Discrete(3)
    shifted.reset(seed=0)
    shifted.step(0)
    assert shifted.unwrapped.received == [-1]  # type: ignore[attr-defined]


@pytest.mark.parametrize(
    "task", ["FrozenLake-v1", "CliffWalking-v1", "Blackjack-v1", "Pendulum-v1"]
)
def test_adapted_gymnasium_tasks_pass_the_checker_and_a_tree_learns_on_them(task: str) -> None:
    env = adapt_env(gym.make(task))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the checker's note that env is wrapped
        check_env(env, skip_render_check=True)
    agent = preset("general").agent(env.observation_space, env.action_space, seed=0)
    history = agent.learn(env, 3, reset_seed=0)
    assert len(history) == 3
    obs, _ = env.reset(seed=1)
    assert env.action_space.contains(agent.predict(obs))


def test_a_tree_learns_cliff_walking_through_the_index(greedy_return: Callable) -> None:
    """CliffWalking's 48 cells as one index input, split by the tree's own tests (no table):
    after 100 episodes the greedy walk reaches the goal without falling (-13 is the edge path,
    -17 the safe one; a fall costs -100)."""
    env = adapt_env(gym.make("CliffWalking-v1"))
    config = dataclasses.replace(preset("general").config, table_cells=None)
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, "adaptive+tabu", 0, config
    )
    assert agent.n_leaves == 2
    agent.learn(env, 100, reset_seed=0)
    total = greedy_return(env, agent, 0)
    assert -17.0 <= total <= -13.0  # 13-17 steps of -1 that ended: only the goal ends so soon
    assert agent.n_leaves > 10  # the index was split into cells


@pytest.mark.parametrize(
    ("space", "message"),
    [
        (spaces.Text(5), "is a Text"),
        (spaces.Tuple((spaces.Discrete(2), spaces.Text(3))), r"observation_space\[1\] is a Text"),
        (spaces.Dict({"x": spaces.Sequence(spaces.Discrete(2))}), r"\['x'\] is a Sequence"),
    ],
)
def test_unsupported_observation_spaces_are_named(space: spaces.Space, message: str) -> None:
    with pytest.raises(TypeError, match=message):
        BoxObservation(SpaceEnv(space, spaces.Discrete(2)))


@pytest.mark.parametrize(
    ("action_space", "bins", "error", "message"),
    [
        (spaces.Box(-1.0, 1.0, (1,)), 1, ValueError, r"int >= 2, got 1"),
        (spaces.Box(-1.0, 1.0, (1,)), 0, ValueError, r"int >= 2, got 0"),
        (spaces.Box(-1.0, 1.0, (1,)), 2.5, ValueError, r"int >= 2 or one per dimension, got 2.5"),
        (spaces.Box(-1.0, 1.0, (1,)), True, ValueError, r"got True"),
        (spaces.Box(-1.0, 1.0, (1,)), "5", ValueError, r"got '5'"),
        (spaces.Box(-1.0, 1.0, (1,)), None, ValueError, r"got None"),
        (spaces.Box(-1.0, 1.0, (2,)), [3, 2.0], ValueError, r"every bin count .* got \[3, 2.0\]"),
        (spaces.Box(-1.0, 1.0, (2,)), (3, -4), ValueError, r"every bin count"),
        (spaces.Box(-1.0, 1.0, (2,)), (3,), ValueError, r"1 counts for a 2-dimensional"),
        (spaces.Box(-1.0, 1.0, (3,)), 17, ValueError, r"4,913 actions, more than 4,096"),
        (spaces.Box(-np.inf, 1.0, (1,)), 5, ValueError, r"unbounded"),
        (spaces.MultiBinary(13), 5, ValueError, r"8,192 actions"),
        (spaces.Text(4), 5, TypeError, r"action space is a Text"),
        (spaces.Box(0.0, 1.0, (0,)), 5, ValueError, r"has no entries"),
    ],
)
def test_bad_action_spaces_and_bins_are_named(
    action_space: spaces.Space, bins: Any, error: type[Exception], message: str
) -> None:
    with pytest.raises(error, match=message):
        DiscreteActions(SpaceEnv(spaces.Box(0, 1, (1,)), action_space), bins)


@pytest.mark.parametrize("bad", [-1, 5, 2.0, True, "1", None, np.float64(1.0)])
def test_an_index_outside_the_grid_is_refused(bad: Any) -> None:
    env = DiscreteActions(SpaceEnv(spaces.Box(0, 1, (1,)), spaces.Box(-1.0, 1.0, (1,))), 5)
    with pytest.raises(ValueError, match="index in \\[0, 5\\)"):
        env.action(bad)
    assert env.action(np.int64(4)).tolist() == [1.0]


def test_the_action_grid_cap_is_inclusive() -> None:
    env = DiscreteActions(SpaceEnv(spaces.Box(0, 1, (1,)), spaces.MultiBinary(12)))
    assert env.action_space.n == MAX_ACTIONS  # type: ignore[attr-defined]


def test_the_agents_refusal_points_to_adapt_env() -> None:
    with pytest.raises(TypeError, match="adapt_env"):
        TreeAgent(spaces.Discrete(5), spaces.Discrete(2))
    with pytest.raises(TypeError, match="adapt_env"):
        TreeAgent(spaces.Box(0, 1, (2,)), spaces.Box(-1.0, 1.0, (1,)))
