"""Speed and memory of the bullet_maze env, against raw pybullet and Gymnasium-Robotics.

One run prints steps per second through ``gymnasium.make`` for the kinematic and the dynamic
mode, raw pybullet ``stepSimulation`` for the same substeps in the same world, and
``PointMaze_UMaze-v3`` when gymnasium-robotics is installed (``pip install -e ".[bench]"``),
with the ratios the targets are stated in; then the resident memory over many create/close
cycles. Run: ``python bench/bench_env.py`` (``--quick`` for a short run).
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


def best_rate(run: Callable[[], None], steps: int, repeats: int) -> float:
    """Steps per second of the fastest of ``repeats`` runs (the machine is shared)."""
    best = 0.0
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        best = max(best, steps / (time.perf_counter() - start))
    return best


def env_rate(env_id: str, steps: int, repeats: int, **kwargs: object) -> float:
    """Random-action steps per second through ``gymnasium.make`` (resets included)."""
    env = gym.make(env_id, **kwargs)
    env.reset(seed=0)
    actions = list(np.random.default_rng(0).integers(0, 4, steps))
    if env_id.startswith("PointMaze"):
        actions = list(np.random.default_rng(0).uniform(-1.0, 1.0, (steps, 2)))

    def run() -> None:
        for action in actions:
            _, _, terminated, truncated, _ = env.step(action)
            if terminated or truncated:
                env.reset()

    rate = best_rate(run, steps, repeats)
    env.close()
    return rate


def raw_rate(steps: int, repeats: int, substeps: int) -> float:
    """Env-step equivalents per second of bare ``stepSimulation`` calls in the env's world."""
    env = bullet_maze.BulletMazeEnv(mode="dynamic", substeps=substeps)
    env.reset(seed=0)
    client = env.client_id
    pb.resetBaseVelocity(env.robot.body_id, (1.0, 0.0, 0.0), physicsClientId=client)

    def run() -> None:
        for _ in range(steps * substeps):
            pb.stepSimulation(physicsClientId=client)

    rate = best_rate(run, steps, repeats)
    env.close()
    return rate


def pointmaze_rate(steps: int, repeats: int) -> float | None:
    try:
        import gymnasium_robotics
    except ImportError:
        return None
    gym.register_envs(gymnasium_robotics)
    return env_rate("PointMaze_UMaze-v3", steps, repeats)


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
    parser.add_argument("--steps", type=int, default=20_000, help="steps per timed run")
    parser.add_argument("--repeats", type=int, default=3, help="timed runs; the best counts")
    parser.add_argument("--cycles", type=int, default=1000, help="create/close cycles")
    parser.add_argument("--quick", action="store_true", help="a short run for a smoke test")
    args = parser.parse_args()
    if args.quick:
        args.steps, args.repeats, args.cycles = 2000, 1, 50
    substeps = bullet_maze.PhysicsParams().substeps

    kinematic = env_rate("BulletMaze-v0", args.steps, args.repeats)
    dynamic = env_rate("BulletMaze-v0", args.steps // 4, args.repeats, mode="dynamic")
    raw = raw_rate(args.steps // 4, args.repeats, substeps)
    husky = env_rate("BulletMaze-v0", args.steps // 4, args.repeats, robot="husky")
    pointmaze = pointmaze_rate(args.steps // 4, args.repeats)

    print(f"steps per second through gymnasium.make, best of {args.repeats}, one process")
    print(f"  kinematic (disc, paper)         {kinematic:10,.0f}")
    print(f"  kinematic (husky, paper)        {husky:10,.0f}")
    print(f"  dynamic (disc, {substeps} substeps)      {dynamic:10,.0f}")
    print(f"  raw stepSimulation x {substeps}          {raw:10,.0f}")
    print(f"  dynamic overhead: env step time / raw physics time = {raw / dynamic:.2f}"
          f"  (target <= 1.25)")
    if pointmaze is None:
        print("  PointMaze_UMaze-v3: gymnasium-robotics not installed (pip install -e '.[bench]')")
    else:
        print(f"  PointMaze_UMaze-v3 (MuJoCo)     {pointmaze:10,.0f}")
        print(f"  kinematic / PointMaze = {kinematic / pointmaze:.1f}  (target >= 5)")
        print(f"  dynamic / PointMaze   = {dynamic / pointmaze:.1f}  (target >= 1)")

    marks = memory_cycles(args.cycles)
    print(f"resident memory over {args.cycles} gymnasium.make/reset/step/close cycles (MiB)")
    print("  " + "  ".join(f"{i}: {mb:.1f}" for i, mb in marks))
    print(f"  growth after the first 10 %: {marks[-1][1] - marks[1][1]:+.1f} MiB")


if __name__ == "__main__":
    main()
