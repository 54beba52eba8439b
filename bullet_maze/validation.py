"""Every check a layout must pass, in one place: sizes within their bounds, solids inside the
arena, start and goal placed where the robot can be and can get.

``validate_layout`` is what ``load_layout`` and the generators call; ``check_placement`` is its
part about one start and one goal, for callers that move them (the env's reset options). Every
failure is a ``ValueError`` that names where the value came from (``source``, the field or the
option), the value and the bound it breaks.
"""

from __future__ import annotations

import math

import numpy as np

from bullet_maze.geometry import clearance
from bullet_maze.layout_types import MazeLayout
from bullet_maze.params import MAX_ARENA_SIDE, MAX_SOLIDS, MIN_ROBOT_RADIUS, MIN_SOLID_SIZE
from bullet_maze.planning import coarsest_cell, goal_reachable


def validate_layout(layout: MazeLayout, robot_radius: float | None = None) -> None:
    """Check ``layout`` for a robot of ``robot_radius`` (default: the layout's own).

    Sizes (``check_sizes``), every solid inside the arena, and the layout's start and goal
    (``check_placement``). Raises ``ValueError`` naming ``layout.source`` and the field.
    """
    radius = layout.robot_radius if robot_radius is None else robot_radius
    check_sizes(layout, radius)
    check_solids_inside(layout)
    check_placement(layout, radius, layout.start, layout.goal)


def check_sizes(layout: MazeLayout, robot_radius: float) -> None:
    """The bounds of ``bullet_maze.params`` that keep memory and time bounded: the arena's
    sides, the number of solids, the least solid size, and robot and goal radii no smaller than
    the planning grid resolves in this arena (``planning.coarsest_cell``)."""
    src = layout.source
    _check_numbers(layout, robot_radius)
    for axis, side in enumerate(layout.arena):
        if not 0.0 < side <= MAX_ARENA_SIDE:
            raise ValueError(
                f"{src}: field 'arena.size[{axis}]' = {side:g} is outside (0, "
                f"{MAX_ARENA_SIDE:g}] maze units (bullet_maze.params.MAX_ARENA_SIDE)"
            )
    if layout.solid_count > MAX_SOLIDS:
        raise ValueError(
            f"{src}: {len(layout.walls)} walls and {len(layout.obstacles)} obstacles make "
            f"{layout.solid_count:,} solids, more than the {MAX_SOLIDS:,} allowed "
            "(bullet_maze.params.MAX_SOLIDS)"
        )
    for i, obstacle in enumerate(layout.obstacles):
        if not obstacle.radius >= MIN_SOLID_SIZE:
            raise ValueError(
                f"{src}: field 'obstacles[{i}].radius' = {obstacle.radius:g} is below the "
                f"least solid size {MIN_SOLID_SIZE:g} (bullet_maze.params.MIN_SOLID_SIZE)"
            )
    for i, wall in enumerate(layout.walls):
        for axis, side in enumerate(wall.size):
            if not side >= MIN_SOLID_SIZE:
                raise ValueError(
                    f"{src}: field 'walls[{i}].size[{axis}]' = {side:g} is below the least "
                    f"solid size {MIN_SOLID_SIZE:g} (bullet_maze.params.MIN_SOLID_SIZE)"
                )
    cell = coarsest_cell(layout.arena)
    least = max(MIN_ROBOT_RADIUS, cell)
    arena = f"{layout.arena[0]:g} x {layout.arena[1]:g}"
    if not robot_radius >= least:
        raise ValueError(
            f"{src}: robot radius {robot_radius:g} is below the least radius {least:.3g} for a "
            f"{arena} arena (the planning grid's coarsest cell there is {cell:.3g}: "
            "bullet_maze.params.MAX_PLANNER_NODES; at least MIN_ROBOT_RADIUS "
            f"{MIN_ROBOT_RADIUS:g})"
        )
    if not layout.goal_radius >= cell:
        raise ValueError(
            f"{src}: field 'goal.radius' = {layout.goal_radius:g} is below the least goal radius "
            f"{cell:.3g} for a {arena} arena (the planning grid's coarsest cell there: "
            "bullet_maze.params.MAX_PLANNER_NODES)"
        )
    if not layout.start_size <= max(layout.arena):
        raise ValueError(
            f"{src}: field 'start.size' = {layout.start_size:g} is larger than the arena ({arena})"
        )


def _check_numbers(layout: MazeLayout, robot_radius: float) -> None:
    """Every number of the layout a finite real number (a bool is not one)."""
    named: list[tuple[str, object]] = [
        ("arena.size", layout.arena),
        ("start.position", layout.start),
        ("goal.position", layout.goal),
        ("goal.radius", layout.goal_radius),
        ("robot_radius", robot_radius),
        ("start.heading", layout.start_heading),
        ("start.size", layout.start_size),
    ]
    named += [(f"obstacles[{i}].center", o.center) for i, o in enumerate(layout.obstacles)]
    named += [(f"obstacles[{i}].radius", o.radius) for i, o in enumerate(layout.obstacles)]
    named += [(f"walls[{i}].center", w.center) for i, w in enumerate(layout.walls)]
    named += [(f"walls[{i}].size", w.size) for i, w in enumerate(layout.walls)]
    for name, value in named:
        values = value if isinstance(value, tuple) else (value,)
        if not (isinstance(value, tuple) and len(value) == 2) and isinstance(value, tuple):
            raise ValueError(f"{layout.source}: field '{name}' must be a pair, got {value!r}")
        for v in values:
            if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
                raise ValueError(
                    f"{layout.source}: field '{name}' must hold finite numbers, got {value!r}"
                )


def check_solids_inside(layout: MazeLayout) -> None:
    """Every wall and obstacle lies within the arena ``[0, width] x [0, height]``."""
    width, height = layout.arena
    shapes = [
        (f"obstacles[{i}]", o.center, (o.radius, o.radius)) for i, o in enumerate(layout.obstacles)
    ] + [
        (f"walls[{i}]", w.center, (w.size[0] / 2, w.size[1] / 2))
        for i, w in enumerate(layout.walls)
    ]
    for name, (cx, cy), (hx, hy) in shapes:
        if not (cx - hx >= 0.0 and cx + hx <= width and cy - hy >= 0.0 and cy + hy <= height):
            raise ValueError(
                f"{layout.source}: {name} (centre ({cx:g}, {cy:g})) extends outside the arena "
                f"[0, {width:g}] x [0, {height:g}]: it spans [{cx - hx:g}, {cx + hx:g}] x "
                f"[{cy - hy:g}, {cy + hy:g}]"
            )


def check_placement(
    layout: MazeLayout,
    robot_radius: float,
    start: tuple[float, float],
    goal: tuple[float, float],
    *,
    start_name: str = "field 'start.position'",
    goal_name: str = "field 'goal.position'",
    prefix: str | None = None,
) -> None:
    """A start and a goal in ``layout`` for a robot of ``robot_radius``: both strictly inside
    the arena, the goal's centre in no solid, the robot's disc at the start touching none, the
    start outside the goal circle, and the goal circle reachable from the start
    (``planning.goal_reachable``).

    ``start_name`` and ``goal_name`` say in messages where the two came from (by default the
    layout's fields; the env passes ``"options['start']"``); ``prefix`` starts each message
    (default: the layout's source and a colon).
    """
    head = f"{layout.source}: " if prefix is None else prefix
    width, height = layout.arena
    for name, (x, y) in ((start_name, start), (goal_name, goal)):
        if not layout.contains(x, y):
            raise ValueError(
                f"{head}{name} = ({x:g}, {y:g}) lies outside the arena "
                f"[0, {width:g}] x [0, {height:g}]"
            )
    for i, obstacle in enumerate(layout.obstacles):
        if math.dist(goal, obstacle.center) < obstacle.radius:
            raise ValueError(f"{head}{goal_name} = {goal} lies inside obstacles[{i}]")
    for i, wall in enumerate(layout.walls):
        if (
            abs(goal[0] - wall.center[0]) < wall.size[0] / 2
            and abs(goal[1] - wall.center[1]) < wall.size[1] / 2
        ):
            raise ValueError(f"{head}{goal_name} = {goal} lies inside walls[{i}]")
    start_clearance = float(clearance(layout, np.array(start)))
    if not start_clearance >= robot_radius:
        raise ValueError(
            f"{head}{start_name} = {start}: a robot of radius {robot_radius:g} there overlaps "
            f"a wall or an obstacle (clearance {start_clearance:.2f})"
        )
    if math.dist(start, goal) <= layout.goal_radius:
        raise ValueError(
            f"{head}{start_name} = {start} lies inside the goal circle (centre {goal}, radius "
            f"{layout.goal_radius:g}): the episode would end before its first step"
        )
    if not goal_reachable(layout, robot_radius, start, goal):
        raise ValueError(
            f"{head}{goal_name} = {goal}: the goal circle (radius {layout.goal_radius:g}) cannot "
            f"be reached from {start_name} = {start} by a robot of radius {robot_radius:g}"
        )
