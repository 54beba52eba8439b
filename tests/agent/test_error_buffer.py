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


def test_storage_grows_with_the_pairs_until_the_ring_wraps() -> None:
    buf = ErrorBuffer(3, 10)
    assert (len(buf.inputs), len(buf.errors)) == (0, 0)  # nothing held, nothing allocated
    buf.add([[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]], [0.5, -0.5])
    assert (len(buf.inputs), len(buf.errors)) == (6, 2)
    inputs, errors = buf.arrays()
    np.testing.assert_array_equal(inputs, [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]])
    np.testing.assert_array_equal(errors, [0.5, -0.5])
    buf.add([[float(i)] * 3 for i in range(8)], [float(i) for i in range(8)])  # reaches 10
    assert (len(buf.inputs), len(buf.errors)) == (30, 10)  # full size once the ring turns


def test_a_grown_buffer_holds_and_saves_what_a_full_size_one_does() -> None:
    rng = np.random.default_rng(3)
    for capacity in (1, 2, 7, 50):
        grown, full = ErrorBuffer(2, capacity), ErrorBuffer(2, capacity)
        full.allocate()
        for step in range(40):
            n = int(rng.integers(1, 9))
            xs, deltas = rng.normal(size=(n, 2)).tolist(), rng.normal(size=n).tolist()
            grown.add(xs, deltas)
            full.add(xs, deltas)
            if step % 13 == 12:
                grown.clear()
                full.clear()
            for a, b in zip(grown.arrays(), full.arrays(), strict=True):
                np.testing.assert_array_equal(a, b)
            assert grown.mean_variance() == full.mean_variance()
            saved, saved_full = grown.state(), full.state()
            np.testing.assert_array_equal(saved[0], saved_full[0])  # zeros where unwritten
            np.testing.assert_array_equal(saved[1], saved_full[1])
            assert saved[2] == saved_full[2]
            assert saved[0].shape == (2 * capacity,)
