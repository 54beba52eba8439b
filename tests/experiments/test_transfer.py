"""run.py transfer at a tiny scale: saved agents, the grid, files, report, resume, integrity,
worker-count invariance, and bad names (issue 11 item 3)."""

from __future__ import annotations

import copy
import json
import shutil
from pathlib import Path
from typing import Any

import numpy as np
import pybullet_data
import pytest

import run
from experiments import config as config_module
from experiments import fingerprint, runner, store
from experiments import transfer as transfer_module
from experiments.backends import ProcessBackend, SerialBackend
from experiments.config import ConfigError, parse_config
from experiments.transfer import Transfer, parse_spec
from experiments.transfer_cell import Condition, cell_seed

TRAIN = {
    "experiment": {"name": "tiny", "seed": 5, "runs": 2, "episodes": 3, "save_agents": True},
    "env": {"maze": "open", "robot": "disc", "mode": "kinematic", "max_episode_steps": 60},
    "strategy": [
        {
            "name": "grid",
            "agent": "grid",
            "resolution": 5,
            "exploration": "epsilon-greedy",
            "exploration_params": {"epsilon": 0.015},
        }
    ],
}
SPEC: dict[str, Any] = {
    "transfer": {"name": "tiny", "agents": [], "episodes": 2, "max_episode_steps": 25},
    "conditions": {
        "robots": ["disc"],
        "modes": ["kinematic", "dynamic"],
        "levels": ["none", "moderate"],
    },
}


@pytest.fixture(scope="module")
def trained(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A tiny experiment whose two runs saved their agents."""
    folder = tmp_path_factory.mktemp("train") / "tiny"
    runner.run_experiment(parse_config(copy.deepcopy(TRAIN), "tiny.toml"), folder)
    return folder


def _spec(agents: list[str], **changes: Any) -> Any:
    data = copy.deepcopy(SPEC)
    data["transfer"]["agents"] = agents
    data["transfer"].update(changes)
    return parse_spec(data, "tiny_transfer.toml")


def _files(out: Path) -> dict[str, bytes]:
    return {str(p.relative_to(out)): p.read_bytes() for p in sorted((out / "cells").rglob("*.csv"))}


def test_save_agents_stores_a_verified_policy(trained: Path):
    runs = sorted((trained / "runs").glob("*.agent.npz"))
    assert len(runs) == 2
    name = runs[0].name[: -len(".agent.npz")]
    meta = json.loads((trained / "runs" / f"{name}.json").read_text())
    assert meta["agent_bytes"] == runs[0].stat().st_size
    config = config_module.load_config(trained / "config.toml")
    assert config.save_agents
    assert not runner.inspect_folder(config, trained).pending


def test_an_edited_agent_file_makes_its_run_recompute(trained: Path, tmp_path: Path):
    copy_of = tmp_path / "tiny"
    shutil.copytree(trained, copy_of)
    agent = next((copy_of / "runs").glob("*.agent.npz"))
    agent.write_bytes(agent.read_bytes() + b"x")
    config = config_module.load_config(copy_of / "config.toml")
    state = runner.inspect_folder(config, copy_of)
    assert [spec.name for spec in state.pending] == [agent.name[: -len(".agent.npz")]]
    assert "differs from its sidecar" in state.checks[state.pending[0].name].reason


def test_end_to_end_files_report_and_resume(trained: Path, tmp_path: Path):
    out = tmp_path / "transfer"
    job = Transfer(_spec([str(trained)]), out)
    assert len(job.agents) == 2
    # per agent: its training condition + disc x 2 modes x 2 levels
    assert len(job.cells) == 2 * 5
    assert not job.skipped
    computed = job.run()
    assert len(computed) == 10
    report = job.report()
    for name in ("report.md", "cells.csv", "summary.csv", "success.png", "steps_ratio.png"):
        assert (out / name).is_file(), name
    text = report.path.read_text()
    assert "| grid disc kinematic | open | disc | dynamic | moderate | 2 |" in text
    train_rows = [r for r in report.cells if r.level == "train"]
    assert len(train_rows) == 2
    assert all(r.gap == 0.0 for r in train_rows)
    for row in report.cells:
        assert row.gap == pytest.approx(row.success_rate - row.train_success_rate)
    before = _files(out)

    again = Transfer(_spec([str(trained)]), out)
    assert again.run() == []  # every finished cell verifies: nothing to compute
    victim = next(iter(before))
    (out / victim).unlink()  # a cell lost (a kill between its two files)
    sidecar = (out / next(iter(list(before)[1:]))).with_suffix(".json")
    sidecar.write_text(sidecar.read_text().replace('"episodes": 2', '"episodes": 3'))
    recomputed = Transfer(_spec([str(trained)]), out).run()
    assert len(recomputed) == 2
    assert _files(out) == before  # the same numbers, bit for bit


STATIC_URDF = """<?xml version="1.0"?>
<robot name="static">
  <link name="base">
    <inertial><mass value="0"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
    <collision><geometry><cylinder radius="0.5" length="0.2"/></geometry></collision>
  </link>
</robot>
"""


def test_a_condition_the_agent_cannot_act_in_is_listed_with_its_reason(
    trained: Path, tmp_path: Path
):
    # A base of mass 0 cannot move in dynamic mode: that condition is skipped, with the reason.
    (tmp_path / "static.urdf").write_text(STATIC_URDF)
    urdf = tmp_path / "static.toml"
    urdf.write_text('urdf = "static.urdf"\ndrive = "holonomic"\n')
    data = copy.deepcopy(SPEC)
    data["transfer"]["agents"] = [str(trained)]
    data["conditions"]["robots"] = [str(urdf)]
    data["conditions"]["levels"] = ["none"]
    job = Transfer(parse_spec(data, "tiny_transfer.toml"), tmp_path / "transfer")
    # per agent: its training condition + the static robot in kinematic mode
    assert len(job.cells) == 2 * 2
    assert {(s.condition.robot, s.condition.mode) for s in job.skipped} == {(str(urdf), "dynamic")}
    assert "mass 0" in job.skipped[0].reason


def test_changed_inputs_are_refused_by_name(trained: Path, tmp_path: Path):
    out = tmp_path / "transfer"
    Transfer(_spec([str(trained)]), out).run()
    with pytest.raises(ConfigError, match=r"other inputs .*episodes"):
        Transfer(_spec([str(trained)], episodes=3), out).run()
    with pytest.raises(ConfigError, match=r"other inputs .*max_episode_steps"):
        Transfer(_spec([str(trained)], max_episode_steps=30), out).run()


def test_a_retrained_agent_is_refused(trained: Path, tmp_path: Path):
    first, second = sorted((trained / "runs").glob("*.agent.npz"))
    folder = tmp_path / "one"
    folder.mkdir()
    shutil.copy(first, folder / "agent.npz")
    config = config_module.load_config(trained / "config.toml")
    store.atomic_write_text(folder / "config.toml", config_module.dumps(config))
    seed = int(first.name.split("__")[1].split(".")[0])
    (folder / "meta.json").write_text(json.dumps({"seed": seed}))
    out = tmp_path / "transfer"
    Transfer(_spec([str(folder)]), out).run()
    shutil.copy(second, folder / "agent.npz")  # another agent in its place
    with pytest.raises(ConfigError, match=r"other inputs \(agent"):
        Transfer(_spec([str(folder)]), out).run()


def test_the_numbers_do_not_depend_on_the_worker_count(trained: Path, tmp_path: Path):
    data = copy.deepcopy(SPEC)
    data["transfer"]["agents"] = [str(trained)]
    data["conditions"] = {"robots": ["disc"], "modes": ["dynamic"], "levels": ["moderate"]}
    spec = parse_spec(data, "t.toml")
    Transfer(spec, tmp_path / "serial").run(SerialBackend())
    Transfer(spec, tmp_path / "two").run(ProcessBackend(2))
    serial, two = _files(tmp_path / "serial"), _files(tmp_path / "two")
    assert serial == two
    assert len(serial) == 4


def test_cell_seeds_are_per_agent_and_condition():
    here = Condition("disc", "dynamic", "none")
    assert cell_seed(1, here, "L") == cell_seed(1, here, "L")
    others = {
        cell_seed(2, here, "L"),
        cell_seed(1, Condition("husky", "dynamic", "none"), "L"),
        cell_seed(1, Condition("disc", "kinematic", "none"), "L"),
        cell_seed(1, Condition("disc", "dynamic", "strong"), "L"),
        cell_seed(1, here, "M"),
    }
    assert cell_seed(1, here, "L") not in others
    assert len(others) == 5


def test_a_layout_filter_keeps_only_its_agents(trained: Path, tmp_path: Path):
    data = copy.deepcopy(SPEC)
    data["transfer"]["agents"] = [str(trained)]
    data["conditions"]["layouts"] = ["paper"]
    with pytest.raises(ConfigError, match="no condition applies"):
        Transfer(parse_spec(data, "t.toml"), tmp_path / "t")


@pytest.mark.parametrize(
    ("key", "value", "named"),
    [
        ("robots", ["nosuch"], "robot 'nosuch'"),
        ("modes", ["fast"], "unknown mode 'fast'"),
        ("levels", ["extreme"], "unknown perturbation level 'extreme'"),
        ("layouts", ["nowhere"], "layout 'nowhere'"),
        ("robots", "disc,husky", "robot 'disc,husky'"),
        ("levels", [1], "expected a list of names"),
        ("modes", [], "at least one name"),
        ("levels", ["none", "none"], "given twice"),
    ],
)
def test_bad_condition_names_are_named(key: str, value: Any, named: str):
    data = copy.deepcopy(SPEC)
    data["conditions"][key] = value
    with pytest.raises(ConfigError, match=r"tiny_transfer.toml: \[conditions\]") as error:
        parse_spec(data, "tiny_transfer.toml")
    assert named in str(error.value)
    assert key in str(error.value)


@pytest.mark.parametrize(
    ("table", "key", "value", "named"),
    [
        ("transfer", "episodes", 0, "[transfer] episodes"),
        ("transfer", "episodes", True, "[transfer] episodes"),
        ("transfer", "max_episode_steps", 1.5, "[transfer] max_episode_steps"),
        ("transfer", "name", "a/b", "[transfer] name"),
        ("transfer", "typo", 1, "[transfer] typo: unknown key"),
        ("conditions", "robot", ["disc"], "[conditions] robot: unknown key"),
    ],
)
def test_bad_values_are_named(table: str, key: str, value: Any, named: str):
    data = copy.deepcopy(SPEC)
    data[table][key] = value
    with pytest.raises(ConfigError) as error:
        parse_spec(data, "t.toml")
    assert named in str(error.value)


def _fails(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    with pytest.raises(SystemExit) as exit_info:
        run.main(argv)
    assert exit_info.value.code == 2
    error = capsys.readouterr().err
    assert "Traceback" not in error
    return error


@pytest.mark.parametrize(
    ("options", "named"),
    [
        (["--levels", "extreme"], "option --levels: unknown perturbation level 'extreme'"),
        (["--robots", "disc,tank"], "option --robots: robot 'tank'"),
        (["--modes", "slow"], "option --modes: unknown mode 'slow'"),
        (["--layouts", "nowhere"], "option --layouts: layout 'nowhere'"),
        (["--episodes", "0"], "--episodes"),
    ],
)
def test_the_cli_names_a_bad_option(trained: Path, options, named, capsys, tmp_path: Path):
    argv = ["transfer", "--agents", str(trained), "--out", str(tmp_path / "t"), *options]
    assert named in _fails(argv, capsys)


def test_the_cli_names_bad_agent_sources(tmp_path: Path, capsys):
    assert "agent source not found" in _fails(["transfer", "--agents", str(tmp_path / "x")], capsys)
    assert "give a transfer file" in _fails(["transfer"], capsys)
    assert "nosuch_transfer" in _fails(["transfer", "nosuch_transfer"], capsys)
    folder = tmp_path / "exp"
    runner.prepare_folder(
        parse_config({**copy.deepcopy(TRAIN), "experiment": {"name": "e"}}, "e"), folder
    )
    (folder / "runs").mkdir()
    assert "did not save their agents" in _fails(["transfer", "--agents", str(folder)], capsys)


def test_the_cli_runs_and_resumes(trained: Path, tmp_path: Path, capsys):
    argv = ["transfer", "--agents", str(trained), "--robots", "disc", "--modes", "kinematic"]
    argv += ["--levels", "none", "--episodes", "1", "--out", str(tmp_path / "t")]
    argv += ["--backend", "serial", "--no-progress"]
    assert run.main(argv) == 0
    first = capsys.readouterr().out
    assert "4 cells" in first
    assert "computed 4 cells" in first
    assert run.main(argv) == 0
    second = capsys.readouterr().out
    assert "4 already done" in second
    assert "computed" not in second
    summary = (tmp_path / "t" / "summary.csv").read_text().splitlines()
    assert len(summary) == 1 + 2  # the training condition and kinematic/none (the same env)
    values = np.array([float(line.split(",")[6]) for line in summary[1:]])
    assert ((values >= 0) & (values <= 1)).all()


def test_failing_episodes_are_replayed_exactly_and_drawn(trained: Path, tmp_path: Path):
    from experiments.transfer_traces import failing_cells, replay

    out = tmp_path / "transfer"
    job = Transfer(_spec([str(trained)]), out)
    job.run()
    state = job.status()
    for cell in state.finished[:4]:
        stored = state.checks[cell.name].columns
        assert stored is not None
        for episode in (1, 2):
            trace, _ = replay(cell, episode)
            assert len(trace.positions) - 1 == stored["steps"][episode - 1]
            assert trace.success == bool(stored["success"][episode - 1])
            assert trace.collisions.size == stored["collisions"][episode - 1]
    picks = failing_cells(state, limit=2)
    assert picks, "the 3-episode agents fail somewhere at the moderate level"
    report = job.report(traces=2)
    assert (out / "failures.png").is_file()
    assert "failures.png" in report.path.read_text()


def test_ray_backend_gives_the_same_cells(trained: Path, tmp_path: Path):
    pytest.importorskip("ray")
    from experiments.backends import make_backend

    data = copy.deepcopy(SPEC)
    data["transfer"]["agents"] = [str(trained)]
    data["conditions"] = {"robots": ["disc"], "modes": ["dynamic"], "levels": ["strong"]}
    spec = parse_spec(data, "t.toml")
    Transfer(spec, tmp_path / "serial").run(SerialBackend())
    Transfer(spec, tmp_path / "ray").run(make_backend("ray", 2))
    assert _files(tmp_path / "ray") == _files(tmp_path / "serial")


def test_a_killed_transfer_loses_no_finished_cell(trained: Path, tmp_path: Path):
    import os
    import signal
    import subprocess
    import sys
    import time

    out = tmp_path / "t"
    argv = [sys.executable, str(Path(run.__file__)), "transfer", "--agents", str(trained)]
    argv += ["--robots", "disc,husky", "--modes", "dynamic", "--levels", "none,strong"]
    argv += ["--episodes", "2", "--max-episode-steps", "25", "--out", str(out)]
    argv += ["--backend", "serial", "--no-progress"]
    env = {**os.environ, "PYTHONPATH": str(Path(run.__file__).parent)}
    process = subprocess.Popen(argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 60
    while not list((out / "cells").rglob("*.json")) and time.monotonic() < deadline:
        time.sleep(0.05)
    process.send_signal(signal.SIGKILL)
    process.wait()
    kept = {p: p.read_bytes() for p in (out / "cells").rglob("*.*")}
    assert kept, "the transfer was killed before its first cell"
    finished = len([p for p in kept if p.suffix == ".json"])
    assert finished < 10, "the transfer finished before it was killed"
    result = subprocess.run(argv, env=env, capture_output=True, text=True, check=True)
    assert f"{finished} already done" in result.stdout
    assert f"computed {10 - finished} cells" in result.stdout
    for path, data in kept.items():
        if path.suffix == ".json" or path.with_suffix(".json") in kept:
            assert path.read_bytes() == data  # finished cells untouched


def test_agents_may_be_named_by_a_pattern(trained: Path, tmp_path: Path):
    pattern = str(trained / "runs" / "*.agent.npz")
    job = Transfer(_spec([pattern]), tmp_path / "t")
    assert sorted(a.key for a in job.agents) == sorted(
        a.key for a in Transfer(_spec([str(trained)]), tmp_path / "u").agents
    )
    with pytest.raises(ConfigError, match="matches no file"):
        Transfer(_spec([str(trained / "runs" / "nothing*")]), tmp_path / "v")


def test_a_robot_that_tips_over_is_counted_at_the_cap_and_named(trained: Path, tmp_path: Path):
    urdf = Path(pybullet_data.getDataPath()) / "r2d2.urdf"
    robot = tmp_path / "r2d2.toml"
    robot.write_text(
        f'urdf = "{urdf}"\ndrive = "differential"\n[wheels]\n'
        'left = ["left_front_wheel_joint", "left_back_wheel_joint"]\n'
        'right = ["right_front_wheel_joint", "right_back_wheel_joint"]\n'
    )
    data = copy.deepcopy(SPEC)
    data["transfer"].update(agents=[str(trained)], max_episode_steps=12)
    data["conditions"] = {"robots": [str(robot)], "modes": ["dynamic"], "levels": ["none"]}
    out = tmp_path / "transfer"
    job = Transfer(parse_spec(data, "tip_transfer.toml"), out)
    job.run()
    report = job.report()
    fell = [r for r in report.cells if r.robot == "r2d2"]
    assert fell
    assert all(r.tipped == 1.0 for r in fell)  # the r2d2 falls within 12 steps
    assert all(r.mean_steps == 12.0 and r.success_rate == 0.0 for r in fell)
    assert all(r.tipped == 0.0 for r in report.cells if r.robot == "disc")
    text = report.path.read_text()
    assert "## Robots that tipped over" in text
    assert "r2d2 / dynamic / none in open: 2 of 2 episodes" in text
    header = (out / "cells.csv").read_text().splitlines()[0].split(",")
    assert "tipped" in header


def test_two_robots_of_one_file_name_are_refused_before_their_cells_collide(tmp_path: Path):
    """Cells and report rows are named by the robot's file stem: the shipped ``husky`` and a
    user's ``.../husky.urdf`` would share every cell name (the second cell was refused mid-run
    as "its inputs changed"). The grid is refused at once, naming both."""
    urdf = Path(pybullet_data.getDataPath()) / "husky" / "husky.urdf"
    data = copy.deepcopy(SPEC)
    data["conditions"]["robots"] = ["husky", str(urdf)]
    with pytest.raises(ConfigError, match=r"\[conditions\] robots: robots 'husky' and") as error:
        parse_spec(data, "tiny_transfer.toml")
    assert f"{str(urdf)!r} would both be named 'husky'" in str(error.value)
    renamed = tmp_path / "my_husky.urdf"
    renamed.write_text(urdf.read_text().replace('filename="', f'filename="{urdf.parent}/'))
    data["conditions"]["robots"] = ["husky", str(renamed)]
    assert parse_spec(data, "tiny_transfer.toml").conditions.robots == ("husky", str(renamed))


def test_a_bare_urdf_runs_at_every_level_with_the_drive_the_env_detects(
    trained: Path, tmp_path: Path
):
    """A bare URDF declares no drive; the perturbation levels need one. It is read off the
    joints as the env does (pybullet's husky: differential), where it used to be refused."""
    from bullet_maze.perturbations import level_settings
    from bullet_maze.robots import robot_drive
    from experiments.transfer import condition_env

    urdf = str(Path(pybullet_data.getDataPath()) / "husky" / "husky.urdf")
    assert robot_drive(urdf) == "differential"
    assert robot_drive("husky") == "differential"
    assert robot_drive("disc") == "holonomic"
    data = copy.deepcopy(SPEC)
    data["transfer"].update(agents=[str(trained)], max_episode_steps=6)
    data["conditions"] = {"robots": [urdf], "modes": ["dynamic"], "levels": ["none", "strong"]}
    job = Transfer(parse_spec(data, "urdf_transfer.toml"), tmp_path / "transfer")
    strong = next(c for c in job.cells if c.condition.level == "strong")
    expected = level_settings("strong", mode="dynamic", drive="differential")
    env = condition_env(strong.agent, strong.condition, 6)
    assert {k: env.params[k] for k in expected} == {
        k: list(v) if isinstance(v, tuple) else v for k, v in expected.items()
    }
    assert "torque_scale" in expected  # (a motor perturbation: the drive was not holonomic)
    job.run()
    rows = job.report().cells
    assert {(r.robot, r.level) for r in rows} >= {("husky", "none"), ("husky", "strong")}


@pytest.mark.parametrize("tipped", [-1, 3, True, 1.5, "1"])
def test_a_sidecar_with_an_impossible_fall_count_is_invalid(
    trained: Path, tmp_path: Path, tipped: Any
):
    out = tmp_path / "transfer"
    job = Transfer(_spec([str(trained)]), out)
    job.run()
    cell = job.cells[0]
    _, sidecar = transfer_module.cell_paths(out, cell.name)
    meta = json.loads(sidecar.read_text())
    meta.pop("sidecar_sha256")
    meta["tipped"] = tipped  # re-hashed, so only the count itself is wrong
    meta["sidecar_sha256"] = fingerprint.digest(meta)
    sidecar.write_text(json.dumps(meta))
    check = transfer_module.check_cell(out, cell, {})
    assert check.status == "invalid"
    assert f"tipped is {tipped!r} of 2 episodes" in str(check.reason)


def test_an_experiment_with_no_verified_run_says_why(trained: Path, tmp_path: Path):
    """Runs of another code version do not count without --accept-code-change; the refusal
    says so, with the count, where it said only "no finished run that verifies"."""
    folder = tmp_path / "copy"
    shutil.copytree(trained, folder)
    for sidecar in (folder / "runs").glob("*.json"):
        meta = json.loads(sidecar.read_text())
        meta["inputs"]["code"] = {**meta["inputs"]["code"], "sources": "another version"}
        meta.pop("sidecar_sha256")
        meta["sidecar_sha256"] = fingerprint.digest(meta)
        sidecar.write_text(json.dumps(meta))
    with pytest.raises(ConfigError, match=r"its runs: 2 computed by another code version "):
        Transfer(_spec([str(folder)]), tmp_path / "out").run()
    Transfer(_spec([str(folder)]), tmp_path / "out", accept_code_change=True).run()


def test_a_saved_baseline_is_evaluated_and_its_failures_drawn(tmp_path: Path):
    """The tile coder saves its agent (``agent.baseline_files``); the transfer plays it in every
    condition, and its failing episodes are drawn over the maze (it has no partition)."""
    data = copy.deepcopy(TRAIN)
    data["strategy"] = [{"name": "tile", "agent": "tile", "agent_params": {"epsilon": 0.1}}]
    folder = tmp_path / "tile"
    runner.run_experiment(parse_config(data, "tile.toml"), folder)
    out = tmp_path / "transfer"
    job = Transfer(_spec([str(folder)]), out)
    job.run()
    assert len(job.status().finished) == len(job.cells) > 0
    job.report(traces=1)
    assert (out / "failures.png").is_file()
