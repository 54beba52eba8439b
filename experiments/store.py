"""Result files: one CSV per finished run and a sidecar that vouches for it, both atomic.

A run ``<strategy>__<seed>`` is two files in ``runs/``: its CSV (one row per episode, only
what the seed determines, bit for bit the same whatever the backend or the number of workers)
and its JSON sidecar, written after the CSV. The sidecar records the CSV's SHA-256 and size,
the number of episodes, the fingerprint of every input (:mod:`experiments.fingerprint`), the
run's timings, and a hash of all that, so that a damaged sidecar is found too. A run counts
as finished only when :func:`check_run` verifies it: the sidecar parses, matches its own hash
and names the run, the CSV has the recorded size and hash, and its rows are well formed
(numbered 1..n, integer counts, finite returns, each count in its range, exactly the expected
number of episodes). Files are written to a temporary name in the same folder and moved into
place with ``os.replace``, so a killed writer leaves each file whole or absent.
"""

from __future__ import annotations

import csv
import hashlib
import io
import json
import os
import signal
import tempfile
import threading
import warnings
from collections.abc import Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np

from experiments import fingerprint

COLUMNS = ("episode", "steps", "return", "success", "truncated", "leaves", "collisions")
"""Columns of a run's CSV, one row per episode."""

EpisodeRow = tuple[int, int, float, bool, bool, int, int]
"""One episode: number (from 1), steps, return, reached the goal, hit the cap, leaves, hits."""

EVAL_COLUMNS = ("episode", "steps", "return", "success", "truncated", "collisions")
"""Columns of a run's greedy evaluation CSV (``<run>.eval.csv``), one row per episode."""

EvalRow = tuple[int, int, float, bool, bool, int]
"""One greedy episode after training: number (from 1), steps, return, goal, cap, hits."""

SIDECAR_FORMAT = "bullet_maze.run"
SIDECAR_VERSION = 2
"""Version 2 added the data hash and the input fingerprints (version 1 sidecars do not
verify: their runs are recomputed)."""

MAX_ROW_BYTES = 128
"""Longest CSV row a run may hold (a row is about 45 bytes)."""
MAX_SIDECAR_BYTES = 1 << 20
"""Largest sidecar."""


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
    inputs: dict[str, Any] = field(default_factory=dict)
    """Fingerprints of what the run actually used (:func:`experiments.fingerprint.run_inputs`),
    filled in by the worker; empty when a task does not say (the runner then records the
    inputs it expected)."""
    task: str | None = None
    """The task the run belongs to (None in an experiment with one environment)."""
    evaluation: tuple[EvalRow, ...] = ()
    """Greedy episodes after training (empty: no evaluation)."""
    agent_file: bytes = b""
    """The trained agent's policy file (``.npz`` bytes; empty: not saved)."""

    @property
    def name(self) -> str:
        """The run's name, ``<strategy>__<seed>`` or ``<task>/<strategy>__<seed>``."""
        return run_name(self.strategy, self.seed, self.task)

    @property
    def steps_per_second(self) -> float:
        """Environment steps (env + agent) per second of wall time."""
        return self.env_steps / self.wall_time_s if self.wall_time_s > 0 else float("nan")


@dataclass(frozen=True)
class RunData:
    """A run read back from disk and verified, as arrays indexed by episode."""

    name: str
    columns: dict[str, np.ndarray]
    meta: dict[str, Any]
    """The sidecar (timings, ``optimal_steps``, ``inputs``, ...)."""
    evaluation: dict[str, np.ndarray] | None = None
    """The greedy evaluation's columns (:data:`EVAL_COLUMNS`), when the run has one."""

    @property
    def steps(self) -> np.ndarray:
        """Steps of each episode."""
        return self.columns["steps"]


Status = Literal["missing", "valid", "invalid", "changed", "code"]


@dataclass(frozen=True)
class RunCheck:
    """What :func:`check_run` found for one run."""

    name: str
    status: Status
    """``missing`` (no files: not computed yet), ``valid``, ``invalid`` (damaged, cut, edited
    or unverifiable: recompute it), ``changed`` (verified, but computed from other inputs) or
    ``code`` (verified, and only the code version differs)."""
    reason: str = ""
    differences: tuple[str, ...] = ()
    data: RunData | None = None

    @property
    def usable(self) -> bool:
        """Verified and computed from the expected inputs."""
        return self.status == "valid"


def run_name(strategy: str, seed: int, task: str | None = None) -> str:
    """``<strategy>__<seed>``, the CleanRL habit of naming a run by what and which seed; a
    task's runs are in its folder, ``<task>/<strategy>__<seed>``."""
    return f"{strategy}__{seed}" if task is None else f"{task}/{strategy}__{seed}"


@contextmanager
def deferred_interrupt() -> Iterator[None]:
    """Hold a Ctrl-C (SIGINT) until the block ends, then deliver it.

    A run's files are written one after the other; an interrupt between the CSV and its
    sidecar would leave a CSV that nothing vouches for (recomputed on resume, but a finished
    run lost). Outside the main thread, where Python delivers no signals, it does nothing."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    received: list[tuple[int, Any]] = []
    previous = signal.signal(signal.SIGINT, lambda number, frame: received.append((number, frame)))
    restore = signal.SIG_DFL if previous is None else previous  # None: set outside Python
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, restore)
    if not received:
        return
    if callable(restore):
        restore(*received[0])
    elif restore == signal.SIG_DFL:
        os.kill(os.getpid(), signal.SIGINT)


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


def atomic_write_bytes(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` so that readers see the old file or the whole new one."""
    path.parent.mkdir(parents=True, exist_ok=True)
    descriptor, temporary = tempfile.mkstemp(
        dir=path.parent, prefix=f".{path.name}.", suffix=".tmp"
    )
    try:
        with os.fdopen(descriptor, "wb") as handle:
            handle.write(data)
            handle.flush()
            os.fsync(handle.fileno())
        os.chmod(temporary, 0o644)
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


def eval_path(run_dir: Path, name: str) -> Path:
    """The greedy evaluation CSV of run ``name``."""
    return run_dir / f"{name}.eval.csv"


def agent_path(run_dir: Path, name: str) -> Path:
    """The saved agent (policy) of run ``name`` (``[experiment] save_agents``)."""
    return run_dir / f"{name}.agent.npz"


def verified_agent(run_dir: Path, name: str, meta: Mapping[str, Any]) -> Path:
    """The saved agent of a verified run, checked against its sidecar's size and SHA-256
    (``ValueError`` naming the file otherwise)."""
    path = agent_path(run_dir, name)
    for key, kind in (("agent_bytes", int), ("agent_sha256", str)):
        value = meta.get(key)
        if isinstance(value, bool) or not isinstance(value, kind):
            raise ValueError(f"{run_dir / name}.json: records no saved agent ({key} is {value!r})")
    if not path.is_file():
        raise ValueError(f"{path}: missing (its sidecar records it)")
    size = path.stat().st_size
    if size != meta["agent_bytes"]:
        raise ValueError(f"{path}: differs from its sidecar ({size} bytes; edited, cut or damaged)")
    if hashlib.sha256(path.read_bytes()).hexdigest() != meta["agent_sha256"]:
        raise ValueError(f"{path}: differs from its sidecar (SHA-256 mismatch; edited or damaged)")
    return path


def write_run(run_dir: Path, result: RunResult, inputs: Mapping[str, Any] | None = None) -> Path:
    """Store a finished run: its CSV, then the sidecar that vouches for it (the sidecar marks
    it finished). ``inputs`` are its fingerprints (default: those the result carries)."""
    csv_path, meta_path = run_paths(run_dir, result.name)
    text = format_rows(result.rows)
    data = text.encode("utf-8")
    meta = {
        key: value
        for key, value in asdict(result).items()
        if key not in ("rows", "inputs", "evaluation", "task", "agent_file")
    }
    evaluation = format_rows(result.evaluation, EVAL_COLUMNS) if result.evaluation else None
    if result.task is not None:
        meta["task"] = result.task
    if evaluation is not None:
        meta.update(
            evaluation_episodes=len(result.evaluation),
            evaluation_sha256=hashlib.sha256(evaluation.encode("utf-8")).hexdigest(),
            evaluation_bytes=len(evaluation.encode("utf-8")),
        )
    if result.agent_file:
        meta.update(
            agent_sha256=hashlib.sha256(result.agent_file).hexdigest(),
            agent_bytes=len(result.agent_file),
        )
    meta.update(
        format=SIDECAR_FORMAT,
        version=SIDECAR_VERSION,
        name=result.name,
        episodes=len(result.rows),
        steps_per_second=result.steps_per_second,
        data_sha256=hashlib.sha256(data).hexdigest(),
        data_bytes=len(data),
        inputs=dict(inputs if inputs is not None else result.inputs),
    )
    meta["sidecar_sha256"] = fingerprint.digest(meta)  # of everything else in it
    with deferred_interrupt():  # all of the run's files, or a Ctrl-C after them
        if evaluation is not None:
            atomic_write_text(eval_path(run_dir, result.name), evaluation)
        if result.agent_file:
            atomic_write_bytes(agent_path(run_dir, result.name), result.agent_file)
        atomic_write_text(csv_path, text)
        atomic_write_text(meta_path, json.dumps(meta, indent=2, sort_keys=True) + "\n")
    return csv_path


def remove_run(run_dir: Path, name: str) -> None:
    """Delete a run's files (to recompute it)."""
    for path in (*run_paths(run_dir, name), eval_path(run_dir, name), agent_path(run_dir, name)):
        path.unlink(missing_ok=True)


def check_run(
    run_dir: Path,
    name: str,
    episodes: int,
    cap: int,
    expected_inputs: Mapping[str, Any] | None = None,
    eval_episodes: int = 0,
    saved_agent: bool = False,
) -> RunCheck:
    """Verify run ``name`` against its sidecar, its expected ``episodes`` and episode ``cap``,
    its greedy evaluation of ``eval_episodes`` episodes (if any), its saved agent (if
    ``saved_agent``), and (if given) the inputs it should have been computed from."""
    csv_path, meta_path = run_paths(run_dir, name)
    if not csv_path.exists() and not meta_path.exists():
        return RunCheck(name, "missing")
    try:
        data = _read_verified(run_dir, name, episodes, cap, eval_episodes)
        if saved_agent:
            verified_agent(run_dir, name, data.meta)
    except ValueError as error:
        return RunCheck(name, "invalid", str(error))
    if expected_inputs is None:
        return RunCheck(name, "valid", data=data)
    recorded = data.meta.get("inputs")
    if not isinstance(recorded, dict):
        return RunCheck(name, "invalid", f"{meta_path}: no input fingerprints")
    found = fingerprint.differences(recorded, expected_inputs)
    if not found:
        return RunCheck(name, "valid", data=data)
    status: Status = "code" if fingerprint.only_code_differs(found) else "changed"
    labels = sorted({fingerprint.INPUT_LABELS[item.split(".")[0]] for item in found})
    return RunCheck(
        name, status, "computed with another version of " + ", ".join(labels), tuple(found), data
    )


def read_run(
    run_dir: Path,
    name: str,
    episodes: int | None = None,
    cap: int | None = None,
    eval_episodes: int = 0,
) -> RunData:
    """Read a finished run back as column arrays plus its sidecar, verified (``ValueError``
    naming the file and the defect otherwise)."""
    return _read_verified(run_dir, name, episodes, cap, eval_episodes)


def _read_verified(
    run_dir: Path, name: str, episodes: int | None, cap: int | None, eval_episodes: int = 0
) -> RunData:
    csv_path, meta_path = run_paths(run_dir, name)
    meta = _read_sidecar(meta_path, name)
    recorded = meta["episodes"]
    if episodes is not None and recorded != episodes:
        raise ValueError(f"{meta_path}: {recorded} episodes, the experiment has {episodes}")
    if not csv_path.is_file():
        raise ValueError(f"{csv_path}: missing (its sidecar exists)")
    size = csv_path.stat().st_size
    if size != meta["data_bytes"] or size > MAX_ROW_BYTES * (recorded + 1):
        raise ValueError(
            f"{csv_path}: differs from its sidecar ({size} bytes, recorded {meta['data_bytes']}; "
            "edited, cut or damaged)"
        )
    raw = csv_path.read_bytes()
    if hashlib.sha256(raw).hexdigest() != meta["data_sha256"]:
        raise ValueError(
            f"{csv_path}: differs from its sidecar (SHA-256 mismatch; edited or damaged)"
        )
    columns = parse_rows(raw, str(csv_path), cap)
    if len(columns["steps"]) != recorded:
        raise ValueError(f"{csv_path}: {len(columns['steps'])} rows, its sidecar says {recorded}")
    evaluation = (
        _read_evaluation(run_dir, name, meta, eval_episodes, cap) if eval_episodes else None
    )
    return RunData(name=name, columns=columns, meta=meta, evaluation=evaluation)


def _read_evaluation(
    run_dir: Path, name: str, meta: Mapping[str, Any], episodes: int, cap: int | None
) -> dict[str, np.ndarray]:
    """The greedy evaluation CSV of a run, against its sidecar's size, hash and count."""
    path = eval_path(run_dir, name)
    recorded = meta.get("evaluation_episodes")
    if recorded != episodes:
        raise ValueError(
            f"{path}: the sidecar records {recorded!r} greedy episodes, the experiment has "
            f"{episodes}"
        )
    for key, kind in (("evaluation_bytes", int), ("evaluation_sha256", str)):
        value = meta.get(key)
        if isinstance(value, bool) or not isinstance(value, kind):
            raise ValueError(f"{run_dir / name}.json: {key} is {value!r}")
    if not path.is_file():
        raise ValueError(f"{path}: missing (its sidecar records it)")
    size = path.stat().st_size
    if size != meta["evaluation_bytes"] or size > MAX_ROW_BYTES * (episodes + 1):
        raise ValueError(f"{path}: differs from its sidecar ({size} bytes; edited, cut or damaged)")
    raw = path.read_bytes()
    if hashlib.sha256(raw).hexdigest() != meta["evaluation_sha256"]:
        raise ValueError(f"{path}: differs from its sidecar (SHA-256 mismatch; edited or damaged)")
    columns = parse_rows(raw, str(path), cap, EVAL_COLUMNS)
    if len(columns["steps"]) != episodes:
        raise ValueError(f"{path}: {len(columns['steps'])} rows, its sidecar says {episodes}")
    return columns


def _read_sidecar(path: Path, name: str) -> dict[str, Any]:
    if not path.is_file():
        raise ValueError(f"{path}: missing (a run is finished only with its sidecar)")
    if path.stat().st_size > MAX_SIDECAR_BYTES:
        raise ValueError(f"{path}: larger than {MAX_SIDECAR_BYTES:,} bytes")
    try:
        meta = json.loads(path.read_bytes().decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError) as error:
        raise ValueError(f"{path}: not valid JSON ({error})") from None
    if not isinstance(meta, dict):
        raise ValueError(f"{path}: not a JSON object")
    if meta.get("format") != SIDECAR_FORMAT or meta.get("version") != SIDECAR_VERSION:
        raise ValueError(
            f"{path}: not a version {SIDECAR_VERSION} run sidecar (no data hash to verify)"
        )
    recorded = meta.pop("sidecar_sha256", None)
    if recorded != fingerprint.digest(meta):
        raise ValueError(f"{path}: differs from its own recorded hash (edited or damaged)")
    if meta.get("name") != name:
        raise ValueError(f"{path}: names run {meta.get('name')!r}, not {name!r}")
    for key, kind in (("episodes", int), ("data_bytes", int), ("data_sha256", str)):
        value = meta.get(key)
        if isinstance(value, bool) or not isinstance(value, kind):
            raise ValueError(f"{path}: {key} is {value!r}")
    if meta["episodes"] < 1:
        raise ValueError(f"{path}: episodes is {meta['episodes']}")
    return meta


def parse_rows(
    raw: bytes, where: str, cap: int | None = None, expected: Sequence[str] = COLUMNS
) -> dict[str, np.ndarray]:
    """A run CSV's columns (``expected``: :data:`COLUMNS` or :data:`EVAL_COLUMNS`), after
    checking every row (``ValueError`` naming ``where``)."""
    columns_count = len(expected)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        raise ValueError(f"{where}: not UTF-8 text") from None
    header, _, body = text.partition("\n")
    if header != ",".join(expected):
        raise ValueError(f"{where}: header {header[:200]!r} differs from {','.join(expected)!r}")
    if not body or not body.endswith("\n"):
        raise ValueError(f"{where}: no rows, or the last row is cut")
    lines = body[:-1].split("\n")
    if any(line.count(",") != columns_count - 1 for line in lines):
        bad = next(i for i, line in enumerate(lines) if line.count(",") != columns_count - 1)
        raise ValueError(f"{where}: row {bad + 1} does not have {columns_count} fields")
    try:
        with warnings.catch_warnings():  # numpy warns or raises at the first non-number
            warnings.simplefilter("ignore", DeprecationWarning)
            values = np.fromstring(body.replace("\n", ","), dtype=np.float64, sep=",")
    except ValueError:
        values = np.zeros(0)
    if values.size != len(lines) * columns_count:
        raise ValueError(f"{where}: a field is not a number")
    table = values.reshape(len(lines), columns_count)
    if not np.isfinite(table).all():
        row = int(np.flatnonzero(~np.isfinite(table).all(axis=1))[0])
        raise ValueError(f"{where}: row {row + 1} holds a value that is not finite")
    columns: dict[str, np.ndarray] = {}
    for index, column in enumerate(expected):
        values = table[:, index]
        if column == "return":
            columns[column] = values
            continue
        if (values != np.round(values)).any() or (np.abs(values) > 2**53).any():
            raise ValueError(f"{where}: column {column!r} holds a value that is not an integer")
        columns[column] = values.astype(np.int64)
    _check_ranges(columns, where, cap)
    return columns


def _check_ranges(columns: dict[str, np.ndarray], where: str, cap: int | None) -> None:
    n = len(columns["episode"])
    steps = columns["steps"]
    problems = [
        ((columns["episode"] != np.arange(1, n + 1)), "episodes are not numbered 1, 2, ..."),
        (steps < 1, "steps below 1"),
        (~np.isin(columns["success"], (0, 1)), "success is not 0 or 1"),
        (~np.isin(columns["truncated"], (0, 1)), "truncated is not 0 or 1"),
        (
            (columns["success"] + columns["truncated"]) > 1,
            "an episode both succeeded and hit the cap",
        ),
        (columns.get("leaves", steps) < 1, "leaves below 1"),
        (
            (columns["collisions"] < 0) | (columns["collisions"] > steps),
            "collisions outside 0..steps",
        ),
    ]
    if cap is not None:
        problems += [
            (steps > cap, f"steps above the cap {cap}"),
            ((columns["truncated"] == 1) & (steps != cap), f"truncated before the cap {cap}"),
        ]
    for bad, message in problems:
        if bad.any():
            raise ValueError(f"{where}: row {int(np.flatnonzero(bad)[0]) + 1}: {message}")


def remove_stale_temporaries(run_dir: Path, nested: bool = False) -> int:
    """Delete temporary files left by a killed writer (``nested``: in the task folders below
    ``run_dir`` too); returns how many there were. Call it only while holding the folder's
    lock (:mod:`experiments.lock`): a live writer's temporaries look the same."""
    if not run_dir.is_dir():
        return 0
    stale = [*run_dir.glob(".*.tmp"), *(run_dir.glob("*/.*.tmp") if nested else ())]
    for path in stale:
        path.unlink(missing_ok=True)
    return len(stale)
