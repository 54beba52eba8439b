"""Experiments over tasks end to end through ``run.py experiment``, with the real environment
and learner at a tiny scale: files per task, the report, resume, ``--only``, ``--report-only``,
the greedy evaluation's files, and reproduction of one run with ``run.py train --task``."""

from __future__ import annotations

import csv
import json
import shutil
from pathlib import Path

import pytest

import run
from experiments import Experiment, make_backend, store
from experiments.config import load_config
from experiments.runner import run_experiment

ROOT = Path(run.__file__).resolve().parent
TASKS = ["open", "rooms-seed0-rows2-cols2"]


def _experiment(config: Path, out: Path, *extra: str) -> int:
    return run.main(
        [
            "experiment",
            str(config),
            "--backend",
            "serial",
            "--no-progress",
            "--out",
            str(out),
            *extra,
        ]
    )


def _rows(path: Path) -> list[dict[str, str]]:
    with path.open(newline="") as handle:
        return list(csv.DictReader(handle))


def _run_files(out: Path) -> dict[str, int]:
    return {
        str(p.relative_to(out / "runs")): p.stat().st_mtime_ns
        for p in sorted((out / "runs").rglob("*"))
        if p.is_file()
    }


@pytest.fixture(scope="module")
def suite_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """A finished tiny suite experiment (2 strategies x 2 dev layouts x 2 runs)."""
    with pytest.MonkeyPatch.context() as patch:
        patch.syspath_prepend(str(Path(__file__).resolve().parent))
        from standins import tiny_suite_config  # type: ignore[import-not-found]

    folder = tmp_path_factory.mktemp("suite")
    config = tiny_suite_config(folder)
    out = folder / "out"
    assert _experiment(config, out) == 0
    return config, out


@pytest.fixture(autouse=True)
def _standins_on_path(standins):
    return standins


def test_each_task_has_its_own_run_files(suite_run):
    config, out = suite_run
    assert sorted(p.name for p in (out / "runs").iterdir()) == sorted(TASKS)
    seeds = {spec.seed for spec in Experiment.from_file(config, out=out).planned}
    for task in TASKS:
        names = sorted(p.name for p in (out / "runs" / task).iterdir())
        expected = sorted(
            f"{strategy}__{seed}{suffix}"
            for strategy in ("eps", "grid-6")
            for seed in seeds
            for suffix in (".csv", ".json", ".eval.csv")
        )
        assert names == expected
    sidecar = json.loads(next((out / "runs" / "open").glob("eps__*.json")).read_text())
    assert sidecar["task"] == "open"
    assert sidecar["name"].startswith("open/eps__")
    assert sidecar["evaluation_episodes"] == 2
    assert sidecar["inputs"]["config"]["env"]["maze"] == "open"
    rooms = json.loads(next((out / "runs" / TASKS[1]).glob("eps__*.json")).read_text())
    assert rooms["inputs"]["layout"] != sidecar["inputs"]["layout"]


def test_the_gathered_files_name_the_task(suite_run):
    _, out = suite_run
    episodes = _rows(out / "episodes.csv")
    assert len(episodes) == 2 * 2 * 2 * 6
    assert list(episodes[0])[:4] == ["task", "strategy", "run", "seed"]
    assert [r["task"] for r in episodes[::24]] == TASKS
    evaluation = _rows(out / "evaluation.csv")
    assert len(evaluation) == 2 * 2 * 2 * 2
    assert list(evaluation[0]) == ["task", "strategy", "run", "seed", *store.EVAL_COLUMNS]


def test_the_report_has_the_aggregate_and_a_table_per_task(suite_run):
    _, out = suite_run
    text = (out / "report.md").read_text()
    for phrase in (
        "## Aggregate over tasks and runs",
        "### maze, dev split: 2 tasks",
        "**final steps / optimal** (lower is better)",
        "**AUC / optimal** (lower is better)",
        "IQM [95% CI]",
        "P(improvement) over eps [95% CI]",
        "### open (`open`, dev split, cap 150, optimal",
        "### rooms-seed0-rows2-cols2 (`rooms:seed=0,rows=2,cols=2`",
        "runs converged",
        "greedy success (2 episodes)",
    ):
        assert phrase in text, phrase
    for name in ("curves.png", "profile_maze_dev_split.png"):
        assert (out / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    summary = _rows(out / "summary.csv")
    assert [(r["task"], r["strategy"]) for r in summary] == [
        (t, s) for t in TASKS for s in ("eps", "grid-6")
    ]
    for row in summary:
        ratio = float(row["final_steps_mean"]) / float(row["optimal_steps"])
        assert float(row["final_to_optimal_mean"]) == pytest.approx(ratio)
    aggregate = _rows(out / "aggregate.csv")
    assert {(r["score"], r["strategy"]) for r in aggregate} == {
        (score, s) for score in ("final_to_optimal", "auc_to_optimal") for s in ("eps", "grid-6")
    }
    assert all(r["runs"] == "4" and r["tasks"] == "2" for r in aggregate)


def test_the_same_runs_give_the_same_report_twice(suite_run, tmp_path: Path):
    config, out = suite_run
    first = {name: (out / name).read_bytes() for name in ("report.md", "aggregate.csv")}
    assert _experiment(config, out, "--report-only") == 0
    for name, data in first.items():
        assert (out / name).read_bytes() == data, name


def test_the_process_backend_gives_the_same_files(suite_run, tmp_path: Path):
    config, out = suite_run
    other = tmp_path / "two"
    argv = ["experiment", str(config), "--workers", "2", "--no-progress", "--out", str(other)]
    assert run.main(argv) == 0
    for name in ("episodes.csv", "evaluation.csv"):
        assert (other / name).read_bytes() == (out / name).read_bytes(), name


def test_a_deleted_or_damaged_run_is_recomputed_alone(suite_run, tmp_path: Path):
    config, finished = suite_run
    out = tmp_path / "copy"
    shutil.copytree(finished, out)
    before = _run_files(out)
    deleted = next((out / "runs" / "open").glob("grid-6__*.csv"))
    deleted.unlink()
    damaged = next((out / "runs" / TASKS[1]).glob("eps__*.eval.csv"))
    damaged.write_text(damaged.read_text().replace("\n1,", "\n9,", 1))
    assert _experiment(config, out) == 0
    after = _run_files(out)
    changed = {name for name in before if before[name] != after[name]}
    stems = {name.split(".")[0] for name in changed}
    assert stems == {
        str(deleted.relative_to(out / "runs")).removesuffix(".csv"),
        str(damaged.relative_to(out / "runs")).removesuffix(".eval.csv"),
    }
    assert (out / "episodes.csv").read_bytes() == (finished / "episodes.csv").read_bytes()
    assert (out / "evaluation.csv").read_bytes() == (finished / "evaluation.csv").read_bytes()


def test_only_then_the_rest_is_one_experiment(suite_run, tmp_path: Path, capsys):
    config, finished = suite_run
    out = tmp_path / "parts"
    assert _experiment(config, out, "--only", "grid-6") == 0
    files = {p.name.split("__")[0] for p in (out / "runs").rglob("*.csv")}
    assert files == {"grid-6"}
    assert not (out / "episodes.csv").exists()
    text = (out / "report.md").read_text()
    assert "| grid-6 | 2 | 4 |" in text
    assert "| eps |" not in text
    planned = len(list((finished / "runs").rglob("*.json")))
    assert "## Runs not run yet" in text
    assert f"{planned // 2} of the {planned} planned runs have not run (`eps` {planned // 2})" in (
        " ".join(text.split())
    )
    assert f"{planned // 2} planned run(s) not run yet" in capsys.readouterr().out
    assert _experiment(config, out) == 0
    assert (out / "episodes.csv").read_bytes() == (finished / "episodes.csv").read_bytes()
    assert "## Runs not run yet" not in (out / "report.md").read_text()
    assert "not run yet" not in capsys.readouterr().out


def test_the_test_split_goes_to_its_own_folder(tmp_path: Path, monkeypatch, standins):
    config = standins.tiny_suite_config(tmp_path, episodes=3, runs=1)
    monkeypatch.setattr(run, "RESULTS_DIR", tmp_path / "results")
    argv = ["experiment", str(config), "--split", "test", "--backend", "serial", "--no-progress"]
    assert run.main(argv) == 0
    out = tmp_path / "results" / "tinysuite__test"
    assert [p.name for p in (out / "runs").iterdir()] == ["rooms-seed1000-rows2-cols2"]
    assert "### maze, test split: 1 tasks" in (out / "report.md").read_text()
    assert load_config(out / "config.toml").splits == ("test",)


def test_train_task_reproduces_a_run(suite_run, tmp_path: Path):
    config, out = suite_run
    run_csv = next((out / "runs" / TASKS[1]).glob("eps__*.csv"))
    seed = run_csv.stem.split("__")[1]
    argv = [
        "train",
        "--config",
        str(config),
        "--task",
        TASKS[1],
        "--strategy",
        "eps",
        "--seed",
        seed,
        "--time-budget",
        "0",
        "--no-progress",
        "--out",
        str(tmp_path / "one"),
    ]
    assert run.main(argv) == 0
    assert (tmp_path / "one" / "episodes.csv").read_bytes() == run_csv.read_bytes()


def test_a_killed_worker_costs_only_its_run(tmp_path: Path, standins, monkeypatch):
    """Fault tolerance across tasks: a run whose worker dies once is computed again."""
    config = load_config(standins.tiny_suite_config(tmp_path, episodes=20))
    died = tmp_path / "died"
    died.mkdir()
    victim = next(s for s in Experiment(config, tmp_path / "o").planned if s.task == TASKS[1])
    monkeypatch.setenv("STANDIN_DIE_ONCE", str(died))
    monkeypatch.setenv("STANDIN_DIE_NAME", victim.name)
    results = run_experiment(config, tmp_path / "o", make_backend("process", 2), standins.fake_run)
    assert (died / victim.name.replace("/", "__")).exists()
    assert len(results) == 8
    assert victim.name in {r.name for r in results}


CLASSIC = """
[experiment]
name = "cc"
runs = 2
episodes = 3
smoothing_window = 2
final_window = 2
eval_episodes = 2

[env]
max_episode_steps = 40

[[task]]
id = "MountainCar-v0"
name = "mc"
random_return = -40.0
solved_return = -20.0

[[task]]
id = "CartPole-v1"
max_episode_steps = 500
observation_bounds = [[-4.8, -3.0, -0.42, -3.5], [4.8, 3.0, 0.42, 3.5]]

[[task]]
id = "Acrobot-v1"

[agent]
split_min_samples = 20

[[strategy]]
name = "eps"
exploration = "epsilon-greedy"

[[strategy]]
name = "grid"
agent = "grid"
resolution = 4
exploration = "epsilon-greedy"
"""


def test_a_classic_control_task_list(tmp_path: Path):
    path = tmp_path / "cc.toml"
    path.write_text(CLASSIC)
    out = tmp_path / "out"
    assert _experiment(path, out) == 0
    summary = {(r["task"], r["strategy"]): r for r in _rows(out / "summary.csv")}
    assert float(summary[("mc", "eps")]["normalised_return_mean"]) == 0.0  # every return -40
    assert summary[("Acrobot-v1", "eps")]["normalised_return_mean"] == ""  # cap 40: no reference
    text = (out / "report.md").read_text()
    assert "### mc (`MountainCar-v0`, cap 40; random policy -40, solved -20)" in text
    assert "Left out of the aggregate" in text
    assert "`Acrobot-v1`" in text
    assert "greedy return (2 episodes), mean" in text
    aggregate = _rows(out / "aggregate.csv")
    assert {r["group"] for r in aggregate} == {"return"}
    assert all(r["tasks"] == "2" for r in aggregate)


UNSCORED = """
[experiment]
name = "unscored"
runs = 2
episodes = 3
eval_episodes = 1

[[task]]
id = "MountainCar-v0"
max_episode_steps = 20

[[task]]
id = "FrozenLake-v1"
params = { is_slippery = false }

[[strategy]]
name = "eps"
exploration = "epsilon-greedy"
"""


def test_tasks_without_references_and_runs_shorter_than_the_final_window(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
):
    """No task has reference returns, and 3 episodes are fewer than the default final window
    of 100: the report and the summary say there is no aggregate (not an empty table or an
    empty list of sources), and name the 3 episodes the final values are the mean of."""
    path = tmp_path / "unscored.toml"
    path.write_text(UNSCORED)
    out = tmp_path / "out"
    assert _experiment(path, out) == 0
    printed = capsys.readouterr().out
    assert "no aggregate over them" in printed
    assert "aggregate over tasks and runs:" not in printed
    text = (out / "report.md").read_text()
    assert "None: no task has a normalised score." in text
    assert "Interquartile mean" not in text
    assert "training return (last 3), mean" in text
    assert "last 100" not in text
    assert "- reference returns: none" in text
    assert not text.rstrip().endswith("reference returns:")


def test_a_report_without_a_greedy_evaluation_has_no_greedy_column(tmp_path: Path):
    """With ``eval_episodes`` 0 the greedy return was a column of "-" headed "greedy return
    (0 episodes)"; it is left out, and the runs solved are counted on the training return."""
    path = tmp_path / "no_eval.toml"
    path.write_text(
        UNSCORED.replace("eval_episodes = 1\n", "")
        + '\n[[task]]\nid = "CartPole-v1"\nname = "cp"\nrandom_return = 20.0\n'
        "solved_return = 475.0\n"
    )
    out = tmp_path / "out"
    assert _experiment(path, out) == 0
    text = (out / "report.md").read_text()
    assert "greedy return" not in text
    head = next(line for line in text.splitlines() if line.startswith("| strategy | runs"))
    rule = text.splitlines()[text.splitlines().index(head) + 1]
    assert head.count("|") == rule.count("|") == 7
    assert "runs solved (training return (last 3) >= 475)" in text
