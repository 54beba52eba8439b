"""Cost of the lambda blend in the general agent (issue 9, parts 6 and 7; the options are off).

``TreeConfig.model_lambda`` adds a backward pass over each episode's epochs, a blend of each
stored epoch, the undoing of the blends of ``model_lambda_episodes`` episodes back, and a
sweep, at every episode's end. This prints CPU seconds per 1,000 environment steps of the
general preset with the blend (lambda 0.9, undone after 8 episodes, bounded below: the
``recent8-bound`` of ``experiments/lambda_recent_dev.toml``) and of the preset itself, on
MountainCar-v0, on the ``paper`` maze and on Taxi-v4, in interleaved rounds (CPU time of this
process, the agent built before the clock starts), and their ratio (median over rounds, with
its range). The two agents learn differently, so they take different steps: the ratio is per
step.

    python bench/bench_general.py                 # 3 rounds, about 3 minutes
    python bench/bench_general.py --rounds 1 --episodes 50
"""

from __future__ import annotations

import argparse
import dataclasses
import gc
import statistics
import time
from typing import Any

import gymnasium as gym

import bullet_maze  # noqa: F401 (registers BulletMaze-v0)
from agent import TreeConfig, adapt_env, preset
from agent.tree_ensemble import tree_agent_class

TASKS: dict[str, dict[str, Any]] = {
    "MountainCar-v0": {},
    "BulletMaze-v0": {"maze": "paper", "max_episode_steps": 5000},
    "Taxi-v4": {},  # integer inputs through agent.adapt_env (issue 9, part 15)
}


def learning_cost(task: str, config: TreeConfig, episodes: int, seed: int) -> tuple[float, int]:
    """CPU seconds and environment steps of ``episodes`` learning episodes of an agent with
    ``config`` and the general preset's strategy (built before the clock starts)."""
    env = adapt_env(gym.make(task, **TASKS[task]))  # leaves a fitting task alone
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, preset("general").make_exploration(), seed, config
    )
    gc.collect()
    start = time.process_time()
    history = agent.learn(env, episodes, reset_seed=seed)
    cpu = time.process_time() - start
    env.close()
    return cpu, sum(h.steps for h in history)


def compare(label: str, old: TreeConfig, new: TreeConfig, rounds: int, episodes: int) -> None:
    """Print, per task, the CPU seconds per 1,000 steps and per learning episode of ``new``
    and of ``old`` (called ``label``) over ``episodes`` episodes, in interleaved rounds (agent
    and reset seed = the round), and the ratios new / old (median over rounds, with their
    range). The two agents learn differently, so they take different steps."""
    for task in TASKS:
        rows: dict[bool, list[tuple[float, float]]] = {False: [], True: []}
        for seed in range(rounds):
            for is_old, config in ((True, old), (False, new)):
                cpu, steps = learning_cost(task, config, episodes, seed)
                rows[is_old].append((1000.0 * cpu / steps, cpu / episodes))
        step_ratio = [a[0] / b[0] for a, b in zip(rows[False], rows[True], strict=True)]
        episode_ratio = [a[1] / b[1] for a, b in zip(rows[False], rows[True], strict=True)]
        print(
            f"{task}: CPU-s / 1,000 steps {statistics.median(r[0] for r in rows[False]):.3f}"
            f" ({label}: {statistics.median(r[0] for r in rows[True]):.3f}), ratio"
            f" {statistics.median(step_ratio):.2f}x ({min(step_ratio):.2f}-{max(step_ratio):.2f});"
            f" CPU-s / episode {statistics.median(r[1] for r in rows[False]):.4f}"
            f" ({label}: {statistics.median(r[1] for r in rows[True]):.4f}), ratio"
            f" {statistics.median(episode_ratio):.2f}x"
            f" ({min(episode_ratio):.2f}-{max(episode_ratio):.2f})"
        )


def cpu_per_kilostep(task: str, blend: bool, episodes: int, seed: int) -> float:
    """CPU seconds per 1,000 steps of ``episodes`` learning episodes of the general preset
    (``blend=True``: with the recent, bounded lambda blend)."""
    config = preset("general").config
    if blend:
        config = dataclasses.replace(
            config, model_lambda=0.9, model_lambda_episodes=8, model_lambda_lower_bound=True
        )
    cpu, steps = learning_cost(task, config, episodes, seed)
    return 1000.0 * cpu / steps


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--episodes", type=int, default=100)
    args = parser.parse_args()
    print(f"general preset, {args.episodes} episodes a run, {args.rounds} interleaved rounds")
    print("task | CPU-s / 1,000 steps without | with the blend | ratio (median, range)")
    for task in TASKS:
        ratios, plain, blended = [], [], []
        for r in range(args.rounds):
            without = cpu_per_kilostep(task, False, args.episodes, seed=r)
            with_blend = cpu_per_kilostep(task, True, args.episodes, seed=r)
            plain.append(without)
            blended.append(with_blend)
            ratios.append(with_blend / without)
        print(
            f"{task} | {statistics.median(plain):.3f} | {statistics.median(blended):.3f} | "
            f"{statistics.median(ratios):.2f}x ({min(ratios):.2f}-{max(ratios):.2f})"
        )


if __name__ == "__main__":
    main()
