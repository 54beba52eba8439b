"""TreeConfig.model_split_epochs: a leaf splits where one action's stored epochs disagree."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent import TreeAgent, TreeConfig, preset
from agent.model_split import choose_model_split, spread_below
from agent.tree_ensemble import tree_agent_class

LINE = np.array([[0.1], [0.2], [0.3], [0.6], [0.7], [0.8]])
BOX = (np.array([0.0]), np.array([1.0]), np.array([0.01]))


def test_the_cut_between_two_groups_of_targets() -> None:
    targets = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
    # every cut keeps two a side; the one at 0.45 separates the groups exactly
    assert choose_model_split(LINE, targets, *BOX, min_gap=0.5, min_t=3.0) == (
        0,
        pytest.approx(0.45),
    )


def test_a_gap_below_the_threshold_is_no_split() -> None:
    targets = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
    assert choose_model_split(LINE, targets, *BOX, min_gap=1.01, min_t=0.0) is None


def test_the_t_statistic_by_hand() -> None:
    # sides {1, 1.2, 0.8} and {0, 0.2, -0.2}: gap 1, squared deviations 0.08 + 0.08, pooled
    # sd sqrt(0.16 / 4) = 0.2, standard error 0.2 sqrt(2/3) = 0.1633: t = 6.12
    targets = np.array([1.0, 1.2, 0.8, 0.0, 0.2, -0.2])
    assert choose_model_split(LINE, targets, *BOX, min_gap=0.5, min_t=6.0) == (
        0,
        pytest.approx(0.45),
    )
    assert choose_model_split(LINE, targets, *BOX, min_gap=0.5, min_t=6.2) is None


def test_a_child_narrower_than_the_smallest_leaf_is_not_made() -> None:
    targets = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
    low, high, _ = BOX
    # 0.45 leaves a child 0.45 wide, 0.65 one 0.35 wide: neither reaches 0.5
    assert (
        choose_model_split(LINE, targets, low, high, np.array([0.5]), min_gap=0.5, min_t=0) is None
    )
    # with 0.4 the cut at 0.45 is allowed (0.45 and 0.55 wide)
    found = choose_model_split(LINE, targets, low, high, np.array([0.4]), min_gap=0.5, min_t=0)
    assert found == (0, pytest.approx(0.45))


def test_the_dimension_that_separates_wins() -> None:
    rng = np.random.default_rng(0)
    firsts = np.column_stack([rng.uniform(0, 1, 12), np.linspace(0.05, 0.95, 12)])
    targets = np.where(firsts[:, 1] < 0.5, 2.0, -2.0)
    low, high = np.zeros(2), np.ones(2)
    dim, value = choose_model_split(
        firsts, targets, low, high, np.full(2, 0.01), min_gap=1.0, min_t=3.0
    ) or (None, None)
    assert dim == 1
    assert firsts[:, 1][firsts[:, 1] < 0.5].max() < value < firsts[:, 1][firsts[:, 1] > 0.5].min()


def test_equal_inputs_are_never_cut_apart_and_too_few_epochs_never_split() -> None:
    same = np.full((6, 1), 0.5)
    targets = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
    assert choose_model_split(same, targets, *BOX, min_gap=0.1, min_t=0.0) is None
    assert choose_model_split(LINE[:3], targets[:3], *BOX, min_gap=0.1, min_t=0.0) is None


class Ledge(gym.Env[np.ndarray, int]):
    """One step from x ~ U(0, 1): action 0 pays +1 left of 0.5 and -1 right of it (a ledge the
    leaf hides); action 1 pays 0. The best policy needs a split at 0.5."""

    observation_space = spaces.Box(0.0, 1.0, (1,), dtype=np.float64)
    action_space = spaces.Discrete(2)

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        super().reset(seed=seed)
        self.x = float(self.np_random.uniform(0.0, 1.0))
        return np.array([self.x]), {}

    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        reward = 0.0 if action == 1 else (1.0 if self.x < 0.5 else -1.0)
        return np.array([self.x]), reward, True, False, {}


class CutLedge(Ledge):
    """The ledge, but each episode is cut by a time limit (truncated): never a terminal."""

    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        obs, reward, _, _, info = super().step(action)
        return obs, reward, False, True, info


LEDGE = TreeConfig(
    split_min_samples=10_000,  # the paper's test never runs: only the model can split
    planning="sweep",
    presplit_each_dimension=False,
    model_split_epochs=8,
    model_split_gap=0.5,
)


def _train(config: TreeConfig, episodes: int = 60, env: Ledge | None = None) -> TreeAgent:
    env = env if env is not None else Ledge()
    agent = TreeAgent(env.observation_space, env.action_space, "epsilon-greedy", 3, config)
    agent.learn(env, episodes, reset_seed=3)
    return agent


def test_the_ledge_is_found_from_the_stored_epochs() -> None:
    agent = _train(LEDGE)
    assert agent.n_leaves >= 2
    first = agent.partition  # the root's cut is the first split
    assert first._dim[0] == 0
    assert 0.3 < first._threshold[0] < 0.7
    assert agent.predict(np.array([0.1])) == 0
    assert agent.predict(np.array([0.9])) == 1


def test_off_the_leaf_is_never_split() -> None:
    agent = _train(dataclasses.replace(LEDGE, model_split_epochs=None))
    assert agent.n_leaves == 1


def test_a_split_hands_each_child_its_epochs() -> None:
    agent = _train(LEDGE)
    assert agent.model is not None
    for leaf in agent.partition.leaves():
        low, high = agent.partition.leaf_bounds(leaf)
        firsts, _ = agent.model.targets(leaf, 0, agent.q)
        assert all(low[0] <= x[0] <= high[0] for x in firsts)


def test_the_agent_file_keeps_the_option(tmp_path: Path) -> None:
    agent = _train(LEDGE, 20)
    loaded = TreeAgent.load(agent.save(tmp_path / "ledge.npz"))
    assert loaded.config.model_split_epochs == 8
    assert loaded.config.model_split_gap == 0.5


@pytest.mark.parametrize(
    ("field", "bad"),
    [
        ("model_split_epochs", 3),
        ("model_split_epochs", 0),
        ("model_split_epochs", 8.0),
        ("model_split_epochs", True),
        ("model_split_epochs", 33),  # more than the model's window of 32
        ("model_split_gap", -0.1),
        ("model_split_gap", float("nan")),
        ("model_split_gap", float("inf")),
        ("model_split_gap", "0.2"),
        ("model_split_t", -1.0),
        ("model_split_t", True),
        ("model_split_drops_pairs", 1),
        ("model_split_drops_pairs", "yes"),
        ("model_split_from_terminal", 1),
    ],
)
def test_bad_values_are_refused_by_name(field: str, bad: Any) -> None:
    with pytest.raises((ValueError, TypeError), match=field):
        dataclasses.replace(LEDGE, **{field: bad})


def test_it_needs_the_model() -> None:
    with pytest.raises(ValueError, match=r"model_split_epochs.*planning = 'sweep'"):
        TreeConfig(model_split_epochs=8)


def test_the_paper_presets_leave_it_off() -> None:
    for name in ("paper", "paper-literal"):
        assert preset(name).config.model_split_epochs is None


def test_the_tree_ensemble_runs_it_too() -> None:
    config = dataclasses.replace(LEDGE, hold_terminals=5)
    env = Ledge()
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, "epsilon-greedy", 3, config
    )
    agent.learn(env, 60, reset_seed=3)
    assert agent.n_leaves >= 2
    assert agent.predict(np.array([0.1])) == 0


def test_a_model_split_hands_the_pairs_to_the_children_or_drops_them() -> None:
    # the pairs never decide anything here (the paper's test needs 10,000), so both agents
    # act the same and differ only in what the root's children hold
    kept = _train(LEDGE, 30)
    dropped = _train(dataclasses.replace(LEDGE, model_split_drops_pairs=True), 30)
    assert kept.q == dropped.q
    assert kept.partition._threshold == dropped.partition._threshold

    def held(agent: TreeAgent) -> int:
        return sum(buffer.count for buffer in agent.partition._buffers.values())

    assert held(kept) == 30  # one pair an episode, every one kept (the test never runs)
    assert held(dropped) < 30


def test_from_the_first_terminal_waits_for_one() -> None:
    waiting = dataclasses.replace(LEDGE, model_split_from_terminal=True)
    # no terminal ever: the model's epochs disagree as much, but no model split is made
    assert _train(LEDGE, env=CutLedge()).n_leaves >= 2
    never = _train(waiting, env=CutLedge())
    assert never.model is not None
    assert never.model.terminals == 0
    assert never.n_leaves == 1
    # every episode ends in a terminal: the same agent as without the option
    assert _train(waiting).q == _train(LEDGE).q


@pytest.mark.parametrize("field", ["model_split_from_terminal", "model_split_drops_pairs"])
def test_the_model_split_switches_need_model_splits(field: str) -> None:
    with pytest.raises(ValueError, match=f"{field} = True needs model_split_epochs"):
        dataclasses.replace(LEDGE, model_split_epochs=None, **{field: True})


def test_spread_below_is_the_first_test_of_the_model_split() -> None:
    """``spread_below`` (issue 9, part 34) says True only where choose_model_split returns None,
    and at the same boundary: a range equal to the gap is tested in full."""
    rng = np.random.default_rng(34)
    firsts = rng.uniform(0.0, 1.0, size=(12, 2))
    box = (np.zeros(2), np.ones(2), np.full(2, 0.01))
    for _ in range(200):
        targets = rng.normal(0.0, 1.0, size=12)
        gap = float(rng.uniform(0.0, 4.0))
        if spread_below(targets.tolist(), gap):
            assert choose_model_split(firsts, targets, *box, min_gap=gap, min_t=0.0) is None
    targets = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
    assert spread_below(targets.tolist(), 1.01)
    assert not spread_below(targets.tolist(), 1.0)
    assert choose_model_split(LINE, targets, *BOX, min_gap=1.0, min_t=3.0) is not None


def test_the_agent_learns_the_same_without_the_shortcut(monkeypatch: pytest.MonkeyPatch) -> None:
    """The general preset's run is the same, Q-bar for Q-bar, with the shortcut of ``_model_split``
    bypassed (every test built in full, as before part 34)."""
    import agent.learner

    def run() -> tuple[list[list[float]], int, list[int]]:
        env = gym.make("CartPole-v1")
        agent = preset("general").agent(env.observation_space, env.action_space, seed=3)
        history = agent.learn(env, 40, reset_seed=3)
        return agent.q, agent.n_leaves, [s.steps for s in history]

    shortcut = run()
    skipped = 0

    def never(targets: list[float], min_gap: float) -> bool:
        nonlocal skipped
        skipped += spread_below(targets, min_gap)
        return False

    monkeypatch.setattr(agent.learner, "spread_below", never)
    assert run() == shortcut
    assert skipped > 10  # tests the shortcut would have ended were run in full here
