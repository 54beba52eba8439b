"""Scale-free thresholds: the measured units, and invariance to the reward's scale."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

from agent import TreeAgent, TreeConfig, preset
from agent.scale import EXACT_VALUES, ReturnScale, RewardScale


def test_reward_scale_is_the_median_magnitude_over_one_minus_gamma() -> None:
    s = RewardScale(0.99)
    assert s.value == 0.0
    s.add([0.0, 0.0])
    assert s.value == 0.0  # zeros are not counted
    s.add([-0.01, -0.01, -1.0, 5.0])  # magnitudes 0.01, 0.01, 1, 5: lower median 0.01
    assert s.value == pytest.approx(1.0)
    s.add([-1.0, -1.0, -1.0])
    assert s.value == pytest.approx(100.0)
    again = RewardScale(0.5)
    again.restore(s.state())
    assert again.value == s.value
    assert RewardScale(1.0).gamma == 1.0


def test_a_given_horizon_replaces_one_over_one_minus_gamma() -> None:
    s = RewardScale(0.995, horizon=100.0)
    s.add([-1.0, -1.0, 5.0])
    assert s.value == 100.0  # median 1 times H, not 1 / (1 - 0.995) = 200
    copy = RewardScale(0.995, horizon=100.0)
    copy.restore(s.state())
    assert copy.value == s.value
    assert RewardScale(0.995).value == 0.0
    with pytest.raises(ValueError, match="horizon must be in"):
        RewardScale(0.99, horizon=0.5)


def test_scale_horizon_keeps_the_unit_when_gamma_moves(make_corridor: Callable[..., Any]) -> None:
    def unit(**fields: Any) -> float:
        env = make_corridor()
        config = TreeConfig(threshold_units="scale", scale_rule="reward_median", **fields)
        agent = TreeAgent(env.observation_space, env.action_space, "adaptive+tabu", 3, config)
        agent.learn(env, 3, reset_seed=5)
        return float(agent.scale.value)

    base = unit(gamma=0.99)
    assert base > 0.0
    assert unit(gamma=0.995, scale_horizon=100.0) == pytest.approx(base)
    assert unit(gamma=0.995) == pytest.approx(2.0 * base)  # the unit follows gamma by default


@pytest.mark.parametrize("bad", [0.0, 0.99, -5.0, 2e6, float("nan"), float("inf"), True, "100"])
def test_bad_scale_horizon_is_refused_by_name(bad: Any) -> None:
    with pytest.raises(ValueError, match=r"TreeConfig\.scale_horizon must be None or a number"):
        TreeConfig(scale_horizon=bad)


def test_reward_scale_bins_continuous_rewards() -> None:
    rewards = np.random.default_rng(0).normal(size=2 * EXACT_VALUES).tolist()
    s = RewardScale(0.0)
    s.add(rewards)
    median = float(np.sort(np.abs(rewards))[(len(rewards) + 1) // 2 - 1])
    assert s.value == pytest.approx(median, rel=0.05)
    doubled = RewardScale(0.0)
    doubled.add([4.0 * r for r in rewards])
    assert doubled.value == 4.0 * s.value  # homogeneous under powers of two


def test_return_scale_is_the_standard_deviation() -> None:
    s = ReturnScale()
    s.add([1.0, 3.0])
    s.add([5.0])
    assert s.value == pytest.approx(np.std([1.0, 3.0, 5.0]))
    copy = ReturnScale()
    copy.restore(s.state())
    assert copy.value == s.value


def run(
    make_corridor: Callable[..., Any], factor: float, rule: str, episodes: int = 12
) -> tuple[TreeAgent, list[int], list[Any]]:
    actions: list[int] = []

    class Record(gym.Wrapper):
        def step(self, action: int) -> Any:
            actions.append(int(action))
            return self.env.step(action)

    env = Record(gym.wrappers.TransformReward(make_corridor(), lambda r: factor * r))
    config = TreeConfig(
        threshold_units="scale",
        scale_rule=rule,  # type: ignore[arg-type]
        split_min_samples=40,
        split_min_variance=0.01,
        planning="sweep",
        model_bonus=0.01,
    )
    agent = TreeAgent(env.observation_space, env.action_space, "adaptive+tabu", 3, config)
    history = agent.learn(env, episodes, reset_seed=5)
    return agent, actions, history


@pytest.mark.parametrize("rule", ["return_std", "reward_median"])
@pytest.mark.parametrize("factor", [4.0, 0.25, 100.0])
def test_same_tree_and_actions_whatever_the_reward_scale(
    make_corridor: Callable[..., Any], rule: str, factor: float
) -> None:
    base, base_actions, base_history = run(make_corridor, 1.0, rule)
    scaled, actions, history = run(make_corridor, factor, rule)
    assert base.n_leaves > 3  # the tree did split
    assert actions == base_actions
    assert [s.steps for s in history] == [s.steps for s in base_history]
    assert [base.partition.leaf_bounds(v) for v in base.partition.leaves()] == [
        scaled.partition.leaf_bounds(v) for v in scaled.partition.leaves()
    ]
    assert scaled.scale.value == pytest.approx(factor * base.scale.value)
    assert np.asarray(scaled.q) == pytest.approx(factor * np.asarray(base.q))


def test_reward_units_are_not_invariant(make_corridor: Callable[..., Any]) -> None:
    # the paper's thresholds are in reward units: a scaled task grows another tree
    def leaves(factor: float) -> int:
        env = gym.wrappers.TransformReward(make_corridor(), lambda r: factor * r)
        config = TreeConfig(split_min_samples=40, split_min_variance=0.01)
        agent = TreeAgent(env.observation_space, env.action_space, "adaptive+tabu", 3, config)
        agent.learn(env, 12, reset_seed=5)
        return agent.n_leaves

    assert leaves(1.0) != leaves(100.0)


def _general_run(task: str, episodes: int, factor: float) -> tuple[Any, list[int]]:
    actions: list[int] = []

    class Record(gym.Wrapper):
        def step(self, action: int) -> Any:
            actions.append(int(action))
            return self.env.step(action)

    env = Record(gym.wrappers.TransformReward(gym.make(task), lambda r: factor * r))
    agent = preset("general").agent(env.observation_space, env.action_space, seed=3)
    agent.learn(env, episodes, reset_seed=5)
    return agent, actions


@pytest.mark.parametrize(("task", "episodes"), [("MountainCar-v0", 60), ("CartPole-v1", 150)])
@pytest.mark.parametrize("factor", [1 / 128, 512.0])
def test_the_general_preset_is_the_same_agent_whatever_the_reward_scale(
    task: str, episodes: int, factor: float
) -> None:
    # every option of the general preset reads rewards through its measured unit, so a
    # reward multiplied by a power of two (exact in floating point) gives the same actions,
    # the same tree, the same discount (CartPole's failure latch opens the same) and values
    # multiplied by the factor
    base, base_actions = _general_run(task, episodes, 1.0)
    scaled, actions = _general_run(task, episodes, factor)
    assert base.n_leaves > 16  # the tree grew past its presplit
    assert actions == base_actions
    assert scaled.n_leaves == base.n_leaves
    assert scaled.discount == base.discount == (0.9995 if task == "CartPole-v1" else 0.999)
    assert np.asarray(scaled.q) == pytest.approx(factor * np.asarray(base.q), rel=1e-12)


def _general_run_in_units(factor: float, episodes: int = 60) -> tuple[Any, list[int]]:
    actions: list[int] = []

    class Record(gym.Wrapper):
        def step(self, action: int) -> Any:
            actions.append(int(action))
            return self.env.step(action)

    car = gym.make("MountainCar-v0")
    box = car.observation_space
    space = gym.spaces.Box(box.low * factor, box.high * factor, dtype=np.float32)
    env = Record(
        gym.wrappers.TransformObservation(car, lambda o: (o * factor).astype(np.float32), space)
    )
    agent = preset("general").agent(env.observation_space, env.action_space, seed=3)
    agent.learn(env, episodes, reset_seed=5)
    return agent, actions


@pytest.mark.parametrize("factor", [1 / 64, 256.0])
def test_the_general_preset_is_the_same_agent_whatever_the_observation_units(
    factor: float,
) -> None:
    # positions in metres or millimetres: every width the tree uses is a fraction of the
    # observation box, so inputs (and bounds) times a power of two give the same actions and
    # the same tree, with every cut moved by the factor
    base, base_actions = _general_run_in_units(1.0)
    scaled, actions = _general_run_in_units(factor)
    assert base.n_leaves > 16
    assert actions == base_actions
    assert np.asarray(scaled.q) == pytest.approx(np.asarray(base.q), rel=1e-12)
    for leaf in base.partition.leaves():
        low, high = base.partition.leaf_bounds(leaf)
        low_scaled, high_scaled = scaled.partition.leaf_bounds(leaf)
        assert np.asarray(low_scaled) == pytest.approx(factor * np.asarray(low))
        assert np.asarray(high_scaled) == pytest.approx(factor * np.asarray(high))
