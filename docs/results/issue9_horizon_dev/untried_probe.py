"""A prototype, not an agent option: untried actions first (issue 9, after part 11; dev only).

On each decision the exploration strategy sees the leaf's Q-bar row with every action that has
no epoch in the model (``LeafModel.epochs``: none recorded or re-filed into this leaf) and a
Q-bar within ``DELTA`` units of the row's best raised by 10^6, so its greedy choice tries such an
action before the ones already tested. Greedy evaluation (``predict``) is not changed. The
agent's class is patched here, for the maze driver of part 8 (600 episodes, greedy probes
every 50)::

    PYTHONPATH=. python docs/results/issue9_horizon_dev/untried_probe.py \\
        "forest:seed=0" 2 untried01 0.1 docs/results/issue9_horizon_dev/untried.jsonl
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

from agent.tree_ensemble import TreeEnsembleAgent

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "issue9_hold_terminals_dev"))
import curves  # the part 8 maze driver, beside this folder


def patch(delta: float) -> None:
    """Wrap every new TreeEnsembleAgent's strategy choice as the module docstring says."""
    original_init = TreeEnsembleAgent.__init__

    def init(self: TreeEnsembleAgent, *args: Any, **kwargs: Any) -> None:
        original_init(self, *args, **kwargs)
        select = self.exploration.select
        n = self.n_actions

        def untried_first(leaf: int, row: list[float], rng: Any) -> int:
            model = self.model
            if model is None:
                return select(leaf, row, rng)
            floor = max(row) - self._in_units(delta)
            raised = [
                q + 1e6 if q >= floor and model.epochs.get(leaf * n + a, 0) == 0 else q
                for a, q in enumerate(row)
            ]
            return select(leaf, raised, rng)

        self.exploration.select = untried_first  # type: ignore[method-assign]

    TreeEnsembleAgent.__init__ = init  # type: ignore[method-assign]


if __name__ == "__main__":
    maze, seed, label, delta, out = sys.argv[1:6]
    patch(float(delta))
    curves.run(maze, int(seed), label, {}, Path(out))  # the label names the delta
