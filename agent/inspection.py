"""Looking inside a trained agent: per-leaf records and a text rendering of the partition."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from agent.learner import SMDPAgent


@dataclass(frozen=True)
class LeafInfo:
    """One leaf of the partition."""

    leaf: int
    """Leaf id (stable until the leaf splits)."""
    depth: int
    """Depth in the tree (0 for the root; 0 for grid cells)."""
    low: tuple[float, ...]
    """Lower corner of the leaf's box."""
    high: tuple[float, ...]
    """Upper corner of the leaf's box."""
    q_values: tuple[float, ...]
    """Q-bar(leaf, a) for every action."""
    visits: tuple[int, ...]
    """Epochs that held each action in this leaf (since the leaf was made, by default)."""
    epsilon: float
    """The exploration strategy's epsilon in this leaf."""


def describe_leaf(agent: SMDPAgent, leaf: int) -> str:
    """One line: id, box, Q-bar, counts and epsilon of a leaf."""
    info = agent.leaf_info(leaf)
    box = " x ".join(f"[{lo:.4g}, {hi:.4g})" for lo, hi in zip(info.low, info.high, strict=True))
    q = ", ".join(f"{v:.3f}" for v in info.q_values)
    return f"leaf {leaf} {box} Q=[{q}] n={list(info.visits)} eps={info.epsilon:.3f}"


def render_partition(agent: SMDPAgent) -> str:
    """Text rendering of the whole partition, one node per line, indented by depth."""
    return "\n".join(agent.partition.render_lines(lambda leaf: describe_leaf(agent, leaf)))
