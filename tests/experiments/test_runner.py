"""The runner with a stand-in learner: files, resume, determinism across backends."""

from __future__ import annotations

import csv
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from experiments import config as config_module
from experiments import runner, store
from experiments.backends import ProcessBackend, SerialBackend, make_backend
from experiments.config import ConfigError, with_overrides


def _computed(log: Path) -> list[str]:
    return log.read_text().split() if log.exists() else []


def test_serial_run_writes_every_file(small_config, standins, tmp_path: Path):
    computed = runner.run_experiment(small_config, tmp_path, SerialBackend(), standins.fake_run)
    names = sorted(spec.name for spec in runner.plan(small_config))
    assert sorted(r.name for r in computed) == names
    assert sorted(p.stem for p in (tmp_path / "runs").glob("*.csv")) == names
    assert len(names) == 6
    assert all("__" in n for n in names)
    recorded = config_module.load_config(tmp_path / "config.toml")
    assert config_module.same_experiment(recorded, small_config) == []
    with (tmp_path / "episodes.csv").open() as handle:
        rows = list(csv.DictReader(handle))
    assert list(rows[0]) == ["strategy", "run", "seed", *store.COLUMNS]
    assert len(rows) == 2 * 3 * 120
    assert [r["strategy"] for r in rows[:: 3 * 120]] == ["eps", "adaptive+tabu"]
    assert {int(r["episode"]) for r in rows} == set(range(1, 121))
    assert all(0 < int(r["steps"]) <= 300 for r in rows)


def test_common_seeds_across_strategies(small_config):
    specs = runner.plan(small_config)
    by_run: dict[int, set[int]] = {}
    for spec in specs:
        by_run.setdefault(spec.run_index, set()).add(spec.seed)
    assert all(len(seeds) == 1 for seeds in by_run.values())
    assert len({next(iter(s)) for s in by_run.values()}) == small_config.runs


def test_resume_computes_only_what_is_missing(
    small_config, standins, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
):
    log = tmp_path / "computed.log"
    monkeypatch.setenv("STANDIN_LOG", str(log))
    out = tmp_path / "out"
    runner.run_experiment(small_config, out, SerialBackend(), standins.fake_run)
    assert len(_computed(log)) == 6
    first = (out / "episodes.csv").read_bytes()
    mtimes = {p.name: p.stat().st_mtime_ns for p in (out / "runs").iterdir()}
    assert runner.run_experiment(small_config, out, SerialBackend(), standins.fake_run) == []
    assert len(_computed(log)) == 6
    assert {p.name: p.stat().st_mtime_ns for p in (out / "runs").iterdir()} == mtimes
    more = with_overrides(small_config, runs=4)
    added = runner.run_experiment(more, out, SerialBackend(), standins.fake_run)
    assert sorted(r.run_index for r in added) == [3, 3]
    assert (out / "episodes.csv").read_bytes().startswith(first.split(b"\n")[0])


def test_only_computes_a_subset_and_the_rest_completes_later(
    small_config, standins, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
):
    log = tmp_path / "computed.log"
    monkeypatch.setenv("STANDIN_LOG", str(log))
    out = tmp_path / "out"
    first = runner.run_experiment(
        small_config, out, SerialBackend(), standins.fake_run, only=["eps"]
    )
    assert {r.strategy for r in first} == {"eps"}
    assert len(first) == 3
    assert not (out / "episodes.csv").exists()
    loaded = runner.load_results(small_config, out, task=standins.fake_run)
    assert {name: len(runs) for name, runs in loaded.items()} == {
        "eps": 3,
        "adaptive+tabu": 0,
    }
    rest = runner.run_experiment(small_config, out, SerialBackend(), standins.fake_run)
    assert {r.strategy for r in rest} == {"adaptive+tabu"}
    assert len(rest) == 3
    runner.run_experiment(small_config, tmp_path / "whole", SerialBackend(), standins.fake_run)
    assert (out / "episodes.csv").read_bytes() == (tmp_path / "whole" / "episodes.csv").read_bytes()


def test_a_merged_file_of_an_earlier_plan_is_removed_until_the_new_plan_is_finished(
    small_config, standins, tmp_path: Path
):
    runner.run_experiment(small_config, tmp_path, SerialBackend(), standins.fake_run)
    assert (tmp_path / "episodes.csv").exists()
    more = with_overrides(small_config, runs=4)
    added = runner.run_experiment(more, tmp_path, SerialBackend(), standins.fake_run, only=["eps"])
    assert [r.run_index for r in added] == [3]
    assert not (tmp_path / "episodes.csv").exists()  # its 3 runs a strategy are no longer the plan
    runner.run_experiment(more, tmp_path, SerialBackend(), standins.fake_run)
    with (tmp_path / "episodes.csv").open() as handle:
        runs = {(r["strategy"], r["run"]) for r in csv.DictReader(handle)}
    assert len(runs) == 2 * 4


@pytest.mark.parametrize("only", [["nope"], []])
def test_only_names_unknown_strategies(small_config, standins, tmp_path: Path, only):
    with pytest.raises(ConfigError, match=r"--only.*(nope|no strategy).*adaptive\+tabu"):
        runner.run_experiment(small_config, tmp_path, SerialBackend(), standins.fake_run, only=only)


def test_a_folder_of_another_experiment_is_refused(small_config, standins, tmp_path: Path):
    runner.run_experiment(small_config, tmp_path, SerialBackend(), standins.fake_run)
    other = with_overrides(small_config, episodes=60)
    with pytest.raises(ConfigError, match=r"experiment\.episodes"):
        runner.run_experiment(other, tmp_path, SerialBackend(), standins.fake_run)


def test_one_and_two_workers_give_identical_csv(small_config, standins, tmp_path: Path):
    runner.run_experiment(small_config, tmp_path / "one", ProcessBackend(1), standins.fake_run)
    results = runner.run_experiment(
        small_config, tmp_path / "two", ProcessBackend(2), standins.fake_run
    )
    assert len({r.meta["pid"] for r in results}) == 2
    assert (tmp_path / "one" / "episodes.csv").read_bytes() == (
        tmp_path / "two" / "episodes.csv"
    ).read_bytes()
    for path in (tmp_path / "one" / "runs").glob("*.csv"):
        assert path.read_bytes() == (tmp_path / "two" / "runs" / path.name).read_bytes()


def test_resume_after_a_kill(
    small_config, standins, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
):
    out, log = tmp_path / "killed", tmp_path / "computed.log"
    script = textwrap.dedent(f"""
        import standins
        from experiments.config import parse_config
        from experiments.runner import run_experiment
        from experiments.backends import SerialBackend
        config = parse_config({config_module.to_dict(small_config)!r}, source="small.toml")
        run_experiment(config, __import__("pathlib").Path({str(out)!r}), SerialBackend(),
                       standins.fake_run)
    """)
    env = {**os.environ, "STANDIN_LOG": str(log), "STANDIN_SLEEP": "0.4"}
    process = subprocess.Popen([sys.executable, "-c", script], env=env)
    deadline = time.monotonic() + 60
    while len(list((out / "runs").glob("*.json"))) < 2 and time.monotonic() < deadline:
        time.sleep(0.05)
    process.send_signal(signal.SIGKILL)
    process.wait()
    finished = {p.stem for p in (out / "runs").glob("*.json")}  # the sidecar comes last
    assert 2 <= len(finished) < 6
    assert not (out / "episodes.csv").exists()
    before = len(_computed(log))

    monkeypatch.setenv("STANDIN_LOG", str(log))
    runner.run_experiment(small_config, out, SerialBackend(), standins.fake_run)
    recomputed = _computed(log)[before:]
    assert not finished & set(recomputed)
    assert sorted(recomputed) == sorted({s.name for s in runner.plan(small_config)} - finished)
    assert not list((out / "runs").glob(".*.tmp"))

    fresh = tmp_path / "fresh"
    monkeypatch.delenv("STANDIN_LOG")
    runner.run_experiment(small_config, fresh, SerialBackend(), standins.fake_run)
    assert (out / "episodes.csv").read_bytes() == (fresh / "episodes.csv").read_bytes()


def test_unknown_backend_is_named():
    with pytest.raises(ValueError, match="gpu"):
        make_backend("gpu")


def test_process_workers_get_one_blas_thread_and_the_parent_is_unchanged():
    names = ["OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS"]
    before = {name: os.environ.get(name) for name in names}
    seen = list(ProcessBackend(1).map_unordered(os.getenv, names))
    assert seen == [before[name] or "1" for name in names]
    assert {name: os.environ.get(name) for name in names} == before
