"""``BulletMazeEnv``: the maze of section V.A as a Gymnasium environment in headless pybullet."""

from __future__ import annotations

import contextlib
import dataclasses
import logging
import math
import os
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any, SupportsFloat

import gymnasium as gym
import numpy as np
import pybullet as pb
from gymnasium import spaces

from bullet_maze.actions import DIRECTIONS
from bullet_maze.geometry import clearance
from bullet_maze.layout import DEFAULT_LAYOUT, MazeLayout, load_layout
from bullet_maze.params import MODES, PhysicsParams, TaskParams
from bullet_maze.planning import PhysicalLimit, goal_reachable, shortest_path
from bullet_maze.rendering import TopDownCamera
from bullet_maze.robots import Robot, make_robot, wrap_angle
from bullet_maze.validation import validate_layout
from bullet_maze.world import CONTACT_TOLERANCE, World

logger = logging.getLogger(__name__)

NOISE_BLOCK = 1024
"""Steps of noise drawn from ``np_random`` at once (one draw per step costs more than a step)."""

_FAST_ACTION_TYPES = frozenset((int, np.int64))
"""Action types ``step`` looks up without conversion (``bool`` is not one: it is refused)."""

_TASK = TaskParams()
_PHYSICS = PhysicsParams()


class BulletMazeEnv(gym.Env[np.ndarray, np.int64]):
    """
    ## Description

    The robot maze of section V.A of Hwang, Li and Jiang, "Adaptive Exploration Strategies for
    Reinforcement Learning", simulated in headless pybullet: a walled 300 x 300 arena with grey
    cylindrical obstacles, a green start square and a red goal circle. The robot moves in four
    directions by steps of 5.0 units with Gaussian noise; it must reach the goal.

    Layouts are TOML files (`assets/mazes/`, see `bullet_maze.load_layout`); robots are
    swappable (`"disc"`, `"husky"` or any URDF path).

    ## Action Space

    `Discrete(4)`, the `bullet_maze.Action` enum:

    | Num | Action | Move (maze units)          |
    |-----|--------|----------------------------|
    | 0   | UP     | (0, +step_size) + noise    |
    | 1   | DOWN   | (0, -step_size) + noise    |
    | 2   | LEFT   | (-step_size, 0) + noise    |
    | 3   | RIGHT  | (+step_size, 0) + noise    |

    The noise is Gaussian, mean 0 and variance `noise_variance` (0.3) on each axis, drawn from
    the env's seeded `np_random`.

    ## Observation Space

    `Box(float64)` of the robot's pose in maze units (x to the right, y up, origin at the arena's
    lower-left corner):

    | Num | Observation | Min  | Max          |
    |-----|-------------|------|--------------|
    | 0   | x           | 0    | arena width  |
    | 1   | y           | 0    | arena height |
    | 2   | heading     | -pi  | pi           |

    The heading (radians from +x) is present only for robots that have one (the husky); the
    disc and user URDFs observe `(x, y)`.

    ## Rewards

    Section V.A: `goal_reward` (+5) when the step ends with the robot's centre inside the goal
    circle, `collision_reward` (-1) when the step touches a wall or an obstacle, `step_reward`
    (-0.01) otherwise.

    ## Starting State

    The layout's start pose (the centre of the start square), or `options["start"]`.

    ## Episode End

    1. Termination: the robot's centre is within the goal radius of the goal centre.
    2. Truncation: 5,000 steps (section V.A), set by the registration's `max_episode_steps`.

    A collision never ends the episode.

    ## Modes

    * `"kinematic"` (default), the paper's exact step: the straight move from the current to the
      proposed position is swept with the robot's footprint disc against the walls and obstacles
      with pybullet distance queries; if it touches anything the robot stays put.
    * `"dynamic"`: the move is a velocity command run through `substeps` physics steps with mass,
      friction and contacts (the husky turns in place, then drives, through its wheels). A step
      that touches a solid is undone if `revert_on_collision` (default, as the paper), otherwise
      physics resolves the contact. The realised move is close to, not exactly, the commanded one.

    ## Arguments

    ```python
    import gymnasium as gym
    import bullet_maze  # registers the ids

    env = gym.make("BulletMaze-v0", maze="paper", robot="disc", mode="kinematic")
    ```

    * `maze`: a layout name (`paper`, `paper_narrow`, `open`, `corridors`), a TOML path or a
      `MazeLayout`.
    * `robot`: `"disc"`, `"husky"` or a URDF path; `robot_radius` rescales it to that
      footprint radius (default: the layout's robot radius; a user URDF keeps its own size).
    * `mode`: `"kinematic"` or `"dynamic"`; `render_mode`: `None`, `"rgb_array"` (a top-down
      TinyRenderer image, no display needed) or `"human"` (the pybullet GUI).
    * `step_size`, `noise_variance`, `goal_reward`, `collision_reward`, `step_reward`: the task,
      defaults from section V.A (`bullet_maze.params.TaskParams`).
    * `time_step`, `substeps`, `solver_iterations`, `revert_on_collision`,
      `max_turn_substeps`, `max_drive_substeps`: dynamic mode
      (`bullet_maze.params.PhysicsParams`).
    * `render_width`, `render_height`: image size in pixels.

    `reset(seed=..., options={"start": (x, y) or (x, y, heading), "goal": (x, y)})` moves the
    start and the goal for that episode (validated). `info` has `collision`,
    `distance_to_goal` and `is_success`. `env.unwrapped.optimal_steps` is the least number of
    steps that can reach the goal (see `bullet_maze.shortest_path`).

    ## Version History

    * v0: initial version.
    """

    metadata = {"render_modes": ["human", "rgb_array"], "render_fps": 30}  # noqa: RUF012

    def __init__(
        self,
        maze: str | Path | MazeLayout = DEFAULT_LAYOUT,
        robot: str | Path = "disc",
        mode: str = "kinematic",
        render_mode: str | None = None,
        *,
        step_size: float = _TASK.step_size,
        noise_variance: float = _TASK.noise_variance,
        goal_reward: float = _TASK.goal_reward,
        collision_reward: float = _TASK.collision_reward,
        step_reward: float = _TASK.step_reward,
        time_step: float = _PHYSICS.time_step,
        substeps: int = _PHYSICS.substeps,
        solver_iterations: int = _PHYSICS.solver_iterations,
        revert_on_collision: bool = _PHYSICS.revert_on_collision,
        max_turn_substeps: int = _PHYSICS.max_turn_substeps,
        max_drive_substeps: int = _PHYSICS.max_drive_substeps,
        robot_radius: float | None = None,
        render_width: int = 256,
        render_height: int = 256,
    ) -> None:
        if mode not in MODES:
            raise ValueError(f"mode must be one of {list(MODES)}, got {mode!r}")
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(
                f"render_mode must be None or one of "
                f"{self.metadata['render_modes']}, got {render_mode!r}"
            )
        if robot_radius is not None and not (
            isinstance(robot_radius, int | float) and 0 < robot_radius < math.inf
        ):
            raise ValueError(f"robot_radius must be a positive number, got {robot_radius!r}")
        self.task = TaskParams(
            step_size, noise_variance, goal_reward, collision_reward, step_reward
        )
        self.physics = PhysicsParams(
            time_step,
            substeps,
            solver_iterations,
            revert_on_collision,
            max_turn_substeps,
            max_drive_substeps,
        )
        self.layout = load_layout(maze)
        self.mode = mode
        self._kinematic = mode == "kinematic"
        self.render_mode = render_mode
        self._camera = TopDownCamera(self.layout.arena, render_width, render_height)
        self._client = -1
        self._client = self._connect(render_mode)
        try:
            self.robot: Robot = self._make_robot(robot, robot_radius)
            if not math.isclose(self.robot.radius, self.layout.robot_radius, rel_tol=1e-6):
                validate_layout(self.layout, self.robot.radius)
            self.world = World(self._client, self.layout, self.robot.radius)
            self.physics = self._enough_substeps(self.physics)
            pb.setGravity(0.0, 0.0, -9.81, physicsClientId=self._client)
            pb.setPhysicsEngineParameter(
                fixedTimeStep=self.physics.time_step,
                numSolverIterations=self.physics.solver_iterations,
                physicsClientId=self._client,
            )
            self.robot.configure(self.physics)
            self.robot.place(*self.layout.start, self.layout.start_heading)
            self._initial_state = pb.saveState(physicsClientId=self._client)
        except BaseException:
            self.close()
            raise

        width, height = self.layout.arena
        low, high = [0.0, 0.0], [width, height]
        if self.robot.has_heading:
            low.append(-math.pi)
            high.append(math.pi)
        self.observation_space = spaces.Box(np.array(low), np.array(high), dtype=np.float64)
        self.action_space = spaces.Discrete(len(DIRECTIONS))

        self._has_heading = self.robot.has_heading
        self._human = render_mode == "human"
        self._arena = self.layout.arena
        self._moves: dict[int | np.integer, tuple[float, float]] = {
            action: (float(mx), float(my))
            for action, (mx, my) in enumerate(DIRECTIONS * self.task.step_size)
        }
        self._goal_reward = self.task.goal_reward
        self._collision_reward = self.task.collision_reward
        self._step_reward = self.task.step_reward
        self._noise_std = self.task.noise_std
        self._noise: list[float] = []
        self._noise_index = 0
        self._x, self._y = self.layout.start
        self._heading = self.layout.start_heading
        self._start = self.layout.start
        self._goal = self.layout.goal
        self._goal_radius = self.layout.goal_radius
        self._body_in_sync = True
        self._limits: dict[tuple[tuple[float, float], tuple[float, float]], PhysicalLimit] = {}

    def _connect(self, render_mode: str | None) -> int:
        if render_mode == "human":
            if not _display_available():
                # pybullet's GUI would end the whole process without a display.
                logger.warning(
                    "render_mode='human' needs a display; none found (DISPLAY is "
                    "unset), so the simulation runs headless and shows nothing"
                )
                return pb.connect(pb.DIRECT)
            client = pb.connect(pb.GUI)
            if client < 0:
                raise RuntimeError(
                    "render_mode='human' could not open the pybullet GUI "
                    "(pybullet allows one GUI per process)"
                )
            return client
        return pb.connect(pb.DIRECT)

    def _enough_substeps(self, physics: PhysicsParams) -> PhysicsParams:
        """At least as many substeps as keep every substep's move within the robot's radius
        (a step's length plus four standard deviations of its noise)."""
        if self.robot.has_heading:  # wheeled robots creep at wheel speed, whatever the step
            return physics
        longest = self.task.step_size + 4.0 * math.sqrt(2.0) * self.task.noise_std
        needed = math.ceil(longest / self.robot.radius)
        if physics.substeps >= needed:
            return physics
        logger.info(
            "substeps raised from %d to %d so that no substep moves the robot farther "
            "than its radius",
            physics.substeps,
            needed,
        )
        return dataclasses.replace(physics, substeps=needed)

    def _make_robot(self, robot: str | Path, radius: float | None) -> Robot:
        is_path = isinstance(robot, Path) or (isinstance(robot, str) and robot.endswith(".urdf"))
        if not isinstance(robot, str | Path):
            raise TypeError(
                f"robot must be 'disc', 'husky' or a URDF path, got {type(robot).__name__}"
            )
        if radius is None and not is_path:
            radius = self.layout.robot_radius
        return make_robot(robot, self._client, radius)

    # -- Gymnasium API -----------------------------------------------------------------------

    def step(
        self, action: int | np.integer
    ) -> tuple[np.ndarray, SupportsFloat, bool, bool, dict[str, Any]]:
        if self._client < 0:
            raise RuntimeError("step() called on a closed BulletMazeEnv")
        # The hot path takes a Python or numpy int in range straight from the table of moves.
        move = self._moves.get(action) if type(action) in _FAST_ACTION_TYPES else None
        if move is None:
            move = self._moves[self._check_action(action)]
        i = self._noise_index
        noise = self._noise
        if i >= len(noise):
            self._draw_noise()
            i, noise = 0, self._noise
        self._noise_index = i + 2
        dx = move[0] + noise[i]
        dy = move[1] + noise[i + 1]
        if self._kinematic:
            x0, y0 = self._x, self._y
            collided = self.world.sweep_collides(x0, y0, x0 + dx, y0 + dy)
            if not collided:
                self._x, self._y = x0 + dx, y0 + dy
                if self._has_heading:
                    self._heading = math.atan2(dy, dx)
                self._body_in_sync = False
        else:
            collided = self._dynamic_step(dx, dy)

        x, y = self._x, self._y
        gx, gy = self._goal
        distance = math.hypot(x - gx, y - gy)
        success = distance <= self._goal_radius
        if collided:
            reward = self._collision_reward
        elif success:
            reward = self._goal_reward
        else:
            reward = self._step_reward
        if self._human:
            self._sync_body()
            self.world.park_probe()
        info = {"collision": collided, "distance_to_goal": distance, "is_success": success}
        if self._has_heading:
            return np.array((x, y, self._heading)), reward, success, False, info
        return np.array((x, y)), reward, success, False, info

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        super().reset(seed=seed)
        if self._client < 0:
            raise RuntimeError("reset() called on a closed BulletMazeEnv")
        if seed is not None:  # a new stream: forget noise drawn from the old one
            self._noise, self._noise_index = [], 0
        start, heading, goal = self._parse_options(options)
        self.world.restore(self._initial_state)
        self.robot.place(start[0], start[1], heading)
        self._x, self._y = start
        self._heading = wrap_angle(heading) if self.robot.has_heading else heading
        self._body_in_sync = True
        if (start, goal) != (self._start, self._goal):
            self.world.move_markers(start, goal)
        self._start, self._goal = start, goal
        distance = math.hypot(start[0] - goal[0], start[1] - goal[1])
        info = {"collision": False, "distance_to_goal": distance, "is_success": False}
        return self._observation(), info

    def render(self) -> np.ndarray | None:
        if self.render_mode is None:
            gym.logger.warn(
                "render() called without a render_mode; make the env with "
                "render_mode='rgb_array' to get images"
            )
            return None
        if self._client < 0:
            raise RuntimeError("render() called on a closed BulletMazeEnv")
        self._sync_body()
        self.world.park_probe()
        if self.render_mode == "rgb_array":
            return self._camera.render(self._client)
        return None

    def close(self) -> None:
        """Disconnect the pybullet client; calling it again does nothing."""
        client = getattr(self, "_client", -1)
        if client >= 0:
            self._client = -1
            try:
                pb.disconnect(physicsClientId=client)
            except pb.error:  # already gone with its server
                logger.debug("pybullet client %d was already disconnected", client)

    def __del__(self) -> None:
        # An env dropped without close() must not keep its pybullet client (about 150 MB); at
        # interpreter shutdown pybullet may already be gone.
        with contextlib.suppress(Exception):
            self.close()

    # -- The physical limit ----------------------------------------------------------------

    @property
    def physical_limit(self) -> PhysicalLimit:
        """Shortest path and least steps from this episode's start to its goal (cached)."""
        key = (self._start, self._goal)
        if key not in self._limits:
            layout = self.layout
            if key != (layout.start, layout.goal):
                layout = dataclasses.replace(layout, start=key[0], goal=key[1])
            self._limits[key] = shortest_path(layout, self.robot.radius, self.task.step_size)
        return self._limits[key]

    @property
    def optimal_steps(self) -> int:
        """Least number of steps of ``step_size`` from start to goal: the L1 geodesic divided
        by the step, rounded up (see ``bullet_maze.shortest_path``)."""
        return self.physical_limit.steps

    @property
    def pose(self) -> tuple[float, float, float]:
        """The robot's (x, y, heading) in maze units and radians."""
        return self._x, self._y, self._heading

    @property
    def goal(self) -> tuple[float, float]:
        """This episode's goal centre in maze units."""
        return self._goal

    @property
    def client_id(self) -> int:
        """The env's pybullet client (-1 once closed)."""
        return self._client

    # -- Internals -----------------------------------------------------------------------

    def _dynamic_step(self, dx: float, dy: float) -> bool:
        robot, world = self.robot, self.world
        x0, y0 = self._x, self._y
        length = math.hypot(dx, dy)
        reach = length + robot.reach_margin
        if world.certified_clear(x0, y0, reach):
            near = False
        elif self._has_heading:
            near = not world.clear_within(x0, y0, reach)
        else:
            # A holonomic body moves along its command and only friction shortens the move, so
            # contacts need watching only if the commanded segment (a little longer) is not
            # proved free. Physics decides the rest: an exact sweep would cost as much as
            # watching the contacts, and most moves it would sweep end in a wall.
            stretch = reach / length if length > 0.0 else 0.0
            near = not world.certified_free(x0, y0, x0 + dx * stretch, y0 + dy * stretch)
        touched = False
        if not near:
            robot.drive(dx, dy, None)
        elif self.physics.revert_on_collision:
            # The step is undone if it touches, so its remaining substeps need not run.
            saved = robot.snapshot()
            if robot.drive(dx, dy, world, stop_on_touch=True):
                robot.restore(saved)
                return True
        else:
            touched = robot.drive(dx, dy, world)
        if self._has_heading:
            x, y, self._heading = robot.pose()
        else:
            x, y = robot.position()
        # Physics may push a body a hair past the arena's edge; the observation stays in its box.
        width, height = self._arena
        self._x = x if 0.0 <= x <= width else 0.0 if x < 0.0 else width
        self._y = y if 0.0 <= y <= height else 0.0 if y < 0.0 else height
        return touched

    def _draw_noise(self) -> None:
        """Section V.A's noise for the next ``NOISE_BLOCK`` steps, from the seeded ``np_random``
        in one draw (x then y for each step, so the stream is the same as drawing per step)."""
        block = self.np_random.standard_normal(2 * NOISE_BLOCK) * self._noise_std
        self._noise = block.tolist()
        self._noise_index = 0

    def _observation(self) -> np.ndarray:
        if self.robot.has_heading:
            return np.array((self._x, self._y, self._heading))
        return np.array((self._x, self._y))

    def _sync_body(self) -> None:
        if not self._body_in_sync:
            self.robot.place(self._x, self._y, self._heading)
            self._body_in_sync = True

    def _check_action(self, action: Any) -> int:
        if isinstance(action, np.ndarray) and action.shape == ():
            action = action.item()
        if isinstance(action, bool) or not isinstance(action, int | np.integer):
            raise TypeError(
                f"action must be an integer in [0, {len(DIRECTIONS)}) "
                f"(bullet_maze.Action), got {action!r}"
            )
        if not 0 <= action < len(DIRECTIONS):
            raise ValueError(
                f"action {action} is not in [0, {len(DIRECTIONS)}) (UP, DOWN, LEFT, RIGHT)"
            )
        return int(action)

    def _parse_options(
        self, options: dict[str, Any] | None
    ) -> tuple[tuple[float, float], float, tuple[float, float]]:
        layout = self.layout
        start, heading, goal = layout.start, layout.start_heading, layout.goal
        if not options:
            return start, heading, goal
        if not isinstance(options, dict):
            raise TypeError(f"options must be a dict, got {type(options).__name__}")
        unknown = set(options) - {"start", "goal"}
        if unknown:
            raise ValueError(
                f"unknown reset option(s) {sorted(unknown)}: allowed are 'start' and 'goal'"
            )
        if options.get("start") is not None:
            values = _finite_numbers(options["start"], "options['start']", (2, 3))
            start = (values[0], values[1])
            if len(values) == 3:
                heading = values[2]
            self._check_inside(start, "options['start']")
            gap = self.world.distance(start[0], start[1], 0.0)
            if gap < CONTACT_TOLERANCE:
                raise ValueError(
                    f"options['start'] = {start}: a robot of radius "
                    f"{self.robot.radius:g} there overlaps a wall or an obstacle"
                )
        if options.get("goal") is not None:
            values = _finite_numbers(options["goal"], "options['goal']", (2,))
            goal = (values[0], values[1])
            self._check_inside(goal, "options['goal']")
            if float(clearance(layout, np.array(goal))) < 0.0:
                raise ValueError(f"options['goal'] = {goal} lies inside a wall or an obstacle")
        if math.dist(start, goal) <= layout.goal_radius:
            raise ValueError(
                f"options: the start {start} lies inside the goal circle "
                f"(centre {goal}, radius {layout.goal_radius:g})"
            )
        if (start, goal) != (layout.start, layout.goal):
            self._check_reachable(start, goal, options)
        return start, heading, goal

    def _check_reachable(
        self, start: tuple[float, float], goal: tuple[float, float], options: dict[str, Any]
    ) -> None:
        """A ValueError naming the option unless the robot can get from the start into the goal
        circle (see ``bullet_maze.planning.goal_reachable``: the layout's free regions for this
        radius are computed once, about 30 ms, then each check is a lookup)."""
        radius = self.robot.radius
        if goal_reachable(self.layout, radius, start, goal):
            return
        robot = f"a robot of radius {radius:g}"
        if options.get("goal") is None:
            raise ValueError(
                f"options['start'] = {start}: the goal circle around {goal} cannot "
                f"be reached from there by {robot}"
            )
        where = (
            f"options['start'] = {start}"
            if options.get("start") is not None
            else f"the start {start}"
        )
        raise ValueError(
            f"options['goal'] = {goal}: its circle (radius "
            f"{self.layout.goal_radius:g}) cannot be reached from {where} by "
            f"{robot}"
        )

    def _check_inside(self, point: tuple[float, float], name: str) -> None:
        if not self.layout.contains(*point):
            raise ValueError(
                f"{name} = {point} lies outside the arena [0, "
                f"{self.layout.arena[0]:g}] x [0, {self.layout.arena[1]:g}]"
            )


def _display_available() -> bool:
    """Whether a GUI can open: always assumed off Linux, else an X11 or Wayland display."""
    if not sys.platform.startswith("linux"):
        return True
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def _finite_numbers(value: Any, name: str, lengths: Sequence[int]) -> list[float]:
    try:
        values = [float(v) for v in value]
    except (TypeError, ValueError) as err:
        raise ValueError(
            f"{name} must be a sequence of {' or '.join(map(str, lengths))} numbers, got {value!r}"
        ) from err
    if len(values) not in lengths:
        raise ValueError(
            f"{name} must have {' or '.join(map(str, lengths))} numbers, got {value!r}"
        )
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return values
