"""Speed and memory of the bullet_maze env, against raw pybullet and Gymnasium-Robotics.

One run prints env steps per second through ``gymnasium.make`` (random actions, resets
included) for the kinematic and the dynamic mode, raw pybullet ``stepSimulation`` for the same
substeps in the same world, and ``PointMaze_UMaze-v3`` when gymnasium-robotics is installed
(``pip install -e ".[bench]"``), with the ratios the targets are stated in; then the resident
memory over many create/close cycles. The machine may be shared: rates are measured in CPU time of
this process (``time.process_time``; everything here runs in one thread), so time spent waiting
for a core does not count, and every measurement is repeated in rounds, interleaved with the
others (each round runs them all, alternately forwards and backwards, so that an env and its
reference run side by side). A rate is the median over the rounds; a ratio is the median of the
ratios measured within each round, so that load which slows a whole round cancels out.
``--wall`` uses wall-clock time instead.

Run: ``python bench/bench_env.py`` (``--quick`` for a smoke test).
"""

from __future__ import annotations

import argparse
import gc
import os
import statistics
import time
from collections.abc import Callable

import gymnasium as gym
import numpy as np
import pybullet as pb

import bullet_maze


def rss_mb() -> float:
    """Resident set size of this process in MiB (Linux)."""
    with open("/proc/self/statm") as handle:
        pages = int(handle.read().split()[1])
    return pages * os.sysconf("SC_PAGE_SIZE") / 2**20


CLOCK = time.process_time
"""The clock of every rate: CPU time of this process, or wall time with ``--wall``."""


def env_runner(env_id: str, steps: int, **kwargs: object) -> Callable[[], float]:
    """A function timing ``steps`` random-action steps through ``gymnasium.make``."""
    env = gym.make(env_id, **kwargs)
    rng = np.random.default_rng(0)
    if env_id.startswith("PointMaze"):
        actions = list(rng.uniform(-1.0, 1.0, (steps, 2)).astype(np.float32))
    else:
        actions = list(rng.integers(0, 4, steps))

    def run() -> float:
        env.reset(seed=0)
        start = CLOCK()
        for action in actions:
            _, _, terminated, truncated, _ = env.step(action)
            if terminated or truncated:
                env.reset()
        return steps / (CLOCK() - start)

    return run


def raw_runner(steps: int, substeps: int) -> Callable[[], float]:
    """Bare pybullet in the dynamic env's own world and settings: per env step, the disc's
    velocity command for a random direction, then the same number of ``stepSimulation``, each
    call naming the client positionally as the env does (a keyword costs about 0.25 us)."""
    env = bullet_maze.BulletMazeEnv(mode="dynamic", substeps=substeps)
    env.reset(seed=0)
    client, body = env.client_id, env.robot.body_id
    physics = env.physics
    substeps = range(physics.substeps)
    speed = (
        env.task.step_size * bullet_maze.METRES_PER_UNIT / (physics.substeps * physics.time_step)
    )
    velocities = [
        (speed * dx, speed * dy, 0.0)
        for dx, dy in bullet_maze.actions.DIRECTIONS[np.random.default_rng(0).integers(0, 4, steps)]
    ]

    def run() -> float:
        env.reset(seed=0)
        start = CLOCK()
        for velocity in velocities:
            pb.resetBaseVelocity(body, velocity, (0.0, 0.0, 0.0), client)
            for _ in substeps:
                pb.stepSimulation(client)
        return steps / (CLOCK() - start)

    return run


def memory_cycles(cycles: int, **kwargs: object) -> list[tuple[int, float]]:
    """RSS after 0, 10 %, ... 100 % of ``cycles`` make/reset/step/close cycles."""
    marks = []
    for i in range(cycles + 1):
        if i % max(1, cycles // 10) == 0:
            gc.collect()
            marks.append((i, rss_mb()))
        if i == cycles:
            break
        env = gym.make("BulletMaze-v0", **kwargs)
        env.reset(seed=i)
        env.step(0)
        env.close()
    return marks


def measure(runners: dict[str, Callable[[], float]], rounds: int) -> dict[str, list[float]]:
    """Every runner once per round, forwards in even rounds and backwards in odd ones."""
    rates: dict[str, list[float]] = {name: [] for name in runners}
    names = list(runners)
    for i in range(rounds):
        for name in names if i % 2 == 0 else names[::-1]:
            rates[name].append(runners[name]())
    return rates


def paired_ratio(rates: dict[str, list[float]], slow: str, fast: str) -> tuple[float, float, float]:
    """Median and quartiles over the rounds of ``rate[fast] / rate[slow]`` within each round
    (the time of a ``slow`` step over the time of a ``fast`` step)."""
    ratios = sorted(f / s for s, f in zip(rates[slow], rates[fast], strict=True))
    if len(ratios) < 4:
        return statistics.median(ratios), ratios[0], ratios[-1]
    low, _, high = statistics.quantiles(ratios, n=4)
    return statistics.median(ratios), low, high


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=20_000, help="kinematic steps per round")
    parser.add_argument("--rounds", type=int, default=21, help="interleaved rounds; medians count")
    parser.add_argument("--cycles", type=int, default=1000, help="create/close cycles")
    parser.add_argument("--quick", action="store_true", help="a short run for a smoke test")
    parser.add_argument("--wall", action="store_true", help="wall-clock time, not CPU time")
    parser.add_argument("--only", choices=("speed", "memory"), help="run one part")
    args = parser.parse_args()
    global CLOCK
    if args.wall:
        CLOCK = time.perf_counter
    if args.quick:
        args.steps, args.rounds, args.cycles = 2000, 3, 50
    if args.only != "memory":
        speed(args.steps, args.rounds, args.wall)
    if args.only != "speed":
        memory(args.cycles)


def speed(steps: int, rounds: int, wall: bool) -> None:
    """Steps per second of every case, and the ratios the targets are stated in."""
    dyn = max(100, steps // 10)
    default = bullet_maze.PhysicsParams().substeps
    # Each env beside its reference, so that the two run next to each other in every round.
    runners: dict[str, Callable[[], float]] = {
        "kinematic, disc": env_runner("BulletMaze-v0", steps),
        "kinematic, disc, sweep before 2026-12-07": env_runner(
            "BulletMaze-v0", steps, contact_release=False
        ),
        "kinematic, husky": env_runner("BulletMaze-v0", steps, robot="husky"),
        "kinematic, disc, corridors": env_runner("BulletMaze-corridors-v0", steps),
        "dynamic, disc": env_runner("BulletMaze-v0", dyn, mode="dynamic"),
        "raw stepSimulation, same substeps": raw_runner(dyn, default),
        f"raw stepSimulation, {2 * default} substeps": raw_runner(dyn, 2 * default),
        f"dynamic, disc, {2 * default} substeps": env_runner(
            "BulletMaze-v0", dyn, mode="dynamic", substeps=2 * default
        ),
        "dynamic, husky": env_runner(
            "BulletMaze-v0", max(10, dyn // 100), mode="dynamic", robot="husky"
        ),
    }
    pointmaze = "PointMaze_UMaze-v3 (MuJoCo)"
    try:
        import gymnasium_robotics
    except ImportError:
        print(
            "PointMaze_UMaze-v3 skipped: gymnasium-robotics is not installed "
            "(pip install -e '.[bench]')"
        )
    else:
        gym.register_envs(gymnasium_robotics)
        runners[pointmaze] = env_runner("PointMaze_UMaze-v3", dyn)
        # PointMaze beside the dynamic disc as well: run it again right after it.
        order = list(runners)
        order.insert(order.index("dynamic, disc"), order.pop(order.index(pointmaze)))
        runners = {name: runners[name] for name in order}

    for run in runners.values():  # warm up: caches, lazily built cells, first-call checks
        run()
    rates = measure(runners, rounds)

    physics = bullet_maze.PhysicsParams()
    clock = "wall-clock" if wall else "CPU"
    print(
        f"env steps per {clock} second through gymnasium.make, median of {rounds} interleaved "
        f"rounds (quartiles), one process (dynamic: {physics.substeps} substeps of "
        f"{physics.time_step:.5f} s)"
    )
    for name, values in rates.items():
        if len(values) >= 4:
            low, _, high = statistics.quantiles(values, n=4)
        else:
            low, high = min(values), max(values)
        print(f"  {name:36s} {statistics.median(values):10,.0f}  ({low:,.0f}-{high:,.0f})")
    print("ratios, median of the per-round ratios (quartiles):")
    for label, slow, fast, target in (
        (
            "dynamic overhead: env step time / raw physics time",
            "dynamic, disc",
            "raw stepSimulation, same substeps",
            "target <= 1.25",
        ),
        (
            f"the same with {2 * default} substeps",
            f"dynamic, disc, {2 * default} substeps",
            f"raw stepSimulation, {2 * default} substeps",
            "target <= 1.25",
        ),
    ):
        median, low, high = paired_ratio(rates, slow, fast)
        print(f"  {label:52s} {median:5.2f}  ({low:.2f}-{high:.2f}; {target})")
    # contact_release (issue 9, part 31): the same random walk, which the old sweep could hold
    # against a wall; a held robot's steps are refused moves, so this compares walks, not only
    # the sweep's extra comparison
    median, low, high = paired_ratio(
        rates, "kinematic, disc", "kinematic, disc, sweep before 2026-12-07"
    )
    label = "kinematic disc step time, today's sweep / the old one"
    print(f"  {label:52s} {median:5.2f}  ({low:.2f}-{high:.2f}; no target)")
    if pointmaze in rates:
        for label, name, target in (
            ("kinematic / PointMaze", "kinematic, disc", ">= 5"),
            ("dynamic / PointMaze", "dynamic, disc", ">= 1"),
        ):
            median, low, high = paired_ratio(rates, pointmaze, name)
            print(f"  {label:52s} {median:5.2f}  ({low:.2f}-{high:.2f}; target {target})")


def memory(cycles: int) -> None:
    """Resident memory over many make/reset/step/close cycles, disc and husky."""
    for label, count, kwargs in (
        ("disc", cycles, {}),
        ("husky", max(10, cycles // 5), {"robot": "husky"}),
    ):
        marks = memory_cycles(count, **kwargs)
        print(f"resident memory (MiB) over {count} make/reset/step/close cycles, {label}:")
        print("  " + "  ".join(f"{i}: {mb:.1f}" for i, mb in marks))
        print(f"  growth after the first 10 %: {marks[-1][1] - marks[1][1]:+.1f} MiB")


if __name__ == "__main__":
    main()
