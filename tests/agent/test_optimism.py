"""TreeConfig.optimistic_untried: untried actions valued at the largest return an epoch has
paid (issue 9, part 16; docs/paper-notes.md, "Optimism for untried actions")."""

from __future__ import annotations

import dataclasses
import json
import warnings
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

from agent import GridAgent, TreeConfig, adapt_env, preset
from agent.fast_loop import ineligible_reason
from agent.optimism import UntriedOptimism
from agent.tree_agent import TreeAgent
from agent.tree_ensemble import tree_agent_class


def test_a_new_bound_raises_only_untried_values_below_it() -> None:
    q = [[0.0, 0.0], [0.0, 3.0], [2.0, 0.5]]
    optimism = UntriedOptimism(2, [0, 1, 2], 0.0)
    optimism.tried(0, 1)
    optimism.tried(2, 0)
    assert optimism.paid(-1.0, q) == {}  # not above the bound (q_init)
    moved = optimism.paid(1.5, q)
    # leaf 0: action 0 untried 0 -> 1.5 (V-bar 0 -> 1.5), action 1 tried; leaf 1: action 0
    # untried 0 -> 1.5 but V-bar stays 3.0, action 1 untried at 3.0 is above the bound;
    # leaf 2: action 1 untried 0.5 -> 1.5 (V-bar stays 2.0, the tried action's)
    assert q == [[1.5, 0.0], [1.5, 3.0], [2.0, 1.5]]
    assert moved == {0: 1.5}
    assert optimism.best == 1.5
    assert optimism.paid(1.5, q) == {}  # the same bound again: nothing


def test_children_inherit_the_parents_untried_actions() -> None:
    optimism = UntriedOptimism(3, [0], 0.0)
    optimism.tried(0, 2)
    optimism.split(0, (1, 2))
    assert optimism.untried == {1 * 3 + 0, 1 * 3 + 1, 2 * 3 + 0, 2 * 3 + 1}
    optimism.tried(2, 0)
    assert optimism.untried == {3, 4, 7}


def test_the_state_round_trips_and_damage_is_named() -> None:
    optimism = UntriedOptimism(2, [1, 2], 0.25)
    optimism.tried(1, 0)
    again = UntriedOptimism.from_state(2, json.loads(json.dumps(optimism.state())), {1, 2})
    assert (again.best, again.untried) == (0.25, optimism.untried)
    for state, defect in (
        ({"best": 0.0}, "keys best and untried"),
        ({"best": True, "untried": []}, "best True is not a number"),
        ({"best": float("inf"), "untried": []}, "not finite"),
        ({"best": 0.0, "untried": [2, -1]}, "key -1 is not an int >= 0"),
        ({"best": 0.0, "untried": [2, 1.5]}, "key 1.5 is not an int"),
        ({"best": 0.0, "untried": [0]}, "key 0 is not on a leaf"),
        ({"best": 0.0, "untried": "3"}, "must be a list"),
    ):
        with pytest.raises(ValueError, match=defect):
            UntriedOptimism.from_state(2, state, {1, 2})


class Chain(gym.Env[np.ndarray, int]):
    """A corridor of 5 cells (an integer input); action 1 moves right, action 0 stays. The
    rightmost cell ends the episode with ``goal`` (default +1); every other step pays
    ``step``. At most 20 steps."""

    def __init__(self, goal: float = 1.0, step: float = 0.0) -> None:
        self.observation_space = gym.spaces.Box(0, 4, (1,), dtype=np.int64)
        self.action_space = gym.spaces.Discrete(2)
        self.goal, self.step_reward = goal, step
        self._x = self._t = 0

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None) -> Any:
        super().reset(seed=seed)
        self._x = self._t = 0
        return np.array([0]), {}

    def step(self, action: int) -> Any:
        self._x = min(4, self._x + int(action))
        self._t += 1
        done = self._x == 4
        reward = self.goal if done else self.step_reward
        return np.array([self._x]), reward, done, self._t >= 20 and not done, {}


def _agent(optimistic: bool, seed: int = 0) -> TreeAgent:
    config = dataclasses.replace(
        preset("general").config, optimistic_untried=optimistic, novelty_cells=None
    )
    env = Chain()
    return tree_agent_class(config)(
        env.observation_space, env.action_space, "epsilon-greedy", seed, config
    )


def test_after_the_first_goal_every_untried_action_is_valued_at_what_it_paid() -> None:
    """The chain's table: before the goal the bound is q_init (0) and nothing moves; the goal
    pays +1 in its last step, and every action no epoch has started with is then valued 1."""
    agent = _agent(True)
    env = Chain()
    for episode in range(50):
        if agent.learn(env, 1, reset_seed=episode)[0].episode_return > 0.0:
            break
        assert agent.optimism is not None
        assert agent.optimism.best == 0.0  # no return above q_init yet: nothing raised
    optimism = agent.optimism
    assert optimism is not None
    assert optimism.best == 1.0
    assert optimism.untried  # the walk to the goal left some actions untried
    for key in optimism.untried:
        leaf, action = divmod(key, 2)
        assert agent.q[leaf][action] == 1.0
        assert agent.visits[leaf][action] == 0


def test_where_no_reward_is_positive_the_option_changes_nothing() -> None:
    """Rewards of -1 a step and 0 at the goal: the bound never rises above q_init, so the run
    is the same to the bit (MountainCar, Acrobot, Pendulum are such tasks)."""
    runs = []
    for optimistic in (False, True):
        config = dataclasses.replace(preset("general").config, optimistic_untried=optimistic)
        env = Chain(goal=0.0, step=-1.0)
        agent = tree_agent_class(config)(
            env.observation_space, env.action_space, "adaptive+tabu", 3, config
        )
        history = agent.learn(env, 30, reset_seed=1)
        runs.append(([h.episode_return for h in history], agent.q))
    assert runs[0] == runs[1]


def test_an_optimistic_agent_saves_and_continues_identically(tmp_path: Path) -> None:
    agent = _agent(True, seed=4)
    env = Chain()
    agent.learn(env, 3, reset_seed=0)
    path = agent.save(tmp_path / "chain")
    again = type(agent).load(path)
    assert again.optimism is not None
    assert agent.optimism is not None
    assert (again.optimism.best, again.optimism.untried) == (
        agent.optimism.best,
        agent.optimism.untried,
    )
    ours = [h.episode_return for h in agent.learn(env, 5, reset_seed=9)]
    theirs = [h.episode_return for h in again.learn(env, 5, reset_seed=9)]
    assert ours == theirs
    assert agent.q == again.q


def _rewrite(source: Path, target: Path, learner_optimism: Any, config: Any = None) -> Path:
    with np.load(source, allow_pickle=False) as data:
        arrays = {name: data[name].copy() for name in data.files}
    meta = json.loads(arrays.pop("metadata").tobytes())
    meta["learner"]["optimism"] = learner_optimism
    if config is not None:
        meta["config"].update(config)
    np.savez(target, metadata=np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8), **arrays)
    return target


@pytest.mark.parametrize(
    ("optimism", "config", "defect"),
    [
        ({"best": "1", "untried": []}, None, "optimism best '1' is not a number"),
        ({"best": 1.0, "untried": [10**6]}, None, "key 1000000 is not on a leaf"),
        ({"best": 1.0}, None, "keys best and untried"),
        ([], None, "optimism are not objects"),
        ({"best": 1.0, "untried": []}, {"optimistic_untried": False}, "optimistic_untried is off"),
    ],
)
def test_a_tampered_optimism_state_names_the_file(
    tmp_path: Path, optimism: Any, config: Any, defect: str
) -> None:
    agent = _agent(True)
    agent.learn(Chain(), 2, reset_seed=0)
    good = agent.save(tmp_path / "good")
    bad = _rewrite(good, tmp_path / "bad.npz", optimism, config)
    with pytest.raises(ValueError, match=defect) as error:
        type(agent).load(bad)
    assert str(bad) in str(error.value)


def test_the_option_is_refused_when_not_a_bool_and_keeps_the_fast_loop_out() -> None:
    for bad in (1, "yes", None):
        with pytest.raises(ValueError, match="optimistic_untried must be a bool"):
            TreeConfig(optimistic_untried=bad)  # type: ignore[arg-type]
    config = TreeConfig(optimistic_untried=True)
    agent = TreeAgent(gym.spaces.Box(0.0, 1.0, (2,)), gym.spaces.Discrete(4), "tabu", 0, config)
    reason = ineligible_reason(agent, None)
    assert reason == "optimism for untried actions (TreeConfig.optimistic_untried)"


def test_frozen_lake_is_learnt_with_optimism_and_not_without() -> None:
    """FrozenLake (slippery, 16 cells as a table), 1,000 episodes of the general preset with
    and without the option, agent seed 2 (a development seed, docs/results.md "Part 16"):
    the greedy policy reaches the goal from more than 0.6 of 200 starts with it, from fewer
    than 0.3 without it (the optimum is about 0.74)."""
    warnings.simplefilter("ignore")
    env = adapt_env(gym.make("FrozenLake-v1"))
    success = {}
    for optimistic in (True, False):
        config = dataclasses.replace(preset("general").config, optimistic_untried=optimistic)
        agent = tree_agent_class(config)(
            env.observation_space, env.action_space, "adaptive+tabu", 2, config
        )
        agent.learn(env, 1000, reset_seed=2)
        wins = 0
        for i in range(200):
            obs, _ = env.reset(seed=10_000 + i)
            done, reward = False, 0.0
            while not done:
                obs, reward, terminated, truncated, _ = env.step(agent.predict(obs))
                done = terminated or truncated
            wins += reward > 0
        success[optimistic] = wins / 200
    assert success[True] > 0.6, success
    assert success[False] < 0.3, success


def test_the_grid_agent_refuses_the_option_by_name() -> None:
    config = TreeConfig(optimistic_untried=True)
    with pytest.raises(ValueError, match="optimistic_untried = True is implemented by the tree"):
        GridAgent(
            gym.spaces.Box(0.0, 1.0, (2,)), gym.spaces.Discrete(4), "tabu", 0, config, None, 4
        )
