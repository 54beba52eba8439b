"""Common random seeds: run i of every strategy gets the same environment and agent seeds.

Seeds come from ``numpy.random.SeedSequence``. Run i's integer seed is drawn from the child
sequence with spawn key ``(i,)`` of the experiment seed, so it does not depend on how many runs
an experiment has (adding runs later keeps the earlier ones). A run's integer seed names its
files (``<strategy>__<seed>``) and is all that ``run.py train --seed`` needs to reproduce it: the
environment and agent seeds are derived from it in turn.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class RunSeeds:
    """The two seeds of one run."""

    env: int
    """Seed of the environment's first ``reset`` (its noise generator ``env.np_random``)."""
    agent: int
    """Seed of the agent's own ``numpy.random.Generator``."""
    evaluation: int
    """Seed of the first reset of the greedy evaluation after training."""


def run_seed(experiment_seed: int, run_index: int) -> int:
    """The integer seed of run ``run_index``, common to every strategy of the experiment."""
    if experiment_seed < 0 or run_index < 0:
        raise ValueError(f"seeds and run indices must be >= 0, got {experiment_seed}, {run_index}")
    sequence = np.random.SeedSequence(experiment_seed, spawn_key=(run_index,))
    return int(sequence.generate_state(1, dtype=np.uint32)[0])


def derive_seeds(seed: int) -> RunSeeds:
    """Independent environment, agent and evaluation seeds from one run seed (the children
    0, 1 and 2 of its ``SeedSequence``: adding the third left the first two as they were)."""
    if seed < 0:
        raise ValueError(f"seed must be >= 0, got {seed}")
    env_child, agent_child, evaluation_child = np.random.SeedSequence(seed).spawn(3)
    return RunSeeds(
        env=int(env_child.generate_state(1, dtype=np.uint32)[0]),
        agent=int(agent_child.generate_state(1, dtype=np.uint32)[0]),
        evaluation=int(evaluation_child.generate_state(1, dtype=np.uint32)[0]),
    )
