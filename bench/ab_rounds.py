"""Interleaved A/B rounds for the benches that time one change that must not change the run.

``ab_rounds(run, rounds)`` calls ``run(False, seed)`` then ``run(True, seed)`` for each seed in
``range(rounds)``; each call returns (CPU seconds, what the run ended with). The row gives the
median CPU of each side, the ratio with over without (median, with its range) and whether every
round's two runs ended the same.
"""

from __future__ import annotations

import statistics
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class ABRow:
    """The rounds of one case."""

    without: float
    """Median CPU seconds without the change."""
    with_change: float
    """Median CPU seconds with it."""
    ratios: tuple[float, ...]
    """With over without, per round."""
    same: bool
    """Every round's two runs ended the same."""

    def cells(self, digits: int = 2) -> str:
        """``without | with | ratio (median, range) | same`` for a Markdown row."""
        r = self.ratios
        return (
            f"{self.without:.2f} | {self.with_change:.2f} | {statistics.median(r):.{digits}f}x "
            f"({min(r):.{digits}f}-{max(r):.{digits}f}) | {'yes' if self.same else 'NO'}"
        )


def ab_rounds(run: Callable[[bool, int], tuple[float, Any]], rounds: int) -> ABRow:
    """``rounds`` interleaved rounds of ``run`` without and with the change."""
    without, with_change, ratios, same = [], [], [], True
    for seed in range(rounds):
        cpu_without, end_without = run(False, seed)
        cpu_with, end_with = run(True, seed)
        without.append(cpu_without)
        with_change.append(cpu_with)
        ratios.append(cpu_with / cpu_without)
        same = same and end_without == end_with
    return ABRow(statistics.median(without), statistics.median(with_change), tuple(ratios), same)
