"""TreeConfig.model_bonus_terminals: the model's count bonus only until the goal is first found."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from pathlib import Path
from typing import Any

import gymnasium as gym
import pytest

import bullet_maze  # noqa: F401 (registers the env)
from agent import GridAgent, TreeAgent, TreeConfig, preset
from agent.fast_loop import ineligible_reason
from agent.leaf_model import LeafModel

SWEEP = TreeConfig(
    split_min_samples=20,
    split_min_variance=0.0,
    max_epoch_steps=10,
    planning="sweep",
    model_bonus=0.2,
)
UNTIL_GOAL = dataclasses.replace(SWEEP, model_bonus_terminals=1)


def test_the_default_is_off_and_the_general_preset_leaves_it_off() -> None:
    assert TreeConfig().model_bonus_terminals == 0
    assert preset("paper").config.model_bonus_terminals == 0
    assert preset("general").config.model_bonus_terminals == 0


@pytest.mark.parametrize("bad", [-1, 1.5, True, "1"])
def test_a_bad_count_is_refused_by_name(bad: Any) -> None:
    with pytest.raises((ValueError, TypeError), match="model_bonus_terminals"):
        TreeConfig(model_bonus_terminals=bad)


def test_without_a_goal_the_bonus_applies_as_always(train_corridor: Callable[..., Any]) -> None:
    unreachable = {"goal": (0.95, 0.95), "goal_radius": 0.01}
    a, history_a = train_corridor(SWEEP, 5, **unreachable)
    b, history_b = train_corridor(UNTIL_GOAL, 5, **unreachable)
    assert not any(s.success for s in history_b)
    assert [s.steps for s in history_a] == [s.steps for s in history_b]
    assert a.q == b.q
    assert b.model is not None
    assert b.model.terminals == 0
    assert b._bonus_function() is not None


def test_the_bonus_ends_at_the_first_goal(train_corridor: Callable[..., Any]) -> None:
    always, history_always = train_corridor(SWEEP, 30)
    until, history_until = train_corridor(UNTIL_GOAL, 30)
    first = next(i for i, s in enumerate(history_until) if s.success)
    # the same agent up to the end of the first successful episode
    same = [s.steps for s in history_until[: first + 1]]
    assert same == [s.steps for s in history_always[: first + 1]]
    assert until.model is not None
    assert until.model.terminals == sum(s.success for s in history_until) > 0
    assert until._bonus_function() is None
    assert until._bonus(0, 0) == 0.0
    assert always._bonus_function() is not None
    # no Q-bar keeps a bonus: each modelled pair is its model value, up to the backups the
    # last sweeps left queued (a fresh pass moves no leaf by more than the sweep tolerance)
    q = [list(row) for row in until.q]
    changes = until.model.backup_all(q)
    assert max(changes.values(), default=0.0) < 0.05


def test_the_bonus_steers_the_greedy_policy_before_the_goal(
    train_corridor: Callable[..., Any],
) -> None:
    _none, history_none = train_corridor(dataclasses.replace(SWEEP, model_bonus=0.0), 8)
    _until, history_until = train_corridor(UNTIL_GOAL, 8)
    assert [s.steps for s in history_none] != [s.steps for s in history_until]


def test_the_count_is_saved_and_learning_continues_the_same(
    make_corridor: Callable[..., Any], train_corridor: Callable[..., Any], tmp_path: Path
) -> None:
    agent, _history = train_corridor(UNTIL_GOAL, 15)
    assert agent.model is not None
    assert agent.model.terminals > 0
    loaded = TreeAgent.load(agent.save(tmp_path / "until"))
    assert loaded.model is not None
    assert loaded.model.terminals == agent.model.terminals
    a = [s.steps for s in agent.learn(make_corridor(), 10, reset_seed=5)]
    b = [s.steps for s in loaded.learn(make_corridor(), 10, reset_seed=5)]
    assert a == b
    assert agent.q == loaded.q


@pytest.mark.parametrize("bad", [-1, 2.5, True, "3"])
def test_a_tampered_terminal_count_is_refused(bad: Any) -> None:
    state = LeafModel(4, 8).state()
    state["terminals"] = bad
    with pytest.raises(ValueError, match="terminal count"):
        LeafModel.from_state(4, state)


def test_a_model_saved_before_the_field_loads_with_no_terminals() -> None:
    state = LeafModel(4, 8).state()
    del state["terminals"]
    assert LeafModel.from_state(4, state).terminals == 0


def test_a_grid_agent_ends_its_bonus_too(make_corridor: Callable[..., Any]) -> None:
    corridor = make_corridor()
    agent = GridAgent(
        corridor.observation_space,
        corridor.action_space,
        "epsilon-greedy",
        0,
        UNTIL_GOAL,
        resolution=8,
    )
    history = agent.learn(corridor, 30, reset_seed=0)
    assert any(s.success for s in history)
    assert agent._bonus_function() is None


def test_the_paper_agent_still_takes_the_fast_loop() -> None:
    env = gym.make("BulletMaze-v0", mode="kinematic")
    for config in (TreeConfig(), TreeConfig(model_bonus_terminals=3)):
        agent = TreeAgent(env.observation_space, env.action_space, "adaptive+tabu", 0, config)
        assert ineligible_reason(agent, env) is None
    env.close()
