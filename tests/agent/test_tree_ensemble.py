"""Offset trees with averaged Q-bar (``TreeConfig.ensemble_trees``, beyond the paper)."""

from __future__ import annotations

import dataclasses
import json
from array import array
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent import TreeAgent, TreeConfig, preset
from agent.exploration import make_exploration
from agent.leaf_model import LeafModel
from agent.tree_ensemble import (
    ShiftedPartitionTree,
    TreeEnsembleAgent,
    presplit_shifts,
    tree_agent_class,
)


class Walk(gym.Env[np.ndarray, int]):
    """x starts at 0.02 and moves 0.1 a step (action 1) or 0.05 (action 0); -1 a step; the
    episode ends at x >= 1."""

    observation_space = spaces.Box(0.0, 1.0, (1,), dtype=np.float64)
    action_space = spaces.Discrete(2)

    def reset(self, *, seed: int | None = None, options: Any = None) -> tuple[np.ndarray, dict]:
        super().reset(seed=seed)
        self.x = 0.02
        return np.array([self.x]), {}

    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict]:
        self.x += 0.1 if action == 1 else 0.05
        return np.array([min(self.x, 1.0)]), -1.0, self.x >= 1.0, False, {}


def plain_config(**changes: Any) -> TreeConfig:
    """No learned splits, no model, no hold: epochs and updates can be counted by hand."""
    base = TreeConfig(
        split_min_samples=10_000,
        presplit_each_dimension=True,
        hold_exploration=False,
        max_epoch_steps=None,
        q_init=0.0,
        alpha=0.5,
    )
    return dataclasses.replace(base, **changes)


def test_offsets_are_suttons_asymmetric_ones_in_half_widths() -> None:
    # (2d + 1) k / K mod 1, read in [-1/2, 1/2): K = 4, two dimensions
    assert presplit_shifts(0, 4, 2) == [0.0, 0.0]
    assert presplit_shifts(1, 4, 2) == [0.25, -0.25]
    assert presplit_shifts(2, 4, 2) == [-0.5, -0.5]
    assert presplit_shifts(3, 4, 2) == [-0.25, 0.25]


def test_a_shifted_tree_presplits_off_the_midpoints() -> None:
    tree = ShiftedPartitionTree([0.0, 0.0], [1.0, 1.0], plain_config(), [0.25, -0.25])
    # dimension 0 at 0.5 + 0.25 x 0.5 = 0.625, dimension 1 at 0.5 - 0.25 x 0.5 = 0.375
    assert tree.n_leaves == 4
    assert tree.leaf_of([0.62, 0.37]) != tree.leaf_of([0.63, 0.37])
    assert tree.leaf_of([0.62, 0.37]) != tree.leaf_of([0.62, 0.38])
    assert tree.leaf_of([0.3, 0.1]) == tree.leaf_of([0.6, 0.3])


B = 1e-9
"""Action 1's start value in :func:`_walked_once`: action 0 starts so bad that greedy always
takes action 1."""


def _walked_once(**changes: Any) -> tuple[TreeEnsembleAgent, Any]:
    """A greedy ensemble of ``plain_config(**changes)`` after one episode of the walk, every
    row starting at [-1e6, B]."""
    env = Walk()
    config = plain_config(**changes)
    agent = TreeEnsembleAgent(env.observation_space, env.action_space, "greedy", 0, config)
    for member in agent.members:
        for row in member.q:
            row[:] = [-1e6, B]
    return agent, agent.learn(env, 1, reset_seed=0)[0]


def test_any_trees_leaf_change_is_a_decision_point_and_every_tree_learns_it() -> None:
    # K = 2 on [0, 1]: tree 0 presplits at 0.5, tree 1 (shift -1/2) at 0.25. Action 0 starts
    # so bad that greedy always takes action 1: x = 0.02, 0.12, ..., 0.92, then 1.02 (the end).
    agent, stats = _walked_once(ensemble_trees=2)
    tree0, tree1 = agent.members
    b = B
    assert stats.steps == 10
    assert stats.epochs == 3  # inputs 0.02-0.22 | 0.32-0.42 | 0.52-0.92: tree 1, then tree 0
    left0, right0 = tree0.partition.leaf_of([0.1]), tree0.partition.leaf_of([0.6])
    left1, right1 = tree1.partition.leaf_of([0.1]), tree1.partition.leaf_of([0.3])
    assert tree0.partition.leaf_of([0.3]) == left0
    g = 0.99
    three = [-1 + g * (-1 + g * (-1 + g * b)), -1 + g * (-1 + g * b), -1 + g * b]  # eq. (9)
    two = [-1 + g * (-1 + g * b), -1 + g * b]
    q1 = 0.5 * b + 0.5 * sum(three) / 3  # eq. (10), alpha 0.5
    # tree 0's left leaf learnt two epochs (its own leaf did not change at 0.32)
    assert tree0.visits[left0][1] == 2
    assert tree0.q[left0][1] == pytest.approx(0.5 * q1 + 0.5 * sum(two) / 2, abs=1e-12)
    assert tree0.visits[right0][1] == 1
    # tree 1's left leaf learnt the first epoch only, its right leaf the other two
    assert tree1.visits[left1][1] == 1
    assert tree1.q[left1][1] == pytest.approx(q1, abs=1e-12)
    assert tree1.visits[right1][1] == 2


def _suffix_returns(steps: int, bootstrap: float, g: float = 0.99) -> list[float]:
    """Eq. (9)'s targets of an epoch of ``steps`` steps of -1, from each of its steps."""
    out = []
    for k in range(steps, 0, -1):
        value = bootstrap
        for _ in range(k):
            value = -1 + g * value
        out.append(value)
    return out


def test_first_tree_decisions_keep_one_trees_epochs_and_the_others_learn_their_own_leaves() -> None:
    # The walk of the test above with ensemble_decisions = "first": the agent decides only when
    # tree 0's leaf changes (at 0.52), so 2 epochs instead of 3; tree 1 learns the first
    # decision's stretch as one epoch per run of its own leaves (0.02-0.22 | 0.32-0.42).
    agent, stats = _walked_once(ensemble_trees=2, ensemble_decisions="first")
    tree0, tree1 = agent.members
    b = B
    assert stats.steps == 10
    assert stats.epochs == 2
    left0, right0 = tree0.partition.leaf_of([0.1]), tree0.partition.leaf_of([0.6])
    left1, right1 = tree1.partition.leaf_of([0.1]), tree1.partition.leaf_of([0.3])
    mean = np.mean
    assert tree0.visits[left0][1] == 1
    assert tree0.q[left0][1] == pytest.approx(0.5 * b + 0.5 * mean(_suffix_returns(5, b)))
    assert tree0.visits[right0][1] == 1
    assert tree0.q[right0][1] == pytest.approx(0.5 * b + 0.5 * mean(_suffix_returns(5, 0.0)))
    assert tree1.visits[left1][1] == 1
    assert tree1.q[left1][1] == pytest.approx(0.5 * b + 0.5 * mean(_suffix_returns(3, b)))
    assert tree1.visits[right1][1] == 2
    first = 0.5 * b + 0.5 * mean(_suffix_returns(2, b))
    assert tree1.q[right1][1] == pytest.approx(0.5 * first + 0.5 * mean(_suffix_returns(5, 0.0)))


def test_ensemble_decisions_are_checked() -> None:
    with pytest.raises(ValueError, match="ensemble_decisions must be one of"):
        plain_config(ensemble_trees=2, ensemble_decisions="all")
    with pytest.raises(ValueError, match=r"ensemble_decisions = 'first' needs ensemble_trees >= 2"):
        plain_config(ensemble_decisions="first")
    assert plain_config(ensemble_trees=2).ensemble_decisions == "any"


def test_actions_follow_the_mean_of_the_trees_rows() -> None:
    env = Walk()
    agent = TreeEnsembleAgent(
        env.observation_space, env.action_space, "greedy", 0, plain_config(ensemble_trees=2)
    )
    tree0, tree1 = agent.members
    leaf0, leaf1 = tree0.partition.leaf_of([0.1]), tree1.partition.leaf_of([0.1])
    tree0.q[leaf0] = [1.0, 0.0]
    tree1.q[leaf1] = [-3.0, 0.0]
    assert agent.mean_row([leaf0, leaf1]) == [-1.0, 0.0]
    assert agent.predict(np.array([0.1])) == 1  # tree 0 alone would pick action 0


def test_one_tree_is_the_plain_tree_bit_for_bit() -> None:
    env = gym.make("CartPole-v1")
    # the general preset without its loop options (hold_terminals, collision_splits,
    # failure_gamma and its measure, greedy_tie_trial): TreeAgent's loop can run it
    config = dataclasses.replace(
        preset("general").config,
        hold_terminals=None,
        collision_splits=False,
        failure_gamma=None,
        failure_measure="mean",
        greedy_tie_trial=None,
    )
    plain = TreeAgent(env.observation_space, env.action_space, "adaptive+tabu", 3, config)
    one = TreeEnsembleAgent(env.observation_space, env.action_space, "adaptive+tabu", 3, config)
    a = plain.learn(env, 25, reset_seed=3)
    b = one.learn(env, 25, reset_seed=3)
    assert a == b
    assert plain.q == one.q
    env.close()


def test_bad_ensembles_are_refused_with_the_field_named() -> None:
    with pytest.raises(ValueError, match="ensemble_trees = 2 needs a presplit"):
        TreeConfig(ensemble_trees=2)
    with pytest.raises(ValueError, match="ensemble_trees must be an int >= 1"):
        TreeConfig(ensemble_trees=0)
    with pytest.raises(ValueError, match="at most 64"):
        TreeConfig(ensemble_trees=65, presplit_each_dimension=True)
    with pytest.raises(ValueError, match="cannot be combined"):
        TreeConfig(ensemble_trees=2, presplit_each_dimension=True, leaves_per_terminal=4)
    config = plain_config(ensemble_trees=2)
    env = Walk()
    with pytest.raises(ValueError, match=r"needs agent\.tree_ensemble\.TreeEnsembleAgent"):
        TreeAgent(env.observation_space, env.action_space, "greedy", 0, config)
    assert tree_agent_class(config) is TreeEnsembleAgent
    assert tree_agent_class(plain_config()) is TreeAgent
    agent = TreeEnsembleAgent(env.observation_space, env.action_space, "greedy", 0, config)
    with pytest.raises(ValueError, match="has no file format yet"):
        agent.save("x.npz")


def test_decision_steps_cut_greedy_epochs_but_not_held_runs(tmp_path: Any) -> None:
    env = Walk()
    config = plain_config(decision_steps=2)
    agent = tree_agent_class(config)(env.observation_space, env.action_space, "greedy", 0, config)
    assert type(agent) is TreeEnsembleAgent
    for row in agent.q:
        row[:] = [-1e6, 1e-9]
    stats = agent.learn(env, 1, reset_seed=0)[0]
    # inputs 0.02 0.12 | 0.22 0.32 | 0.42 | (the leaf changes) 0.52 0.62 | 0.72 0.82 | 0.92
    assert (stats.steps, stats.epochs) == (10, 6)
    # an exploratory action is still held for max_epoch_steps (None: to the episode's end)
    held = dataclasses.replace(config, hold_exploration=True, decision_steps=1)
    explorer = TreeEnsembleAgent(env.observation_space, env.action_space, "epsilon-greedy", 0, held)
    explorer.exploration._epsilon = 1.0  # type: ignore[attr-defined]
    stats = explorer.learn(env, 1, reset_seed=0)[0]
    assert stats.epochs == 1
    assert stats.steps >= 10
    # one tree on this loop saves and loads like a TreeAgent
    path = agent.save(tmp_path / "agent.npz")
    loaded = TreeAgent.load(path)
    assert type(loaded) is TreeEnsembleAgent
    assert loaded.q == agent.q
    assert loaded.config.decision_steps == 2
    with pytest.raises(ValueError, match="decision_steps must be a positive int or None"):
        TreeConfig(decision_steps=0)
    with pytest.raises(ValueError, match=r"decision_steps = 2 needs agent\.tree_ensemble"):
        TreeAgent(env.observation_space, env.action_space, "greedy", 0, config)


def test_a_cut_inside_the_leaf_continues_greedily_past_the_tabu_list() -> None:
    # greedy + tabu: every epoch lists (leaf, action). Asked at every one-step cut, the strategy
    # would switch to action 0 (0.05 a step) each second step; the cut keeps the greedy action 1.
    env = Walk()
    config = plain_config(decision_steps=1)
    agent = TreeEnsembleAgent(env.observation_space, env.action_space, "greedy+tabu", 0, config)
    for row in agent.q:
        row[:] = [-1e6, 1e-9]
    stats = agent.learn(env, 1, reset_seed=0)[0]
    assert (stats.steps, stats.epochs) == (10, 10)


def test_hold_steps_cap_a_held_run_only() -> None:
    env = Walk()
    config = plain_config(hold_exploration=True, max_epoch_steps=None, hold_steps=3)
    explorer = tree_agent_class(config)(
        env.observation_space, env.action_space, "epsilon-greedy", 0, config
    )
    explorer.exploration._epsilon = 1.0  # type: ignore[attr-defined]
    stats = explorer.learn(env, 1, reset_seed=0)[0]
    # every choice is random and held for 3 steps (the last run may be cut by the end)
    assert stats.epochs == -(-stats.steps // 3)
    with pytest.raises(ValueError, match="hold_steps must be a positive int or None"):
        TreeConfig(hold_steps=0)


def test_decisions_from_the_first_terminal_on(tmp_path: Any) -> None:
    env = Walk()
    config = plain_config(decision_steps=2, decision_from_terminal=True)
    agent = tree_agent_class(config)(env.observation_space, env.action_space, "greedy", 0, config)
    for row in agent.q:
        row[:] = [-1e6, 1e-9]
    first, second = agent.learn(env, 2, reset_seed=0)
    assert first.epochs == 2  # no terminal seen yet: the leaf change at 0.5 only
    assert second.epochs == 6  # then every second step as well
    assert agent.terminals_seen == 2
    loaded = TreeAgent.load(agent.save(tmp_path / "agent.npz"))
    assert loaded.terminals_seen == 2  # type: ignore[attr-defined]


def test_held_exploration_stops_after_hold_terminals_terminals(tmp_path: Any) -> None:
    # Every choice random (epsilon 1). One terminal allowed: episode 0 holds its random actions
    # (one epoch per leaf crossed, learnt as a held run: the whole episode is one choice), and
    # from episode 1 on each random action lasts one epoch, ending at the leaf change at 0.5.
    env = Walk()
    config = plain_config(hold_exploration=True, hold_terminals=1)
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, "epsilon-greedy", 0, config
    )
    assert type(agent) is TreeEnsembleAgent
    agent.exploration._epsilon = 1.0  # type: ignore[attr-defined]
    first, second, third = agent.learn(env, 3, reset_seed=0)
    assert first.epochs == 1  # held to the goal, across the split at 0.5
    assert (second.epochs, third.epochs) == (2, 2)  # not held: a new choice at the split
    assert agent.terminals_seen == 3
    # the same agent without the option holds every episode's random action
    always = dataclasses.replace(config, hold_terminals=None)
    holder = TreeAgent(env.observation_space, env.action_space, "epsilon-greedy", 0, always)
    holder.exploration._epsilon = 1.0  # type: ignore[attr-defined]
    assert [s.epochs for s in holder.learn(env, 3, reset_seed=0)] == [1, 1, 1]
    # the count of terminals travels with a saved agent, so a loaded one does not hold again
    loaded = TreeAgent.load(agent.save(tmp_path / "agent.npz"))
    assert loaded.terminals_seen == 3  # type: ignore[attr-defined]
    loaded.exploration._epsilon = 1.0  # type: ignore[attr-defined]
    assert loaded.learn(env, 1, reset_seed=5)[0].epochs == 2


def test_an_episode_after_a_truncated_one_holds_again(tmp_path: Any) -> None:
    # Every choice random, the walk cut at 12 steps: action 1 reaches the goal in 10 steps,
    # action 0 (0.05 a step) crosses the split at 0.5 after 10 and is cut at 12. A held episode
    # is one choice (1 epoch); an unheld one chooses again at the split (2 epochs). With one
    # terminal allowed, an episode holds until the first goal, and after any cut episode.
    env = gym.wrappers.TimeLimit(Walk(), max_episode_steps=12)
    config = plain_config(hold_exploration=True, hold_terminals=1, hold_after_truncation=True)
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, "epsilon-greedy", 0, config
    )
    agent.exploration._epsilon = 1.0  # type: ignore[attr-defined]
    episodes = agent.learn(env, 30, reset_seed=0)
    goals = 0
    cut_before = False
    kinds = set()
    for episode in episodes:
        held = goals < 1 or cut_before
        assert episode.epochs == (1 if held else 2)
        kinds.add((held, goals > 0))
        goals += not episode.truncated
        cut_before = episode.truncated
    assert kinds == {(True, False), (True, True), (False, True)}  # every case met
    assert agent.last_truncated is episodes[-1].truncated
    loaded = TreeAgent.load(agent.save(tmp_path / "agent.npz"))
    assert loaded.last_truncated is agent.last_truncated  # type: ignore[attr-defined]


def test_hold_terminals_is_off_by_default_and_checked() -> None:
    assert TreeConfig().hold_terminals is None
    assert type(tree_agent_class(TreeConfig())) is not TreeEnsembleAgent
    with pytest.raises(ValueError, match="hold_after_truncation = True needs hold_terminals"):
        TreeConfig(hold_after_truncation=True)
    with pytest.raises(TypeError, match="hold_after_truncation must be a bool, got 1"):
        TreeConfig(hold_terminals=3, hold_after_truncation=1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"hold_terminals = 1 needs agent\.tree_ensemble"):
        TreeAgent(
            Walk.observation_space, Walk.action_space, "greedy", 0, plain_config(hold_terminals=1)
        )


def test_hold_crossings_cap_a_held_run_at_a_multiple_of_the_mean_leaf_crossing(
    tmp_path: Any,
) -> None:
    # One tree presplit at 0.5. A greedy episode crosses the split once, after 5 steps of 0.1
    # (0.02 -> 0.52); its last epoch ends at the goal inside the same leaf (not a crossing).
    env = Walk()
    config = plain_config(hold_exploration=True, hold_crossings=0.4)
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, "epsilon-greedy", 0, config
    )
    assert type(agent) is TreeEnsembleAgent
    for row in agent.q:
        row[:] = [-1e6, 1e-9]
    agent.exploration._epsilon = 0.0  # type: ignore[attr-defined]
    first = agent.learn(env, 1, reset_seed=0)[0]
    assert (first.steps, first.epochs) == (10, 2)
    assert (agent.crossing_steps, agent.crossings) == (5, 1)
    # Every choice now random and held: each run ends after ceil(0.4 x 5) = 2 steps, and held
    # runs are not crossings (the mean stays 5).
    agent.exploration._epsilon = 1.0  # type: ignore[attr-defined]
    second = agent.learn(env, 1, reset_seed=1)[0]
    assert second.epochs == -(-second.steps // 2)
    assert (agent.crossing_steps, agent.crossings) == (5, 1)
    # the counts travel with a saved agent
    loaded = TreeAgent.load(agent.save(tmp_path / "agent.npz"))
    assert (loaded.crossing_steps, loaded.crossings) == (5, 1)  # type: ignore[attr-defined]


def test_hold_crossings_is_off_by_default_and_checked() -> None:
    assert TreeConfig().hold_crossings is None
    assert preset("general").config.hold_crossings is None
    assert type(tree_agent_class(TreeConfig())) is not TreeEnsembleAgent
    for bad in (0, -1.0, float("nan"), float("inf"), True, "2"):
        with pytest.raises(ValueError, match="hold_crossings must be a positive number or None"):
            TreeConfig(hold_crossings=bad)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="set one of them"):
        TreeConfig(hold_crossings=2.0, hold_steps=5)
    with pytest.raises(ValueError, match=r"hold_crossings = 2.0 needs agent\.tree_ensemble"):
        TreeAgent(
            Walk.observation_space, Walk.action_space, "greedy", 0, plain_config(hold_crossings=2.0)
        )


class Fall(Walk):
    """Walk with +1 a step: reaching x >= 1 ends the episode as CartPole's fall ends it."""

    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict]:
        obs, _, terminated, truncated, info = super().step(action)
        return obs, 1.0, terminated, truncated, info


def _gated_agent(env: gym.Env) -> TreeEnsembleAgent:
    config = plain_config(decision_steps=2, decision_on_failure=True, gamma=0.5)
    agent = tree_agent_class(config)(env.observation_space, env.action_space, "greedy", 0, config)
    assert isinstance(agent, TreeEnsembleAgent)
    for row in agent.q:
        row[:] = [-1e6, 0.0]  # greedy takes action 1; its values start at q_init's 0
    return agent


def test_decisions_on_failure_open_where_the_terminal_ends_positive_rewards() -> None:
    # Greedy takes action 1: x = 0.02, 0.12, ..., 0.92, 1.02; the split at 0.5 is crossed
    # after 5 steps, and the episode ends 5 steps later.
    agent = _gated_agent(Fall())
    right = agent.partition.leaf_of([0.9])
    first = agent.learn(Fall(), 1, reset_seed=0)[0]
    # Episode 0: nothing measured before it. Its one non-terminal epoch ended at x = 0.52 with
    # r = 1, bootstrapping from the right leaf's unlearnt 0: target 1, equal to the terminal
    # step's reward 1, so no failure yet.
    assert first.epochs == 2
    assert (agent.terminals_seen, agent.terminal_reward_sum) == (1, 1.0)
    assert (agent.targets, agent.target_sum) == (1, 1.0)
    assert not agent.terminals_fail
    learnt = agent.q[right][1]
    assert learnt > 0.0
    second = agent.learn(Fall(), 1, reset_seed=1)[0]
    assert second.epochs == 2  # the gate is read at the episode's start: still shut
    # Episode 1's crossing bootstraps from what episode 0 taught the right leaf
    assert (agent.targets, agent.target_sum) == (2, 1.0 + 1.0 + 0.5 * learnt)
    assert agent.terminal_reward_sum == 2.0
    assert agent.terminals_fail  # mean target above 1: ending the episode loses value
    third = agent.learn(Fall(), 1, reset_seed=2)[0]
    assert third.epochs == 6  # re-decided every second step from now on
    assert agent.targets == 7


def test_decisions_on_failure_stay_shut_where_the_terminal_is_a_goal(tmp_path: Any) -> None:
    agent = _gated_agent(Walk())  # -1 a step: the end at x >= 1 is a goal
    config = plain_config(gamma=0.5)  # the gated agent's, without the option
    plain = tree_agent_class(config)(
        Walk().observation_space, Walk().action_space, "greedy", 0, config
    )
    for row in plain.q:
        row[:] = [-1e6, 0.0]
    gated = agent.learn(Walk(), 3, reset_seed=0)
    assert [s.epochs for s in gated] == [2, 2, 2]
    assert not agent.terminals_fail
    # target -1 + 0.5 max Q(right leaf) < -1 once the right leaf has learnt; the terminal -1
    assert agent.terminal_reward_sum == -3.0
    assert agent.target_sum / agent.targets < -1.0
    assert [s.episode_return for s in gated] == [
        s.episode_return for s in plain.learn(Walk(), 3, reset_seed=0)
    ]
    assert [list(row) for row in agent.q] == [list(row) for row in plain.q]
    loaded = TreeAgent.load(agent.save(tmp_path / "agent.npz"))
    assert isinstance(loaded, TreeEnsembleAgent)
    assert (loaded.terminal_reward_sum, loaded.target_sum, loaded.targets) == (
        agent.terminal_reward_sum,
        agent.target_sum,
        agent.targets,
    )


def _discounting_agent(env: gym.Env, **changes: Any) -> TreeEnsembleAgent:
    """Greedy on action 1 as :func:`_gated_agent`, gamma 0.5, with ``changes`` (the ensemble's
    loop with or without them)."""
    config = plain_config(gamma=0.5, **changes)
    agent = TreeEnsembleAgent(env.observation_space, env.action_space, "greedy", 0, config)
    for row in agent.q:
        row[:] = [-1e6, 0.0]
    return agent


def test_the_failure_discount_latches_once_the_terminals_are_failures(tmp_path: Any) -> None:
    agent = _discounting_agent(Fall(), failure_gamma=0.9)
    plain = _discounting_agent(Fall())
    # Episodes 0 and 1 are the run without the option (the measure opens after episode 1,
    # as in test_decisions_on_failure_open_where_the_terminal_ends_positive_rewards)
    for seed in (0, 1):
        assert agent.learn(Fall(), 1, reset_seed=seed) == plain.learn(Fall(), 1, reset_seed=seed)
        assert agent.q == plain.q
        assert not agent.failure_discount
        assert agent.discount == 0.5
    assert agent.terminals_fail
    # From episode 2 on the agent learns as one whose gamma is 0.9, from the same state
    longer = _discounting_agent(Fall())
    longer.q = [list(row) for row in agent.q]
    longer.config = dataclasses.replace(longer.config, gamma=0.9)
    latched = agent.learn(Fall(), 2, reset_seed=2)
    assert [(s.steps, s.epochs) for s in latched] == [
        (s.steps, s.epochs) for s in longer.learn(Fall(), 2, reset_seed=2)
    ]
    assert agent.failure_discount
    assert agent.discount == 0.9
    assert agent.q == longer.q
    plain.learn(Fall(), 2, reset_seed=2)
    assert agent.q != plain.q  # gamma 0.5 learns other values
    # The latch survives a file, and stays shut in an agent that had not latched
    loaded = TreeAgent.load(agent.save(tmp_path / "latched.npz"))
    assert isinstance(loaded, TreeEnsembleAgent)
    assert loaded.failure_discount
    assert loaded.discount == 0.9
    fresh = TreeAgent.load(_discounting_agent(Fall(), failure_gamma=0.9).save(tmp_path / "f.npz"))
    assert isinstance(fresh, TreeEnsembleAgent)
    assert not fresh.failure_discount
    assert fresh.discount == 0.5


def test_the_failure_discount_leaves_a_run_to_a_goal_as_it_was() -> None:
    agent = _discounting_agent(Walk(), failure_gamma=0.9)  # -1 a step: the end is a goal
    plain = _discounting_agent(Walk())
    assert agent.learn(Walk(), 4, reset_seed=0) == plain.learn(Walk(), 4, reset_seed=0)
    assert agent.q == plain.q
    assert not agent.failure_discount
    assert agent.discount == 0.5


class FallOrGoal(Fall):
    """Fall, whose first episode ends at a goal that pays +5 on its terminal step."""

    episodes = 0

    def reset(self, *, seed: int | None = None, options: Any = None) -> tuple[np.ndarray, dict]:
        FallOrGoal.episodes += 1
        return super().reset(seed=seed, options=options)

    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict]:
        obs, reward, terminated, truncated, info = super().step(action)
        goal = terminated and FallOrGoal.episodes == 1
        return obs, 5.0 if goal else reward, terminated, truncated, info


def test_every_terminal_must_fail_for_the_every_measure() -> None:
    latched = {}
    for measure in ("mean", "every"):
        FallOrGoal.episodes = 0
        agent = _discounting_agent(FallOrGoal(), failure_gamma=0.9, failure_measure=measure)
        agent.learn(FallOrGoal(), 12, reset_seed=0)
        assert agent.terminal_reward_max == 5.0
        assert agent.terminals_fail  # the falls outweigh the one goal in the mean
        assert not agent.every_terminal_fails  # the goal paid more than going on
        latched[measure] = agent.failure_discount
    assert latched == {"mean": True, "every": False}


def test_the_every_measure_is_the_mean_where_every_terminal_pays_alike(tmp_path: Any) -> None:
    mean = _discounting_agent(Fall(), failure_gamma=0.9)
    every = _discounting_agent(Fall(), failure_gamma=0.9, failure_measure="every")
    assert every.learn(Fall(), 4, reset_seed=0) == mean.learn(Fall(), 4, reset_seed=0)
    assert every.q == mean.q
    assert every.failure_discount
    assert mean.failure_discount
    loaded = TreeAgent.load(every.save(tmp_path / "every.npz"))
    assert isinstance(loaded, TreeEnsembleAgent)
    assert loaded.terminal_reward_max == 1.0
    assert loaded.every_terminal_fails


def test_a_file_without_the_largest_terminal_reward_loads_as_none(tmp_path: Any) -> None:
    """Files written before part 20 have no terminal_reward_max; their config's measure is
    "mean", which does not read it."""
    agent = _discounting_agent(Fall(), failure_gamma=0.9)
    agent.learn(Fall(), 2, reset_seed=0)
    good = agent.save(tmp_path / "good.npz")
    with np.load(good, allow_pickle=False) as data:
        arrays = {key: data[key].copy() for key in data.files}
    meta = json.loads(arrays.pop("metadata").tobytes())
    del meta["learner"]["loop"]["terminal_reward_max"]
    older = tmp_path / "older.npz"
    np.savez(older, metadata=np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8), **arrays)
    loaded = TreeAgent.load(older)
    assert isinstance(loaded, TreeEnsembleAgent)
    assert loaded.terminal_reward_max is None
    assert agent.terminal_reward_max == 1.0
    assert loaded.q == agent.q


def test_every_tree_of_an_ensemble_takes_the_latched_discount() -> None:
    agent = _discounting_agent(Fall(), failure_gamma=0.9, ensemble_trees=2)
    member = agent.members[1]
    assert member.discount == 0.5
    agent.failure_discount = True
    assert member.discount == 0.9


def test_the_failure_discount_is_checked_by_name() -> None:
    for bad in (1.5, -0.1, float("nan")):
        with pytest.raises(ValueError, match=r"TreeConfig.failure_gamma must be in \[0.0, 1.0\]"):
            TreeConfig(failure_gamma=bad)
    for wrong in ("0.9", True):
        with pytest.raises(TypeError, match=r"TreeConfig\.failure_gamma must be a number or None"):
            TreeConfig(failure_gamma=wrong)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"failure_measure must be one of \['mean', 'every'\]"):
        TreeConfig(failure_gamma=0.9, failure_measure="max")
    with pytest.raises(ValueError, match="failure_measure = 'every' needs failure_gamma"):
        TreeConfig(failure_measure="every")
    config = TreeConfig(failure_gamma=0.9995)
    assert config.loop_options() == {"failure_gamma": 0.9995}
    assert tree_agent_class(config) is TreeEnsembleAgent
    with pytest.raises(ValueError, match=r"failure_gamma = 0\.9995 needs agent\.tree_ensemble"):
        TreeAgent(Walk().observation_space, Walk().action_space, "greedy", 0, config)


def _edit_loop(source: Any, target: Any, name: str, value: object) -> Any:
    with np.load(source, allow_pickle=False) as data:
        arrays = {key: data[key].copy() for key in data.files}
    meta = json.loads(arrays.pop("metadata").tobytes())
    meta["learner"]["loop"][name] = value
    np.savez(target, metadata=np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8), **arrays)
    return target


@pytest.mark.parametrize(
    ("name", "value", "defect"),
    [
        ("target_sum", "1.0", r"learner loop target_sum '1\.0' is not a number"),
        ("target_sum", True, r"learner loop target_sum True is not a number"),
        ("terminal_reward_sum", 1e400, r"not valid JSON|is not finite"),
        ("targets", -1, r"learner loop targets -1 is not an int >= 0"),
        ("targets", 2.5, r"learner loop targets 2\.5 is not an int >= 0"),
        ("last_truncated", 1, r"learner loop last_truncated 1 is not a bool"),
        ("last_truncated", "false", r"learner loop last_truncated 'false' is not a bool"),
        ("last_truncated", None, r"learner loop last_truncated None is not a bool"),
        ("failure_discount", 1, r"learner loop failure_discount 1 is not a bool"),
        ("failure_discount", "true", r"learner loop failure_discount 'true' is not a bool"),
        ("terminal_reward_max", "1", r"learner loop terminal_reward_max '1' is not a number"),
        ("terminal_reward_max", False, r"terminal_reward_max False is not a number"),
    ],
)
def test_a_damaged_failure_measure_in_a_file_is_refused_by_name(
    tmp_path: Any, name: str, value: object, defect: str
) -> None:
    agent = _gated_agent(Fall())
    agent.learn(Fall(), 1, reset_seed=0)
    good = agent.save(tmp_path / "good.npz")
    bad = _edit_loop(good, tmp_path / "bad.npz", name, value)
    with pytest.raises(ValueError, match=defect) as error:
        TreeAgent.load(bad)
    assert str(bad) in str(error.value)


def test_decisions_on_failure_are_checked() -> None:
    with pytest.raises(ValueError, match="decision_on_failure = True needs decision_steps"):
        TreeConfig(decision_on_failure=True)
    with pytest.raises(TypeError, match="decision_on_failure must be a bool, got 1"):
        TreeConfig(decision_steps=1, decision_on_failure=1)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="decision_from_terminal must be a bool, got 'yes'"):
        TreeConfig(decision_from_terminal="yes")  # type: ignore[arg-type]


def test_a_blended_model_epoch_takes_lambda_of_the_return_after_it() -> None:
    model = LeafModel(n_actions=2, window=4)
    first = model.add(0, 1, [0.1], -2.0, 0.5, [0.6], 3)  # the stored epoch's handle
    terminal = model.add(0, 1, [0.2], -1.0, 0.25, None, -1)  # terminal: nothing to blend
    q = [[0.0, 0.0] for _ in range(4)]
    q[3] = [-8.0, -6.0]
    assert model.value(0, 1, q) == ((-2.0 + 0.5 * -6.0) + -1.0) / 2
    assert model.blend(0, 1, first, 0.25, -10.0)
    # R + lam D after = -2 - 1.25, D (1 - lam) = 0.375
    assert model.value(0, 1, q) == ((-3.25 + 0.375 * -6.0) + -1.0) / 2
    assert not model.blend(0, 1, terminal, 0.25, -10.0)  # the terminal epoch
    assert not model.blend(0, 1, array("d", [0.1]), 0.25, -10.0)  # equal, not the stored one
    assert not model.blend(1, 1, first, 0.25, -10.0)  # nothing stored there


def test_model_lambda_one_makes_a_leaf_value_the_episodes_own_return() -> None:
    # Greedy takes action 1: 5 steps to x = 0.52 (the split at 0.5), 5 more to the end.
    env = Walk()
    config = plain_config(planning="sweep", sweep_backups=8, gamma=0.5, model_lambda=1.0)
    agent = tree_agent_class(config)(env.observation_space, env.action_space, "greedy", 0, config)
    assert isinstance(agent, TreeEnsembleAgent)
    for row in agent.q:
        row[:] = [-1e6, 0.0]
    left, right = agent.partition.leaf_of([0.1]), agent.partition.leaf_of([0.9])
    agent.learn(env, 1, reset_seed=0)
    gamma = 0.5
    after = -sum(gamma**j for j in range(5))  # the second epoch, from its first input
    # every input k of the first epoch: its rewards to the crossing, then the observed return
    returns = [-sum(gamma**j for j in range(5 - k)) + gamma ** (5 - k) * after for k in range(5)]
    assert agent.q[left][1] == pytest.approx(sum(returns) / 5, abs=1e-12)
    # the terminal epoch has no bootstrap: eq. (8)'s mean over its inputs, as without lambda
    tail = [-sum(gamma**j for j in range(5 - k)) for k in range(5)]
    assert agent.q[right][1] == pytest.approx(sum(tail) / 5, abs=1e-12)
    # without the option the first epoch bootstraps from the right leaf's value at its end (0)
    plain = plain_config(planning="sweep", sweep_backups=8, gamma=0.5)
    other = tree_agent_class(plain)(env.observation_space, env.action_space, "greedy", 0, plain)
    for row in other.q:
        row[:] = [-1e6, 0.0]
    other.learn(env, 1, reset_seed=0)
    assert other.q[right][1] == agent.q[right][1]
    assert other.q[left][1] != pytest.approx(agent.q[left][1])


def test_a_model_lambda_agent_saves_loads_and_continues_bit_for_bit(tmp_path: Any) -> None:
    """Every loop option is found by one list (TreeConfig.loop_options): a file of a
    model_lambda agent loads as the ensemble's loop, and learns on exactly as the original."""
    env = Walk()
    config = plain_config(planning="sweep", sweep_backups=8, gamma=0.9, model_lambda=0.5)
    assert config.loop_options() == {"model_lambda": 0.5}
    assert plain_config().loop_options() == {}
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, "epsilon-greedy", 3, config
    )
    agent.learn(env, 3, reset_seed=0)
    loaded = TreeAgent.load(agent.save(tmp_path / "lambda.npz"))
    assert type(loaded) is TreeEnsembleAgent
    assert loaded.config == config
    assert loaded.q == agent.q
    ahead = [s.steps for s in agent.learn(env, 3, reset_seed=7)]
    assert [s.steps for s in loaded.learn(env, 3, reset_seed=7)] == ahead
    assert loaded.q == agent.q
    with pytest.raises(ValueError, match=r"model_lambda = 0.5 needs agent\.tree_ensemble"):
        TreeAgent(env.observation_space, env.action_space, "greedy", 0, config)


class Timeout(Walk):
    """Walk cut by a time limit after 5 steps (a truncation: the last epoch bootstraps)."""

    def reset(self, *, seed: int | None = None, options: Any = None) -> tuple[np.ndarray, dict]:
        self.steps = 0
        return super().reset(seed=seed, options=options)

    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict]:
        self.steps += 1
        obs, reward, terminated, _, info = super().step(action)
        return obs, reward, terminated, self.steps >= 5, info


def test_model_lambda_bootstraps_a_truncated_episode_from_the_value_where_it_stopped() -> None:
    # The one epoch (x = 0.02 -> 0.52, 5 steps) ends at the time limit in the right leaf,
    # whose value -4 was set by hand and never learnt in the episode: the return after the
    # epoch is that V-bar, so lambda = 1 gives the one-step value.
    env = Timeout()
    config = plain_config(planning="sweep", sweep_backups=8, gamma=0.5, model_lambda=1.0)
    agent = tree_agent_class(config)(env.observation_space, env.action_space, "greedy", 0, config)
    for row in agent.q:
        row[:] = [-1e6, 0.0]
    left, right = agent.partition.leaf_of([0.1]), agent.partition.leaf_of([0.9])
    agent.q[right][1] = -4.0
    stats = agent.learn(env, 1, reset_seed=0)[0]
    assert stats.truncated
    assert stats.steps == 5
    gamma = 0.5
    returns = [-sum(gamma**j for j in range(5 - k)) + gamma ** (5 - k) * -4.0 for k in range(5)]
    assert agent.q[left][1] == pytest.approx(sum(returns) / 5, abs=1e-12)
    assert agent.q[right][1] == -4.0


def _lambda_one_agent(**changes: Any) -> tuple[TreeEnsembleAgent, int, int]:
    """A model agent with lambda 1 and gamma 0.5 on the walk, its values at q_init's 0 (action
    1 greedy), and its left and right leaves."""
    env = Walk()
    config = plain_config(planning="sweep", sweep_backups=8, gamma=0.5, model_lambda=1.0, **changes)
    agent = tree_agent_class(config)(env.observation_space, env.action_space, "greedy", 0, config)
    assert isinstance(agent, TreeEnsembleAgent)
    for row in agent.q:
        row[:] = [-1e6, 0.0]
    return agent, agent.partition.leaf_of([0.1]), agent.partition.leaf_of([0.9])


@pytest.mark.parametrize(("watkins", "expected"), [(False, -1.75), (True, -1.625)])
def test_model_lambda_watkins_cuts_the_return_at_an_exploratory_epoch(
    watkins: bool, expected: float
) -> None:
    # Epoch A: one greedy step in the left leaf (-1) into the right leaf; epoch B: an
    # exploratory action there, two steps (-1, -1) to the end. gamma 0.5, lambda 1.
    agent, left, right = _lambda_one_agent(model_lambda_watkins=watkins)
    agent._explored = False
    agent._end_epoch(left, 1, [[0.1]], [-1.0], 0.0, [0.6], False)
    agent._explored = True
    agent._end_epoch(right, 1, [[0.6], [0.8]], [-1.0, -1.0], 0.0, [1.0], True)
    assert agent.q[right][1] == (-1.5 + -1.0) / 2  # eq. (8): the mean over B's two inputs
    agent._blend_episode(terminated=True)
    # on-policy: A's return after it is B's own, -1.5: -1 + 0.5 x -1.5; Watkins: V-bar where
    # B began, the right leaf's -1.25: -1 + 0.5 x -1.25
    assert agent.q[left][1] == expected


@pytest.mark.parametrize(("both_tried", "expected"), [(False, -1.625), (True, -1.75)])
def test_model_lambda_tried_only_keeps_the_bootstrap_where_an_action_is_untried(
    both_tried: bool, expected: float
) -> None:
    # Epoch A: one step in the left leaf (-1) into the right leaf; epoch B: two steps there
    # (-1, -1) to the end. gamma 0.5, lambda 1. The right leaf's action 0 is untried unless an
    # epoch of it is stored first (a terminal one: -3, not A's bootstrap, which is the max).
    agent, left, right = _lambda_one_agent(model_lambda_tried_only=True)
    if both_tried:
        agent._end_epoch(right, 0, [[0.7]], [-3.0], 0.0, [1.0], True)
        agent._trace = []  # an earlier episode's
    agent._end_epoch(left, 1, [[0.1]], [-1.0], 0.0, [0.6], False)
    agent._end_epoch(right, 1, [[0.6], [0.8]], [-1.0, -1.0], 0.0, [1.0], True)
    agent._blend_episode(terminated=True)
    # untried: the one-step value -1 + 0.5 x V-bar(right) = -1 + 0.5 x -1.25; both tried: the
    # episode's own return after A, -1 + 0.5 x -1.5
    assert agent.q[left][1] == expected


@pytest.mark.parametrize(
    ("changes", "defect"),
    [
        ({"model_lambda_watkins": True}, r"model_lambda_watkins = True needs model_lambda > 0"),
        ({"model_lambda_tried_only": True}, r"model_lambda_tried_only = True needs model_lambda"),
        (
            {"model_lambda": 1.5, "planning": "sweep"},
            r"model_lambda must be a number in \[0, 1\], got 1\.5",
        ),
        (
            {"model_lambda": True, "planning": "sweep"},
            r"model_lambda must be a number in \[0, 1\], got True",
        ),
        ({"model_lambda": "0.5", "planning": "sweep"}, r"got '0\.5'"),
        ({"model_lambda": float("nan"), "planning": "sweep"}, r"got nan"),
        ({"model_lambda": 0.5}, r"model_lambda = 0\.5 needs planning = 'sweep'"),
        (
            {
                "model_lambda": 0.5,
                "planning": "sweep",
                "ensemble_trees": 2,
                "presplit_each_dimension": True,
            },
            r"model_lambda = 0\.5 works with one tree only",
        ),
    ],
)
def test_model_lambda_is_checked(changes: dict[str, Any], defect: str) -> None:
    with pytest.raises(ValueError, match=defect):
        TreeConfig(**changes)


def test_model_lambda_cuts_must_be_bools() -> None:
    for name in ("model_lambda_watkins", "model_lambda_tried_only"):
        with pytest.raises(TypeError, match=rf"{name} must be a bool, got 1"):
            TreeConfig(model_lambda=0.5, planning="sweep", **{name: 1})


@pytest.mark.parametrize(
    "name", ["max_epoch_steps", "hold_steps", "decision_steps", "hold_terminals"]
)
@pytest.mark.parametrize("value", [True, 0, -3, 2.5, "5"])
def test_step_counts_are_positive_ints_or_none(name: str, value: object) -> None:
    with pytest.raises(ValueError, match=rf"TreeConfig\.{name} must be a positive int or None"):
        TreeConfig(**{name: value})


def test_a_restored_model_epoch_takes_its_one_step_form_back() -> None:
    model = LeafModel(n_actions=2, window=4)
    first = model.add(0, 1, [0.1], -2.0, 0.5, [0.6], 3)
    assert first is model.last_added
    assert list(first) == [0.1]
    q = [[0.0, 0.0] for _ in range(4)]
    q[3] = [-8.0, -6.0]
    assert model.locate(0, 1, first) == 0
    assert model.locate(0, 1, array("d", [0.1])) is None  # an equal input is another epoch
    assert model.first_input(1, 0) is first
    assert model.blend(0, 1, first, 0.25, -10.0) == (-2.0, 0.5)
    assert model.value(0, 1, q) == -3.25 + 0.375 * -6.0
    assert model.restore(0, 1, first, -2.0, 0.5)
    assert model.value(0, 1, q) == -2.0 + 0.5 * -6.0
    assert not model.restore(1, 1, first, -2.0, 0.5)  # not stored there
    with pytest.raises(IndexError):
        model.first_input(1, 1)


def _left_records(agent: Any) -> list[tuple[float, float]]:
    """(R, D) of each stored epoch of the left leaf's action 1, oldest first."""
    assert agent.model is not None
    left = agent.partition.leaf_of([0.1])
    state = dict((key, records) for key, records in agent.model.state()["records"])
    return [(r, d) for _, r, d, _, _ in state[left * 2 + 1]]


def test_model_lambda_episodes_undo_each_blend_after_that_many_later_episodes() -> None:
    # Greedy action 1 on the walk every episode, whatever the values: the three agents see
    # the same epochs. Kept for one later episode, episode 0's blend is undone at the end of
    # episode 1 (its one-step form back, as the agent without lambda stores it), while
    # episode 1's own blend is the one the agent that keeps every blend makes.
    recent, left, _ = _lambda_one_agent(model_lambda_episodes=1)
    always, _, _ = _lambda_one_agent()
    plain_cfg = plain_config(planning="sweep", sweep_backups=8, gamma=0.5)
    plain = tree_agent_class(plain_cfg)(
        Walk().observation_space, Walk().action_space, "greedy", 0, plain_cfg
    )
    for row in plain.q:
        row[:] = [-1e6, 0.0]
    recent.learn(Walk(), 1, reset_seed=0)
    always.learn(Walk(), 1, reset_seed=0)
    plain.learn(Walk(), 2, reset_seed=0)
    assert _left_records(recent) == _left_records(always) != _left_records(plain)[:1]
    recent.learn(Walk(), 1, reset_seed=1)
    always.learn(Walk(), 1, reset_seed=1)
    one_step, blended = _left_records(recent)
    assert one_step == _left_records(plain)[0]
    assert blended == _left_records(always)[1]
    assert _left_records(always)[0] != one_step
    assert recent.q[left][1] == recent.model.value(left, 1, recent.q)  # type: ignore[union-attr]


def test_model_lambda_lower_bound_never_takes_the_return_below_the_value_where_it_ended() -> None:
    # lambda 1, gamma 0.5: the return after the first epoch is the second epoch's, -1.9375
    # from its first input; the right leaf's value at the episode's end is the mean over
    # that epoch's inputs, -1.6125, above it: the bound takes that value instead.
    agent, left, right = _lambda_one_agent(model_lambda_lower_bound=True)
    agent.learn(Walk(), 1, reset_seed=0)
    gamma = 0.5
    tail = [-sum(gamma**j for j in range(5 - k)) for k in range(5)]
    v_end = sum(tail) / 5
    assert agent.q[right][1] == pytest.approx(v_end, abs=1e-12)
    assert -sum(gamma**j for j in range(5)) < v_end
    returns = [-sum(gamma**j for j in range(5 - k)) + gamma ** (5 - k) * v_end for k in range(5)]
    assert agent.q[left][1] == pytest.approx(sum(returns) / 5, abs=1e-12)
    unbounded, _, _ = _lambda_one_agent()
    unbounded.learn(Walk(), 1, reset_seed=0)
    assert unbounded.q[left][1] < agent.q[left][1]


class NoisyWalk(Walk):
    """Walk whose steps are longer by a uniform draw of up to 0.05 (the reset seed's): the
    right leaf's value moves from episode to episode, so an undone blend changes values."""

    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict]:
        self.x += float(self.np_random.uniform(0.0, 0.05))
        return super().step(action)


def _recent_agent() -> TreeEnsembleAgent:
    config = plain_config(
        planning="sweep",
        sweep_backups=8,
        gamma=0.9,
        model_lambda=0.8,
        model_lambda_episodes=2,
        model_lambda_lower_bound=True,
    )
    explore = make_exploration("epsilon-greedy", epsilon=0.3)  # the end leaf's value varies
    agent = tree_agent_class(config)(
        Walk().observation_space, Walk().action_space, explore, 5, config
    )
    assert isinstance(agent, TreeEnsembleAgent)
    return agent


def test_recent_blends_save_load_and_continue_bit_for_bit(tmp_path: Any) -> None:
    agent = _recent_agent()
    agent.learn(NoisyWalk(), 4, reset_seed=0)
    path = agent.save(tmp_path / "recent.npz")
    loaded = TreeAgent.load(path)
    assert isinstance(loaded, TreeEnsembleAgent)
    assert loaded.blend_state() == agent.blend_state()
    assert len(agent.blend_state()) == 2
    assert all(agent.blend_state())
    ahead = [(s.steps, s.episode_return) for s in agent.learn(NoisyWalk(), 4, reset_seed=9)]
    assert [
        (s.steps, s.episode_return) for s in loaded.learn(NoisyWalk(), 4, reset_seed=9)
    ] == ahead
    assert loaded.q == agent.q
    # without its blends the file's agent would not undo them: the state is needed
    forgetful = TreeAgent.load(_edit_loop(path, tmp_path / "forgot.npz", "blended", []))
    forgetful.learn(NoisyWalk(), 4, reset_seed=9)
    assert forgetful.q != agent.q


@pytest.mark.parametrize(
    ("value", "defect"),
    [
        ("x", "expected a list of at most 2 episodes"),
        ([[], [], []], "expected a list of at most 2 episodes"),
        ([5], "blended episode 0: expected a list"),
        ([[[0, 0, 1.0]]], r"\[0, 0, 1\.0\] is not \[key, index, R, D\]"),
        ([[[True, 0, 1.0, 0.5]]], "is not"),
        ([[[0, 0, "1", 0.5]]], "is not"),
        ([[[0, 0.5, 1.0, 0.5]]], "is not"),
        ([[[999, 0, 1.0, 0.5]]], "holds no epoch 0 of key 999"),
        ([[[1, 10_000, 1.0, 0.5]]], "holds no epoch 10000 of key 1"),
        ("twice", r"epoch \d+ of key \d+ twice"),
        ([[[0, 0, float("nan"), 0.5]]], r"not valid JSON|is not \[key"),
    ],
)
def test_damaged_blends_in_a_file_are_refused_by_name(
    tmp_path: Any, value: object, defect: str
) -> None:
    agent = _recent_agent()
    agent.learn(NoisyWalk(), 4, reset_seed=0)
    row = agent.blend_state()[0][0]  # a stored epoch's [key, index, R, D]
    if value == "twice":
        value = [[row, row]]
    bad = _edit_loop(agent.save(tmp_path / "good.npz"), tmp_path / "bad.npz", "blended", value)
    with pytest.raises(ValueError, match=defect) as error:
        TreeAgent.load(bad)
    assert str(bad) in str(error.value)


def test_a_blend_list_in_a_file_without_recent_blends_is_refused(tmp_path: Any) -> None:
    agent, _, _ = _lambda_one_agent()
    agent.learn(Walk(), 1, reset_seed=0)
    bad = _edit_loop(agent.save(tmp_path / "good.npz"), tmp_path / "bad.npz", "blended", [])
    with pytest.raises(ValueError, match=r"blended epochs without TreeConfig\.model_lambda_ep"):
        TreeAgent.load(bad)


@pytest.mark.parametrize(
    ("changes", "defect"),
    [
        ({"model_lambda_episodes": 4}, r"model_lambda_episodes = 4 needs model_lambda > 0"),
        ({"model_lambda_lower_bound": True}, r"model_lambda_lower_bound = True needs model_"),
        (
            {"model_lambda": 0.5, "planning": "sweep", "model_lambda_episodes": 0},
            r"model_lambda_episodes must be a positive int or None, got 0",
        ),
        (
            {"model_lambda": 0.5, "planning": "sweep", "model_lambda_episodes": True},
            r"got True",
        ),
        (
            {"model_lambda": 0.5, "planning": "sweep", "model_lambda_episodes": 2.0},
            r"got 2\.0",
        ),
    ],
)
def test_recent_lambda_options_are_checked(changes: dict[str, Any], defect: str) -> None:
    with pytest.raises(ValueError, match=defect):
        TreeConfig(**changes)
    with pytest.raises(TypeError, match="model_lambda_lower_bound must be a bool, got 1"):
        TreeConfig(model_lambda=0.5, planning="sweep", model_lambda_lower_bound=1)  # type: ignore[arg-type]


def test_offset_trees_that_would_all_be_the_same_tree_are_refused() -> None:
    """The offsets move only presplit cuts of bounded dimensions. Over an unbounded box (MuJoCo's
    InvertedPendulum) K trees used to be K identical copies: K times the cost, the same runs."""
    config = dataclasses.replace(preset("general").config, ensemble_trees=4)
    unbounded = spaces.Box(-np.inf, np.inf, (4,), np.float64)
    with pytest.raises(ValueError, match=r"ensemble_trees = 4: every tree would be the same tree"):
        TreeEnsembleAgent(unbounded, spaces.Discrete(2), "adaptive+tabu", 0, config)
    bounded = (np.full(4, -1.0), np.full(4, 1.0))
    agent = TreeEnsembleAgent(unbounded, spaces.Discrete(2), "adaptive+tabu", 0, config, bounded)
    cuts = [member.partition.cuts for member in agent.members]
    assert len({tuple(c) for c in cuts}) == 4
    half = spaces.Box(np.array([-1.0, -np.inf]), np.array([1.0, np.inf]), dtype=np.float64)
    mixed = TreeEnsembleAgent(half, spaces.Discrete(2), "adaptive+tabu", 0, config)
    assert len({tuple(m.partition.cuts) for m in mixed.members}) == 4


def test_unbounded_offsets_move_each_trees_cut_in_squashed_coordinates() -> None:
    """``ensemble_unbounded_offsets``: tree k's cut of an unbounded dimension lies where the
    squash ``x / (1 + |x|)`` equals its offset s, at ``x = s / (1 - |s|)``. With K = 4 and four
    dimensions the offsets ((2d + 1) k / 4 mod 1, read in [-1/2, 1/2)) are, by hand: tree 1
    1/4, -1/4, 1/4, -1/4; tree 2 -1/2 in every dimension; tree 3 -1/4, 1/4, -1/4, 1/4."""
    config = dataclasses.replace(
        preset("general").config, ensemble_trees=4, ensemble_unbounded_offsets=True
    )
    unbounded = spaces.Box(-np.inf, np.inf, (4,), np.float64)
    agent = TreeEnsembleAgent(unbounded, spaces.Discrete(2), "adaptive+tabu", 0, config)
    third = 1.0 / 3.0
    expected = [
        [0.0, 0.0, 0.0, 0.0],
        [third, -third, third, -third],
        [-1.0, -1.0, -1.0, -1.0],
        [-third, third, -third, third],
    ]
    for member, cuts in zip(agent.members, expected, strict=True):
        first = {}
        for dim, threshold in member.partition.cuts:
            first.setdefault(dim, threshold)
        assert [first[d] for d in range(4)] == pytest.approx(cuts)
        x = [c + 1e-9 for c in cuts]  # just above every cut: the root's right side each time
        leaf = member.partition.leaf_of(x)
        low, _ = member.partition.leaf_bounds(leaf)
        assert low == pytest.approx(cuts)


def test_unbounded_offsets_need_several_trees_and_leave_bounded_boxes_alone() -> None:
    with pytest.raises(ValueError, match="ensemble_unbounded_offsets = True needs ensemble_trees"):
        TreeConfig(ensemble_unbounded_offsets=True)
    base = dataclasses.replace(preset("general").config, ensemble_trees=4)
    moved = dataclasses.replace(base, ensemble_unbounded_offsets=True)
    box = spaces.Box(-1.0, 1.0, (3,), np.float64)
    plain = TreeEnsembleAgent(box, spaces.Discrete(2), "adaptive+tabu", 0, base)
    offset = TreeEnsembleAgent(box, spaces.Discrete(2), "adaptive+tabu", 0, moved)
    assert [m.partition.cuts for m in plain.members] == [m.partition.cuts for m in offset.members]
    unbounded = spaces.Box(-np.inf, np.inf, (2,), np.float64)
    with pytest.raises(ValueError, match="set ensemble_unbounded_offsets = True"):
        TreeEnsembleAgent(unbounded, spaces.Discrete(2), "adaptive+tabu", 0, base)
