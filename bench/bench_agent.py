"""Agent cost per environment step (choose, observe, update), measured against the env alone.

Two parts.

1. The reference loop on a trivial env: the same trivial env twice, once with a fixed action
   cycle (the env's own cost) and once under ``TreeAgent.learn(fast=False)`` with a tree of
   500 leaves (a balanced tree over the box, capped there with ``max_leaves`` so the split
   test still runs but the size stays put). The agent's cost is the difference. (The fast loop
   runs only on our env: on this one ``learn`` falls back to the reference.)
2. ``--fast``: the reference against the fast loop (``agent/fast_loop.py``) in the default
   maze (kinematic, ``gymnasium.make``, cap 5,000), with the same 500-leaf trees: both paths
   on the same seeds take the same actions, so the env's share can be taken out of each. The
   reference's agent cost is (its learning time) - (the same actions replayed through
   ``gymnasium.make``); the fast loop's is (its learning time) - (time in the env's Python
   code: sweeps and ``env.step``), an upper bound, since its own kinematic steps count as
   agent. Interleaved rounds, medians of per-round ratios.

Times are this process's CPU time (``time.process_time``), because the machine is shared.
Results go in docs/benchmarks.md, section "Agent".

    python bench/bench_agent.py [--steps 200000] [--leaves 500]
    python bench/bench_agent.py --fast [--episodes 40] [--rounds 3]
"""

from __future__ import annotations

import argparse
import statistics
import time
import tracemalloc
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from agent import GridAgent, TreeAgent, TreeConfig


class TrivialEnv:
    """A point in [0, 300]^2 moved 5 units by each of 4 actions; no noise, no goal.

    The maze's proportions (a step is 1/60 of the width) so that epochs are as long as there.
    Walls stop the point and report a collision; episodes are truncated after ``horizon`` steps.
    """

    def __init__(self, horizon: int = 5000) -> None:
        self.observation_space = spaces.Box(0.0, 300.0, shape=(2,), dtype=np.float64)
        self.action_space = spaces.Discrete(4)
        self.horizon = horizon
        self._moves = ((0.0, 5.0), (0.0, -5.0), (-5.0, 0.0), (5.0, 0.0))

    def reset(self, *, seed: int | None = None, options: Any = None) -> tuple[np.ndarray, dict]:
        self.x, self.y, self.t = 150.0, 150.0, 0
        return np.array((self.x, self.y)), {}

    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        dx, dy = self._moves[action]
        x, y = self.x + dx, self.y + dy
        hit = not (0.0 <= x <= 300.0 and 0.0 <= y <= 300.0)
        if not hit:
            self.x, self.y = x, y
        self.t += 1
        info = {"collision": hit}
        return (
            np.array((self.x, self.y)),
            (-1.0 if hit else -0.01),
            False,
            self.t >= self.horizon,
            info,
        )


def env_only_seconds(steps: int, horizon: int) -> float:
    """Wall time of ``steps`` env steps with a fixed action cycle (no agent)."""
    env = TrivialEnv(horizon)
    env.reset()
    t0 = time.process_time()
    for i in range(steps):
        _, _, _, truncated, _ = env.step((i // 3) % 4)
        if truncated:
            env.reset()
    return time.process_time() - t0


def balanced_tree(agent: TreeAgent, leaves: int) -> None:
    """Split the widest leaf at its middle until the tree has ``leaves`` leaves."""
    while agent.n_leaves < leaves:
        infos = agent.leaves()
        widest = max(infos, key=lambda i: max(h - lo for lo, h in zip(i.low, i.high, strict=True)))
        widths = [h - lo for lo, h in zip(widest.low, widest.high, strict=True)]
        dim = int(np.argmax(widths))
        agent.split_leaf(widest.leaf, dim, widest.low[dim] + widths[dim] / 2)


def agent_seconds(agent: Any, steps: int, horizon: int) -> tuple[float, int]:
    """Wall time and steps of ``agent.learn`` on the trivial env (whole episodes)."""
    env = TrivialEnv(horizon)
    episodes = max(1, steps // horizon)
    t0 = time.process_time()
    history = agent.learn(env, episodes, reset_seed=0, fast=False)
    return time.process_time() - t0, sum(s.steps for s in history)


class RecordActions(gym.Wrapper):
    """Records every action (the reference loop runs through any wrapper)."""

    def __init__(self, env: gym.Env) -> None:
        super().__init__(env)
        self.actions: list[list[int]] = []

    def reset(self, **kwargs: Any) -> Any:
        self.actions.append([])
        return self.env.reset(**kwargs)

    def step(self, action: Any) -> Any:
        self.actions[-1].append(int(action))
        return self.env.step(action)


def maze_agent(strategy: str, leaves: int, env: gym.Env) -> Any:
    """A 500-leaf agent for the maze (a balanced tree capped there, or a 60 x 60 grid)."""
    if strategy == "grid":
        return GridAgent(env.observation_space, env.action_space, "adaptive+tabu", 0, resolution=60)
    config = TreeConfig(max_leaves=leaves)
    agent = TreeAgent(env.observation_space, env.action_space, strategy, seed=0, config=config)
    balanced_tree(agent, leaves)
    return agent


def fast_agent_cost(strategy: str, leaves: int, episodes: int, rounds: int) -> None:
    """Part 2 for one case: the agent's cost per step on each path, in interleaved rounds."""
    import bullet_maze  # noqa: F401
    from agent import fast_loop

    def make_env() -> gym.Env:
        return gym.make("BulletMaze-v0", max_episode_steps=5000)

    fast_loop.load_kernel()
    recorder = RecordActions(make_env())
    history = maze_agent(strategy, leaves, recorder).learn(recorder, episodes, reset_seed=1)
    steps = sum(s.steps for s in history)
    recorder.close()

    def reference() -> float:
        env = make_env()
        agent = maze_agent(strategy, leaves, env)
        t0 = time.process_time()
        assert agent.learn(env, episodes, reset_seed=1, fast=False) == history
        seconds = time.process_time() - t0
        env.close()
        return seconds

    def replay() -> float:
        env = make_env()
        t0 = time.process_time()
        for i, actions in enumerate(recorder.actions):
            env.reset(seed=1 if i == 0 else None)
            for action in actions:
                env.step(action)
        seconds = time.process_time() - t0
        env.close()
        return seconds

    def fast() -> tuple[float, float]:
        env = make_env()
        agent = maze_agent(strategy, leaves, env)
        runner = fast_loop.episode_runner(agent, env)
        assert isinstance(runner, fast_loop.FastRunner)
        runner.env_seconds = 0.0
        out = []
        t0 = time.process_time()
        for i in range(episodes):
            obs, _ = env.reset(seed=1 if i == 0 else None)
            out.append(runner(env, obs))
        runner.sync()  # what learn does at its end: the agent written back
        seconds = time.process_time() - t0
        assert out == history
        env.close()
        return seconds, runner.env_seconds

    ratios, ref_costs, fast_costs = [], [], []
    for i in range(rounds):
        measured: dict[str, Any] = {}
        order = ("reference", "replay", "fast") if i % 2 == 0 else ("fast", "replay", "reference")
        for name in order:
            measured[name] = {"reference": reference, "replay": replay, "fast": fast}[name]()
        ref_cost = (measured["reference"] - measured["replay"]) / steps
        fast_total, fast_env = measured["fast"]
        fast_cost = (fast_total - fast_env) / steps
        ratios.append(ref_cost / fast_cost)
        ref_costs.append(ref_cost)
        fast_costs.append(fast_cost)
    label = "grid 60x60, adaptive+tabu" if strategy == "grid" else f"tree {leaves}, {strategy}"
    print(
        f"{label:<32} {steps:>9,d} {1 / statistics.median(ref_costs):>14,.0f} "
        f"{1 / statistics.median(fast_costs):>14,.0f} {statistics.median(ratios):>6.2f}x "
        f"({min(ratios):.2f}-{max(ratios):.2f})"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="part 2: reference vs fast loop")
    parser.add_argument("--episodes", type=int, default=40, help="episodes of part 2")
    parser.add_argument("--rounds", type=int, default=3, help="interleaved rounds of part 2")
    parser.add_argument("--steps", type=int, default=200_000)
    parser.add_argument("--leaves", type=int, default=500)
    parser.add_argument("--horizon", type=int, default=5000)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    if args.fast:
        print(
            f"agent cost in the default maze, {args.episodes} episodes, CPU time, median of "
            f"{args.rounds} interleaved rounds (range); agent steps/s = 1 / agent cost per step"
        )
        print(f"{'case':<32} {'steps':>9} {'reference':>14} {'fast (bound)':>14} {'ratio':>7}")
        for strategy in ("adaptive+tabu", "epsilon-greedy", "vdbe", "grid"):
            fast_agent_cost(strategy, args.leaves, args.episodes, args.rounds)
        return

    env_time = min(env_only_seconds(args.steps, args.horizon) for _ in range(args.repeats))
    env_per_step = env_time / args.steps
    print(f"trivial env alone: {1 / env_per_step:,.0f} steps/s ({env_per_step * 1e6:.2f} us/step)")
    obs_space, act_space = TrivialEnv().observation_space, TrivialEnv().action_space
    cases: list[tuple[str, Any]] = []
    for strategy in ("epsilon-greedy", "adaptive+tabu", "vdbe"):
        config = TreeConfig(max_leaves=args.leaves)
        tree = TreeAgent(obs_space, act_space, strategy, seed=0, config=config)
        balanced_tree(tree, args.leaves)
        cases.append((f"tree {args.leaves} leaves, {strategy}", tree))
    cases.append(("grid 60x60, adaptive+tabu", GridAgent(obs_space, act_space, resolution=60)))
    print(f"{'case':<40} {'agent steps/s':>14} {'us/step':>8} {'ratio':>6} {'steps/epoch':>11}")
    for label, agent in cases:
        tracemalloc.start()
        seconds, steps = agent_seconds(agent, args.steps, args.horizon)
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
        # timing under tracemalloc is slower; measure again without it
        seconds, steps = min(
            agent_seconds(agent, args.steps, args.horizon) for _ in range(args.repeats)
        )
        per_step = seconds / steps
        agent_cost = per_step - env_per_step
        epochs = sum(v for row in agent.visits for v in row) / (args.repeats + 1)
        print(
            f"{label:<40} {1 / agent_cost:>14,.0f} {agent_cost * 1e6:>8.2f} "
            f"{per_step / env_per_step:>6.2f} {steps / max(epochs, 1):>11.2f}"
            f"   (peak traced memory {peak / 1e6:.1f} MB, leaves {agent.n_leaves})"
        )


if __name__ == "__main__":
    main()
