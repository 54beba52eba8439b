"""Layout suites: named sets of layouts with a development split and a held-out test split.

Choose methods and parameters on ``dev`` only, and report on both. A suite is a TOML file in
``assets/suites/`` (or any path)::

    name = "mazes"
    description = "..."
    dev = ["paper", "corridors", "rooms:seed=0", "maze:seed=0,rows=8", ...]
    test = ["rooms:seed=1000", "maze:seed=1000,rows=8", ...]

Each entry is a layout spec, anything ``load_layout`` takes as a string: a shipped name, a
generator spec or a path (relative paths are read from the suite file's folder). Loading checks
every layout (``load_layout`` validates it), that no layout appears twice, and that the test
split's generated layouts use seeds that no development layout of the same family uses::

    suite = bullet_maze.load_suite("mazes")
    for spec in suite.dev:                      # strings, for gym.make(..., maze=spec)
        layout = bullet_maze.load_layout(spec)  # or suite.layouts("dev")
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from assets import SUITE_DIR
from bullet_maze.generators import is_generator_spec
from bullet_maze.layout import load_layout, read_toml
from bullet_maze.layout_types import MazeLayout

SPLITS = ("dev", "test")
"""The splits of a suite: ``dev`` to develop on, ``test`` held out."""

MAX_SUITE_LAYOUTS = 1000
"""Most layouts in one split."""

_KEYS = {"name", "description", *SPLITS}


@dataclass(frozen=True)
class LayoutSuite:
    """A checked suite: its layout specs per split (strings ``load_layout`` and
    ``gym.make("BulletMaze-v0", maze=...)`` accept)."""

    name: str
    description: str
    dev: tuple[str, ...]
    test: tuple[str, ...]
    source: str = field(default="<suite>", compare=False)

    def split(self, split: str) -> tuple[str, ...]:
        """The specs of ``split`` (``"dev"`` or ``"test"``)."""
        if split not in SPLITS:
            raise ValueError(f"unknown split {split!r} of suite {self.name!r}: choose dev or test")
        return self.dev if split == "dev" else self.test

    def layouts(self, split: str) -> list[MazeLayout]:
        """The layouts of ``split``, loaded (and checked) in order."""
        return [load_layout(spec) for spec in self.split(split)]


def available_suites() -> list[str]:
    """Names of the suites shipped in ``assets/suites/``."""
    return sorted(p.stem for p in SUITE_DIR.glob("*.toml"))


def load_suite(name_or_path: str | Path) -> LayoutSuite:
    """A suite by name (``"mazes"``) or from a TOML file, every layout of it checked."""
    if isinstance(name_or_path, str) and not name_or_path.endswith(".toml"):
        if "/" in name_or_path or "\\" in name_or_path or not name_or_path:
            raise ValueError(f"a suite name has no path separator, got {name_or_path!r}")
        path = SUITE_DIR / f"{name_or_path}.toml"
        if not path.is_file():
            raise ValueError(
                f"unknown suite {name_or_path!r}: choose one of {available_suites()} or give a "
                "path to a .toml file"
            )
    elif isinstance(name_or_path, str | Path):
        path = Path(name_or_path)
    else:
        raise TypeError(f"suite must be a name or a path, got {type(name_or_path).__name__}")
    data = read_toml(path, what="suite")
    source = str(path)
    for key in data:
        if key not in _KEYS:
            raise ValueError(
                f"{source}: unknown field {key!r} (allowed: {', '.join(sorted(_KEYS))})"
            )
    name = data.get("name", path.stem)
    description = data.get("description", "")
    for key, value in (("name", name), ("description", description)):
        if not isinstance(value, str):
            raise ValueError(f"{source}: field {key!r} must be a string, got {value!r}")
    splits = {split: _specs(data, split, source, path.parent) for split in SPLITS}
    _check_layouts(splits, source)
    return LayoutSuite(name, description, splits["dev"], splits["test"], source)


def _specs(data: dict[str, Any], split: str, source: str, folder: Path) -> tuple[str, ...]:
    if split not in data:
        raise ValueError(f"{source}: missing field {split!r} (an array of layout specs)")
    items = data[split]
    if not isinstance(items, list) or not items:
        raise ValueError(f"{source}: field {split!r} must be a non-empty array of layout specs")
    if len(items) > MAX_SUITE_LAYOUTS:
        raise ValueError(
            f"{source}: field {split!r} has {len(items):,} layouts, more than the "
            f"{MAX_SUITE_LAYOUTS:,} allowed"
        )
    specs = []
    for i, item in enumerate(items):
        if not isinstance(item, str) or not item.strip():
            raise ValueError(
                f"{source}: {split}[{i}] must be a layout spec (a string), got {item!r}"
            )
        if item.endswith(".toml") and not Path(item).is_absolute():
            item = str(folder / item)
        specs.append(item)
    return tuple(specs)


def _check_layouts(splits: dict[str, tuple[str, ...]], source: str) -> None:
    """Every layout loads; none appears twice; the test split's generated layouts use seeds that
    the development split's layouts of the same family do not."""
    seen: dict[MazeLayout, str] = {}
    seeds: dict[str, dict[str, set[int]]] = {split: {} for split in SPLITS}
    for split, specs in splits.items():
        for i, spec in enumerate(specs):
            where = f"{split}[{i}] = {spec!r}"
            try:
                layout = load_layout(spec)
            except (ValueError, FileNotFoundError) as err:
                raise ValueError(f"{source}: {where}: {err}") from None
            if layout in seen:
                raise ValueError(f"{source}: {where} is the same layout as {seen[layout]}")
            seen[layout] = where
            if is_generator_spec(spec):
                family, seed = _family_and_seed(layout.name)
                seeds[split].setdefault(family, set()).add(seed)
    for family, test_seeds in seeds["test"].items():
        shared = test_seeds & seeds["dev"].get(family, set())
        if shared:
            raise ValueError(
                f"{source}: the test split's {family} layouts reuse the development split's "
                f"seed(s) {sorted(shared)}: held-out layouts must come from other seeds"
            )


def _family_and_seed(name: str) -> tuple[str, int]:
    """The family and seed of a generated layout's canonical name (``"rooms:seed=3,..."``)."""
    family, _, rest = name.partition(":")
    seed = int(rest.split(",")[0].removeprefix("seed="))
    return family, seed
