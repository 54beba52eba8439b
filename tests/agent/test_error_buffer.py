"""The bounded state-error buffer: capacity, FIFO order, running mean and variance."""

from __future__ import annotations

import numpy as np
import pytest

from agent.error_buffer import ErrorBuffer


def test_fills_then_overwrites_oldest() -> None:
    buf = ErrorBuffer(2, 3)
    buf.add([[0.0, 1.0], [2.0, 3.0]], [1.0, 2.0])
    assert buf.count == 2
    buf.add([[4.0, 5.0], [6.0, 7.0]], [3.0, 4.0])
    inputs, errors = buf.arrays()
    assert buf.count == 3
    np.testing.assert_array_equal(inputs, [[2.0, 3.0], [4.0, 5.0], [6.0, 7.0]])
    np.testing.assert_array_equal(errors, [2.0, 3.0, 4.0])
    assert buf.mean_variance() == pytest.approx((3.0, 2.0 / 3.0))


def test_running_moments_match_numpy_after_many_wraps() -> None:
    rng = np.random.default_rng(0)
    buf = ErrorBuffer(1, 50)
    values = rng.normal(0.3, 2.0, 1237)
    for chunk in np.array_split(values, 400):
        buf.add([[v] for v in chunk.tolist()], chunk.tolist())
    mean, var = buf.mean_variance()
    assert mean == pytest.approx(values[-50:].mean())
    assert var == pytest.approx(values[-50:].var())


def test_clear_and_restore() -> None:
    buf = ErrorBuffer(1, 4)
    buf.add([[1.0], [2.0]], [0.5, -0.5])
    copy = ErrorBuffer.restore(1, 4, *buf.state())
    assert copy.arrays()[1].tolist() == [0.5, -0.5]
    buf.clear()
    assert buf.count == 0
    assert buf.mean_variance() == (0.0, 0.0)
