"""Fuzzing transfer files and stored cells: every case's outcome is asserted.

Random edits of a valid transfer document (refused naming the file, or accepted with every
name checked), random damage to the shipped transfer file's bytes (refused naming the file, or
accepted), and random damage to a stored cell's files (the cell does not verify and is
recomputed; nothing raises). Seeded, so every failure repeats.
"""

from __future__ import annotations

import copy
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from experiments.config import EXPERIMENT_DIR, ConfigError, EnvSpec
from experiments.transfer import check_cell, load_spec, parse_spec, write_cell
from experiments.transfer_cell import Cell, CellResult, Condition, TransferAgent

VALID: dict[str, Any] = {
    "transfer": {"name": "fuzz", "agents": ["a", "b"], "episodes": 3, "max_episode_steps": 50},
    "conditions": {
        "robots": ["disc", "husky"],
        "modes": ["kinematic", "dynamic"],
        "layouts": ["paper", "open"],
        "levels": ["none", "moderate", "strong"],
    },
}
JUNK: list[Any] = [
    None,
    True,
    0,
    -1,
    2**70,
    1.5,
    float("nan"),
    "",
    "x" * 5000,
    "disc\x00",
    "../../etc",
    [],
    [1],
    [[]],
    ["disc", 3],
    {},
    {"low": 1},
    b"bytes",
]


def _mutate(rng: np.random.Generator, data: dict[str, Any]) -> None:
    table = data[["transfer", "conditions"][int(rng.integers(2))]]
    keys = [*list(table), "unknown", "episodes", "levels"]
    key = keys[int(rng.integers(len(keys)))]
    choice = int(rng.integers(3))
    if choice == 0:
        table.pop(key, None)
    elif choice == 1:
        table[key] = JUNK[int(rng.integers(len(JUNK)))]
    else:
        names = ["none", "moderate", "extreme", "dynamic", "disc", "rover", "paper", "nope"]
        table[key] = [names[int(i)] for i in rng.integers(len(names), size=rng.integers(0, 4))]


def _outcome(build: Any) -> tuple[Any, str | None]:
    """What ``build()`` returns, or the message of the ConfigError it raises (nothing else
    may be raised)."""
    try:
        return build(), None
    except ConfigError as error:
        return None, str(error)


@pytest.mark.parametrize("seed", range(4))
def test_random_edits_are_refused_by_name_or_accepted_checked(seed: int):
    rng = np.random.default_rng(seed)
    for _ in range(60):
        data = copy.deepcopy(VALID)
        for _ in range(int(rng.integers(1, 4))):
            _mutate(rng, data)
        spec, error = _outcome(lambda: parse_spec(data, "fuzz.toml"))  # noqa: B023
        if error is not None:
            assert error.startswith("fuzz.toml: ")
            continue
        assert spec is not None
        grid = spec.conditions
        assert set(grid.modes) <= {"kinematic", "dynamic"}
        assert set(grid.levels) <= {"none", "moderate", "strong"}
        assert spec.episodes >= 1
        assert all(isinstance(a, str) for a in spec.agents)


@pytest.mark.parametrize("seed", range(3))
def test_damaged_transfer_files_are_refused_by_name(seed: int, tmp_path: Path):
    raw = bytearray((EXPERIMENT_DIR / "transfer_study.toml").read_bytes())
    rng = np.random.default_rng(seed)
    for index in range(30):
        damaged = bytearray(raw)
        for _ in range(int(rng.integers(1, 6))):
            damaged[int(rng.integers(len(damaged)))] = int(rng.integers(256))
        path = tmp_path / f"t{index}.toml"
        path.write_bytes(bytes(damaged))
        _, error = _outcome(lambda: load_spec(path))  # noqa: B023
        assert error is None or str(path) in error


def _cell(tmp_path: Path) -> Cell:
    agent = TransferAgent("a", tmp_path / "a.npz", "0" * 64, EnvSpec(), 1, "g", "L", 2, 4)
    env = EnvSpec(maze="open", max_episode_steps=40)
    return Cell(agent, Condition("disc", "dynamic", "none"), env, 3, 7)


@pytest.mark.parametrize("seed", range(3))
def test_damaged_cells_do_not_verify(seed: int, tmp_path: Path):
    cell = _cell(tmp_path)
    inputs = {"agent": "0" * 64, "config": {"env": {"max_episode_steps": 40}}}
    rows = (
        (1, 12, -1.0, True, False, 0),
        (2, 40, -3.5, False, True, 2),
        (3, 9, 1.0, True, False, 0),
    )
    write_cell(tmp_path, CellResult(cell.name, rows, 45.0, 0.1, 61, False), inputs)
    assert check_cell(tmp_path, cell, inputs).status == "valid"
    rng = np.random.default_rng(seed)
    csv_path = tmp_path / "cells" / "a" / "disc__dynamic__none.csv"
    json_path = csv_path.with_suffix(".json")
    originals = {p: p.read_bytes() for p in (csv_path, json_path)}
    for _ in range(40):
        path = [csv_path, json_path][int(rng.integers(2))]
        damaged = bytearray(originals[path])
        kind = int(rng.integers(3))
        if kind == 0:
            damaged[int(rng.integers(len(damaged)))] ^= 1 << int(rng.integers(8))
        elif kind == 1:
            del damaged[int(rng.integers(len(damaged))) :]
        else:
            damaged += b"1,2,3\n"
        path.write_bytes(bytes(damaged))
        assert check_cell(tmp_path, cell, inputs).status == "invalid"
        path.write_bytes(originals[path])
    assert check_cell(tmp_path, cell, inputs).status == "valid"
