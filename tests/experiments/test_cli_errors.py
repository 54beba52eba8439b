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


# --- issue 12: hostile input is refused by name, never with a traceback ---------------------


def _write(folder: Path, name: str, text: str | bytes) -> Path:
    path = folder / name
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text)
    return path


SMALL_FILE = """
[experiment]
name = "small"
runs = 1
episodes = 2

[env]
max_episode_steps = 20

[[strategy]]
name = "eps"
exploration = "epsilon-greedy"
"""


@pytest.mark.parametrize(
    ("edit", "named"),
    [
        ("[agent]\ngamma = true\n", "[agent] gamma: expected a number, got true"),
        ("[agent]\nmax_leaves = true\n", "[agent] max_leaves: expected an integer"),
        ("[agent]\nsplit_min_samples = 100000000\n", "split_min_samples: at most 1,000,000"),
        ("[agent]\nalpha = nan\n", "[agent] alpha: must be finite"),
        ("[env.params]\nrobot_radius = true\n", "[env.params] robot_radius: expected a number"),
        ("[env.params]\nstep_size = inf\n", "[env] params.step_size: must be finite"),
        ("[env.params]\nrender_mode = 'human'\n", "[env.params] render_mode"),
        ("[env.params]\nwarp = 9\n", "[env.params] warp: BulletMaze-v0 takes no such argument"),
    ],
)
def test_quietly_accepted_values_are_refused(tmp_path: Path, capsys, edit, named):
    text = SMALL_FILE.replace("[[strategy]]", edit + "\n[[strategy]]")
    error = _fails(["experiment", str(_write(tmp_path, "f.toml", text)), "--report-only"], capsys)
    assert "f.toml" in error
    assert named in error


@pytest.mark.parametrize(
    ("params", "named"),
    [
        (
            'exploration_params = { deviation_explores = "false" }\nexploration = "tabu"',
            "deviation_explores: expected true or false, got 'false'",
        ),
        ('exploration_params = { c_n = inf }\nexploration = "adaptive"', "c_n: must be finite"),
        (
            'exploration_params = { epsilon = true }\nexploration = "epsilon-greedy"',
            "epsilon: expected a number, got true",
        ),
        ('agent = "grid"\nresolution = [1000, 1000, 1000]', "at most 1,000,000"),
    ],
)
def test_strategy_values_are_strict(tmp_path: Path, capsys, params, named):
    text = SMALL_FILE.replace('exploration = "epsilon-greedy"\n', "") + params + "\n"
    error = _fails(["experiment", str(_write(tmp_path, "s.toml", text)), "--report-only"], capsys)
    assert "s.toml" in error
    assert named in error


@pytest.mark.parametrize(
    ("argv", "named"),
    [
        (["--agent-param", "gamma=true"], "option --agent-param gamma: expected a number"),
        (["--agent-param", "max_leaves=true"], "option --agent-param max_leaves: expected an"),
        (
            ["--exploration", "tabu", "--param", 'deviation_explores="false"'],
            "option --param deviation_explores: expected true or false, got 'false'",
        ),
        (
            ["--exploration", "adaptive", "--param", "c_n=inf"],
            "option --param c_n: must be finite",
        ),
        (["--param", "epsilon"], "option --param: expected KEY=VALUE"),
        (["--param", "epsilon=0.1", "--param", "epsilon=0.2"], "epsilon is given twice"),
        (["--maze", "nosuchmaze"], "option --maze: unknown maze 'nosuchmaze'"),
        (["--robot", "no/such.urdf"], "option --robot: robot file not found"),
        (["--seed", "99999999999"], "option --seed: expected an integer from 0 to"),
        (["--episodes", "100000000"], "option --episodes: expected an integer from 1 to 1,000,000"),
        (["--strategy", "nope"], "option --strategy: no strategy named 'nope'"),
    ],
)
def test_train_options_are_strict_and_named(argv, named, capsys):
    error = _fails(["train", "--episodes", "1", *argv], capsys)
    assert named in error
    assert "quick.toml: [env]" not in error


def test_a_maze_error_from_the_option_names_the_option(capsys):
    """Issue 12: --maze errors were reported as 'experiments/quick.toml: [env]: ...'."""
    error = _fails(["train", "--maze", "nosuchmaze", "--episodes", "1"], capsys)
    assert error.startswith("run.py train: error: option --maze:")


def test_runs_beyond_the_bound_are_refused_at_once(tmp_path: Path, capsys):
    import time

    path = _write(tmp_path, "big.toml", SMALL_FILE.replace("runs = 1", "runs = 1000000000"))
    start = time.perf_counter()
    error = _fails(["experiment", str(path)], capsys)
    assert time.perf_counter() - start < 5
    assert "[experiment] runs: must be an integer from 1 to 10,000, got 1,000,000,000" in error
    error = _fails(["experiment", "quick", "--runs", "1000000000"], capsys)
    assert "option --runs: expected an integer from 1 to 10,000" in error


@pytest.mark.parametrize(
    ("content", "named"),
    [
        (b'[experiment]\nname = "\xff\xfe"\n', "not UTF-8 text"),
        ("[experiment]\nname = 'x'\nseed = " + "[" * 3000 + "]" * 3000 + "\n", "nested more than"),
        (
            "a = " + "{b = " * 17 + "1" + "}" * 17 + "\n",
            "nested more than 16 levels",
        ),
        ("[experiment\n", "not valid TOML"),
    ],
    ids=["non-utf8", "deep arrays", "deep tables", "syntax"],
)
def test_unreadable_toml_is_a_clear_error(tmp_path: Path, capsys, content, named):
    error = _fails(["experiment", str(_write(tmp_path, "bad.toml", content))], capsys)
    assert "bad.toml" in error
    assert named in error


def test_out_pointing_at_a_file_is_a_clear_error(tmp_path: Path, capsys):
    afile = _write(tmp_path, "afile", "not a folder")
    for argv in (
        ["experiment", "quick", "--out", str(afile)],
        ["experiment", "quick", "--out", str(afile / "sub")],
        ["train", "--episodes", "1", "--out", str(afile)],
    ):
        error = _fails(argv, capsys)
        assert "option --out" in error
        assert "a file, not a folder" in error


def test_import_paths_and_unknown_ids_are_refused(tmp_path: Path, capsys):
    for env_id, named in (
        ("os:X-v0", "is an import path"),
        ("Nonexistent-v7", "is not a registered Gymnasium id"),
    ):
        text = SMALL_FILE.replace("[env]", f'[env]\nid = "{env_id}"')
        error = _fails(
            ["experiment", str(_write(tmp_path, "e.toml", text)), "--report-only"], capsys
        )
        assert named in error


def test_evaluate_never_lets_a_config_beside_the_agent_import_a_module(
    tmp_path: Path, capsys, monkeypatch: pytest.MonkeyPatch
):
    """Issue 12: ``[env] id = "somemodule:X-v0"`` in a shared folder made Gymnasium import it."""
    import sys

    marker = tmp_path / "imported"
    _write(tmp_path, "evilenv.py", f"open({str(marker)!r}, 'w').write('ran')\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    folder = tmp_path / "shared"
    folder.mkdir()
    import numpy as np

    np.savez(folder / "agent.npz", x=np.zeros(1))
    _write(folder, "config.toml", SMALL_FILE.replace("[env]", '[env]\nid = "evilenv:X-v0"'))
    for command in ("evaluate", "render"):
        error = _fails([command, str(folder)], capsys)
        assert "config.toml: [env] id: 'evilenv:X-v0' is an import path" in error
    assert not marker.exists()
    assert "evilenv" not in sys.modules


def _tampered_agent(folder: Path, edit) -> Path:
    import json

    import numpy as np

    from agent import TreeAgent

    agent = TreeAgent(
        __import__("gymnasium").spaces.Box(0.0, 300.0, shape=(2,)),
        __import__("gymnasium").spaces.Discrete(4),
        seed=1,
    )
    agent.split_leaf(0, 0, 150.0)
    agent.split_leaf(1, 1, 150.0)
    path = agent.save(folder / "agent.npz")
    with np.load(path) as data:
        arrays = {k: data[k].copy() for k in data.files}
    meta = json.loads(arrays.pop("metadata").tobytes())
    edit(meta, arrays)
    np.savez(path, metadata=np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8), **arrays)
    return path


def _cycle(meta, arrays):
    arrays["partition.left"][1] = 0


def _out_of_range(meta, arrays):
    arrays["partition.left"][0] = 999


@pytest.mark.parametrize(("edit", "defect"), [(_cycle, "a cycle"), (_out_of_range, "child id")])
@pytest.mark.parametrize("command", ["evaluate", "render"])
def test_a_tampered_agent_is_refused_by_evaluate_and_render(
    tmp_path: Path, capsys, edit, defect, command
):
    path = _tampered_agent(tmp_path, edit)
    error = _fails([command, str(path), "--max-episode-steps", "5"], capsys)
    assert str(path) in error
    assert defect in error


@pytest.mark.parametrize(
    "content", [b"", b"plain text\n", b"PK\x03\x04truncated"], ids=["empty", "text", "cut zip"]
)
def test_an_agent_that_is_no_agent_file_is_refused(tmp_path: Path, capsys, content):
    path = _write(tmp_path, "agent.npz", content)
    error = _fails(["evaluate", str(path)], capsys)
    assert str(path) in error
    assert "allow_pickle" not in error


def test_a_grid_too_fine_for_the_observation_is_refused_before_any_run(tmp_path: Path, capsys):
    text = SMALL_FILE.replace('exploration = "epsilon-greedy"', 'agent = "grid"\nresolution = 5000')
    out = tmp_path / "out"
    error = _fails(["experiment", str(_write(tmp_path, "g.toml", text)), "--out", str(out)], capsys)
    assert "g.toml: [strategy 'eps'] resolution" in error
    assert "25,000,000 cells, at most 1,000,000" in error
    assert not out.exists()


def test_train_with_an_exploration_and_no_param_works(tmp_path: Path, capsys):
    """Issue 12: ``run.py train --exploration vdbe --episodes 2`` (documented usage) failed."""
    out = tmp_path / "vdbe"
    argv = ["train", "--exploration", "vdbe", "--episodes", "2", "--max-episode-steps", "30"]
    assert run.main([*argv, "--no-progress", "--out", str(out)]) == 0
    assert "training vdbe" in capsys.readouterr().out
    assert (out / "policy.npz").is_file()


def test_the_command_line_goes_through_the_front_door_only():
    """run.py imports nothing but the experiments package's public names."""
    import ast

    tree = ast.parse(Path(run.__file__).read_text())
    modules = {
        node.module for node in ast.walk(tree) if isinstance(node, ast.ImportFrom) and node.module
    } | {
        alias.name
        for node in ast.walk(tree)
        if isinstance(node, ast.Import)
        for alias in node.names
    }
    ours = {m for m in modules if m.split(".")[0] in {"experiments", "agent", "bullet_maze"}}
    assert ours == {"experiments"}


def test_the_runner_is_entered_once_per_experiment_command(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys
):
    from experiments import runner

    calls: list[str] = []
    original = runner.run_experiment

    def counting(*args, **kwargs):
        calls.append("run_experiment")
        return original(*args, **kwargs)

    monkeypatch.setattr(runner, "run_experiment", counting)
    path = _write(tmp_path, "one.toml", SMALL_FILE)
    argv = ["experiment", str(path), "--backend", "serial", "--no-progress"]
    assert run.main([*argv, "--out", str(tmp_path / "out")]) == 0
    assert calls == ["run_experiment"]


def test_report_only_of_a_file_that_changes_runs_is_refused(tmp_path: Path, capsys):
    """The folder's config.toml describes its report: a file with another seed is refused by
    --report-only as by a run, naming the key; a changed report setting is recorded."""
    out = tmp_path / "out"
    path = _write(tmp_path, "f.toml", SMALL_FILE)
    assert run.main(["experiment", str(path), "--out", str(out), "--workers", "1"]) == 0
    capsys.readouterr()
    reseeded = _write(tmp_path, "g.toml", SMALL_FILE.replace("runs = 1", "runs = 1\nseed = 5"))
    error = _fails(["experiment", str(reseeded), "--out", str(out), "--report-only"], capsys)
    assert "differs in experiment.seed" in error
    windowed = _write(
        tmp_path, "h.toml", SMALL_FILE.replace("runs = 1", "runs = 1\nfinal_window = 1")
    )
    assert run.main(["experiment", str(windowed), "--out", str(out), "--report-only"]) == 0
    assert "final_window = 1" in (out / "config.toml").read_text()


def test_report_only_writes_no_config_into_an_empty_folder(tmp_path: Path, capsys):
    _fails(["experiment", "quick", "--report-only", "--out", str(tmp_path)], capsys)
    assert not (tmp_path / "config.toml").exists()


ENSEMBLE = "config = { ensemble_trees = 4, presplit_each_dimension = true }\n"


def test_an_ensemble_that_must_be_saved_is_refused_before_any_run(tmp_path: Path, capsys):
    """A tree ensemble has no file format. ``save_agents`` used to fail each run after its
    training, and ``run.py train`` with a traceback after writing half its folder."""
    text = SMALL_FILE.replace("[experiment]\n", "[experiment]\nsave_agents = true\n") + ENSEMBLE
    out = tmp_path / "out"
    error = _fails(["experiment", str(_write(tmp_path, "e.toml", text)), "--out", str(out)], capsys)
    assert "e.toml: [experiment] save_agents = true, but strategy 'eps' cannot be saved" in error
    assert "a tree ensemble (TreeConfig.ensemble_trees = 4) has no file format yet" in error
    assert not out.exists()
    trained = tmp_path / "trained"
    argv = ["train", "--config", str(_write(tmp_path, "t.toml", SMALL_FILE + ENSEMBLE))]
    error = _fails([*argv, "--out", str(trained)], capsys)
    assert "[strategy 'eps']: run.py train saves the agent, and a tree ensemble" in error
    assert not trained.exists()
    option = ["--agent-param", "ensemble_trees=4", "--agent-param", "presplit_each_dimension=true"]
    plain = _write(tmp_path, "plain.toml", SMALL_FILE)
    error = _fails(["train", "--config", str(plain), *option, "--out", str(trained)], capsys)
    assert "run.py train saves the agent" in error
    assert not trained.exists()


def test_an_ensemble_runs_when_nothing_must_be_saved(tmp_path: Path, capsys):
    out = tmp_path / "out"
    config = _write(tmp_path, "e.toml", SMALL_FILE + ENSEMBLE)
    run.main(["experiment", str(config), "--out", str(out), "--no-progress"])
    assert list(out.glob("**/*.csv"))
