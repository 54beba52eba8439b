"""Fuzzing the command line: every option given every hostile value, and random command lines.

Every case's outcome is asserted: a hostile value exits with code 2 and a one-line message that
names the option (never a traceback); a random command line exits 0 or 2, never anything else,
never with a traceback. Runs are kept tiny: the default experiment is replaced by a one-run,
two-episode file and nothing is written outside the test's folder.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import run

TINY = """
[experiment]
name = "tiny"
runs = 1
episodes = 2
smoothing_window = 1
final_window = 1

[env]
max_episode_steps = 15

[[strategy]]
name = "eps"
exploration = "epsilon-greedy"
"""

INTEGERS = ["", "abc", "1.5", "1e3", "nan", "inf", "0x10", "true", "99999999999999999999999"]
NEGATIVE = ["-1", "-99999999999"]
TEXT = ["", "\x00", "x" * 5000]


@pytest.fixture
def folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A tiny default experiment, results kept in ``tmp_path``, a trained agent there."""
    config = tmp_path / "tiny.toml"
    config.write_text(TINY)
    monkeypatch.setattr(run, "DEFAULT_CONFIG", str(config))
    monkeypatch.setattr(run, "RESULTS_DIR", tmp_path / "results")
    (tmp_path / "afile").write_text("not a folder")
    return tmp_path


def _outcome(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str]:
    try:
        code = run.main(argv)
    except SystemExit as exit_info:
        code = exit_info.code if isinstance(exit_info.code, int) else 2
    error = capsys.readouterr().err
    return code, error


def _cases() -> list[tuple[str, list[str], list[str]]]:
    """(option, base command line, hostile values)."""
    train = ["train", "--episodes", "1", "--max-episode-steps", "10", "--no-progress"]
    experiment = ["experiment", "{tiny}", "--backend", "serial", "--no-progress"]
    evaluate = ["evaluate", "{agent}", "--episodes", "1", "--max-episode-steps", "5"]
    render = ["render", "{agent}", "--max-episode-steps", "5", "--max-frames", "2"]
    cases = []
    for option in ("--episodes", "--max-episode-steps"):
        cases.append((option, train, [*INTEGERS, *NEGATIVE, "0", "100000000"]))
    cases += [
        ("--seed", train, [*INTEGERS, *NEGATIVE, "4294967296"]),
        ("--time-budget", train, ["", "soon", "-1", "nan", "inf", "1e30"]),
        ("--strategy", train, [*TEXT, "nope"]),
        ("--exploration", train, [*TEXT, "boltzman", "os:system"]),
        (
            "--param",
            [*train, "--exploration", "adaptive"],
            ["c_n", "=1", "c_n=inf", "c_n=true", "c_n='0.1'", "c_n=[1]", "c_n=1\nx=2", "zz=1"],
        ),
        (
            "--agent-param",
            train,
            [
                "gamma=true",
                "gamma=nan",
                "gamma=2",
                "alpha='0.3'",
                "max_leaves=1e3",
                "split_min_samples=999999999",
                "hold_exploration='false'",
                "nofield=1",
                "x",
                "greedy_min_epochs=-1",
                "greedy_min_epochs=1.5",
                "greedy_min_epochs=true",
                "greedy_min_epochs=2",  # needs planning = 'sweep'
                "greedy_cell_epochs=-1",
                "greedy_cell_epochs=1",  # needs greedy_min_epochs > 0 and planning = 'sweep'
                "greedy_cell_epochs='1'",
                "greedy_smoothing=-1",
                "greedy_smoothing=nan",
                "greedy_smoothing=2",
                "greedy_tie_errors=0",
                "greedy_tie_errors=-0.5",
                "greedy_tie_errors=inf",
                "greedy_tie_errors='0.5'",
                "greedy_tie_errors=0.5",  # needs greedy_smoothing > 0 and planning = 'sweep'
                "greedy_smoothing_links=1",
                "greedy_smoothing_links=true",  # needs greedy_smoothing > 0
                "greedy_tie_ancestors=0",
                "greedy_tie_ancestors=-1",
                "greedy_tie_ancestors=nan",
                "greedy_tie_ancestors='1'",
                "greedy_tie_ancestors=1",  # needs greedy_tie_errors
            ],
        ),
        ("--maze", train, [*TEXT, "nosuch", "/etc/passwd", "missing.toml", "{afile}"]),
        ("--robot", train, [*TEXT, "nosuch", "missing.urdf", "{afile}"]),
        ("--mode", train, [*TEXT, "wobbly", "KINEMATIC"]),
        ("--out", train, ["{afile}", "{afile}/sub"]),
        ("--config", train, [*TEXT, "nonexistent", "{afile}", "/dev/null", "{tmp}"]),
        ("--allow-env", experiment, ["os:system"]),
        ("--runs", experiment, [*INTEGERS, *NEGATIVE, "0", "1000000000"]),
        ("--workers", experiment, [*INTEGERS, *NEGATIVE, "0", "100000"]),
        ("--backend", experiment, [*TEXT, "gpu", "threads"]),
        ("--only", experiment, ["", ",", "nope", "eps,nope"]),
        ("--out", experiment, ["{afile}", "{afile}/sub"]),
        ("--episodes", evaluate, [*INTEGERS, *NEGATIVE, "0", "10000000"]),
        ("--seed", evaluate, [*INTEGERS, *NEGATIVE]),
        ("--fps", render, [*INTEGERS, "0", "1000"]),
        ("--max-frames", render, [*INTEGERS, "0", "100000"]),
        ("--out", render, ["{tmp}", "{afile}/x.gif"]),
    ]
    return [(option, base, [value]) for option, base, values in cases for value in values]


CASES = _cases()


@pytest.fixture(scope="module")
def agent_file(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A small trained agent (one folder for the whole module)."""
    import gymnasium as gym

    from agent import TreeAgent

    folder = tmp_path_factory.mktemp("agent")
    agent = TreeAgent(gym.spaces.Box(0.0, 300.0, shape=(2,)), gym.spaces.Discrete(4), seed=0)
    agent.split_leaf(0, 1, 150.0)
    return agent.save(folder / "agent.npz")


@pytest.mark.parametrize(
    ("option", "base", "values"), CASES, ids=[f"{b[0]} {o} {v[0]!r:.20}" for o, b, v in CASES]
)
def test_every_hostile_value_is_refused_by_name(
    folder: Path, agent_file: Path, capsys, option: str, base: list[str], values: list[str]
):
    fill = {"{tiny}": str(folder / "tiny.toml"), "{agent}": str(agent_file)}
    argv = [fill.get(a, a) for a in base]
    value = values[0].replace("{afile}", str(folder / "afile")).replace("{tmp}", str(folder))
    code, error = _outcome([*argv, option, value], capsys)
    assert code == 2, error
    assert "Traceback" not in error
    assert error.count("\n") <= 25
    named = option in error or (value and value[:50] in error) or "argument" in error
    assert named, error


VOCABULARY = [
    "train",
    "experiment",
    "evaluate",
    "render",
    "--episodes",
    "--runs",
    "--seed",
    "--out",
    "--maze",
    "--robot",
    "--mode",
    "--param",
    "--agent-param",
    "--strategy",
    "--exploration",
    "--only",
    "--workers",
    "--time-budget",
    "--max-episode-steps",
    "--backend",
    "--config",
    "--report-only",
    "--accept-code-change",
    "--allow-env",
    "--env-module",
    "--fps",
    "--max-frames",
    "--no-progress",
    "1",
    "2",
    "0",
    "-1",
    "nan",
    "x",
    "",
    "eps",
    "serial",
    "dynamic",
    "open",
    "disc",
    "husky",
    "epsilon=0.1",
    "gamma=true",
    "{tiny}",
    "{agent}",
    "{afile}",
    "{tmp}/o",
    "vdbe",
    "tabu",
    "CartPole-v1",
    "--help",
]
"""Tokens of random command lines: no value here can start a long computation (a run needs
``{tiny}`` or the tiny default; caps and episodes are at most 2, the backend serial)."""


def test_random_command_lines_never_end_in_a_traceback(folder: Path, agent_file: Path, capsys):
    rng = np.random.default_rng(2012)
    fill = {
        "{tiny}": str(folder / "tiny.toml"),
        "{agent}": str(agent_file),
        "{afile}": str(folder / "afile"),
        "{tmp}/o": str(folder / "o"),
    }
    codes = []
    for _ in range(60):
        argv = [fill.get(t, t) for t in rng.choice(VOCABULARY, int(rng.integers(1, 7)))]
        if argv[0] == "experiment":
            argv += ["--backend", "serial"]  # no worker processes to start
        elif argv[0] in ("train", "evaluate", "render"):
            argv += ["--max-episode-steps", "10"]
        code, error = _outcome(argv, capsys)
        assert code in (0, 2), (argv, error)
        assert "Traceback" not in error, (argv, error)
        codes.append(code)
    assert codes.count(2) > 30
