"""Speed of the learning loop (env + agent) and of the parallel runner.

Four measurements, each printed as a ratio against its reference:

1. ``ratio``: the fast loop (``learn(fast=True)``, ``agent/fast_loop.py``) against the
   reference loop (``learn(fast=False)``, today's ``_run_episode``) for every strategy of
   ``experiments/paper_fig4.toml`` (tree and grid agents), default maze, kinematic: both paths
   on the same seeds in interleaved rounds, CPU time of this process, the median of the
   per-round ratios (quartiles), and a check that both gave the same episodes;
2. ``speed``: steps per second of one learning run (the proposed agent in the default maze),
   against the target of 20,000 per core, and against the bare environment stepped with random
   actions;
3. ``workers``: the same small experiment with 1 and with 2 workers (``--backend process`` or
   ``ray``): the speed-up, against the target 1.8x (run with nothing else busy: two workers
   need two free cores);
4. ``memory``: resident memory of a worker over a long run, sampled every few episodes.

    python bench/bench_learning.py --only ratio     # (1), a few minutes
    python bench/bench_learning.py                  # all of them
"""

from __future__ import annotations

import argparse
import dataclasses
import gc
import multiprocessing
import os
import statistics
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

from experiments import factory, runner
from experiments.backends import ProcessBackend, make_backend
from experiments.config import load_config, with_overrides
from experiments.seeding import derive_seeds, run_seed
from experiments.training import resident_memory_mb, train


def bare_env_speed(steps: int, seed: int = 0) -> float:
    """Steps per second of the environment alone, random actions, resets included."""
    config = load_config("quick")
    env = factory.make_env(config.env)
    rng = np.random.default_rng(seed)
    actions = rng.integers(0, env.action_space.n, steps)
    env.reset(seed=seed)
    start = time.perf_counter()
    for action in actions:
        _, _, terminated, truncated, _ = env.step(int(action))
        if terminated or truncated:
            env.reset()
    elapsed = time.perf_counter() - start
    env.close()
    return steps / elapsed


def learning_speed(episodes: int, strategy: str = "adaptive+tabu") -> tuple[float, int, float]:
    """Steps per second of one learning run; also its steps and wall time."""
    config = with_overrides(load_config("quick"), episodes=episodes)
    spec = config.strategy(strategy)
    seeds = derive_seeds(run_seed(config.seed, 0))
    env = factory.make_env(config.env)
    agent = factory.make_agent(config, spec, env, seeds.agent)
    training = train(env, agent, episodes, env_seed=seeds.env)
    env.close()
    return training.steps_per_second, training.env_steps, training.wall_time_s


def timed_learning(name: str, episodes: int, fast: bool, run: int = 0) -> tuple[float, list]:
    """CPU seconds of one ``paper_fig4`` run of strategy ``name`` (``learn(fast=fast)``) and
    its episode statistics; the env and agent are built before the clock starts, and Python's
    cyclic garbage collector is run to completion then too.

    Why the collection: a full (oldest-generation) collection costs about 50 ms in this
    process (some 130,000 tracked objects: numba, pybullet, NumPy) and is triggered by the
    garbage of the runs before (envs and agents built and dropped here), so it lands on
    whichever timed run happens to cross the threshold; on a 50-ms fast run that halves its
    ratio. Collected before the clock starts, both paths start from the same empty
    generations; what their own allocations trigger is still timed."""
    config = with_overrides(load_config("paper_fig4"), episodes=episodes)
    seeds = derive_seeds(run_seed(config.seed, run))
    env = factory.make_env(config.env)
    agent = factory.make_agent(config, config.strategy(name), env, seeds.agent)
    gc.collect()
    start = time.process_time()
    history = agent.learn(env, episodes, reset_seed=seeds.env, fast=fast)
    seconds = time.process_time() - start
    env.close()
    return seconds, history


def fast_ratios(episodes: int, rounds: int) -> None:
    """(1): reference / fast time of every paper_fig4 strategy, interleaved rounds."""
    from agent import fast_loop

    fast_loop.load_kernel()  # compiled or loaded from numba's cache before any clock runs
    names = [spec.name for spec in load_config("paper_fig4").strategies]
    timed_learning(names[0], 1, True)  # the fingerprints of the mirrored code, checked once
    ratios: dict[str, list[float]] = {name: [] for name in names}
    rates: dict[str, list[tuple[float, float]]] = {name: [] for name in names}
    steps: dict[str, int] = {}
    identical = {name: True for name in names}
    for i in range(rounds):
        for name in names if i % 2 == 0 else names[::-1]:
            order = (False, True) if i % 2 == 0 else (True, False)
            timed = {fast: timed_learning(name, episodes, fast) for fast in order}
            (reference, history0), (fast, history1) = timed[False], timed[True]
            identical[name] &= history0 == history1
            steps[name] = sum(s.steps for s in history0)
            ratios[name].append(reference / fast)
            rates[name].append((steps[name] / reference, steps[name] / fast))
    print(
        f"learning loop, paper_fig4 strategies, default maze, kinematic, {episodes} episodes "
        f"(run 0's seeds), CPU time, median of {rounds} interleaved rounds (quartiles)"
    )
    print(f"  {'strategy':26s} {'steps':>9s} {'reference/s':>12s} {'fast/s':>11s} ratio")
    for name in names:
        values = sorted(ratios[name])
        low, high = (
            statistics.quantiles(values, n=4)[::2] if len(values) >= 4 else (values[0], values[-1])
        )
        reference = statistics.median(r for r, _ in rates[name])
        fast = statistics.median(f for _, f in rates[name])
        print(
            f"  {name:26s} {steps[name]:>9,d} {reference:>12,.0f} {fast:>11,.0f} "
            f"{statistics.median(values):5.2f}x ({low:.2f}-{high:.2f})"
            f"{'' if identical[name] else '  EPISODES DIFFER'}"
        )
    print(f"  identical episodes in every round: {all(identical.values())} (target: 3x, same CSVs)")


@dataclasses.dataclass(frozen=True)
class PoolTiming:
    """One experiment run with a given number of workers."""

    workers: int
    wall_s: float
    cpu_per_run_s: float
    """Mean CPU time of a run's learning loop (rises when runs share a core or its caches)."""
    load_before: float
    """1-minute load average when it started (other people's processes count)."""
    steps_per_s: float = 0.0
    """Mean over runs of a run's steps per second of wall time (per worker)."""


def worker_speedup(
    runs: int, episodes: int, backend: str = "process"
) -> tuple[list[PoolTiming], bool]:
    """One small experiment with 1 and then 2 workers; and whether the CSVs agree.

    The experiment is epsilon-greedy 0.015 alone: in the default maze its early episodes run
    to the cap, so the runs cost about the same and the speed-up measures the pool, not how
    unequal the runs are. Worker start-up (spawn, imports) is included.
    """
    config = with_overrides(load_config("quick"), runs=runs, episodes=episodes)
    config = dataclasses.replace(
        config, time_budget_s=None, baseline=None, strategies=(config.strategy("eps-greedy-0.015"),)
    )
    timings = []
    with tempfile.TemporaryDirectory() as folder:
        for workers in (1, 2):
            out = Path(folder) / f"w{workers}"
            load = os.getloadavg()[0]
            start = time.perf_counter()
            pool = (
                ProcessBackend(workers) if backend == "process" else make_backend(backend, workers)
            )
            results = runner.run_experiment(config, out, pool)
            wall = time.perf_counter() - start
            cpu = float(np.mean([r.meta["cpu_time_s"] for r in results]))
            rate = float(np.mean([r.steps_per_second for r in results]))
            timings.append(PoolTiming(workers, wall, cpu, load, rate))
        same = (Path(folder) / "w1" / runner.EPISODES_FILE).read_bytes() == (
            Path(folder) / "w2" / runner.EPISODES_FILE
        ).read_bytes()
    return timings, same


def _spin(iterations: int) -> int:
    total = 0
    for i in range(iterations):
        total += i
    return total


def machine_speedup(iterations: int = 15_000_000) -> float:
    """What this machine gives right now: two pure-Python loops on 1 worker vs on 2.

    The reference for the pool's speed-up: on a shared machine, the 1.8x target is reachable
    only if this ratio is well above it.
    """
    times = []
    for workers in (1, 2):
        context = multiprocessing.get_context("spawn")
        with ProcessPoolExecutor(workers, mp_context=context) as pool:
            list(pool.map(_spin, [1000] * workers))  # start the workers, not timed
            start = time.perf_counter()
            list(pool.map(_spin, [iterations, iterations]))
            times.append(time.perf_counter() - start)
    return times[0] / times[1]


def memory_profile(episodes: int, every: int) -> tuple[list[float], int, int]:
    """Resident memory (MB) of this process every ``every`` episodes of a long run; also the
    run's steps and its final number of leaves (the tree is what may grow)."""
    config = with_overrides(load_config("quick"), episodes=episodes)
    seeds = derive_seeds(run_seed(config.seed, 0))
    env = factory.make_env(config.env)
    agent = factory.make_agent(config, config.strategies[0], env, seeds.agent)
    samples = [resident_memory_mb()]
    training = train(env, agent, episodes, env_seed=seeds.env, memory_every=every)
    env.close()
    return samples + training.rss_mb, training.env_steps, agent.n_leaves


def main() -> None:
    """Run the measurements chosen on the command line and print them."""
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument(
        "--only", choices=("ratio", "speed", "workers", "memory"), help="run one measurement only"
    )
    parser.add_argument(
        "--ratio-episodes", type=int, default=100, help="episodes per run of (1) (default: 100)"
    )
    parser.add_argument(
        "--rounds", type=int, default=5, help="interleaved rounds of (1) (default: 5)"
    )
    parser.add_argument(
        "--backend", choices=("process", "ray"), default="process", help="backend of (3)"
    )
    parser.add_argument(
        "--episodes", type=int, default=300, help="episodes of the speed measurement (default: 300)"
    )
    parser.add_argument(
        "--runs",
        type=int,
        default=8,
        help="runs of the 1-vs-2-worker experiment (default: 8)",
    )
    parser.add_argument(
        "--worker-episodes",
        type=int,
        default=1000,
        help="episodes per run of the 1-vs-2-worker experiment (default: 1000)",
    )
    parser.add_argument(
        "--memory-episodes",
        type=int,
        default=4000,
        help="episodes of the memory run (default: 4000, as the paper)",
    )
    args = parser.parse_args()

    if args.only in (None, "ratio"):
        fast_ratios(args.ratio_episodes, args.rounds)
    if args.only in (None, "speed"):
        bare = bare_env_speed(50_000)
        rate, steps, wall = learning_speed(args.episodes)
        print(f"bare env (random actions):      {bare:>10,.0f} steps/s")
        print(
            f"learning loop (env + agent):    {rate:>10,.0f} steps/s "
            f"({steps:,} steps in {wall:.1f} s, {args.episodes} episodes)"
        )
        print(
            f"  vs target 20,000 steps/s/core: {rate / 20_000:.2f}x; vs the bare env: "
            f"{rate / bare:.2f}x"
        )
    if args.only in (None, "workers"):
        reference = machine_speedup()
        timings, same = worker_speedup(args.runs, args.worker_episodes, args.backend)
        one, two = timings
        print(
            f"experiment ({args.backend}) {args.runs} runs x {args.worker_episodes} episodes: "
            f"1 worker {one.wall_s:.1f} s, 2 workers {two.wall_s:.1f} s, speed-up "
            f"{one.wall_s / two.wall_s:.2f}x (target 1.8x); identical CSVs: {same}"
        )
        print(
            f"  CPU time per run {one.cpu_per_run_s:.1f} s alone, {two.cpu_per_run_s:.1f} s two "
            f"at a time; load average before: {one.load_before:.1f}, {two.load_before:.1f} "
            f"(on {os.cpu_count()} cores); the machine itself gave {reference:.2f}x for two "
            "pure-Python loops just before"
        )
        print(
            f"  steps/s per worker (mean over runs): {one.steps_per_s:,.0f} with 1 worker, "
            f"{two.steps_per_s:,.0f} with 2"
        )
        print(
            f"  bound set by the CPU time per run (2 x alone / two at a time): "
            f"{2 * one.cpu_per_run_s / two.cpu_per_run_s:.2f}x; the rest is start-up and the tail"
        )
    if args.only in (None, "memory"):
        every = max(1, args.memory_episodes // 20)
        samples, steps, leaves = memory_profile(args.memory_episodes, every)
        half = len(samples) // 2
        print(
            f"memory over {args.memory_episodes} episodes, {steps:,} steps, {leaves} leaves at "
            f"the end (MB every {every}): " + " ".join(f"{m:.0f}" for m in samples)
        )
        print(
            f"  first sample after start {samples[1]:.1f} MB, last {samples[-1]:.1f} MB; "
            f"growth over the second half {samples[-1] - samples[half]:+.1f} MB"
        )


if __name__ == "__main__":
    main()
