"""A user's own env through the harness: ``run.py --env-module MODULE`` imports the module that
registers it, here and in every spawned worker, and accepts the ids it registers; the env's code
is an input of its runs, so an edited env is never mixed with runs computed before the edit.
Bad names and modules are one line naming the option and the module."""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import gymnasium as gym
import pytest

import run
from experiments import ModuleError, import_env_modules

ROOT = Path(run.__file__).resolve().parent

ENV_ID = "ModuleCorridor-v0"

MODULE = """
import gymnasium as gym
import numpy as np
from gymnasium import spaces

REWARD = -1.0


class Corridor(gym.Env):
    \"\"\"Ten cells; action 1 moves right, 0 left; the last cell ends the episode.\"\"\"

    observation_space = spaces.Box(0.0, 10.0, (1,), np.float32)
    action_space = spaces.Discrete(2)

    def __init__(self, render_mode=None):
        self.render_mode = render_mode

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        self.x = 0
        return np.array([0.0], np.float32), {}

    def step(self, action):
        self.x = min(10, max(0, self.x + (1 if action else -1)))
        return np.array([self.x], np.float32), REWARD, self.x >= 10, False, {}


gym.register("ModuleCorridor-v0", entry_point=Corridor, max_episode_steps=100)
"""

EXPERIMENT = f"""
[experiment]
name = "corridor"
runs = 2
episodes = 4
eval_episodes = 2

[[task]]
id = "{ENV_ID}"
random_return = -100.0
solved_return = -10.0

[[strategy]]
name = "general"
preset = "general"
"""


@pytest.fixture
def user_module(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[tuple[str, Path]]:
    """A module on ``sys.path`` (and on ``PYTHONPATH`` for subprocesses) that registers
    ``ENV_ID`` when imported; unregistered and forgotten afterwards."""
    name = f"user_envs_{os.getpid()}_{tmp_path.name}".replace("-", "_")
    path = tmp_path / f"{name}.py"
    path.write_text(MODULE)
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([str(tmp_path), str(ROOT)]))
    yield name, path
    gym.registry.pop(ENV_ID, None)
    sys.modules.pop(name, None)


def test_a_module_s_ids_are_returned_once_imported(user_module: tuple[str, Path]) -> None:
    name, _ = user_module
    assert ENV_ID not in gym.registry
    assert import_env_modules([name]) == {ENV_ID}
    assert ENV_ID in gym.registry


@pytest.mark.parametrize(
    ("name", "message"),
    [
        ("./my_envs.py", r"--env-module './my_envs.py': not a module name"),
        ("my_envs.py/", r"not a module name"),
        ("", r"--env-module '': not a module name"),
        ("1envs", r"not a module name"),
        ("os:system", r"not a module name"),
        ("..envs", r"not a module name"),
        ("envs.", r"not a module name"),
        (
            "no_such_module_anywhere",
            r"--env-module no_such_module_anywhere: importing it failed: "
            r"ModuleNotFoundError: No module named 'no_such_module_anywhere'",
        ),
        ("json", r"--env-module json: importing it registered no new Gymnasium id"),
    ],
)
def test_a_bad_module_is_refused_by_name(name: str, message: str) -> None:
    with pytest.raises(ModuleError, match=message):
        import_env_modules([name])


def test_a_module_that_raises_on_import_is_named_with_its_error(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (tmp_path / "broken_envs_p41.py").write_text("raise RuntimeError('no licence file')\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    with pytest.raises(
        ModuleError,
        match=r"--env-module broken_envs_p41: importing it failed: RuntimeError: no licence file",
    ):
        import_env_modules(["broken_envs_p41"])
    sys.modules.pop("broken_envs_p41", None)


def test_too_many_modules_are_refused() -> None:
    with pytest.raises(ModuleError, match=r"at most 64 modules, got 65"):
        import_env_modules(["json"] * 65)


def _run(argv: list[str], cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, str(ROOT / "run.py"), *argv],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=300,
    )


def test_an_experiment_on_a_user_env_runs_in_spawned_workers_and_an_edit_is_not_mixed(
    user_module: tuple[str, Path], tmp_path: Path
) -> None:
    name, path = user_module
    (tmp_path / "corridor.toml").write_text(EXPERIMENT)
    argv = ["--env-module", name, "experiment", "corridor.toml", "--out", "out"]
    argv += ["--backend", "process", "--workers", "2", "--no-progress"]
    first = _run(argv, tmp_path)
    assert first.returncode == 0, first.stderr
    runs = sorted(p.name for p in (tmp_path / "out" / "runs" / ENV_ID).glob("*.json"))
    assert len(runs) == 2, runs
    assert ENV_ID in (tmp_path / "out" / "report.md").read_text()
    # the same runs in this one process (the serial backend), bit for bit
    serial = ["--env-module", name, "experiment", "corridor.toml", "--out", "serial"]
    assert _run([*serial, "--backend", "serial", "--no-progress"], tmp_path).returncode == 0
    assert len(list((tmp_path / "out" / "runs" / ENV_ID).glob("*.csv"))) == 4
    for csv in (tmp_path / "out" / "runs" / ENV_ID).glob("*.csv"):
        assert csv.read_bytes() == (tmp_path / "serial" / "runs" / ENV_ID / csv.name).read_bytes()
    if importlib.util.find_spec("ray") is not None:  # Ray's workers import the module too
        on_ray = ["--env-module", name, "experiment", "corridor.toml", "--out", "ray"]
        result = _run([*on_ray, "--backend", "ray", "--workers", "2", "--no-progress"], tmp_path)
        assert result.returncode == 0, result.stderr
        for csv in (tmp_path / "out" / "runs" / ENV_ID).glob("*.csv"):
            assert csv.read_bytes() == (tmp_path / "ray" / "runs" / ENV_ID / csv.name).read_bytes()
    # without the module, the id is unknown, and the error says how to name the module
    missing = _run(argv[2:], tmp_path)
    assert missing.returncode == 2
    assert "run.py --env-module MODULE" in missing.stderr, missing.stderr
    assert "Traceback" not in missing.stderr
    # a comment is not a change: the finished runs are taken as they are
    path.write_text(MODULE.replace("REWARD = -1.0", "REWARD = -1.0  # per step"))
    again = _run(argv, tmp_path)
    assert again.returncode == 0, again.stderr
    assert "2 of 2 runs already done" in again.stdout, again.stdout
    # an edited env is another input: its old runs are named, never mixed with new ones
    path.write_text(MODULE.replace("REWARD = -1.0", "REWARD = -2.0"))
    edited = _run(argv, tmp_path)
    assert edited.returncode == 2, edited.stdout + edited.stderr
    assert "2 finished run(s) were computed from other inputs" in edited.stderr, edited.stderr
    assert "(a user's env) code (env)" in edited.stderr, edited.stderr
    assert "Traceback" not in edited.stderr


def test_a_bad_module_on_the_command_line_is_one_line(tmp_path: Path) -> None:
    result = _run(["--env-module", "./envs.py", "experiment", "quick"], tmp_path)
    assert result.returncode == 2
    assert result.stderr.strip().splitlines()[-1] == (
        "run.py experiment: error: --env-module './envs.py': not a module name (dotted Python "
        "identifiers, such as my_envs or my_package.envs; not a file path)"
    )
    assert "Traceback" not in result.stderr


@pytest.mark.parametrize(
    "value",
    ["", "\x00", "x" * 5000, "os:system", "../envs", "envs.py", "a b", "json", "1", "-m"],
    ids=repr,
)
def test_every_hostile_module_name_is_one_line_with_exit_code_2(
    value: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as caught:
        run.main(["--env-module", value, "experiment", "quick", "--no-progress"])
    assert caught.value.code == 2
    error = capsys.readouterr().err
    assert "Traceback" not in error
    assert error.count("\n") <= 3, error  # one line (argparse's own errors add its usage)
    assert "--env-module" in error.strip().splitlines()[-1], error


@pytest.mark.parametrize("layout", ["module", "package", "namespace"])
def test_a_user_package_s_fingerprint_follows_its_statements_not_its_comments(
    layout: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The env's source is read as the code fingerprint reads ours: a single module, every module
    of a package, or of a namespace package (a folder without ``__init__.py``, which has no
    ``__file__``)."""
    from experiments.fingerprint import package_fingerprint

    name = f"fp_{layout}_{os.getpid()}"
    if layout == "module":
        source = tmp_path / f"{name}.py"
    else:
        (tmp_path / name).mkdir()
        if layout == "package":
            (tmp_path / name / "__init__.py").write_text("")
        source = tmp_path / name / "envs.py"
    monkeypatch.syspath_prepend(str(tmp_path))

    def fingerprint(text: str) -> str:
        source.write_text(text)
        package_fingerprint.cache_clear()
        for module in [m for m in sys.modules if m == name or m.startswith(f"{name}.")]:
            del sys.modules[module]
        return package_fingerprint(name)

    first = fingerprint("REWARD = -1.0\n")
    assert first == fingerprint("REWARD = -1.0  # per step\n\n")
    assert first != fingerprint("REWARD = -2.0\n")
    package_fingerprint.cache_clear()
    for module in [m for m in sys.modules if m == name or m.startswith(f"{name}.")]:
        del sys.modules[module]


def test_the_shipped_example_of_a_user_env_runs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    """README's command for your own envs: ``examples/corridor_envs.py`` registers two corridors
    and ``examples/corridor_tasks.toml`` runs them beside CartPole (here one run, 3 episodes)."""
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([str(ROOT / "examples"), str(ROOT)]))
    argv = [
        "--env-module",
        "corridor_envs",
        "experiment",
        str(ROOT / "examples/corridor_tasks.toml"),
    ]
    argv += ["--runs", "1", "--episodes", "3", "--out", "out", "--no-progress"]
    result = _run(argv, tmp_path)
    assert result.returncode == 0, result.stderr
    for task in ("Corridor-v0", "LongCorridor-v0", "CartPole-v1"):
        assert len(list((tmp_path / "out" / "runs" / task).glob("*.json"))) == 2, task
    assert "LongCorridor-v0" in (tmp_path / "out" / "report.md").read_text()
