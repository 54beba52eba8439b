"""Several adaptive trees over one trajectory, their Q-bar averaged (beyond the paper).

Tile coding generalises across the boundary of a tile because its tilings are offset: the value
of a state is the sum of one weight per tiling, and neighbouring states share most of them.
One adaptive tree has no such sharing: a leaf's value is all it knows, and a state near a leaf
boundary is as far from the neighbouring leaf's value as one deep inside.
``TreeConfig(ensemble_trees=K)`` keeps K trees whose presplit points are offset as Sutton's
tilings are (tree k moves the presplit point of dimension d from the midpoint by
``((2d + 1) k / K mod 1)`` of half the leaf's width, read in [-1/2, 1/2); an unbounded
dimension keeps its split at 0 unless ``TreeConfig.ensemble_unbounded_offsets`` moves it in
squashed coordinates; without it a box with no bounded dimension would give K copies of one
tree, and the agent is refused), and acts on the mean of their rows,

    Q(s, a) = (1/K) sum_k Q-bar_k(leaf_k(s), a),

as the averaged shifted histogram averages offset histograms. Every tree is a full learner of
section IV on the same trajectory: its own SMDP epochs (eqs. 9-10), its own split test and, with
``planning="sweep"``, its own model; tree k bootstraps from its own V-bar. A decision point
(section IV.A) is any tree's leaf change, so the composite cells, the intersections of the
trees' leaves, are finer than any one tree's leaves; at a decision point every tree ends its
epoch. Tree 0 is the agent itself (its presplit is at the midpoints, so K = 1 is the plain tree)
and carries the exploration strategy: its leaf is the one the strategy's per-leaf state (the
adaptive epsilon, the tabu list) is kept for, and the strategy sees tree 0's Delta-Q. A held
exploratory run (``hold_exploration``) is learnt by each tree as one epoch per stretch of its
own leaves, as :meth:`SMDPAgent._end_held_run` does for one tree.
"""

from __future__ import annotations

import dataclasses
import math
from collections import deque
from collections.abc import Collection
from os import PathLike
from pathlib import Path
from typing import Any

from gymnasium import spaces

from agent.config import TreeConfig
from agent.env_checks import deterministic_flag, observation_vector
from agent.episode_stats import EpisodeStats
from agent.exploration import Exploration, Greedy
from agent.exploration.base import greedy_action
from agent.leaf_model import Stored
from agent.learner import Bounds
from agent.partition_tree import PartitionTree
from agent.smdp import epoch_returns
from agent.tree_agent import TreeAgent


def save_refusal(config: TreeConfig) -> str | None:
    """Why an agent of ``config`` cannot be saved, or None when it can: a tree ensemble of
    several trees has no file format yet. The harness asks before it trains an agent it must
    save (``run.py train``, ``[experiment] save_agents``)."""
    if config.ensemble_trees > 1:
        return (
            f"a tree ensemble (TreeConfig.ensemble_trees = {config.ensemble_trees}) has no file "
            "format yet"
        )
    return None


def presplit_shifts(tree: int, trees: int, dims: int) -> list[float]:
    """Tree ``tree``'s presplit offsets, one per dimension, in half-widths of the leaf:
    ``(2d + 1) tree / trees mod 1``, read in [-1/2, 1/2) (Sutton's asymmetric offsets)."""
    out = []
    for d in range(dims):
        f = ((2 * d + 1) * tree % trees) / trees
        out.append(f if f < 0.5 else f - 1.0)
    return out


class ShiftedPartitionTree(PartitionTree):
    """A tree whose presplit points are moved from the midpoints by ``shifts`` (half-widths)."""

    def __init__(
        self,
        low: list[float],
        high: list[float],
        config: TreeConfig,
        shifts: list[float],
        integer: bool = False,
        unbounded_offsets: bool = False,
    ) -> None:
        self.shifts = list(shifts)
        self.unbounded_offsets = unbounded_offsets
        """Whether unbounded dimensions' cuts move too (``TreeConfig.ensemble_unbounded_offsets``
        of the ensemble: a member's own config has one tree)."""
        super().__init__(low, high, config, integer)

    def _presplit_point(self, dim: int, low: float, high: float) -> float:
        return 0.5 * (low + high) + self.shifts[dim] * 0.5 * (high - low)

    def _unbounded_presplit_point(self, dim: int) -> float:
        if not self.unbounded_offsets:
            return 0.0
        shift = self.shifts[dim]  # in half-widths of the squashed range (-1, 1): y = shift
        return shift / (1.0 - abs(shift))  # the x whose squash x / (1 + |x|) is y


class _Member(TreeAgent):
    """Tree k > 0 of an ensemble: a plain learner with a shifted presplit that never chooses."""

    ensembles = True

    def __init__(self, ensemble: TreeEnsembleAgent, shifts: list[float]) -> None:
        self._shifts = shifts
        self._ensemble = ensemble
        low, high = ensemble.bounds
        super().__init__(
            ensemble.observation_space,
            ensemble.action_space,
            Greedy(),
            ensemble.seed,
            dataclasses.replace(
                ensemble.config,
                ensemble_trees=1,
                ensemble_decisions="any",
                ensemble_unbounded_offsets=False,
            ),
            (low, high),
        )

    @property
    def discount(self) -> float:
        """The ensemble's discount (``TreeConfig.failure_gamma`` latches for every tree)."""
        return self._ensemble.discount

    def _make_partition(self, low: list[float], high: list[float]) -> PartitionTree:
        return ShiftedPartitionTree(
            low,
            high,
            self.config,
            self._shifts,
            self.integer_inputs,
            self._ensemble.config.ensemble_unbounded_offsets,
        )


class TreeEnsembleAgent(TreeAgent):
    """``TreeConfig.ensemble_trees`` adaptive trees with offset presplits, Q-bar averaged; its
    loop also runs ``TreeConfig.decision_steps`` and ``hold_steps`` (for one tree too).

    Example::

        config = dataclasses.replace(preset("general").config, ensemble_trees=4)
        agent = TreeEnsembleAgent(env.observation_space, env.action_space, "adaptive+tabu",
                                  seed=0, config=config)
    """

    kind = "tree"
    """One tree's file is a tree's file; :meth:`SMDPAgent.load` picks this class by its config."""
    ensembles = True
    runs_loop_options = True

    def __init__(
        self,
        observation_space: spaces.Space,
        action_space: spaces.Space,
        exploration: str | Exploration = "adaptive+tabu",
        seed: int = 0,
        config: TreeConfig | None = None,
        bounds: Bounds | None = None,
    ) -> None:
        super().__init__(observation_space, action_space, exploration, seed, config, bounds)
        k = self.config.ensemble_trees
        dims = len(self.bounds[0])
        self.members: list[TreeAgent] = [self]
        self.members += [_Member(self, presplit_shifts(i, k, dims)) for i in range(1, k)]
        """Tree 0 (this agent) and the shifted trees."""
        if k > 1 and not any(
            member.partition.cuts != self.partition.cuts for member in self.members[1:]
        ):
            raise ValueError(
                f"TreeConfig.ensemble_trees = {k}: every tree would be the same tree, K times the "
                "cost for nothing. The trees differ only by where their presplit cuts the "
                "observation's bounded dimensions, and here none is cut at a finite midpoint "
                f"(bounds low={self.bounds[0]}, high={self.bounds[1]}). Give the agent finite "
                "bounds=(low, high), set ensemble_unbounded_offsets = True (offsets in "
                "squashed coordinates) or use ensemble_trees = 1"
            )
        self.terminals_seen = 0
        """Terminal transitions seen (``TreeConfig.decision_from_terminal``)."""
        self.last_truncated = False
        """Whether the last episode was cut by the time limit (``hold_after_truncation``)."""
        self.crossing_steps = 0
        self.crossings = 0
        """Steps and count of the leaf crossings so far (``TreeConfig.hold_crossings``)."""
        self._trace: list[tuple[Stored, int, float, int, bool, list[float], bool]] | None
        self._trace = [] if self.config.model_lambda > 0.0 and self.model is not None else None
        """This episode's model epochs in order (``TreeConfig.model_lambda``): first input,
        action, discounted reward from the first input, length, terminal, end input, and
        whether its action was exploratory."""
        self._explored = False
        """Whether the action of the epoch under way was exploratory (``model_lambda``)."""
        self._blended: deque[list[tuple[Stored, int, float, float]]] = deque()
        """``TreeConfig.model_lambda_episodes``: per recent episode, oldest first, each epoch it
        blended: first input, action, and the R and D it had before the blend."""
        self.terminal_reward_sum = 0.0
        self.target_sum = 0.0
        self.targets = 0
        """The terminal steps' rewards (over :attr:`terminals_seen` of them), and the sum and
        count of the one-step targets of the steps that ended a non-terminal epoch
        (``TreeConfig.decision_on_failure``)."""
        self.terminal_reward_max: float | None = None
        """The largest terminal reward seen (None before the first; ``failure_measure``
        "every")."""
        self.failure_discount = False
        """Whether ``TreeConfig.failure_gamma`` has latched: the measure found the terminals
        failures at the start of an episode, and the discount is failure_gamma from then on."""

    @property
    def discount(self) -> float:
        """:attr:`SMDPAgent.discount`: ``TreeConfig.failure_gamma`` once latched
        (:attr:`failure_discount`), else ``TreeConfig.gamma``."""
        failure = self.config.failure_gamma
        return failure if self.failure_discount and failure is not None else self.config.gamma

    def learn(
        self,
        env: Any,
        episodes: int,
        callback: Any = None,
        reset_seed: int | None = None,
        fast: bool = True,
    ) -> list[EpisodeStats]:
        """:meth:`SMDPAgent.learn` on the ensemble's loop (never the compiled one)."""
        if not isinstance(fast, bool):
            raise TypeError(f"fast must be a bool, got {fast!r}")
        return super().learn(env, episodes, callback, reset_seed, fast=False)

    def mean_row(self, leaves: list[int]) -> list[float]:
        """The ensemble's Q row: the mean over the trees of each tree's row at its leaf."""
        rows = [m.q[leaf] for m, leaf in zip(self.members, leaves, strict=True)]
        if len(rows) == 1:
            return rows[0]
        k = float(len(rows))
        return [sum(column) / k for column in zip(*rows, strict=True)]

    def _leaves(self, x: list[float]) -> list[int]:
        return [m.partition.leaf_of(x) for m in self.members]

    def predict(self, obs: Any, deterministic: bool = True) -> int:
        """The greedy action of the mean row (lowest index among ties); with
        ``deterministic=False`` the exploration strategy chooses on the mean row."""
        x = observation_vector(obs, len(self.bounds[0]), "predict")
        leaves = self._leaves(x)
        row = self.mean_row(leaves)
        if deterministic_flag(
            deterministic
        ):  # smoothing moves by tree 0's leaf and reads every tree's row
            return self._greedy_choice(x, self.members, leaves, row, self._leaves, self.mean_row)
        return self.exploration.select(leaves[0], row, self.uniform)

    @property
    def n_leaves(self) -> int:
        """Leaves of all the trees together."""
        return sum(m.partition.n_leaves for m in self.members)

    def save(self, path: str | PathLike[str], policy_only: bool = False) -> Path:
        """:meth:`SMDPAgent.save` for one tree (``decision_steps`` alone); an ensemble of
        several trees has no file format yet (a ValueError)."""
        refusal = save_refusal(self.config)
        if refusal is None:
            return super().save(path, policy_only)
        raise ValueError(f"cannot save {path}: {refusal}")

    @property
    def terminals_fail(self) -> bool:
        """``TreeConfig.decision_on_failure``'s measure: the mean reward of the terminal steps
        seen is below the mean one-step target ``r + gamma max_a Q(s', a)`` of the steps that
        ended a non-terminal epoch (False before either has been seen)."""
        if self.terminals_seen == 0 or self.targets == 0:
            return False
        return self.terminal_reward_sum / self.terminals_seen < self.target_sum / self.targets

    @property
    def every_terminal_fails(self) -> bool:
        """``TreeConfig.failure_measure`` "every": the largest terminal reward seen is below
        the mean one-step target of :attr:`terminals_fail` (False before either is seen)."""
        if self.terminal_reward_max is None or self.targets == 0:
            return False
        return self.terminal_reward_max < self.target_sum / self.targets

    def _end_epoch(
        self,
        leaf: int,
        action: int,
        xs: list[list[float]],
        rs: list[float],
        bootstrap: float,
        end_x: list[float] | None = None,
        terminated: bool = False,
    ) -> bool:
        """:meth:`SMDPAgent._end_epoch`, and with ``TreeConfig.model_lambda`` the epoch kept
        for the episode's lambda-returns (:meth:`_blend_episode`)."""
        if self._trace is None or end_x is None:
            return super()._end_epoch(leaf, action, xs, rs, bootstrap, end_x, terminated)
        start = epoch_returns(rs, 0.0, self.discount)[0]  # the discount before this epoch
        split = super()._end_epoch(leaf, action, xs, rs, bootstrap, end_x, terminated)
        assert self.model is not None  # a trace is kept only with the model
        first = self.model.last_added  # the handle of the epoch just stored
        self._trace.append((first, action, start, len(rs), terminated, end_x, self._explored))
        return split

    def _blend_episode(self, terminated: bool) -> None:
        """``TreeConfig.model_lambda`` at the end of an episode: going back from its last
        epoch, G_after(e) is the lambda-return after epoch e,

            G_after(last) = 0 (terminal) or V-bar(s'_last) (truncated),
            G_after(e - 1) = R0_e + gamma^tau_e [(1 - lambda) V-bar(s'_e) + lambda G_after(e)],

        R0_e the epoch's discounted rewards from its first input (eq. 6) and V-bar under the
        values now. With ``TreeConfig.model_lambda_watkins`` the return before an epoch whose
        action was exploratory is cut there, G_after(e - 1) = V-bar(s_e) (Watkins's Q(lambda):
        what follows an exploratory action says nothing of the greedy policy's return). With
        ``TreeConfig.model_lambda_tried_only`` the return is cut, G_after(e) = V-bar(s'_e), where
        epoch e ends in a leaf with an action the model has no epoch of. With
        ``TreeConfig.model_lambda_lower_bound`` G_after(e) = max(G_after(e), V-bar(s'_e)) at
        each step. Each stored epoch is blended with its G_after (:meth:`LeafModel.blend`);
        with ``TreeConfig.model_lambda_episodes`` = n the blends of the episode n episodes
        back are undone (:meth:`LeafModel.restore`). The Q-bar of every changed (leaf,
        action) is set to its model value, and the moved leaves are swept as after an
        epoch."""
        trace, self._trace = self._trace, []
        model = self.model
        if model is None:
            return
        cfg = self.config
        lam = cfg.model_lambda
        watkins = cfg.model_lambda_watkins
        tried_only = cfg.model_lambda_tried_only
        bound = cfg.model_lambda_lower_bound
        kept = cfg.model_lambda_episodes
        actions = range(self.n_actions)
        gamma = self.discount
        q = self.q
        leaf_of = self.partition.leaf_of
        touched: dict[tuple[int, int], None] = {}
        blended: list[tuple[Stored, int, float, float]] = []
        after = 0.0
        if trace:
            after = 0.0 if terminated else max(q[leaf_of(trace[-1][5])])
        for first, action, start, tau, terminal, end_x, explored in reversed(trace or ()):
            if terminal:
                after = start
            else:
                end_leaf = leaf_of(end_x)
                v_end = max(q[end_leaf])
                if tried_only and any(model.count(end_leaf, a) == 0 for a in actions):
                    after = v_end  # an untried action's optimism stays in the bootstrap
                if bound and after < v_end:
                    after = v_end  # a longer return says nothing against the value held
                leaf = leaf_of(first)
                prior = model.blend(leaf, action, first, lam, after)
                if prior is not None:
                    touched[(leaf, action)] = None
                    blended.append((first, action, *prior))
                after = start + gamma**tau * ((1.0 - lam) * v_end + lam * after)
            if explored and watkins:  # the return before an exploratory action is cut there
                after = max(q[leaf_of(first)])
        if kept is not None:
            self._blended.append(blended)
            if len(self._blended) > kept:
                for first, action, reward, discount in self._blended.popleft():
                    leaf = leaf_of(first)
                    if model.restore(leaf, action, first, reward, discount):
                        touched[(leaf, action)] = None
        if not trace and not touched:
            return
        tolerance = self._in_units(cfg.sweep_tolerance)
        for leaf, action in touched:
            row = q[leaf]
            before = max(row)
            modelled = model.value(leaf, action, q)
            if modelled is None:
                continue
            row[action] = modelled + self._bonus(leaf, action)
            change = abs(max(row) - before)
            if change > tolerance:
                model.push(leaf, change)
        model.sweep(q, cfg.sweep_backups, tolerance, self._bonus_function())

    def blend_state(self) -> list[list[list[float]]]:
        """``TreeConfig.model_lambda_episodes``' blends as plain data, oldest episode first:
        per episode ``[key, index, R, D]`` of each blended epoch still stored (its place in
        the model's window, :meth:`LeafModel.locate`, and its form before the blend)."""
        model = self.model
        episodes: list[list[list[float]]] = []
        if model is None:
            return episodes
        n = self.n_actions
        for blends in self._blended:
            rows: list[list[float]] = []
            for first, action, reward, discount in blends:
                leaf = self.partition.leaf_of(first)
                index = model.locate(leaf, action, first)
                if index is not None:  # an epoch no longer stored is never restored
                    rows.append([leaf * n + action, index, reward, discount])
            episodes.append(rows)
        return episodes

    def load_blend_state(self, episodes: Any) -> None:
        """Inverse of :meth:`blend_state`, on this agent's restored model; a ValueError
        names the first defect (a shape, a number, an epoch the model does not hold, more
        episodes than ``model_lambda_episodes``)."""
        kept = self.config.model_lambda_episodes
        model = self.model
        if kept is None or model is None:
            raise ValueError("blended epochs without TreeConfig.model_lambda_episodes")
        if not isinstance(episodes, list) or len(episodes) > kept:
            raise ValueError(f"blended: expected a list of at most {kept} episodes")
        restored: deque[list[tuple[Stored, int, float, float]]] = deque()
        seen: set[tuple[int, int]] = set()
        for e, rows in enumerate(episodes):
            if not isinstance(rows, list):
                raise ValueError(f"blended episode {e}: expected a list, got {rows!r}")
            blends: list[tuple[Stored, int, float, float]] = []
            for row in rows:
                ok = isinstance(row, list) and len(row) == 4
                ok = ok and all(isinstance(v, int) and not isinstance(v, bool) for v in row[:2])
                ok = ok and all(
                    isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)
                    for v in row[2:]
                )
                if not ok:
                    raise ValueError(f"blended episode {e}: {row!r} is not [key, index, R, D]")
                key, index, reward, discount = row
                if (key, index) in seen:
                    raise ValueError(f"blended episode {e}: epoch {index} of key {key} twice")
                seen.add((key, index))
                try:
                    first = model.first_input(key, index)
                except (KeyError, IndexError):
                    raise ValueError(
                        f"blended episode {e}: the model holds no epoch {index} of key {key}"
                    ) from None
                leaf, action = divmod(key, self.n_actions)
                if self.partition.leaf_of(first) != leaf:
                    raise ValueError(f"blended episode {e}: key {key} is not its epoch's leaf")
                blends.append((first, action, float(reward), float(discount)))
            restored.append(blends)
        self._blended = restored

    def _crossings_hold_cap(self, crossings: float) -> int:
        """``TreeConfig.hold_crossings``: ``crossings`` times the mean leaf crossing so far,
        rounded up, at least one step (at least one crossing seen)."""
        return max(1, math.ceil(crossings * self.crossing_steps / self.crossings))

    def _run_episode(self, env: Any, obs: Any) -> EpisodeStats:
        """The reference loop (:meth:`SMDPAgent._run_episode`) over every tree at once."""
        cfg = self.config
        members = self.members
        strategy = self.exploration
        rng = self.uniform
        cap = cfg.max_epoch_steps if cfg.max_epoch_steps is not None else 1 << 62
        hold_cap = cap if cfg.hold_steps is None else cfg.hold_steps
        crossings_cap = cfg.hold_crossings
        if crossings_cap is not None and self.crossings:
            hold_cap = self._crossings_hold_cap(crossings_cap)
        if cfg.failure_gamma is not None and not self.failure_discount:
            every = cfg.failure_measure == "every"
            if self.every_terminal_fails if every else self.terminals_fail:
                self.failure_discount = True  # the latch: failure_gamma for the rest of the run
        if cfg.decision_on_failure:
            redecide = cfg.decision_steps is not None and self.terminals_fail
        else:
            redecide = cfg.decision_steps is not None and (
                self.terminals_seen > 0 or not cfg.decision_from_terminal
            )
        measure = cfg.decision_on_failure or cfg.failure_gamma is not None
        gamma = self.discount
        decide = cfg.decision_steps if redecide and cfg.decision_steps is not None else cap
        key = cfg.collision_key
        end_on_collision = cfg.end_epoch_on_collision
        mark_collisions = cfg.collision_splits
        hold_exploration = cfg.hold_exploration and (
            cfg.hold_terminals is None
            or self.terminals_seen < cfg.hold_terminals
            or (cfg.hold_after_truncation and self.last_truncated)
        )

        first_only = cfg.ensemble_decisions == "first"
        trial = self.tie_trial is not None and self.tie_trial.tries(self.episodes_done)
        avoid_collided = trial and cfg.greedy_tie_trial_avoid_collided
        collided_choices: set[tuple[int, int]] = set()  # (tree 0's leaf, action) of the trial
        x = [float(v) for v in obs]
        leaves = self._leaves(x)
        row = self.mean_row(leaves)
        proposed = action = strategy.select(leaves[0], row, rng)
        if trial:
            action = self._trial_choice(leaves, row, action, collided_choices)
        hold = hold_exploration and strategy.explored
        self._explored = strategy.explored
        eps_sum = strategy.epsilon(leaves[0])
        xs: list[list[float]] = []
        rs: list[float] = []
        held: list[list[int]] = [[] for _ in members]
        current = list(leaves)
        steps = collisions = 0
        epochs = 1
        total = 0.0
        terminated = truncated = False
        info: dict[str, Any] = {}
        while True:
            obs, reward, terminated, truncated, info = env.step(action)
            r = float(reward)
            xs.append(x)
            rs.append(r)
            if hold or first_only:  # tree k's own leaves between two decisions
                for run, leaf in zip(held, current, strict=True):
                    run.append(leaf)
            steps += 1
            total += r
            x = [float(v) for v in obs]
            collided = bool(info.get(key, False))
            if collided:
                collisions += 1
            nxt = self._leaves(x)
            current = nxt
            done = terminated or truncated
            changed = nxt[0] != leaves[0] if first_only else nxt != leaves
            if (
                done
                or (changed and not hold)
                or len(rs) >= (hold_cap if hold else decide)
                or (collided and end_on_collision)
            ):
                # decision_steps: an unheld epoch cut inside the same cell continues greedily
                inside = (
                    redecide and not hold and not changed and not (collided and end_on_collision)
                )
                if avoid_collided and collided and not changed and action != proposed:
                    collided_choices.add((leaves[0], action))
                if measure:  # decision_on_failure, failure_gamma; before this epoch's updates
                    if terminated:
                        self.terminal_reward_sum += r
                        top = self.terminal_reward_max
                        self.terminal_reward_max = r if top is None or r > top else top
                    else:
                        self.target_sum += r + gamma * max(self.mean_row(nxt))
                        self.targets += 1
                splits = []
                for i, m in enumerate(members):
                    m.collision_end = x if collided and mark_collisions else None
                    if hold or (first_only and i > 0):
                        split = m._end_held_run(action, xs, rs, held[i], x, terminated)
                    else:
                        bootstrap = 0.0 if terminated else max(m.q[nxt[i]])
                        split = m._end_epoch(leaves[i], action, xs, rs, bootstrap, x, terminated)
                    m.collision_end = None
                    splits.append(split)
                if not hold and changed:  # a leaf crossing (hold_crossings)
                    self.crossing_steps += len(rs)
                    self.crossings += 1
                    if crossings_cap is not None:
                        hold_cap = self._crossings_hold_cap(crossings_cap)
                if done:
                    break
                leaves = [
                    m.partition.leaf_of(x) if split else leaf
                    for m, split, leaf in zip(members, splits, nxt, strict=True)
                ]
                current = list(leaves)
                held = [[] for _ in members]
                if inside and not any(splits):
                    proposed = action = greedy_action(self.mean_row(leaves), rng)
                    hold = False
                    self._explored = False
                else:
                    row = self.mean_row(leaves)
                    proposed = action = strategy.select(leaves[0], row, rng)
                    if trial:
                        action = self._trial_choice(leaves, row, action, collided_choices)
                    hold = hold_exploration and strategy.explored
                    self._explored = strategy.explored
                eps_sum += strategy.epsilon(leaves[0])
                epochs += 1
                xs = []
                rs = []
        if terminated:
            self.terminals_seen += 1
        self.last_truncated = bool(truncated) and not terminated
        if self._trace is not None:
            self._blend_episode(terminated)
        success = bool(info["is_success"]) if "is_success" in info else bool(terminated)
        strategy.on_episode_end(success)
        for m in members[1:]:
            m.exploration.on_episode_end(success)
            m.episodes_done += 1
        stats = EpisodeStats(
            episode=self.episodes_done,
            steps=steps,
            episode_return=total,
            success=success,
            truncated=bool(truncated) and not terminated,
            leaves=self.n_leaves,
            collisions=collisions,
            epochs=epochs,
            mean_epsilon=eps_sum / epochs,
        )
        if self.tie_trial is not None:
            self.tie_trial.record(self.episodes_done, total)
        self.episodes_done += 1
        return stats

    def _trial_choice(
        self,
        leaves: list[int],
        row: list[float],
        action: int,
        avoided: Collection[tuple[int, int]] = (),
    ) -> int:
        """``TreeConfig.greedy_tie_trial`` in a trial episode: the strategy's ``action`` for the
        trees' ``leaves`` (``row`` their mean Q-bar row), or, where it was a greedy choice that
        ``predict`` would test for ties, the choice of ``predict``'s rule at the trial width z'
        (:mod:`agent.tie_trial`). The choice stands when the strategy explored, when the leaf
        holds one input (a table's cell, which ``predict`` does not test), when the action has
        fewer than max(``greedy_min_epochs``, 1) stored epochs in some tree's leaf, or when no
        other such action is off the strategy's list. Otherwise the actions tied with the best
        of those within z' standard errors (``greedy_tie_errors``' test) are compared by the
        ancestors at z' (``greedy_tie_ancestors``). The standard errors and the ancestors' sums
        are read as ``predict`` caches them, afresh after each episode and each split. A choice
        in ``avoided`` (pairs of tree 0's leaf and an action:
        ``TreeConfig.greedy_tie_trial_avoid_collided``) gives way to the strategy's."""
        trial = self.tie_trial
        assert trial is not None
        if self.exploration.explored or self.holds_one_input(leaves[0]):
            return action
        least = max(self.config.greedy_min_epochs, 1)
        counts = self.fewest_epochs(self.members, leaves)
        if counts[action] < least:
            return action
        listed = self.exploration.listed(leaves[0])
        allowed = [a for a, c in enumerate(counts) if c >= least and a not in listed]
        if action not in allowed or len(allowed) < 2:
            return action
        tied = self._tied(self.members, leaves, row, allowed, trial.trial)
        if len(tied) < 2:
            return action
        choice = self._ancestors_choice(self.members, leaves, tied, trial.trial)
        return action if (leaves[0], choice) in avoided else choice


def tree_agent_class(config: TreeConfig) -> type[TreeAgent]:
    """The tree agent a configuration asks for: :class:`TreeEnsembleAgent` when any of its
    loop options is set (``TreeConfig.loop_options``: its loop runs them), else
    :class:`TreeAgent`."""
    return TreeEnsembleAgent if config.loop_options() else TreeAgent
