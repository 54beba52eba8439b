"""The paper's learner: SMDP Q-learning over an adaptive decision tree (section IV)."""

from __future__ import annotations

import numpy as np

from agent.collision_split import choose_collided_only_split, choose_collision_split
from agent.learner import SMDPAgent
from agent.optimism import UntriedOptimism
from agent.partition_tree import GatedPartitionTree, PartitionTree
from agent.smdp import epoch_returns


class TreeAgent(SMDPAgent):
    """Adaptive decision-tree agent of Hwang, Li and Jiang (section IV).

    Example::

        agent = TreeAgent(env.observation_space, env.action_space, "adaptive+tabu", seed=0)
        history = agent.learn(env, episodes=100, reset_seed=0)
        action = agent.predict(obs)
    """

    kind = "tree"
    accepts_unbounded = True
    partition: PartitionTree
    collision_end: list[float] | None = None
    """``TreeConfig.collision_splits``: the input at which the epochs ending now end, when
    their last step collided (the loop sets it; None otherwise). An epoch whose ``end_x`` is
    this very list ended on the collision; the earlier stretches of a held run do not."""

    optimism: UntriedOptimism | None = None
    """``TreeConfig.optimistic_untried``: the untried actions and their bound (made with the
    first epoch, so that it sees the tree's initial leaves; None while off)."""

    def _make_partition(self, low: list[float], high: list[float]) -> PartitionTree:
        if self.config.leaves_per_terminal > 0:
            return GatedPartitionTree(low, high, self.config, self.integer_inputs)
        return PartitionTree(low, high, self.config, self.integer_inputs)

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
        """:meth:`SMDPAgent._end_epoch`; a terminal epoch first grows a gated tree's leaf
        budget (``TreeConfig.leaves_per_terminal``) and afterwards may end the model's bonus
        (``TreeConfig.model_bonus_terminals``); an epoch that ended on a collision is marked in
        the model and may cut its leaf (``TreeConfig.collision_splits``)."""
        if terminated and type(self.partition) is GatedPartitionTree:
            self.partition.terminals += 1
        if self.config.optimistic_untried:
            self._pay(leaf, action, rs)
        split = super()._end_epoch(leaf, action, xs, rs, bootstrap, end_x, terminated)
        if terminated:
            self._after_terminal_epoch()
        if end_x is not None and end_x is self.collision_end and self.model is not None:
            first = self.model.last_added  # the epoch just stored
            held = self.partition.leaf_of(first)  # the epoch's leaf, or the child holding it
            self.model.mark_collided(held, action, first)
            if not split:
                split = self._collision_split(leaf, action)
        return split

    def _pay(self, leaf: int, action: int, rs: list[float]) -> None:
        """``TreeConfig.optimistic_untried``: ``action`` is tried in ``leaf``, and the largest
        return the epoch's rewards paid may raise the untried actions' bound
        (:class:`agent.optimism.UntriedOptimism`)."""
        optimism = self.optimism
        if optimism is None:
            optimism = self.optimism = UntriedOptimism(
                self.n_actions, self.partition.leaves(), self.q_init
            )
        optimism.tried(leaf, action)
        moved = optimism.paid(max(epoch_returns(rs, 0.0, self.discount)), self.q)
        if self.model is not None:
            tolerance = self._in_units(self.config.sweep_tolerance)
            for moved_leaf, change in moved.items():
                if change > tolerance:
                    self.model.push(moved_leaf, change)

    def _grow(self, parent: int, children: tuple[int, int]) -> None:
        """:meth:`SMDPAgent._grow`; the children inherit the parent's untried actions
        (``TreeConfig.optimistic_untried``)."""
        super()._grow(parent, children)
        if self.optimism is not None:
            self.optimism.split(parent, children)

    def _collision_split(self, leaf: int, action: int) -> bool:
        """``TreeConfig.collision_splits``: cut ``leaf`` where the stored epochs of ``action``
        that ended on a collision and those that did not best separate
        (:func:`agent.collision_split.choose_collision_split`), or, with
        ``collision_splits_collided_only``, where all of them collided, off their part of the
        leaf (:func:`agent.collision_split.choose_collided_only_split`); returns whether it
        split."""
        partition = self.partition
        if not partition.may_split():
            return False
        firsts, collided = self.model.collisions(leaf, action)  # type: ignore[union-attr]
        low, high, _, min_width = partition.split_box(leaf)
        args = (np.asarray(firsts, dtype=np.float64), np.asarray(collided, dtype=np.bool_))
        choice = choose_collision_split(*args, low, high, min_width)
        if choice is None and self.config.collision_splits_collided_only:
            choice = choose_collided_only_split(*args, low, high, min_width)
        if choice is None:
            return False
        self._grow(leaf, partition.split_with_samples(leaf, *choice))
        return True

    @property
    def depth(self) -> int:
        return self.partition.depth

    def split_leaf(self, leaf: int, dim: int, value: float) -> tuple[int, int]:
        """Split ``leaf`` at ``x[dim] = value`` by hand (the children get Q-bar as in a learned
        split); returns the children's ids. For tests, benchmarks and hand-made initial trees.
        """
        children = self.partition.split(leaf, dim, value)
        self._grow(leaf, children)
        self.forget_greedy_cache()
        return children
