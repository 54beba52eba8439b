"""A run that cannot finish (a user's env hands the agent a NaN) ends ``run.py experiment`` with
one line naming the run and the cause, exit code 1 and no traceback; the runs finished before it
are kept, and the same command resumes them."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

import run

NAN_ID = "NanRewardTest-v0"


class NanReward(gym.Env):
    """Ten-step episodes whose fifth step pays NaN."""

    observation_space = spaces.Box(-1.0, 1.0, (2,), np.float32)
    action_space = spaces.Discrete(3)

    def __init__(self, render_mode: str | None = None) -> None:
        self.render_mode = render_mode
        self.t = 0

    def reset(self, *, seed: int | None = None, options: dict | None = None) -> Any:
        super().reset(seed=seed)
        self.t = 0
        return np.zeros(2, np.float32), {}

    def step(self, action: Any) -> Any:
        self.t += 1
        reward = float("nan") if self.t == 5 else -1.0
        return np.zeros(2, np.float32), reward, self.t >= 10, False, {}


@pytest.fixture
def nan_env():
    gym.register(NAN_ID, entry_point=NanReward, max_episode_steps=50)
    yield NAN_ID
    del gym.registry[NAN_ID]


def _experiment(tmp_path: Path) -> Path:
    path = tmp_path / "nan.toml"
    path.write_text(
        f"""
[experiment]
name = "nan"
runs = 1
episodes = 2
eval_episodes = 1

[[task]]
id = "CartPole-v1"

[[task]]
id = "{NAN_ID}"
random_return = -10.0
solved_return = 0.0

[[strategy]]
name = "general"
preset = "general"
"""
    )
    return path


def test_a_failed_run_is_one_line_and_finished_runs_are_kept(nan_env, tmp_path: Path, capsys):
    out = tmp_path / "out"
    argv = ["--allow-env", nan_env, "experiment", str(_experiment(tmp_path)), "--out", str(out)]
    argv += ["--backend", "serial", "--no-progress"]
    assert run.main(argv) == 1
    err = capsys.readouterr().err
    assert "Traceback" not in err
    assert f"run.py experiment: error: run {nan_env}/general__" in err, err
    cause = "failed: ValueError: env.step (step 5 of the learn call's episode 0): reward nan"
    assert f"{cause} is not finite. Finished runs are kept" in err, err
    kept = sorted(p.name for p in (out / "runs" / "CartPole-v1").glob("*.json"))
    assert len(kept) == 1, kept
    assert not list((out / "runs").glob(f"{nan_env}/*.json"))
    # the same command resumes: the finished run is not computed again, the failed one fails
    assert run.main(argv) == 1
    assert "1 of 2 runs already done" in capsys.readouterr().out


def test_a_run_failed_in_a_worker_is_one_line_too(nan_env, tmp_path: Path, capsys):
    """The process backend: the worker's error comes back as the same one line (a worker that
    cannot make an id registered only in the driver says so, or the NaN is refused there)."""
    out = tmp_path / "out"
    argv = ["--allow-env", nan_env, "experiment", str(_experiment(tmp_path)), "--out", str(out)]
    argv += ["--backend", "process", "--workers", "1", "--no-progress"]
    assert run.main(argv) == 1
    err = capsys.readouterr().err
    assert "Traceback" not in err
    assert f"run.py experiment: error: run {nan_env}/general__" in err, err
    assert ("NameNotFound" in err) != ("reward nan is not finite" in err), err
    assert err.count("\n") == 1, err


def test_a_transfer_cell_that_raises_is_named(monkeypatch):
    """``run.py transfer``'s task gives its errors back the same way, naming the cell."""
    from types import SimpleNamespace

    from experiments import RunFailed, transfer_cell

    def broken(cell: Any) -> Any:
        raise ValueError("the robot's URDF has no base")

    monkeypatch.setattr(transfer_cell, "_evaluate_cell", broken)
    with pytest.raises(RunFailed) as caught:
        transfer_cell.evaluate_cell(SimpleNamespace(name="agent-3/husky-dynamic-mild"))
    assert str(caught.value) == (
        "cell agent-3/husky-dynamic-mild failed: ValueError: the robot's URDF has no base"
    )


def test_a_greedy_episode_refuses_a_nan_reward_by_step():
    """Greedy evaluation (``run.py evaluate``, the evaluation CSVs, transfer cells) reads the
    reward as training does: a NaN is refused naming the step, never summed into a return."""
    from types import SimpleNamespace

    from experiments.evaluation import greedy_episode

    env = NanReward()
    agent = SimpleNamespace(predict=lambda obs: 0)  # a constant policy
    with pytest.raises(ValueError, match=r"^env.step \(step 5 of a greedy episode\): reward nan"):
        greedy_episode(env, agent, seed=0)
