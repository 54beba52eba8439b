"""The paper's learner: SMDP Q-learning over an adaptive decision tree (section IV)."""

from __future__ import annotations

from agent.learner import SMDPAgent
from agent.partition_tree import GatedPartitionTree, PartitionTree


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

    def _make_partition(self, low: list[float], high: list[float]) -> PartitionTree:
        if self.config.leaves_per_terminal > 0:
            return GatedPartitionTree(low, high, self.config)
        return PartitionTree(low, high, self.config)

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
        (``TreeConfig.model_bonus_terminals``)."""
        if terminated and type(self.partition) is GatedPartitionTree:
            self.partition.terminals += 1
        split = super()._end_epoch(leaf, action, xs, rs, bootstrap, end_x, terminated)
        if terminated:
            self._after_terminal_epoch()
        return split

    @property
    def depth(self) -> int:
        return self.partition.depth

    def split_leaf(self, leaf: int, dim: int, value: float) -> tuple[int, int]:
        """Split ``leaf`` at ``x[dim] = value`` by hand (the children get Q-bar as in a learned
        split); returns the children's ids. For tests, benchmarks and hand-made initial trees.
        """
        children = self.partition.split(leaf, dim, value)
        self._grow(leaf, children)
        return children
