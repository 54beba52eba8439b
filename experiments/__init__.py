"""The experiment harness behind ``run.py``.

One small module per concern:

- :mod:`experiments.config`: experiment TOML files, loaded and validated into dataclasses;
- :mod:`experiments.seeding`: common random seeds derived with ``numpy.random.SeedSequence``;
- :mod:`experiments.factory`: builds the environment and the agent of one run;
- :mod:`experiments.training`: trains one agent and collects its per-episode statistics;
- :mod:`experiments.single_run`: one agent trained, saved and pictured (``run.py train``);
- :mod:`experiments.store`: per-run result files written atomically, and resume;
- :mod:`experiments.backends`: serial, process-pool and Ray executors;
- :mod:`experiments.runner`: runs an experiment (strategies x runs) on a backend;
- :mod:`experiments.statistics`: moving averages, bootstrap bands, convergence, IQM, P(improvement);
- :mod:`experiments.plots`: learning curves and the Figure 4 analog;
- :mod:`experiments.partition`: the learned partition drawn over the maze;
- :mod:`experiments.evaluation`: greedy episodes of a trained agent;
- :mod:`experiments.animation`: a GIF of one greedy episode;
- :mod:`experiments.report`: the Markdown report of an experiment.

The experiment files themselves (``paper_fig4.toml``, ``quick.toml``) live beside these modules.
"""

from __future__ import annotations

from pathlib import Path

EXPERIMENT_DIR = Path(__file__).resolve().parent

__all__ = ["EXPERIMENT_DIR"]
