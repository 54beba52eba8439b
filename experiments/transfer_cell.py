"""One cell of a transfer (:mod:`experiments.transfer`): an agent in one condition, and the task
that evaluates it in a worker. Kept apart from the planning and storage of the transfer, so that
the code fingerprint of a cell's numbers covers only the code that computes them (this module,
with ``agent``, ``bullet_maze`` and the harness's evaluation path)."""

from __future__ import annotations

import hashlib
import re
import time
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from experiments import factory, fingerprint, store
from experiments.backends import RunFailed
from experiments.config import EnvSpec
from experiments.evaluation import evaluate

_UNSAFE = re.compile(r"[^A-Za-z0-9_.+-]+")


def safe_name(text: str) -> str:
    """``text`` with every run of characters a file name should not hold replaced by ``_``."""
    return _UNSAFE.sub("_", text)[:150] or "agent"


@dataclass(frozen=True)
class TransferAgent:
    """A saved agent with what it was trained in."""

    key: str
    """File-name safe and unique: names its folder of cells."""
    path: Path
    sha256: str
    env: EnvSpec
    """Its training environment."""
    seed: int
    """The run seed it was trained with."""
    group: str
    """Its training recipe, the unit the report aggregates over (strategy, robot, mode,
    perturbations)."""
    layout: str
    """The layout's fingerprint (:func:`experiments.fingerprint.layout_fingerprint`)."""
    observation_dims: int
    n_actions: int


def robot_label(robot: str) -> str:
    """The name a robot goes by in cell names and the report: its file stem (``husky`` for the
    shipped robot, ``r2d2`` for ``.../r2d2.urdf``), made safe for a file name."""
    return safe_name(Path(robot).stem)


@dataclass(frozen=True)
class Condition:
    """One evaluation condition of an agent."""

    robot: str
    mode: str
    level: str

    @property
    def name(self) -> str:
        """``<robot>__<mode>__<level>`` (the robot's file stem for a path)."""
        return f"{robot_label(self.robot)}__{self.mode}__{self.level}"


@dataclass(frozen=True)
class Cell:
    """One agent in one condition: the task a worker computes."""

    agent: TransferAgent
    condition: Condition
    env: EnvSpec
    episodes: int
    seed: int

    @property
    def name(self) -> str:
        """``<agent>/<robot>__<mode>__<level>``."""
        return f"{self.agent.key}/{self.condition.name}"


@dataclass(frozen=True)
class CellResult:
    """What a worker returns for one cell."""

    name: str
    rows: tuple[store.EvalRow, ...]
    optimal_steps: float
    wall_time_s: float
    env_steps: int
    projected: bool
    inputs: dict[str, Any] = field(default_factory=dict)
    tipped: int = 0
    """Episodes whose robot had tipped over by their end (``info["tipped"]``)."""


def cell_seed(run_seed: int, condition: Condition, layout: str) -> int:
    """The seed of a cell's first reset: a child of the agent's run seed keyed by the
    condition (``SeedSequence`` spawn key ``(3, ...)``; children 0-2 are the run's training
    seeds), the same whatever else is evaluated."""
    text = f"{condition.robot}|{condition.mode}|{condition.level}|{layout}"
    words = np.frombuffer(hashlib.sha256(text.encode("utf-8")).digest()[:8], dtype=np.uint32)
    sequence = np.random.SeedSequence(run_seed, spawn_key=(3, *(int(w) for w in words)))
    return int(sequence.generate_state(1, dtype=np.uint32)[0])


def cell_inputs(cell: Cell, env_prints: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """Every input of a cell, fingerprinted."""
    settings = {
        "episodes": cell.episodes,
        "seed": cell.seed,
        "run_seed": cell.agent.seed,
        "condition": asdict(cell.condition),
        "env": asdict(cell.env),
    }
    return {
        "task": fingerprint.task_name(evaluate_cell),
        "agent": cell.agent.sha256,
        "config": fingerprint.normalized(settings),
        **(env_prints if env_prints is not None else fingerprint.env_inputs(cell.env)),
        "code": fingerprint.code_fingerprint(evaluate_cell),
    }


def evaluate_cell(cell: Cell) -> CellResult:
    """The task of one cell (picklable, for the backends): the agent loaded, its greedy
    episodes in the condition's environment, and the inputs this worker actually used; any
    error it raises comes back as :class:`experiments.backends.RunFailed` naming the cell."""
    try:
        return _evaluate_cell(cell)
    except Exception as error:
        raise RunFailed.of(f"cell {cell.name}", error) from error


def _evaluate_cell(cell: Cell) -> CellResult:
    raw = cell.agent.path.read_bytes()
    agent = factory.load_agent(cell.agent.path)
    env = factory.make_env(cell.env)
    try:
        used = fingerprint.env_inputs(cell.env, layout=getattr(env.unwrapped, "layout", None))
        inputs = cell_inputs(cell, used)
        inputs["agent"] = hashlib.sha256(raw).hexdigest()
        played = factory.fitted_to(env, agent.observation_space.shape[0])
        projected = played is not env
        optimal = factory.optimal_steps(env)
        start = time.perf_counter()
        result = evaluate(played, agent, cell.episodes, seed=cell.seed)
        wall = time.perf_counter() - start
    finally:
        env.close()
    rows = tuple(
        (i + 1, e.steps, e.episode_return, e.success, e.truncated, e.collisions)
        for i, e in enumerate(result.episodes)
    )
    return CellResult(
        cell.name,
        rows,
        optimal,
        wall,
        int(sum(e.steps for e in result.episodes)),
        projected,
        inputs,
        result.tipped,
    )
