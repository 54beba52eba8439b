"""The paper's learner: SMDP Q-learning over an adaptive decision tree (section IV)."""

from __future__ import annotations

from agent.learner import SMDPAgent
from agent.partition_tree import PartitionTree


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
        return PartitionTree(low, high, self.config)

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
