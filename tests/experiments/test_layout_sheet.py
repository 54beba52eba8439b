"""``run.py layouts``: a contact sheet of layouts or of a suite, and clear errors."""

from __future__ import annotations

from pathlib import Path

import pytest

import run
from experiments.layout_sheet import draw_layout_sheet

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def test_a_sheet_of_layouts_is_a_png(tmp_path: Path) -> None:
    path = draw_layout_sheet(["open", "maze:seed=1,rows=4,cols=4"], tmp_path / "sheet.png")
    data = path.read_bytes()
    assert data[:8] == PNG_SIGNATURE
    assert len(data) > 10_000


def test_run_py_layouts_draws_a_suite_split(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    suite = tmp_path / "small.toml"
    suite.write_text('dev = ["open"]\ntest = ["maze:seed=1,rows=3,cols=3", "rooms:seed=2"]\n')
    out = tmp_path / "suite.png"
    assert run.main(["layouts", "--suite", str(suite), "--split", "test", "--out", str(out)]) == 0
    assert out.read_bytes()[:8] == PNG_SIGNATURE
    assert str(out) in capsys.readouterr().out


@pytest.mark.parametrize(
    ("argv", "named"),
    [
        (["layouts"], "give MAZE names or --suite"),
        (["layouts", "paper", "--suite", "mazes"], "give MAZE names or --suite"),
        (["layouts", "paper", "--split", "dev"], "--split goes with --suite"),
        (["layouts", "nowhere"], "unknown maze 'nowhere'"),
        (["layouts", "rooms:door=3"], "'door' = 3 must be at least"),
        (["layouts", "--suite", "nosuch"], "unknown suite 'nosuch'"),
        (["layouts", "missing.toml"], "maze file not found"),
    ],
)
def test_bad_layouts_exit_2_with_a_message(
    argv: list[str], named: str, capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    with pytest.raises(SystemExit) as exit_info:
        run.main([*argv, "--out", str(tmp_path / "x.png")])
    assert exit_info.value.code == 2
    error = capsys.readouterr().err
    assert named in error
    assert "Traceback" not in error
