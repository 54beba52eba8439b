"""Agent files of the fixed baselines (:class:`agent.TileCodingAgent`,
:class:`agent.AdaptiveQAgent`): ``save`` and ``load`` as the tree agents have them.

The container is the tree agents' (:mod:`agent.serialization`): one ``.npz`` holding the JSON
metadata and the arrays, never a pickle, read with the same guards (the archive's size and
entries, each array's header before its bytes). The metadata holds the format and version, the
agent's kind, its spaces, its constructor arguments (``params()``), the episodes done and the
random stream; the arrays are its ``state()``. Loading builds the agent from the saved
arguments (its constructor checks them), reads exactly the arrays a fresh agent of those
arguments has, with their dtypes and dimensions, lets the agent check what they hold
(``check_state``: a tile table that numbers every used tile once, a box tree whose children
halve their parent, finite values), and only then restores it. A file that fails any check is
a ``ValueError`` naming the file and the defect.
"""

from __future__ import annotations

from os import PathLike
from pathlib import Path
from typing import Any, Protocol, Self, TypeVar, cast

import numpy as np
from gymnasium import spaces
from numpy.typing import NDArray

from agent import serialization

FORMAT = "bullet_maze.baseline"
VERSION = 1
_KEYS = {"format", "version", "kind", "observation_space", "n_actions", "params"}
_KEYS |= {"episodes_done", "rng"}


class Baseline(Protocol):
    """What a fixed baseline gives its file."""

    kind: str
    observation_space: spaces.Space[Any]
    n_actions: int

    def params(self) -> dict[str, Any]: ...

    def state(self) -> tuple[dict[str, NDArray[Any]], dict[str, Any]]: ...

    def check_state(self, arrays: dict[str, NDArray[Any]]) -> None: ...

    def restore(self, arrays: dict[str, NDArray[Any]], meta: dict[str, Any]) -> None: ...


_B = TypeVar("_B", bound=Baseline)


class BaselineFile:
    """``save`` and ``load`` for a fixed baseline's class (mixed in; the class gives what
    :class:`Baseline` names)."""

    def save(self, path: str | PathLike[str], policy_only: bool = False) -> Path:
        """Write the agent to ``path`` (``.npz``; :func:`save_baseline`); returns the path
        written. ``policy_only`` is the tree agents' argument and changes nothing here."""
        return save_baseline(cast(Baseline, self), path, policy_only)

    @classmethod
    def load(cls, path: str | PathLike[str]) -> Self:
        """An agent written by :meth:`save`, acting and learning on exactly as it would have;
        a ValueError naming the file and the defect for a file that fails a check."""
        return cast(Self, load_baseline(cast(type[Baseline], cls), path))


def save_baseline(agent: Baseline, path: str | PathLike[str], policy_only: bool) -> Path:
    """Write ``agent`` to ``path`` (``.npz`` added if missing); ``policy_only`` is accepted for
    the tree agents' interface and changes nothing (a baseline keeps nothing that only
    continued learning reads)."""
    if not isinstance(policy_only, bool):
        raise ValueError(f"save: policy_only must be True or False, got {policy_only!r}")
    arrays, meta = agent.state()
    metadata = {
        "format": FORMAT,
        "version": VERSION,
        "kind": agent.kind,
        "observation_space": serialization.space_to_json(agent.observation_space),
        "n_actions": agent.n_actions,
        **meta,
    }
    return serialization.write_agent_file(path, metadata, arrays)


def load_baseline(cls: type[_B], path: str | PathLike[str]) -> _B:
    """The agent of class ``cls`` saved at ``path`` by :func:`save_baseline`, after every check
    (module docstring)."""

    def read(archive: Any, where: Path, fail: Any) -> _B:
        members = serialization.archive_members(archive, fail)
        meta = serialization.read_metadata(archive, members["metadata"], fail, _check_meta)
        if meta["kind"] != cls.kind:
            raise fail(f"holds a {meta['kind']!r} agent, not a {cls.kind!r} one ({cls.__name__})")
        params = dict(meta["params"])
        try:
            agent = cls(  # type: ignore[call-arg]
                serialization.saved_box(meta), spaces.Discrete(meta["n_actions"]), **params
            )
        except (TypeError, ValueError) as error:
            raise fail(f"metadata params: {error}") from None
        expected, _ = agent.state()
        names = set(members) - {"metadata"}
        if names != set(expected):
            raise fail(
                f"entries {sorted(names)} differ from a {cls.kind!r} agent's {sorted(expected)}"
            )
        arrays = {
            name: serialization.read_array(
                archive,
                members[name],
                name,
                f"{array.dtype.kind}{array.dtype.itemsize}",
                array.ndim,
                fail,
            )
            for name, array in expected.items()
        }
        try:
            agent.check_state(arrays)
        except (TypeError, ValueError, KeyError) as error:
            raise fail(str(error)) from None
        try:  # (the arrays passed their checks: what fails now is the random stream's state)
            agent.restore(arrays, meta)
        except (TypeError, ValueError, KeyError) as error:
            raise fail(f"metadata rng is not a random generator's state ({error})") from None
        return agent

    return serialization.read_archive(path, read)


def baseline_kind(path: str | PathLike[str]) -> str | None:
    """The kind of the baseline saved at ``path`` (``"tile"``, ``"adaptive-q"``), or None when
    the file is not a baseline's (a tree or grid agent's, which ``SMDPAgent.load`` reads and
    checks); a file that is no agent file at all is a ValueError naming it."""

    def read(archive: Any, where: Path, fail: Any) -> str | None:
        members = serialization.archive_members(archive, fail)
        meta = serialization.read_metadata(archive, members["metadata"], fail, _any_object)
        if meta.get("format") != FORMAT:
            return None
        _check_meta(meta, fail)
        return str(meta["kind"])

    return serialization.read_archive(path, read)


def _any_object(meta: Any, fail: Any) -> None:
    if not isinstance(meta, dict):
        raise fail("metadata is not a JSON object")


def _check_meta(meta: Any, fail: Any) -> None:
    """The metadata document's structure and types."""
    if not isinstance(meta, dict):
        raise fail("metadata is not a JSON object")
    if meta.get("format") != FORMAT or meta.get("version") != VERSION:
        raise fail(
            f"format {meta.get('format')!r} version {meta.get('version')!r}, expected {FORMAT!r} "
            f"version {VERSION} (a tree or grid agent's file loads with SMDPAgent.load)"
        )
    if set(meta) != _KEYS:
        raise fail(f"metadata keys {sorted(meta)}, expected {sorted(_KEYS)}")

    def need(condition: bool, what: str) -> None:
        if not condition:
            raise fail(f"metadata {what}")

    need(isinstance(meta["kind"], str), "kind is not a string")
    serialization.check_spaces(meta, need)
    need(isinstance(meta["params"], dict), "params is not an object")
    done = meta["episodes_done"]
    need(
        isinstance(done, int) and not isinstance(done, bool) and done >= 0,
        f"episodes_done {done!r} is not an integer >= 0",
    )
    serialization.check_rng(meta["rng"], need)


def finite(arrays: dict[str, NDArray[Any]], names: tuple[str, ...]) -> None:
    """A ValueError naming the first of ``names`` whose array holds a value that is not
    finite."""
    for name in names:
        if not np.isfinite(arrays[name]).all():
            raise ValueError(f"entry {name!r} holds values that are not finite")
