"""Baseline: the same SMDP learner over a fixed uniform grid (the paper's section I foil)."""

from __future__ import annotations

from collections.abc import Sequence

from gymnasium import spaces

from agent.config import TreeConfig
from agent.exploration import Exploration
from agent.learner import Bounds, SMDPAgent
from agent.uniform_grid import UniformGrid


class GridAgent(SMDPAgent):
    """Q-learning on ``resolution`` equal cells per dimension, with the tree agent's epochs and
    strategies, so that coarse, fine and adaptive partitions compare on equal terms.

    An epoch holds its action while the input stays in one cell (eqs. 9-10 over cells). The
    split fields of ``config`` (and ``table_cells``: the grid's cells are its resolution) are
    unused; ``optimistic_untried``, which the tree agents implement, and
    ``greedy_tie_ancestors``, which needs a tree, are refused.
    """

    kind = "grid"
    partition: UniformGrid

    def __init__(
        self,
        observation_space: spaces.Space,
        action_space: spaces.Space,
        exploration: str | Exploration = "adaptive+tabu",
        seed: int = 0,
        config: TreeConfig | None = None,
        bounds: Bounds | None = None,
        resolution: int | Sequence[int] = 20,
    ) -> None:
        self.resolution = resolution
        if config is not None and getattr(config, "optimistic_untried", False) is True:
            raise ValueError(
                "TreeConfig.optimistic_untried = True is implemented by the tree agents "
                "(agent.TreeAgent), not GridAgent"
            )
        if config is not None and getattr(config, "greedy_tie_ancestors", None) is not None:
            raise ValueError(
                f"TreeConfig.greedy_tie_ancestors = {config.greedy_tie_ancestors!r} needs the "
                "adaptive tree's ancestors (agent.TreeAgent); GridAgent's cells have none"
            )
        super().__init__(observation_space, action_space, exploration, seed, config, bounds)

    def _make_partition(self, low: list[float], high: list[float]) -> UniformGrid:
        return UniformGrid(low, high, self.resolution)

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
        """:meth:`SMDPAgent._end_epoch`; a terminal epoch may end the model's bonus
        (``TreeConfig.model_bonus_terminals``)."""
        split = super()._end_epoch(leaf, action, xs, rs, bootstrap, end_x, terminated)
        if terminated:
            self._after_terminal_epoch()
        return split
