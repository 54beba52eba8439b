"""Faults survived: a worker that dies costs only its run; the driver's death ends its workers;
Ctrl-C keeps the finished runs."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

import run
from experiments import config as config_module
from experiments import runner
from experiments.backends import ProcessBackend, SerialBackend, TasksLost

HERE = Path(__file__).resolve().parent
ROOT = Path(run.__file__).resolve().parent


def _alive(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie waiting for its reaper does not)."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (FileNotFoundError, ProcessLookupError, IndexError):
        return False
    return state != "Z"


def _children(pid: int) -> set[int]:
    found: set[int] = set()
    for task in Path(f"/proc/{pid}/task").iterdir():
        text = (task / "children").read_text().split()
        found |= {int(child) for child in text}
    return found


def _default_sigint() -> None:
    """In a child before it runs: SIGINT back to its default (see the Ctrl-C test)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _wait_for(condition, timeout: float = 60.0) -> None:
    deadline = time.monotonic() + timeout
    while not condition():
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.05)


def test_a_killed_worker_costs_only_its_run_which_is_retried(
    small_config, standins, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
):
    markers, victim = tmp_path / "died", runner.plan(small_config)[1].name
    markers.mkdir()
    monkeypatch.setenv("STANDIN_DIE_ONCE", str(markers))
    monkeypatch.setenv("STANDIN_DIE_NAME", victim)
    log = tmp_path / "computed.log"
    monkeypatch.setenv("STANDIN_LOG", str(log))
    computed = runner.run_experiment(
        small_config, tmp_path / "faulty", ProcessBackend(2), standins.fake_run
    )
    assert sorted(r.name for r in computed) == sorted(s.name for s in runner.plan(small_config))
    assert [p.name for p in markers.iterdir()] == [victim]  # its first worker was killed
    assert sorted(log.read_text().split()) == sorted(r.name for r in computed)  # once each
    monkeypatch.delenv("STANDIN_DIE_ONCE")
    monkeypatch.delenv("STANDIN_LOG")
    runner.run_experiment(small_config, tmp_path / "clean", SerialBackend(), standins.fake_run)
    for path in (tmp_path / "clean" / "runs").glob("*.csv"):
        assert path.read_bytes() == (tmp_path / "faulty" / "runs" / path.name).read_bytes()
    assert (tmp_path / "clean" / "episodes.csv").read_bytes() == (
        tmp_path / "faulty" / "episodes.csv"
    ).read_bytes()


def test_a_run_whose_workers_keep_dying_is_given_up_and_the_rest_finish(
    small_config, standins, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
):
    monkeypatch.setenv("STANDIN_ALWAYS_DIE", "adaptive+tabu")
    small_config = config_module.with_overrides(small_config, runs=2)
    stored: list[str] = []
    with pytest.raises(TasksLost) as error:
        runner.run_experiment(
            small_config,
            tmp_path,
            ProcessBackend(2, max_retries=1),
            standins.fake_run,
            on_result=lambda result: stored.append(result.name),
        )
    lost = sorted(item.task.name for item in error.value.lost)
    assert lost == sorted(s.name for s in runner.plan(small_config, ["adaptive+tabu"]))
    assert all(item.attempts == 2 for item in error.value.lost)
    assert "killed by signal 9" in str(error.value)
    assert sorted(stored) == sorted(s.name for s in runner.plan(small_config, ["eps"]))
    state = runner.inspect_folder(small_config, tmp_path, standins.fake_run)
    assert sorted(spec.name for spec, _ in state.finished) == sorted(stored)


DRIVER = """
import standins
from pathlib import Path
from experiments.backends import ProcessBackend
from experiments.config import parse_config
from experiments.runner import run_experiment
config = parse_config({config!r}, source="small.toml")
run_experiment(config, Path({out!r}), ProcessBackend(2), standins.fake_run)
"""


def test_the_drivers_death_takes_its_workers_with_it(small_config, tmp_path: Path):
    started = tmp_path / "started"
    script = DRIVER.format(config=config_module.to_dict(small_config), out=str(tmp_path / "out"))
    env = {
        **os.environ,
        "STANDIN_SLEEP": "60",
        "STANDIN_STARTED": str(started),
        "PYTHONPATH": f"{HERE}:{os.environ.get('PYTHONPATH', '')}",
    }
    driver = subprocess.Popen([sys.executable, "-c", textwrap.dedent(script)], env=env)
    try:
        _wait_for(lambda: started.exists() and len(started.read_text().split()) == 2)
        workers = {int(pid) for pid in started.read_text().split()}
        helpers = _children(driver.pid)  # the workers and multiprocessing's resource tracker
        assert workers <= helpers
    finally:
        driver.send_signal(signal.SIGKILL)
        driver.wait()
    _wait_for(lambda: not any(_alive(pid) for pid in helpers), timeout=10.0)


def test_ctrl_c_keeps_finished_runs_and_ends_the_workers(standins, tmp_path: Path):
    config = standins.tiny_config(tmp_path, episodes=20, cap=300, runs=3)
    out = tmp_path / "interrupted"
    command = [
        sys.executable,
        str(ROOT / "run.py"),
        "experiment",
        str(config),
        "--workers",
        "2",
        "--no-progress",
        "--out",
        str(out),
    ]
    # A user's Ctrl-C reaches a foreground process. A test runner started in the background
    # (`cmd &` in a script) ignores SIGINT, and its children inherit that: Python then installs
    # no KeyboardInterrupt handler and the experiment would run to its end. So the driver
    # starts with SIGINT at its default, as in a terminal.
    driver = subprocess.Popen(
        command,
        cwd=ROOT,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=_default_sigint,
    )
    _wait_for(lambda: list((out / "runs").glob("*.json")))
    helpers = _children(driver.pid)
    driver.send_signal(signal.SIGINT)
    _, stderr = driver.communicate(timeout=60)
    assert driver.returncode == 130, stderr
    assert "finished runs are kept" in stderr
    assert "Traceback" not in stderr
    _wait_for(lambda: not any(_alive(pid) for pid in helpers), timeout=10.0)
    loaded = config_module.load_config(config)
    state = runner.inspect_folder(loaded, out)
    assert 1 <= len(state.finished) < 9
    assert not state.invalid
    assert not list((out / "runs").glob(".*.tmp"))
