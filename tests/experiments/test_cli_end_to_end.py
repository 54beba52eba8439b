"""run.py end to end with the real environment and agent, at a tiny scale."""

from __future__ import annotations

import csv
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pybullet_data
import pytest

import run
from experiments import store

ROOT = Path(run.__file__).resolve().parent
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def assert_png(path: Path) -> None:
    data = path.read_bytes()
    assert data[:8] == PNG_SIGNATURE, path
    assert len(data) > 10_000, path


def read_csv(path: Path) -> list[dict[str, str]]:
    with path.open(newline="") as handle:
        return list(csv.DictReader(handle))


@pytest.fixture(scope="module")
def trained(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, str]:
    """A folder written by ``run.py train`` (small), and what it printed."""
    out = tmp_path_factory.mktemp("train") / "agent"
    argv = [
        "train",
        "--episodes",
        "6",
        "--max-episode-steps",
        "150",
        "--seed",
        "3",
        "--time-budget",
        "0",
        "--no-progress",
        "--out",
        str(out),
    ]
    result = subprocess.run(
        [sys.executable, str(ROOT / "run.py"), *argv],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=120,
        check=True,
    )
    return out, result.stdout


def test_train_writes_its_folder(trained):
    out, stdout = trained
    assert sorted(p.name for p in out.iterdir()) == [
        "agent.npz",
        "config.toml",
        "episodes.csv",
        "learning_curve.png",
        "meta.json",
        "partition.png",
        "policy.npz",
    ]
    rows = read_csv(out / "episodes.csv")
    assert list(rows[0]) == list(store.COLUMNS)
    assert [int(r["episode"]) for r in rows] == list(range(1, 7))
    for row in rows:
        steps = int(row["steps"])
        assert 1 <= steps <= 150
        assert row["success"] in {"0", "1"}
        if row["truncated"] == "1":
            assert steps == 150
        if steps < 150:
            assert row["success"] == "1"
        assert int(row["leaves"]) >= 1
        assert -2.0 * steps <= float(row["return"]) <= 5.0
    assert_png(out / "learning_curve.png")
    assert_png(out / "partition.png")
    for phrase in ("success rate", "vs optimal", "leaves:", "steps/s"):
        assert phrase in stdout


def test_same_seed_same_training(trained, tmp_path: Path):
    out, _ = trained
    assert (
        run.main(
            [
                "train",
                "--episodes",
                "6",
                "--max-episode-steps",
                "150",
                "--seed",
                "3",
                "--time-budget",
                "0",
                "--no-progress",
                "--out",
                str(tmp_path),
            ]
        )
        == 0
    )
    assert (tmp_path / "episodes.csv").read_bytes() == (out / "episodes.csv").read_bytes()


def test_default_job_runs_the_quick_config(tmp_path: Path, monkeypatch, capsys):
    (tmp_path / "q.toml").write_text(
        (ROOT / "experiments" / "quick.toml")
        .read_text()
        .replace("episodes = 4000", "episodes = 3")
        .replace("max_episode_steps = 5000", "max_episode_steps = 100")
    )
    monkeypatch.setattr(run, "DEFAULT_CONFIG", str(tmp_path / "q.toml"))
    monkeypatch.setattr(run, "RESULTS_DIR", tmp_path / "results")
    assert run.main([]) == 0
    folders = list((tmp_path / "results").iterdir())
    assert len(folders) == 1
    assert folders[0].name.startswith("paper__adaptive+tabu__")
    assert len(read_csv(folders[0] / "episodes.csv")) == 3
    printed = capsys.readouterr().out
    assert "training adaptive+tabu" in printed
    assert "all episodes done" in printed


def test_time_budget_stops_training(tmp_path: Path, capsys):
    assert (
        run.main(
            [
                "train",
                "--episodes",
                "1000",
                "--max-episode-steps",
                "100",
                "--time-budget",
                "0.01",
                "--no-progress",
                "--out",
                str(tmp_path),
            ]
        )
        == 0
    )
    assert len(read_csv(tmp_path / "episodes.csv")) < 1000
    assert "stopped by the time budget" in capsys.readouterr().out


def test_evaluate_in_dynamic_mode_with_the_husky(trained, capsys):
    out, _ = trained
    assert (
        run.main(
            [
                "evaluate",
                str(out),
                "--episodes",
                "1",
                "--mode",
                "dynamic",
                "--robot",
                "husky",
                "--max-episode-steps",
                "5",
            ]
        )
        == 0
    )
    printed = capsys.readouterr().out
    assert "the robot's heading dropped from the observation" in printed
    assert "success rate: 0.0%" in printed
    assert "mean 5.0" in printed


def test_evaluate_reports_success_and_steps(trained, capsys):
    from experiments import factory
    from experiments.config import load_config, with_overrides
    from experiments.evaluation import evaluate

    out, _ = trained
    assert (
        run.main(
            ["evaluate", str(out / "agent.npz"), "--episodes", "2", "--max-episode-steps", "50"]
        )
        == 0
    )
    printed = capsys.readouterr().out
    assert "2 greedy episodes" in printed
    agent = factory.load_agent(out / "agent.npz")
    config = with_overrides(load_config(out / "config.toml"), max_episode_steps=50)
    env = factory.make_env(config.env)
    result = evaluate(env, agent, 2, seed=0)
    env.close()
    assert f"success rate: {result.success_rate:.1%}" in printed
    assert f"mean {result.steps.mean():.1f}" in printed
    for episode in result.episodes:
        assert episode.positions.shape == (episode.steps + 1, 2)
        assert episode.steps <= 50
        assert episode.success or episode.truncated


def test_render_writes_a_gif(trained, tmp_path: Path):
    out, _ = trained
    gif = tmp_path / "episode.gif"
    assert (
        run.main(
            [
                "render",
                str(out),
                "--out",
                str(gif),
                "--max-episode-steps",
                "20",
                "--max-frames",
                "5",
            ]
        )
        == 0
    )
    assert gif.read_bytes()[:6] == b"GIF89a"


def test_evaluate_and_render_say_when_the_robot_tipped(trained, tmp_path: Path, capsys):
    out, _ = trained
    r2d2 = str(Path(pybullet_data.getDataPath()) / "r2d2.urdf")
    common = ["--robot", r2d2, "--mode", "dynamic", "--max-episode-steps", "12"]
    assert run.main(["evaluate", str(out), *common, "--episodes", "2"]) == 0
    text = capsys.readouterr().out
    assert "the robot tipped over (info['tipped']) in 2 of 2 episodes" in text
    gif = tmp_path / "fall.gif"
    assert run.main(["render", str(out), *common, "--out", str(gif), "--max-frames", "3"]) == 0
    assert "did not reach the goal, the robot having tipped over" in capsys.readouterr().out


def test_experiment_with_one_and_two_workers(tmp_path: Path, capsys, standins):
    config = standins.tiny_config(tmp_path)
    for workers in ("1", "2"):
        assert (
            run.main(
                [
                    "experiment",
                    str(config),
                    "--workers",
                    workers,
                    "--no-progress",
                    "--out",
                    str(tmp_path / f"w{workers}"),
                ]
            )
            == 0
        )
    one, two = tmp_path / "w1", tmp_path / "w2"
    assert (one / "episodes.csv").read_bytes() == (two / "episodes.csv").read_bytes()
    rows = read_csv(one / "episodes.csv")
    assert len(rows) == 3 * 2 * 4
    assert {r["strategy"] for r in rows} == {"eps", "adaptive+tabu", "grid-6"}
    by_run = {(r["strategy"], r["run"]): r["seed"] for r in rows}
    assert by_run[("eps", "0")] == by_run[("grid-6", "0")] != by_run[("eps", "1")]
    assert all(int(r["leaves"]) == 36 for r in rows if r["strategy"] == "grid-6")
    for name in ("figure4.png", "leaves.png"):
        assert_png(one / name)
    summary = read_csv(one / "summary.csv")
    assert [r["strategy"] for r in summary] == ["eps", "adaptive+tabu", "grid-6"]
    assert float(summary[0]["p_improvement"]) == 0.5
    assert "report:" in capsys.readouterr().out


def test_experiment_resumes_after_a_kill(tmp_path: Path, standins):
    config = standins.tiny_config(tmp_path, episodes=30, cap=300, runs=3)
    out = tmp_path / "killed"
    command = [
        sys.executable,
        str(ROOT / "run.py"),
        "experiment",
        str(config),
        "--backend",
        "serial",
        "--no-progress",
        "--out",
        str(out),
    ]
    process = subprocess.Popen(
        command, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    deadline = time.monotonic() + 60
    while not list((out / "runs").glob("*.json")) and time.monotonic() < deadline:
        time.sleep(0.01)
    process.send_signal(signal.SIGKILL)
    process.wait()
    # a run is finished once its sidecar is written (after its CSV)
    finished = {
        p.with_suffix(".csv").name: p.with_suffix(".csv").stat().st_mtime_ns
        for p in (out / "runs").glob("*.json")
    }
    assert 1 <= len(finished) < 9, "the kill came too late to test a resume"
    assert not (out / "episodes.csv").exists()

    subprocess.run(command, cwd=ROOT, check=True, capture_output=True, timeout=120)
    assert len(list((out / "runs").glob("*.csv"))) == 9
    for name, mtime in finished.items():
        assert (out / "runs" / name).stat().st_mtime_ns == mtime, f"{name} was recomputed"

    fresh = tmp_path / "fresh"
    assert run.main([*command[2:-1], str(fresh)]) == 0
    assert (out / "episodes.csv").read_bytes() == (fresh / "episodes.csv").read_bytes()


def test_ray_backend_gives_the_same_csv(tmp_path: Path, standins):
    pytest.importorskip("ray")
    config = standins.tiny_config(tmp_path, runs=1)
    for backend in ("serial", "ray"):
        assert (
            run.main(
                [
                    "experiment",
                    str(config),
                    "--backend",
                    backend,
                    "--workers",
                    "2",
                    "--no-progress",
                    "--out",
                    str(tmp_path / backend),
                ]
            )
            == 0
        )
    assert (tmp_path / "ray" / "episodes.csv").read_bytes() == (
        tmp_path / "serial" / "episodes.csv"
    ).read_bytes()
    meta = [
        store.read_run(tmp_path / "ray" / "runs", p.stem).meta
        for p in (tmp_path / "ray" / "runs").glob("*.csv")
    ]
    assert len(meta) == 3
    assert all(m["meta"]["pid"] != os.getpid() for m in meta)
    assert all(np.isfinite(m["steps_per_second"]) for m in meta)


CLASSIC = """
[experiment]
name = "mc"
runs = 2
episodes = 3
smoothing_window = 2
final_window = 2

[env]
id = "MountainCar-v0"
max_episode_steps = 40

[agent]
split_min_samples = 20

[[strategy]]
name = "eps"
exploration = "epsilon-greedy"

[[strategy]]
name = "grid"
agent = "grid"
resolution = 6
exploration = "epsilon-greedy"
"""


def test_a_gymnasium_classic_control_experiment_runs(tmp_path: Path, capsys):
    """Gymnasium's own ids stay usable in experiment files (no maze, robot or mode)."""
    path = tmp_path / "mc.toml"
    path.write_text(CLASSIC)
    out = tmp_path / "out"
    argv = ["experiment", str(path), "--backend", "serial", "--no-progress", "--out", str(out)]
    assert run.main(argv) == 0
    rows = read_csv(out / "episodes.csv")
    assert len(rows) == 2 * 2 * 3
    assert all(int(r["steps"]) == 40 and r["truncated"] == "1" for r in rows)
    assert "maze" not in (out / "config.toml").read_text()
    train = tmp_path / "train"
    argv = ["train", "--config", str(path), "--episodes", "2", "--no-progress", "--out", str(train)]
    assert run.main(argv) == 0
    assert not (train / "partition.png").exists()
    assert run.main(["evaluate", str(train), "--episodes", "1"]) == 0
    assert "in MountainCar-v0 (cap 40)" in capsys.readouterr().out


def test_a_task_other_than_a_maze_is_summarised_by_its_returns(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """CartPole's ``terminated`` is a fall, so a "success rate" would count falls, and a task has
    no known optimum ("optimal nan" was printed): train and evaluate print returns and how the
    episodes ended instead."""
    config = tmp_path / "cartpole.toml"
    config.write_text(
        '[experiment]\nname = "cp"\nruns = 1\nepisodes = 4\n\n[env]\nid = "CartPole-v1"\n\n'
        '[[strategy]]\nname = "general"\npreset = "general"\n'
    )
    out = tmp_path / "agent"
    assert run.main(["train", "--config", str(config), "--no-progress", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert re.search(r"training general in CartPole-v1, seed \d+: up to 4 episodes\n", printed)
    assert "return per episode: mean " in printed
    assert re.search(r"greedy policy: return \d+ in \d+ steps \(ended by the task\)", printed)
    for wrong in ("success", "goal", "optimal", "nan"):
        assert wrong not in printed
    assert run.main(["evaluate", str(out / "agent.npz"), "--episodes", "2"]) == 0
    printed = capsys.readouterr().out
    assert "2 greedy episodes in CartPole-v1 (cap 500)" in printed
    assert "return per episode: mean " in printed
    assert "cut by the time limit in 0 of 2 episodes" in printed
    assert re.search(r"\n[\d,]+ steps/s\n", printed)
    for wrong in ("success", "optimal", "nan", "collisions"):
        assert wrong not in printed
