"""The fast learning loop against the reference loop: the same seeds give the same everything.

Every strategy of ``experiments/paper_fig4.toml`` (tree and grid agents) and the options the
kernel implements are run twice, ``learn(fast=False)`` and ``learn(fast=True)``, and compared:
episode statistics, Q-bar, counts, the tree with its error buffers, the strategy's state (dict
order included), the random streams and the env's state. Then the fallbacks: an env that is not
ours, the compiled kernel missing, a configuration or strategy outside the whitelist, changed
mirrored code; each must run the reference and give its results.
"""

from __future__ import annotations

import dataclasses
import math
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import agent.fast_loop as fast_loop
from agent import GridAgent, TreeAgent, TreeConfig, make_exploration
from agent.exploration import EpsilonGreedy, exploration_spec
from agent.partition_tree import PartitionTree

ROOT = Path(__file__).resolve().parents[2]
pytest.importorskip("bullet_maze")
from experiments import factory  # noqa: E402
from experiments.config import load_config  # noqa: E402
from experiments.seeding import derive_seeds, run_seed  # noqa: E402

FIG4 = load_config("paper_fig4")


def _env(max_steps: int = 600, **kwargs: Any) -> gym.Env:
    import bullet_maze  # noqa: F401

    return gym.make("BulletMaze-v0", max_episode_steps=max_steps, **kwargs)


def agent_state(agent: Any) -> dict[str, Any]:
    """Everything the agent holds, in comparable form (dict orders included)."""
    partition = agent.partition
    arrays, meta = partition.to_arrays()
    state = {
        "episodes_done": agent.episodes_done,
        "q": agent.q,
        "visits": agent.visits,
        "partition": {name: value.tolist() for name, value in arrays.items()},
        "meta": meta,
        "n_leaves": partition.n_leaves,
        "exploration": exploration_spec(agent.exploration),
        "explored": vars(agent.exploration).get("explored"),
        "uniform": agent.uniform.state(),
    }
    if isinstance(partition, PartitionTree):
        state["buffer_order"] = list(partition._buffers)
        state["buffer_counters"] = [
            (b.count, b.head, b.sum, b.sum_sq) for b in partition._buffers.values()
        ]
    base = getattr(agent.exploration, "base", None)
    if base is not None:
        state["base_explored"] = vars(base).get("explored")
        state["by_leaf"] = {k: sorted(v) for k, v in agent.exploration._by_leaf.items()}
    return state


def env_state(env: gym.Env) -> dict[str, Any]:
    base = env.unwrapped
    return {
        "pose": base.pose,
        "noise": list(base._noise),
        "noise_index": base._noise_index,
        "elapsed": env._elapsed_steps,
        "safe": base.world._safe,
        "cells": list(base.world._cells),
        "rng": base.np_random.bit_generator.state,
    }


def run_both(make_agent: Any, episodes: int, make_env: Any = _env, seed: int = 7) -> Any:
    """Learn with each path on fresh copies; return (reference, fast) results."""
    results = []
    for fast in (False, True):
        env = make_env()
        try:
            agent = make_agent(env)
            history = agent.learn(env, episodes, reset_seed=seed, fast=fast)
            results.append((history, agent_state(agent), env_state(env)))
        finally:
            env.close()
    return results


def assert_same(results: Any) -> None:
    (history0, agent0, env0), (history1, agent1, env1) = results
    assert history1 == history0
    assert agent1 == agent0
    assert env1 == env0


def fig4_agent(name: str, **config_changes: Any) -> Any:
    spec = FIG4.strategy(name)
    if config_changes:
        spec = dataclasses.replace(spec, config={**spec.config, **config_changes})
    seed = derive_seeds(run_seed(FIG4.seed, 0)).agent
    return lambda env: factory.make_agent(FIG4, spec, env, seed)


@pytest.mark.parametrize("name", [s.name for s in FIG4.strategies])
def test_every_fig4_strategy_is_bit_identical(name: str) -> None:
    results = run_both(fig4_agent(name), episodes=8)
    assert_same(results)
    assert sum(s.steps for s in results[0][0]) > 1000


@pytest.mark.parametrize("name", [s.name for s in FIG4.strategies if s.agent == "tree"])
def test_every_fig4_tree_strategy_with_many_splits_is_bit_identical(name: str) -> None:
    results = run_both(fig4_agent(name, split_min_samples=40), episodes=6)
    assert_same(results)
    assert results[1][1]["n_leaves"] > 5  # split tests ran in Python, several times


VARIANTS = [
    ("adaptive", {"variant": "cn_exponent", "inherit_on_split": False}, {}),
    ("adaptive+tabu", {"on_split": "inherit", "random_respects_list": True}, {}),
    ("adaptive+tabu", {"all_listed": "greedy", "initial_capacity": 3, "min_capacity": 1}, {}),
    ("vdbe", {"form": "exponential", "delta": 0.5, "sigma": 0.2}, {}),
    ("vdbe+tabu", {"inherit_on_split": True, "shrink_every": 1}, {"max_epoch_steps": None}),
    ("greedy", {}, {"end_epoch_on_collision": False}),
    ("greedy+tabu", {"deviation_explores": False}, {"hold_exploration": False}),
    ("epsilon-greedy", {"epsilon": 0.3}, {"max_epoch_steps": 3, "q_init": 1.0}),
    ("tabu", {"epsilon": 0.2}, {"inherit_q": False, "reset_counts_on_split": False}),
    ("adaptive", {}, {"children_inherit_samples": False, "split_point": "midpoint"}),
    # part 17: the 2-D maze beyond a limit of 1 presplits only x
    ("adaptive", {}, {"presplit_each_dimension": True, "presplit_max_dimensions": 1}),
    (
        "greedy",
        {},
        {
            "presplit_each_dimension": True,
            "presplit_max_dimensions": 1,
            "presplit_beyond_dimensions": 1,
        },
    ),
]


@pytest.mark.parametrize(("strategy", "params", "config"), VARIANTS)
@pytest.mark.parametrize("kind", ["tree", "grid"])
def test_implemented_options_are_bit_identical(
    strategy: str, params: dict[str, Any], config: dict[str, Any], kind: str
) -> None:
    def make(env: gym.Env) -> Any:
        cfg = TreeConfig(split_min_samples=30, **config)
        exploration = make_exploration(strategy, **params)
        if kind == "grid":
            return GridAgent(
                env.observation_space, env.action_space, exploration, 3, cfg, resolution=17
            )
        return TreeAgent(env.observation_space, env.action_space, exploration, 3, cfg)

    assert_same(run_both(make, episodes=5))


def test_a_second_learn_call_and_other_mazes_are_bit_identical() -> None:
    def make_env() -> gym.Env:
        return _env(max_steps=900, maze="corridors")

    results = []
    for fast in (False, True):
        env = make_env()
        agent = fig4_agent("adaptive+tabu", split_min_samples=50)(env)
        history = agent.learn(env, 4, reset_seed=1, fast=fast)
        history += agent.learn(env, 4, fast=fast)  # continues the same env and agent
        results.append((history, agent_state(agent), env_state(env)))
        env.close()
    assert_same(results)


def test_callbacks_see_the_reference_state_and_can_stop_learning() -> None:
    seen: dict[bool, list[Any]] = {False: [], True: []}
    for fast in (False, True):
        env = _env()
        agent = fig4_agent("adaptive+tabu", split_min_samples=50)(env)

        def callback(stats: Any, agent: Any = agent, fast: bool = fast) -> bool:
            seen[fast].append((stats, agent_state(agent), agent.predict([150.0, 150.0])))
            return stats.episode < 4

        history = agent.learn(env, 10, callback=callback, reset_seed=3, fast=fast)
        assert len(history) == 5
        env.close()
    assert seen[True] == seen[False]


def test_a_callback_that_replaces_the_strategy_is_followed() -> None:
    def run(fast: bool) -> Any:
        env = _env()
        agent = fig4_agent("adaptive+tabu")(env)

        def callback(stats: Any) -> None:
            if stats.episode == 1:
                agent.exploration = EpsilonGreedy(0.2)
                agent.exploration.bind(agent.n_actions)

        history = agent.learn(env, 4, callback=callback, reset_seed=2, fast=fast)
        env.close()
        return history, agent_state(agent)

    assert run(True) == run(False)


def test_an_exception_in_a_callback_leaves_the_reference_state() -> None:
    states = []
    for fast in (False, True):
        env = _env()
        agent = fig4_agent("vdbe", split_min_samples=50)(env)

        def callback(stats: Any) -> None:
            if stats.episode == 2:
                raise KeyboardInterrupt

        with pytest.raises(KeyboardInterrupt):
            agent.learn(env, 5, callback=callback, reset_seed=4, fast=fast)
        states.append((agent_state(agent), env_state(env)))
        env.close()
    assert states[1] == states[0]


def test_the_fast_loop_runs_for_every_fig4_strategy() -> None:
    env = _env()
    try:
        for spec in FIG4.strategies:
            agent = factory.make_agent(FIG4, spec, env, 0)
            assert fast_loop.ineligible_reason(agent, env) is None, spec.name
            assert isinstance(fast_loop.episode_runner(agent, env), fast_loop.FastRunner)
        runner = fast_loop.episode_runner(agent, env)
        assert isinstance(runner, fast_loop.FastRunner)
        obs, _ = env.reset(seed=0)
        runner(env, obs)
        assert runner.kernel_steps > 0  # (a cold cell cache sends many moves to pybullet)
    finally:
        env.close()


def test_the_mirrored_code_is_the_code_the_kernel_was_checked_against() -> None:
    """A failure names functions changed since the fast loop was checked against them: check
    agent/fast_kernel.py (or the driver) against the new code, then renew FINGERPRINTS."""
    env = _env()
    try:
        current = fast_loop.current_fingerprints(env.unwrapped)
    finally:
        env.close()
    changed = {k: v for k, v in current.items() if fast_loop.FINGERPRINTS.get(k) != v}
    assert not changed, f"renew FINGERPRINTS after checking the kernel: {changed}"


# -- fallbacks ---------------------------------------------------------------------------


def _reference_only(agent: Any, env: gym.Env) -> None:
    runner = fast_loop.episode_runner(agent, env)
    assert not isinstance(runner, fast_loop.FastRunner)
    assert runner == agent._run_episode


def test_an_env_that_is_not_ours_runs_the_reference() -> None:
    config = TreeConfig(split_max_abs_mean=5.0, split_min_variance=1.0, split_min_samples=200)

    def make_env() -> gym.Env:
        return gym.make("MountainCar-v0")

    def make(env: gym.Env) -> Any:
        return TreeAgent(env.observation_space, env.action_space, "adaptive+tabu", 1, config)

    env = make_env()
    _reference_only(make(env), env)
    env.close()
    (h0, a0, _), (h1, a1, _) = [
        (history, state, None) for history, state, _env_state in _mountain_car_runs(make_env, make)
    ]
    assert h1 == h0
    assert a1 == a0


def _mountain_car_runs(make_env: Any, make: Any) -> list[Any]:
    out = []
    for fast in (False, True):
        env = make_env()
        agent = make(env)
        out.append((agent.learn(env, 3, reset_seed=1, fast=fast), agent_state(agent), None))
        env.close()
    return out


@pytest.mark.parametrize(
    "env_kwargs",
    [{"mode": "dynamic"}, {"robot": "husky"}, {"render_mode": "rgb_array"}],
    ids=["dynamic", "husky", "render"],
)
def test_an_env_outside_the_kinematic_disc_runs_the_reference(env_kwargs: dict) -> None:
    env = _env(**env_kwargs)
    try:
        agent = TreeAgent(env.observation_space, env.action_space, "adaptive+tabu", 0)
        _reference_only(agent, env)
    finally:
        env.close()


def test_an_unknown_wrapper_runs_the_reference_with_the_same_results() -> None:
    def make_env() -> gym.Env:
        return gym.wrappers.RecordEpisodeStatistics(_env())

    env = make_env()
    agent = fig4_agent("tabu")(env)
    _reference_only(agent, env)
    env.close()
    results = []
    for fast in (False, True):
        env = make_env()
        agent = fig4_agent("tabu")(env)
        results.append((agent.learn(env, 3, reset_seed=5, fast=fast), agent_state(agent)))
        env.close()
    assert results[1] == results[0]


class _Subclassed(EpsilonGreedy):
    def epsilon(self, leaf: int) -> float:
        return 0.5 if leaf % 2 else 0.0


@dataclasses.dataclass(frozen=True)
class _NewConfig(TreeConfig):
    new_option: bool = True


@pytest.mark.parametrize(
    "case",
    [
        "window-buffer",
        "collision-key",
        "subclassed-strategy",
        "extra-attribute",
        "config-subclass",
        "unknown-parameter-value",
        "bool-as-float",
    ],
)
def test_what_the_whitelist_does_not_cover_runs_the_reference(case: str) -> None:
    def make(env: gym.Env) -> Any:
        config = TreeConfig(split_min_samples=40)
        exploration: Any = make_exploration("adaptive+tabu")
        if case == "window-buffer":
            config = TreeConfig(split_min_samples=40, error_buffer="window")
        elif case == "collision-key":
            config = TreeConfig(collision_key="is_success")
        elif case == "subclassed-strategy":
            exploration = _Subclassed(0.1)
        elif case == "extra-attribute":
            exploration.base.temperature = 2.0
        elif case == "config-subclass":
            config = _NewConfig(split_min_samples=40)
        elif case == "unknown-parameter-value":
            exploration = make_exploration("vdbe", delta=1)  # an int: not whitelisted
        elif case == "bool-as-float":
            exploration = make_exploration("epsilon-greedy")
            exploration._epsilon = True
        return TreeAgent(env.observation_space, env.action_space, exploration, 2, config)

    env = _env()
    agent = make(env)
    assert fast_loop.ineligible_reason(agent, env) is not None
    _reference_only(agent, env)
    env.close()
    (h0, a0, e0), (h1, a1, e1) = run_both(make, episodes=3)
    assert (h1, a1, e1) == (h0, a0, e0)


def test_changed_mirrored_code_runs_the_reference(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(fast_loop.FINGERPRINTS, "Tabu.select", "0" * 16)
    monkeypatch.setattr(fast_loop, "_checked_types", {})
    env = _env()
    try:
        agent = fig4_agent("adaptive+tabu")(env)
        reason = fast_loop.ineligible_reason(agent, env)
        assert reason is not None
        assert "Tabu.select" in reason
        _reference_only(agent, env)
    finally:
        env.close()


def test_without_the_compiled_kernel_the_reference_runs_with_the_same_results() -> None:
    script = textwrap.dedent(
        """
        import sys
        sys.modules["numba"] = None  # numba missing: importing the kernel fails
        import logging
        logging.basicConfig(level=logging.WARNING)
        import gymnasium as gym
        import bullet_maze
        import agent.fast_loop as fast_loop
        from agent import TreeAgent
        histories = []
        for fast in (False, True):
            env = gym.make("BulletMaze-v0", max_episode_steps=400)
            agent = TreeAgent(env.observation_space, env.action_space, "adaptive+tabu", 5)
            if fast:
                assert fast_loop.episode_runner(agent, env) == agent._run_episode
            histories.append(agent.learn(env, 3, reset_seed=2, fast=fast))
            env.close()
        assert histories[0] == histories[1]
        assert fast_loop.load_kernel() is None
        print("reference ran")
        """
    )
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, cwd=ROOT, check=False
    )
    assert done.returncode == 0, done.stderr
    assert "reference ran" in done.stdout
    assert "fast learning loop unavailable" in done.stderr


def test_fast_must_be_a_bool() -> None:
    env = _env()
    try:
        agent = TreeAgent(env.observation_space, env.action_space, "adaptive+tabu", 0)
        for bad in (1, "yes", None):
            with pytest.raises(TypeError, match="fast must be a bool"):
                agent.learn(env, 1, fast=bad)  # type: ignore[arg-type]
    finally:
        env.close()


# -- the kernel's arithmetic -------------------------------------------------------------


def test_hypot_le_agrees_with_cpython_or_abstains() -> None:
    kernel = fast_loop.load_kernel()
    rng = np.random.default_rng(0)
    a = rng.standard_normal(20000) * 50
    b = rng.standard_normal(20000) * 50
    abstained = 0
    for x, y in zip(a.tolist(), b.tolist(), strict=True):
        exact = math.hypot(x, y)
        for r in (exact, math.nextafter(exact, 0.0), math.nextafter(exact, math.inf), 10.0):
            answer = kernel.hypot_le(x, y, r)
            if answer < 0:
                abstained += 1
            else:
                assert bool(answer) == (exact <= r), (x, y, r)
    assert abstained <= 3 * 20000  # only the three near-threshold radii may abstain
    assert kernel.hypot_le(math.nan, 1.0, -math.inf) == 0
    assert kernel.hypot_le(math.nan, 1.0, 3.0) == -1
    assert kernel.hypot_le(1e-200, 1e-200, 1.0) == -1  # underflow: Python decides


def test_adaptive_epsilon_agrees_with_python() -> None:
    from agent.exploration.adaptive import adaptive_epsilon

    kernel = fast_loop.load_kernel()
    rng = np.random.default_rng(1)
    for _ in range(3000):
        counts = rng.integers(0, 50, size=(1, 4))
        if counts.sum() == 0:
            continue
        delta = float(rng.standard_normal() * 10.0 ** rng.integers(-6, 2))
        for variant in ("literal", "cn_exponent"):
            expected = adaptive_epsilon(counts[0].tolist(), delta, 0.001, 0.025, variant)
            got = kernel.adaptive_epsilon(counts, 0, 4, delta, 0.001, 0.025, variant != "literal")
            assert got == expected


# -- the split test in the kernel --------------------------------------------------------


def _runs_with_sums(make: Any, episodes: int, seed: int = 7) -> tuple[Any, int]:
    """run_both, and how many rings the fast run's kernel filled (exact sums from NumPy)."""
    results = []
    sums = 0
    for fast in (False, True):
        env = _env()
        try:
            agent = make(env)
            if fast:
                runner = fast_loop.episode_runner(agent, env)
                assert isinstance(runner, fast_loop.FastRunner)
                assert runner.st[runner.k.C_KREC] == 1
                history = []
                for i in range(episodes):
                    obs, _ = env.reset(seed=seed if i == 0 else None)
                    history.append(runner(env, obs))
                runner.sync()
                sums = runner.sums_events
            else:
                history = agent.learn(env, episodes, reset_seed=seed, fast=False)
            results.append((history, agent_state(agent), env_state(env)))
        finally:
            env.close()
    return results, sums


KERNEL_SPLITS = [
    # epochs longer than the buffer: the ring wraps inside one add, again and again
    ("adaptive+tabu", {}, {"split_min_samples": 7, "max_epoch_steps": None}, 6, False),
    ("vdbe", {}, {"split_min_samples": 30, "hold_exploration": False}, 5, False),
    ("vdbe", {"form": "exponential"}, {"split_min_samples": 20}, 6, False),
    # wide margins: a child takes all of the pairs (its ring full at once)
    (
        "adaptive+tabu",
        {"on_split": "inherit"},
        {"split_min_samples": 12, "min_leaf_fraction": 0.2},
        6,
        True,
    ),
    (
        "epsilon-greedy",
        {"epsilon": 0.3},
        {"split_min_samples": 15, "min_leaf_fraction": 0.5},
        5,
        True,
    ),
    # the other split rules
    ("adaptive", {}, {"split_min_samples": 20, "split_point": "midpoint"}, 5, False),
    (
        "tabu",
        {},
        {"split_min_samples": 20, "range_normalization": "none", "split_min_t": 1.5},
        6,
        False,
    ),
    ("adaptive", {"inherit_on_split": False}, {"split_min_samples": 25, "max_leaves": 6}, 5, False),
]


@pytest.mark.parametrize(("strategy", "params", "config", "seed", "child_rings"), KERNEL_SPLITS)
def test_split_tests_in_the_kernel_are_bit_identical(
    strategy: str, params: dict[str, Any], config: dict[str, Any], seed: int, child_rings: bool
) -> None:
    def make(env: gym.Env) -> Any:
        exploration = make_exploration(strategy, **params)
        cfg = TreeConfig(**{"split_max_abs_mean": 10.0, "split_min_variance": 1e-4, **config})
        return TreeAgent(env.observation_space, env.action_space, exploration, seed, cfg)

    results, sums = _runs_with_sums(make, episodes=4)
    assert_same(results)
    assert results[1][1]["n_leaves"] > 3
    assert sums[0] > 0  # full rings: NumPy's exact sums were asked for
    assert (sums[2] > 0) == child_rings


def test_the_python_split_test_still_runs_for_large_buffers(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(fast_loop, "MAX_KERNEL_BUFFER", 10)
    env = _env()
    try:
        runner = fast_loop.episode_runner(fig4_agent("adaptive+tabu")(env), env)
        assert isinstance(runner, fast_loop.FastRunner)
        assert runner.st[runner.k.C_KREC] == 0
    finally:
        env.close()
    results = run_both(fig4_agent("adaptive+tabu", split_min_samples=40), episodes=4)
    assert_same(results)
    assert results[1][1]["n_leaves"] > 3


def test_a_runner_called_directly_syncs_on_request() -> None:
    env = _env()
    try:
        agent = fig4_agent("adaptive+tabu", split_min_samples=40)(env)
        runner = fast_loop.episode_runner(agent, env)
        obs, _ = env.reset(seed=3)
        runner(env, obs)
        assert agent.q == [[0.0] * agent.n_actions]  # lazy: not written yet
        runner.sync()
        runner.sync()  # nothing pending: no change
        assert agent.partition.n_leaves == runner.st[runner.k.I_NLEAVES]
        assert agent.q != [[0.0] * agent.n_actions]
    finally:
        env.close()


def test_pairwise_sums_agree_with_numpy() -> None:
    kernel = fast_loop.load_kernel()
    rng = np.random.default_rng(4)
    for n in [*range(1, 40), 127, 128, 129, 255, 256, 257, 500, 1000, 1023, 4096, 5000]:
        a = rng.standard_normal(2 * n) * 10.0 ** rng.uniform(-3, 3)
        assert kernel.pairwise_sum(a, 0, n, 1) == a[:n].sum()
        assert 0.0 + kernel.pairwise_sum(a, 1, n, 2) == a[1::2].sum()


def test_the_split_statistics_agree_with_numpy() -> None:
    from agent import split_statistics as stats

    kernel = fast_loop.load_kernel()
    k = kernel
    rng = np.random.default_rng(5)
    for trial in range(400):
        capacity = int(rng.choice([4, 9, 40, 500, fast_loop.MAX_KERNEL_BUFFER]))
        full = trial % 2 == 0
        count = capacity if full else int(rng.integers(4, capacity + 1))
        head = int(rng.integers(0, capacity)) if full else count % capacity
        low = rng.uniform(0.0, 100.0, 2)
        high = low + rng.uniform(1.0, 200.0, 2)
        root_low, root_high = np.zeros(2), np.array([300.0, 300.0])
        inputs = rng.uniform(low, high, (capacity, 2))
        errors = rng.standard_normal(capacity) + rng.uniform(-0.5, 0.5)
        errors[rng.random(capacity) < 0.05] = 0.0
        fraction = float(rng.choice([1 / 256, 0.01, 0.3]))
        rule = "midpoint" if trial % 7 == 0 else "quest"
        norm = "none" if trial % 5 == 0 else "root"
        min_t = 2.0 if trial % 3 == 0 else 0.0
        # the reference, on the ring in ErrorBuffer.arrays() order
        order = np.arange(count) if count < capacity else (np.arange(capacity) + head) % capacity
        xs, es = inputs[order], errors[order]
        root_width = root_high - root_low
        min_width = root_width * fraction
        ranges = high - low
        if norm == "root":
            ranges = np.where(root_width > 0.0, ranges / root_width, 0.0)
        expected = None
        if ((high - low) >= 2.0 * min_width).any():
            expected = stats.choose_split(xs, es, low, high, ranges, min_width, rule, min_t)
        st = np.zeros(k.N_INT, dtype=np.int64)
        fs = np.zeros(k.N_FLOAT, dtype=np.float64)
        lf = np.zeros((1, k.N_LF), dtype=np.float64)
        st[k.I_NLEAVES], st[k.C_MAX_LEAVES] = 1, 10
        st[k.C_MIDPOINT], st[k.C_ROOT_NORM] = rule == "midpoint", norm == "root"
        fs[k.F_RW0], fs[k.F_RW1] = root_width
        fs[k.F_MIN_FRACTION], fs[k.F_MIN_T] = fraction, min_t
        lf[0, k.LF_LO0 : k.LF_LO1 + 1], lf[0, k.LF_HI0 : k.LF_HI1 + 1] = low, high
        bctr = np.array([[count, head, capacity, 0]], dtype=np.int64)
        dim, value = kernel.choose_split(
            0, 0, st, fs, lf, inputs.reshape(1, -1).copy(), errors.reshape(1, -1).copy(), bctr
        )
        assert (None if dim < 0 else (dim, value)) == expected, trial


def test_numpy_reduces_axis_0_row_by_row_up_to_the_kernel_buffer() -> None:
    kernel = fast_loop.load_kernel()
    rng = np.random.default_rng(6)
    for n in (2, 3, 17, 129, 1000, fast_loop.MAX_KERNEL_BUFFER):
        group = rng.standard_normal((n, 2)) * 100.0
        for c in range(2):
            mean, var = kernel.column_stats(group, c)
            assert (mean, var) == (group.mean(axis=0)[c], group.var(axis=0, ddof=1)[c])
            mean, var = kernel.vector_stats(group, c)
            assert (mean, var) == (float(group[:, c].mean()), float(group[:, c].var(ddof=1)))


def test_density_crossing_agrees_with_python() -> None:
    from agent.split_statistics import density_crossing

    kernel = fast_loop.load_kernel()
    rng = np.random.default_rng(7)
    for _ in range(5000):
        m1, m2 = rng.uniform(0.0, 10.0, 2)
        v1, v2 = rng.uniform(0.01, 5.0, 2)
        if rng.random() < 0.1:
            v2 = v1
        n1, n2 = (int(v) for v in rng.integers(2, 500, 2))
        expected = density_crossing(m1, v1, n1, m2, v2, n2)
        found, root = kernel.density_crossing(m1, v1, n1, m2, v2, n2)
        assert (root if found else None) == expected


def test_an_exception_in_a_sweep_reaches_the_caller() -> None:
    env = _env()
    try:
        agent = fig4_agent("adaptive+tabu")(env)
        world = env.unwrapped.world
        original = world.sweep_collides
        calls = [0]

        def failing(*args: float) -> bool:  # called by the kernel through its ctypes callback
            calls[0] += 1
            if calls[0] == 20:
                raise KeyboardInterrupt
            return original(*args)

        world.sweep_collides = failing
        assert isinstance(fast_loop.episode_runner(agent, env), fast_loop.FastRunner)
        with pytest.raises(KeyboardInterrupt):
            agent.learn(env, 3, reset_seed=1)
        assert calls[0] == 20
    finally:
        env.close()
