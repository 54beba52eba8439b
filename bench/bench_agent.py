"""Agent cost per environment step (choose, observe, update), measured against a trivial env.

Runs the same trivial env twice, once with a fixed action cycle (the env's own cost) and once
under ``TreeAgent.learn`` with a tree of 500 leaves (a balanced tree over the box, capped there
with ``max_leaves`` so the split test still runs but the size stays put). The agent's cost is
the difference. Times are this process's CPU time (``time.process_time``), not wall time, and
each is the best of ``--repeats`` runs, because the machine is shared. Prints agent steps per
second and the ratio of the two runs' times. Results go in
docs/benchmarks.md, section "Agent".

    python bench/bench_agent.py [--steps 200000] [--leaves 500]
"""

from __future__ import annotations

import argparse
import time
import tracemalloc
from typing import Any

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
    history = agent.learn(env, episodes, reset_seed=0)
    return time.process_time() - t0, sum(s.steps for s in history)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=200_000)
    parser.add_argument("--leaves", type=int, default=500)
    parser.add_argument("--horizon", type=int, default=5000)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()

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
