"""The physical limit: shortest collision-free path and least number of steps."""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable

import gymnasium as gym
import numpy as np
import pytest

from bullet_maze import load_layout, shortest_path
from bullet_maze.geometry import clearance


def test_open_arena_is_a_straight_line() -> None:
    limit = shortest_path(load_layout("open"))
    # Start (150, 30) to the goal circle of radius 15 around (150, 270).
    assert limit.length == pytest.approx(225.0, abs=0.01)
    assert limit.l1_length == pytest.approx(225.0, abs=0.5)
    assert limit.steps == 45
    assert limit.lattice_steps == 45


def test_narrow_layout_needs_about_ninety_steps() -> None:
    # The guide's figure: an L1 geodesic of 449 units on a 1-unit grid, 90 steps of 5. The
    # exact L1 length is 2 * (150 - 35) + (270 - 30) - 15 * sqrt(2) = 448.8.
    limit = shortest_path(load_layout("paper_narrow"))
    assert limit.l1_length == pytest.approx(448.8, abs=1.5)
    assert limit.steps == 90
    # Going round the cylinders' outer sides is much longer than the straight 225.
    assert 300.0 < limit.length < limit.l1_length


def test_paths_need_a_detour_where_the_paper_says_so() -> None:
    straight = math.dist(load_layout("paper").start, load_layout("paper").goal) - 15.0
    assert shortest_path(load_layout("paper")).length > straight + 5.0
    corridors = shortest_path(load_layout("corridors"))
    assert corridors.length > 3 * 225.0  # the serpentine crosses the arena four times


@pytest.mark.parametrize("name", ["paper", "paper_narrow", "corridors"])
def test_waypoints_keep_the_robot_clear(name: str) -> None:
    layout = load_layout(name)
    limit = shortest_path(layout)
    points = limit.waypoints
    assert np.allclose(points[0], layout.start)
    t = np.linspace(0.0, 1.0, 200)[:, None]
    for a, b in itertools.pairwise(points):
        assert clearance(layout, a + t * (b - a)).min() >= layout.robot_radius - 0.1
    assert math.dist(points[-1], layout.goal) <= layout.goal_radius + 1e-9


def test_euclidean_is_never_longer_than_l1_and_steps_cover_l1() -> None:
    for name in ("paper", "paper_narrow", "open", "corridors"):
        limit = shortest_path(load_layout(name))
        assert limit.length <= limit.l1_length + 1e-9
        assert limit.steps == math.ceil(limit.l1_length / 5.0 - 1e-9)
        assert limit.lattice_steps is not None
        assert limit.lattice_steps >= limit.steps


def test_a_larger_robot_needs_a_longer_path() -> None:
    layout = load_layout("paper_narrow")
    small = shortest_path(layout, robot_radius=2.0)
    large = shortest_path(layout, robot_radius=10.0)
    assert small.l1_length < large.l1_length


@pytest.mark.parametrize("name", ["paper", "paper_narrow", "corridors"])
def test_the_lattice_path_succeeds_in_the_simulator(
    make_env: Callable[..., gym.Env],
    name: str,
) -> None:
    env = make_env(maze=name, noise_variance=0.0)
    env.reset(seed=0)
    limit = env.unwrapped.physical_limit
    assert env.unwrapped.optimal_steps == limit.steps
    for i, action in enumerate(limit.actions):
        _, reward, terminated, _, info = env.step(action)
        assert not info["collision"], f"step {i} of the planned path collided"
        assert terminated == (i == len(limit.actions) - 1)
    assert reward == 5.0


def test_goal_test_answers_as_the_regions_do_whatever_the_order_of_goals() -> None:
    """The env's kept ``goal_test`` (its goal circle's regions remembered between calls) against
    the regions' labels compared node by node, over starts and goals in a maze with dead ends,
    switching goals between calls."""
    from bullet_maze.planning import _free_regions, _solids, goal_test

    layout = load_layout("maze:seed=3,rows=6,cols=6,cell=20")
    test = goal_test(layout, layout.robot_radius)
    regions = _free_regions(_solids(layout), float(layout.robot_radius))
    rng = np.random.default_rng(0)
    points = [tuple(float(v) for v in rng.uniform(0, layout.arena[0], 2)) for _ in range(40)]
    answers = set()
    for start, goal in itertools.product(points[:20], points[20:]):
        node = regions.grid.start_node(start)
        goals = regions.grid.goal_nodes(goal, layout.goal_radius)
        expected = node is not None and bool(np.any(regions.labels[goals] == regions.labels[node]))
        assert test(start, goal) == expected
        answers.add(expected)
    assert answers == {False, True}
