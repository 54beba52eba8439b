"""A saved agent played on a robot with a heading it was not trained with
(``experiments.factory.fitted_to``): only the heading is dropped, so a lidar's ranges stay in the
places the agent learnt them; any other difference is refused with both sizes."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import bullet_maze  # noqa: F401  (registers the ids)
from experiments.factory import DropHeading, fitted_to


def _maze(robot: str, **kwargs: object) -> gym.Env:
    return gym.make("BulletMaze-v0", maze="open", robot=robot, **kwargs)


def test_a_lidar_observation_loses_the_heading_and_keeps_every_range_in_place() -> None:
    disc = _maze("disc", observation="lidar")
    husky = _maze("husky", observation="lidar")
    try:
        dims = disc.observation_space.shape[0]  # x, y and 36 ranges
        fitted = fitted_to(husky, dims)
        assert isinstance(fitted, DropHeading)
        assert fitted.observation_space.shape == (dims,)
        raw, _ = husky.reset(seed=4)
        seen = fitted.observation(raw)
        assert seen.tolist() == [raw[0], raw[1], *raw[3:]]  # (x, y, ranges): heading gone
        assert not np.array_equal(seen, raw[:dims])  # the old cut shifted every range
        space = husky.observation_space
        assert fitted.observation_space.low.tolist() == np.delete(space.low, 2).tolist()
        assert fitted.observation_space.high.tolist() == np.delete(space.high, 2).tolist()
    finally:
        disc.close()
        husky.close()


def test_the_same_size_is_played_as_it_is_and_a_pose_loses_its_heading() -> None:
    husky = _maze("husky")
    try:
        assert fitted_to(husky, 3) is husky
        fitted = fitted_to(husky, 2)
        raw, _ = husky.reset(seed=1)
        assert fitted.observation(raw).tolist() == raw[:2].tolist()
    finally:
        husky.close()


@pytest.mark.parametrize(
    ("robot", "kwargs", "dims", "message"),
    [
        ("disc", {"observation": "lidar", "lidar_rays": 72}, 38, r"observes 38 values; .* 74$"),
        ("husky", {"observation": "lidar"}, 2, r"observes 2 values; .* 39 \(its robot's heading"),
        ("disc", {}, 3, r"observes 3 values; this environment gives 2$"),
        ("disc", {"observation": "goal"}, 2, r"observes 2 values; this environment gives Dict"),
    ],
)
def test_what_cutting_cannot_fit_is_refused_with_both_sizes(
    robot: str, kwargs: dict, dims: int, message: str
) -> None:
    env = _maze(robot, **kwargs)
    try:
        with pytest.raises(ValueError, match=message):
            fitted_to(env, dims)
    finally:
        env.close()


def test_a_goal_conditioned_observation_loses_the_heading_where_the_flattening_put_it() -> None:
    """``adapt_env`` flattens the goal ``Dict`` as (achieved, desired, observation): the husky's
    heading is the seventh value, not the third (which is the desired goal's x)."""
    from agent import adapt_env

    disc = adapt_env(_maze("disc", observation="goal"))
    husky = adapt_env(_maze("husky", observation="goal"))
    try:
        fitted = fitted_to(husky, disc.observation_space.shape[0])
        assert isinstance(fitted, DropHeading)
        assert fitted.index == 6
        raw, _ = husky.reset(seed=2)
        seen, _ = fitted.reset(seed=2)
        assert seen.tolist() == raw[:6].tolist()
        assert seen.tolist() == disc.reset(seed=2)[0].tolist()  # what the disc agent saw
    finally:
        disc.close()
        husky.close()
