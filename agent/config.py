"""Every threshold of the learner in one dataclass; the defaults are the paper's Table I.

Hwang, Li and Jiang, "Adaptive Exploration Strategies for Reinforcement Learning": section IV
(eqs. 6-13) and Table I. Where the paper is silent the default is the reading documented in
``docs/paper-notes.md``; every alternative reading is a field here.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any, Literal

ErrorBuffer = Literal["clear", "window"]
RangeNormalization = Literal["root", "none"]
SplitPointRule = Literal["quest", "midpoint"]


@dataclass(frozen=True)
class TreeConfig:
    """Learning, epoch and split parameters of the adaptive decision tree (section IV)."""

    alpha: float = 0.3
    """Learning rate of eq. (10) (Table I: 0.3)."""
    gamma: float = 0.99
    """Discount rate of eqs. (6), (7), (9) (Table I: 0.99)."""
    q_init: float = 0.0
    """Initial Q-bar of every (leaf, action) of a fresh partition (not given by the paper)."""
    max_epoch_steps: int | None = 50
    """An epoch (section IV.A) ends after this many steps; None holds it until the leaf changes."""
    hold_exploration: bool = True
    """An exploratory (random) action is held across leaf boundaries until a collision, the end
    of the episode or ``max_epoch_steps``; learning still sees one epoch per leaf crossed.
    Not in the paper (False is the literal reading): without it the robot chatters across leaf
    boundaries and most seeds never learn (docs/paper-notes.md, "Held exploration")."""
    end_epoch_on_collision: bool = True
    """An epoch also ends when the env reports a collision (``info[collision_key]``)."""
    collision_key: str = "collision"
    """Key of the env's ``info`` dict that reports a collision (counted in EpisodeStats)."""
    split_min_samples: int = 500
    """Split condition 1, N_th: state-error pairs a leaf must hold before it is tested (Table I)."""
    split_max_abs_mean: float = 0.5
    """Split condition 2, mu_th: split only if |mean error| < this (Table I: threshold mean)."""
    split_min_variance: float = 0.03
    """Split condition 3, sigma_th^2: split only if the error variance > this (Table I)."""
    error_buffer: ErrorBuffer = "clear"
    """State-error pairs per leaf: "clear" (emptied after each split test) or "window" (FIFO)."""
    range_normalization: RangeNormalization = "root"
    """range_i of eq. (12): the leaf's width divided by the root's ("root") or raw ("none")."""
    split_point: SplitPointRule = "quest"
    """Eq. (13): where the count-weighted group densities cross ("quest", Loh and Shih 1997,
    the midpoint of the group means when they do not cross between them) or always the
    midpoint of the two group means ("midpoint")."""
    inherit_q: bool = True
    """Children of a split start with the parent's Q-bar (else with q_init)."""
    reset_counts_on_split: bool = True
    """Children's visit counts restart at 0 (else they copy the parent's)."""
    children_inherit_samples: bool = True
    """A split divides the parent's stored state-error pairs between the children (else dropped)."""
    min_leaf_fraction: float = 1.0 / 256.0
    """No leaf narrower than this fraction of the root's width in the split dimension (a guard)."""
    max_leaves: int = 4096
    """The tree stops splitting at this many leaves, which bounds memory (a guard)."""

    def __post_init__(self) -> None:
        _check_range("alpha", self.alpha, 0.0, 1.0, low_open=True)
        _check_range("gamma", self.gamma, 0.0, 1.0)
        if not math.isfinite(self.q_init):
            raise ValueError(f"TreeConfig.q_init must be finite, got {self.q_init!r}")
        if self.max_epoch_steps is not None and (
            not isinstance(self.max_epoch_steps, int) or self.max_epoch_steps < 1
        ):
            raise ValueError(
                f"TreeConfig.max_epoch_steps must be a positive int or None, "
                f"got {self.max_epoch_steps!r}"
            )
        if not isinstance(self.split_min_samples, int) or self.split_min_samples < 2:
            raise ValueError(
                f"TreeConfig.split_min_samples must be an int >= 2, got {self.split_min_samples!r}"
            )
        for name in ("split_max_abs_mean", "split_min_variance"):
            value = getattr(self, name)
            if not value >= 0.0:  # also rejects NaN
                raise ValueError(f"TreeConfig.{name} must be >= 0, got {value!r}")
        _check_choice("error_buffer", self.error_buffer, ("clear", "window"))
        _check_choice("range_normalization", self.range_normalization, ("root", "none"))
        _check_choice("split_point", self.split_point, ("quest", "midpoint"))
        _check_range("min_leaf_fraction", self.min_leaf_fraction, 0.0, 0.5, low_open=True)
        if not isinstance(self.max_leaves, int) or self.max_leaves < 1:
            raise ValueError(f"TreeConfig.max_leaves must be an int >= 1, got {self.max_leaves!r}")

    def to_dict(self) -> dict[str, Any]:
        """The fields as a JSON-ready dict."""
        return dataclasses.asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> TreeConfig:
        """Rebuild from :meth:`to_dict`; unknown keys raise a ValueError naming them."""
        known = {f.name for f in dataclasses.fields(cls)}
        unknown = sorted(set(data) - known)
        if unknown:
            raise ValueError(f"unknown TreeConfig fields {unknown}; known: {sorted(known)}")
        return cls(**data)


def _check_range(
    name: str, value: float, low: float, high: float, *, low_open: bool = False
) -> None:
    ok = (low < value if low_open else low <= value) and value <= high
    if not ok:
        bracket = "(" if low_open else "["
        raise ValueError(f"TreeConfig.{name} must be in {bracket}{low}, {high}], got {value!r}")


def _check_choice(name: str, value: str, choices: tuple[str, ...]) -> None:
    if value not in choices:
        raise ValueError(f"TreeConfig.{name} must be one of {list(choices)}, got {value!r}")
