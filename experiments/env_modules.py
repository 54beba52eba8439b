"""A user's own environments for the harness: modules that register Gymnasium ids on import.

An experiment file never imports code (``experiments.config``: an id, never ``module:Id``).
A user who wants the harness to run their own env names the module that registers it on the
command line, ``run.py --env-module my_envs``: that is their explicit choice to run their code,
as ``python -c "import my_envs"`` would be.

- :func:`import_env_modules` imports each module in this process and returns the ids it
  registered, which the command then accepts as it accepts ``--allow-env`` ids. A name that is
  not a dotted module name, a module that fails to import, and one that registers no new id
  are each a :class:`ModuleError` naming the option and the module.
- :func:`call_with_modules` is what a backend runs in its workers instead of the task itself:
  it imports the same modules first (a ``spawn``ed process or a Ray worker starts with none of
  the driver's registrations), then runs the task. A module already imported costs nothing.

The module must be importable by the workers too: on ``sys.path`` through ``PYTHONPATH`` or an
installed package (spawned workers inherit the driver's environment; a Ray cluster's nodes need
it installed).
"""

from __future__ import annotations

import importlib
import re
from collections.abc import Callable, Sequence
from typing import TypeVar

from gymnasium.envs.registration import registry

T = TypeVar("T")
R = TypeVar("R")

MODULE_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)*")
"""A dotted module name (no path, no file name, no relative import)."""

MAX_MODULES = 64
"""The most ``--env-module`` options one command takes."""


class ModuleError(ValueError):
    """An ``--env-module`` that cannot give the harness an environment."""


def import_env_modules(names: Sequence[str], where: str = "--env-module") -> frozenset[str]:
    """Import each module of ``names`` (in order) and return every Gymnasium id they registered.

    Each must be a dotted module name that imports without error and registers at least one
    id that was not registered before it (a module that was imported already registers
    nothing new; name it once, first). Raises :class:`ModuleError` naming ``where`` and the
    module otherwise."""
    if len(names) > MAX_MODULES:
        raise ModuleError(f"{where}: at most {MAX_MODULES} modules, got {len(names)}")
    added: set[str] = set()
    for name in names:
        if not isinstance(name, str) or MODULE_NAME.fullmatch(name) is None:
            raise ModuleError(
                f"{where} {name!r}: not a module name (dotted Python identifiers, such as "
                "my_envs or my_package.envs; not a file path)"
            )
        before = set(registry)
        try:
            importlib.import_module(name)
        except Exception as error:  # the user's module: any failure is theirs to read
            raise ModuleError(
                f"{where} {name}: importing it failed: {type(error).__name__}: {error}"
            ) from error
        new = set(registry) - before
        if not new:
            raise ModuleError(
                f"{where} {name}: importing it registered no new Gymnasium id (the module "
                "must call gymnasium.register(...) when it is imported, and be named before "
                "anything else imports it)"
            )
        added |= new
    return frozenset(added)


def call_with_modules(modules: tuple[str, ...], fn: Callable[[T], R], task: T) -> R:
    """Import ``modules`` (registering their ids in this worker), then return ``fn(task)``."""
    for name in modules:
        importlib.import_module(name)
    return fn(task)
