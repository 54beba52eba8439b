"""Per-run result files: atomic writes, exact number format, round trip."""

from __future__ import annotations

import os
import signal
from pathlib import Path

import numpy as np
import pytest

from experiments import store


def test_atomic_write_replaces_and_leaves_no_temporary(tmp_path: Path):
    path = tmp_path / "sub" / "file.csv"
    store.atomic_write_text(path, "old\n")
    store.atomic_write_text(path, "new\n")
    assert path.read_text() == "new\n"
    assert sorted(p.name for p in path.parent.iterdir()) == ["file.csv"]
    assert path.stat().st_mode & 0o777 == 0o644


def test_floats_are_written_exactly():
    value = 0.1 + 0.2
    text = store.format_rows([(1, 2, value, True, False, 3, 0)])
    assert text.splitlines() == [",".join(store.COLUMNS), f"1,2,{value!r},1,0,3,0"]
    assert float(text.splitlines()[1].split(",")[2]) == value


def test_run_round_trip(tmp_path: Path):
    rows = ((1, 40, 4.61, True, False, 1, 2), (2, 5000, -50.0, False, True, 3, 0))
    result = store.RunResult(
        "eps", 0, 123, rows, wall_time_s=2.0, env_steps=5040, optimal_steps=30.0
    )
    store.write_run(tmp_path, result)
    assert store.check_run(tmp_path, "eps__123", episodes=2, cap=5000).status == "valid"
    data = store.read_run(tmp_path, "eps__123")
    np.testing.assert_array_equal(data.steps, [40, 5000])
    np.testing.assert_array_equal(data.columns["success"], [1, 0])
    assert data.columns["return"].tolist() == [4.61, -50.0]
    assert data.meta["steps_per_second"] == 2520.0
    assert data.meta["optimal_steps"] == 30.0


def test_stale_temporaries_are_removed(tmp_path: Path):
    (tmp_path / ".eps__1.csv.abc.tmp").write_text("half")
    assert store.remove_stale_temporaries(tmp_path) == 1
    assert list(tmp_path.iterdir()) == []


def test_ctrl_c_between_a_runs_csv_and_its_sidecar_waits_for_the_sidecar(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
):
    # The CI failure this guards: a Ctrl-C landed after a run's CSV and before its sidecar,
    # leaving a finished run that nothing vouched for.
    write_text = store.atomic_write_text

    def write_then_interrupt(path: Path, text: str) -> None:
        write_text(path, text)
        if path.suffix == ".csv":
            os.kill(os.getpid(), signal.SIGINT)  # delivered here if nothing holds it

    monkeypatch.setattr(store, "atomic_write_text", write_then_interrupt)
    result = store.RunResult("eps", 0, 7, ((1, 40, 4.61, True, False, 1, 2),))
    with pytest.raises(KeyboardInterrupt):
        store.write_run(tmp_path, result)
    assert store.check_run(tmp_path, "eps__7", episodes=1, cap=5000).status == "valid"
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_no_interrupt_leaves_the_handler_as_it_was(tmp_path: Path):
    store.write_run(tmp_path, store.RunResult("eps", 0, 8, ((1, 40, 4.61, True, False, 1, 2),)))
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    assert store.check_run(tmp_path, "eps__8", episodes=1, cap=5000).status == "valid"
