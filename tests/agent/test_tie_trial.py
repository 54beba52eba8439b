"""The run tries a wider tie width and keeps it where it earns more
(``TreeConfig.greedy_tie_trial``; issue 9, part 30; docs/paper-notes.md, "Tie width chosen by
the run")."""

from __future__ import annotations

import dataclasses
import json
import math
import statistics
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces
from gymnasium.wrappers import TimeLimit

from agent import TreeAgent, TreeConfig, adapt_env, general_as_of, preset
from agent.exploration import Greedy
from agent.serialization import config_from_data
from agent.tie_trial import RunningMoments, TieTrial
from agent.tree_ensemble import TreeEnsembleAgent, tree_agent_class


def _trial_agent(env: gym.Env, seed: int = 0, **fields: object) -> TreeAgent:
    general = preset("general")
    config = dataclasses.replace(general.config, greedy_tie_trial=2.0, **fields)  # type: ignore[arg-type]
    return tree_agent_class(config)(
        env.observation_space, env.action_space, general.make_exploration(), seed, config
    )


def test_running_moments_match_the_sample_mean_and_variance() -> None:
    values = [3.0, -1.5, 7.25, 0.0, 2.0, 2.0, -40.0]
    moments = RunningMoments()
    assert moments.variance == math.inf
    for v in values:
        moments.add(v)
    assert moments.count == len(values)
    assert moments.mean == pytest.approx(statistics.mean(values))
    assert moments.variance == pytest.approx(statistics.variance(values))


def test_episodes_alternate_from_the_start_plain_first() -> None:
    trial = TieTrial((1.0, 1.0), 2.0, start=5, margin=2.0, every=2)
    assert [trial.tries(e) for e in range(10)] == [False] * 6 + [True, False, True, False]
    for episode, ret in enumerate([99.0] * 5 + [1.0, 10.0, 2.0, 11.0, 3.0, 12.0]):
        trial.record(episode, ret)  # the five before the start are not kept
    assert (trial.plain.count, trial.tried.count) == (3, 3)
    assert (trial.plain.mean, trial.tried.mean) == (2.0, 11.0)


def test_one_episode_in_every_is_a_trial_the_last_of_each_group() -> None:
    trial = TieTrial((1.0, 1.0), 2.0, start=3, margin=2.0, every=4)
    assert [e for e in range(20) if trial.tries(e)] == [6, 10, 14, 18]
    for episode in range(20):
        trial.record(episode, float(episode))
    assert (trial.plain.count, trial.tried.count) == (13, 4)
    assert trial.tried.mean == 12.0


def test_the_trial_width_is_adopted_only_beyond_the_margin_by_hand() -> None:
    trial = TieTrial((1.0, 0.5), 2.0, start=0, margin=2.0, every=2)
    assert trial.widths() == (1.0, 0.5)  # nothing measured
    for episode, ret in enumerate([1.0, 10.0, 2.0, 11.0, 3.0, 12.0]):
        trial.record(episode, ret)
    diff, se = trial.difference()
    assert diff == 9.0
    assert se == pytest.approx(math.sqrt(1 / 3 + 1 / 3))  # both variances are 1
    assert trial.adopted
    assert trial.widths() == (2.0, 2.0)
    near = TieTrial((1.0, 0.5), 2.0, start=0, margin=2.0, every=2)
    for episode, ret in enumerate([1.0, 2.5, 3.0, 4.5, 5.0, 6.5]):
        near.record(episode, ret)  # diff 1.5 against se 1.63: not adopted
    assert not near.adopted
    assert near.widths() == (1.0, 0.5)


def test_following_swaps_the_kinds_while_the_width_is_adopted_by_hand() -> None:
    trial = TieTrial((1.0, 1.0), 2.0, start=2, margin=2.0, every=4, follow=True)
    assert [e for e in range(10) if trial.tries(e)] == [5, 9]  # not adopted: as without follow
    returns = {2: 1.0, 3: 2.0, 4: 3.0, 5: 20.0, 6: 1.5, 7: 2.5, 8: 3.5, 9: 21.0}
    for episode in range(10):
        trial.record(episode, returns.get(episode, 99.0))  # 0 and 1 precede the start
    assert (trial.plain.count, trial.tried.count) == (6, 2)
    assert trial.adopted  # 20.5 against 2.25, se 0.58
    assert [e for e in range(10, 18) if trial.tries(e)] == [10, 11, 12, 14, 15, 16]
    trial.record(10, 40.0)  # a z' episode now, kept as a trial episode's return
    trial.record(13, 4.0)  # the last of its group: plain
    assert (trial.plain.count, trial.tried.count) == (7, 3)
    assert trial.tried.mean == pytest.approx((20.0 + 21.0 + 40.0) / 3)
    kept = TieTrial((1.0, 1.0), 2.0, start=2, margin=2.0, every=4)
    kept.restore(trial.state(), "test")
    assert kept.adopted
    assert [e for e in range(10, 18) if kept.tries(e)] == [13, 17]


def test_following_is_today_s_run_while_the_width_is_never_adopted() -> None:
    env = adapt_env(gym.make("Acrobot-v1"))
    fields = {"greedy_tie_trial_episodes": 2, "greedy_tie_trial_margin": 1e9}
    alone = _trial_agent(env, seed=4, **fields)
    following = _trial_agent(env, seed=4, greedy_tie_trial_follow=True, **fields)
    assert alone.learn(env, 10, reset_seed=3) == following.learn(env, 10, reset_seed=3)
    assert alone.q == following.q
    assert following.tie_trial is not None
    assert following.tie_trial.tried.count == 2


def test_following_trains_at_the_trial_width_once_adopted() -> None:
    env = adapt_env(gym.make("Acrobot-v1"))
    agent = _trial_agent(env, seed=1, greedy_tie_trial_episodes=2, greedy_tie_trial_follow=True)
    assert isinstance(agent, TreeEnsembleAgent)
    assert agent.tie_trial is not None
    agent.learn(env, 2, reset_seed=5)
    agent.tie_trial.restore({"plain": [10, -500.0, 9.0], "tried": [10, -300.0, 9.0]}, "test")
    assert agent.tie_trial.adopted
    episodes: set[int] = set()
    choose = agent._trial_choice

    def watched(leaves: list[int], row: list[float], action: int, avoided: Any = ()) -> int:
        episodes.add(agent.episodes_done)
        return choose(leaves, row, action, avoided)

    agent._trial_choice = watched  # type: ignore[method-assign]
    agent.learn(env, 8, reset_seed=6)  # episodes 2-9: groups 2-5 and 6-9
    assert agent.tie_trial.adopted  # 8 more returns do not undo a 200-step lead
    assert episodes == {2, 3, 4, 6, 7, 8}
    assert (agent.tie_trial.plain.count, agent.tie_trial.tried.count) == (12, 16)


@pytest.mark.parametrize(
    ("fields", "message"),
    [
        ({"greedy_tie_trial": 0.0}, "greedy_tie_trial must be a number > 0"),
        ({"greedy_tie_trial": -2.0}, "greedy_tie_trial must be a number > 0"),
        ({"greedy_tie_trial": math.inf}, "greedy_tie_trial must be a number > 0"),
        ({"greedy_tie_trial": True}, "greedy_tie_trial must be a number > 0"),
        ({"greedy_tie_trial": "2"}, "greedy_tie_trial must be a number > 0"),
        ({"greedy_tie_trial_episodes": -1}, "greedy_tie_trial_episodes must be an int >= 0"),
        ({"greedy_tie_trial_episodes": 3.0}, "greedy_tie_trial_episodes must be an int >= 0"),
        ({"greedy_tie_trial_every": 1}, "greedy_tie_trial_every must be an int in"),
        ({"greedy_tie_trial_every": 2.0}, "greedy_tie_trial_every must be an int in"),
        ({"greedy_tie_trial_every": 10**6}, "greedy_tie_trial_every must be an int in"),
        ({"greedy_tie_trial_margin": -0.1}, "greedy_tie_trial_margin must be a finite number"),
        ({"greedy_tie_trial_margin": math.nan}, "greedy_tie_trial_margin must be a finite number"),
        ({"greedy_tie_trial_follow": 1}, "greedy_tie_trial_follow must be a bool, got 1"),
        ({"greedy_tie_trial_follow": "yes"}, "greedy_tie_trial_follow must be a bool"),
        ({"greedy_tie_trial_follow": None}, "greedy_tie_trial_follow must be a bool"),
        ({"greedy_tie_trial_avoid_collided": 1}, "greedy_tie_trial_avoid_collided must be a bool"),
        ({"greedy_tie_trial_avoid_collided": "no"}, "avoid_collided must be a bool, got 'no'"),
    ],
)
def test_bad_settings_are_refused_by_name(fields: dict[str, object], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        dataclasses.replace(preset("general").config, **fields)  # type: ignore[arg-type]


def test_the_trial_needs_the_ancestors_and_runs_the_ensemble_loop() -> None:
    with pytest.raises(ValueError, match=r"greedy_tie_trial = 2\.0 needs greedy_tie_ancestors"):
        TreeConfig(greedy_tie_trial=2.0)
    config = dataclasses.replace(preset("general").config, greedy_tie_trial=2.0)
    assert tree_agent_class(config) is TreeEnsembleAgent
    with pytest.raises(ValueError, match="greedy_tie_trial"):
        config_from_data({"greedy_tie_trial": "wide"}, "experiment.toml [agent]")


def test_before_the_start_training_is_today_s_bit_for_bit() -> None:
    env = gym.make("CartPole-v1")
    general = preset("general")
    plain = general.agent(env.observation_space, env.action_space, seed=3)
    tried = _trial_agent(env, seed=3, greedy_tie_trial_episodes=1000)
    assert plain.learn(env, 12, reset_seed=1) == tried.learn(env, 12, reset_seed=1)
    assert plain.q == tried.q
    assert tried.tie_trial is not None
    assert tried.tie_trial.plain.count == tried.tie_trial.tried.count == 0
    probe = np.random.default_rng(0).uniform(-0.2, 0.2, size=(50, 4))
    assert [plain.predict(x) for x in probe] == [tried.predict(x) for x in probe]


def test_trial_episodes_break_ties_at_the_trial_width_and_are_counted() -> None:
    env = adapt_env(gym.make("Acrobot-v1"))
    plain = preset("general").agent(env.observation_space, env.action_space, seed=1)
    tried = _trial_agent(env, seed=1, greedy_tie_trial_episodes=4, greedy_tie_trial_every=2)
    assert isinstance(tried, TreeEnsembleAgent)
    calls: list[tuple[int, int, int]] = []
    choose = tried._trial_choice

    def watched(leaves: list[int], row: list[float], action: int, avoided: Any = ()) -> int:
        out = choose(leaves, row, action, avoided)
        calls.append((tried.episodes_done, action, out))
        return out

    tried._trial_choice = watched  # type: ignore[method-assign]
    history = tried.learn(env, 15, reset_seed=2)
    assert tried.tie_trial is not None
    assert (tried.tie_trial.plain.count, tried.tie_trial.tried.count) == (6, 5)
    kept = [h.episode_return for h in history[5::2]]
    assert tried.tie_trial.tried.mean == pytest.approx(statistics.mean(kept))
    assert {episode for episode, _, _ in calls} == {5, 7, 9, 11, 13}  # trial episodes alone
    assert any(before != after for _, before, after in calls)  # some ties were broken anew
    assert plain.learn(env, 15, reset_seed=2)[:5] == history[:5]
    assert plain.q != tried.q


def test_predict_uses_the_trial_width_for_both_tests_once_adopted() -> None:
    env = gym.make("CartPole-v1")
    agent = _trial_agent(env, seed=0, greedy_tie_trial_episodes=0)
    agent.learn(env, 40, reset_seed=0)
    assert agent.tie_trial is not None
    agent.tie_trial.restore({"plain": [10, 20.0, 90.0], "tried": [10, 80.0, 90.0]}, "test")
    assert agent.tie_trial.adopted
    probe = np.random.default_rng(1).uniform(-0.2, 0.2, size=(200, 4))
    adopted = [agent.predict(x) for x in probe]
    agent.tie_trial = None  # the same tree with both widths at 2 in the configuration
    agent.config = dataclasses.replace(
        agent.config, greedy_tie_trial=None, greedy_tie_errors=2.0, greedy_tie_ancestors=2.0
    )
    assert [agent.predict(x) for x in probe] == adopted
    agent.config = dataclasses.replace(
        agent.config, greedy_tie_errors=1.0, greedy_tie_ancestors=1.0
    )
    assert [agent.predict(x) for x in probe] != adopted  # the widths matter on this tree


@pytest.mark.parametrize("policy_only", [False, True])
def test_files_keep_the_trial_and_act_alike(tmp_path: Path, policy_only: bool) -> None:
    env = gym.make("CartPole-v1")
    agent = _trial_agent(env, seed=2, greedy_tie_trial_episodes=4)
    agent.learn(env, 20, reset_seed=0)
    assert agent.tie_trial is not None
    path = agent.save(tmp_path / "agent.npz", policy_only=policy_only)
    loaded = TreeAgent.load(path)
    assert isinstance(loaded, TreeEnsembleAgent)
    assert loaded.tie_trial is not None
    assert loaded.tie_trial.state() == agent.tie_trial.state()
    probe = np.random.default_rng(3).uniform(-0.2, 0.2, size=(100, 4))
    assert [loaded.predict(x) for x in probe] == [agent.predict(x) for x in probe]
    if not policy_only:  # the full file continues bit for bit, trial episodes included
        assert loaded.learn(env, 6, reset_seed=9) == agent.learn(env, 6, reset_seed=9)
        assert loaded.tie_trial.state() == agent.tie_trial.state()


HOSTILE_STATES: list[object] = [
    None,
    [],
    "plain",
    {"plain": [1, 0.0, 0.0]},
    {"plain": [1, 0.0, 0.0], "tried": [1, 0.0, 0.0], "extra": 1},
    {"plain": [-1, 0.0, 0.0], "tried": [1, 0.0, 0.0]},
    {"plain": [1.5, 0.0, 0.0], "tried": [1, 0.0, 0.0]},
    {"plain": [True, 0.0, 0.0], "tried": [1, 0.0, 0.0]},
    {"plain": [1, "0", 0.0], "tried": [1, 0.0, 0.0]},
    {"plain": [1, 0.0, -1.0], "tried": [1, 0.0, 0.0]},
    {"plain": [1, 0.0, 1e400], "tried": [1, 0.0, 0.0]},
    {"plain": [1, 0.0], "tried": [1, 0.0, 0.0]},
]


@pytest.mark.parametrize("state", HOSTILE_STATES)
def test_a_damaged_trial_entry_is_refused_by_file_name(tmp_path: Path, state: object) -> None:
    env = gym.make("CartPole-v1")
    agent = _trial_agent(env, seed=0, greedy_tie_trial_episodes=0)
    agent.learn(env, 4, reset_seed=0)
    good = agent.save(tmp_path / "good.npz")
    with np.load(good, allow_pickle=False) as data:
        arrays = {k: data[k] for k in data.files}
    meta = json.loads(arrays.pop("metadata").tobytes())
    if state is None:
        del meta["tie_trial"]  # the config asks for the trial; the file has no record of it
    else:
        meta["tie_trial"] = state
    text = json.dumps(meta).replace("Infinity", "1e400")
    bad = tmp_path / "bad.npz"
    np.savez(bad, metadata=np.frombuffer(text.encode(), dtype=np.uint8), **arrays)
    with pytest.raises(ValueError, match=r"bad\.npz.*tie_trial"):
        TreeAgent.load(bad)


def test_a_trial_entry_without_the_option_is_refused(tmp_path: Path) -> None:
    env = gym.make("CartPole-v1")
    config = general_as_of(29)  # the general preset before the trial
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, "adaptive+tabu", 0, config
    )
    agent.learn(env, 3, reset_seed=0)
    good = agent.save(tmp_path / "good.npz")
    with np.load(good, allow_pickle=False) as data:
        arrays = {k: data[k] for k in data.files}
    meta = json.loads(arrays.pop("metadata").tobytes())
    meta["tie_trial"] = {"plain": [0, 0.0, 0.0], "tried": [0, 0.0, 0.0]}
    bad = tmp_path / "bad.npz"
    np.savez(bad, metadata=np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8), **arrays)
    with pytest.raises(ValueError, match=r"bad\.npz.*tie_trial must be present exactly"):
        TreeAgent.load(bad)


class Wall(gym.Env[np.ndarray, int]):
    """A corridor from x = 0.05 to the goal at 1: action 1 moves 0.1 to the right (-0.01),
    action 0 pushes into the wall beside it (-1, ``info["collision"]``, no move); the maze's
    rewards, one dimension."""

    observation_space = spaces.Box(0.0, 1.0, (1,), dtype=np.float64)
    action_space = spaces.Discrete(2)

    def __init__(self, report: bool = True) -> None:
        self.report = report
        self.x = 0.05

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        super().reset(seed=seed)
        self.x = 0.05
        return np.array([self.x]), {}

    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        if action == 0:
            info = {"collision": True} if self.report else {}
            return np.array([self.x]), -1.0, False, False, info
        self.x = min(self.x + 0.1, 1.0)
        return np.array([self.x]), -0.01, self.x >= 1.0, False, {}


Choice = tuple[int, int, int, int]
"""A trial's choice: episode, tree 0's leaf, the strategy's action, the trial's."""


def _wall_run(avoid: bool, report: bool = True) -> tuple[list[Any], list[Choice]]:
    """Three episodes (the second a trial) of an agent whose trial always breaks its tie
    towards the wall, with the trial's choices: the ties, the ancestors' choice and the
    stored-epoch counts are fixed by hand, since in a run they are cached for the episode and
    the trial can repeat itself."""
    env = TimeLimit(Wall(report), max_episode_steps=200)
    config = dataclasses.replace(
        preset("general").config,
        greedy_tie_trial=2.0,
        greedy_tie_trial_episodes=0,
        greedy_tie_trial_every=2,
        greedy_tie_trial_avoid_collided=avoid,
    )
    agent = TreeEnsembleAgent(env.observation_space, env.action_space, Greedy(), 0, config)
    agent.fewest_epochs = lambda members, leaves: [5, 5]  # type: ignore[method-assign]
    agent.holds_one_input = lambda leaf: False  # type: ignore[method-assign]
    agent._tied = lambda members, leaves, row, allowed, z: list(allowed)  # type: ignore[method-assign]
    agent._ancestors_choice = lambda members, leaves, tied, z: 0  # type: ignore[method-assign]
    choices: list[Choice] = []
    choose = agent._trial_choice

    def watched(leaves: list[int], row: list[float], action: int, avoided: Any = ()) -> int:
        out = choose(leaves, row, action, avoided)
        choices.append((agent.episodes_done, leaves[0], action, out))
        return out

    agent._trial_choice = watched  # type: ignore[method-assign]
    return agent.learn(env, 3, reset_seed=0), choices


def test_a_trial_choice_that_collided_is_not_remade_in_its_leaf() -> None:
    pressed, _ = _wall_run(avoid=False)
    assert pressed[1].truncated
    assert pressed[1].steps == pressed[1].collisions == 200
    history, choices = _wall_run(avoid=True)
    assert history[0] == pressed[0]  # a plain episode is today's
    trial = history[1]
    assert not trial.truncated
    assert trial.success
    assert {episode for episode, *_ in choices} == {1}
    remade = [(leaf, out) for _, leaf, proposed, out in choices if out != proposed]
    walls = [(leaf, out) for leaf, out in remade if out == 0]
    assert walls  # the trial sent the robot into the wall ...
    assert len(walls) == len(set(walls))  # ... but once at most from each leaf
    assert trial.steps - trial.collisions == 10  # every other step moved on


def test_avoiding_collided_choices_needs_the_env_s_collision_flag() -> None:
    silent, _ = _wall_run(avoid=True, report=False)
    assert silent == _wall_run(avoid=False, report=False)[0]
    assert silent[1].truncated  # nothing tells the trial it pressed into the wall


def test_avoiding_collided_choices_leaves_a_classic_task_s_run_as_it_was() -> None:
    """Classic control reports no collisions: part 32's preset runs part 31's run there."""
    env = adapt_env(gym.make("Acrobot-v1"))
    fields = {"greedy_tie_trial_episodes": 2, "greedy_tie_trial_every": 2}
    runs, remade = [], []
    for avoid in (False, True):
        agent = _trial_agent(env, seed=2, greedy_tie_trial_avoid_collided=avoid, **fields)
        choose = agent._trial_choice

        def watched(
            leaves: list[int], row: list[float], action: int, avoided: Any = (), c: Any = choose
        ) -> int:
            out: int = c(leaves, row, action, avoided)
            remade.append(out != action)
            return out

        agent._trial_choice = watched  # type: ignore[method-assign]
        runs.append((agent.learn(env, 8, reset_seed=4), agent.q))
    assert runs[0] == runs[1]
    assert any(remade)  # the trial did remake choices, and none was held back
    assert general_as_of(31) == dataclasses.replace(
        general_as_of(32), greedy_tie_trial_avoid_collided=False
    )
