"""Baseline: adaptive Q-learning with UCB bonuses (Sinclair, Banerjee and Yu 2019).

Sinclair, Banerjee and Yu, "Adaptive discretization for episodic reinforcement learning in
metric spaces" (Proc. ACM Meas. Anal. Comput. Syst. 3(3), 2019; arXiv:1910.08151), Algorithm 1.
Their learner keeps, for each step h of a finite horizon H, a partition of the state-action
space into balls; it plays the ball with the largest optimistic Q among those that hold the
state, updates that ball by Q <- (1 - a_t) Q + a_t (r + V(x') + b_t) with the learning rate
a_t = (H + 1) / (H + t) and a UCB bonus b_t proportional to 1 / sqrt(t), t the ball's visits,
Q starting at H (optimistic), and splits a ball into halves once t >= (d_max / r(B))^2, the
children inheriting the parent's estimate and count. The authors' code
(github.com/seanrsinclair/AdaptiveQLearning) uses the bonus ``scaling / sqrt(t)``.

Read for this project's tasks, which are discounted, with discrete actions and episodes of
thousands of steps (each adaptation a parameter, documented in docs/paper-notes.md):
- **discrete actions**: one partition of the state box per action, as rlberry's
  ``AdaptiveQLAgent`` does (the action's metric is discrete, so a ball is a box x one action);
  a box splits into 2^d halves along every dimension (the dyadic split of the authors'
  multi-dimensional code), and no action's partition grows beyond ``max_boxes`` boxes (a memory
  guard: in 6 dimensions every split makes 64 boxes);
- **stationary and discounted**: one partition for all steps instead of one per step h (a
  5,000-step maze episode would need 5,000 partitions), with ``gamma`` in the target, the
  value bound ``V_max = max(r_max, 0) / (1 - gamma)`` as the optimistic start and the clip of
  V(x'), and a horizon ``horizon`` in the learning rate (default ``1 / (1 - gamma)``, the
  effective horizon; the rate keeps a box's estimate optimistic for about that many visits);
- **reward units**: the paper assumes rewards in [0, 1]; here ``r_max`` (the largest reward)
  and ``reward_range`` (largest minus smallest reward) say what the task pays, the bonus is
  ``bonus_scale * reward_range / sqrt(t)`` and V(x') is clipped to ``V_max``;
- an unbounded observation dimension is squashed onto (-1, 1) by ``x / (1 + |x|)``.

State is plain data: per action the boxes (low, high), Q, visits, depth and children.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from gymnasium import spaces
from numpy.typing import NDArray

from agent.baseline_files import BaselineFile
from agent.env_checks import CheckedEnv, deterministic_flag, observation_vector
from agent.episode_stats import Callback, EpisodeStats, check_learn_arguments, run_episodes
from agent.exploration.base import greedy_action
from agent.random_stream import UniformStream
from agent.smdp import greedy_among
from agent.spaces import action_count, observation_bounds, squash
from agent.value_checks import check_arguments, check_seed


class BoxTree:
    """A dyadic partition of a box: each split halves the box along every dimension."""

    def __init__(self, low: list[float], high: list[float], value: float, max_depth: int) -> None:
        self.dims = len(low)
        self.max_depth = max_depth
        self.low: list[list[float]] = [list(low)]
        self.high: list[list[float]] = [list(high)]
        self.q: list[float] = [value]
        self.visits: list[int] = [0]
        self.depth: list[int] = [0]
        self.first_child: list[int] = [-1]
        """-1 for a leaf, else the id of the first of its 2^d children."""
        self.n_leaves = 1

    def leaf_of(self, x: Sequence[float]) -> int:
        """The leaf box holding ``x`` (children are numbered by the bits of x >= midpoint)."""
        node = 0
        first = self.first_child
        while first[node] >= 0:
            low, high = self.low[node], self.high[node]
            index = 0
            for d in range(self.dims):
                if x[d] >= 0.5 * (low[d] + high[d]):
                    index |= 1 << d
            node = first[node] + index
        return node

    def split(self, node: int) -> None:
        """Cover ``node`` by its 2^d halves, which inherit its Q and visit count."""
        low, high = self.low[node], self.high[node]
        self.first_child[node] = len(self.q)
        for index in range(1 << self.dims):
            child_low, child_high = [], []
            for d in range(self.dims):
                middle = 0.5 * (low[d] + high[d])
                if index >> d & 1:
                    child_low.append(middle)
                    child_high.append(high[d])
                else:
                    child_low.append(low[d])
                    child_high.append(middle)
            self.low.append(child_low)
            self.high.append(child_high)
            self.q.append(self.q[node])
            self.visits.append(self.visits[node])
            self.depth.append(self.depth[node] + 1)
            self.first_child.append(-1)
        self.n_leaves += (1 << self.dims) - 1

    def arrays(self) -> dict[str, NDArray[Any]]:
        """Plain-data state."""
        return {
            "low": np.asarray(self.low, dtype=np.float64),
            "high": np.asarray(self.high, dtype=np.float64),
            "q": np.asarray(self.q, dtype=np.float64),
            "visits": np.asarray(self.visits, dtype=np.int64),
            "depth": np.asarray(self.depth, dtype=np.int64),
            "first_child": np.asarray(self.first_child, dtype=np.int64),
        }

    def load(self, arrays: dict[str, NDArray[Any]]) -> None:
        """Inverse of :meth:`arrays`."""
        self.low = arrays["low"].tolist()
        self.high = arrays["high"].tolist()
        self.q = arrays["q"].tolist()
        self.visits = [int(v) for v in arrays["visits"]]
        self.depth = [int(v) for v in arrays["depth"]]
        self.first_child = [int(v) for v in arrays["first_child"]]
        self.n_leaves = sum(1 for c in self.first_child if c < 0)


class AdaptiveQAgent(BaselineFile):
    """Adaptive Q-learning with UCB bonuses (Sinclair et al. 2019), read as documented above.

    Same interface as :class:`agent.SMDPAgent` (``learn``, ``predict``, ``n_leaves``: the boxes
    over all actions). Greedy in the optimistic Q: the bonus is the exploration.
    """

    kind = "adaptive-q"

    def __init__(
        self,
        observation_space: spaces.Space,
        action_space: spaces.Space,
        seed: int = 0,
        gamma: float = 0.99,
        r_max: float = 1.0,
        reward_range: float = 1.0,
        bonus_scale: float = 1.0,
        max_depth: int = 10,
        max_boxes: int = 1 << 16,
        horizon: float | None = None,
        bounds: tuple[Sequence[float], Sequence[float]] | None = None,
        collision_key: str = "collision",
    ) -> None:
        for label, value in (
            ("gamma", gamma),
            ("r_max", r_max),
            ("reward_range", reward_range),
            ("bonus_scale", bonus_scale),
        ):
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise TypeError(f"AdaptiveQAgent: {label} must be a number, got {value!r}")
            if not math.isfinite(value):
                raise ValueError(f"AdaptiveQAgent: {label} must be finite, got {value!r}")
        if not 0.0 <= gamma < 1.0:
            raise ValueError(f"AdaptiveQAgent: gamma must be in [0, 1), got {gamma!r}")
        if reward_range <= 0.0 or bonus_scale < 0.0:
            raise ValueError(
                f"AdaptiveQAgent: reward_range must be > 0 and bonus_scale >= 0, "
                f"got {reward_range!r} and {bonus_scale!r}"
            )
        if isinstance(max_depth, bool) or not isinstance(max_depth, int) or not max_depth >= 0:
            raise ValueError(f"AdaptiveQAgent: max_depth must be an int >= 0, got {max_depth!r}")
        if horizon is not None and (
            isinstance(horizon, bool)
            or not isinstance(horizon, int | float)
            or not (horizon >= 1.0 and math.isfinite(horizon))
        ):
            raise ValueError(
                f"AdaptiveQAgent: horizon must be a number >= 1 or None, got {horizon!r}"
            )
        if isinstance(max_boxes, bool) or not isinstance(max_boxes, int) or max_boxes < 1:
            raise ValueError(f"AdaptiveQAgent: max_boxes must be an int >= 1, got {max_boxes!r}")
        check_seed(seed)
        check_arguments(AdaptiveQAgent.__init__, "AdaptiveQAgent", {"collision_key": collision_key})
        low, high = observation_bounds(observation_space, bounds, allow_unbounded=True)
        self.unbounded = [
            not (math.isfinite(lo) and math.isfinite(hi)) for lo, hi in zip(low, high, strict=True)
        ]
        for d, (lo, hi) in enumerate(zip(low, high, strict=True)):
            if math.isfinite(lo) != math.isfinite(hi):
                raise ValueError(
                    f"AdaptiveQAgent: dimension {d} is bounded on one side only "
                    f"({lo}, {hi}); pass bounds=(low, high)"
                )
        box_low = [-1.0 if free else lo for lo, free in zip(low, self.unbounded, strict=True)]
        box_high = [1.0 if free else hi for hi, free in zip(high, self.unbounded, strict=True)]
        self.observation_space = observation_space
        self.action_space = action_space
        self.n_actions = action_count(action_space)
        self.bounds = (low, high)
        self.gamma = float(gamma)
        self.r_max = float(r_max)
        self.reward_range = float(reward_range)
        self.bonus_scale = float(bonus_scale)
        self.max_depth = max_depth
        self.max_boxes = max_boxes
        self.collision_key = collision_key
        self.horizon = 1.0 / (1.0 - self.gamma) if horizon is None else float(horizon)
        self._horizon_param = horizon
        self.v_max = max(self.r_max, 0.0) / (1.0 - self.gamma)
        self.trees = [
            BoxTree(box_low, box_high, self.v_max, max_depth) for _ in range(self.n_actions)
        ]
        self.seed = int(seed)
        self.rng = np.random.default_rng(self.seed)
        self.uniform = UniformStream(self.rng)
        self.episodes_done = 0

    @property
    def n_leaves(self) -> int:
        """Boxes over all actions."""
        return sum(tree.n_leaves for tree in self.trees)

    def _input(self, obs: Any) -> list[float]:
        return self._squashed(np.asarray(obs, dtype=np.float64).reshape(-1).tolist())

    def _squashed(self, x: list[float]) -> list[float]:
        """``x`` with its unbounded inputs squashed onto (-1, 1) (:func:`agent.spaces.squash`)."""
        if any(self.unbounded):
            x = [squash(v) if free else v for v, free in zip(x, self.unbounded, strict=True)]
        return x

    def _values(self, x: list[float]) -> tuple[list[float], list[int]]:
        nodes = [tree.leaf_of(x) for tree in self.trees]
        return [tree.q[n] for tree, n in zip(self.trees, nodes, strict=True)], nodes

    def _greedy(self, values: list[float]) -> int:
        return greedy_action(values, self.uniform)

    def learn(
        self,
        env: Any,
        episodes: int,
        callback: Callback | None = None,
        reset_seed: int | None = None,
    ) -> list[EpisodeStats]:
        """Train for ``episodes`` episodes (as :meth:`agent.SMDPAgent.learn`)."""
        check_learn_arguments(env, episodes, self.n_actions, callback, reset_seed)
        checked = CheckedEnv(env, len(self.bounds[0]), self.bounds)
        return run_episodes(checked, episodes, self._run_episode, callback, reset_seed)

    def update(self, x: list[float], action: int, reward: float, next_value: float) -> None:
        """One step of Algorithm 1 on the box of (x, action); ``next_value`` is V(x') (0 at a
        terminal state), clipped to V_max."""
        tree = self.trees[action]
        node = tree.leaf_of(x)
        tree.visits[node] += 1
        t = tree.visits[node]
        rate = (self.horizon + 1.0) / (self.horizon + t)
        bonus = self.bonus_scale * self.reward_range / math.sqrt(t)
        target = reward + self.gamma * min(self.v_max, next_value) + bonus
        tree.q[node] = (1.0 - rate) * tree.q[node] + rate * target
        if (
            tree.depth[node] < tree.max_depth
            and t >= 4 ** tree.depth[node]
            and len(tree.q) + (1 << tree.dims) <= self.max_boxes
        ):
            tree.split(node)  # r(B) halves per split, so (d_max / r)^2 = 4^depth

    def _run_episode(self, env: Any, obs: Any) -> EpisodeStats:
        x = self._input(obs)
        steps = collisions = 0
        total = 0.0
        info: dict[str, Any] = {}
        terminated = truncated = False
        while not (terminated or truncated):
            values, _ = self._values(x)
            action = self._greedy(values)
            obs, reward, terminated, truncated, info = env.step(action)
            r = float(reward)
            steps += 1
            total += r
            collisions += bool(info.get(self.collision_key, False))
            nxt = self._input(obs)
            next_value = 0.0 if terminated else max(self._values(nxt)[0])
            self.update(x, action, r, next_value)
            x = nxt
        success = bool(info["is_success"]) if "is_success" in info else bool(terminated)
        stats = EpisodeStats(
            episode=self.episodes_done,
            steps=steps,
            episode_return=total,
            success=success,
            truncated=bool(truncated) and not terminated,
            leaves=self.n_leaves,
            collisions=collisions,
            epochs=steps,
            mean_epsilon=0.0,
        )
        self.episodes_done += 1
        return stats

    def predict(self, obs: Any, deterministic: bool = True) -> int:
        """The action of the largest optimistic Q (lowest index among ties unless
        ``deterministic=False``, which breaks ties at random)."""
        x = observation_vector(obs, len(self.bounds[0]), "predict")
        values, _ = self._values(self._squashed(x))
        if deterministic_flag(deterministic):
            return greedy_among(values)
        return self._greedy(values)

    def params(self) -> dict[str, Any]:
        """Constructor arguments, JSON-ready."""
        return {
            "seed": self.seed,
            "gamma": self.gamma,
            "r_max": self.r_max,
            "reward_range": self.reward_range,
            "bonus_scale": self.bonus_scale,
            "max_depth": self.max_depth,
            "max_boxes": self.max_boxes,
            "horizon": self._horizon_param,
            "bounds": [list(self.bounds[0]), list(self.bounds[1])],
            "collision_key": self.collision_key,
        }

    def state(self) -> tuple[dict[str, NDArray[Any]], dict[str, Any]]:
        """Plain-data state: each action's boxes as arrays, and JSON-ready metadata."""
        arrays = {
            f"action{a}.{k}": v
            for a, tree in enumerate(self.trees)
            for k, v in tree.arrays().items()
        }
        meta = {
            "params": self.params(),
            "episodes_done": self.episodes_done,
            "rng": self.uniform.state(),
        }
        return arrays, meta

    def check_state(self, arrays: dict[str, NDArray[Any]]) -> None:
        """A ValueError unless ``arrays`` is a state this agent can take (an agent file's,
        :mod:`agent.baseline_files`): for each action at most ``max_boxes`` boxes whose root
        is this agent's box, each split box's 2^d children a block that halves it (every box
        but the root the child of one box), depths counted from the root up to ``max_depth``,
        finite Q values and visit counts >= 0."""
        from agent.baseline_files import finite

        for a, fresh in enumerate(self.trees):
            key = f"action{a}."
            n = arrays[key + "q"].shape[0]
            dims, fan = fresh.dims, 1 << fresh.dims
            shapes = {"low": (n, dims), "high": (n, dims)}
            for name in ("q", "visits", "depth", "first_child", "low", "high"):
                if arrays[key + name].shape != shapes.get(name, (n,)):
                    raise ValueError(
                        f"entry {key + name!r} has shape {arrays[key + name].shape}, expected "
                        f"{shapes.get(name, (n,))}"
                    )
            finite(arrays, (key + "q", key + "low", key + "high"))
            low, high = arrays[key + "low"], arrays[key + "high"]
            depth, first = arrays[key + "depth"], arrays[key + "first_child"]
            if not 1 <= n <= self.max_boxes:
                raise ValueError(f"action {a} has {n} boxes, not 1 to max_boxes")
            if low[0].tolist() != fresh.low[0] or high[0].tolist() != fresh.high[0]:
                raise ValueError(f"action {a}'s root box differs from the agent's")
            if (arrays[key + "visits"] < 0).any():
                raise ValueError(f"entry {key + 'visits'!r} holds negative counts")
            parent = np.full(n, -1)
            for node in np.flatnonzero(first >= 0).tolist():
                start = int(first[node])
                if not node < start <= n - fan:
                    raise ValueError(f"action {a}: box {node}'s children lie outside the boxes")
                block = np.arange(start, start + fan)
                if (parent[block] >= 0).any():
                    raise ValueError(f"action {a}: a box is the child of two boxes")
                parent[block] = node
                middle = 0.5 * (low[node] + high[node])
                upper = ((np.arange(fan)[:, None] >> np.arange(dims)) & 1).astype(bool)
                if not (
                    np.array_equal(low[block], np.where(upper, middle, low[node]))
                    and np.array_equal(high[block], np.where(upper, high[node], middle))
                ):
                    raise ValueError(f"action {a}: box {node}'s children do not halve it")
            if (parent[1:] < 0).any():
                raise ValueError(f"action {a}: a box other than the root has no parent")
            expected = np.zeros(n, dtype=np.int64)
            for node in range(1, n):  # (a parent's id is below its children's)
                expected[node] = expected[parent[node]] + 1
            if not np.array_equal(depth, expected) or (depth > self.max_depth).any():
                raise ValueError(
                    f"entry {key + 'depth'!r} is not each box's depth (at most max_depth)"
                )

    def restore(self, arrays: dict[str, NDArray[Any]], meta: dict[str, Any]) -> None:
        """Inverse of :meth:`state` on an agent built with the same parameters."""
        for a, tree in enumerate(self.trees):
            prefix = f"action{a}."
            tree.load({k[len(prefix) :]: v for k, v in arrays.items() if k.startswith(prefix)})
        self.episodes_done = int(meta["episodes_done"])
        self.uniform.restore(meta["rng"])

    def __repr__(self) -> str:
        return (
            f"AdaptiveQAgent(gamma={self.gamma}, r_max={self.r_max}, "
            f"reward_range={self.reward_range}, bonus_scale={self.bonus_scale}, seed={self.seed})"
        )
