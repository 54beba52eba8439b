"""A user's env that hands an agent a bad value is refused at that value, by every agent's
``learn`` and ``predict`` (``agent.env_checks``): the error names the value and the call it came
from. A valid env's values pass through unchanged. The hostile cases are kept as a fuzz table."""

from __future__ import annotations

import re
import warnings
from collections.abc import Callable
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent import env_checks, preset
from agent.env_checks import (
    MAX_REWARD_MAGNITUDE,
    CheckedEnv,
    ObservationOutOfBounds,
    checked_reward,
    observation_vector,
)

BOX = spaces.Box(-1.0, 1.0, (2,), np.float32)
ZERO = np.zeros(2, np.float32)


class Fixed(gym.Env):
    """Every reset and step returns the values it was given."""

    observation_space = BOX
    action_space = spaces.Discrete(3)

    def __init__(self, values: tuple) -> None:
        self.values = values

    def reset(self, *, seed: int | None = None, options: dict | None = None) -> Any:
        return self.values[0], {}

    def step(self, action: Any) -> Any:
        return self.values


class Scripted(gym.Env):
    """Ten-step episodes whose step ``bad_at`` returns ``bad`` (a function of the valid
    5-tuple) instead of the valid values."""

    observation_space = BOX
    action_space = spaces.Discrete(3)

    def __init__(self, bad: Callable[[tuple], Any] | None = None, bad_at: int = 4) -> None:
        self.bad, self.bad_at, self.t = bad, bad_at, 0

    def reset(self, *, seed: int | None = None, options: dict | None = None) -> Any:
        super().reset(seed=seed)
        self.t = 0
        return ZERO.copy(), {}

    def step(self, action: Any) -> Any:
        self.t += 1
        valid = (np.array([0.1 * self.t, -0.5], np.float32), -1.0, self.t >= 10, False, {})
        if self.bad is not None and self.t == self.bad_at:
            return self.bad(valid)
        return valid


def _replace(index: int, value: Any) -> Callable[[tuple], Any]:
    return lambda valid: (*valid[:index], value, *valid[index + 1 :])


HOSTILE: list[tuple[str, Callable[[tuple], Any], str]] = [
    (
        "nan input",
        _replace(0, np.array([np.nan, 0.0], np.float32)),
        r"not finite at input\(s\) \[0\]",
    ),
    ("inf input", _replace(0, np.array([0.0, -np.inf])), r"not finite at input\(s\) \[1\]"),
    ("three inputs", _replace(0, np.zeros(3)), "has 3 values .* observation space has 2"),
    ("text input", _replace(0, "up"), "observation 'up' is not numeric"),
    ("nan reward", _replace(1, float("nan")), "reward nan is not finite"),
    ("inf reward", _replace(1, -np.inf), "reward -inf is not finite"),
    ("huge reward", _replace(1, 1e300), r"reward 1e\+300 is beyond"),
    ("huge int reward", _replace(1, 10**400), "integer too large for a float"),
    ("no reward", _replace(1, None), "reward None .* is not a real number"),
    ("vector reward", _replace(1, np.array([1.0, 2.0])), "is not a real number"),
    ("bool reward", _replace(1, True), "reward True .* is not a real number"),
    ("string flag", _replace(2, "yes"), "terminated 'yes' .* is not a bool"),
    ("array flag", _replace(3, np.array([False, True])), "truncated .* is not a bool"),
    ("list info", _replace(4, []), r"info \[\] .* is not a dict"),
    ("old gym API", lambda valid: (*valid[:3], valid[4]), "returned 4 values"),
    ("no tuple", lambda valid: valid[0], "returned a ndarray, not a tuple"),
]


@pytest.mark.parametrize(("name", "bad", "message"), HOSTILE, ids=[h[0] for h in HOSTILE])
def test_every_agent_refuses_a_bad_step_naming_it_and_where(
    name: str, bad: Callable[[tuple], Any], message: str, every_agent_kind: Callable[..., list[Any]]
) -> None:
    for agent in every_agent_kind(BOX, Scripted.action_space):
        with pytest.raises(ValueError, match=message) as caught:
            agent.learn(Scripted(bad, bad_at=4), 3)
        assert str(caught.value).startswith("env.step (step 4 of the learn call's episode 0)"), str(
            caught.value
        )


def test_a_bad_reset_is_refused_naming_the_episode(
    every_agent_kind: Callable[..., list[Any]],
) -> None:
    class BadReset(Scripted):
        def reset(self, *, seed: int | None = None, options: dict | None = None) -> Any:
            super().reset(seed=seed)
            return (np.array([np.nan, 0.0]), {}) if seed is None else (ZERO.copy(), {})

    class OldReset(Scripted):
        def reset(self, *, seed: int | None = None, options: dict | None = None) -> Any:
            return ZERO.copy()

    for agent in every_agent_kind(BOX, Scripted.action_space):
        with pytest.raises(ValueError, match=r"env.reset \(the learn call's episode 1\): .*"):
            agent.learn(BadReset(), 3, reset_seed=0)
        with pytest.raises(ValueError, match=r"env.reset .* returned a ndarray, not a tuple"):
            agent.learn(OldReset(), 1)


def test_predict_refuses_a_bad_observation_by_name(
    every_agent_kind: Callable[..., list[Any]],
) -> None:
    for agent in every_agent_kind(BOX, Scripted.action_space):
        with pytest.raises(ValueError, match=r"predict: observation \[nan, 0.0\] is not finite"):
            agent.predict(np.array([np.nan, 0.0]))
        with pytest.raises(ValueError, match="predict: observation has 1 values"):
            agent.predict(np.zeros(1))
        assert agent.predict(np.array([0.5, -0.5])) in range(3)


def test_valid_values_of_every_kind_pass_unchanged() -> None:
    kinds = [
        (np.array([0.2, 0.3]), -1, np.bool_(False), 0, {"x": 1}),
        ([0.2, 0.3], np.float32(-0.5), False, np.int64(1), {}),
        (np.array([0.2, 0.3]), np.float32(-0.5), False, False, {}),  # (BipedalWalker's kind)
        (np.array([1, 2], np.int64), np.array(2.5), True, False, {}),
        (np.array([5.0, -7.0], np.float32), MAX_REWARD_MAGNITUDE, False, False, {}),
    ]
    for values in kinds:
        checked = CheckedEnv(Fixed(values), 2)
        assert checked.reset(seed=0)[0] is values[0]
        with warnings.catch_warnings():  # a float32 reward once cast the bound 1e100 to
            warnings.simplefilter("error")  # float32: an overflow warning on every step
            result = checked.step(0)
        assert all(a is b for a, b in zip(result, values, strict=True))
        assert checked.observation_space is BOX  # other attributes are the env's own


def test_checks_do_not_change_a_valid_run(monkeypatch: pytest.MonkeyPatch) -> None:
    """The same seeds give the same run with the check and with it taken out of ``learn``
    (the general preset's reference loop on MountainCar; the check only reads)."""
    import agent.learner

    env = gym.make("MountainCar-v0")
    runs = []
    for wrap in (True, False):
        if not wrap:
            monkeypatch.setattr(agent.learner, "CheckedEnv", lambda env, n_inputs, bounds: env)
        learner = preset("general").agent(env.observation_space, env.action_space, 3)
        history = learner.learn(env, 3, reset_seed=3)
        runs.append(([h.steps for h in history], [h.episode_return for h in history], learner.q))
    assert runs[0] == runs[1]
    assert len(runs[0][0]) == 3
    env.close()


def _flag_ok(flag: Any) -> bool:
    return isinstance(flag, bool | np.bool_) or (isinstance(flag, int) and flag in (0, 1))


def test_the_quick_path_agrees_with_the_full_checks() -> None:
    """Seeded fuzz: steps built from valid and hostile parts are refused or passed exactly as
    the full checks (observation_vector, checked_reward) decide."""
    rng = np.random.default_rng(39)
    observations = [
        np.array([0.1, 0.2]),
        np.array([0.1, 0.2], np.float32),
        np.array([np.nan, 0.0]),
        np.array([1e308, -1e308]),
        np.array([np.inf, 0.0], np.float32),
        np.zeros(3),
        np.zeros((1, 2)),
        [0.0, 1.0],
    ]
    rewards = [0.0, -1, 1e100, -1e101, float("nan"), np.float64(3.0), True, None, 2**70]
    flags = [True, False, np.bool_(True), 0, 1, 2, None]
    infos = [{}, {"a": 1}, None]

    def full(obs: Any, reward: Any, term: Any, trunc: Any, info: Any) -> bool:
        try:
            observation_vector(obs, 2, "w")
            checked_reward(reward, "w")
        except ValueError:
            return False
        return _flag_ok(term) and _flag_ok(trunc) and isinstance(info, dict)

    for _ in range(400):
        values = (
            observations[rng.integers(len(observations))],
            rewards[rng.integers(len(rewards))],
            flags[rng.integers(len(flags))],
            flags[rng.integers(len(flags))],
            infos[rng.integers(len(infos))],
        )

        checked = CheckedEnv(Fixed(values), 2)
        if full(*values):
            assert checked.step(0) is values
        else:
            with pytest.raises(ValueError, match=r"^env.step \(step 1 "):
                checked.step(0)


def test_a_checked_env_copies_without_recursion() -> None:
    """``copy`` builds the wrapper without ``__init__``; looking up ``env`` then must not
    recurse through ``__getattr__``."""
    import copy

    checked = CheckedEnv(Fixed((ZERO.copy(), -1.0, False, False, {})), 2)
    twin = copy.copy(checked)
    assert twin.env is checked.env
    assert twin.step(0)[1] == -1.0
    assert copy.deepcopy(checked).n_inputs == 2


class Sloppy(gym.Env):
    """Declares a box of [-1, 1] and walks out of it: 0.3 or 0.15 a step, whatever the action."""

    observation_space = BOX
    action_space = spaces.Discrete(2)

    def reset(self, seed: int | None = None, options: dict | None = None) -> tuple:
        super().reset(seed=seed)
        self.x, self.t = np.zeros(2), 0
        return self.x.astype(np.float32), {}

    def step(self, action: int) -> tuple:
        self.t += 1
        self.x = self.x - (0.3 if action else 0.15)
        return self.x.astype(np.float32), -1.0, bool(abs(self.x[0]) > 5), self.t >= 30, {}


def test_an_observation_outside_the_bounds_is_warned_of_once_per_learn_call(
    every_agent_kind: Callable[..., list[Any]],
) -> None:
    """Not refused (envs that overstep their declared box a little are common, and the agents
    still act there), not silent: one warning naming the input, the value, the bounds, the step
    and the episode, pointed at the caller's line."""
    env = Sloppy()
    for learner in every_agent_kind(env.observation_space, env.action_space):
        with pytest.warns(ObservationOutOfBounds) as caught:
            learner.learn(env, 3, reset_seed=0)
        assert len(caught) == 1
        message = str(caught[0].message)
        assert re.match(
            r"env\.step \(step \d+ of the learn call's episode \d\): observation "
            r"input 0 = -1\.\d+ lies outside the bounds the agent was built for, "
            r"\[-1\.0, 1\.0\]",
            message,
        ), message
        assert caught[0].filename == __file__
        with pytest.warns(ObservationOutOfBounds):  # once per call, so again in the next
            learner.learn(env, 1)


def test_observations_inside_the_bounds_raise_no_warning(
    every_agent_kind: Callable[..., list[Any]],
) -> None:
    env = gym.make("MountainCar-v0")
    for learner in every_agent_kind(env.observation_space, env.action_space):
        with warnings.catch_warnings():
            warnings.simplefilter("error", ObservationOutOfBounds)
            learner.learn(env, 2, reset_seed=0)
    env.close()


class Endless(gym.Env):
    """Never terminates; truncates itself after ``ends_at`` steps (so that the test ends), with
    no time limit declared: made directly, not through ``gymnasium.make``."""

    observation_space = BOX
    action_space = spaces.Discrete(2)

    def __init__(self, ends_at: int) -> None:
        self.ends_at = ends_at

    def reset(self, seed: int | None = None, options: dict | None = None) -> tuple:
        super().reset(seed=seed)
        self.t = 0
        return ZERO, {}

    def step(self, action: int) -> tuple:
        self.t += 1
        return ZERO, -1.0, False, self.t >= self.ends_at, {}


def test_a_long_episode_in_an_env_without_a_time_limit_is_warned_of_once_per_learn_call(
    every_agent_kind: Callable[..., list[Any]], monkeypatch: pytest.MonkeyPatch
) -> None:
    """An env that never ends an episode would keep ``learn`` in it for ever, silently: at
    ``LONG_EPISODE_STEPS`` steps one warning names the episode, the steps and the remedy, pointed
    at the caller's line; the episode goes on."""
    monkeypatch.setattr(env_checks, "LONG_EPISODE_STEPS", 50)
    env = Endless(ends_at=80)
    for learner in every_agent_kind(env.observation_space, env.action_space):
        with pytest.warns(env_checks.LongEpisode) as caught:
            history = learner.learn(env, 2, reset_seed=0)
        assert len(caught) == 1
        message = str(caught[0].message)
        assert message.startswith(
            "env.step (the learn call's episode 0): the episode has run 50 steps without "
            "ending (terminated or truncated), and the env declares no time limit"
        ), message
        assert "gymnasium.wrappers.TimeLimit" in message
        assert caught[0].filename == __file__
        assert [h.steps for h in history] == [80, 80]  # warned, not stopped
        with pytest.warns(env_checks.LongEpisode):  # once per call, so again in the next
            learner.learn(env, 1)


def test_an_env_with_a_time_limit_or_short_episodes_raises_no_long_episode_warning(
    every_agent_kind: Callable[..., list[Any]], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(env_checks, "LONG_EPISODE_STEPS", 50)
    limited = gym.wrappers.TimeLimit(Endless(ends_at=10**9), max_episode_steps=80)
    short = Endless(ends_at=50)  # ends at the threshold: no step past it
    for env in (limited, short):
        for learner in every_agent_kind(env.observation_space, env.action_space):
            with warnings.catch_warnings():
                warnings.simplefilter("error", env_checks.LongEpisode)
                learner.learn(env, 1, reset_seed=0)


def test_declared_time_limit_reads_the_spec_and_every_time_limit_wrapper() -> None:
    from gymnasium.envs.classic_control import CartPoleEnv

    assert env_checks.declared_time_limit(gym.make("CartPole-v1")) == 500
    assert env_checks.declared_time_limit(gym.make("CartPole-v1", max_episode_steps=20)) == 20
    assert env_checks.declared_time_limit(CartPoleEnv()) is None
    assert env_checks.declared_time_limit(gym.wrappers.TimeLimit(CartPoleEnv(), 7)) == 7
    nested = gym.wrappers.TimeLimit(gym.wrappers.TimeLimit(CartPoleEnv(), 30), 9)
    assert env_checks.declared_time_limit(nested) == 9
    assert env_checks.declared_time_limit(Endless(5)) is None
