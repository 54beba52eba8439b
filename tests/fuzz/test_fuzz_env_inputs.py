"""Hostile environment settings given to the harness (experiment files, ``--maze``), and the
import graph.

Each case is written as the clear error it must give, whether the harness or the simulation
refuses it.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from experiments import ConfigError, Experiment
from experiments.config import EXPERIMENT_DIR, parse_config

ROOT = EXPERIMENT_DIR.parent

BASE = {
    "experiment": {"name": "hostile", "runs": 1, "episodes": 1},
    "env": {"max_episode_steps": 5},
    "strategy": [{"name": "eps", "exploration": "epsilon-greedy"}],
}


def _experiment(tmp_path: Path, env: dict) -> Experiment:
    data = {**BASE, "env": {**BASE["env"], **env}}
    return Experiment(parse_config(data, source="hostile.toml"), tmp_path / "out")


def test_a_bool_for_the_robot_radius_is_refused(tmp_path: Path):
    with pytest.raises(ConfigError, match=r"\[env.params\] robot_radius: expected a number"):
        _experiment(tmp_path, {"params": {"robot_radius": True}})


def test_a_render_width_that_exhausts_memory_is_refused(tmp_path: Path):
    with pytest.raises(ConfigError, match="render_width"):
        _experiment(tmp_path, {"params": {"render_width": 100_000}}).check()


def test_a_step_size_that_takes_minutes_a_step_is_refused(tmp_path: Path):
    with pytest.raises(ConfigError, match="step_size"):
        _experiment(tmp_path, {"mode": "dynamic", "params": {"step_size": 1e9}}).check()


def test_substeps_that_take_minutes_a_step_are_refused(tmp_path: Path):
    with pytest.raises(ConfigError, match="substeps"):
        _experiment(tmp_path, {"mode": "dynamic", "params": {"substeps": 10**8}}).check()


LAYOUT = """
[arena]
size = [300.0, 300.0]
[start]
position = {start}
[goal]
position = [150.0, 270.0]
radius = 15.0
{extra}
"""


def test_a_maze_whose_start_lies_in_the_goal_is_refused_naming_the_option(tmp_path: Path):
    from experiments import EnvOptions, factory
    from experiments.config import load_config

    maze = tmp_path / "bad.toml"
    maze.write_text(LAYOUT.format(start="[150.0, 270.0]", extra=""))
    config, origins = EnvOptions(maze=str(maze)).apply(load_config("quick"))
    with pytest.raises(ConfigError, match=r"option --maze: .*start"):
        factory.check_env(config.env, origins).close()


def test_a_maze_with_an_obstacle_outside_the_arena_is_refused(tmp_path: Path):
    maze = tmp_path / "bad.toml"
    extra = "[[obstacles]]\ncenter = [900.0, 900.0]\nradius = 10.0\n"
    maze.write_text(LAYOUT.format(start="[150.0, 30.0]", extra=extra))
    with pytest.raises(ConfigError, match="obstacles"):
        _experiment(tmp_path, {"maze": str(maze)}).check()


def test_a_string_start_in_reset_options_is_refused():
    import bullet_maze

    env = bullet_maze.BulletMazeEnv()
    try:
        with pytest.raises((TypeError, ValueError), match="start"):
            env.reset(options={"start": "99"})
    finally:
        env.close()


def _imports(package: str) -> dict[str, set[str]]:
    """Every module's imports of modules of ``package`` (module level, in functions, and under
    TYPE_CHECKING: a circle is a circle wherever the import sits)."""
    files = {
        ".".join(p.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__"): p
        for p in (ROOT / package).rglob("*.py")
    }
    graph: dict[str, set[str]] = {}
    for name, path in files.items():
        found: set[str] = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                found |= {a.name for a in node.names}
            elif isinstance(node, ast.ImportFrom) and node.module:
                for alias in node.names:
                    sub = f"{node.module}.{alias.name}"
                    found.add(sub if sub in files else node.module)
        graph[name] = {m for m in found if m in files and m != name}
    return graph


def _cycle(graph: dict[str, set[str]]) -> list[str] | None:
    state: dict[str, int] = {}
    path: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        path.append(node)
        for nxt in sorted(graph[node]):
            if state.get(nxt) == 1:
                return [*path[path.index(nxt) :], nxt]
            if nxt not in state and (found := visit(nxt)):
                return found
        path.pop()
        state[node] = 2
        return None

    for start in sorted(graph):
        if start not in state and (found := visit(start)):
            return found
    return None


@pytest.mark.parametrize("package", ["agent", "experiments"])
def test_no_import_circles(package: str):
    assert _cycle(_imports(package)) is None


def test_no_import_circles_in_the_simulation():
    assert _cycle(_imports("bullet_maze")) is None
