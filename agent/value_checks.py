"""Strict checks of settings against the annotations of the code that takes them.

One rule for every setting of the agents, whichever door it comes in by: ``TreeConfig``'s fields
and the exploration strategies' parameters given in Python (``TreeConfig(alpha=...)``,
``EpsilonGreedy(epsilon=...)``) and the same values read from experiment files, ``--param``
options or agent files (:mod:`agent.serialization`). The type comes from the annotation (a bool
is not a number, a string is not a bool), floats must be finite, integers and strings bounded.
A failure is a :class:`SettingError` naming where the value came from and what was expected.
"""

from __future__ import annotations

import math
import types
import typing
from collections.abc import Mapping, Sequence
from typing import Any, Literal, Union, get_args, get_origin, get_type_hints

import numpy as np

MAX_INT = 2**31 - 1
"""Largest integer a setting may hold unless a reader says less."""

MAX_TEXT = 1000
"""Longest string a setting may hold."""


class SettingError(TypeError, ValueError):
    """A setting of the wrong type or not finite. It is both a ``TypeError`` (what Python code
    passing a wrong type expects) and a ``ValueError`` (what the file readers report)."""


def check_value(value: Any, hint: Any, where: str, python: bool = False) -> None:
    """Raise :class:`SettingError` unless ``value`` is of type ``hint`` (strictly), finite and
    bounded. The message spells values as files do (``true``, ``none``), or as Python does
    (``True``, ``None``) with ``python``.

    ``hint`` is an annotation: ``float`` (an int or float, not a bool, finite), ``int`` (not a
    bool, within :data:`MAX_INT`), ``bool``, ``str``, ``Literal[...]``, ``X | None``, lists and
    tuples of those. An annotation it does not know only gets the finiteness check.
    """
    problem = type_problem(value, hint, python)
    if problem is not None:
        shown = str(value).lower() if isinstance(value, bool) and not python else repr(value)
        raise SettingError(f"{where}: expected {problem}, got {shown}")
    check_finite(value, where)


def check_arguments(target: Any, where: str, values: Mapping[str, Any]) -> None:
    """:func:`check_value` (spelt as Python) of each of ``values`` against ``target``'s
    annotation of the same name (a function's parameters or a class's fields); ``where`` names
    the owner (``"epsilon-greedy"`` gives ``"epsilon-greedy epsilon: expected a number, got
    None"``)."""
    known = type_hints(target)
    for name, value in values.items():
        hint = known.get(name)
        if hint is not None:
            check_value(value, hint, f"{where} {name}", python=True)


def check_seed(seed: Any) -> int:
    """An agent's seed as an int: a Python or numpy integer (not a bool), at least 0, as numpy's
    generators take it; a :class:`SettingError` naming the seed otherwise."""
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer):
        raise SettingError(f"seed must be an int, got {seed!r}")
    if seed < 0:
        raise SettingError(f"seed must be an int >= 0, got {int(seed)}")
    return int(seed)


def plain_scalar(value: Any) -> Any:
    """A numpy integer or floating scalar as the Python ``int`` or ``float`` of the same value
    (so a setting computed with numpy is taken, and saves as JSON); anything else unchanged."""
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.floating):
        return float(value)
    return value


def type_problem(value: Any, hint: Any, python: bool = False) -> str | None:
    """None if ``value`` fits ``hint``, else what was expected (:func:`describe`)."""
    origin = get_origin(hint)
    if hint is Any:
        return None
    if origin in (Union, types.UnionType):
        options = get_args(hint)
        if any(type_problem(value, option, python) is None for option in options):
            return None
        return " or ".join(describe(option, python) for option in options)
    if origin is Literal:
        choices = get_args(hint)
        ok = any(type(value) is type(choice) and value == choice for choice in choices)
        return None if ok else describe(hint, python)
    if hint is type(None):
        return None if value is None else describe(hint, python)
    if hint is bool:
        return None if isinstance(value, bool) else describe(hint, python)
    if hint is int:
        ok = isinstance(value, int) and not isinstance(value, bool) and abs(value) <= MAX_INT
        return None if ok else describe(hint, python)
    if hint is float:
        ok = isinstance(value, int | float) and not isinstance(value, bool)
        return None if ok else describe(hint, python)
    if hint is str:
        return None if isinstance(value, str) and len(value) <= MAX_TEXT else describe(hint, python)
    if origin in (list, tuple, Sequence, typing.Sequence) or hint in (list, tuple):
        if not isinstance(value, list | tuple) or isinstance(value, str):
            return describe(hint, python)
        args = [a for a in get_args(hint) if a is not Ellipsis]
        if args and any(type_problem(item, args[0], python) is not None for item in value):
            return describe(hint, python)
        return None
    return None


def describe(hint: Any, python: bool = False) -> str:
    """What an annotation asks for, in words (``True``/``None`` as Python spells them with
    ``python``, else ``true``/``none`` as the files do)."""
    origin = get_origin(hint)
    if origin is Literal:
        return "one of " + ", ".join(repr(c) for c in get_args(hint))
    if origin in (Union, types.UnionType):
        return " or ".join(describe(option, python) for option in get_args(hint))
    names = {
        bool: "True or False" if python else "true or false",
        int: f"an integer (at most {MAX_INT} in size)",
        float: "a number",
        str: f"a string (at most {MAX_TEXT} characters)",
        type(None): "None" if python else "nothing (none)",
    }
    if hint in names:
        return names[hint]
    if origin in (list, tuple, Sequence, typing.Sequence):
        args = [a for a in get_args(hint) if a is not Ellipsis]
        return f"a list of {describe(args[0], python)}" if args else "a list"
    return getattr(hint, "__name__", str(hint))


def check_finite(value: Any, where: str) -> None:
    """Raise :class:`SettingError` if ``value`` is, or holds, a float that is not finite."""
    if isinstance(value, float) and not math.isfinite(value):
        raise SettingError(f"{where}: must be finite, got {value!r}")
    if isinstance(value, list | tuple):
        for item in value:
            check_finite(item, where)
    if isinstance(value, Mapping):
        for item in value.values():
            check_finite(item, where)


_HINTS: dict[Any, dict[str, Any]] = {}


def type_hints(target: Any) -> dict[str, Any]:
    """A class's or function's resolved annotations ({} if they cannot be resolved), read once
    per target."""
    hints = _HINTS.get(target)
    if hints is None:
        try:
            hints = get_type_hints(target)
        except (NameError, TypeError):
            hints = {}
        _HINTS[target] = hints
    return hints
