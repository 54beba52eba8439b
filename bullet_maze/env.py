"""``BulletMazeEnv``: the maze of section V.A as a Gymnasium environment in headless pybullet."""

from __future__ import annotations

import contextlib
import dataclasses
import itertools
import logging
import math
import numbers
import os
import sys
from collections import deque
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any, NamedTuple, SupportsFloat

import gymnasium as gym
import numpy as np
import pybullet as pb
from gymnasium import spaces

from bullet_maze.action_sets import ActionParams, CompassActions, make_action_set
from bullet_maze.geometry import clearance
from bullet_maze.goals import collision_flags, goal_reward, goal_space
from bullet_maze.layout import DEFAULT_LAYOUT, MazeLayout, load_layout
from bullet_maze.params import MODES, PhysicsParams, TaskParams
from bullet_maze.perturbations import NAMES as PERTURBATION_NAMES
from bullet_maze.perturbations import (
    PHYSICAL,
    Range,
    Setting,
    applies,
    child_generator,
    draw,
    largest,
    parse_setting,
    parse_settings,
)
from bullet_maze.planning import PhysicalLimit, goal_test, shortest_path
from bullet_maze.rendering import TopDownCamera
from bullet_maze.robots import (
    Command,
    Move,
    Robot,
    RobotSpec,
    make_robot,
    resolve_robot,
    wrap_angle,
)
from bullet_maze.robots.drives import facing
from bullet_maze.sensors import Lidar, LidarParams
from bullet_maze.validation import validate_layout
from bullet_maze.world import CELL, CELL_REACH, CONTACT_TOLERANCE, World

logger = logging.getLogger(__name__)

NOISE_BLOCK = 1024
"""Steps of noise drawn from ``np_random`` at once (one draw per step costs more than a step)."""

OBSERVATIONS = ("pose", "lidar", "goal", "goal+lidar")
"""The values of the env's ``observation`` argument."""

PARAMS = (TaskParams, PhysicsParams, ActionParams, LidarParams)
"""The dataclasses whose fields are the env's keyword parameters; each default lives there."""

_FAST_ACTION_TYPES = frozenset((int, np.int64))
"""Action types ``step`` looks up without conversion (``bool`` is not one: it is refused)."""


class FastCore(NamedTuple):
    """What ``BulletMazeEnv.fast_core`` hands the fast learning loop (read-only views)."""

    world: World
    moves: tuple[tuple[float, float], ...]
    """The move of each action, before noise."""
    goal: tuple[float, float]
    goal_radius: float
    goal_reward: float
    collision_reward: float
    step_reward: float
    position: tuple[float, float]
    noise: list[float]
    """The current noise block (x then y per step); ``step`` draws the next when it is spent."""
    noise_index: int
    cells: dict[tuple[int, int], Any]
    """``World._cells``: each seen cell's bounds (``_CellBounds`` or None); grows as cells are
    seen."""
    safe_ball: tuple[float, float, float]
    arena: tuple[float, float]
    cell: float
    cell_reach: float
    tolerance: float


class BulletMazeEnv(gym.Env[Any, Any]):
    """
    ## Description

    The robot maze of section V.A of Hwang, Li and Jiang, "Adaptive Exploration Strategies for
    Reinforcement Learning", simulated in headless pybullet: a walled 300 x 300 arena with grey
    cylindrical obstacles, a green start square and a red goal circle. The robot moves by steps
    with Gaussian noise; it must reach the goal.

    Layouts are TOML files (`assets/mazes/`, see `bullet_maze.load_layout`); robots are robot
    files (`assets/robots/`: `disc`, `husky`, `racecar`, `r2d2`, or a path to a `.toml` robot
    file; see `docs/robots.md`) or bare URDF paths, whose wheels are detected where the file
    makes that unambiguous.

    ## Action Space

    Chosen with `actions=` (`bullet_maze.actions`):

    * `"compass"` (default, the paper's): `Discrete(4)`, `bullet_maze.Action`:

      | Num | Action | Move (maze units)          |
      |-----|--------|----------------------------|
      | 0   | UP     | (0, +step_size) + noise    |
      | 1   | DOWN   | (0, -step_size) + noise    |
      | 2   | LEFT   | (-step_size, 0) + noise    |
      | 3   | RIGHT  | (+step_size, 0) + noise    |

      A holonomic robot is pushed along the move; a differential robot turns in place to face
      the target (or away from it, whichever needs the smaller turn) and drives there. A car
      (ackermann drive) cannot turn in place: it keeps its heading and reaches the target by a
      short manoeuvre of full-lock arcs (a lane change, or a forward-and-back zig-zag for a
      step across its heading; `bullet_maze.robots.car_compass`), swept arc by arc in
      kinematic mode (it ends exactly at the target) and driven through its steering hinges
      and rear wheels in dynamic mode (it ends within about a unit of it; see
      `docs/robots.md`).
    * `"native"`: `Discrete(4)`, `bullet_maze.NativeAction` FORWARD, BACKWARD, TURN_LEFT,
      TURN_RIGHT at the drive's full speed or turn rate for `control_period` seconds (a car
      turns by driving ahead at full lock); a holonomic robot's native actions are the compass
      ones.
    * `"continuous"`: `Box(-1, 1, (2,), float32)`: (vx, vy) times `step_size` per step for a
      holonomic robot; (speed, turn rate) for a differential one and (speed, steering) for a
      car, as fractions of the drive's top values, held for `control_period` seconds.

    Noise, the same in every set: two Gaussians per step, mean 0 and variance `noise_variance`
    (0.3) in maze units squared, drawn from the env's seeded `np_random`: on x and y of a
    displacement, or on the distance a wheeled robot's base travels and the arc the rim of its
    footprint travels.

    ## Observation Space

    Chosen with `observation=`. `"pose"` (default): `Box(float64)` of the robot's pose in maze
    units (x to the right, y up, origin at the arena's lower-left corner):

    | Num | Observation | Min  | Max          |
    |-----|-------------|------|--------------|
    | 0   | x           | 0    | arena width  |
    | 1   | y           | 0    | arena height |
    | 2   | heading     | -pi  | pi           |

    The heading (radians from +x, the robot's forward direction) is there for every robot with
    a drive that has one (differential, ackermann; bare URDFs with detected wheels included);
    holonomic robots (the disc) observe `(x, y)`. `"lidar"` appends `lidar_rays` ranges in
    `[0, lidar_range]` (`bullet_maze.sensors`), evenly spaced counter-clockwise from the
    heading (from +x without one). `"goal"` and `"goal+lidar"` give the goal-conditioned `Dict`
    of Gymnasium-Robotics' mazes: `observation` (the `Box` above), `achieved_goal` (x, y) and
    `desired_goal` (the goal centre), with a vectorised `compute_reward(achieved_goal,
    desired_goal, info)` for Stable-Baselines3's `HerReplayBuffer`.

    ## Rewards

    Section V.A: `goal_reward` (+5) when the step ends with the robot's centre inside the goal
    circle, `collision_reward` (-1) when the step touches a wall or an obstacle, `step_reward`
    (-0.01) otherwise.

    ## Starting State

    The layout's start pose (the centre of the start square), or `options["start"]`.

    ## Episode End

    1. Termination: the robot's centre is within the goal radius of the goal centre.
    2. Truncation: 5,000 steps (section V.A), set by the registration's `max_episode_steps`
       (`gymnasium.make(..., max_episode_steps=N)` changes it; the env does not take it).

    A collision never ends the episode.

    ## Modes

    * `"kinematic"` (default), the paper's exact step: the robot follows its drive's exact
      kinematic model (a straight move; the unicycle; the bicycle model), swept with its
      footprint disc against the walls and obstacles with pybullet distance queries; if it
      touches anything the robot stays put. A robot resting against a solid may still leave it:
      only a move towards the solid is a collision (`contact_release`, default True; False is
      the sweep before 2026-12-07, which could hold a robot against a wall for good).
    * `"dynamic"`: physics, through the robot's own actuators (the base velocity of a
      holonomic body; wheel velocities; rear-wheel speed and steering angles), for `substeps`
      physics steps (holonomic), the turn-and-drive of a compass step, or `control_period`
      seconds. A step that touches a solid is undone if `revert_on_collision` (default, as the
      paper), otherwise physics resolves the contact. The realised move is close to, not
      exactly, the commanded one.

    ## Arguments

    ```python
    import gymnasium as gym
    import bullet_maze  # registers the ids

    env = gym.make("BulletMaze-v0", maze="paper", robot="disc", mode="kinematic")
    env = gym.make("BulletMaze-v0", robot="racecar", actions="native", observation="lidar")
    env = gym.make("BulletMaze-v0", step_size=2.5, substeps=8)  # any parameter below
    ```

    * `maze`: a layout name (`paper`, `paper_narrow`, `open`, `corridors`), a TOML path or a
      `MazeLayout`.
    * `robot`: a robot name (`bullet_maze.available_robots()`), a `.toml` robot file, a `.urdf`
      path or a `bullet_maze.RobotSpec`; `robot_radius` rescales it to that footprint radius
      (default: the robot file's, usually the layout's robot radius; a bare URDF keeps its own
      size).
    * `mode`: `"kinematic"` or `"dynamic"`; `render_mode`: `None`, `"rgb_array"` (a top-down
      TinyRenderer image, no display needed) or `"human"` (the pybullet GUI).
    * `actions`: `"compass"`, `"native"` or `"continuous"`; `observation`: `"pose"`, `"lidar"`,
      `"goal"` or `"goal+lidar"`.
    * `render_width`, `render_height`: image size in pixels (at most 4,096).
    * Parameters, each a keyword whose default lives in one dataclass (unknown keywords are a
      `TypeError`; a bool is not a number):
      * `bullet_maze.TaskParams` (section V.A): `step_size`, `noise_variance`, `goal_reward`,
        `collision_reward`, `step_reward`;
      * `bullet_maze.PhysicsParams` (dynamic mode, and `contact_release` for the kinematic
        sweep): `time_step`, `substeps`, `solver_iterations`, `revert_on_collision`,
        `max_turn_substeps`, `max_drive_substeps`, `contact_release` (a robot file's
        `[physics]` may set its own `time_step` and `solver_iterations`, per action set: the
        husky's compass steps run at 40 Hz);
      * `bullet_maze.ActionParams`: `control_period`;
      * `bullet_maze.LidarParams`: `lidar_rays`, `lidar_range` (a robot file may set its own
        defaults).

    `reset(seed=..., options={"start": (x, y) or (x, y, heading), "goal": (x, y)})` moves the
    start and the goal for that episode (validated). `info` has `collision`,
    `distance_to_goal` and `is_success`, and in dynamic mode `tipped`: the robot's up axis is
    more than `tip_angle` (60 degrees) from the vertical, so it lies on its side and will not
    move again; with `end_on_tip=True` that step truncates the episode (default: it goes on).
    `env.unwrapped.optimal_steps` is the least number of compass steps that can reach the goal
    (see `bullet_maze.shortest_path`).

    ## Perturbations

    Keywords, each `None` (not set) by default; with none set the env is exactly the one
    above, bit for bit, with the same draws from `np_random` (`bullet_maze.perturbations`,
    `docs/perturbations.md`).

    | keyword | unit | bounds | what it changes (where) |
    |---------|------|--------|-------------------------|
    | `noise_variance` | units^2 | [0, 100] | the noise above, per episode (a range) |
    | `bias_along` | units/step | [-10, 10] | over-travel along the commanded motion |
    | `bias_left` | units/step | [-10, 10] | veer to its left (a Twist: turn by it / radius) |
    | `floor_friction_scale` | factor | [0, 10] | the floor's friction (dynamic) |
    | `wheel_friction_scale` | factor | [0, 10] | the wheels' friction (dynamic) |
    | `mass_scale` | factor | [0.01, 100] | every link's mass and inertia (dynamic) |
    | `torque_scale` | factor | [0, 100] | the motors' force limits (dynamic, wheeled) |
    | `latency_steps` | env steps | [0, 100] | actions execute k steps late (integer) |
    | `observation_noise` | units (std) | [0, 100] | observed x, y, clipped to the arena |
    | `heading_noise` | rad (std) | [0, pi] | observed heading, wrapped (a heading) |
    | `lidar_noise` | units (std) | [0, 1000] | readings of rays that hit, clipped (a lidar) |

    A fixed value is a number; a **range** is `[low, high]`, `(low, high)` or `{"low": low,
    "high": high}` (TOML arrays and inline tables arrive so), and each reset draws the episode's
    value uniformly (integers inclusive for `latency_steps`), one draw per randomised keyword in
    the order of the table, only for ranges. These draws and the observation and lidar noise
    come from a generator derived from `np_random`'s seed sequence without drawing from it
    (`perturbations.child_generator`), so the same seed gives the same draws and the same action
    noise as without perturbations (a randomised `noise_variance` scales the same standard
    normals). A perturbation where it means nothing (a mass in kinematic mode, motors of a
    holonomic robot, the mass of a holonomic robot whose touching steps are undone, a heading
    noise without a heading, a lidar noise without a lidar) is a `ValueError` saying why, never
    silently ignored. The bias is added to the step's two noise draws in the frame of the
    action's noise-free command (a `Move` along its direction and to its left; a `Twist` on its
    distance and on its rim's arc). During the first `latency_steps` steps of an episode no
    command reaches the robot: it stays at rest (no physics, no noise drawn) and the step is
    rewarded as any other. The observation noises change what the agent sees (the observation,
    and `achieved_goal` with the same noisy x, y); the true pose (`env.unwrapped.pose`), the
    reward, termination and `info` are computed from the truth. `info["perturbation"]` (at reset
    and every step) and `env.unwrapped.perturbation` give the episode's values, fixed and drawn;
    a `noise_variance` range leaves its upper end in `env.unwrapped.task` (it sizes the dynamic
    substeps).

    ## Version History

    * v0: initial version; robot files, drives, action sets and observations added without
      changing the disc's compass rollouts; perturbations and domain randomisation added
      without changing any rollout that sets none.
    """

    parameter_classes = PARAMS
    """The dataclasses whose fields are the keyword parameters that ``**params`` takes."""
    parameter_names = PERTURBATION_NAMES
    """The other keyword parameters ``**params`` takes: the perturbations, each a value or a
    range, checked by :meth:`check_parameter`."""
    check_parameter = staticmethod(parse_setting)
    """``check_parameter(name, value)``: a perturbation's value checked (``TypeError`` or
    ``ValueError`` naming it), so that a config can be checked without building the env."""

    metadata = {"render_modes": ["human", "rgb_array"], "render_fps": 30}  # noqa: RUF012
    _rng_parent: np.random.Generator | None
    """The ``np_random`` that the perturbations' generator was derived from."""
    _sensor_noise: list[float]
    """Standard normals for the observation noise, three per observation."""

    def __init__(
        self,
        maze: str | Path | MazeLayout = DEFAULT_LAYOUT,
        robot: str | Path | RobotSpec = "disc",
        mode: str = "kinematic",
        render_mode: str | None = None,
        *,
        actions: str = "compass",
        observation: str = "pose",
        robot_radius: float | None = None,
        render_width: int = 256,
        render_height: int = 256,
        **params: Any,
    ) -> None:
        if mode not in MODES:
            raise ValueError(f"mode must be one of {list(MODES)}, got {mode!r}")
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(
                f"render_mode must be None or one of "
                f"{self.metadata['render_modes']}, got {render_mode!r}"
            )
        if observation not in OBSERVATIONS:
            raise ValueError(
                f"observation must be one of {list(OBSERVATIONS)}, got {observation!r}"
            )
        if robot_radius is not None:
            if isinstance(robot_radius, bool) or not isinstance(robot_radius, int | float):
                raise TypeError(f"robot_radius must be a number, got {robot_radius!r}")
            if not 0 < robot_radius < math.inf:
                raise ValueError(f"robot_radius must be a positive number, got {robot_radius!r}")
        spec = resolve_robot(robot)
        task, physics, action_params, lidar_params, settings = _split_params(params, spec, actions)
        self.task, self.physics = task, physics
        self.layout = load_layout(maze)
        self._goal_test: Callable[[tuple[float, float], tuple[float, float]], bool] | None = None
        self.mode = mode
        self._kinematic = mode == "kinematic"
        self.render_mode = render_mode
        self._camera = TopDownCamera(self.layout.arena, render_width, render_height)
        self._client = -1
        self._client = self._connect(render_mode)
        try:
            self.robot: Robot = make_robot(
                spec, self._client, robot_radius, self.layout.robot_radius, not self._kinematic
            )
            self.actions = make_action_set(
                actions, self.robot, task.step_size, action_params.control_period
            )
            if not math.isclose(self.robot.radius, self.layout.robot_radius, rel_tol=1e-6):
                validate_layout(self.layout, self.robot.radius)
            self.world = World(
                self._client, self.layout, self.robot.radius, self.physics.contact_release
            )
            self.lidar = (
                Lidar(self.world.pieces(), lidar_params, self.robot.radius)
                if observation.endswith("lidar")
                else None
            )
            self._settings = settings
            self._check_perturbations(settings)
            self.physics = self._enough_substeps(self.physics)
            pb.setGravity(0.0, 0.0, -9.81, physicsClientId=self._client)
            pb.setPhysicsEngineParameter(
                fixedTimeStep=self.physics.time_step,
                numSolverIterations=self.physics.solver_iterations,
                physicsClientId=self._client,
            )
            self.robot.configure(self.physics)
            self._ground_friction = pb.getDynamicsInfo(
                self.world.ground_id, -1, physicsClientId=self._client
            )[1]
            self._perturbation: dict[str, float | int] = {}
            self._set_perturbation(
                {name: value for name, value in settings.items() if not isinstance(value, Range)}
            )
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
        if self.lidar is not None:
            low += [0.0] * self.lidar.rays
            high += [self.lidar.range] * self.lidar.rays
        pose_space = spaces.Box(np.array(low), np.array(high), dtype=np.float64)
        self.observation_mode = observation
        self._goal_conditioned = observation.startswith("goal")
        self.observation_space: spaces.Space[Any] = (
            goal_space(pose_space, self.layout.arena) if self._goal_conditioned else pose_space
        )
        self.action_space: spaces.Space[Any] = self.actions.space
        if self._goal_conditioned:
            self.compute_reward = self._compute_reward
            self.compute_terminated = self._compute_terminated
            self.compute_truncated = self._compute_truncated

        self._has_heading = self.robot.has_heading
        self._human = render_mode == "human"
        self._arena = self.layout.arena
        # The compass set's moves in a dict that takes int and np.int64 alike (the hot path);
        # any other action set goes through its ``check`` and ``command``.
        # The compass hot path sweeps a straight segment: a car's manoeuvre goes through its
        # drive's path instead (``_kinematic_step``), like the other action sets.
        self._compass = (
            isinstance(self.actions, CompassActions) and self.robot.drive.kind != "ackermann"
        )
        self._holonomic = self.robot.drive.kind == "holonomic"
        self._moves: dict[int | np.integer, tuple[float, float]] = (
            dict(enumerate(self.actions.moves)) if isinstance(self.actions, CompassActions) else {}
        )
        self._perturbed = bool(settings)
        self._plain = (
            self._compass
            and self.lidar is None
            and not self._goal_conditioned
            and not self._perturbed
        )
        self._goal_reward = self.task.goal_reward
        self._collision_reward = self.task.collision_reward
        self._step_reward = self.task.step_reward
        # A randomised noise variance keeps standard normals in the block and scales them by
        # the episode's standard deviation at each step (the same stream in every episode).
        self._noise_std = 1.0 if "noise_variance" in settings else self.task.noise_std
        self._noise: list[float] = []
        self._noise_index = 0
        self._x, self._y = self.layout.start
        self._heading = self.layout.start_heading
        self._start = self.layout.start
        self._goal = self.layout.goal
        self._goal_radius = self.layout.goal_radius
        self._body_in_sync = True
        self._tipped = False
        self._tipped_before = False  # warned once per env
        self._tip_cosine = math.cos(self.physics.tip_angle)
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
        if self.robot.drive.kind != "holonomic":  # wheeled robots creep at wheel speed
            return physics
        longest = self.task.step_size + 4.0 * math.sqrt(2.0) * self.task.noise_std
        if "bias_along" in self._settings or "bias_left" in self._settings:
            longest += math.hypot(
                largest(self._settings.get("bias_along")), largest(self._settings.get("bias_left"))
            )
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

    # -- Gymnasium API -----------------------------------------------------------------------

    def step(self, action: Any) -> tuple[Any, SupportsFloat, bool, bool, dict[str, Any]]:
        if self._client < 0:
            raise RuntimeError("step() called on a closed BulletMazeEnv")
        i = self._noise_index
        noise = self._noise
        if i >= len(noise):
            self._draw_noise()
            i, noise = 0, self._noise
        if self._perturbed:
            collided = self._perturbed_move(action)
        elif self._compass:
            # The hot path takes a Python or numpy int in range straight from the table.
            move = self._moves.get(action) if type(action) in _FAST_ACTION_TYPES else None
            if move is None:
                move = self._moves[self.actions.check(action)]
            self._noise_index = i + 2
            dx = move[0] + noise[i]
            dy = move[1] + noise[i + 1]
            if not self._kinematic:
                collided = self._dynamic_step(Move(dx, dy))
            else:
                x0, y0 = self._x, self._y
                collided = self.world.sweep_collides(x0, y0, x0 + dx, y0 + dy)
                if not collided:
                    self._x, self._y = x0 + dx, y0 + dy
                    if self._has_heading:
                        self._heading = facing(self._heading, dx, dy)
                    self._body_in_sync = False
        else:
            checked = self.actions.check(action)
            self._noise_index = i + 2
            command = self.actions.command(checked, noise[i], noise[i + 1])
            if self._kinematic:
                collided = self._kinematic_step(command)
            else:
                collided = self._dynamic_step(command)

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
        info: dict[str, Any] = {
            "collision": collided,
            "distance_to_goal": distance,
            "is_success": success,
        }
        cut = False
        if not self._kinematic:
            info["tipped"] = tipped = self._tipped
            cut = tipped and self.physics.end_on_tip
        if self._perturbed:
            info["perturbation"] = dict(self._perturbation)
        if not self._plain:
            return self._observation(), reward, success, cut, info
        if self._has_heading:
            return np.array((x, y, self._heading)), reward, success, cut, info
        return np.array((x, y)), reward, success, cut, info

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[Any, dict[str, Any]]:
        super().reset(seed=seed)
        if self._client < 0:
            raise RuntimeError("reset() called on a closed BulletMazeEnv")
        if seed is not None:  # a new stream: forget noise drawn from the old one
            self._noise, self._noise_index = [], 0
        start, heading, goal = self._parse_options(options)
        self.world.restore(self._initial_state)
        if self._perturbed and self._rng_parent is not self.np_random:
            self._rng_parent = self.np_random
            self._rng = child_generator(self.np_random)
            self._sensor_noise, self._sensor_index = [], 0
        if self._randomised:
            self._set_perturbation(draw(self._settings, self._rng))
        if self._queue is not None:
            self._queue.clear()
        self.robot.place(start[0], start[1], heading)
        self._x, self._y = start
        self._heading = wrap_angle(heading) if self.robot.has_heading else heading
        self._body_in_sync = True
        self._tipped = False
        if (start, goal) != (self._start, self._goal):
            self.world.move_markers(start, goal)
        self._start, self._goal = start, goal
        distance = math.hypot(start[0] - goal[0], start[1] - goal[1])
        info: dict[str, Any] = {
            "collision": False,
            "distance_to_goal": distance,
            "is_success": False,
        }
        if not self._kinematic:
            info["tipped"] = False
        if self._perturbed:
            info["perturbation"] = dict(self._perturbation)
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
        """Disconnect the pybullet clients (the world's, and its query index's and the lidar
        scene's if it has them); calling it again does nothing."""
        client = getattr(self, "_client", -1)
        if client >= 0:
            self._client = -1
            world = getattr(self, "world", None)
            if world is not None:
                world.close()
            lidar = getattr(self, "lidar", None)
            if lidar is not None:
                lidar.close()
            try:
                pb.disconnect(physicsClientId=client)
            except pb.error:  # already gone with its server
                logger.debug("pybullet client %d was already disconnected", client)

    def __del__(self) -> None:
        # An env dropped without close() must not keep its pybullet client (about 150 MB); at
        # interpreter shutdown pybullet may already be gone.
        with contextlib.suppress(Exception):
            self.close()

    # -- Goal-conditioned API (observation="goal"): bound as compute_reward, compute_terminated
    # and compute_truncated only then, since tools such as Stable-Baselines3 take an env with a
    # compute_reward for a goal-conditioned one.

    def _compute_reward(self, achieved_goal: Any, desired_goal: Any, info: Any) -> Any:
        """The reward of reaching ``achieved_goal`` when ``desired_goal`` was wanted, for one
        transition or a batch (leading axes); ``info`` is the step's info dict or a batch of
        them (their ``collision`` entries). See ``bullet_maze.goals``."""
        reward = goal_reward(
            achieved_goal,
            desired_goal,
            info,
            self._goal_radius,
            (self._goal_reward, self._collision_reward, self._step_reward),
        )
        return float(reward) if reward.ndim == 0 else reward

    def _compute_terminated(self, achieved_goal: Any, desired_goal: Any, info: Any) -> Any:
        """Whether the achieved goal lies in the desired goal's circle (one or a batch)."""
        distance = np.linalg.norm(
            np.asarray(achieved_goal, dtype=np.float64)
            - np.asarray(desired_goal, dtype=np.float64),
            axis=-1,
        )
        done = distance <= self._goal_radius
        return bool(done) if done.ndim == 0 else done

    def _compute_truncated(self, achieved_goal: Any, desired_goal: Any, info: Any) -> Any:
        """Whether the step's robot had tipped over (``info["tipped"]`` with ``end_on_tip``;
        the time limit is the registration's ``max_episode_steps``), whatever the goals."""
        shape = np.shape(np.asarray(achieved_goal))[:-1]
        if not self.physics.end_on_tip:
            return False if shape == () else np.zeros(shape, dtype=bool)
        cut = collision_flags(info, shape, key="tipped")
        return bool(cut) if shape == () else cut

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
        """Least number of compass steps of ``step_size`` from start to goal: the L1 geodesic
        divided by the step, rounded up (see ``bullet_maze.shortest_path``)."""
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

    def fast_core(self, commit: tuple[float, float, int, bool] | None = None) -> FastCore | None:
        """The fast learning loop's contract (``agent/fast_loop.py``): what it reads to take
        kinematic steps itself, or None when this env is not eligible (dynamic mode, a robot
        with a heading, actions other than the compass, an observation other than the pose, a
        render mode).

        With ``commit=(x, y, noise_index, moved)`` the position and the noise position are
        first set to what ``step`` would have left after the same steps (``moved``: one of them
        moved the robot). The loop repeats ``step``'s kinematic branch with the noise of
        ``noise`` from ``noise_index``: it takes the moves that ``World.certified_free`` proves
        free from the cached cell bounds and safe ball given here, asks
        ``world.sweep_collides`` (``step``'s own call) about the others, then reads the safe ball
        (``World._safe``) and the live cell dict again, and leaves a step that needs a new noise
        block to ``step`` itself.
        """
        if (
            not self._kinematic
            or self._has_heading
            or not self._plain
            or self.render_mode is not None
        ):
            return None
        if commit is not None:
            self._x, self._y, self._noise_index, moved = commit
            if moved:
                self._body_in_sync = False
        return FastCore(
            world=self.world,
            moves=tuple(self._moves.values()),  # keyed 0, 1, ... in order
            goal=self._goal,
            goal_radius=self._goal_radius,
            goal_reward=self._goal_reward,
            collision_reward=self._collision_reward,
            step_reward=self._step_reward,
            position=(self._x, self._y),
            noise=self._noise,
            noise_index=self._noise_index,
            cells=self.world._cells,
            safe_ball=self.world._safe,
            arena=self._arena,
            cell=CELL,
            cell_reach=CELL_REACH,
            tolerance=CONTACT_TOLERANCE,
        )

    # -- Internals -----------------------------------------------------------------------

    def _kinematic_step(self, command: Command) -> bool:
        """The drive's exact model: sweep its path; stay put if it touches a solid."""
        points, end = self.robot.kinematic_path((self._x, self._y, self._heading), command)
        sweep = self.world.sweep_collides
        for (x0, y0), (x1, y1) in itertools.pairwise(points):
            if sweep(x0, y0, x1, y1):
                return True
        self._x, self._y = end[0], end[1]
        if self._has_heading:
            self._heading = end[2]
        self._body_in_sync = False
        return False

    def _dynamic_step(self, command: Command) -> bool:
        robot, world = self.robot, self.world
        x0, y0 = self._x, self._y
        reach = robot.drive.reach(command)
        if world.certified_clear(x0, y0, reach):
            near = False
        elif not self._holonomic or not isinstance(command, Move):
            near = not world.clear_within(x0, y0, reach)
        else:
            # A holonomic body moves along its command and only friction shortens the move, so
            # contacts need watching only if the commanded segment (a little longer) is not
            # proved free. Physics decides the rest: an exact sweep would cost as much as
            # watching the contacts, and most moves it would sweep end in a wall.
            dx, dy = command
            length = math.hypot(dx, dy)
            stretch = reach / length if length > 0.0 else 0.0
            near = not world.certified_free(x0, y0, x0 + dx * stretch, y0 + dy * stretch)
        touched = False
        if not near:
            robot.execute(command, None)
        elif self.physics.revert_on_collision:
            # The step is undone if it touches, so its remaining substeps need not run.
            saved = robot.snapshot()
            if robot.execute(command, world, stop_on_touch=True):
                robot.restore(saved)
                return True
        else:
            touched = robot.execute(command, world)
        x, y, heading, up = robot.placement(self._has_heading)
        if self._has_heading:
            self._heading = heading
        tipped = up < self._tip_cosine  # tilted past tip_angle
        if tipped and not self._tipped_before:
            self._tipped_before = True
            self._warn_tipped(up)
        self._tipped = tipped
        # Physics may push a body a hair past the arena's edge; the observation stays in its box.
        width, height = self._arena
        self._x = x if 0.0 <= x <= width else 0.0 if x < 0.0 else width
        self._y = y if 0.0 <= y <= height else 0.0 if y < 0.0 else height
        return touched

    def _warn_tipped(self, up: float) -> None:
        """Say once per env that the robot fell, and what a robot file can change."""
        drive = self.robot.drive
        hint = (
            f"; its wheels turn at up to {drive.limits.wheel_speed:g} rad/s, which a robot file "
            "can lower ([limits] max_wheel_speed)"
            if drive.kind != "holonomic"
            else ""
        )
        logger.warning(
            "robot %s tipped over in dynamic mode (tilted %.0f degrees): it lies on its side "
            "until the episode ends, info['tipped'] reports it%s (docs/simulation.md)",
            self.robot.name,
            math.degrees(math.acos(max(-1.0, min(1.0, up)))),
            hint,
        )

    # -- Perturbations (bullet_maze.perturbations) ---------------------------------------

    @property
    def perturbation(self) -> dict[str, float | int]:
        """This episode's perturbation values (fixed and drawn; empty if none is set), as
        ``info["perturbation"]`` reports them."""
        return dict(self._perturbation)

    def _check_perturbations(self, settings: Mapping[str, Setting]) -> None:
        """Refuse a perturbation that means nothing for this mode, robot and observation (see
        ``bullet_maze.perturbations.applies``), and keep what ``step`` needs to know."""
        for name in settings:
            reason = applies(
                name,
                mode=self.mode,
                drive=self.robot.drive.kind,
                has_heading=self.robot.has_heading,
                lidar=self.lidar is not None,
                revert_on_collision=self.physics.revert_on_collision,
            )
            if reason is not None:
                raise ValueError(f"{name} = {settings[name]} does not apply here: {reason}")
        self._randomised = any(isinstance(value, Range) for value in settings.values())
        self._physical_drawn = any(isinstance(settings.get(name), Range) for name in PHYSICAL)
        self._queue: deque[Any] | None = deque() if "latency_steps" in settings else None
        self._latency = 0
        self._biased = "bias_along" in settings or "bias_left" in settings
        self._along = self._left = 0.0
        self._position_noise = self._heading_noise = self._lidar_noise = 0.0
        self._noise_scale: float | None = None
        self._rng_parent = None
        self._rng = np.random.default_rng(0)  # replaced at the first reset
        self._sensor_noise = []
        self._sensor_index = 0
        self._nominal: dict[int, Command] = {}

    def _set_perturbation(self, values: dict[str, float | int]) -> None:
        """Make ``values`` this episode's perturbation: the bodies' physics (at construction for
        fixed values, at every reset for drawn ones) and what ``step`` and the observation use."""
        first = not self._perturbation
        self._perturbation = values
        if any(name in values for name in PHYSICAL) and (first or self._physical_drawn):
            if "floor_friction_scale" in values:
                pb.changeDynamics(
                    self.world.ground_id,
                    -1,
                    lateralFriction=self._ground_friction * values["floor_friction_scale"],
                    physicsClientId=self._client,
                )
            if any(name in values for name in PHYSICAL[1:]):
                self.robot.scale_dynamics(
                    mass=values.get("mass_scale", 1.0),
                    friction=values.get("wheel_friction_scale", 1.0),
                    torque=values.get("torque_scale", 1.0),
                )
        if "noise_variance" in values:
            self._noise_scale = math.sqrt(values["noise_variance"])
        self._latency = int(values.get("latency_steps", 0))
        self._along = float(values.get("bias_along", 0.0))
        self._left = float(values.get("bias_left", 0.0))
        self._position_noise = float(values.get("observation_noise", 0.0))
        self._heading_noise = float(values.get("heading_noise", 0.0))
        self._lidar_noise = float(values.get("lidar_noise", 0.0))

    def _perturbed_move(self, action: Any) -> bool:
        """One step of a perturbed env, any action set: the action checked now, executed
        ``latency_steps`` later (until then the robot stays at rest and draws no noise), its
        noise biased by ``bias_along`` / ``bias_left``; whether it collided."""
        checked = self.actions.check(action)
        queue = self._queue
        if queue is not None:
            queue.append(checked)
            if len(queue) <= self._latency:
                return False
            checked = queue.popleft()
        i = self._noise_index
        noise_a, noise_b = self._noise[i], self._noise[i + 1]
        self._noise_index = i + 2
        if self._noise_scale is not None:
            noise_a, noise_b = noise_a * self._noise_scale, noise_b * self._noise_scale
        if self._biased:
            noise_a, noise_b = self._bias(checked, noise_a, noise_b)
        command = self.actions.command(checked, noise_a, noise_b)
        if self._kinematic:
            return self._kinematic_step(command)
        return self._dynamic_step(command)

    def _bias(self, action: Any, noise_a: float, noise_b: float) -> tuple[float, float]:
        """The step's two noise draws plus the actuation bias, in the frame of the action's
        nominal (noise-free) command: a ``Move`` gets ``bias_along`` along its direction and
        ``bias_left`` to its left; a ``Twist`` gets ``bias_along`` on its distance (in the sense
        of its sign) and ``bias_left`` on the arc its rim travels (a turn to the left)."""
        along, left = self._along, self._left
        nominal = self._nominal.get(action) if isinstance(action, int) else None
        if nominal is None:
            nominal = self.actions.command(action, 0.0, 0.0)
            if isinstance(action, int):  # a discrete action's nominal command never changes
                self._nominal[action] = nominal
        if isinstance(nominal, Move):
            length = math.hypot(nominal.dx, nominal.dy)
            if length == 0.0:
                return noise_a, noise_b
            ux, uy = nominal.dx / length, nominal.dy / length
            return noise_a + along * ux - left * uy, noise_b + along * uy + left * ux
        if nominal.distance != 0.0:
            noise_a += math.copysign(along, nominal.distance)
        return noise_a, noise_b + left

    def _draw_noise(self) -> None:
        """Section V.A's noise for the next ``NOISE_BLOCK`` steps, from the seeded ``np_random``
        in one draw (two values per step, so the stream is the same as drawing per step)."""
        block = self.np_random.standard_normal(2 * NOISE_BLOCK) * self._noise_std
        self._noise = block.tolist()
        self._noise_index = 0

    def _observation(self) -> Any:
        if self.robot.has_heading:
            pose = np.array((self._x, self._y, self._heading))
        else:
            pose = np.array((self._x, self._y))
        if self._position_noise > 0.0 or self._heading_noise > 0.0:
            self._add_observation_noise(pose)
        if self.lidar is not None:
            heading = self._heading if self._has_heading else 0.0
            readings = self.lidar.read(self._x, self._y, heading, self._lidar_noise, self._rng)
            pose = np.concatenate((pose, readings))
        if not self._goal_conditioned:
            return pose
        return {
            "observation": pose,
            "achieved_goal": pose[:2].copy(),
            "desired_goal": np.array(self._goal),
        }

    def _add_observation_noise(self, pose: np.ndarray) -> None:
        """``observation_noise`` on x and y (clipped to the arena) and ``heading_noise`` on the
        heading (wrapped): three standard normals per observation (x, y, heading, whichever
        are set), from the perturbations' generator in blocks of ``NOISE_BLOCK``
        observations."""
        i = self._sensor_index
        if i >= len(self._sensor_noise):
            self._sensor_noise = self._rng.standard_normal(3 * NOISE_BLOCK).tolist()
            i = 0
        self._sensor_index = i + 3
        z = self._sensor_noise
        if self._position_noise > 0.0:
            width, height = self._arena
            std = self._position_noise
            pose[0] = min(width, max(0.0, pose[0] + z[i] * std))
            pose[1] = min(height, max(0.0, pose[1] + z[i + 1] * std))
        if self._heading_noise > 0.0:
            pose[2] = wrap_angle(pose[2] + z[i + 2] * self._heading_noise)

    def _sync_body(self) -> None:
        if not self._body_in_sync:
            self.robot.place(self._x, self._y, self._heading)
            self._body_in_sync = True

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
        radius are computed once, about 30 ms, then each check is a lookup; the env keeps its
        ``goal_test``, whose cache lookup hashes every solid)."""
        radius = self.robot.radius
        if self._goal_test is None:  # the layout and the radius are the env's for its lifetime
            self._goal_test = goal_test(self.layout, radius)
        if self._goal_test(start, goal):
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


def _split_params(
    params: dict[str, Any], spec: RobotSpec, actions: str = "compass"
) -> tuple[TaskParams, PhysicsParams, ActionParams, LidarParams, dict[str, Setting]]:
    """The env's keyword parameters as the dataclasses that hold their defaults, and the
    perturbations given (``bullet_maze.perturbations``): unknown names and booleans given for
    numbers are refused; the robot file's lidar and physics defaults (its ``[physics]`` for the
    action set ``actions``) fill in. A ``noise_variance`` given
    as a range is a perturbation; ``TaskParams`` then holds its upper end (which sizes the
    dynamic substeps)."""
    if "max_episode_steps" in params:
        raise TypeError(
            f"max_episode_steps={params['max_episode_steps']!r} is not an env argument: the "
            f"time limit is set by gymnasium.make(..., max_episode_steps=N) with N > 0"
        )
    fields = {f.name: (cls, f) for cls in PARAMS for f in dataclasses.fields(cls)}
    unknown = sorted(set(params) - set(fields) - set(PERTURBATION_NAMES))
    if unknown:
        raise TypeError(
            f"BulletMazeEnv got unknown keyword argument(s) {unknown}; its parameters are "
            f"{sorted(fields)}, the perturbations {sorted(set(PERTURBATION_NAMES) - set(fields))} "
            f"(and maze, robot, mode, render_mode, actions, observation, robot_radius, "
            f"render_width, render_height)"
        )
    params = dict(params)
    given = {
        name: params.pop(name)
        for name in PERTURBATION_NAMES
        if name in params and name not in fields
    }
    if isinstance(params.get("noise_variance"), Mapping | list | tuple | np.ndarray):
        given["noise_variance"] = params.pop("noise_variance")
    settings = parse_settings(given)
    noise = settings.get("noise_variance")
    if isinstance(noise, Range):
        for end in (noise.low, noise.high):
            try:
                TaskParams(noise_variance=end)
            except ValueError as error:
                raise ValueError(f"noise_variance = {given['noise_variance']!r}: {error}") from None
        params["noise_variance"] = noise.high
    for name, value in params.items():
        default = getattr(fields[name][0](), name)
        if isinstance(value, bool) != isinstance(default, bool):
            kind = "a bool" if isinstance(default, bool) else "a number"
            raise TypeError(f"{name} must be {kind}, got {value!r}")
    if spec.lidar_rays is not None:
        params = {"lidar_rays": spec.lidar_rays, **params}
    if spec.lidar_range is not None:
        params = {"lidar_range": spec.lidar_range, **params}
    params = {**spec.physics_defaults(actions), **params}
    built = []
    for cls in PARAMS:
        own = {f.name: params[f.name] for f in dataclasses.fields(cls) if f.name in params}
        built.append(cls(**own))
    task, physics, action_params, lidar_params = built
    assert isinstance(task, TaskParams)
    assert isinstance(physics, PhysicsParams)
    assert isinstance(action_params, ActionParams)
    assert isinstance(lidar_params, LidarParams)
    return task, physics, action_params, lidar_params, settings


def _display_available() -> bool:
    """Whether a GUI can open: always assumed off Linux, else an X11 or Wayland display."""
    if not sys.platform.startswith("linux"):
        return True
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def _finite_numbers(value: Any, name: str, lengths: Sequence[int]) -> list[float]:
    """A sequence of real numbers (not strings, not booleans) of one of ``lengths``."""
    wanted = " or ".join(map(str, lengths))
    if isinstance(value, str | bytes | dict) or not isinstance(value, Sequence | np.ndarray):
        raise ValueError(f"{name} must be a sequence of {wanted} numbers, got {value!r}")
    items = list(np.asarray(value).tolist()) if isinstance(value, np.ndarray) else list(value)
    if any(isinstance(v, bool | np.bool_) or not isinstance(v, numbers.Real) for v in items):
        raise ValueError(f"{name} must be a sequence of {wanted} numbers, got {value!r}")
    if len(items) not in lengths:
        raise ValueError(f"{name} must have {wanted} numbers, got {value!r}")
    values = [float(v) for v in items]
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return values
