"""Block-drawn uniforms: the same draws as the generator's, and a state that restores exactly."""

from __future__ import annotations

import numpy as np

from agent.random_stream import UniformStream


def test_draws_are_the_generators_in_order() -> None:
    stream = UniformStream(np.random.default_rng(5), block=7)
    expected = np.random.default_rng(5).random(7 * 3).tolist()
    assert [stream.random() for _ in range(21)] == expected


def test_state_round_trip_mid_block() -> None:
    stream = UniformStream(np.random.default_rng(1), block=16)
    for _ in range(5):
        stream.random()
    copy = UniformStream(np.random.default_rng(999))
    copy.restore(stream.state())
    assert [copy.random() for _ in range(40)] == [stream.random() for _ in range(40)]
