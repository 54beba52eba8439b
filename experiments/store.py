"""Result files: one CSV per finished run, written atomically, and resume.

A run ``<strategy>__<seed>`` is finished when ``runs/<strategy>__<seed>.csv`` exists. Files are
written to a temporary name in the same folder and moved into place with ``os.replace``, so a
killed experiment leaves either the whole file or none. The CSV holds only what the seed
determines (bit for bit the same whatever the backend or the number of workers); timings and
memory go to a JSON sidecar written just before it.
"""

from __future__ import annotations

import csv
import io
import json
import os
import tempfile
from collections.abc import Iterable, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

COLUMNS = ("episode", "steps", "return", "success", "truncated", "leaves", "collisions")
"""Columns of a run's CSV, one row per episode."""

EpisodeRow = tuple[int, int, float, bool, bool, int, int]
"""One episode: number (from 1), steps, return, reached the goal, hit the cap, leaves, hits."""


@dataclass(frozen=True)
class RunResult:
    """What one finished run returns to the runner."""

    strategy: str
    run_index: int
    seed: int
    rows: tuple[EpisodeRow, ...]
    wall_time_s: float = 0.0
    env_steps: int = 0
    optimal_steps: float = float("nan")
    meta: dict[str, Any] = field(default_factory=dict)

    @property
    def name(self) -> str:
        """The run's name, ``<strategy>__<seed>``."""
        return run_name(self.strategy, self.seed)

    @property
    def steps_per_second(self) -> float:
        """Environment steps (env + agent) per second of wall time."""
        return self.env_steps / self.wall_time_s if self.wall_time_s > 0 else float("nan")


@dataclass(frozen=True)
class RunData:
    """A run read back from disk, as arrays indexed by episode."""

    name: str
    columns: dict[str, np.ndarray]
    meta: dict[str, Any]

    @property
    def steps(self) -> np.ndarray:
        """Steps of each episode."""
        return self.columns["steps"]


def run_name(strategy: str, seed: int) -> str:
    """``<strategy>__<seed>``, the CleanRL habit of naming a run by what and which seed."""
    return f"{strategy}__{seed}"


def atomic_write_text(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` so that readers see the old file or the whole new one."""
    path.parent.mkdir(parents=True, exist_ok=True)
    descriptor, temporary = tempfile.mkstemp(
        dir=path.parent, prefix=f".{path.name}.", suffix=".tmp"
    )
    try:
        with os.fdopen(descriptor, "w", encoding="utf-8", newline="") as handle:
            handle.write(text)
            handle.flush()
            os.fsync(handle.fileno())
        os.chmod(temporary, 0o644)  # mkstemp makes it private; results are for everyone
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def format_rows(rows: Iterable[Sequence[Any]], columns: Sequence[str] = COLUMNS) -> str:
    """CSV text with a fixed number format: integers as such, floats by ``repr`` (exact)."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(columns)
    for row in rows:
        writer.writerow([_format(value) for value in row])
    return buffer.getvalue()


def _format(value: Any) -> str:
    if isinstance(value, bool | np.bool_):
        return "1" if value else "0"
    if isinstance(value, int | np.integer):
        return str(int(value))
    if isinstance(value, float | np.floating):
        return repr(float(value))
    return str(value)


def run_paths(run_dir: Path, name: str) -> tuple[Path, Path]:
    """The CSV and the JSON sidecar of run ``name``."""
    return run_dir / f"{name}.csv", run_dir / f"{name}.json"


def write_run(run_dir: Path, result: RunResult) -> Path:
    """Store a finished run (sidecar first, CSV last: the CSV marks it finished)."""
    csv_path, meta_path = run_paths(run_dir, result.name)
    meta = {key: value for key, value in asdict(result).items() if key != "rows"}
    meta["episodes"] = len(result.rows)
    meta["steps_per_second"] = result.steps_per_second
    atomic_write_text(meta_path, json.dumps(meta, indent=2, sort_keys=True) + "\n")
    atomic_write_text(csv_path, format_rows(result.rows))
    return csv_path


def is_finished(run_dir: Path, name: str) -> bool:
    """Whether run ``name`` has its CSV (written last and atomically)."""
    return run_paths(run_dir, name)[0].is_file()


def read_run(run_dir: Path, name: str) -> RunData:
    """Read a finished run back as column arrays plus its sidecar metadata."""
    csv_path, meta_path = run_paths(run_dir, name)
    with csv_path.open(newline="", encoding="utf-8") as handle:
        reader = csv.reader(handle)
        header = next(reader)
        if tuple(header) != COLUMNS:
            raise ValueError(f"{csv_path}: columns {header} differ from {list(COLUMNS)}")
        values = list(reader)
    table = np.array(values, dtype=float).reshape(len(values), len(COLUMNS))
    columns = {}
    for index, column in enumerate(COLUMNS):
        data = table[:, index]
        columns[column] = data if column == "return" else data.astype(np.int64)
    meta = json.loads(meta_path.read_text(encoding="utf-8")) if meta_path.is_file() else {}
    return RunData(name=name, columns=columns, meta=meta)


def remove_stale_temporaries(run_dir: Path) -> int:
    """Delete temporary files left by a killed writer; returns how many there were."""
    stale = list(run_dir.glob(".*.tmp")) if run_dir.is_dir() else []
    for path in stale:
        path.unlink(missing_ok=True)
    return len(stale)
