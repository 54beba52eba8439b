"""Speed and memory of the bullet_maze env, against raw pybullet and Gymnasium-Robotics.

One run prints env steps per second through ``gymnasium.make`` (random actions, resets
included) for the kinematic and the dynamic mode, raw pybullet ``stepSimulation`` for the same
substeps in the same world, and ``PointMaze_UMaze-v3`` when gymnasium-robotics is installed
(``pip install -e ".[bench]"``), with the ratios the targets are stated in; then the resident
memory over many create/close cycles. The machine may be shared: rates are measured in CPU time of
this process (``time.process_time``; everything here runs in one thread), so time spent waiting
for a core does not count, and every measurement is repeated in rounds, interleaved with the
others, the best round counting. ``--wall`` uses wall-clock time instead.

Run: ``python bench/bench_env.py`` (``--quick`` for a smoke test).
"""

from __future__ import annotations

import argparse
import gc
import os
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
    velocity command for a random direction, then the same number of ``stepSimulation``."""
    env = bullet_maze.BulletMazeEnv(mode="dynamic", substeps=substeps)
    env.reset(seed=0)
    client, body = env.client_id, env.robot.body_id
    physics = env.physics
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
            pb.resetBaseVelocity(body, velocity, (0.0, 0.0, 0.0), physicsClientId=client)
            for _ in range(physics.substeps):
                pb.stepSimulation(physicsClientId=client)
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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=20_000, help="kinematic steps per round")
    parser.add_argument("--rounds", type=int, default=5, help="interleaved rounds; best counts")
    parser.add_argument("--cycles", type=int, default=1000, help="create/close cycles")
    parser.add_argument("--quick", action="store_true", help="a short run for a smoke test")
    parser.add_argument("--wall", action="store_true", help="wall-clock time, not CPU time")
    args = parser.parse_args()
    global CLOCK
    if args.wall:
        CLOCK = time.perf_counter
    if args.quick:
        args.steps, args.rounds, args.cycles = 2000, 1, 50
    steps, dyn = args.steps, args.steps // 5
    default = bullet_maze.PhysicsParams().substeps

    runners: dict[str, Callable[[], float]] = {
        "kinematic, disc": env_runner("BulletMaze-v0", steps),
        "kinematic, husky": env_runner("BulletMaze-v0", steps, robot="husky"),
        "kinematic, disc, corridors": env_runner("BulletMaze-corridors-v0", steps),
        "dynamic, disc": env_runner("BulletMaze-v0", dyn, mode="dynamic"),
        "raw stepSimulation, same substeps": raw_runner(dyn, default),
        f"dynamic, disc, {2 * default} substeps": env_runner(
            "BulletMaze-v0", dyn, mode="dynamic", substeps=2 * default),
        f"raw stepSimulation, {2 * default} substeps": raw_runner(dyn, 2 * default),
        "dynamic, husky": env_runner(
            "BulletMaze-v0", max(20, dyn // 100), mode="dynamic", robot="husky"
        ),
    }
    try:
        import gymnasium_robotics
    except ImportError:
        print(
            "PointMaze_UMaze-v3 skipped: gymnasium-robotics is not installed "
            "(pip install -e '.[bench]')"
        )
    else:
        gym.register_envs(gymnasium_robotics)
        runners["PointMaze_UMaze-v3 (MuJoCo)"] = env_runner("PointMaze_UMaze-v3", dyn)

    best = dict.fromkeys(runners, 0.0)
    for _ in range(args.rounds):
        for name, run in runners.items():
            best[name] = max(best[name], run())

    physics = bullet_maze.PhysicsParams()
    clock = "wall-clock" if args.wall else "CPU"
    print(
        f"env steps per {clock} second through gymnasium.make, best of {args.rounds} rounds, "
        f"one process (dynamic: {physics.substeps} substeps of {physics.time_step:.5f} s)"
    )
    for name, rate in best.items():
        print(f"  {name:36s} {rate:10,.0f}")
    overhead = best["raw stepSimulation, same substeps"] / best["dynamic, disc"]
    print(f"  dynamic overhead: env step time / raw physics time = {overhead:.2f} (target <= 1.25)")
    pointmaze = best.get("PointMaze_UMaze-v3 (MuJoCo)")
    if pointmaze:
        print(f"  kinematic / PointMaze = {best['kinematic, disc'] / pointmaze:.1f} (target >= 5)")
        print(f"  dynamic / PointMaze   = {best['dynamic, disc'] / pointmaze:.2f} (target >= 1)")

    for label, cycles, kwargs in (
        ("disc", args.cycles, {}),
        ("husky", max(10, args.cycles // 5), {"robot": "husky"}),
    ):
        marks = memory_cycles(cycles, **kwargs)
        print(f"resident memory (MiB) over {cycles} make/reset/step/close cycles, {label}:")
        print("  " + "  ".join(f"{i}: {mb:.1f}" for i, mb in marks))
        print(f"  growth after the first 10 %: {marks[-1][1] - marks[1][1]:+.1f} MiB")


if __name__ == "__main__":
    main()
