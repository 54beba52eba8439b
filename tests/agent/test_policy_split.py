"""TreeConfig.policy_splits: a leaf is cut where the greedy choice between two actions flips."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent import TreeAgent, TreeConfig, general_as_of, preset
from agent.exploration import make_exploration
from agent.model_split import choose_policy_split
from agent.tree_ensemble import tree_agent_class

A_FIRSTS = np.array([[0.1], [0.2], [0.6], [0.7]])
B_FIRSTS = np.array([[0.15], [0.25], [0.65], [0.75]])
BOX = (np.array([0.0]), np.array([1.0]), np.array([0.01]))


def test_the_one_cut_with_two_epochs_of_each_action_a_side() -> None:
    # sorted: a a(0.1, 0.2) b b(0.15, 0.25) | a a(0.6, 0.7) b b(0.65, 0.75): only the cut
    # between 0.25 and 0.6 keeps two of each action on each side. a is better left (1 against
    # 0), b right: the advantage goes from +1 to -1, a change of 2; no spread: t = inf
    a, b = np.array([1.0, 1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0, 1.0])
    found = choose_policy_split(A_FIRSTS, a, B_FIRSTS, b, *BOX, min_gap=1.0, min_t=3.0)
    assert found == (np.inf, 0, pytest.approx(0.425))
    assert choose_policy_split(A_FIRSTS, a, B_FIRSTS, b, *BOX, min_gap=2.01, min_t=0) is None


def test_the_t_statistic_by_hand() -> None:
    # a's left targets 1.1 and 0.9: squared deviations 0.02, the other groups none; pooled sd
    # sqrt(0.02 / (8 - 4)) = 0.0707, standard error 0.0707 sqrt(4 x 1/2) = 0.1; change 2: t = 20
    a, b = np.array([1.1, 0.9, 0.0, 0.0]), np.array([0.0, 0.0, 1.0, 1.0])
    found = choose_policy_split(A_FIRSTS, a, B_FIRSTS, b, *BOX, min_gap=1.0, min_t=19.9)
    assert found is not None
    assert found[0] == pytest.approx(20.0)
    assert choose_policy_split(A_FIRSTS, a, B_FIRSTS, b, *BOX, min_gap=1.0, min_t=20.1) is None


def test_no_flip_is_no_split_however_large_the_change() -> None:
    # a is better on both sides (by 1, then by 0.25): its value changes, the choice does not
    a, b = np.array([1.0, 1.0, 0.25, 0.25]), np.zeros(4)
    assert choose_policy_split(A_FIRSTS, a, B_FIRSTS, b, *BOX, min_gap=0.1, min_t=0) is None


def test_too_few_epochs_narrow_children_and_equal_inputs_never_split() -> None:
    a, b = np.array([1.0, 1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0, 1.0])
    low, high, _ = BOX
    # a child would be at most 0.425 wide on one side
    narrow = np.array([0.5])
    assert (
        choose_policy_split(A_FIRSTS, a, B_FIRSTS, b, low, high, narrow, min_gap=0, min_t=0) is None
    )
    assert choose_policy_split(A_FIRSTS[:3], a[:3], B_FIRSTS, b, *BOX, min_gap=0, min_t=0) is None
    same = np.full((4, 1), 0.5)
    assert choose_policy_split(same, a, same, b, *BOX, min_gap=0, min_t=0) is None


def test_the_input_whose_cut_flips_the_choice_wins() -> None:
    rng = np.random.default_rng(0)

    def firsts() -> np.ndarray:
        return np.column_stack([rng.uniform(0, 1, 16), rng.uniform(0, 1, 16)])

    fa, fb = firsts(), firsts()
    a = np.where(fa[:, 1] < 0.5, 1.0, -1.0) + rng.normal(0, 0.1, 16)
    b = np.where(fb[:, 1] < 0.5, -1.0, 1.0) + rng.normal(0, 0.1, 16)
    found = choose_policy_split(
        fa, a, fb, b, np.zeros(2), np.ones(2), np.full(2, 0.01), min_gap=1.0, min_t=3.0
    )
    assert found is not None
    _, dim, value = found
    assert dim == 1
    assert 0.35 < value < 0.65


class Crossing(gym.Env[np.ndarray, int]):
    """One step from x ~ U(0, 1): action 0 pays +0.3 left of 0.5 and -0.3 right of it, action
    1 the opposite. Each action's own targets differ by 0.6 across 0.5, below a model split's
    gap of 1; the advantage changes by 1.2 and flips there."""

    observation_space = spaces.Box(0.0, 1.0, (1,), dtype=np.float64)
    action_space = spaces.Discrete(2)

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        super().reset(seed=seed)
        self.x = float(self.np_random.uniform(0.0, 1.0))
        return np.array([self.x]), {}

    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        left = self.x < 0.5
        reward = 0.3 if left == (action == 0) else -0.3
        return np.array([self.x]), reward, True, False, {}


CROSSING = TreeConfig(
    split_min_samples=10_000,  # the paper's test never runs
    planning="sweep",
    presplit_each_dimension=False,
    model_split_epochs=8,
    model_split_gap=1.0,  # above each action's own change of 0.6: no model split
    policy_splits=True,
)


def _train(config: TreeConfig, episodes: int = 80) -> TreeAgent:
    env = Crossing()
    both = make_exploration("epsilon-greedy", epsilon=0.5)  # each action gets its 8 epochs
    agent = tree_agent_class(config)(env.observation_space, env.action_space, both, 3, config)
    agent.learn(env, episodes, reset_seed=3)
    return agent  # type: ignore[return-value]


def test_the_crossing_is_cut_where_the_model_split_sees_nothing() -> None:
    assert _train(dataclasses.replace(CROSSING, policy_splits=False)).n_leaves == 1
    agent = _train(CROSSING)
    assert agent.n_leaves >= 2
    root = agent.partition
    assert root._dim[0] == 0
    assert 0.3 < root._threshold[0] < 0.7
    assert agent.predict(np.array([0.1])) == 0
    assert agent.predict(np.array([0.9])) == 1


def test_the_tree_ensemble_runs_it_too() -> None:
    agent = _train(dataclasses.replace(CROSSING, hold_terminals=5))
    assert type(agent).__name__ == "TreeEnsembleAgent"
    assert agent.n_leaves >= 2
    assert agent.predict(np.array([0.9])) == 1


def test_the_agent_file_keeps_the_option(tmp_path: Path) -> None:
    agent = _train(CROSSING, 20)
    loaded = TreeAgent.load(agent.save(tmp_path / "crossing.npz"))
    assert loaded.config.policy_splits is True


@pytest.mark.parametrize("bad", [1, "yes", None, 0.0])
def test_bad_values_are_refused_by_name(bad: Any) -> None:
    with pytest.raises(TypeError, match="policy_splits"):
        dataclasses.replace(CROSSING, policy_splits=bad)


def test_it_needs_model_splits() -> None:
    with pytest.raises(ValueError, match="policy_splits = True needs model_split_epochs"):
        dataclasses.replace(CROSSING, model_split_epochs=None)


def test_the_paper_presets_leave_it_off_and_part_20_had_it_off() -> None:
    for name in ("paper", "paper-literal"):
        assert preset(name).config.policy_splits is False
    assert general_as_of(20).policy_splits is False
