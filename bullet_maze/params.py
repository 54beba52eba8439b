"""Every number of the simulation in one place: the paper's task values and the physics settings.

The task values are those of the paper's section V.A (Hwang, Li and Jiang, "Adaptive Exploration
Strategies for Reinforcement Learning"): a step of 5.0 maze units, Gaussian noise of mean 0 and
variance 0.3 on each axis, rewards +5 / -1 / -0.01 and episodes capped at 5,000 steps.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

METRES_PER_UNIT = 0.1
"""World scale: one maze unit is 0.1 m in pybullet, so the paper's 300 x 300 arena is 30 m wide,
a step of 5.0 units is 0.5 m and the default robot (radius 5 units) is a 1 m disc. At this scale
the husky from ``pybullet_data`` is used near its real size and contacts stay well resolved at the
default 240 Hz physics rate."""

MAX_EPISODE_STEPS = 5000
"""Section V.A: an episode ends at the goal or after 5,000 steps (set in the registration)."""

WALL_HEIGHT = 10.0
"""Height of walls and obstacles in maze units (1 m), taller than every robot."""

BOUNDARY_THICKNESS = 10.0
"""Thickness of the four arena walls in maze units, outside the arena."""

MODES = ("kinematic", "dynamic")
"""Actuation modes: ``kinematic`` is the paper's exact step, ``dynamic`` runs physics substeps."""

# Bounds: every size that could exhaust memory or time has one, checked where it is given (the
# layout file, the generator's parameters, the env's arguments) with a ValueError that names it.

MAX_ARENA_SIDE = 2000.0
"""Longest arena side in maze units (200 m). The simulation's per-cell collision cache holds at
most (side / 5)^2 entries, and the physical limit's grid at most ``MAX_PLANNER_NODES`` nodes."""

MAX_SOLIDS = 4000
"""Most walls and obstacles in one layout. Building the world, planning and rendering grow with
the count (``docs/benchmarks.md``, section *Layouts at scale*); a kinematic step does not."""

MIN_SOLID_SIZE = 0.01
"""Least wall side and obstacle radius in maze units (1 mm): thinner shapes are degenerate for
pybullet's collision detection."""

MAX_PLANNER_NODES = 400_000
"""Most nodes of the physical limit's grid (``bullet_maze.planning``): about 0.5 s and 120 MB.
The grid's cell is 0.5 units or finer where the robot and goal need it, and coarser in arenas
larger than about 316 x 316, where the cell is ``sqrt(width * height / MAX_PLANNER_NODES)``."""

MIN_ROBOT_RADIUS = 0.1
"""Least robot radius in maze units (1 cm). Radii must also be at least the planning grid's
coarsest cell, ``sqrt(width * height / MAX_PLANNER_NODES)``, so that the grid resolves the robot
and the goal circle (0.47 units in a 300 x 300 arena, 1.58 in 1,000 x 1,000)."""

MAX_LAYOUT_FILE_BYTES = 4_000_000
"""Largest layout or suite file read (4 MB; a layout of ``MAX_SOLIDS`` solids takes about
250 KB)."""

MAX_RENDER_SIDE = 2048
"""Largest rendered image side in pixels: a 2,048 x 2,048 TinyRenderer image takes about 1 s
and 260 MB (pybullet aborts the process at 100,000 and crashes at 20,000)."""

MAX_STEP_SIZE = 100.0
"""Longest nominal move of one action in maze units (20 steps of the paper's 5.0)."""

MAX_NOISE_VARIANCE = 100.0
"""Largest per-axis noise variance (standard deviation 10 maze units, two of the paper's steps)."""

MAX_SUBSTEPS = 10_000
"""Most physics steps per env step (``substeps``, ``max_turn_substeps``,
``max_drive_substeps``): a husky step of 10,000 physics steps takes about half a second."""

MAX_SOLVER_ITERATIONS = 1000
"""Most constraint-solver iterations per physics step (pybullet's default is 50)."""

MIN_TIME_STEP = 1e-4
"""Shortest physics time step in seconds (10 kHz); the longest is 0.1 s."""


@dataclass(frozen=True)
class TaskParams:
    """The maze task of section V.A; every field is a keyword argument of the env."""

    step_size: float = 5.0
    """Length of one action's nominal move in maze units (section V.A: 5.0)."""
    noise_variance: float = 0.3
    """Variance of the zero-mean Gaussian noise added to each axis of a move (section V.A: 0.3)."""
    goal_reward: float = 5.0
    """Reward for reaching the goal, which terminates the episode (section V.A: +5)."""
    collision_reward: float = -1.0
    """Reward for hitting a wall or an obstacle; the robot stays put (section V.A: -1)."""
    step_reward: float = -0.01
    """Reward of every other step (section V.A: -0.01)."""

    def __post_init__(self) -> None:
        for name in (
            "step_size",
            "noise_variance",
            "goal_reward",
            "collision_reward",
            "step_reward",
        ):
            value = getattr(self, name)
            if (
                isinstance(value, bool)
                or not isinstance(value, int | float)
                or not math.isfinite(value)
            ):
                raise ValueError(f"{name} must be a finite number, got {value!r}")
        if self.step_size <= 0:
            raise ValueError(f"step_size must be positive, got {self.step_size!r}")
        if self.step_size > MAX_STEP_SIZE:
            raise ValueError(
                f"step_size must be at most {MAX_STEP_SIZE:g} maze units "
                f"(bullet_maze.params.MAX_STEP_SIZE), got {self.step_size!r}"
            )
        if self.noise_variance < 0:
            raise ValueError(f"noise_variance must be >= 0, got {self.noise_variance!r}")
        if self.noise_variance > MAX_NOISE_VARIANCE:
            raise ValueError(
                f"noise_variance must be at most {MAX_NOISE_VARIANCE:g} "
                f"(bullet_maze.params.MAX_NOISE_VARIANCE), got {self.noise_variance!r}"
            )

    @property
    def noise_std(self) -> float:
        """Standard deviation of the per-axis noise, the square root of its variance."""
        return math.sqrt(self.noise_variance)


@dataclass(frozen=True)
class PhysicsParams:
    """Settings of ``mode="dynamic"`` and of the kinematic sweep (``contact_release``); every
    field is a keyword argument of the env."""

    time_step: float = 1.0 / 240.0
    """pybullet's fixed time step in seconds (its default, 240 Hz)."""
    substeps: int = 4
    """Physics steps per env step for holonomic robots: a step lasts ``substeps * time_step``
    (1/60 s by default). The env raises it, if needed, so that no substep moves the robot
    farther than its radius: a body that jumps further could pass through a thin wall."""
    solver_iterations: int = 10
    """Constraint solver iterations per physics step (pybullet's default is 50): ten resolve a
    disc or a husky on a floor against static walls, and each physics step costs 25 % less."""
    revert_on_collision: bool = True
    """A step that touches a wall or an obstacle is undone, as in the paper; if False, physics
    resolves the contact and the robot stays where it came to rest (still rewarded -1)."""
    max_turn_substeps: int = 360
    """Upper bound on the physics steps a wheeled robot may spend turning towards a step (at the
    husky's 40 Hz compass physics a quarter turn takes about 35)."""
    max_drive_substeps: int = 240
    """Upper bound on the physics steps a wheeled robot may spend driving one step."""
    tip_angle: float = math.pi / 3.0
    """Radians between the robot's up axis and the vertical past which a dynamic robot has
    tipped over (60 degrees; ``place`` stands every robot upright, 0). A tipped robot lies on
    its side and no command moves it again (pybullet_data's tall ``r2d2.urdf`` falls on its
    third compass step), so ``info["tipped"]`` reports it at every dynamic step. pi: never."""
    end_on_tip: bool = False
    """A step that leaves the robot tipped ends the episode as truncated (a cut, not a terminal
    state, so that ending there is no escape from the step rewards for an agent that
    bootstraps as at a time limit); it saves the physics of a robot that will not move again.
    False (default): the episode goes on, the robot lying where it fell, until the time limit,
    so a fall counts as a failure of the full length in every step count. The experiment
    harness counts a failed episode's steps at the cap and refuses True."""
    contact_release: bool = True
    """The kinematic sweep (``World.sweep_collides``, both modes' exact moves): a robot within
    the contact tolerance of a solid may still move away from it or along it; only a move
    towards it is a collision. False keeps the sweep as it was before 2026-12-07, which refused
    every move that started inside the band, so a robot whose move ended there was held, every
    action a collision, for the rest of the episode (issue 9, part 31): only to reproduce
    results recorded before the fix."""

    def __post_init__(self) -> None:
        if not (
            isinstance(self.time_step, int | float)
            and not isinstance(self.time_step, bool)
            and MIN_TIME_STEP <= self.time_step <= 0.1
        ):
            raise ValueError(
                f"time_step must be in [{MIN_TIME_STEP:g}, 0.1] seconds, got {self.time_step!r}"
            )
        for name in ("substeps", "solver_iterations", "max_turn_substeps", "max_drive_substeps"):
            value = getattr(self, name)
            if not isinstance(value, int) or isinstance(value, bool) or value < 1:
                raise ValueError(f"{name} must be a positive integer, got {value!r}")
            bound = MAX_SOLVER_ITERATIONS if name == "solver_iterations" else MAX_SUBSTEPS
            if value > bound:
                raise ValueError(
                    f"{name} must be at most {bound:,} (bullet_maze.params), got {value!r}"
                )
        if not isinstance(self.revert_on_collision, bool):
            raise TypeError(f"revert_on_collision must be a bool, got {self.revert_on_collision!r}")
        if not isinstance(self.contact_release, bool):
            raise TypeError(f"contact_release must be a bool, got {self.contact_release!r}")
        if not isinstance(self.end_on_tip, bool):
            raise TypeError(f"end_on_tip must be a bool, got {self.end_on_tip!r}")
        if not (
            isinstance(self.tip_angle, int | float)
            and not isinstance(self.tip_angle, bool)
            and 0.0 < self.tip_angle <= math.pi
        ):
            raise ValueError(f"tip_angle must be in (0, pi] radians, got {self.tip_angle!r}")
