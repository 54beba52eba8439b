"""Procedural layouts: deterministic in the seed, valid and solvable over many seeds, usable
wherever a layout is (specs, files, the env), and every bad family or parameter refused by name."""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

from bullet_maze import FAMILIES, generate_layout, layout_to_toml, load_layout, shortest_path
from bullet_maze.__main__ import main as layout_cli
from bullet_maze.geometry import clearance
from bullet_maze.planning import goal_reachable

SEEDS = range(25)


@pytest.mark.parametrize("family", sorted(FAMILIES))
def test_the_same_seed_gives_the_same_layout_and_other_seeds_others(family: str) -> None:
    layouts = [generate_layout(family, seed) for seed in SEEDS]
    assert [generate_layout(family, seed) for seed in SEEDS] == layouts
    assert len({(lay.walls, lay.obstacles) for lay in layouts}) >= len(layouts) - 2


def test_no_global_random_state_is_used_or_touched() -> None:
    # The legacy global generator is used here on purpose: to show that nothing else uses it.
    state = np.random.get_state()  # noqa: NPY002
    first = generate_layout("forest", 7)
    after = np.random.get_state()  # noqa: NPY002
    assert all(np.array_equal(a, b) for a, b in zip(state, after, strict=True))
    np.random.seed(99)  # noqa: NPY002
    assert generate_layout("forest", 7) == first


@pytest.mark.parametrize("family", sorted(FAMILIES))
def test_every_seed_gives_a_solvable_layout_inside_its_arena(family: str) -> None:
    for seed in SEEDS:
        layout = generate_layout(family, seed)
        assert goal_reachable(layout, layout.robot_radius)
        assert float(clearance(layout, np.array(layout.start))) >= layout.robot_radius
        assert math.dist(layout.start, layout.goal) > layout.goal_radius
        for wall in layout.walls:
            assert wall.center[0] - wall.size[0] / 2 >= 0.0
            assert wall.center[0] + wall.size[0] / 2 <= layout.arena[0]
        for tree in layout.obstacles:
            assert tree.radius <= tree.center[0] <= layout.arena[0] - tree.radius


@pytest.mark.parametrize(
    "spec",
    [
        "rooms:seed=4",
        "rooms:seed=5,door=11.1,loops=0",  # a door 1.1 wider than the robot's diameter
        "forest:seed=4,count=90,radius_max=8,gap=10.5",
        "serpentine:seed=4,stubs=3",
        "maze:seed=4,rows=10,cols=10,cell=30",
    ],
)
def test_the_optimum_of_generated_layouts_keeps_the_robot_clear(spec: str) -> None:
    layout = load_layout(spec)
    limit = shortest_path(layout)
    assert limit.length <= limit.l1_length + 1e-9
    assert limit.steps == math.ceil(limit.l1_length / 5.0 - 1e-9)
    t = np.linspace(0.0, 1.0, 400)[:, None]
    for a, b in itertools.pairwise(limit.waypoints):
        assert clearance(layout, a + t * (b - a)).min() >= layout.robot_radius - 0.06
    assert math.dist(limit.waypoints[-1], layout.goal) <= layout.goal_radius + 1e-9


def test_the_narrowest_door_is_a_little_wider_than_the_robot() -> None:
    with pytest.raises(ValueError, match=r"'door' = 11 must be at least 11\.02"):
        generate_layout("rooms", 0, door=11.0)
    layout = generate_layout("rooms", 0, door=11.02, loops=0.0)
    assert goal_reachable(layout, layout.robot_radius)
    assert layout.robot_radius == 5.0


@pytest.mark.parametrize("spec", ["maze:seed=2", "serpentine:seed=3"])
def test_the_noise_free_plan_succeeds_in_the_simulator(
    make_env: Callable[..., gym.Env], spec: str
) -> None:
    env = make_env(maze=spec, noise_variance=0.0)
    env.reset(seed=0)
    limit = env.unwrapped.physical_limit
    assert limit.lattice_steps is not None
    for action in limit.actions:
        _, reward, terminated, _, info = env.step(action)
        assert not info["collision"]
    assert terminated
    assert reward == 5.0


def test_a_spec_names_the_same_layout_as_the_call() -> None:
    layout = load_layout("rooms:seed=3,door=30")
    assert layout == generate_layout("rooms", 3, door=30)
    assert layout.name == "rooms:seed=3"  # 30 is the default door
    assert load_layout(" rooms:seed=3, door = 24.0 ".strip()).name == "rooms:seed=3,door=24"
    assert load_layout("maze:").name == "maze:seed=0"
    assert layout.source == layout.name


def test_gymnasium_make_takes_a_spec(make_env: Callable[..., gym.Env]) -> None:
    env = make_env(maze="maze:seed=1,rows=4,cols=5")
    obs, _ = env.reset(seed=0)
    assert env.unwrapped.layout.arena == (250.0, 200.0)
    assert tuple(obs) == (25.0, 25.0)
    assert env.unwrapped.optimal_steps == shortest_path(env.unwrapped.layout).steps


def test_generate_writes_a_file_that_loads_as_the_same_layout(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "my.toml"
    for family in FAMILIES:
        spec = f"{family}:seed=11"
        assert layout_cli(["generate", spec, "--out", str(out), "--force"]) == 0
        assert load_layout(out) == load_layout(spec)
        assert load_layout(str(out)).source == str(out)
    assert "wrote" in capsys.readouterr().out
    with pytest.raises(SystemExit) as exit_info:
        layout_cli(["generate", "maze:seed=1", "--out", str(out)])
    assert exit_info.value.code == 2
    assert "exists" in capsys.readouterr().err


def test_layout_to_toml_round_trips_every_family(tmp_path: Path) -> None:
    for i, family in enumerate(FAMILIES):
        layout = generate_layout(family, 100 + i)
        path = tmp_path / f"{family}.toml"
        path.write_text(layout_to_toml(layout, header="a comment\nand another"))
        assert load_layout(path) == layout


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        (lambda: generate_layout("roomz", 0), ValueError, r"unknown layout family 'roomz'.*rooms"),
        (lambda: generate_layout(3, 0), ValueError, r"unknown layout family 3"),
        (lambda: generate_layout("rooms", -1), ValueError, r"seed must be in \[0, 2\*\*63 - 1\]"),
        (lambda: generate_layout("rooms", 2**63), ValueError, r"seed must be in"),
        (lambda: generate_layout("rooms", True), TypeError, r"seed must be an integer"),
        (lambda: generate_layout("rooms", 1.5), TypeError, r"seed must be an integer"),
        (lambda: generate_layout("rooms", "1"), TypeError, r"seed must be an integer"),
        (lambda: generate_layout("rooms", 0, dor=30), ValueError, r"unknown parameter 'dor'"),
        (lambda: generate_layout("rooms", 0, door=True), TypeError, r"'door' must be a number"),
        (lambda: generate_layout("rooms", 0, door="30"), TypeError, r"'door' must be a number"),
        (lambda: generate_layout("rooms", 0, door=math.nan), ValueError, r"'door' = nan"),
        (lambda: generate_layout("rooms", 0, door=math.inf), ValueError, r"'door' = inf"),
        (lambda: generate_layout("rooms", 0, door=-3), ValueError, r"outside its bounds"),
        (lambda: generate_layout("rooms", 0, rows=2.0), TypeError, r"'rows' must be an integer"),
        (lambda: generate_layout("rooms", 0, rows=10**9), ValueError, r"'rows' = 1000000000"),
        (lambda: generate_layout("rooms", 0, rows=1, cols=1), ValueError, r"at least 2"),
        (lambda: generate_layout("rooms", 0, door=95), ValueError, r"does not fit.*94"),
        (
            lambda: generate_layout("rooms", 0, rows=40, cols=40),
            ValueError,
            r"arena of 4000 x 4000, larger than MAX_ARENA_SIDE 2000",
        ),
        (lambda: generate_layout("forest", 0, count=4000), ValueError, r"could not place tree"),
        (
            lambda: generate_layout("forest", 0, radius_min=9, radius_max=3),
            ValueError,
            r"'radius_max' = 3 must be at least 9",
        ),
        (lambda: generate_layout("forest", 0, gap=0.0, count=600), ValueError, r"tree"),
        (lambda: generate_layout("maze", 0, cell=14), ValueError, r"'cell' = 14 must be at"),
        (lambda: generate_layout("maze", 0, rows=100, cols=100), ValueError, r"5000 x 5000"),
        (lambda: generate_layout("serpentine", 0, width=10), ValueError, r"'width' = 10"),
        (lambda: generate_layout("serpentine", 0, stubs=50), ValueError, r"50 stubs.*do not fit"),
        (
            lambda: generate_layout("maze", 0, robot_radius=0.01),
            ValueError,
            r"'robot_radius' = 0.01 is outside its bounds \[0.1, 100\]",
        ),
        (
            lambda: generate_layout("maze", 0, rows=2, cols=2, goal_radius=80),
            ValueError,
            r"maze:seed=0,rows=2,cols=2,goal_radius=80: no valid layout.*inside the goal circle",
        ),
        (lambda: load_layout("rooms:door"), ValueError, r"expected key=value, got 'door'"),
        (lambda: load_layout("rooms:door=1,door=2"), ValueError, r"'door' given twice"),
        (lambda: load_layout("rooms:door=nan"), ValueError, r"'door' must be a finite number"),
        (lambda: load_layout("rooms:door=1e999"), ValueError, r"'door' must be a finite number"),
        (lambda: load_layout("rooms:door=true"), ValueError, r"'door' must be a finite number"),
        (lambda: load_layout("rooms:seed=1.5"), ValueError, r"seed must be an integer"),
        (lambda: load_layout("rooms:seed=-2"), ValueError, r"seed must be in"),
        (lambda: load_layout("rooms:,"), ValueError, r"expected key=value, got ''"),
        (lambda: load_layout("castle:seed=1"), ValueError, r"unknown layout family 'castle'"),
    ],
)
def test_bad_families_and_parameters_are_named(
    call: Callable[[], object], error: type[Exception], match: str
) -> None:
    with pytest.raises(error, match=match):
        call()
