"""The data of a transfer (:mod:`experiments.transfer`): its spec, the conditions that do not
apply, the verdict on each stored cell and the folder's state. Shared by the job, its report
and its traces, so that none of them imports another."""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from experiments.transfer_cell import Cell, Condition, TransferAgent

TRAIN_LEVEL = "train"
"""The level of an agent's own training condition (its environment exactly as trained)."""


@dataclass(frozen=True)
class Conditions:
    """The grid: every robot x mode x level, on each agent's layout if it is in ``layouts``."""

    robots: tuple[str, ...] = ("disc",)
    modes: tuple[str, ...] = ("dynamic",)
    layouts: tuple[str, ...] | None = None
    """Layouts whose agents are evaluated (None: every agent's own)."""
    levels: tuple[str, ...] = ("none",)


@dataclass(frozen=True)
class TransferSpec:
    """What ``run.py transfer`` evaluates: agents, the grid, episodes per cell, the cap."""

    name: str
    agents: tuple[str, ...]
    """Agent files, train folders or experiment folders."""
    conditions: Conditions
    episodes: int = 10
    """Greedy episodes per agent and condition."""
    max_episode_steps: int | None = None
    """Episode cap of every cell (None: each agent's training cap)."""
    source: str = "<options>"


@dataclass(frozen=True)
class Skipped:
    """A condition that does not apply to an agent, and why."""

    agent: TransferAgent
    condition: Condition
    reason: str


@dataclass(frozen=True)
class CellCheck:
    """What :func:`check_cell` found: ``missing``, ``valid``, ``invalid`` (recompute it),
    ``changed`` (other inputs: refused) or ``code`` (only the code version differs)."""

    status: str
    reason: str = ""
    columns: dict[str, np.ndarray] | None = None
    meta: dict[str, Any] | None = None


@dataclass(frozen=True)
class TransferState:
    """The planned cells with the verdict on each, and the conditions that do not apply."""

    cells: tuple[Cell, ...]
    checks: Mapping[str, CellCheck]
    skipped: tuple[Skipped, ...]
    accept_code_change: bool = False

    def _with(self, *statuses: str) -> list[Cell]:
        return [c for c in self.cells if self.checks[c.name].status in statuses]

    @property
    def finished(self) -> list[Cell]:
        """Verified cells that count."""
        return self._with("valid", "code") if self.accept_code_change else self._with("valid")

    @property
    def pending(self) -> list[Cell]:
        """Cells to compute: missing, or not verifying."""
        return self._with("missing", "invalid")

    @property
    def refused(self) -> list[Cell]:
        """Verified cells computed from other inputs (and other code, unless accepted)."""
        return self._with("changed") if self.accept_code_change else self._with("changed", "code")


def iter_finished(state: TransferState) -> Iterator[tuple[Cell, CellCheck]]:
    """The finished cells with their verified data, in plan order."""
    for cell in state.finished:
        yield cell, state.checks[cell.name]


def steps_ratio(steps: np.ndarray, optimal: float) -> float:
    """Mean steps over the episodes (a capped episode counts its cap) / the optimum."""
    if not math.isfinite(optimal) or optimal <= 0:
        return math.nan
    return float(np.mean(steps)) / optimal
