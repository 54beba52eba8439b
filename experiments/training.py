"""Train one agent: the learning loop's bookkeeping (rows, timing, budget) and one run's task.

:func:`train` wraps ``agent.learn`` with a per-episode hook and an optional wall-clock budget;
:func:`train_run` is the picklable task that the backends execute for each (strategy, run).
"""

from __future__ import annotations

import math
import os
import resource
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from experiments import factory, fingerprint
from experiments.backends import RunFailed
from experiments.evaluation import evaluate
from experiments.plan import RunSpec
from experiments.seeding import derive_seeds
from experiments.store import EpisodeRow, EvalRow, RunResult

if TYPE_CHECKING:
    import gymnasium as gym


@dataclass
class Training:
    """What a call to :func:`train` did."""

    rows: list[EpisodeRow] = field(default_factory=list)
    wall_time_s: float = 0.0
    cpu_time_s: float = 0.0
    """CPU time of this process while learning (wall time minus waiting for a shared core)."""
    stopped_by_budget: bool = False
    rss_mb: list[float] = field(default_factory=list)
    """Resident memory of this process every ``memory_every`` episodes (MB)."""

    @property
    def env_steps(self) -> int:
        """Environment steps taken over all episodes."""
        return sum(row[1] for row in self.rows)

    @property
    def steps_per_second(self) -> float:
        """Environment steps (env + agent) per second of wall time."""
        return self.env_steps / self.wall_time_s if self.wall_time_s > 0 else math.nan


def episode_row(stats: Any, episode: int) -> EpisodeRow:
    """A CSV row from an ``agent.EpisodeStats`` (numbered by the harness, from 1)."""
    return (
        episode,
        int(stats.steps),
        float(stats.episode_return),
        bool(stats.success),
        bool(stats.truncated),
        int(stats.leaves),
        int(stats.collisions),
    )


def resident_memory_mb() -> float:
    """Resident set size of this process in MB (Linux ``/proc``; peak RSS elsewhere)."""
    try:
        with open("/proc/self/statm", encoding="ascii") as handle:
            pages = int(handle.read().split()[1])
        return pages * os.sysconf("SC_PAGE_SIZE") / 2**20
    except (OSError, ValueError, IndexError):
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def train(
    env: gym.Env,
    agent: Any,
    episodes: int,
    env_seed: int | None = None,
    time_budget_s: float | None = None,
    on_episode: Callable[[EpisodeRow], None] | None = None,
    memory_every: int = 0,
) -> Training:
    """Run ``agent.learn`` for up to ``episodes`` episodes, or until the time budget is spent.

    The budget is checked after each episode (an episode is never cut), so a budgeted run is
    reproducible only up to where it stopped.
    """
    training = Training()
    start, cpu_start = time.perf_counter(), time.process_time()

    def callback(stats: Any) -> bool:
        row = episode_row(stats, len(training.rows) + 1)
        training.rows.append(row)
        if memory_every and row[0] % memory_every == 0:
            training.rss_mb.append(resident_memory_mb())
        if on_episode is not None:
            on_episode(row)
        if time_budget_s is not None and time.perf_counter() - start >= time_budget_s:
            training.stopped_by_budget = len(training.rows) < episodes
            return False
        return True

    agent.learn(env, episodes, callback=callback, reset_seed=env_seed)
    training.wall_time_s = time.perf_counter() - start
    training.cpu_time_s = time.process_time() - cpu_start
    return training


def evaluation_rows(env: gym.Env, agent: Any, episodes: int, seed: int) -> tuple[EvalRow, ...]:
    """``episodes`` greedy episodes of a trained agent, the first reset seeded with ``seed``."""
    result = evaluate(env, agent, episodes, seed=seed)
    return tuple(
        (i + 1, e.steps, e.episode_return, e.success, e.truncated, e.collisions)
        for i, e in enumerate(result.episodes)
    )


def policy_bytes(agent: Any) -> bytes:
    """The agent's policy file (``agent.save(policy_only=True)``) as bytes, for the runner to
    store beside the run."""
    with tempfile.TemporaryDirectory(prefix="bullet_maze_agent_") as folder:
        return Path(agent.save(Path(folder) / "agent.npz", policy_only=True)).read_bytes()


def train_run(spec: RunSpec) -> RunResult:
    """:func:`_train_run`, with any error it raises (an ``Exception``, not an interrupt) given
    back as :class:`RunFailed` naming the run."""
    try:
        return _train_run(spec)
    except Exception as error:
        raise RunFailed.of(f"run {spec.name}", error) from error


def _train_run(spec: RunSpec) -> RunResult:
    """The task of one run: a fresh environment and agent seeded from the run's seed, trained,
    then (if the experiment asks) evaluated greedily from the run's evaluation seed.

    The result carries the fingerprints of the inputs this worker actually used (the layout
    its environment loaded), which the runner checks against those it expected.
    """
    experiment, strategy = spec.experiment, spec.strategy
    seeds = derive_seeds(spec.seed)
    env = factory.make_env(spec.env)
    try:
        used = fingerprint.env_inputs(spec.env, layout=getattr(env.unwrapped, "layout", None))
        inputs = fingerprint.run_inputs(experiment, strategy, spec.env, spec.seed, train_run, used)
        agent = factory.make_agent(
            experiment, strategy, env, seeds.agent, bounds=spec.env.observation_bounds
        )
        rss_start = resident_memory_mb()
        memory_every = max(1, experiment.episodes // 20)
        training = train(
            env, agent, experiment.episodes, env_seed=seeds.env, memory_every=memory_every
        )
        evaluation = (
            evaluation_rows(env, agent, experiment.eval_episodes, seeds.evaluation)
            if experiment.eval_episodes
            else ()
        )
        optimal = factory.optimal_steps(env)
        agent_file = policy_bytes(agent) if experiment.save_agents else b""
    finally:
        env.close()
    return RunResult(
        agent_file=agent_file,
        task=spec.task,
        evaluation=evaluation,
        strategy=strategy.name,
        run_index=spec.run_index,
        seed=spec.seed,
        rows=tuple(training.rows),
        wall_time_s=training.wall_time_s,
        env_steps=training.env_steps,
        optimal_steps=optimal,
        meta={
            "env_seed": seeds.env,
            "agent_seed": seeds.agent,
            **({"evaluation_seed": seeds.evaluation} if evaluation else {}),
            "pid": os.getpid(),
            "cpu_time_s": training.cpu_time_s,
            "rss_mb_start": rss_start,
            "rss_mb": training.rss_mb,
            "rss_mb_every_episodes": memory_every,
        },
        inputs=inputs,
    )
