"""Training speed in physics (issue 11, item 4): the learning loop (env + the proposed agent) in
dynamic mode, per robot and action set, without and with domain randomisation, against the
kinematic disc in the same run.

Each case builds the environment of the ``quick`` experiment (``experiments/quick.toml``: the
default maze, the proposed agent adaptive + tabu with Table I's values) with its ``[env]`` table
changed as an experiment file would change it (``mode``, ``robot``, ``[env.params]``: the
action set and the perturbation level's settings from ``bullet_maze.perturbations``), then
trains a fresh agent for a few capped episodes with ``experiments.training.train`` and reports
env steps per CPU second of training (``time.process_time``: environment and agent together).

Every round runs every case once, forwards in even rounds and backwards in odd ones; a rate is
the median over the rounds, a ratio the median of the ratios measured within each round, so
that load which slows a whole round cancels out. The reference is the kinematic disc.

Then the disc's env alone (a fixed cycle of compass actions, no agent) with and without the
moderate level, in both modes: what the perturbed step path costs the env itself.

Run: ``python bench/bench_physics_training.py`` (``--rounds``, ``--quick`` for a smoke test).
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
import time
from collections.abc import Callable
from typing import Any

import gymnasium as gym

from bullet_maze.perturbations import level_settings
from experiments import factory
from experiments.config import load_config
from experiments.seeding import derive_seeds, run_seed
from experiments.training import train

SETS: tuple[tuple[str, str, int, int], ...] = (
    # robot, actions, dynamic episodes, dynamic cap (compass steps of wheeled robots take
    # hundreds of physics steps: fewer and shorter episodes)
    ("disc", "compass", 10, 1000),
    ("husky", "compass", 2, 100),
    ("husky", "native", 4, 500),
    ("rover", "compass", 2, 150),
    ("rover", "native", 4, 500),
    ("racecar", "native", 4, 500),
)
"""Every robot of the zoo with the action sets the agent's discrete actions can drive."""

CASES: tuple[tuple[str, str, str, str, int, int], ...] = tuple(
    case
    for robot, actions, episodes, cap in SETS
    for case in (
        (robot, "kinematic", actions, "none", 10, 2000),
        *(((robot, "kinematic", actions, "moderate", 10, 2000),) if robot == "disc" else ()),
        (robot, "dynamic", actions, "none", episodes, cap),
        (robot, "dynamic", actions, "moderate", episodes, cap),
        *(((robot, "dynamic", actions, "strong", episodes, cap),) if robot == "disc" else ()),
    )
)
"""(robot, mode, actions, perturbation level, episodes, cap); the first is the reference."""

DRIVES = {"disc": "holonomic", "husky": "differential", "rover": "differential"}
"""Drive kinds of the zoo (the racecar is the car)."""


def trainer(
    robot: str, mode: str, actions: str, level: str, episodes: int, cap: int
) -> Callable[[int], float]:
    """A function of the round that trains a fresh agent and returns env steps per CPU second."""
    config = load_config("quick")
    settings = level_settings(level, mode=mode, drive=DRIVES.get(robot, "ackermann"))
    params: dict[str, Any] = {"actions": actions, **settings}
    env_spec = dataclasses.replace(
        config.env, robot=robot, mode=mode, max_episode_steps=cap, params=params
    )
    config = dataclasses.replace(config, env=env_spec)
    strategy = config.strategies[0]

    def run(round_index: int) -> float:
        seeds = derive_seeds(run_seed(config.seed, round_index))
        env = factory.make_env(config.env)
        try:
            agent = factory.make_agent(config, strategy, env, seeds.agent)
            training = train(env, agent, episodes, env_seed=seeds.env)
        finally:
            env.close()
        return training.env_steps / training.cpu_time_s

    return run


ENV_CASES = (
    ("kinematic", "none"),
    ("kinematic", "moderate"),
    ("dynamic", "none"),
    ("dynamic", "moderate"),
)
"""The disc's env alone (a fixed action cycle, no agent): what the perturbed step path costs."""


def env_runner(mode: str, level: str, steps: int) -> Callable[[int], float]:
    """Env steps per CPU second of the disc, compass actions, a fixed cycle of actions."""
    settings: dict[str, Any] = dict(level_settings(level, mode=mode, drive="holonomic"))
    env = gym.make("BulletMaze-v0", mode=mode, **settings)
    cycle = [0, 3, 0, 2, 1, 2, 0, 3]

    def run(round_index: int) -> float:
        env.reset(seed=round_index)
        start = time.process_time()
        for i in range(steps):
            _, _, terminated, truncated, _ = env.step(cycle[i % 8])
            if terminated or truncated:
                env.reset()
        return steps / (time.process_time() - start)

    return run


def env_speed(rounds: int, steps: int) -> None:
    runners = {case: env_runner(*case, steps) for case in ENV_CASES}
    rates = interleaved(runners, rounds)
    print("\n| disc, compass, env alone | env steps/s | / same mode, no perturbation |")
    print("| --- | --- | --- |")
    for mode, level in ENV_CASES:
        ratio = statistics.median(
            r / q for r, q in zip(rates[(mode, level)], rates[(mode, "none")], strict=True)
        )
        print(f"| {mode}, {level} | {statistics.median(rates[(mode, level)]):,.0f} | {ratio:.2f} |")


def interleaved(runners: dict[Any, Callable[[int], float]], rounds: int) -> dict[Any, list[float]]:
    """Every runner once per round (given the round's index), forwards in even rounds and
    backwards in odd ones."""
    names = list(runners)
    rates: dict[Any, list[float]] = {name: [] for name in names}
    for i in range(rounds):
        for name in names if i % 2 == 0 else names[::-1]:
            rates[name].append(runners[name](i))
    return rates


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=7)
    parser.add_argument("--quick", action="store_true", help="one round, a tenth of the work")
    args = parser.parse_args()
    rounds = 1 if args.quick else args.rounds
    runners = {}
    for robot, mode, actions, level, episodes, cap in CASES:
        if args.quick:
            episodes, cap = max(1, episodes // 5), max(20, cap // 2)
        runners[(robot, mode, actions, level)] = trainer(robot, mode, actions, level, episodes, cap)
    names = list(runners)
    rates = interleaved(runners, rounds)
    reference = names[0]
    print(
        "| robot | actions | mode | perturbation level | training steps/s | / kinematic disc | "
        "/ same robot and actions, kinematic | / same, no perturbation |"
    )
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")

    def ratio(a: tuple[str, str, str, str], b: tuple[str, str, str, str]) -> float:
        return statistics.median(x / y for x, y in zip(rates[a], rates[b], strict=True))

    for name in names:
        robot, mode, actions, level = name
        kinematic = ratio(name, (robot, "kinematic", actions, "none"))
        plain = ratio(name, (robot, mode, actions, "none"))
        print(
            f"| {robot} | {actions} | {mode} | {level} | {statistics.median(rates[name]):,.0f} | "
            f"{ratio(name, reference):.4f} | {kinematic:.4f} | {plain:.2f} |",
            flush=True,
        )
    env_speed(rounds, 2000 if args.quick else 50000)


if __name__ == "__main__":
    main()
