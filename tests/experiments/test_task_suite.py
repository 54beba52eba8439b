"""The multi-task script: runs, resume, the summary, and bad options (exit 2, named)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from experiments import task_suite


def test_classic_runs_write_csv_sidecar_and_summary(tmp_path: Path) -> None:
    argv = ["classic", "--tasks", "cp", "--agents", "general,tile", "--seeds", "3"]
    argv += ["--episodes", "3", "--eval-episodes", "2", "--out", str(tmp_path)]
    assert task_suite.main(argv) == 0
    csv = tmp_path / "runs" / "cp__general__3.csv"
    meta = json.loads((tmp_path / "runs" / "cp__general__3.json").read_text())
    assert (
        csv.read_text().splitlines()[0]
        == "episode,steps,return,success,truncated,leaves,collisions"
    )
    assert len(csv.read_text().splitlines()) == 4
    assert len(meta["greedy_returns"]) == 2
    summary = (tmp_path / "summary.md").read_text()
    assert "| general | 1 |" in summary
    assert "| tile | 1 |" in summary
    before = csv.read_text()
    assert task_suite.main(argv) == 0  # resumes: the finished run is kept as it was
    assert csv.read_text() == before


def test_maze_run_is_scored_by_steps(tmp_path: Path) -> None:
    argv = ["maze", "--tasks", "open", "--agents", "general,grid10", "--seeds", "0"]
    argv += ["--episodes", "2", "--out", str(tmp_path)]
    assert task_suite.main(argv) == 0
    summary = (tmp_path / "summary.md").read_text()
    assert "maze open" in summary
    assert "| grid10 | 1 |" in summary


@pytest.mark.parametrize(
    ("argv", "named"),
    [
        (["classic", "--tasks", "pong"], "--tasks"),
        (["classic", "--agents", "general,wizard"], "wizard"),
        (["classic", "--seeds", "1-x"], "--seeds"),
        (["classic", "--episodes", "0"], "--episodes"),
        (["maze"], "--tasks"),
    ],
)
def test_bad_options_exit_2_naming_them(
    argv: list[str], named: str, capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    with pytest.raises(SystemExit) as exit_info:
        task_suite.main([*argv, "--out", str(tmp_path)])
    assert exit_info.value.code == 2
    error = capsys.readouterr().err
    assert named in error
    assert "Traceback" not in error
    assert task_suite.parse_seeds("100-102,7") == [100, 101, 102, 7]
