"""Bad options and bad experiment files: a clear message naming the key, exit code 2."""

from __future__ import annotations

from pathlib import Path

import pytest

import run


def _fails(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    with pytest.raises(SystemExit) as exit_info:
        run.main(argv)
    assert exit_info.value.code == 2
    error = capsys.readouterr().err
    assert "Traceback" not in error
    return error


@pytest.mark.parametrize(
    ("argv", "named"),
    [
        (["experiment", "quick", "--runs", "0"], "--runs"),
        (["experiment", "quick", "--workers", "two"], "--workers"),
        (["experiment", "quick", "--backend", "gpu"], "--backend"),
        (["train", "--mode", "wobbly"], "--mode"),
        (["train", "--episodes", "-3"], "--episodes"),
        (["train", "--time-budget", "-1"], "--time-budget"),
        (["train", "--time-budget", "soon"], "--time-budget"),
        (["frobnicate"], "frobnicate"),
        (["experiment", "quick", "--address", "auto"], "--address"),
    ],
)
def test_bad_options_name_the_option(argv, named, capsys):
    assert named in _fails(argv, capsys)


@pytest.mark.parametrize(
    ("argv", "named"),
    [
        (["train", "--maze", "nosuchmaze", "--episodes", "1"], "nosuchmaze"),
        (["train", "--strategy", "nope"], "nope"),
        (["train", "--param", "epsilonn=0.1", "--episodes", "1"], "epsilonn"),
        (["train", "--agent-param", "alpha=7", "--episodes", "1"], "alpha"),
        (["evaluate", "no/such/agent.npz"], "no/such/agent.npz"),
        (["experiment", "quick", "--only", "eps-greedy-0.15", "--out", "{tmp}"], "eps-greedy-0.15"),
    ],
)
def test_bad_values_are_named(argv, named, capsys, tmp_path: Path):
    assert named in _fails([a.replace("{tmp}", str(tmp_path)) for a in argv], capsys)


def test_unknown_config_key_names_file_and_key(tmp_path: Path, capsys):
    path = tmp_path / "typo.toml"
    path.write_text('[experiment]\nname = "typo"\nepisodez = 10\n[[strategy]]\nname = "a"\n')
    error = _fails(["experiment", str(path)], capsys)
    assert "typo.toml" in error
    assert "episodez" in error


def test_missing_config_file_is_named(capsys):
    assert "nonexistent" in _fails(["experiment", "nonexistent"], capsys)


def test_every_option_is_explained(capsys):
    parser = run.build_parser()
    subparsers = next(a for a in parser._actions if a.dest == "command").choices
    for name, sub in subparsers.items():
        for action in sub._actions:
            assert action.help, f"{name} {action.option_strings or action.dest} has no help"


def test_report_of_an_empty_folder_is_an_error(tmp_path: Path, capsys):
    error = _fails(["experiment", "quick", "--report-only", "--out", str(tmp_path)], capsys)
    assert "no finished runs" in error
