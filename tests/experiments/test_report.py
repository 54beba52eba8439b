"""The report of an experiment, from stand-in runs: real PNGs, a table row per strategy."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from experiments import runner
from experiments.backends import SerialBackend
from experiments.report import write_report

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def assert_png(path: Path, min_bytes: int = 5_000) -> None:
    """``path`` is a real PNG of some size."""
    data = path.read_bytes()
    assert data[:8] == PNG_SIGNATURE
    assert len(data) >= min_bytes


def test_report_files_and_table(small_config, standins, tmp_path: Path):
    runner.run_experiment(small_config, tmp_path, SerialBackend(), standins.fake_run)
    report = write_report(small_config, tmp_path, task=standins.fake_run)
    for figure in report.figures:
        assert_png(figure)
    text = report.markdown.read_text()
    assert "![Figure 4 analog](figure4.png)" in text
    table = [line for line in text.splitlines() if line.startswith("| ")]
    assert [line.split("|")[1].strip() for line in table[1:]] == ["eps", "adaptive+tabu"]
    assert "Episodes to convergence" in text
    with report.summary_csv.open() as handle:
        rows = list(csv.DictReader(handle))
    assert [r["strategy"] for r in rows] == ["eps", "adaptive+tabu"]
    baseline = rows[0]
    assert float(baseline["p_improvement"]) == 0.5
    assert float(baseline["final_to_optimal"]) == float(baseline["final_steps_mean"]) / 20.0
    assert 0.0 <= float(rows[1]["success_rate"]) <= 1.0
    assert report.optimal_steps == 20.0
    assert np.isclose(float(baseline["wall_time_s_mean"]), 0.5)


def test_report_of_a_partial_experiment(small_config, standins, tmp_path: Path):
    runner.run_experiment(small_config, tmp_path, SerialBackend(), standins.fake_run)
    for path in list((tmp_path / "runs").glob("adaptive+tabu__*.csv"))[:2]:
        path.unlink()
    report = write_report(small_config, tmp_path, task=standins.fake_run)
    assert [s.runs for s in report.summaries] == [3, 1]
    assert len(report.excluded) == 2
    assert all("missing" in check.reason for check in report.excluded)
    assert "## Runs left out" in report.markdown.read_text()


def test_report_names_the_planned_runs_not_run_yet(small_config, standins, tmp_path: Path):
    runner.run_experiment(
        small_config, tmp_path, SerialBackend(), standins.fake_run, only=["adaptive+tabu"]
    )
    report = write_report(small_config, tmp_path, task=standins.fake_run)
    assert [s.strategy for s in report.summaries] == ["adaptive+tabu"]
    assert len(report.not_run) == 3
    assert all(name.startswith("eps__") for name in report.not_run)
    assert report.excluded == ()
    text = " ".join(report.markdown.read_text().split())
    assert "## Runs not run yet 3 of the 6 planned runs have not run (`eps` 3)" in text
    assert "covers 3 finished runs" in text
    runner.run_experiment(small_config, tmp_path, SerialBackend(), standins.fake_run)
    report = write_report(small_config, tmp_path, task=standins.fake_run)
    assert report.not_run == ()
    assert "Runs not run yet" not in report.markdown.read_text()


def test_a_tasks_mean_returns_keep_three_significant_digits() -> None:
    """A task whose returns are fractions (Blackjack's are about -0.05) is not rounded to one
    decimal, where every strategy would read "-0.1"; returns of 10 or more keep one decimal."""
    from experiments.task_report import _return_num

    cases = {
        -0.0523: "-0.0523",
        -0.0777: "-0.0777",
        0.5: "0.500",
        5.8: "5.80",
        -3.75: "-3.75",
        19.3: "19.3",
        -166.34: "-166.3",
        1000.0: "1000.0",
        0.0: "0.0",
        1e-9: "0.000000",
        float("nan"): "n/a",
    }
    assert {value: _return_num(value) for value in cases} == cases
