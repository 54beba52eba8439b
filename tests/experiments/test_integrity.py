"""Results you can trust: every run verified before use, inputs fingerprinted, one writer.

Each defect of issue 12's "silent wrong results" has a case here: damaged run files are named
and recomputed (never reported), runs from other inputs are refused by name, a second writer
is refused and deletes nothing.
"""

from __future__ import annotations

import dataclasses
import json
import os
import subprocess
import sys
import textwrap
import time
from collections.abc import Callable
from pathlib import Path

import pytest

from experiments import config as config_module
from experiments import fingerprint, runner, store
from experiments.backends import SerialBackend
from experiments.config import ConfigError, parse_config
from experiments.lock import FolderLock
from experiments.report import write_report

HERE = Path(__file__).resolve().parent


def _computed(log: Path) -> list[str]:
    return log.read_text().split() if log.exists() else []


def _csv(out: Path, name: str) -> Path:
    return out / "runs" / f"{name}.csv"


def _cut_rows(path: Path) -> None:  # at a line boundary: half the episodes
    lines = path.read_text().splitlines(keepends=True)
    path.write_text("".join(lines[: 1 + (len(lines) - 1) // 2]))


def _nan_steps(path: Path) -> None:
    lines = path.read_text().splitlines(keepends=True)
    fields = lines[5].split(",")
    fields[1] = "nan"
    lines[5] = ",".join(fields)
    path.write_text("".join(lines))


def _duplicate_rows(path: Path) -> None:
    lines = path.read_text().splitlines(keepends=True)
    path.write_text("".join([*lines, *lines[1:11]]))


def _cut_mid_line(path: Path) -> None:
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2 + 3])


DAMAGE: list[tuple[str, Callable[[Path], None], str]] = [
    ("cut at a row", _cut_rows, "differs from its sidecar"),
    ("nan steps", _nan_steps, "SHA-256"),
    ("duplicated rows", _duplicate_rows, "differs from its sidecar"),
    ("cut mid-line", _cut_mid_line, "differs from its sidecar"),
    ("empty", lambda p: p.write_text(""), "differs from its sidecar"),
    (
        "header only",
        lambda p: p.write_text(",".join(store.COLUMNS) + "\n"),
        "differs from its sidecar",
    ),
    ("garbage", lambda p: p.write_bytes(os.urandom(300)), "differs from its sidecar"),
    ("deleted", lambda p: p.unlink(), "missing (its sidecar exists)"),
    ("sidecar cut", lambda p: _truncate(p.with_suffix(".json")), "not valid JSON"),
    ("sidecar edited", lambda p: _edit_timing(p.with_suffix(".json")), "its own recorded hash"),
    ("sidecar deleted", lambda p: p.with_suffix(".json").unlink(), "sidecar"),
    ("old sidecar", lambda p: _old_sidecar(p.with_suffix(".json")), "no data hash"),
]


def _truncate(path: Path) -> None:
    path.write_bytes(path.read_bytes()[:40])


def _edit_timing(path: Path) -> None:
    meta = json.loads(path.read_text())
    meta["wall_time_s"] = 0.001
    path.write_text(json.dumps(meta))


def _old_sidecar(path: Path) -> None:  # a sidecar from before version 2: nothing to verify
    meta = json.loads(path.read_text())
    for key in ("format", "version", "data_sha256", "data_bytes", "inputs", "sidecar_sha256"):
        meta.pop(key)
    path.write_text(json.dumps(meta))


@pytest.mark.parametrize(("damage", "reason"), [d[1:] for d in DAMAGE], ids=[d[0] for d in DAMAGE])
def test_a_damaged_run_is_named_recomputed_and_never_used(
    small_config, standins, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, damage, reason
):
    out, log = tmp_path / "out", tmp_path / "computed.log"
    runner.run_experiment(small_config, out, SerialBackend(), standins.fake_run)
    episodes_before = (out / "episodes.csv").read_bytes()
    name = runner.plan(small_config)[2].name
    damage(_csv(out, name))

    state = runner.inspect_folder(small_config, out, standins.fake_run)  # what a report reads
    assert [check.name for _, check in state.excluded] == [name]
    assert reason in state.checks[name].reason
    loaded = runner.results_of(small_config, state)
    assert sum(len(runs) for runs in loaded.values()) == 5
    assert all(len(run.steps) == small_config.episodes for runs in loaded.values() for run in runs)

    monkeypatch.setenv("STANDIN_LOG", str(log))
    seen: list[runner.FolderState] = []
    runner.run_experiment(
        small_config, out, SerialBackend(), standins.fake_run, on_start=seen.append
    )
    assert [spec.name for spec in seen[0].pending] == [name]
    assert [spec.name for spec, _ in seen[0].invalid] == [name]
    assert _computed(log) == [name]
    assert (out / "episodes.csv").read_bytes() == episodes_before


def test_report_only_leaves_a_cut_run_out_by_name(small_config, standins, tmp_path: Path):
    """Issue 12: a run cut to half its episodes once moved a strategy's final steps from 170
    to 301 and its P(improvement) from 0.50 to 0.00; now it is left out, by name."""
    out = tmp_path / "out"
    runner.run_experiment(small_config, out, SerialBackend(), standins.fake_run)
    name = runner.plan(small_config)[3].name
    _cut_rows(_csv(out, name))
    report = write_report(small_config, out, task=standins.fake_run)
    assert [c.name for c in report.excluded] == [name]
    assert [s.runs for s in report.summaries] == [3, 2]
    text = report.markdown.read_text()
    assert f"`{name}`: invalid:" in text


def test_rows_are_checked_even_when_the_hash_agrees(tmp_path: Path):
    """A CSV edited together with its sidecar's hash still has to hold well-formed rows."""
    good = store.format_rows([(i, 10, -0.1, True, False, 1, 0) for i in range(1, 6)])
    cases = {
        "nan": good.replace("1,10,-0.1", "1,nan,-0.1"),
        "duplicated": good + good.split("\n", 1)[1],
        "float count": good.replace("2,10,", "2,10.5,"),
        "success 2": good.replace(",1,0,1,0\n", ",2,0,1,0\n", 1),
        "cut": good[:-9],
        "above the cap": good.replace("3,10,", "3,10000,"),
        "truncated early": good.replace("4,10,-0.1,1,0", "4,10,-0.1,0,1"),
        "collisions above steps": good.replace("5,10,-0.1,1,0,1,0", "5,10,-0.1,1,0,1,11"),
        "header": good.replace("steps", "Steps"),
        "text field": good.replace("1,10,-0.1", "1,10,abc"),
        "empty field": good.replace("2,10,-0.1", "2,,-0.1"),
    }
    for label, text in cases.items():
        with pytest.raises(ValueError, match=r"where\.csv") as error:
            store.parse_rows(text.encode(), "where.csv", cap=300)
        assert "Traceback" not in str(error.value), label
    assert len(store.parse_rows(good.encode(), "where.csv", cap=300)["steps"]) == 5


def test_an_edited_maze_is_refused_by_name_and_a_comment_is_not(
    small_data, standins, tmp_path: Path
):
    maze = tmp_path / "maze.toml"
    source = (config_module.EXPERIMENT_DIR.parent / "assets" / "mazes" / "open.toml").read_text()
    maze.write_text(source)
    small_data["env"]["maze"] = str(maze)
    config = parse_config(small_data, source="small.toml")
    out = tmp_path / "out"
    runner.run_experiment(config, out, SerialBackend(), standins.fake_run, only=["eps"])

    maze.write_text("# a comment changes nothing\n" + source)
    runner.run_experiment(config, out, SerialBackend(), standins.fake_run, only=["eps"])

    maze.write_text(source.replace("position = [150.0, 270.0]", "position = [150.0, 200.0]"))
    assert fingerprint.layout_fingerprint(str(maze)) != fingerprint.layout_fingerprint(
        config_module.EXPERIMENT_DIR.parent / "assets" / "mazes" / "open.toml"
    )
    with pytest.raises(ConfigError, match=r"eps__\d+: .*maze layout \(layout\)") as error:
        runner.run_experiment(config, out, SerialBackend(), standins.fake_run)
    assert "another --out" in str(error.value)
    with pytest.raises(ValueError, match=r"no finished runs.*maze layout"):
        write_report(config, out, task=standins.fake_run)


def test_an_edited_robot_mesh_is_refused_by_name_and_a_moved_folder_is_not(
    small_data, standins, tmp_path: Path
):
    """A URDF's meshes are its collision shapes: editing one changes the physics, so it is a
    changed input (the fingerprint once held the URDF's bytes only). Each mesh counts by its
    name as written, so the same files in another folder are the same robot."""
    import shutil

    import pybullet_data

    source = Path(pybullet_data.getDataPath()) / "husky"
    robot = tmp_path / "mine" / "husky.urdf"
    shutil.copytree(source, robot.parent)
    moved = tmp_path / "elsewhere" / "husky.urdf"
    shutil.copytree(source, moved.parent)
    content = fingerprint.robot_content(str(robot))
    assert set(content["meshes"]) == {
        f"meshes/{name}.stl" for name in ("base_link", "bumper", "top_plate", "user_rail", "wheel")
    }
    assert fingerprint.robot_fingerprint(str(robot)) == fingerprint.robot_fingerprint(str(moved))
    assert "meshes" not in fingerprint.robot_content(str(source / "husky.urdf"))  # shipped

    small_data["env"]["robot"] = str(robot)
    config = parse_config(small_data, source="small.toml")
    out = tmp_path / "out"
    runner.run_experiment(config, out, SerialBackend(), standins.fake_run, only=["eps"])
    runner.run_experiment(config, out, SerialBackend(), standins.fake_run, only=["eps"])

    bumper = robot.parent / "meshes" / "bumper.stl"
    bumper.write_bytes(bumper.read_bytes() + b"\0")
    assert fingerprint.robot_fingerprint(str(robot)) != fingerprint.robot_fingerprint(str(moved))
    with pytest.raises(ConfigError, match=r"eps__\d+: .*robot") as error:
        runner.run_experiment(config, out, SerialBackend(), standins.fake_run)
    assert "another --out" in str(error.value)


def _resealed(path: Path, edit: Callable[[dict], None]) -> None:
    """Edit a sidecar and record its hash again, as a run computed that way would have it."""
    meta = json.loads(path.read_text())
    meta.pop("sidecar_sha256")
    edit(meta)
    meta["sidecar_sha256"] = fingerprint.digest(meta)
    path.write_text(json.dumps(meta))


def test_a_changed_default_shows_as_a_changed_setting(small_config, standins, tmp_path: Path):
    out = tmp_path / "out"
    runner.run_experiment(small_config, out, SerialBackend(), standins.fake_run)
    sidecar = out / "runs" / f"{runner.plan(small_config)[0].name}.json"

    def other_default(meta: dict) -> None:  # as if computed under another default
        meta["inputs"]["config"]["agent_config"]["max_leaves"] = 17

    _resealed(sidecar, other_default)
    with pytest.raises(ConfigError, match=r"config\.agent_config\.max_leaves"):
        runner.run_experiment(small_config, out, SerialBackend(), standins.fake_run)


CODE_TASK = '''
"""A task module for the code-version test."""

from standins import fake_run


def task(spec):
    """Compute the run."""
    return fake_run(spec)
'''


def test_code_changes_are_refused_unless_accepted_and_docstrings_do_not_count(
    small_config, standins, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
):
    module = tmp_path / "codetask.py"
    module.write_text(CODE_TASK)
    monkeypatch.syspath_prepend(str(tmp_path))
    import codetask

    out = tmp_path / "out"
    runner.run_experiment(small_config, out, SerialBackend(), codetask.task, only=["eps"])

    module.write_text(
        CODE_TASK.replace("Compute the run.", "Compute the run (reworded).") + "\n# a comment\n"
    )
    fingerprint._code_fingerprint.cache_clear()
    runner.run_experiment(small_config, out, SerialBackend(), codetask.task, only=["eps"])

    module.write_text(
        CODE_TASK.replace("return fake_run(spec)", "result = fake_run(spec)\n    return result")
    )
    fingerprint._code_fingerprint.cache_clear()
    with pytest.raises(ConfigError, match=r"--accept-code-change") as error:
        runner.run_experiment(small_config, out, SerialBackend(), codetask.task)
    assert "code version" in str(error.value)
    runner.run_experiment(
        small_config, out, SerialBackend(), codetask.task, accept_code_change=True
    )
    report = write_report(small_config, out, task=codetask.task, accept_code_change=True)
    assert len(report.accepted) == 3
    assert [s.runs for s in report.summaries] == [3, 3]
    assert "## Runs from another code version (accepted)" in report.markdown.read_text()
    without = write_report(small_config, out, task=codetask.task)
    assert [s.runs for s in without.summaries] == [3]
    fingerprint._code_fingerprint.cache_clear()
    monkeypatch.delitem(sys.modules, "codetask")


def test_code_fingerprint_ignores_docstrings_comments_and_layout(tmp_path: Path):
    a, b, c = tmp_path / "a.py", tmp_path / "b.py", tmp_path / "c.py"
    a.write_text('"""Doc."""\n\n\ndef f(x):\n    """Say."""\n    return x + 1\n')
    b.write_text('"""Other doc."""\ndef f( x ):  # why\n    return x+1\n')
    c.write_text("def f(x):\n    return x + 2\n")
    assert fingerprint.source_fingerprint(a) == fingerprint.source_fingerprint(b)
    assert fingerprint.source_fingerprint(a) != fingerprint.source_fingerprint(c)


def test_a_second_writer_is_refused_and_deletes_nothing(small_config, standins, tmp_path: Path):
    out = tmp_path / "out"
    live_temporary = out / "runs" / ".eps__1.csv.live.tmp"
    live_temporary.parent.mkdir(parents=True)
    live_temporary.write_text("a live writer's half-written file")
    with FolderLock(out):  # a live writer holds the folder
        with pytest.raises(
            ConfigError, match=rf"{out} is being written by another experiment \(pid {os.getpid()}"
        ):
            runner.run_experiment(small_config, out, SerialBackend(), standins.fake_run)
        assert live_temporary.exists()
        assert not (out / "config.toml").exists()
    runner.run_experiment(small_config, out, SerialBackend(), standins.fake_run)
    assert not live_temporary.exists()  # stale once no writer holds the lock


def test_two_experiments_started_on_one_folder(small_config, standins, tmp_path: Path):
    """A second process started on a folder that a first is writing is refused at once; the
    first finishes every run, each verified."""
    small_config = config_module.with_overrides(small_config, runs=2)
    out, log = tmp_path / "out", tmp_path / "computed.log"
    script = textwrap.dedent(f"""
        import sys, standins
        from pathlib import Path
        from experiments.config import ConfigError, parse_config
        from experiments.runner import run_experiment
        from experiments.backends import SerialBackend
        config = parse_config({config_module.to_dict(small_config)!r}, source="small.toml")
        try:
            run_experiment(config, Path({str(out)!r}), SerialBackend(), standins.fake_run)
        except ConfigError as error:
            print(error)
            sys.exit(2)
    """)
    env = {
        **os.environ,
        "STANDIN_LOG": str(log),
        "STANDIN_SLEEP": "0.6",
        "PYTHONPATH": f"{HERE}:{os.environ.get('PYTHONPATH', '')}",
    }
    first = subprocess.Popen([sys.executable, "-c", script], env=env)
    deadline = time.monotonic() + 60
    lock = out / ".lock"
    while not (lock.exists() and lock.read_text()) and time.monotonic() < deadline:
        time.sleep(0.02)  # the first holds the folder
    second = subprocess.run(
        [sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=60
    )
    assert first.wait(timeout=60) == 0
    assert second.returncode == 2
    assert "being written by another experiment" in second.stdout
    assert sorted(_computed(log)) == sorted(spec.name for spec in runner.plan(small_config))
    state = runner.inspect_folder(small_config, out, standins.fake_run)
    assert len(state.finished) == 4


def test_inputs_that_change_while_running_are_not_stored(small_config, standins, tmp_path: Path):
    def lying_task(spec):
        result = standins.fake_run(spec)
        inputs = fingerprint.run_inputs(
            spec.experiment, spec.strategy, spec.env, spec.seed, lying_task
        )
        inputs["layout"] = "0" * 64  # the worker loaded another layout than expected
        return store.RunResult(**{**result.__dict__, "inputs": inputs})

    out = tmp_path / "out"
    with pytest.raises(ConfigError, match=r"inputs changed while the experiment ran \(layout\)"):
        runner.run_experiment(small_config, out, SerialBackend(), lying_task)
    assert not list((out / "runs").glob("*.json"))


# --- a folder's config.toml always describes its report ------------------------------------


def _report_only(config, out: Path, standins) -> None:
    from experiments.jobs import Experiment

    Experiment(config, out, task=standins.fake_run).report()


def test_report_only_records_changed_report_settings(small_data, standins, tmp_path: Path):
    """Changing a report setting (final_window) and reporting again once left the folder's
    config.toml at the old value beside a report computed with the new one."""
    out = tmp_path / "out"
    config = parse_config(small_data, source="small.toml")
    runner.run_experiment(config, out, SerialBackend(), standins.fake_run)
    runs_before = {p.name: p.read_bytes() for p in (out / "runs").iterdir()}
    _report_only(config, out, standins)
    assert "of the last 20 episodes" in (out / "report.md").read_text()
    small_data["experiment"]["final_window"] = 30
    wider = parse_config(small_data, source="small.toml")
    _report_only(wider, out, standins)
    recorded = config_module.load_config(out / runner.CONFIG_FILE)
    assert recorded.final_window == 30
    assert "of the last 30 episodes" in (out / "report.md").read_text()
    # the description is the report's too
    small_data["experiment"]["description"] = "a new description"
    _report_only(parse_config(small_data, source="small.toml"), out, standins)
    assert config_module.load_config(out / runner.CONFIG_FILE).description == "a new description"
    assert "a new description" in (out / "report.md").read_text()
    assert {p.name: p.read_bytes() for p in (out / "runs").iterdir()} == runs_before
    # a run with the new file finds every run finished: nothing is recomputed or refused
    assert runner.run_experiment(wider, out, SerialBackend(), standins.fake_run) == []


def test_report_only_refuses_a_file_that_changes_runs(small_data, standins, tmp_path: Path):
    out = tmp_path / "out"
    runner.run_experiment(
        parse_config(small_data, source="small.toml"), out, SerialBackend(), standins.fake_run
    )
    recorded_before = (out / runner.CONFIG_FILE).read_bytes()
    small_data["experiment"]["seed"] += 1
    small_data["experiment"]["final_window"] = 30
    other = parse_config(small_data, source="small.toml")
    with pytest.raises(ConfigError, match=r"different experiment \(differs in experiment\.seed\)"):
        _report_only(other, out, standins)
    assert (out / runner.CONFIG_FILE).read_bytes() == recorded_before
    assert not (out / "report.md").exists()


def test_a_run_with_changed_report_settings_is_recorded(small_data, standins, tmp_path: Path):
    out = tmp_path / "out"
    runner.run_experiment(
        parse_config(small_data, source="small.toml"), out, SerialBackend(), standins.fake_run
    )
    small_data["experiment"]["smoothing_window"] = 15
    small_data["experiment"]["convergence_tolerance"] = 0.2
    changed = parse_config(small_data, source="small.toml")
    assert runner.run_experiment(changed, out, SerialBackend(), standins.fake_run) == []
    recorded = config_module.load_config(out / runner.CONFIG_FILE)
    assert (recorded.smoothing_window, recorded.convergence_tolerance) == (15, 0.2)


def test_report_only_on_an_unchanged_file_needs_no_lock(small_config, standins, tmp_path: Path):
    """A report can be read while another process holds the folder (a run going on)."""
    out = tmp_path / "out"
    runner.run_experiment(small_config, out, SerialBackend(), standins.fake_run)
    with FolderLock(out):
        _report_only(small_config, out, standins)
        assert (out / "report.md").exists()
        changed = dataclasses.replace(small_config, final_window=30)
        with pytest.raises(ConfigError, match="being written by another experiment"):
            _report_only(changed, out, standins)


def test_task_report_settings_are_told_apart_from_run_settings():
    from experiments.config import run_differences, same_experiment

    config = config_module.load_config("other_tasks")
    first = config.tasks[0]
    moved = dataclasses.replace(first, random_return=first.random_return + 1.0)
    changed = dataclasses.replace(config, tasks=(moved, *config.tasks[1:]))
    found = same_experiment(config, changed)
    assert found == [f"task[{first.name}].random_return"]
    assert run_differences(found) == []
    capped = dataclasses.replace(first, env=dataclasses.replace(first.env, max_episode_steps=50))
    assert run_differences(
        same_experiment(config, dataclasses.replace(config, tasks=(capped, *config.tasks[1:])))
    ) == [f"task[{first.name}].max_episode_steps"]


def test_a_physics_engine_version_is_an_input_of_its_envs(monkeypatch: pytest.MonkeyPatch):
    """Gymnasium's MuJoCo and Box2D envs step another engine, whose upgrade is other physics:
    its version joins their env fingerprint (Gymnasium's own version is in the code's). Shown
    on CartPole by treating its module as an engine's, since neither engine is installed here;
    an env outside ``ENGINES`` keeps the fingerprint it had."""
    from experiments.config import EnvSpec

    spec = EnvSpec(id="CartPole-v1", maze=None, robot=None, mode=None, max_episode_steps=500)
    plain = fingerprint.env_fingerprint(spec)
    assert set(fingerprint.ENGINES) == {"gymnasium.envs.mujoco", "gymnasium.envs.box2d"}
    monkeypatch.setattr(fingerprint, "ENGINES", {"gymnasium.envs.classic_control": "engine"})
    monkeypatch.setattr(fingerprint, "_version", lambda package: "1.0")
    first = fingerprint.env_fingerprint(spec)
    monkeypatch.setattr(fingerprint, "_version", lambda package: "2.0")
    second = fingerprint.env_fingerprint(spec)
    assert len({plain, first, second}) == 3
    monkeypatch.setattr(fingerprint, "ENGINES", {"gymnasium.envs.mujoco": "mujoco"})
    assert fingerprint.env_fingerprint(spec) == plain
