"""Agents from untrusted plain data: agent files and agent settings, verified before use.

Two kinds of plain data become agent objects, and both are checked here before anything is
built from them:

* **Settings** (:func:`config_from_data`, :func:`exploration_from_data`): ``TreeConfig`` fields
  and exploration parameters given as TOML or JSON values (experiment files, ``--param``
  options, an agent file's metadata). Types are strict, read from the classes' own annotations
  (a bool is not a number, a string is not a bool), floats finite, integers and sizes bounded
  (:data:`SIZE_LIMITS`); every failure is a ``ValueError`` naming where the value came from.
* **Agent files** (:func:`write_agent_file`, :func:`read_agent_file`): one ``.npz`` (a zip of
  ``.npy`` arrays) whose ``metadata`` entry is a JSON document (agent kind, config, spaces,
  exploration strategy with its learned state, the generator's state). Never pickle: members
  are read with ``allow_pickle=False``, and only after the zip directory has been checked: every
  entry known, every declared size within :data:`MAX_FILE_BYTES`, every array header's dtype and
  shape what the metadata implies. Then the content: finite values, index ranges, a tree whose
  child ids exceed their parent's (so it has no cycle) and whose boxes nest. Every failure is a
  ``ValueError`` naming the file and the defect.

A *policy-only* file (:data:`LEARNING_ARRAYS` left out) holds what acting needs: the partition,
Q-bar, counts, the strategy and the generator (and, with ``TreeConfig.greedy_min_epochs`` or
``TreeConfig.greedy_tie_ancestors``, the model's stored-epoch counts, entry ``support``; with
``TreeConfig.greedy_tie_errors`` the standard errors, ``errors``; with
``TreeConfig.greedy_smoothing_links`` the linked leaf pairs, ``links``). Loaded, it acts exactly
like the full file; it continues learning with empty error buffers, so only the full file
resumes training exactly.

This module imports no agent class: the learner (``SMDPAgent.save`` / ``load``) gathers and
restores its own state and calls these functions for the checked reading and writing.
"""

from __future__ import annotations

import json
import math
import zipfile
import zlib
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, fields
from os import PathLike
from pathlib import Path
from tokenize import TokenError
from typing import Any, TypeVar

import numpy as np
from gymnasium import spaces

from agent.config import TreeConfig
from agent.exploration import Exploration, Tabu, make_exploration
from agent.spaces import MAX_OBSERVATION_DIMS, UNBOUNDED_MAGNITUDE
from agent.uniform_grid import MAX_GRID_CELLS
from agent.value_checks import check_value, type_hints

_T = TypeVar("_T")

FORMAT = "bullet_maze.agent"
VERSION = 2
"""Version 2 stores the metadata as UTF-8 bytes (version 1, still read, as UTF-32 text)."""
READ_VERSIONS = (1, 2)

MAX_FILE_BYTES = 1 << 30
"""Largest agent file, and largest total of its members' declared (uncompressed) sizes: 1 GiB.
A tree of 4,096 leaves (the default cap) with full error buffers takes about 50 MB."""

MAX_METADATA_BYTES = 64 << 20
"""Largest ``metadata`` entry (its JSON text as stored)."""

OBSERVATION_DTYPES = (
    *("float32", "float64", "int8", "int16", "int32", "int64"),
    *("uint8", "uint16", "uint32", "uint64"),
)
"""The observation box dtypes a file may name (an integer one: inputs are cells,
:mod:`agent.spaces`)."""
MAX_ACTIONS = 4096
"""Most actions an agent file may declare."""

SIZE_LIMITS: dict[str, int] = {
    "split_min_samples": 1_000_000,
    "max_leaves": 1_000_000,
    "max_epoch_steps": 10_000_000,
}
"""Settings that size memory: one error buffer holds ``split_min_samples`` pairs (24 bytes
each in 2-D), the tree at most ``max_leaves`` leaves, an epoch at most ``max_epoch_steps``."""

TREE_ARRAYS = ("dim", "threshold", "left", "parent", "low", "high", "depth")
"""Arrays of a tree partition that acting needs (``PartitionTree.to_arrays``)."""

LEARNING_ARRAYS = (
    "buffer_leaf",
    "buffer_inputs",
    "buffer_errors",
    "buffer_counters",
    "seen_low",
    "seen_high",
)
"""Arrays of a tree partition that only continued learning needs: its leaves' error buffers and
the range each unbounded dimension has shown (``PartitionTree.seen_bounds``)."""

OPTIONAL_ARRAYS = ("seen_low", "seen_high")
"""Tree arrays that files written before unbounded dimensions were grown do not have."""

_METADATA_KEYS = {
    "format",
    "version",
    "kind",
    "config",
    "observation_space",
    "n_actions",
    "bounds",
    "seed",
    "episodes_done",
    "exploration",
    "rng",
    "partition",
}
_OPTIONAL_METADATA_KEYS = {"policy_only", "learner", "tie_trial"}
"""``learner``: the learner's own state beyond the paper (the measured reward unit of
``TreeConfig.threshold_units="scale"``, the model of ``planning="sweep"``), when it has any.
``tie_trial``: the returns of ``TreeConfig.greedy_tie_trial`` (policy-only files too)."""


# --- settings -----------------------------------------------------------------------------


def config_from_data(data: Any, where: str) -> TreeConfig:
    """A ``TreeConfig`` from plain data, strictly: only its fields, each of its annotated type,
    finite and within :data:`SIZE_LIMITS`; ``where`` names the source in every error."""
    if not isinstance(data, Mapping):
        raise ValueError(f"{where}: expected a table of TreeConfig fields, got {data!r}")
    hints = type_hints(TreeConfig)
    known = [f.name for f in fields(TreeConfig)]
    for key, value in data.items():
        if key not in known:
            raise ValueError(
                f"{where}: {key!r} is not a field of TreeConfig; known fields: "
                f"{', '.join(sorted(known))}"
            )
        check_value(value, hints[key], f"{where} {key}")
        _check_size(key, value, f"{where} {key}")
    try:
        return TreeConfig(**data)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{where}: {error}") from None


def exploration_from_data(name: Any, params: Any, where: str) -> Exploration:
    """``make_exploration(name, **params)`` after checking each parameter strictly against the
    annotation of the class that takes it; ``where`` names the source in every error."""
    if not isinstance(name, str):
        raise ValueError(f"{where}: the strategy name must be a string, got {name!r}")
    if not isinstance(params, Mapping):
        raise ValueError(f"{where}: expected a table of parameters, got {params!r}")
    try:
        classes = _strategy_classes(make_exploration(name))
    except (TypeError, ValueError) as error:
        raise ValueError(f"{where}: {error}") from None
    for key, value in params.items():
        hint = _parameter_hint(classes, key)
        if hint is not None:
            check_value(value, hint, f"{where} {key}")
    try:
        return make_exploration(name, **params)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{where}: {error}") from None


def _strategy_classes(strategy: Exploration) -> list[type]:
    classes: list[type] = [type(strategy)]
    if isinstance(strategy, Tabu):
        classes.append(type(strategy.base))
    return classes


def _parameter_hint(classes: list[type], key: str) -> Any:
    for cls in classes:
        hints = type_hints(cls.__init__)  # type: ignore[misc]
        if key in hints:
            return hints[key]
    return None  # unknown keys are refused by make_exploration itself


def _check_size(key: str, value: Any, where: str) -> None:
    limit = SIZE_LIMITS.get(key)
    if limit is not None and isinstance(value, int) and value > limit:
        raise ValueError(f"{where}: at most {limit:,}, got {value:,}")


def check_grid_resolution(resolution: Any, dims: int, where: str) -> list[int]:
    """Cells per dimension: a positive integer or ``dims`` of them, at most
    :data:`MAX_GRID_CELLS` cells in all."""
    items = [resolution] * dims if not isinstance(resolution, list | tuple) else list(resolution)
    if not items or any(
        isinstance(r, bool) or not isinstance(r, int) or r < 1 or r > MAX_GRID_CELLS for r in items
    ):
        raise ValueError(f"{where}: expected positive integers, got {resolution!r}")
    if len(items) != dims:
        raise ValueError(f"{where}: expected {dims} cell counts, got {resolution!r}")
    cells = math.prod(items)
    if cells > MAX_GRID_CELLS:
        raise ValueError(f"{where}: {cells:,} cells, at most {MAX_GRID_CELLS:,}")
    return items


# --- writing ------------------------------------------------------------------------------


def space_to_json(space: spaces.Space) -> dict[str, Any]:
    """A ``Box`` observation space as JSON-ready data."""
    if not isinstance(space, spaces.Box):
        raise TypeError(f"only a Box observation space is saved, got {space!r}")
    return {
        "low": np.asarray(space.low, dtype=np.float64).tolist(),
        "high": np.asarray(space.high, dtype=np.float64).tolist(),
        "dtype": str(space.dtype),
    }


def write_agent_file(
    path: str | PathLike[str], metadata: dict[str, Any], arrays: Mapping[str, Any]
) -> Path:
    """Write ``metadata`` (JSON) and ``arrays`` to one ``.npz``; returns the path written
    (``.npz`` is added if missing)."""
    path = Path(path)
    if path.suffix != ".npz":
        path = path.with_name(path.name + ".npz")
    text = json.dumps(metadata, separators=(",", ":"))
    payload = {"metadata": np.frombuffer(text.encode("utf-8"), dtype=np.uint8), **arrays}
    np.savez(path, **payload)
    return path


# --- reading ------------------------------------------------------------------------------


@dataclass(frozen=True)
class SavedAgent:
    """An agent file after every check: what the learner needs to rebuild the agent."""

    path: Path
    kind: str
    config: TreeConfig
    observation_space: spaces.Box
    action_space: spaces.Discrete
    bounds: tuple[list[float], list[float]]
    seed: int
    episodes_done: int
    exploration_name: str
    exploration_params: dict[str, Any]
    exploration_state: dict[str, Any]
    rng: dict[str, Any]
    partition: dict[str, Any]
    """The partition's metadata (``root_low``, ``root_high``; ``resolution`` for a grid)."""
    partition_arrays: dict[str, np.ndarray]
    """The partition's arrays, complete (empty error buffers for a policy-only file)."""
    q: np.ndarray
    visits: np.ndarray
    policy_only: bool
    learner: dict[str, Any] | None = None
    """The learner's state beyond the paper (``scale``, ``model``), if the file has any."""
    tie_trial: Any = None
    """``TreeConfig.greedy_tie_trial``'s moments, unchecked (the learner checks them)."""
    support: np.ndarray | None = None
    """A policy-only file's stored-epoch counts per (leaf, action), which the greedy choice of
    ``TreeConfig.greedy_min_epochs`` reads in place of the model (None otherwise)."""
    errors: np.ndarray | None = None
    """A policy-only file's standard errors per (leaf, action), which
    ``TreeConfig.greedy_tie_errors`` reads in place of the model (None otherwise)."""
    links: np.ndarray | None = None
    """A policy-only file's linked leaf pairs, one ``(a, b)`` with ``a < b`` a row, which
    ``TreeConfig.greedy_smoothing_links`` reads in place of the model (None otherwise)."""

    def fail(self, message: str) -> ValueError:
        """A ``ValueError`` naming the file."""
        return ValueError(f"{self.path}: {message}")


def resolve_agent_path(path: str | PathLike[str]) -> Path:
    """``path``, or ``path.npz`` when only that exists (``np.savez`` adds the suffix)."""
    path = Path(path)
    if not path.exists() and path.with_name(path.name + ".npz").exists():
        path = path.with_name(path.name + ".npz")
    return path


def read_agent_file(path: str | PathLike[str]) -> SavedAgent:
    """Read and verify an agent file written by :func:`write_agent_file`.

    Raises ``ValueError`` naming the file and what is wrong with it (``FileNotFoundError`` if
    there is no file); never executes or unpickles anything, and reads no member before its
    declared size and header are known to be what the metadata implies.
    """
    return read_archive(path, _read_archive)


def read_archive(
    path: str | PathLike[str],
    read: Callable[[zipfile.ZipFile, Path, Callable[[str], ValueError]], _T],
) -> _T:
    """``read(archive, path, fail)`` on the agent file at ``path`` once it is known to be a
    ``.npz`` archive of a size an agent file may have; a damaged or unreadable archive is a
    ``ValueError`` naming the file (``FileNotFoundError`` if there is none)."""
    path = resolve_agent_path(path)
    if not path.is_file():
        raise FileNotFoundError(f"agent file not found: {path}")

    def fail(message: str) -> ValueError:
        return ValueError(f"{path}: {message}")

    size = path.stat().st_size
    if size > MAX_FILE_BYTES:
        raise fail(f"{size:,} bytes, more than an agent file may hold ({MAX_FILE_BYTES:,})")
    if not zipfile.is_zipfile(path):
        raise fail("not an agent file (not a .npz archive)")
    try:
        with zipfile.ZipFile(path) as archive:
            return read(archive, path, fail)
    except (zipfile.BadZipFile, zipfile.LargeZipFile, NotImplementedError, zlib.error) as error:
        raise fail(f"damaged archive ({error})") from None
    except (OSError, EOFError, RuntimeError) as error:
        raise fail(f"cannot be read ({error})") from None


def archive_members(
    archive: zipfile.ZipFile, fail: Callable[[str], ValueError]
) -> dict[str, zipfile.ZipInfo]:
    """The archive's ``.npy`` entries by name, once each, declaring at most an agent file's
    size, one of them the ``metadata``."""
    members: dict[str, zipfile.ZipInfo] = {}
    for info in archive.infolist():
        if not info.filename.endswith(".npy") or info.filename[: -len(".npy")] in members:
            raise fail(f"unexpected entry {info.filename!r} (not an agent file)")
        members[info.filename[: -len(".npy")]] = info
    declared = sum(info.file_size for info in members.values())
    if declared > MAX_FILE_BYTES:
        raise fail(f"entries declare {declared:,} bytes, more than {MAX_FILE_BYTES:,}")
    if "metadata" not in members:
        raise fail("not an agent file (no 'metadata' entry)")
    return members


def _read_archive(
    archive: zipfile.ZipFile, path: Path, fail: Callable[[str], ValueError]
) -> SavedAgent:
    members = archive_members(archive, fail)
    meta = read_metadata(archive, members["metadata"], fail)

    kind = meta["kind"]
    dims = len(meta["observation_space"]["low"])
    n_actions = meta["n_actions"]
    config = config_from_data(meta["config"], f"{path}: metadata config")
    policy_only = meta.get("policy_only", False)
    partition_meta = meta["partition"]
    expected = _expected_entries(kind, policy_only, fail)
    if policy_only and config.greedy_reads_support:  # the greedy choice's counts
        expected.append("support")
    if policy_only and config.greedy_tie_errors is not None:  # the greedy choice's ties
        expected.append("errors")
    if policy_only and config.greedy_smoothing_links:  # the smoothing's links
        expected.append("links")
    unknown = sorted(set(members) - {"metadata", "q", "visits"} - set(expected))
    missing = sorted(
        {"q", "visits", *expected} - set(members) - {f"partition.{n}" for n in OPTIONAL_ARRAYS}
    )
    if unknown:
        raise fail(f"unknown entries {unknown} (an agent file of kind {kind!r} has no such data)")
    if missing:
        raise fail(f"missing entries {missing}")

    def read(name: str, dtype: str, ndim: int) -> np.ndarray:
        return read_array(archive, members[name], name, dtype, ndim, fail)

    if kind == "tree":
        partition_arrays = {
            entry[len("partition.") :]: read(entry, *_TREE_DTYPES[entry[len("partition.") :]])
            for entry in expected
            if entry in members and entry.startswith("partition.")
        }
        if policy_only:
            capacity = config.split_min_samples
            partition_arrays.update(_empty_buffers(dims, capacity))
        n_ids = _check_tree(partition_arrays, partition_meta, dims, config, fail)
    else:
        resolution = check_grid_resolution(
            partition_meta.get("resolution"), dims, f"{path}: metadata partition.resolution"
        )
        partition_arrays = {}
        n_ids = math.prod(resolution)
    q = read("q", "f8", 2)
    visits = read("visits", "i8", 2)
    for name, array in (("q", q), ("visits", visits)):
        if array.shape != (n_ids, n_actions):
            raise fail(f"entry {name!r} has shape {array.shape}, expected {(n_ids, n_actions)}")
    if not np.isfinite(q).all():
        raise fail("entry 'q' holds values that are not finite")
    if (visits < 0).any():
        raise fail("entry 'visits' holds negative counts")
    support = None
    if "support" in expected:
        support = read("support", "i8", 2)
        if support.shape != (n_ids, n_actions):
            raise fail(f"entry 'support' has shape {support.shape}, expected {(n_ids, n_actions)}")
        window = config.model_window
        if ((support < 0) | (support > window)).any():
            raise fail(f"entry 'support' holds counts outside [0, model_window = {window}]")
    errors = None
    if "errors" in expected:
        errors = read("errors", "f8", 2)
        if errors.shape != (n_ids, n_actions):
            raise fail(f"entry 'errors' has shape {errors.shape}, expected {(n_ids, n_actions)}")
        if np.isnan(errors).any() or (errors < 0).any():
            raise fail("entry 'errors' holds standard errors that are negative or not a number")
    links = None
    if "links" in expected:
        links = read("links", "i8", 2)
        if links.shape[1:] != (2,):
            raise fail(f"entry 'links' has shape {links.shape}, expected (pairs, 2)")
        if ((links < 0) | (links >= n_ids)).any() or (links[:, 0] >= links[:, 1]).any():
            raise fail(f"entry 'links' holds pairs that are not leaf ids a < b below {n_ids}")

    observation_space = saved_box(meta)
    exploration = meta["exploration"]
    return SavedAgent(
        path=path,
        kind=kind,
        config=config,
        observation_space=observation_space,
        action_space=spaces.Discrete(n_actions),
        bounds=(list(meta["bounds"][0]), list(meta["bounds"][1])),
        seed=meta["seed"],
        episodes_done=meta["episodes_done"],
        exploration_name=exploration["name"],
        exploration_params=exploration["params"],
        exploration_state=exploration["state"],
        rng=meta["rng"],
        partition=partition_meta,
        partition_arrays=partition_arrays,
        q=q,
        visits=visits,
        policy_only=policy_only,
        learner=meta.get("learner"),
        tie_trial=meta.get("tie_trial"),
        support=support,
        errors=errors,
        links=links,
    )


_TREE_DTYPES: dict[str, tuple[str, int]] = {
    "dim": ("i8", 1),
    "threshold": ("f8", 1),
    "left": ("i8", 1),
    "parent": ("i8", 1),
    "low": ("f8", 2),
    "high": ("f8", 2),
    "depth": ("i8", 1),
    "buffer_leaf": ("i8", 1),
    "buffer_inputs": ("f8", 2),
    "buffer_errors": ("f8", 2),
    "buffer_counters": ("f8", 2),
    "seen_low": ("f8", 1),
    "seen_high": ("f8", 1),
}


def _expected_entries(kind: str, policy_only: bool, fail: Callable[[str], ValueError]) -> list[str]:
    if kind == "tree":
        names = TREE_ARRAYS if policy_only else TREE_ARRAYS + LEARNING_ARRAYS
        return [f"partition.{name}" for name in names]
    if kind == "grid":
        return []
    raise fail(f"unknown agent kind {kind!r} (known: grid, tree)")


def _empty_buffers(dims: int, capacity: int) -> dict[str, np.ndarray]:
    return {
        "buffer_leaf": np.zeros(0, dtype=np.int64),
        "buffer_inputs": np.zeros((0, capacity * dims), dtype=np.float64),
        "buffer_errors": np.zeros((0, capacity), dtype=np.float64),
        "buffer_counters": np.zeros((0, 4), dtype=np.float64),
    }


def _read_header(
    archive: zipfile.ZipFile, info: zipfile.ZipInfo, name: str, fail: Callable[[str], ValueError]
) -> tuple[tuple[int, ...], np.dtype[Any], int]:
    """The ``.npy`` header of a member: shape, dtype and the header's length in bytes."""
    with archive.open(info) as handle:
        try:
            version = np.lib.format.read_magic(handle)
            if version == (1, 0):
                shape, fortran, dtype = np.lib.format.read_array_header_1_0(handle)
            elif version == (2, 0):
                shape, fortran, dtype = np.lib.format.read_array_header_2_0(handle)
            else:
                raise ValueError(f"unsupported .npy version {version}")
        except (ValueError, SyntaxError, EOFError, TokenError) as error:  # a damaged header
            raise fail(f"entry {name!r} is not a NumPy array ({error})") from None
        header = handle.tell()
    if fortran:
        raise fail(f"entry {name!r} is stored in Fortran order (not written by this code)")
    return tuple(shape), dtype, header


def read_array(
    archive: zipfile.ZipFile,
    info: zipfile.ZipInfo,
    name: str,
    dtype: str,
    ndim: int,
    fail: Callable[[str], ValueError],
) -> np.ndarray:
    """A member's array after its header says: dtype ``dtype`` (little-endian), ``ndim``
    dimensions and exactly as many bytes as the member declares."""
    shape, found, header = _read_header(archive, info, name, fail)
    wanted = np.dtype(f"<{dtype}")
    if found != wanted or found.hasobject:
        raise fail(f"entry {name!r} has dtype {found}, expected {wanted}")
    if len(shape) != ndim:
        raise fail(f"entry {name!r} has {len(shape)} dimensions, expected {ndim}")
    nbytes = math.prod(shape) * found.itemsize
    if header + nbytes != info.file_size:
        raise fail(f"entry {name!r} declares shape {shape} but holds {info.file_size} bytes")
    with archive.open(info) as handle:
        try:
            return np.lib.format.read_array(handle, allow_pickle=False)
        except (ValueError, EOFError, OSError) as error:
            raise fail(f"entry {name!r} cannot be read ({error})") from None


def read_metadata(
    archive: zipfile.ZipFile,
    info: zipfile.ZipInfo,
    fail: Callable[[str], ValueError],
    check: Callable[[Any, Callable[[str], ValueError]], None] | None = None,
) -> dict[str, Any]:
    """The archive's JSON metadata, checked by ``check`` (default: a tree or grid agent's)."""
    if info.file_size > MAX_METADATA_BYTES:
        raise fail(
            f"entry 'metadata' holds {info.file_size:,} bytes, at most {MAX_METADATA_BYTES:,}"
        )
    shape, dtype, header = _read_header(archive, info, "metadata", fail)
    if dtype == np.dtype(np.uint8) and len(shape) == 1:  # version 2: UTF-8 bytes
        size = shape[0]
    elif dtype.kind == "U" and shape == ():  # version 1: UTF-32 text
        size = dtype.itemsize
    else:
        raise fail("entry 'metadata' is not a JSON text")
    if header + size != info.file_size:
        raise fail("entry 'metadata' declares a size it does not hold")
    with archive.open(info) as handle:
        stored = np.lib.format.read_array(handle, allow_pickle=False)
    try:
        text = stored.tobytes().decode("utf-8") if stored.dtype == np.uint8 else str(stored)
    except UnicodeDecodeError as error:
        raise fail(f"entry 'metadata' is not UTF-8 text ({error})") from None
    try:
        meta = json.loads(text, parse_constant=_json_constant)
    except (ValueError, RecursionError) as error:
        raise fail(f"entry 'metadata' is not valid JSON ({error})") from None
    (_check_metadata if check is None else check)(meta, fail)
    return meta


def _json_constant(name: str) -> float:
    if name == "NaN":
        raise ValueError("NaN is not allowed")
    return math.inf if name == "Infinity" else -math.inf


def check_spaces(
    meta: dict[str, Any], need: Callable[[bool, str], None]
) -> tuple[list[float], list[float]]:
    """The metadata's ``observation_space`` (a Box of 1 to 64 dimensions, a known dtype) and
    ``n_actions``; returns the box's lows and highs."""
    box = meta["observation_space"]
    need(isinstance(box, dict) and set(box) == {"low", "high", "dtype"}, "observation_space: bad")
    low, high = box["low"], box["high"]
    need(
        _numbers(low, allow_infinite=True) and _numbers(high, allow_infinite=True),
        "observation_space low/high are not lists of numbers",
    )
    dims = len(low)
    need(
        1 <= dims <= MAX_OBSERVATION_DIMS and len(high) == dims,
        f"observation_space has {dims} lows and {len(high)} highs "
        f"(1 to {MAX_OBSERVATION_DIMS} dimensions)",
    )
    need(all(a <= b for a, b in zip(low, high, strict=True)), "observation_space has low > high")
    need(box["dtype"] in OBSERVATION_DTYPES, f"observation_space dtype {box['dtype']!r}")
    need(
        box["dtype"] in ("float32", "float64")
        or all(math.isfinite(v) and float(v).is_integer() for v in (*low, *high)),
        f"observation_space of dtype {box['dtype']} has bounds that are not integers",
    )
    need(
        _integer(meta["n_actions"]) and 1 <= meta["n_actions"] <= MAX_ACTIONS,
        f"n_actions must be an integer in [1, {MAX_ACTIONS}], got {meta['n_actions']!r}",
    )
    return low, high


def saved_box(meta: dict[str, Any]) -> spaces.Box:
    """The observation space of metadata that :func:`check_spaces` passed."""
    box = meta["observation_space"]
    dtype = np.dtype(box["dtype"])
    return spaces.Box(
        low=np.asarray(box["low"], dtype=dtype),
        high=np.asarray(box["high"], dtype=dtype),
        dtype=dtype,
    )


def check_rng(rng: Any, need: Callable[[bool, str], None]) -> None:
    """A :class:`agent.random_stream.UniformStream` state's structure (its bit generator's
    state is checked by NumPy when it is set)."""
    need(
        isinstance(rng, dict) and set(rng) == {"bit_generator", "pending", "block"},
        "rng must hold bit_generator, pending and block",
    )
    need(isinstance(rng["bit_generator"], dict), "rng bit_generator is not an object")
    need(_integer(rng["block"]) and 1 <= rng["block"] <= 1_000_000, "rng block out of range")
    need(
        _numbers(rng["pending"])
        and len(rng["pending"]) <= rng["block"]
        and all(0.0 <= v < 1.0 for v in rng["pending"]),
        "rng pending draws are not uniform draws in [0, 1)",
    )


def _check_metadata(meta: Any, fail: Callable[[str], ValueError]) -> None:
    """The metadata document's structure and types (the values' meaning is checked later)."""
    if not isinstance(meta, dict):
        raise fail("metadata is not a JSON object")
    version = meta.get("version")
    if meta.get("format") != FORMAT or not _integer(version) or version not in READ_VERSIONS:
        raise fail(
            f"format {meta.get('format')!r} version {version!r}, expected {FORMAT!r} "
            f"version {' or '.join(map(str, READ_VERSIONS))}"
        )
    unknown = sorted(set(meta) - _METADATA_KEYS - _OPTIONAL_METADATA_KEYS)
    missing = sorted(_METADATA_KEYS - set(meta))
    if unknown:
        raise fail(f"metadata has unknown keys {unknown}")
    if missing:
        raise fail(f"metadata lacks keys {missing}")

    def need(condition: bool, what: str) -> None:
        if not condition:
            raise fail(f"metadata {what}")

    need(isinstance(meta["kind"], str), "kind is not a string")
    need(isinstance(meta.get("policy_only", False), bool), "policy_only is not true or false")
    low, high = check_spaces(meta, need)
    dims = len(low)
    bounds = meta["bounds"]
    need(
        isinstance(bounds, list)
        and len(bounds) == 2
        and all(_numbers(b, allow_infinite=True) and len(b) == dims for b in bounds),
        f"bounds must be two lists of {dims} numbers",
    )
    need(
        all(
            (math.isfinite(b) or (b == -math.inf and lo <= -UNBOUNDED_MAGNITUDE))
            for b, lo in zip(bounds[0], low, strict=True)
        )
        and all(
            (math.isfinite(b) or (b == math.inf and hi >= UNBOUNDED_MAGNITUDE))
            for b, hi in zip(bounds[1], high, strict=True)
        ),
        "bounds are infinite where the observation space is bounded",
    )
    need(all(a < b for a, b in zip(bounds[0], bounds[1], strict=True)), "bounds have low >= high")
    need(_integer(meta["seed"]) and meta["seed"] >= 0, f"seed {meta['seed']!r} is not >= 0")
    need(
        _integer(meta["episodes_done"]) and meta["episodes_done"] >= 0,
        f"episodes_done {meta['episodes_done']!r} is not >= 0",
    )
    exploration = meta["exploration"]
    need(
        isinstance(exploration, dict)
        and set(exploration) == {"name", "params", "state"}
        and isinstance(exploration["params"], dict)
        and isinstance(exploration["state"], dict),
        "exploration must hold name, params and state",
    )
    need(_finite_everywhere(exploration), "exploration holds a value that is not finite")
    check_rng(meta["rng"], need)
    partition = meta["partition"]
    need(isinstance(partition, dict), "partition is not an object")
    need(
        _numbers(partition.get("root_low"), allow_infinite=True)
        and _numbers(partition.get("root_high"), allow_infinite=True),
        "partition root_low/root_high are not lists of numbers",
    )
    need(
        partition["root_low"] == bounds[0] and partition["root_high"] == bounds[1],
        "partition root box differs from the bounds",
    )
    need(set(partition) <= {"root_low", "root_high", "resolution"}, "partition has unknown keys")
    learner = meta.get("learner")
    if learner is not None:
        need(
            isinstance(learner, dict)
            and set(learner) <= {"scale", "model", "gate", "loop", "optimism"},
            "learner must be an object with scale, model, gate, loop and/or optimism",
        )
        need(
            all(isinstance(v, dict) for v in learner.values()),
            "learner scale/model/gate/loop/optimism are not objects",
        )
        need(_finite_everywhere(learner), "learner holds a value that is not finite")


def _integer(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def _numbers(value: Any, allow_infinite: bool = False) -> bool:
    return isinstance(value, list) and all(
        isinstance(v, int | float)
        and not isinstance(v, bool)
        and (math.isfinite(v) or (allow_infinite and not math.isnan(v)))
        for v in value
    )


def _finite_everywhere(value: Any) -> bool:
    if isinstance(value, float):
        return math.isfinite(value)
    if isinstance(value, dict):
        return all(_finite_everywhere(v) for v in value.values())
    if isinstance(value, list):
        return all(_finite_everywhere(v) for v in value)
    return True


def _check_tree(
    arrays: dict[str, np.ndarray],
    meta: dict[str, Any],
    dims: int,
    config: TreeConfig,
    fail: Callable[[str], ValueError],
) -> int:
    """A tree partition's arrays describe a tree (returns its number of node ids).

    Node ids are never reused and a split appends its two children, so every child id exceeds
    its parent's: checked, this makes every walk from the root end at a leaf (no cycle).
    """
    dim, left, parent, depth = (arrays[k] for k in ("dim", "left", "parent", "depth"))
    threshold, low, high = arrays["threshold"], arrays["low"], arrays["high"]
    n = dim.shape[0]
    leaves = int((dim == -1).sum())
    if n < 1 or n != 2 * leaves - 1:
        raise fail(f"tree of {n} nodes and {leaves} leaves (a binary tree has 2 * leaves - 1)")
    if leaves > config.max_leaves:
        raise fail(f"tree has {leaves} leaves, more than its max_leaves {config.max_leaves}")
    for name in ("threshold", "left", "parent", "depth"):
        if arrays[name].shape != (n,):
            raise fail(f"tree entry {name!r} has shape {arrays[name].shape}, expected {(n,)}")
    for name, array in (("low", low), ("high", high)):
        if array.shape != (n, dims):
            raise fail(f"tree entry {name!r} has shape {array.shape}, expected {(n, dims)}")
    if not np.isfinite(threshold).all():
        raise fail("tree entry 'threshold' holds values that are not finite")
    # A box is infinite only along a dimension the root leaves unbounded (grown from the data).
    root_low = np.asarray(meta["root_low"], dtype=np.float64)
    root_high = np.asarray(meta["root_high"], dtype=np.float64)
    for name, array, edge in (("low", low, -np.inf), ("high", high, np.inf)):
        infinite = ~np.isfinite(array)
        allowed = (array == edge) & ~np.isfinite(root_low if edge < 0 else root_high)
        if (infinite & ~allowed).any():
            raise fail(f"tree entry {name!r} holds values that are not finite")
    for name in OPTIONAL_ARRAYS:
        if name in arrays:
            seen = arrays[name]
            if seen.shape != (dims,) or np.isnan(seen).any():
                raise fail(f"tree entry {name!r} must be {dims} numbers, got shape {seen.shape}")
    if ((dim < -1) | (dim >= dims)).any():
        raise fail(f"tree entry 'dim' holds a dimension outside -1..{dims - 1}")
    internal = np.flatnonzero(dim >= 0)
    if (left[dim == -1] != -1).any():
        raise fail("tree entry 'left' gives a child to a leaf")
    if ((left[internal] <= internal) | (left[internal] + 1 >= n)).any():
        raise fail("tree entry 'left' holds a child id that is not after its parent (a cycle)")
    children = np.concatenate([left[internal], left[internal] + 1])
    if np.unique(children).size != children.size or children.size != n - 1:
        raise fail("tree entry 'left' gives a node two parents")
    if parent[0] != -1 or depth[0] != 0:
        raise fail("tree root has a parent or a depth")
    expected_parent = np.full(n, -1)
    expected_parent[left[internal]] = internal
    expected_parent[left[internal] + 1] = internal
    if (parent != expected_parent).any():
        raise fail("tree entry 'parent' contradicts 'left'")
    if (depth[1:] != depth[parent[1:]] + 1).any():
        raise fail("tree entry 'depth' contradicts 'parent'")
    if low[0].tolist() != list(meta["root_low"]) or high[0].tolist() != list(meta["root_high"]):
        raise fail("tree root box differs from the partition's root_low/root_high")
    if not (low < high).all():
        raise fail("tree entry 'low'/'high' holds an empty box")
    d = dim[internal]
    t = threshold[internal]
    if not ((low[internal, d] < t) & (t < high[internal, d])).all():
        raise fail("tree split threshold outside its node's box")
    first, second = left[internal], left[internal] + 1
    left_high = high[internal].copy()
    left_high[np.arange(internal.size), d] = t
    right_low = low[internal].copy()
    right_low[np.arange(internal.size), d] = t
    if not (
        (low[first] == low[internal]).all()
        and (high[first] == left_high).all()
        and (low[second] == right_low).all()
        and (high[second] == high[internal]).all()
    ):
        raise fail("tree children's boxes do not split their parent's")
    _check_buffers(arrays, dim, dims, config, fail)
    return n


def _check_buffers(
    arrays: dict[str, np.ndarray],
    dim: np.ndarray,
    dims: int,
    config: TreeConfig,
    fail: Callable[[str], ValueError],
) -> None:
    leaf, inputs = arrays["buffer_leaf"], arrays["buffer_inputs"]
    errors, counters = arrays["buffer_errors"], arrays["buffer_counters"]
    m, capacity = leaf.shape[0], config.split_min_samples
    shapes = {
        "buffer_inputs": (inputs, (m, capacity * dims)),
        "buffer_errors": (errors, (m, capacity)),
        "buffer_counters": (counters, (m, 4)),
    }
    for name, (array, shape) in shapes.items():
        if array.shape != shape:
            raise fail(f"tree entry {name!r} has shape {array.shape}, expected {shape}")
        if not np.isfinite(array).all():
            raise fail(f"tree entry {name!r} holds values that are not finite")
    if m and ((leaf < 0).any() or (leaf >= dim.shape[0]).any() or np.unique(leaf).size != m):
        raise fail("tree entry 'buffer_leaf' holds a node id out of range or twice")
    if m and (dim[leaf] != -1).any():
        raise fail("tree entry 'buffer_leaf' names a node that is not a leaf")
    count, head = counters[:, 0], counters[:, 1]
    whole = (count == np.round(count)) & (head == np.round(head))
    if not (whole & (count >= 0) & (count <= capacity) & (head >= 0) & (head < capacity)).all():
        raise fail(f"tree entry 'buffer_counters' holds a count or head outside 0..{capacity}")


def check_exploration_state(strategy: Exploration, leaves: Sequence[int], where: str) -> None:
    """After ``load_state_dict``: every leaf's epsilon is a probability."""
    for leaf in leaves:
        value = strategy.epsilon(leaf)
        if isinstance(value, bool) or not (isinstance(value, int | float) and 0.0 <= value <= 1.0):
            raise ValueError(f"{where}: exploration state gives leaf {leaf} epsilon {value!r}")
