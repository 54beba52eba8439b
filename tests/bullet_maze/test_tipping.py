"""A dynamic robot that tips over (``info["tipped"]``, ``tip_angle``, ``end_on_tip``).

pybullet_data's ``r2d2.urdf`` is tall on small wheels: driven by the generic compass controller it
falls on its side on the third step north from the open maze's start, and no command moves it
again. Before ``info["tipped"]`` the episode went on silently, the robot lying still until the cap.
"""

from __future__ import annotations

import math
from pathlib import Path

import gymnasium as gym
import numpy as np
import pybullet_data
import pytest

from bullet_maze import Action, BulletMazeEnv
from experiments.config import ConfigError, load_config
from experiments.evaluation import evaluate

R2D2 = str(Path(pybullet_data.getDataPath()) / "r2d2.urdf")


class North:
    """An agent that always drives north."""

    def predict(self, obs: object, deterministic: bool = True) -> int:
        return int(Action.UP)


def test_a_robot_that_tips_over_is_reported_and_the_episode_goes_on(
    caplog: pytest.LogCaptureFixture,
) -> None:
    env = BulletMazeEnv(maze="open", robot=R2D2, mode="dynamic")
    try:
        _, info = env.reset(seed=0)
        assert info["tipped"] is False
        assert env.robot.tilt() < 0.05  # placed upright
        flags = []
        for _ in range(5):
            _, _, _, truncated, info = env.step(Action.UP)
            flags.append(info["tipped"])
            assert truncated is False  # end_on_tip is off by default
        assert flags == [False, False, True, True, True]
        assert env.robot.tilt() > math.pi / 3
        _, info = env.reset(seed=0)  # reset stands it up again
        assert info["tipped"] is False
        assert env.robot.tilt() < 0.05
        for _ in range(4):  # it falls again, and the warning is not repeated
            env.step(Action.UP)
    finally:
        env.close()
    warnings = [r.getMessage() for r in caplog.records if "tipped over" in r.getMessage()]
    assert len(warnings) == 1
    assert "robot r2d2 tipped over in dynamic mode" in warnings[0]
    assert "[limits] max_wheel_speed" in warnings[0]


def test_end_on_tip_truncates_the_step_that_tips_and_a_wide_angle_never_does() -> None:
    env = BulletMazeEnv(maze="open", robot=R2D2, mode="dynamic", end_on_tip=True)
    try:
        env.reset(seed=0)
        cuts = [env.step(Action.UP)[3] for _ in range(3)]
        assert cuts == [False, False, True]
    finally:
        env.close()
    env = BulletMazeEnv(maze="open", robot=R2D2, mode="dynamic", tip_angle=math.pi)
    try:
        env.reset(seed=0)
        assert not any(env.step(Action.UP)[4]["tipped"] for _ in range(4))
    finally:
        env.close()


def test_an_upright_robot_never_tips_and_kinematic_mode_does_not_report() -> None:
    env = BulletMazeEnv(maze="open", robot="husky", mode="dynamic")
    rng = np.random.default_rng(0)
    try:
        env.reset(seed=0)
        for action in rng.integers(0, 4, size=40):
            _, _, terminated, truncated, info = env.step(int(action))
            assert info["tipped"] is False
            assert truncated is False
            if terminated:
                env.reset()
        assert env.robot.tilt() < 0.3
    finally:
        env.close()
    kinematic = BulletMazeEnv(maze="open", robot="husky")
    try:
        _, info = kinematic.reset(seed=0)
        assert "tipped" not in info
        assert "tipped" not in kinematic.step(Action.UP)[4]
    finally:
        kinematic.close()


@pytest.mark.parametrize(
    ("params", "error", "match"),
    [
        ({"tip_angle": 0.0}, ValueError, r"tip_angle must be in \(0, pi\] radians, got 0\.0"),
        ({"tip_angle": 4.0}, ValueError, r"tip_angle must be in \(0, pi\] radians, got 4\.0"),
        ({"tip_angle": float("nan")}, ValueError, r"tip_angle must be in \(0, pi\]"),
        ({"tip_angle": True}, TypeError, r"tip_angle must be a number, got True"),
        ({"end_on_tip": "yes"}, TypeError, r"end_on_tip must be a bool, got 'yes'"),
        ({"end_on_tip": 1}, TypeError, r"end_on_tip must be a bool, got 1"),
    ],
)
def test_bad_tip_settings_are_refused_by_name(
    params: dict[str, object], error: type[Exception], match: str
) -> None:
    with pytest.raises(error, match=match):
        BulletMazeEnv(maze="open", mode="dynamic", **params)  # type: ignore[arg-type]


def test_goal_relabelling_keeps_the_tip_truncation() -> None:
    env = BulletMazeEnv(maze="open", mode="dynamic", observation="goal", end_on_tip=True)
    try:
        achieved = np.zeros((3, 2))
        desired = np.ones((3, 2))
        infos = [{"tipped": False}, {"tipped": True}, {}]
        assert env.compute_truncated(achieved, desired, infos).tolist() == [False, True, False]
        assert env.compute_truncated(achieved[0], desired[0], {"tipped": True}) is True
    finally:
        env.close()
    kept = BulletMazeEnv(maze="open", mode="dynamic", observation="goal")
    try:  # without end_on_tip a fall never truncates
        assert kept.compute_truncated(np.zeros(2), np.ones(2), {"tipped": True}) is False
    finally:
        kept.close()


def test_evaluations_count_the_episodes_whose_robot_tipped() -> None:
    env = gym.make("BulletMaze-v0", maze="open", robot=R2D2, mode="dynamic", max_episode_steps=6)
    try:
        result = evaluate(env, North(), episodes=2, seed=0)
    finally:
        env.close()
    assert result.tipped == 2
    assert result.success_rate == 0.0
    assert result.steps.tolist() == [6, 6]  # the fall counted at the cap, not cut short


def test_the_harness_refuses_end_on_tip(tmp_path: Path) -> None:
    config = tmp_path / "tip.toml"
    config.write_text(
        '[experiment]\nname = "tip"\nruns = 1\nepisodes = 2\n\n'
        '[env]\nmode = "dynamic"\nparams = { end_on_tip = true }\n\n'
        '[[strategy]]\nname = "general"\npreset = "general"\n'
    )
    with pytest.raises(ConfigError, match=r"tip\.toml: \[env\.params\] end_on_tip: would cut"):
        load_config(config)
