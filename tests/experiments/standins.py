"""Stand-ins for the real learner: a deterministic fake run, importable by worker processes.

Tests put this folder on ``sys.path`` so that spawned workers (and subprocesses) import it as
``standins``. Set ``STANDIN_LOG`` to a file to count computations (one line per run computed),
``STANDIN_SLEEP`` to slow each run down, ``STANDIN_STARTED`` to a file that gets each worker's
pid when a run starts, ``STANDIN_DIE_ONCE`` to a folder: the first attempt of each run kills its
own process (SIGKILL) and leaves a marker there (only run ``STANDIN_DIE_NAME``'s, if that is
set), and ``STANDIN_ALWAYS_DIE`` to a strategy name whose runs always kill their process.
"""

from __future__ import annotations

import os
import signal
import time
import zlib
from pathlib import Path

import numpy as np

from experiments.plan import RunSpec
from experiments.store import RunResult


def fake_run(spec: RunSpec) -> RunResult:
    """A learning-curve-shaped run that depends only on the run's seed and strategy."""
    if os.environ.get("STANDIN_STARTED"):
        with open(os.environ["STANDIN_STARTED"], "a", encoding="utf-8") as handle:
            handle.write(f"{os.getpid()}\n")
    if os.environ.get("STANDIN_ALWAYS_DIE") == spec.strategy.name:
        os.kill(os.getpid(), signal.SIGKILL)
    if os.environ.get("STANDIN_DIE_ONCE") and os.environ.get("STANDIN_DIE_NAME", spec.name) == (
        spec.name
    ):
        marker = Path(os.environ["STANDIN_DIE_ONCE"]) / spec.name.replace("/", "__")
        if not marker.exists():
            marker.write_text("died once\n")
            os.kill(os.getpid(), signal.SIGKILL)
    rng = np.random.default_rng([spec.seed, zlib.crc32(spec.strategy.name.encode())])
    episodes, cap = spec.experiment.episodes, spec.env.max_episode_steps
    level = 20 + 10 * rng.random()
    curve = level + (cap - level) * np.exp(-np.arange(episodes) / (episodes / 5))
    steps = np.minimum(cap, np.round(curve * rng.lognormal(0, 0.2, episodes))).astype(int)
    rows = tuple(
        (
            i + 1,
            int(s),
            5.0 - 0.01 * (int(s) - 1) if s < cap else -0.01 * int(s),
            bool(s < cap),
            bool(s >= cap),
            1 + i // 3,
            int(rng.integers(0, 4)),
        )
        for i, s in enumerate(steps)
    )
    if os.environ.get("STANDIN_SLEEP"):
        time.sleep(float(os.environ["STANDIN_SLEEP"]))
    if os.environ.get("STANDIN_LOG"):
        with open(os.environ["STANDIN_LOG"], "a", encoding="utf-8") as handle:
            handle.write(spec.name + "\n")
    return RunResult(
        spec.strategy.name,
        spec.run_index,
        spec.seed,
        rows,
        wall_time_s=0.5,
        env_steps=int(steps.sum()),
        optimal_steps=20.0,
        meta={"pid": os.getpid()},
        task=spec.task,
    )


TINY = """
[experiment]
name = "tiny"
seed = 5
runs = 2
episodes = {episodes}
baseline = "eps"
smoothing_window = 2
final_window = 2

[env]
maze = "paper"
max_episode_steps = {cap}

[agent]
alpha = 0.3
gamma = 0.99
split_min_samples = 50

[[strategy]]
name = "eps"
exploration = "epsilon-greedy"
exploration_params = {{ epsilon = 0.1 }}

[[strategy]]
name = "adaptive+tabu"
exploration = "adaptive+tabu"

[[strategy]]
name = "grid-6"
agent = "grid"
resolution = 6
exploration = "epsilon-greedy"
exploration_params = {{ epsilon = 0.1 }}
"""


def tiny_config(folder: Path, episodes: int = 4, cap: int = 120, runs: int = 2) -> Path:
    """A three-strategy experiment file small enough for a test."""
    path = folder / "tiny.toml"
    path.write_text(TINY.format(episodes=episodes, cap=cap).replace("runs = 2", f"runs = {runs}"))
    return path


TINY_SUITE = """
name = "tiny"
dev = ["open", "rooms:seed=0,rows=2,cols=2"]
test = ["rooms:seed=1000,rows=2,cols=2"]
"""

TINY_SUITE_EXPERIMENT = """
[experiment]
name = "tinysuite"
seed = 3
runs = {runs}
episodes = {episodes}
baseline = "eps"
smoothing_window = 2
final_window = 2
eval_episodes = 2

[env]
suite = "{suite}"
split = {split}
max_episode_steps = 150

[agent]
split_min_samples = 50

[[strategy]]
name = "eps"
exploration = "epsilon-greedy"
exploration_params = {{ epsilon = 0.1 }}

[[strategy]]
name = "grid-6"
agent = "grid"
resolution = 6
exploration = "epsilon-greedy"
exploration_params = {{ epsilon = 0.1 }}
"""


def tiny_suite_config(folder: Path, episodes: int = 6, runs: int = 2, split: str = '"dev"') -> Path:
    """A two-strategy experiment over a three-layout suite (two dev layouts, one test)."""
    suite = folder / "tiny_suite.toml"
    suite.write_text(TINY_SUITE)
    path = folder / "tinysuite.toml"
    path.write_text(
        TINY_SUITE_EXPERIMENT.format(episodes=episodes, runs=runs, suite=suite, split=split)
    )
    return path
