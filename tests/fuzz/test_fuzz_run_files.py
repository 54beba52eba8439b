"""Fuzzing stored runs: any damage to a run's CSV or sidecar is found, never raised, never used.

A run that does not verify comes back as ``invalid`` (with a reason naming the file) from
``store.check_run``, which the runner then recomputes and the report leaves out. The only
damage allowed to pass is none at all.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from experiments import fingerprint, store

ROWS = tuple(
    (i, 10 + i % 7, -0.01 * (10 + i % 7) + 5.0, True, False, 1 + i // 10, i % 3)
    for i in range(1, 81)
)
INPUTS = {"task": "t", "config": {"seed": 1}, "env": "e", "layout": "l", "robot": "r", "code": {}}


def _stored(folder: Path) -> tuple[Path, Path]:
    store.write_run(folder, store.RunResult("eps", 0, 11, ROWS, 1.0, 100, 20.0), INPUTS)
    return store.run_paths(folder, "eps__11")


def _check(folder: Path) -> store.RunCheck:
    return store.check_run(folder, "eps__11", episodes=80, cap=100, expected_inputs=INPUTS)


def test_an_undamaged_run_verifies(tmp_path: Path):
    _stored(tmp_path)
    check = _check(tmp_path)
    assert check.status == "valid"
    assert check.data is not None
    assert check.data.steps.tolist() == [row[1] for row in ROWS]


@pytest.mark.parametrize("target", ["csv", "sidecar"])
def test_random_damage_is_always_found(tmp_path: Path, target: str):
    csv_path, meta_path = _stored(tmp_path)
    path = csv_path if target == "csv" else meta_path
    original = path.read_bytes()
    rng = np.random.default_rng(3 if target == "csv" else 4)
    for _ in range(150):
        data = bytearray(original)
        kind = int(rng.integers(5))
        position = int(rng.integers(len(data)))
        if kind == 0:
            data = data[:position]
        elif kind == 1:
            data[position] ^= int(rng.integers(1, 256))
        elif kind == 2:
            data[position:position] = bytes(rng.integers(0, 256, int(rng.integers(1, 30))).tolist())
        elif kind == 3:
            lines = bytes(data).split(b"\n")
            i = int(rng.integers(len(lines)))
            data = bytearray(b"\n".join([*lines[:i], lines[i], *lines[i:]]))
        else:
            data = bytearray(b"")
        path.write_bytes(bytes(data))
        check = _check(tmp_path)
        if bytes(data) == original:
            assert check.status == "valid"
            continue
        reformatted = target == "sidecar" and _same_json(bytes(data), original)  # whitespace
        assert check.status == ("valid" if reformatted else "invalid"), check
        if check.status == "invalid":
            assert str(tmp_path) in check.reason
            assert check.data is None
    path.write_bytes(original)
    assert _check(tmp_path).status == "valid"


def _same_json(data: bytes, original: bytes) -> bool:
    try:
        return json.loads(data) == json.loads(original)
    except ValueError:
        return False


@pytest.mark.parametrize(
    ("key", "value"),
    [
        ("episodes", "80"),
        ("episodes", 79),
        ("episodes", True),
        ("episodes", 0),
        ("data_bytes", -1),
        ("data_bytes", 10**12),
        ("data_sha256", 5),
        ("data_sha256", "0" * 64),
        ("name", "eps__12"),
        ("format", "bullet_maze.agent"),
        ("version", 1),
        ("inputs", []),
        ("inputs", None),
    ],
)
def test_every_sidecar_field_is_checked(tmp_path: Path, key: str, value: object):
    _, meta_path = _stored(tmp_path)
    meta = json.loads(meta_path.read_text())
    meta.pop("sidecar_sha256")
    meta[key] = value
    meta["sidecar_sha256"] = fingerprint.digest(meta)  # a consistent but wrong sidecar
    meta_path.write_text(json.dumps(meta))
    check = _check(tmp_path)
    assert check.status == "invalid"
    assert str(meta_path) in check.reason or str(meta_path.with_suffix(".csv")) in check.reason


def test_a_sidecar_that_is_not_an_object_is_invalid(tmp_path: Path):
    _, meta_path = _stored(tmp_path)
    for text in ("[]", "null", '"x"', "1e999", "{" * 100_000, "\xff"):
        meta_path.write_text(text, encoding="latin-1")
        assert _check(tmp_path).status == "invalid"


EVAL_ROWS = tuple((i, 12 + i, 4.9 - 0.01 * i, True, False, i % 2) for i in range(1, 6))


def _stored_with_evaluation(folder: Path) -> Path:
    result = store.RunResult("eps", 0, 11, ROWS, 1.0, 100, 20.0, task="open", evaluation=EVAL_ROWS)
    store.write_run(folder, result, INPUTS)
    return store.eval_path(folder, "open/eps__11")


def _check_evaluated(folder: Path, eval_episodes: int = 5) -> store.RunCheck:
    return store.check_run(folder, "open/eps__11", 80, 100, INPUTS, eval_episodes)


def test_a_runs_evaluation_verifies_in_its_task_folder(tmp_path: Path):
    path = _stored_with_evaluation(tmp_path)
    assert path == tmp_path / "open" / "eps__11.eval.csv"
    check = _check_evaluated(tmp_path)
    assert check.status == "valid"
    assert check.data is not None
    assert check.data.evaluation is not None
    assert check.data.evaluation["steps"].tolist() == [row[1] for row in EVAL_ROWS]
    assert _check_evaluated(tmp_path, 6).status == "invalid"
    assert "records 5 greedy episodes" in _check_evaluated(tmp_path, 6).reason
    store.remove_run(tmp_path, "open/eps__11")
    assert not any((tmp_path / "open").iterdir())


def test_random_damage_to_an_evaluation_is_always_found(tmp_path: Path):
    path = _stored_with_evaluation(tmp_path)
    original = path.read_bytes()
    rng = np.random.default_rng(8)
    for _ in range(100):
        data = bytearray(original)
        position = int(rng.integers(len(data)))
        kind = int(rng.integers(3))
        if kind == 0:
            data = data[:position]
        elif kind == 1:
            data[position] ^= int(rng.integers(1, 256))
        else:
            data[position:position] = b"1,"
        path.write_bytes(bytes(data))
        check = _check_evaluated(tmp_path)
        assert check.status == ("valid" if bytes(data) == original else "invalid"), check
    path.unlink()
    check = _check_evaluated(tmp_path)
    assert check.status == "invalid"
    assert "missing" in check.reason
