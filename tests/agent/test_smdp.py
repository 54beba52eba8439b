"""Eqs. (9) and (10) against values computed by hand."""

from __future__ import annotations

import pytest

from agent.smdp import epoch_returns, leaf_update


def test_eq9_returns_by_hand() -> None:
    # gamma 0.9, V-bar(s') = 2: G2 = -1 + 0.9*2 = 0.8, G1 = -0.01 + 0.9*0.8, G0 = -0.01 + 0.9*0.71
    assert epoch_returns([-0.01, -0.01, -1.0], 2.0, 0.9) == pytest.approx([0.629, 0.71, 0.8])


def test_eq9_terminal_bootstrap_zero_and_single_step() -> None:
    assert epoch_returns([5.0], 0.0, 0.99) == [5.0]
    assert epoch_returns([0.0, 0.0], 1.0, 0.5) == pytest.approx([0.25, 0.5])


def test_eq10_update_and_errors_by_hand() -> None:
    # mean of the returns 0.713; (1 - 0.3) 0.5 + 0.3 0.713 = 0.5639
    new_q, errors = leaf_update(0.5, [0.629, 0.71, 0.8], 0.3)
    assert new_q == pytest.approx(0.5639)
    assert errors == pytest.approx([0.129, 0.21, 0.3])
    # the change is alpha times the mean error (the Delta-Q of eq. 5)
    assert new_q - 0.5 == pytest.approx(0.3 * sum(errors) / 3)
