"""Today's numbers stay today's: the golden files of ``record.py`` against the current code.

The paper's method must reproduce bit for bit (the fast learning loop, the learner's new
defaults beside the paper presets); the simulation's rewrites must leave the disc's rollouts and
every layout's physical limit as they were. A deliberate change re-records the file it changes
with ``record.py`` and says so in its commit.
"""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
_spec = importlib.util.spec_from_file_location("golden_record", HERE / "record.py")
assert _spec is not None
assert _spec.loader is not None
record = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(record)


def _fig4_matches(folder: str, tmp_path: Path) -> None:
    out = tmp_path / folder
    record.run_fig4(folder, out)
    golden = sorted((HERE / folder).glob("*.csv"))
    computed = sorted((out / "runs").glob("*.csv"))
    assert [p.name for p in computed] == [p.name for p in golden]
    for expected, actual in zip(golden, computed, strict=True):
        assert actual.read_bytes() == expected.read_bytes(), f"{actual.name} differs"


def test_paper_fig4_short_run_csvs_are_byte_identical(tmp_path: Path) -> None:
    """As recorded at 3bdcf5f, with that day's sweep (``contact_release = false``)."""
    _fig4_matches("paper_fig4_short", tmp_path)


def test_paper_fig4_short_run_csvs_with_today_s_sweep_are_byte_identical(tmp_path: Path) -> None:
    """The same runs with ``contact_release`` (the default since 2026-12-07): only the two runs
    that the old sweep held against a wall differ from the legacy folder."""
    _fig4_matches("paper_fig4_short_release", tmp_path)
    legacy, today = HERE / "paper_fig4_short", HERE / "paper_fig4_short_release"
    differ = sorted(
        p.name for p in legacy.glob("*.csv") if p.read_bytes() != (today / p.name).read_bytes()
    )
    assert differ == ["eps-greedy-0.015__2730688458.csv", "grid-30x30__2244058087.csv"]


@pytest.mark.slow
def test_paper_fig4_medium_run_csvs_are_byte_identical(tmp_path: Path) -> None:
    _fig4_matches("paper_fig4_medium", tmp_path)


def test_env_rollouts_are_unchanged() -> None:
    from experiments.store import format_rows

    expected = (HERE / "env_rollouts.csv").read_text()
    assert format_rows(record.rollout_rows(), record.ROLLOUT_COLUMNS) == expected


def test_physical_limits_are_unchanged() -> None:
    expected = json.loads((HERE / "physical_limits.json").read_text())
    assert record.physical_limits() == expected


def test_agent_rollouts_on_mountain_car_are_unchanged() -> None:
    from experiments.store import format_rows

    expected = (HERE / "agent_rollouts.csv").read_text()
    assert format_rows(record.agent_rows(), record.AGENT_COLUMNS) == expected
