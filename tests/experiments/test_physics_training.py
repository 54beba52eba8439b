"""Training in physics (issue 11 item 4): an experiment trains in dynamic mode, with or without
domain randomisation, through run.py experiment, and saves its agents; the same seeds give the
same runs."""

from __future__ import annotations

from pathlib import Path

import pytest

import run
from experiments import config as config_module
from experiments import runner

EXPERIMENT = """
[experiment]
name = "physics"
seed = 11
runs = 2
episodes = 2
save_agents = true

[env]
maze = "open"
robot = "ROBOT"
mode = "dynamic"
max_episode_steps = CAP

[[task]]
name = "physical"

[[task]]
name = "randomised"
params = PARAMS

[[strategy]]
name = "grid"
agent = "grid"
resolution = 5
exploration = "epsilon-greedy"
exploration_params = { epsilon = 0.015 }
"""
DISC_RANGES = (
    "{ bias_along = [-0.25, 0.25], floor_friction_scale = [0.75, 1.25], latency_steps = [0, 1] }"
)


def _write(tmp_path: Path, robot: str, cap: int, params: str) -> Path:
    text = EXPERIMENT.replace("ROBOT", robot).replace("CAP", str(cap)).replace("PARAMS", params)
    path = tmp_path / f"{robot}.toml"
    path.write_text(text)
    return path


def _run(path: Path, out: Path, capsys: pytest.CaptureFixture[str]) -> dict[str, bytes]:
    argv = ["experiment", str(path), "--out", str(out), "--backend", "serial", "--no-progress"]
    assert run.main(argv) == 0
    capsys.readouterr()
    return {str(p.relative_to(out)): p.read_bytes() for p in sorted(out.rglob("runs/*/*.csv"))}


def test_the_disc_trains_in_physics_with_and_without_randomisation(tmp_path: Path, capsys):
    path = _write(tmp_path, "disc", 40, DISC_RANGES)
    first = _run(path, tmp_path / "a", capsys)
    assert len(first) == 4  # 2 tasks x 2 runs
    agents = sorted((tmp_path / "a" / "runs").rglob("*.agent.npz"))
    assert [p.parent.name for p in agents] == ["physical"] * 2 + ["randomised"] * 2
    config = config_module.load_config(tmp_path / "a" / "config.toml")
    assert {t.env.mode for t in config.tasks} == {"dynamic"}
    assert config.tasks[1].env.params["floor_friction_scale"] == [0.75, 1.25]
    assert not runner.inspect_folder(config, tmp_path / "a").pending
    physical = {k.split("/")[-1]: v for k, v in first.items() if "/physical/" in k}
    randomised = {k.split("/")[-1]: v for k, v in first.items() if "/randomised/" in k}
    assert physical.keys() == randomised.keys()
    assert physical != randomised
    runner.run_experiment(config, tmp_path / "b")  # again, without the report
    again = {
        str(p.relative_to(tmp_path / "b")): p.read_bytes()
        for p in sorted((tmp_path / "b").rglob("runs/*/*.csv"))
    }
    assert again == first  # and repeat bit for bit


def test_a_wheeled_robot_trains_in_physics(tmp_path: Path, capsys):
    path = _write(tmp_path, "rover", 3, "{ mass_scale = [0.8, 1.25], torque_scale = [0.8, 1.25] }")
    files = _run(path, tmp_path / "r", capsys)
    assert len(files) == 4
    assert len(list((tmp_path / "r" / "runs").rglob("*.agent.npz"))) == 4


@pytest.mark.parametrize(
    ("kwargs", "has_optimum"),
    [
        ({}, True),
        ({"actions": "native"}, True),  # (the disc's native actions are the compass ones)
        ({"robot": "racecar"}, True),  # (compass steps by manoeuvre: still compass steps)
        ({"robot": "husky", "actions": "native"}, False),
        ({"actions": "continuous"}, False),
        ({"robot": "rover", "actions": "continuous"}, False),
    ],
)
def test_the_optimum_is_reported_only_for_compass_steps(kwargs: dict, has_optimum: bool):
    """``optimal_steps`` counts compass steps of ``step_size``. A native step of a wheeled
    robot or a continuous step has another length and may go diagonally, so that count is no
    bound on its steps, and a run with them is reported without an optimum (not as a ratio
    that could fall below 1)."""
    import gymnasium as gym
    import numpy as np

    from experiments.factory import optimal_steps

    env = gym.make("BulletMaze-v0", **kwargs)
    try:
        assert (optimal_steps(env) == env.unwrapped.optimal_steps) is has_optimum
        assert np.isnan(optimal_steps(env)) is not has_optimum
    finally:
        env.close()
