"""SMDP Q-learning over the leaves of a partition (section IV.A-B, eqs. 6-10).

:class:`SMDPAgent` is the one learner; :class:`~agent.tree_agent.TreeAgent` and
:class:`~agent.grid_agent.GridAgent` only choose its partition. Q-bar and the visit counts are
lists of Python lists indexed by leaf id, because the per-step path (one leaf lookup, two list
appends, a comparison) must stay near a microsecond; the work of eqs. (9)-(10) and the split
test run once per epoch.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable, Sequence
from os import PathLike
from typing import TYPE_CHECKING, Any, Self

import numpy as np
from gymnasium import spaces

from agent.ancestor_ties import PairedSums, ancestors_choice
from agent.config import TreeConfig
from agent.env_checks import CheckedEnv, deterministic_flag, observation_vector
from agent.episode_stats import Callback, EpisodeStats, check_learn_arguments
from agent.exploration import Exploration, make_exploration
from agent.inspection import LeafInfo, render_partition
from agent.leaf_model import LeafModel
from agent.model_split import FloatArray, choose_model_split, choose_policy_split, spread_below
from agent.novelty import NoveltyGrid
from agent.optimism import UntriedOptimism
from agent.partition import Partition
from agent.partition_tree import PartitionTree
from agent.random_stream import UniformStream
from agent.scale import ReturnScale, ReturnSpread, RewardScale
from agent.smdp import epoch_discounts, epoch_returns, greedy_among, leaf_update
from agent.spaces import action_count, integer_inputs, observation_bounds
from agent.tie_trial import TieTrial
from agent.value_checks import check_seed

if TYPE_CHECKING:
    from pathlib import Path

    from agent.serialization import SavedAgent

logger = logging.getLogger(__name__)

Bounds = tuple[Sequence[float], Sequence[float]]
RunnerFactory = Callable[["SMDPAgent", Any], Callable[[Any, Any], EpisodeStats]]

_fast_runner: RunnerFactory | None = None
"""What ``learn(fast=True)`` asks for each ``learn`` call's episode runner; registered by
:mod:`agent.fast_loop` (imported by the package, so that this module does not import it: the
fast loop mirrors the agents and imports them)."""


def register_fast_runner(factory: RunnerFactory | None) -> None:
    """Set the factory ``learn(fast=True)`` uses (None: always the reference loop)."""
    global _fast_runner
    _fast_runner = factory


class SMDPAgent:
    """Q-learning on SMDP epochs over a partition's leaves, with a pluggable exploration strategy.

    An epoch starts at a decision point (an action is chosen for the current leaf) and holds the
    action until the input leaves the leaf, the episode ends, the env reports a collision
    (``config.end_epoch_on_collision``) or ``config.max_epoch_steps`` steps have passed. Then
    eq. (9) gives each input of the epoch its return, eq. (10) updates Q-bar(leaf, action), the
    strategy is told, and the partition receives the state-error pairs (and may split).

    With ``config.hold_exploration`` an exploratory action (the strategy's random choice) is
    held across leaf boundaries too; the run is then learnt as one epoch per leaf it crossed,
    each bootstrapping from the next (:meth:`_end_held_run`).
    """

    kind = "smdp"
    accepts_unbounded = False
    """Whether the partition grows unbounded observation dimensions from the data."""
    ensembles = False
    """Whether the class runs ``TreeConfig.ensemble_trees`` trees (:mod:`agent.tree_ensemble`)."""

    def __init__(
        self,
        observation_space: spaces.Space,
        action_space: spaces.Space,
        exploration: str | Exploration = "adaptive+tabu",
        seed: int = 0,
        config: TreeConfig | None = None,
        bounds: Bounds | None = None,
    ) -> None:
        low, high = observation_bounds(observation_space, bounds, self.accepts_unbounded)
        self.n_actions = action_count(action_space)
        self.observation_space = observation_space
        self.action_space = action_space
        self.bounds = (low, high)
        self.integer_inputs = integer_inputs(observation_space)
        """Whether the inputs are integer cells (:func:`agent.spaces.integer_inputs`)."""
        self.config = config if config is not None else TreeConfig()
        if not isinstance(self.config, TreeConfig):
            raise TypeError(f"config must be a TreeConfig, got {type(self.config).__name__}")
        if not self.ensembles:
            for name, value in self.config.loop_options().items():
                raise ValueError(
                    f"TreeConfig.{name} = {value} needs "
                    f"agent.tree_ensemble.TreeEnsembleAgent, not {type(self).__name__} "
                    "(agent.tree_ensemble.tree_agent_class(config) picks the class)"
                )
        if isinstance(exploration, str):
            exploration = make_exploration(exploration)
        elif not isinstance(exploration, Exploration):
            raise TypeError(
                f"exploration must be a strategy name or an Exploration, got {exploration!r}"
            )
        exploration.bind(self.n_actions)
        self.exploration = exploration
        self.seed = check_seed(seed)
        self.rng = np.random.default_rng(self.seed)
        self.uniform = UniformStream(self.rng)
        """Every draw of the exploration strategies, from :attr:`rng` in blocks."""
        cfg = self.config
        self.scale: ReturnScale | ReturnSpread | RewardScale
        if cfg.scale_rule == "return_std":
            self.scale = ReturnScale()
        elif cfg.scale_rule == "return_iqr":
            self.scale = ReturnSpread()
        else:
            self.scale = RewardScale(cfg.gamma, cfg.scale_horizon)
        """The reward scale measured so far (``TreeConfig.threshold_units="scale"``)."""
        self._track_scale = cfg.threshold_units == "scale"
        self.model: LeafModel | None = (
            LeafModel(self.n_actions, cfg.model_window) if cfg.planning == "sweep" else None
        )
        """The empirical SMDP model of ``TreeConfig.planning="sweep"`` (None otherwise)."""
        self.saved_support: list[list[int]] | None = None
        """``TreeConfig.greedy_min_epochs``: the stored-epoch counts a policy-only file was
        saved with (None otherwise); they stay a floor on the model's counts for its leaves."""
        self.saved_errors: list[list[float]] | None = None
        """Standard errors a policy-only file was saved with (``TreeConfig.greedy_tie_errors``)."""
        self.saved_links: set[tuple[int, int]] | None = None
        """Leaf links a policy-only file was saved with (``TreeConfig.greedy_smoothing_links``)."""
        self.paired_sums = PairedSums(self.n_actions)
        """Per-node sums of ``TreeConfig.greedy_tie_ancestors``, read by ``predict`` alone and
        dropped after every training episode (:meth:`forget_greedy_cache`)."""
        self.leaf_errors: dict[int, list[float]] = {}
        """Each leaf's :meth:`action_errors` as ``predict`` last computed them
        (``TreeConfig.greedy_tie_errors``), read by ``predict`` alone and dropped with the sums
        (:meth:`forget_greedy_cache`)."""
        self.leaf_choices: dict[tuple[int, ...], int] = {}
        """``predict``'s greedy action per leaf (per tuple of the trees' leaves) under
        ``TreeConfig.greedy_tie_ancestors``, which reads the leaf alone, for the configuration
        in ``_choices_config``; dropped with the sums
        (:meth:`forget_greedy_cache`) and when ``config`` is replaced."""
        self._choices_config: TreeConfig | None = None
        self._choices_widths: tuple[float, float] | None = None
        self.tie_trial: TieTrial | None = None
        """``TreeConfig.greedy_tie_trial``'s returns and the widths ``predict`` uses (None:
        off)."""
        if cfg.greedy_tie_trial is not None:
            assert cfg.greedy_tie_errors is not None
            assert cfg.greedy_tie_ancestors is not None
            self.tie_trial = TieTrial(
                (cfg.greedy_tie_errors, cfg.greedy_tie_ancestors),
                cfg.greedy_tie_trial,
                cfg.greedy_tie_trial_episodes,
                cfg.greedy_tie_trial_margin,
                cfg.greedy_tie_trial_every,
                follow=cfg.greedy_tie_trial_follow,
            )
        self.partition: Partition = self._make_partition(low, high)
        if self._track_scale:
            if hasattr(self.partition, "scale"):
                self.partition.scale = self.scale
            exploration.use_scale(self.scale)
        optimistic = exploration.initial_value(cfg.gamma)
        q0 = cfg.q_init if optimistic is None else optimistic
        self.q_init = q0
        """Initial Q-bar of a new row: ``config.q_init`` or the strategy's optimistic value."""
        if self.model is not None:
            self.model.novel_value = q0
        self.novelty = (
            NoveltyGrid(low, high, cfg.novelty_cells, cfg.novelty_max_cells)
            if cfg.novelty_cells is not None
            else None
        )
        """The grid of ``TreeConfig.novelty_cells`` and ``novelty_max_cells`` (None: off)."""
        self.q: list[list[float]] = [[q0] * self.n_actions for _ in range(self.partition.n_ids)]
        self.visits: list[list[int]] = [[0] * self.n_actions for _ in range(self.partition.n_ids)]
        self.episodes_done = 0

    def _make_partition(self, low: list[float], high: list[float]) -> Partition:
        raise NotImplementedError

    def learn(
        self,
        env: Any,
        episodes: int,
        callback: Callback | None = None,
        reset_seed: int | None = None,
        fast: bool = True,
    ) -> list[EpisodeStats]:
        """Train for ``episodes`` episodes; the first resets with ``reset_seed``, the rest unseeded.

        ``callback(stats)`` runs after each episode; returning ``False`` stops learning.
        ``fast=True`` runs each episode with the compiled loop of :mod:`agent.fast_loop` when it
        applies (the kinematic maze env and the agents, settings and strategies it implements;
        bit-identical results), else with :meth:`_run_episode`, the reference loop, which
        ``fast=False`` always uses.
        """
        if not isinstance(fast, bool):
            raise TypeError(f"fast must be a bool, got {fast!r}")
        check_learn_arguments(env, episodes, self.n_actions, callback, reset_seed)
        run_episode: Callable[[Any, Any], EpisodeStats] = self._run_episode
        if fast and episodes > 0 and _fast_runner is not None:
            run_episode = _fast_runner(self, env)
        if run_episode == self._run_episode:  # a user's env: check what it hands the agent
            env = CheckedEnv(env, len(self.bounds[0]), self.bounds)
        # the fast loop writes its state into the agent only when asked (before a callback
        # can look, and at the end)
        sync: Callable[[], None] | None = getattr(run_episode, "sync", None)
        history: list[EpisodeStats] = []
        try:
            for i in range(episodes):
                obs, _ = env.reset(seed=reset_seed if i == 0 else None)
                stats = run_episode(env, obs)
                self.forget_greedy_cache()
                if self.episodes_done == self.config.novelty_episodes:
                    for member in getattr(self, "members", [self]):  # TreeEnsembleAgent's trees
                        if member._novelty_open(member.episodes_done - 1):  # open until now
                            member._stop_novelty()
                history.append(stats)
                logger.debug("%s", stats)
                if callback is not None:
                    if sync is not None:
                        sync()
                    if callback(stats) is False:
                        break
        finally:
            if sync is not None:
                sync()
            self.forget_greedy_cache()
        return history

    def forget_greedy_cache(self) -> None:
        """Drop what ``predict`` caches between calls, in every tree: the per-node sums and the
        per-leaf choices of ``TreeConfig.greedy_tie_ancestors`` and the leaves' standard errors
        of ``TreeConfig.greedy_tie_errors``. :meth:`learn` calls it after every episode and
        ``split_leaf`` after a split; code that edits Q-bar or the model by hand calls it
        before the next ``predict``."""
        for member in getattr(self, "members", [self]):  # TreeEnsembleAgent's trees
            member.paired_sums.clear()
            member.leaf_errors.clear()
            member.leaf_choices.clear()

    def _run_episode(self, env: Any, obs: Any) -> EpisodeStats:
        cfg = self.config
        q = self.q
        leaf_of = self.partition.leaf_of
        strategy = self.exploration
        rng = self.uniform
        cap = cfg.max_epoch_steps if cfg.max_epoch_steps is not None else 1 << 62
        key = cfg.collision_key
        end_on_collision = cfg.end_epoch_on_collision
        hold_exploration = cfg.hold_exploration
        ndarray = np.ndarray

        x = obs.tolist() if type(obs) is ndarray else [float(v) for v in obs]
        leaf = leaf_of(x)
        action = strategy.select(leaf, q[leaf], rng)
        hold = hold_exploration and strategy.explored
        eps_sum = strategy.epsilon(leaf)
        xs: list[list[float]] = []
        rs: list[float] = []
        held_leaves: list[int] = []  # leaf of each input of a held run
        current = leaf
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
            if hold:
                held_leaves.append(current)
            steps += 1
            total += r
            x = obs.tolist() if type(obs) is ndarray else [float(v) for v in obs]
            collided = bool(info.get(key, False))
            if collided:
                collisions += 1
            nxt = leaf_of(x)
            current = nxt
            done = terminated or truncated
            if (
                done
                or (nxt != leaf and not hold)
                or len(rs) >= cap
                or (collided and end_on_collision)
            ):
                if hold:
                    split = self._end_held_run(action, xs, rs, held_leaves, x, terminated)
                    held_leaves = []
                else:
                    bootstrap = 0.0 if terminated else max(q[nxt])
                    split = self._end_epoch(leaf, action, xs, rs, bootstrap, x, terminated)
                if done:
                    break
                leaf = current = leaf_of(x) if split else nxt
                q = self.q
                action = strategy.select(leaf, q[leaf], rng)
                hold = hold_exploration and strategy.explored
                eps_sum += strategy.epsilon(leaf)
                epochs += 1
                xs = []
                rs = []
        success = bool(info["is_success"]) if "is_success" in info else bool(terminated)
        strategy.on_episode_end(success)
        stats = EpisodeStats(
            episode=self.episodes_done,
            steps=steps,
            episode_return=total,
            success=success,
            truncated=bool(truncated) and not terminated,
            leaves=self.partition.n_leaves,
            collisions=collisions,
            epochs=epochs,
            mean_epsilon=eps_sum / epochs,
        )
        self.episodes_done += 1
        return stats

    @property
    def discount(self) -> float:
        """The discount of eqs. (6), (7), (9) now: ``TreeConfig.gamma`` (the tree ensemble's
        loop may latch ``TreeConfig.failure_gamma`` instead)."""
        return self.config.gamma

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
        """Eqs. (9)-(10) for one epoch, then the strategy's hooks and the partition's split test.

        ``end_x`` is the input the epoch ended at and ``terminated`` whether it was terminal
        (the model of ``TreeConfig.planning="sweep"`` stores them). Returns whether ``leaf`` was
        split.
        """
        cfg = self.config
        row = self.q[leaf]
        old = row[action]
        gamma = self.discount
        returns = epoch_returns(rs, bootstrap, gamma)
        new, errors = leaf_update(old, returns, cfg.alpha)
        if self._track_scale:
            self.scale.add(rs if cfg.scale_rule == "reward_median" else returns)
        model = self.model
        if model is not None and end_x is not None:
            before = max(row)
            rewards = epoch_returns(rs, 0.0, gamma)
            discounts = epoch_discounts(len(rs), gamma)
            tau = len(rs)
            end_leaf = -1 if terminated else self.partition.leaf_of(end_x)
            model.add(
                leaf,
                action,
                xs[0],
                sum(rewards) / tau,
                sum(discounts) / tau,
                None if terminated else end_x,
                end_leaf,
                self.novelty is not None and self._novel_end(xs, end_x, terminated),
            )
            if (
                terminated
                and model.terminals == cfg.novelty_terminals
                and self.novelty is not None
                and (cfg.novelty_episodes is None or self.episodes_done < cfg.novelty_episodes)
            ):  # (novelty_episodes may have ended the novel ends already)
                self._stop_novelty()
            value = model.value(leaf, action, self.q)
            if value is not None:
                new = value + self._bonus(leaf, action)
        row[action] = new
        self.visits[leaf][action] += 1
        strategy = self.exploration
        strategy.update(leaf, action, new - old)
        strategy.on_epoch_end(leaf, action)
        if model is not None:
            change = abs(max(row) - before) if end_x is not None else 0.0
            tolerance = self._in_units(cfg.sweep_tolerance)
            if change > tolerance:
                model.push(leaf, change)
            model.sweep(self.q, cfg.sweep_backups, tolerance, self._bonus_function())
        if not self.partition.records_errors:
            return False
        children = self.partition.record(leaf, xs, errors)
        if children is None and end_x is not None:
            children = self._model_split(leaf, action)
        if children is None:
            return False
        self._grow(leaf, children)
        return True

    def _model_split(self, leaf: int, action: int) -> tuple[int, int] | None:
        """``TreeConfig.model_split_epochs``: split ``leaf`` where the stored epochs of
        ``action`` there disagree (:func:`agent.model_split.choose_model_split`); returns the
        children, or None (off, too few epochs, no room, or no admissible cut)."""
        cfg = self.config
        model = self.model
        partition = self.partition
        least = cfg.model_split_epochs
        if least is None or model is None or not isinstance(partition, PartitionTree):
            return None
        if model.count(leaf, action) < least or not partition.may_split():
            return None
        if cfg.model_split_from_terminal and model.terminals == 0:
            return None
        firsts, targets = model.targets(leaf, action, self.q)
        min_gap = self._in_units(cfg.model_split_gap)
        if not cfg.policy_splits and spread_below(targets, min_gap):
            return None  # choose_model_split's first test, before any array is built
        low, high, _, min_width = partition.split_box(leaf)
        choice = choose_model_split(
            np.asarray(firsts, dtype=np.float64),
            np.asarray(targets, dtype=np.float64),
            low,
            high,
            min_width,
            min_gap=min_gap,
            min_t=cfg.model_split_t,
        )
        if choice is None and cfg.policy_splits:
            choice = self._policy_split(leaf, action, firsts, targets, (low, high, min_width))
        if choice is None:
            return None
        if cfg.model_split_drops_pairs:
            return partition.split(leaf, *choice)
        return partition.split_with_samples(leaf, *choice)

    def _policy_split(
        self,
        leaf: int,
        action: int,
        firsts: Sequence[Sequence[float]],
        targets: list[float],
        box: tuple[FloatArray, FloatArray, FloatArray],
    ) -> tuple[int, float] | None:
        """``TreeConfig.policy_splits``: the cut of ``leaf`` where the greedy choice between
        ``action`` (its stored ``firsts`` and eq. (8) ``targets``) and another action with at
        least ``model_split_epochs`` stored epochs flips (:func:`agent.model_split.
        choose_policy_split`); the largest t over the other actions, the lower action on a
        tie. None when no other action has a crossing."""
        cfg = self.config
        model = self.model
        assert model is not None
        assert cfg.model_split_epochs is not None
        low, high, min_width = box
        mine = np.asarray(firsts, dtype=np.float64)
        mine_targets = np.asarray(targets, dtype=np.float64)
        min_gap = self._in_units(cfg.model_split_gap)
        best: tuple[float, int, float] | None = None
        for other in range(model.n_actions):
            if other == action or model.count(leaf, other) < cfg.model_split_epochs:
                continue
            other_firsts, other_targets = model.targets(leaf, other, self.q)
            found = choose_policy_split(
                mine,
                mine_targets,
                np.asarray(other_firsts, dtype=np.float64),
                np.asarray(other_targets, dtype=np.float64),
                low,
                high,
                min_width,
                min_gap=min_gap,
                min_t=cfg.model_split_t,
            )
            if found is not None and (best is None or found[0] > best[0]):
                best = found
        return None if best is None else (best[1], best[2])

    def _novel_end(self, xs: list[list[float]], end_x: list[float], terminated: bool) -> bool:
        """``TreeConfig.novelty_cells``: count the epoch's inputs and say whether it ended in a
        cell no input has been in (:mod:`agent.novelty`). The terminal epoch that makes
        ``novelty_terminals`` points every novel end at its leaf; from then on nothing is
        counted."""
        model = self.model
        grid = self.novelty
        assert model is not None
        assert grid is not None
        if not self._novelty_open():
            return False
        seen = model.seen
        for x in xs:
            cell = grid.cell(x)
            seen[cell] = seen.get(cell, 0) + 1
        return not terminated and grid.cell(end_x) not in seen

    def _novelty_open(self, episodes: int | None = None) -> bool:
        """Whether novel ends are counted: ``novelty_cells`` on, fewer than
        ``novelty_terminals`` terminal epochs, and fewer than ``novelty_episodes`` episodes
        ended (``episodes``, default :attr:`episodes_done`)."""
        cfg = self.config
        ended = self.episodes_done if episodes is None else episodes
        return (
            self.novelty is not None
            and self.model is not None
            and self.model.terminals < cfg.novelty_terminals
            and (cfg.novelty_episodes is None or ended < cfg.novelty_episodes)
        )

    def _stop_novelty(self) -> None:
        """``novelty_terminals`` terminal epochs recorded, or ``novelty_episodes`` episodes
        ended: every novel end now bootstraps from its end leaf; the values it moves are set
        and their leaves queued for the sweeps."""
        model = self.model
        assert model is not None
        q = self.q
        for key in model.end_novelty(self.partition.leaf_of):
            leaf, action = divmod(key, self.n_actions)
            value = model.value(leaf, action, q)
            if value is None:
                continue
            row = q[leaf]
            before = max(row)
            row[action] = value + self._bonus(leaf, action)
            change = abs(max(row) - before)
            if change > 0.0:
                model.push(leaf, change)

    def _in_units(self, value: float) -> float:
        """A constant of ``TreeConfig`` in reward units (``threshold_units``)."""
        return value * self.scale.value if self._track_scale else value

    def _bonus(self, leaf: int, action: int) -> float:
        """MBIE-EB bonus ``beta / sqrt(n(leaf, action))`` of ``TreeConfig.model_bonus`` (0 once
        ``TreeConfig.model_bonus_terminals`` terminal epochs have been recorded)."""
        beta = self.config.model_bonus
        if beta == 0.0 or self.model is None or self._bonus_expired():
            return 0.0
        n = self.model.epochs.get(leaf * self.n_actions + action, 0)
        return self._in_units(beta) / math.sqrt(n) if n else 0.0

    def _bonus_function(self) -> Callable[[int, int], float] | None:
        if self.config.model_bonus > 0.0 and not self._bonus_expired():
            return self._bonus
        return None

    def _bonus_expired(self) -> bool:
        """Whether ``TreeConfig.model_bonus_terminals`` terminal epochs have been recorded."""
        limit = self.config.model_bonus_terminals
        return limit > 0 and self.model is not None and self.model.terminals >= limit

    def _after_terminal_epoch(self) -> None:
        """Called after each terminal epoch: the epoch that ends the bonus
        (``TreeConfig.model_bonus_terminals``) recomputes every Q-bar the model holds without
        it and queues the leaves that moved, so that no value keeps the bonus it was given."""
        model = self.model
        cfg = self.config
        if model is None or cfg.model_bonus == 0.0 or cfg.model_bonus_terminals == 0:
            return
        if model.terminals != cfg.model_bonus_terminals:
            return
        for leaf, change in model.backup_all(self.q).items():
            model.push(leaf, change)

    def _end_held_run(
        self,
        action: int,
        xs: list[list[float]],
        rs: list[float],
        leaves: list[int],
        last_x: list[float],
        terminated: bool,
    ) -> bool:
        """Learn a held exploratory run as one epoch per maximal stretch of inputs in one leaf.

        Each stretch is an ordinary epoch of eqs. (9)-(10) whose V-bar(s') is the next
        stretch's leaf (the last one bootstraps like any epoch). A split while the stretches
        are learnt re-assigns the inputs not yet learnt to the new leaves. Returns whether any
        leaf split.
        """
        leaf_of = self.partition.leaf_of
        last_leaf = leaf_of(last_x)
        any_split = False
        start, n = 0, len(rs)
        while start < n:
            leaf = leaves[start]
            end = start + 1
            while end < n and leaves[end] == leaf:
                end += 1
            if end < n:
                bootstrap = max(self.q[leaves[end]])
                end_x, end_terminal = xs[end], False
            else:
                bootstrap = 0.0 if terminated else max(self.q[last_leaf])
                end_x, end_terminal = last_x, terminated
            if self._end_epoch(
                leaf, action, xs[start:end], rs[start:end], bootstrap, end_x, end_terminal
            ):
                any_split = True
                leaves[end:] = [leaf_of(x) for x in xs[end:]]
                last_leaf = leaf_of(last_x)
            start = end
        return any_split

    def _grow(self, parent: int, children: tuple[int, int]) -> None:
        """Give the new leaves rows of Q-bar and counts (section IV.B, children of a split)."""
        cfg = self.config
        while len(self.q) < self.partition.n_ids:
            self.q.append([self.q_init] * self.n_actions)
            self.visits.append([0] * self.n_actions)
        for child in children:
            if cfg.inherit_q:
                self.q[child] = list(self.q[parent])
            if not cfg.reset_counts_on_split:
                self.visits[child] = list(self.visits[parent])
        if self.model is not None:
            self._refile_model(parent, children)
        self.exploration.on_split(parent, children)

    def _refile_model(self, parent: int, children: tuple[int, int]) -> None:
        """After a split, both children (and the epochs ending in them) get model values."""
        model = self.model
        assert model is not None
        q = self.q
        parent_value = max(q[parent])
        before = {leaf: max(q[leaf]) for leaf in children}
        for key in model.split(parent, children, self.partition.leaf_of):
            leaf, action = divmod(key, self.n_actions)
            if leaf not in before:
                before[leaf] = max(q[leaf])
            value = model.value(leaf, action, q)
            if value is not None:
                q[leaf][action] = value + self._bonus(leaf, action)
        tolerance = self._in_units(self.config.sweep_tolerance)
        for leaf, old in before.items():
            change = abs(max(q[leaf]) - (parent_value if leaf in children else old))
            if change > tolerance:
                model.push(leaf, change)

    def predict(self, obs: Any, deterministic: bool = True) -> int:
        """The greedy action for ``obs`` (lowest index among ties); with ``deterministic=False``
        the exploration strategy chooses (drawing from the agent's generator).
        """
        x = observation_vector(obs, len(self.bounds[0]), "predict")
        leaf = self.partition.leaf_of(x)
        row = self.q[leaf]
        if deterministic_flag(deterministic):
            leaves_at = lambda p: [self.partition.leaf_of(p)]  # noqa: E731
            return self._greedy_choice(x, [self], [leaf], row, leaves_at, lambda ls: self.q[ls[0]])
        return self.exploration.select(leaf, row, self.uniform)

    def _greedy_choice(
        self,
        x: list[float],
        agents: Sequence[SMDPAgent],
        leaves: list[int],
        row: list[float],
        leaves_at: Callable[[list[float]], list[int]],
        row_of: Callable[[list[int]], list[float]],
    ) -> int:
        """``predict``'s greedy action: eq. (11) over ``row`` (the Q-bar row of ``leaves``,
        ``agents[i]``'s leaf ``leaves[i]`` holding ``x``) among the allowed actions
        (``TreeConfig.greedy_min_epochs``), or with ``TreeConfig.greedy_smoothing`` over the
        smoothed row, among the tied actions of ``TreeConfig.greedy_tie_errors``; with
        ``TreeConfig.greedy_tie_ancestors``, :meth:`_ancestors_rule`, kept per leaf (at the
        widths of ``TreeConfig.greedy_tie_trial`` when it is on, :meth:`tie_widths`).
        ``leaves_at(p)`` gives the leaves of a point and ``row_of(leaves)`` their row."""
        cfg = self.config
        if cfg.greedy_tie_ancestors is not None:  # (with greedy_tie_errors, no smoothing)
            # the choice reads the leaves alone, not where in them x lies: kept per leaf
            widths = self.tie_widths()
            if self._choices_config is not cfg or self._choices_widths != widths:
                self.leaf_choices.clear()
                self._choices_config = cfg
                self._choices_widths = widths
            key = tuple(leaves)
            choice = self.leaf_choices.get(key)
            if choice is None:
                choice = self._ancestors_rule(agents, leaves, row, widths)
                self.leaf_choices[key] = choice
            return choice
        allowed = self._supported(agents, leaves)
        if cfg.greedy_smoothing == 0.0 or self.holds_one_input(leaves[0]):
            return greedy_among(row, allowed)
        if cfg.greedy_tie_errors is not None:
            allowed = self._tied(agents, leaves, row, allowed, cfg.greedy_tie_errors)
            if len(allowed) == 1:
                return allowed[0]
        low, high = self.partition.leaf_bounds(leaves[0])
        h = cfg.greedy_smoothing
        rows = [row]
        for j, (lo, hi) in enumerate(zip(low, high, strict=True)):
            if not -math.inf < lo < hi < math.inf:
                continue  # an unbounded edge: no width to move by
            for step in (-h * (hi - lo), h * (hi - lo)):
                moved = list(x)
                moved[j] += step
                if not cfg.greedy_smoothing_links:
                    rows.append(row_of(leaves_at(moved)))
                    continue
                others = leaves_at(moved)
                if others != leaves and all(
                    other == own or agent.linked(own, other)
                    for agent, own, other in zip(agents, leaves, others, strict=True)
                ):
                    rows.append(row_of(others))
        n = len(rows)
        smoothed = [sum(column) / n for column in zip(*rows, strict=True)]
        return greedy_among(smoothed, allowed)

    def tie_widths(self) -> tuple[float, float]:
        """The widths of ``predict``'s tie tests now, (leaf, ancestors): those of
        ``TreeConfig.greedy_tie_errors`` and ``greedy_tie_ancestors``, or the trial width while
        ``TreeConfig.greedy_tie_trial`` adopts it (:class:`agent.tie_trial.TieTrial`)."""
        if self.tie_trial is not None:
            return self.tie_trial.widths()
        cfg = self.config
        if cfg.greedy_tie_errors is None or cfg.greedy_tie_ancestors is None:
            raise ValueError("tie_widths needs greedy_tie_errors and greedy_tie_ancestors")
        return cfg.greedy_tie_errors, cfg.greedy_tie_ancestors

    def _ancestors_rule(
        self,
        agents: Sequence[SMDPAgent],
        leaves: list[int],
        row: list[float],
        widths: tuple[float, float],
    ) -> int:
        """``TreeConfig.greedy_tie_ancestors``' greedy action for the trees' ``leaves`` (``row``
        their Q-bar row), computed afresh: the best allowed action, unless others are tied with
        it (``greedy_tie_errors``, at ``widths[0]``); then the ancestors choose among them (at
        ``widths[1]``)."""
        allowed = self._supported(agents, leaves)
        if self.holds_one_input(leaves[0]):
            return greedy_among(row, allowed)
        tied = self._tied(agents, leaves, row, allowed, widths[0])
        if len(tied) == 1:
            return tied[0]
        return self._ancestors_choice(agents, leaves, tied, widths[1])

    def _ancestors_choice(
        self, agents: Sequence[SMDPAgent], leaves: list[int], tied: list[int], z: float
    ) -> int:
        """``TreeConfig.greedy_tie_ancestors``: the tied actions compared in the ancestors of
        each tree's leaf (:func:`agent.ancestor_ties.ancestors_choice`)."""
        trees = [agent.tree_structure() for agent in agents]

        def difference(t: int, node: int, a: int, b: int) -> tuple[float, float]:
            agent = agents[t]
            sums = agent.paired_sums.at(node, trees[t], agent.q, agent.support)
            return agent.paired_sums.difference(sums, a, b)

        return ancestors_choice(tied, leaves, lambda t, node: trees[t].parent(node), difference, z)

    def tree_structure(self) -> PartitionTree:
        """The tree ``TreeConfig.greedy_tie_ancestors`` walks (a ValueError for a partition
        without ancestors)."""
        if not isinstance(self.partition, PartitionTree):
            raise ValueError(
                "TreeConfig.greedy_tie_ancestors needs the adaptive tree's ancestors; "
                f"{type(self).__name__}'s partition is a {type(self.partition).__name__}"
            )
        return self.partition

    def _tied(
        self,
        agents: Sequence[SMDPAgent],
        leaves: list[int],
        row: list[float],
        allowed: list[int] | None,
        z: float,
    ) -> list[int]:
        """``TreeConfig.greedy_tie_errors``: the allowed actions whose Q-bar in ``row`` lies
        within ``z`` combined standard errors of the greedy action's (that action first)."""
        best = greedy_among(row, allowed)
        each = [agent.cached_errors(leaf) for agent, leaf in zip(agents, leaves, strict=True)]
        errors = [sum(column) / len(each) for column in zip(*each, strict=True)]
        candidates = range(self.n_actions) if allowed is None else allowed
        tied = [best]
        for a in candidates:
            if a != best and abs(row[best] - row[a]) <= z * math.hypot(errors[best], errors[a]):
                tied.append(a)
        return tied

    def cached_errors(self, leaf: int) -> list[float]:
        """:meth:`action_errors` of ``leaf``, computed once until :meth:`forget_greedy_cache`
        (``predict`` alone reads them; values or a model edited by hand need that call)."""
        errors = self.leaf_errors.get(leaf)
        if errors is None:
            errors = self.leaf_errors[leaf] = self.action_errors(leaf)
        return errors

    def action_errors(self, leaf: int) -> list[float]:
        """The standard error of each action's Q-bar in ``leaf`` (``LeafModel.errors``); for a
        leaf without stored epochs, those a policy-only file was saved with, if any (infinite
        otherwise)."""
        saved = self.saved_errors
        unlearnt = self.model is None or not any(self.model.counts(leaf))
        if saved is not None and leaf < len(saved) and unlearnt:
            return list(saved[leaf])
        if self.model is None:
            return [math.inf] * self.n_actions
        return self.model.errors(leaf, self.q)

    def linked(self, a: int, b: int) -> bool:
        """Whether the model links leaves ``a`` and ``b`` (``LeafModel.linked``) or a
        policy-only file was saved with the link."""
        if self.saved_links is not None and (min(a, b), max(a, b)) in self.saved_links:
            return True
        return self.model is not None and self.model.linked(a, b)

    def support(self, leaf: int) -> list[int]:
        """Epochs of each action stored in the model for ``leaf`` (at least the counts a
        policy-only file was saved with); zeros without a model."""
        counts = [0] * self.n_actions if self.model is None else self.model.counts(leaf)
        saved = self.saved_support
        if saved is not None and leaf < len(saved):
            counts = [max(c, s) for c, s in zip(counts, saved[leaf], strict=True)]
        return counts

    def holds_one_input(self, leaf: int) -> bool:
        """Whether ``leaf`` holds a single input: the inputs are integers
        (:func:`agent.spaces.integer_inputs`) and its box ``[low, high)`` holds one integer in
        every dimension (``TreeConfig.greedy_cell_epochs``)."""
        if not self.integer_inputs:
            return False
        low, high = self.partition.leaf_bounds(leaf)
        for lo, hi in zip(low, high, strict=True):
            if not -math.inf < lo < hi < math.inf or math.ceil(hi) - math.ceil(lo) != 1:
                return False
        return True

    def _supported(self, agents: Sequence[SMDPAgent], leaves: Sequence[int]) -> list[int] | None:
        """``TreeConfig.greedy_min_epochs``: the actions with at least that many stored epochs
        in every tree's leaf (``agents[i]`` holding ``leaves[i]``); None when the option is off
        or no action has them (then every action competes)."""
        k = self.config.greedy_min_epochs
        if k == 0:
            return None
        cell = self.config.greedy_cell_epochs
        if (
            cell is not None
            and self.integer_inputs  # float inputs never hold one input: no per-tree check
            and all(agent.holds_one_input(leaf) for agent, leaf in zip(agents, leaves, strict=True))
        ):
            k = cell  # TreeConfig.greedy_cell_epochs: every tree's leaf is one input
            if k == 0:
                return None
        counts = self.fewest_epochs(agents, leaves)
        allowed = [a for a, c in enumerate(counts) if c >= k]
        return allowed or None

    @staticmethod
    def fewest_epochs(agents: Sequence[SMDPAgent], leaves: Sequence[int]) -> list[int]:
        """Each action's stored epochs (:meth:`support`) in the trees' ``leaves``, the fewest
        over the trees (``agents[i]`` holding ``leaves[i]``)."""
        if len(agents) == 1:
            return agents[0].support(leaves[0])
        each = [agent.support(leaf) for agent, leaf in zip(agents, leaves, strict=True)]
        return [min(column) for column in zip(*each, strict=True)]

    def leaf_of(self, obs: Any) -> int:
        """Id of the leaf that holds ``obs``."""
        return self.partition.leaf_of(observation_vector(obs, len(self.bounds[0]), "leaf_of"))

    @property
    def n_leaves(self) -> int:
        """Number of leaves of the partition."""
        return self.partition.n_leaves

    @property
    def depth(self) -> int:
        """Largest leaf depth (0 for a single root or a grid)."""
        return max(self.partition.leaf_depth(leaf) for leaf in self.partition.leaves())

    def leaf_info(self, leaf: int) -> LeafInfo:
        """Bounds, depth, Q-bar values and visit counts of one leaf (a ValueError naming
        ``leaf`` unless it is the id of a current leaf: an internal node's id, or -1, which
        Python's indexing would read as the last node, is not one)."""
        if (
            isinstance(leaf, bool)
            or not isinstance(leaf, int | np.integer)
            or not self.partition.is_leaf(int(leaf))
        ):
            raise ValueError(
                f"leaf_info: {leaf!r} is not the id of a current leaf (ids of the "
                f"{self.partition.n_leaves} leaves: agent.partition.leaves())"
            )
        leaf = int(leaf)
        low, high = self.partition.leaf_bounds(leaf)
        return LeafInfo(
            leaf=leaf,
            depth=self.partition.leaf_depth(leaf),
            low=tuple(low),
            high=tuple(high),
            q_values=tuple(self.q[leaf]),
            visits=tuple(self.visits[leaf]),
            epsilon=self.exploration.epsilon(leaf),
            greedy=greedy_among(self.q[leaf], self._supported([self], [leaf])),
        )

    def leaves(self) -> list[LeafInfo]:
        """:meth:`leaf_info` of every leaf, by id."""
        return [self.leaf_info(leaf) for leaf in self.partition.leaves()]

    def render(self) -> str:
        """Text rendering of the partition with each leaf's box, Q-bar and counts."""
        return render_partition(self)

    def save(self, path: str | PathLike[str], policy_only: bool = False) -> Path:
        """Write the agent to ``path`` (``.npz`` of arrays + JSON metadata; never pickle) and
        return the path written (``.npz`` is added if missing).

        ``policy_only`` leaves out what only continued learning needs, the leaves' error
        buffers (most of a grown tree's file): that file acts exactly like the full one, but
        training continued from it starts with empty buffers.
        """
        from agent import serialization
        from agent.exploration import exploration_spec

        if not isinstance(policy_only, bool):
            raise ValueError(f"save: policy_only must be True or False, got {policy_only!r}")

        partition_arrays, partition_meta = self.partition.to_arrays()
        if policy_only:
            partition_arrays = {
                k: v for k, v in partition_arrays.items() if k not in serialization.LEARNING_ARRAYS
            }
        metadata: dict[str, Any] = {
            "format": serialization.FORMAT,
            "version": serialization.VERSION,
            "kind": self.kind,
            "config": self.config.to_dict(),
            "observation_space": serialization.space_to_json(self.observation_space),
            "n_actions": self.n_actions,
            "bounds": [list(self.bounds[0]), list(self.bounds[1])],
            "seed": self.seed,
            "episodes_done": self.episodes_done,
            "exploration": exploration_spec(self.exploration),
            "rng": self.uniform.state(),
            "partition": partition_meta,
        }
        if self.tie_trial is not None:  # predict reads it: kept in a policy-only file too
            metadata["tie_trial"] = self.tie_trial.state()
        if policy_only:
            metadata["policy_only"] = True
        else:
            learner: dict[str, Any] = {}
            if self._track_scale:
                learner["scale"] = self.scale.state()
            if self.model is not None:
                learner["model"] = self.model.state()
            terminals = getattr(self.partition, "terminals", None)
            if terminals is not None:
                learner["gate"] = {"terminals": terminals}
            optimism = getattr(self, "optimism", None)  # TreeConfig.optimistic_untried
            if optimism is not None:
                learner["optimism"] = optimism.state()
            seen = getattr(self, "terminals_seen", None)
            if seen is not None:
                learner["loop"] = {
                    "terminals": seen,
                    "crossing_steps": getattr(self, "crossing_steps", 0),
                    "crossings": getattr(self, "crossings", 0),
                    "terminal_reward_sum": getattr(self, "terminal_reward_sum", 0.0),
                    "target_sum": getattr(self, "target_sum", 0.0),
                    "targets": getattr(self, "targets", 0),
                    "last_truncated": getattr(self, "last_truncated", False),
                    "failure_discount": getattr(self, "failure_discount", False),
                    "terminal_reward_max": getattr(self, "terminal_reward_max", None),
                }
                if self.config.model_lambda_episodes is not None and hasattr(self, "blend_state"):
                    learner["loop"]["blended"] = self.blend_state()
            if learner:
                metadata["learner"] = learner
        arrays: dict[str, Any] = {
            "q": np.asarray(self.q, dtype=np.float64),
            "visits": np.asarray(self.visits, dtype=np.int64),
            **{f"partition.{k}": v for k, v in partition_arrays.items()},
        }
        if policy_only and self.config.greedy_reads_support:  # the model is left out
            support = [self.support(leaf) for leaf in range(len(self.q))]
            arrays["support"] = np.asarray(support, dtype=np.int64).reshape(len(self.q), -1)
        if policy_only and self.config.greedy_tie_errors is not None:
            errors = [self.action_errors(leaf) for leaf in range(len(self.q))]
            arrays["errors"] = np.asarray(errors, dtype=np.float64).reshape(len(self.q), -1)
        if policy_only and self.config.greedy_smoothing_links:
            pairs = set(self.saved_links or ())
            if self.model is not None:
                pairs.update(self.model.links())
            arrays["links"] = np.asarray(sorted(pairs), dtype=np.int64).reshape(-1, 2)
        return serialization.write_agent_file(path, metadata, arrays)

    @classmethod
    def load(cls, path: str | PathLike[str]) -> Self:
        """Read an agent written by :meth:`save` (either file); it acts, and from the full file
        continues learning, identically. A file that fails any check
        (``agent.serialization.read_agent_file``) is a ``ValueError`` naming it and the defect.
        """
        from agent import serialization

        saved = serialization.read_agent_file(path)
        kinds: dict[str, type[SMDPAgent]] = {}
        pending: list[type[SMDPAgent]] = [SMDPAgent]
        while pending:  # every agent class registers itself by subclassing, under its kind
            agent_class = pending.pop()
            kinds.setdefault(agent_class.kind, agent_class)
            pending += agent_class.__subclasses__()
        found = kinds.get(saved.kind)
        config = saved.config
        if config.loop_options():  # their class (agent.tree_ensemble), found without importing it
            seen: list[type[SMDPAgent]] = [SMDPAgent]
            while seen:
                agent_class = seen.pop()
                if vars(agent_class).get("runs_loop_options", False):
                    found = agent_class
                seen += agent_class.__subclasses__()
        if found is None or found is SMDPAgent:
            raise saved.fail(f"unknown agent kind {saved.kind!r}")
        if not issubclass(found, cls):
            raise ValueError(f"{saved.path} holds a {found.__name__}, not a {cls.__name__}")
        return found.from_state(saved)

    @classmethod
    def from_state(cls, saved: SavedAgent) -> Self:
        """The agent of a verified file. A subclass's extra constructor arguments (a grid's
        ``resolution``) are read from the partition's metadata under the same names."""
        import inspect

        from agent import serialization

        strategy = serialization.exploration_from_data(
            saved.exploration_name, saved.exploration_params, f"{saved.path}: metadata exploration"
        )
        own = set(inspect.signature(SMDPAgent.__init__).parameters)
        extra = {
            name: saved.partition[name]
            for name in inspect.signature(cls.__init__).parameters
            if name not in own
        }
        try:
            agent = cls(
                saved.observation_space,
                saved.action_space,
                strategy,
                saved.seed,
                saved.config,
                saved.bounds,
                **extra,
            )
            if saved.partition_arrays:
                restore = type(agent.partition).from_arrays  # type: ignore[attr-defined]
                agent.partition = restore(
                    saved.partition_arrays, saved.partition, saved.config, agent.integer_inputs
                )
                if agent._track_scale and hasattr(agent.partition, "scale"):
                    agent.partition.scale = agent.scale
            strategy.load_state_dict(saved.exploration_state)
            agent.uniform.restore(saved.rng)
            if (agent.tie_trial is None) != (saved.tie_trial is None):
                raise ValueError(
                    "metadata tie_trial must be present exactly when config.greedy_tie_trial "
                    f"is set (greedy_tie_trial = {saved.config.greedy_tie_trial!r})"
                )
            if agent.tie_trial is not None:
                agent.tie_trial.restore(saved.tie_trial, "metadata tie_trial")
            learner = saved.learner or {}
            if "scale" in learner:
                agent.scale.restore(learner["scale"])
            if "model" in learner and agent.model is not None:
                agent.model = LeafModel.from_state(
                    agent.n_actions,
                    learner["model"],
                    agent.q_init,
                    dims=len(agent.bounds[0]),
                    leaves=set(agent.partition.leaves()),
                )
            if "optimism" in learner:
                if not agent.config.optimistic_untried:
                    raise ValueError("an optimism state, but optimistic_untried is off")
                setattr(  # noqa: B010 (a TreeAgent)
                    agent,
                    "optimism",
                    UntriedOptimism.from_state(
                        agent.n_actions, learner["optimism"], set(agent.partition.leaves())
                    ),
                )
            if "gate" in learner and hasattr(agent.partition, "terminals"):
                terminals = learner["gate"].get("terminals")
                if isinstance(terminals, bool) or not isinstance(terminals, int) or terminals < 0:
                    raise ValueError(f"learner gate terminals {terminals!r} is not an int >= 0")
                setattr(agent.partition, "terminals", terminals)  # noqa: B010 (a gated tree)
            if "loop" in learner and hasattr(agent, "terminals_seen"):
                seen = learner["loop"].get("terminals")
                if isinstance(seen, bool) or not isinstance(seen, int) or seen < 0:
                    raise ValueError(f"learner loop terminals {seen!r} is not an int >= 0")
                setattr(agent, "terminals_seen", seen)  # noqa: B010 (TreeEnsembleAgent)
                for name in ("crossing_steps", "crossings", "targets"):  # older files: 0
                    count = learner["loop"].get(name, 0)
                    if isinstance(count, bool) or not isinstance(count, int) or count < 0:
                        raise ValueError(f"learner loop {name} {count!r} is not an int >= 0")
                    setattr(agent, name, count)
                for name in ("terminal_reward_sum", "target_sum"):  # older files: 0
                    total = learner["loop"].get(name, 0.0)
                    if isinstance(total, bool) or not isinstance(total, int | float):
                        raise ValueError(f"learner loop {name} {total!r} is not a number")
                    if not math.isfinite(total):
                        raise ValueError(f"learner loop {name} {total!r} is not finite")
                    setattr(agent, name, float(total))
                cut = learner["loop"].get("last_truncated", False)  # older files: False
                if not isinstance(cut, bool):
                    raise ValueError(f"learner loop last_truncated {cut!r} is not a bool")
                setattr(agent, "last_truncated", cut)  # noqa: B010
                latched = learner["loop"].get("failure_discount", False)  # older files: False
                if not isinstance(latched, bool):
                    raise ValueError(f"learner loop failure_discount {latched!r} is not a bool")
                setattr(agent, "failure_discount", latched)  # noqa: B010
                top = learner["loop"].get("terminal_reward_max")  # older files: None ("mean")
                if top is not None:
                    where = "learner loop terminal_reward_max"
                    if isinstance(top, bool) or not isinstance(top, int | float):
                        raise ValueError(f"{where} {top!r} is not a number")
                    if not math.isfinite(top):
                        raise ValueError(f"{where} {top!r} is not finite")
                    top = float(top)
                setattr(agent, "terminal_reward_max", top)  # noqa: B010
                if "blended" in learner["loop"]:  # TreeConfig.model_lambda_episodes
                    load_blends = getattr(agent, "load_blend_state", None)
                    if load_blends is None:
                        raise ValueError(f"a {type(agent).__name__} holds no blended epochs")
                    load_blends(learner["loop"]["blended"])
        except (
            TypeError,
            ValueError,
            KeyError,
            IndexError,
            AttributeError,
            OverflowError,
        ) as error:
            raise saved.fail(f"cannot be restored ({type(error).__name__}: {error})") from None
        if agent.partition.n_ids != len(saved.q):
            raise saved.fail("the partition's metadata does not match its arrays")
        serialization.check_exploration_state(
            strategy, agent.partition.leaves(), f"{saved.path}: metadata exploration"
        )
        agent.q = saved.q.tolist()
        agent.visits = saved.visits.tolist()
        if saved.support is not None:
            agent.saved_support = saved.support.tolist()
        if saved.errors is not None:
            agent.saved_errors = saved.errors.tolist()
        if saved.links is not None:
            agent.saved_links = {(int(a), int(b)) for a, b in saved.links.tolist()}
        agent.episodes_done = saved.episodes_done
        return agent

    def __repr__(self) -> str:
        return (
            f"{type(self).__name__}(leaves={self.n_leaves}, actions={self.n_actions}, "
            f"exploration={self.exploration!r}, seed={self.seed})"
        )
