"""One agent trained, saved and pictured: the job behind ``run.py train`` and the default job.

The folder it writes: ``episodes.csv`` (the run's CSV, as in an experiment), ``agent.npz`` (the
whole agent: training resumes from it exactly), ``policy.npz`` (the policy only: the partition,
Q-bar and the strategy, a small fraction of the size, acting exactly like ``agent.npz``),
``config.toml`` (the one-strategy experiment, resolved), ``meta.json`` (seeds, episodes, whether
the time budget stopped it, timing, optimum, leaves), ``learning_curve.png`` and
``partition.png`` (the partition over the maze with one greedy episode's track).
"""

from __future__ import annotations

import json
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from experiments import config as config_module
from experiments import factory, plots, store
from experiments.config import ExperimentConfig
from experiments.evaluation import Episode, greedy_episode
from experiments.partition import partition_figure
from experiments.seeding import derive_seeds
from experiments.training import Training, train


@dataclass(frozen=True)
class SingleRun:
    """What :func:`train_and_save` did."""

    out: Path
    training: Training
    optimal_steps: float
    leaves: int
    greedy: Episode
    """One greedy episode of the trained agent (seeded with the run's environment seed)."""


def train_and_save(
    config: ExperimentConfig,
    seed: int,
    out: Path,
    on_start: Callable[[float], None] | None = None,
    on_episode: Callable[[store.EpisodeRow], None] | None = None,
    origins: Mapping[str, str] | None = None,
) -> SingleRun:
    """Train the first strategy of ``config`` with run seed ``seed`` and write ``out``.

    ``on_start(optimal_steps)`` is called once the environment exists, ``on_episode(row)``
    after every episode (a progress bar). Stops at ``config.episodes`` or, if set, after the
    episode that passes ``config.time_budget_s`` seconds. ``origins`` say where each
    environment setting came from, for errors (:func:`experiments.factory.env_origins`).
    """
    strategy = config.strategies[0]
    seeds = derive_seeds(seed)
    env = factory.check_env(config.env, origins or factory.env_origins(config.source))
    try:
        agent = factory.make_agent(
            config, strategy, env, seeds.agent, bounds=config.env.observation_bounds
        )
        optimal = factory.optimal_steps(env)
        if on_start is not None:
            on_start(optimal)
        training = train(
            env,
            agent,
            config.episodes,
            env_seed=seeds.env,
            time_budget_s=config.time_budget_s,
            on_episode=on_episode,
        )
        greedy = greedy_episode(env, agent, seed=seeds.env)
        geometry = factory.maze_geometry(env) if config.env.is_maze else None
    finally:
        env.close()
    _write(config, seed, seeds, out, training, optimal, agent)
    plots.learning_curve(
        np.array([r[1] for r in training.rows]),
        np.array([r[5] for r in training.rows]),
        optimal,
        out / "learning_curve.png",
        window=config.smoothing_window,
        title=f"{strategy.name}, seed {seed}",
        cap=config.env.max_episode_steps,
    )
    if geometry is not None:  # the partition drawn over the maze (maze environments only)
        partition_figure(
            agent,
            *geometry,
            out / "partition.png",
            title=f"{strategy.name}: {agent.n_leaves} leaves, greedy actions; "
            f"greedy episode {greedy.steps} steps",
            trajectory=greedy.positions,
        )
    return SingleRun(out, training, optimal, agent.n_leaves, greedy)


def _write(
    config: ExperimentConfig,
    seed: int,
    seeds: Any,
    out: Path,
    training: Training,
    optimal: float,
    agent: Any,
) -> None:
    rows = training.rows
    out.mkdir(parents=True, exist_ok=True)
    store.atomic_write_text(out / "episodes.csv", store.format_rows(rows))
    store.atomic_write_text(out / "config.toml", config_module.dumps(config))
    meta = {
        "strategy": config.strategies[0].name,
        "seed": seed,
        "env_seed": seeds.env,
        "agent_seed": seeds.agent,
        "episodes": len(rows),
        "stopped_by_time_budget": training.stopped_by_budget,
        "wall_time_s": training.wall_time_s,
        "env_steps": training.env_steps,
        "steps_per_second": training.steps_per_second,
        "optimal_steps": optimal,
        "leaves": agent.n_leaves,
    }
    store.atomic_write_text(out / "meta.json", json.dumps(meta, indent=2) + "\n")
    agent.save(out / "agent.npz")
    agent.save(out / "policy.npz", policy_only=True)
