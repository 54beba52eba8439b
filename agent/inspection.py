"""Looking inside a trained agent: per-leaf records and a text rendering of the partition."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol


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
    greedy: int
    """The action ``predict`` chooses in this leaf (eq. (11), lowest index among ties; with
    ``TreeConfig.greedy_min_epochs`` only the actions with stored epochs compete)."""


class _Partition(Protocol):
    def render_lines(self, describe_leaf: Callable[[int], str]) -> list[str]: ...


class Inspectable(Protocol):
    """What the functions here read: an agent's leaves and partition (``SMDPAgent`` is one).

    A protocol rather than the learner's class, so that this module does not import the
    learner that uses it.
    """

    @property
    def partition(self) -> _Partition: ...

    def leaf_info(self, leaf: int) -> LeafInfo: ...


def describe_leaf(agent: Inspectable, leaf: int) -> str:
    """One line: id, box, Q-bar, counts and epsilon of a leaf."""
    info = agent.leaf_info(leaf)
    box = " x ".join(f"[{lo:.4g}, {hi:.4g})" for lo, hi in zip(info.low, info.high, strict=True))
    q = ", ".join(f"{v:.3f}" for v in info.q_values)
    return f"leaf {leaf} {box} Q=[{q}] n={list(info.visits)} eps={info.epsilon:.3f}"


def render_partition(agent: Inspectable) -> str:
    """Text rendering of the whole partition, one node per line, indented by depth."""
    return "\n".join(agent.partition.render_lines(lambda leaf: describe_leaf(agent, leaf)))
