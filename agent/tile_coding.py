"""Baseline: linear Sarsa(lambda) over tile coding, the strong fixed representation.

Tile coding is Sutton's multiple offset grids (Sutton, "Generalization in reinforcement
learning: successful examples using sparse coarse coding", NIPS 1996; Sutton and Barto,
*Reinforcement Learning: An Introduction*, 2nd ed. 2018, section 9.5.4): ``tilings`` grids of
``tiles`` tiles per dimension over the observation box, tiling t shifted by ``t / tilings`` of
a tile times the asymmetric displacement vector (1, 3, 5, ...) that section recommends. A state
activates one tile per tiling; Q(s, a) is the sum of the active tiles' weights for a.
Learning is Sarsa(lambda) with replacing traces over binary features (Sutton and Barto 2018,
section 12.7, the algorithm box "Sarsa(lambda) with binary features and linear function
approximation"): the defaults are their Mountain Car settings, 8 tilings, step size
``alpha / tilings`` with alpha = 0.5, lambda = 0.9, epsilon = 0 with weights at 0 (optimistic
when every reward is negative). ``gamma`` defaults to the learner's 0.99 (the book uses 1 on
Mountain Car). Where rewards are positive, zero weights are pessimistic and epsilon 0 never
revises the first greedy action: give ``epsilon`` (0.1 solved CartPole on 10 of 10 dev seeds
and 10 of 10 held-out runs, against 4 and 5 of 10 with 0; ``docs/results.md``, part 41).

Tiles are numbered on first sight by a table of at most ``max_features`` (2^20) entries
(Sutton's ``tiles3`` index hash table, without its hashing: a full table is an error, never a
silent collision). An unbounded observation dimension (CartPole's velocities) is squashed onto
(-1, 1) by ``x / (1 + |x|)`` before tiling (:func:`agent.spaces.squash`): a documented rule for
unbounded inputs, which assumes they are of order 1 in their own units.

State is plain data: the weights ``(n_actions, max_features)``, the tile table as an integer
array, the generator's state.
"""

from __future__ import annotations

import logging
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

logger = logging.getLogger(__name__)


class TileCoder:
    """The active tile of each tiling for an input vector (Sutton and Barto 2018, 9.5.4)."""

    def __init__(
        self,
        low: Sequence[float],
        high: Sequence[float],
        tilings: int,
        tiles: int,
        max_features: int,
    ) -> None:
        self.dims = len(low)
        self.tilings = tilings
        self.tiles = tiles
        self.max_features = max_features
        self.low = [float(v) for v in low]
        self.unbounded = [not math.isfinite(v) for v in low]
        self.low = [-1.0 if free else v for v, free in zip(self.low, self.unbounded, strict=True)]
        high_f = [1.0 if free else float(v) for v, free in zip(high, self.unbounded, strict=True)]
        # tiles span [low, high] with one extra tile so that every offset grid covers the box
        self.scale = [tiles / (h - lo) for lo, h in zip(self.low, high_f, strict=True)]
        self.offsets = [
            [t * (2 * d + 1) / tilings % 1.0 for d in range(self.dims)] for t in range(tilings)
        ]
        self.table: dict[tuple[int, ...], int] = {}

    def features(self, x: list[float], allocate: bool = True) -> list[int]:
        """Feature index of the active tile in each tiling; new tiles are numbered on sight
        (``allocate=False``: an unseen tile is left out)."""
        scaled = [
            (squash(v) if free else v) - lo
            for v, lo, free in zip(x, self.low, self.unbounded, strict=True)
        ]
        scaled = [v * s for v, s in zip(scaled, self.scale, strict=True)]
        out = []
        table = self.table
        for t, offset in enumerate(self.offsets):
            key = (t, *(math.floor(v + o) for v, o in zip(scaled, offset, strict=True)))
            index = table.get(key)
            if index is None:
                if not allocate:
                    continue
                index = len(table)
                if index >= self.max_features:
                    raise ValueError(
                        f"tile table full ({self.max_features} tiles): raise max_features"
                    )
                table[key] = index
            out.append(index)
        return out

    def table_array(self) -> NDArray[np.int64]:
        """The tile table as rows ``(tiling, coordinates..., index)``."""
        rows = [(*key, index) for key, index in self.table.items()]
        return np.asarray(rows, dtype=np.int64).reshape(len(rows), self.dims + 2)

    def load_table(self, rows: NDArray[np.int64]) -> None:
        """Inverse of :meth:`table_array`."""
        self.table = {tuple(int(v) for v in row[:-1]): int(row[-1]) for row in rows}


class TileCodingAgent(BaselineFile):
    """Sarsa(lambda) with replacing traces over tile coding (a baseline; not the paper's).

    Same interface as :class:`agent.SMDPAgent`: ``learn``, ``predict``, ``n_leaves`` (here the
    tiles in use), EpisodeStats per episode (``epochs`` = steps: every step is a decision).
    """

    kind = "tile"

    def __init__(
        self,
        observation_space: spaces.Space,
        action_space: spaces.Space,
        seed: int = 0,
        tilings: int = 8,
        tiles: int = 8,
        alpha: float = 0.5,
        lam: float = 0.9,
        gamma: float = 0.99,
        epsilon: float = 0.0,
        max_features: int = 1 << 20,
        bounds: tuple[Sequence[float], Sequence[float]] | None = None,
        collision_key: str = "collision",
    ) -> None:
        for label, count in (("tilings", tilings), ("tiles", tiles)):
            if isinstance(count, bool) or not isinstance(count, int) or count < 1:
                raise ValueError(f"TileCodingAgent: {label} must be an int >= 1, got {count!r}")
        if isinstance(max_features, bool) or not isinstance(max_features, int):
            raise TypeError(f"TileCodingAgent: max_features must be an int, got {max_features!r}")
        if not 1 <= max_features <= 1 << 24:
            raise ValueError(
                f"TileCodingAgent: max_features must be in [1, 2^24], got {max_features!r}"
            )
        rates: tuple[tuple[str, float, bool], ...] = (
            ("alpha", alpha, True),
            ("lam", lam, False),
            ("gamma", gamma, False),
            ("epsilon", epsilon, False),
        )
        for label, rate, low_open in rates:
            if isinstance(rate, bool) or not isinstance(rate, int | float):
                raise TypeError(f"TileCodingAgent: {label} must be a number, got {rate!r}")
            ok = (rate > 0.0 if low_open else rate >= 0.0) and rate <= 1.0
            if not ok:
                raise ValueError(f"TileCodingAgent: {label} must be in [0, 1], got {rate!r}")
        check_seed(seed)
        check_arguments(
            TileCodingAgent.__init__, "TileCodingAgent", {"collision_key": collision_key}
        )
        low, high = observation_bounds(observation_space, bounds, allow_unbounded=True)
        for d, (lo, hi) in enumerate(zip(low, high, strict=True)):
            if math.isfinite(lo) != math.isfinite(hi):
                raise ValueError(
                    f"TileCodingAgent: dimension {d} is bounded on one side only "
                    f"({lo}, {hi}); pass bounds=(low, high)"
                )
        self.observation_space = observation_space
        self.action_space = action_space
        self.n_actions = action_count(action_space)
        self.bounds = (low, high)
        self.tilings, self.tiles = tilings, tiles
        self.alpha, self.lam, self.gamma, self.epsilon = (
            float(alpha),
            float(lam),
            float(gamma),
            float(epsilon),
        )
        self.max_features = max_features
        self.collision_key = collision_key
        self.coder = TileCoder(low, high, tilings, tiles, max_features)
        self.weights = np.zeros((self.n_actions, max_features), dtype=np.float64)
        self.seed = int(seed)
        self.rng = np.random.default_rng(self.seed)
        self.uniform = UniformStream(self.rng)
        self.episodes_done = 0

    @property
    def n_leaves(self) -> int:
        """Tiles in use (the size of the representation)."""
        return len(self.coder.table)

    def _values(self, features: list[int]) -> list[float]:
        return self.weights[:, features].sum(axis=1).tolist()

    def _choose(self, values: list[float]) -> int:
        uniform = self.uniform
        if self.epsilon > 0.0 and uniform.random() < self.epsilon:
            return int(uniform.random() * self.n_actions)
        return greedy_action(values, uniform)

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

    def _run_episode(self, env: Any, obs: Any) -> EpisodeStats:
        step_size = self.alpha / self.tilings
        decay = self.gamma * self.lam
        w = self.weights
        traces = np.zeros_like(w)
        features = self.coder.features(np.asarray(obs, dtype=np.float64).tolist())
        values = self._values(features)
        action = self._choose(values)
        steps = collisions = 0
        total = 0.0
        info: dict[str, Any] = {}
        terminated = truncated = False
        while True:
            obs, reward, terminated, truncated, info = env.step(action)
            r = float(reward)
            steps += 1
            total += r
            collisions += bool(info.get(self.collision_key, False))
            delta = r - values[action]
            traces[:, features] = 0.0  # replacing traces: clear the other actions' traces too
            traces[action, features] = 1.0
            if terminated:
                used = len(self.coder.table)
                w[:, :used] += step_size * delta * traces[:, :used]
                break
            features = self.coder.features(np.asarray(obs, dtype=np.float64).tolist())
            values = self._values(features)
            next_action = self._choose(values)
            delta += self.gamma * values[next_action]
            used = len(self.coder.table)
            w[:, :used] += step_size * delta * traces[:, :used]
            traces[:, :used] *= decay
            if truncated:
                break
            values = self._values(features)
            action = next_action
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
            mean_epsilon=self.epsilon,
        )
        self.episodes_done += 1
        return stats

    def q_values(self, obs: Any) -> list[float]:
        """Q(obs, a) for every action (tiles never seen count 0; nothing is numbered)."""
        x = observation_vector(obs, len(self.bounds[0]), "predict")
        features = self.coder.features(x, allocate=False)
        if not features:
            return [0.0] * self.n_actions
        return self._values(features)

    def predict(self, obs: Any, deterministic: bool = True) -> int:
        """The greedy action (lowest index among ties); ``deterministic=False``: epsilon-greedy."""
        values = self.q_values(obs)
        if deterministic_flag(deterministic):
            return greedy_among(values)
        return self._choose(values)

    def params(self) -> dict[str, Any]:
        """Constructor arguments, JSON-ready."""
        return {
            "seed": self.seed,
            "tilings": self.tilings,
            "tiles": self.tiles,
            "alpha": self.alpha,
            "lam": self.lam,
            "gamma": self.gamma,
            "epsilon": self.epsilon,
            "max_features": self.max_features,
            "bounds": [list(self.bounds[0]), list(self.bounds[1])],
            "collision_key": self.collision_key,
        }

    def state(self) -> tuple[dict[str, NDArray[Any]], dict[str, Any]]:
        """Plain-data state: arrays (weights, tile table) and JSON-ready metadata."""
        used = len(self.coder.table)
        arrays = {"weights": self.weights[:, :used].copy(), "tiles": self.coder.table_array()}
        meta = {
            "params": self.params(),
            "episodes_done": self.episodes_done,
            "rng": self.uniform.state(),
        }
        return arrays, meta

    def check_state(self, arrays: dict[str, NDArray[Any]]) -> None:
        """A ValueError unless ``arrays`` is a state this agent can take (an agent file's,
        :mod:`agent.baseline_files`): a tile table of rows ``(tiling, coordinates..., index)``
        that numbers each used tile once, ``0 .. used - 1``, with tilings in range and no tile
        twice, and finite weights of ``(n_actions, used)``."""
        from agent.baseline_files import finite

        tiles, weights = arrays["tiles"], arrays["weights"]
        used = tiles.shape[0]
        if tiles.shape != (used, self.coder.dims + 2):
            raise ValueError(
                f"entry 'tiles' has shape {tiles.shape}, expected (tiles, {self.coder.dims + 2})"
            )
        if used > self.max_features:
            raise ValueError(f"entry 'tiles' holds {used} tiles, more than max_features")
        if weights.shape != (self.n_actions, used):
            raise ValueError(
                f"entry 'weights' has shape {weights.shape}, expected {(self.n_actions, used)}"
            )
        if sorted(tiles[:, -1].tolist()) != list(range(used)):
            raise ValueError("entry 'tiles' does not number the used tiles 0 .. n - 1 once each")
        if ((tiles[:, 0] < 0) | (tiles[:, 0] >= self.tilings)).any():
            raise ValueError(f"entry 'tiles' names a tiling outside 0 .. {self.tilings - 1}")
        if len({tuple(row) for row in tiles[:, :-1].tolist()}) != used:
            raise ValueError("entry 'tiles' lists one tile twice")
        finite(arrays, ("weights",))

    def restore(self, arrays: dict[str, NDArray[Any]], meta: dict[str, Any]) -> None:
        """Inverse of :meth:`state` on an agent built with the same parameters."""
        self.coder.load_table(np.asarray(arrays["tiles"], dtype=np.int64))
        weights = np.asarray(arrays["weights"], dtype=np.float64)
        self.weights[:] = 0.0
        self.weights[:, : weights.shape[1]] = weights
        self.episodes_done = int(meta["episodes_done"])
        self.uniform.restore(meta["rng"])

    def __repr__(self) -> str:
        return (
            f"TileCodingAgent(tilings={self.tilings}, tiles={self.tiles}, alpha={self.alpha}, "
            f"lam={self.lam}, gamma={self.gamma}, epsilon={self.epsilon}, seed={self.seed})"
        )
