"""The learner on small tasks: epochs, eqs. (9)-(10) in place, statistics, determinism, learning."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

from agent import GridAgent, TreeAgent, TreeConfig


class Scripted(gym.Env[np.ndarray, int]):
    """Observation fixed at the box's centre; scripted rewards, collisions and episode end."""

    def __init__(
        self,
        rewards: list[float],
        collisions: tuple[int, ...] = (),
        terminate: bool = True,
        with_success: bool = False,
    ) -> None:
        self.observation_space = spaces.Box(0.0, 1.0, shape=(1,), dtype=np.float64)
        self.action_space = spaces.Discrete(2)
        self.rewards, self.collisions = rewards, collisions
        self.terminate, self.with_success = terminate, with_success
        self.seeds: list[int | None] = []

    def reset(self, *, seed: int | None = None, options: Any = None) -> tuple[np.ndarray, dict]:
        super().reset(seed=seed)
        self.seeds.append(seed)
        self.t = 0
        return np.array([0.5]), {}

    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        reward = self.rewards[self.t]
        self.t += 1
        end = self.t == len(self.rewards)
        info: dict[str, Any] = {"collision": self.t in self.collisions}
        if self.with_success:
            info["is_success"] = False
        return np.array([0.5]), reward, end and self.terminate, end and not self.terminate, info


def agent_for(env: gym.Env, **config: Any) -> TreeAgent:
    return TreeAgent(env.observation_space, env.action_space, "greedy", config=TreeConfig(**config))


def test_one_epoch_updates_q_by_eqs_9_and_10() -> None:
    env = Scripted([1.0, 1.0, 1.0])
    agent = agent_for(env, alpha=0.5, gamma=0.5)
    [stats] = agent.learn(env, 1)
    # returns 1.75, 1.5, 1 (terminal: V-bar = 0); mean 1.41667; Q = 0.5 * 1.41667
    acted = int(np.argmax(agent.visits[0]))
    assert agent.q[0][acted] == pytest.approx(0.5 * (1.75 + 1.5 + 1.0) / 3)
    assert agent.q[0][1 - acted] == 0.0
    assert stats.epochs == 1
    assert stats.steps == 3
    assert stats.success
    assert stats.episode_return == pytest.approx(3.0)


def test_truncation_bootstraps_and_termination_does_not() -> None:
    for terminate, expected in ((True, 0.0), (False, 0.5 * (0.25 + 0.5) / 2)):
        env = Scripted([0.0, 0.0], terminate=terminate)
        agent = agent_for(env, alpha=0.5, gamma=0.5, q_init=1.0)
        [stats] = agent.learn(env, 1)
        acted = int(np.argmax(agent.visits[0]))
        # truncated: V-bar(s') = max Q = 1, returns 0.25 and 0.5
        assert agent.q[0][acted] == pytest.approx(0.5 * 1.0 + expected)
        assert stats.truncated is not terminate


def test_epochs_end_at_the_cap_and_on_collisions() -> None:
    env = Scripted([0.0] * 120)
    assert agent_for(env, max_epoch_steps=50).learn(env, 1)[0].epochs == 3
    assert agent_for(env, max_epoch_steps=None).learn(env, 1)[0].epochs == 1
    env = Scripted([0.0] * 10, collisions=(3, 4, 8))
    stats = agent_for(env, max_epoch_steps=None).learn(env, 1)[0]
    assert stats.collisions == 3
    assert stats.epochs == 4
    kept = agent_for(env, max_epoch_steps=None, end_epoch_on_collision=False).learn(env, 1)[0]
    assert kept.collisions == 3
    assert kept.epochs == 1


def test_collision_key_and_success_from_info() -> None:
    env = Scripted([0.0] * 4, collisions=(1,), with_success=True)
    stats = agent_for(env, collision_key="bump").learn(env, 1)[0]
    assert stats.collisions == 0
    assert stats.success is False  # info["is_success"] wins over terminated


def test_reset_seed_first_episode_only_and_callback_stops() -> None:
    env = Scripted([0.0])
    agent = agent_for(env)
    history = agent.learn(env, 5, callback=lambda s: s.episode < 2, reset_seed=11)
    assert [s.episode for s in history] == [0, 1, 2]
    assert env.seeds == [11, None, None]
    assert agent.learn(env, 1)[0].episode == 3


def corridor_agent(make_corridor: Callable[..., gym.Env], strategy: str, seed: int) -> TreeAgent:
    env = make_corridor()
    return TreeAgent(
        env.observation_space, env.action_space, strategy, seed, TreeConfig(split_min_samples=100)
    )


def test_same_seed_same_tree_bit_for_bit(make_corridor: Callable[..., gym.Env]) -> None:
    runs = []
    for _ in range(2):
        agent = corridor_agent(make_corridor, "adaptive+tabu", seed=3)
        history = agent.learn(make_corridor(), 40, reset_seed=3)
        arrays, _ = agent.partition.to_arrays()
        runs.append((history, arrays, agent.q))
    (h1, a1, q1), (h2, a2, q2) = runs
    assert h1 == h2
    assert a1.keys() == a2.keys()
    for key in a1:
        np.testing.assert_array_equal(a1[key], a2[key])
    assert q1 == q2
    assert h1[-1].leaves > 1


def greedy_steps(agent: TreeAgent | GridAgent, env: gym.Env, episodes: int) -> list[int]:
    out = []
    for i in range(episodes):
        obs, _ = env.reset(seed=100 + i)
        steps, terminated, truncated = 0, False, False
        while not (terminated or truncated):
            obs, _, terminated, truncated, _ = env.step(agent.predict(obs))
            steps += 1
        out.append(steps if terminated else 1000)
    return out


@pytest.mark.parametrize("strategy", ["epsilon-greedy", "adaptive+tabu", "vdbe"])
def test_learns_the_corridor_well_above_chance(
    make_corridor: Callable[..., gym.Env], strategy: str
) -> None:
    # a uniformly random policy needs 160 steps on average and succeeds in under half the
    # episodes (200-step limit); the shortest path is about 12 steps
    agent = corridor_agent(make_corridor, strategy, seed=0)
    history = agent.learn(make_corridor(), 300, reset_seed=0)
    last = history[-50:]
    assert sum(s.success for s in last) >= 45
    assert np.mean([s.steps for s in last]) < 70
    assert np.mean(greedy_steps(agent, make_corridor(), 5)) < 60


@pytest.mark.parametrize(("dims", "resolution"), [(38, 10), (3, [1000, 1000, 2]), (7, 8)])
def test_a_grid_of_too_many_cells_is_refused_before_any_table_is_sized(
    dims: int, resolution: Any
) -> None:
    """A lidar's 38 inputs at 10 cells each once took the process to 21 GB (part 17)."""
    box = spaces.Box(0.0, 1.0, (dims,), np.float64)
    with pytest.raises(ValueError, match=r"resolution .* cells, at most 1,000,000"):
        GridAgent(box, spaces.Discrete(4), "epsilon-greedy", resolution=resolution)


def test_grid_agent_learns_the_corridor(make_corridor: Callable[..., gym.Env]) -> None:
    env = make_corridor()
    agent = GridAgent(env.observation_space, env.action_space, "epsilon-greedy", resolution=10)
    history = agent.learn(env, 200, reset_seed=0)
    assert agent.n_leaves == 100
    assert agent.depth == 0
    assert np.mean([s.steps for s in history[-50:]]) < 40
    assert max(greedy_steps(agent, make_corridor(), 5)) < 40
