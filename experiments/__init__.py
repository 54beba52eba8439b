"""The experiment harness behind ``run.py``.

The front door is three jobs (:mod:`experiments.jobs`), which ``run.py`` only fills from the
command line and prints from:

- :class:`TrainJob`: one agent, one strategy, one seed, saved and pictured;
- :class:`Experiment`: strategies x runs (x tasks: the layouts of a suite split, or
  ``[[task]]`` tables) into a results folder: ``pending()``, ``run()``, ``report()``;
- :class:`Playback`: a saved agent evaluated or rendered in an environment;
- :class:`Transfer` (:mod:`experiments.transfer`): saved agents x conditions (robots x modes x
  layouts x perturbation levels) into a results folder: ``status()``, ``run()``, ``report()``.

Behind it, one small module per concern:

- :mod:`experiments.config`: experiment TOML files, validated strictly and bounded;
- :mod:`experiments.plan`: the runs of an experiment (each with its own environment);
- :mod:`experiments.seeding`: common random seeds derived with ``numpy.random.SeedSequence``;
- :mod:`experiments.factory`: builds the environment and the agent of one run;
- :mod:`experiments.training`: trains one agent and collects its per-episode statistics;
- :mod:`experiments.single_run`: one agent trained, saved and pictured;
- :mod:`experiments.fingerprint`: fingerprints of every input of a run (layout, robot, env,
  resolved config, code version);
- :mod:`experiments.store`: per-run result files with a sidecar that vouches for them;
- :mod:`experiments.lock`: one writer per results folder;
- :mod:`experiments.backends`: serial, process-pool and Ray executors that survive a worker's
  death;
- :mod:`experiments.env_modules`: a user's modules that register their own envs
  (``run.py --env-module``), imported here and in every worker;
- :mod:`experiments.runner`: runs an experiment (strategies x runs) on a backend, verified;
- :mod:`experiments.statistics`: moving averages, bootstrap bands, convergence, IQM, P(improvement);
- :mod:`experiments.plots`: learning curves and the Figure 4 analog;
- :mod:`experiments.partition`: the learned partition drawn over the maze;
- :mod:`experiments.evaluation`: greedy episodes of a trained agent;
- :mod:`experiments.animation`: a GIF of one greedy episode;
- :mod:`experiments.report`: the Markdown report of an experiment in one environment;
- :mod:`experiments.references`: reference returns of Gymnasium tasks (random policy, solved);
- :mod:`experiments.task_scores`: per-task summaries and normalised scores;
- :mod:`experiments.aggregate`: IQM, performance profiles and probability of improvement over
  tasks, with stratified bootstrap intervals;
- :mod:`experiments.task_report`: the report of an experiment over tasks;
- :mod:`experiments.layout_sheet`: contact sheets of layouts with their shortest paths;
- :mod:`experiments.transfer`: the transfer matrix (its file, agents, cells, storage, the job);
  :mod:`experiments.transfer_cell`: one cell and the task that evaluates it;
  :mod:`experiments.transfer_state`: its spec, the verdicts on cells and the folder's state;
  :mod:`experiments.transfer_report`: its tables and heatmaps;
  :mod:`experiments.transfer_traces`: failing episodes replayed and drawn.

The experiment files themselves (``paper_fig4.toml``, ``quick.toml``) live beside these modules.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from experiments.backends import BACKENDS, RunFailed, TasksLost, default_workers, make_backend
    from experiments.config import EXPERIMENT_DIR, MODES, ConfigError
    from experiments.env_modules import ModuleError, import_env_modules
    from experiments.jobs import EnvOptions, Experiment, Playback, TrainJob
    from experiments.layout_sheet import draw_layout_sheet, draw_suite_sheet
    from experiments.runner import FolderState
    from experiments.statistics import interval_text
    from experiments.transfer import Transfer

_EXPORTS = {
    "BACKENDS": "experiments.backends",
    "TasksLost": "experiments.backends",
    "default_workers": "experiments.backends",
    "make_backend": "experiments.backends",
    "EXPERIMENT_DIR": "experiments.config",
    "MODES": "experiments.config",
    "ConfigError": "experiments.config",
    "ModuleError": "experiments.env_modules",
    "import_env_modules": "experiments.env_modules",
    "EnvOptions": "experiments.jobs",
    "Experiment": "experiments.jobs",
    "Playback": "experiments.jobs",
    "TrainJob": "experiments.jobs",
    "FolderState": "experiments.runner",
    "RunFailed": "experiments.backends",
    "Transfer": "experiments.transfer",
    "draw_layout_sheet": "experiments.layout_sheet",
    "draw_suite_sheet": "experiments.layout_sheet",
    "interval_text": "experiments.statistics",
}
"""The public names and their modules, imported on first use: a worker process that imports
``experiments.training`` does not pay for the plotting modules the front door also offers."""

__all__ = [
    "BACKENDS",
    "EXPERIMENT_DIR",
    "MODES",
    "ConfigError",
    "EnvOptions",
    "Experiment",
    "FolderState",
    "ModuleError",
    "Playback",
    "RunFailed",
    "TasksLost",
    "TrainJob",
    "Transfer",
    "default_workers",
    "draw_layout_sheet",
    "draw_suite_sheet",
    "import_env_modules",
    "interval_text",
    "make_backend",
]


def __getattr__(name: str) -> Any:
    if name not in _EXPORTS:
        raise AttributeError(f"module 'experiments' has no attribute {name!r}")
    return getattr(importlib.import_module(_EXPORTS[name]), name)


def __dir__() -> list[str]:
    return __all__
