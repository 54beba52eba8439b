"""Depth, leaf count, per-leaf bounds, Q values, counts and the text rendering."""

from __future__ import annotations

import math

import numpy as np
from gymnasium import spaces

from agent import GridAgent, TreeAgent

BOX = spaces.Box(0.0, 4.0, shape=(2,), dtype=np.float64)


def test_tree_inspection() -> None:
    agent = TreeAgent(BOX, spaces.Discrete(3), "greedy")
    assert (agent.depth, agent.n_leaves) == (0, 1)
    left, right = agent.split_leaf(0, 0, 1.0)
    agent.q[right] = [0.5, -1.0, 2.0]
    a, b = agent.split_leaf(right, 1, 3.0)
    assert agent.q[b] == [0.5, -1.0, 2.0]  # children inherit Q-bar
    assert (agent.depth, agent.n_leaves) == (2, 3)
    infos = agent.leaves()
    assert [i.leaf for i in infos] == [left, a, b]
    assert infos[1].low == (1.0, 0.0)
    assert infos[1].high == (4.0, 3.0)
    assert infos[2].q_values == (0.5, -1.0, 2.0)
    assert infos[2].visits == (0, 0, 0)
    volume = sum(math.prod(h - lo for lo, h in zip(i.low, i.high, strict=True)) for i in infos)
    assert volume == 16.0
    assert agent.predict([3.0, 3.5]) == 2
    text = agent.render()
    assert text.splitlines()[0] == "node 0: split x[0] at 1"
    assert "x[1] >= 3: leaf 4 [1, 4) x [3, 4) Q=[0.500, -1.000, 2.000]" in text
    assert len(text.splitlines()) == 5


def test_grid_inspection() -> None:
    agent = GridAgent(BOX, spaces.Discrete(2), "greedy", resolution=(2, 4))
    assert agent.n_leaves == 8
    assert agent.leaf_of([3.9, 0.1]) == 4
    assert agent.leaf_info(4).low == (2.0, 0.0)
    assert agent.leaf_info(4).high == (4.0, 1.0)
    assert agent.leaf_of([-5.0, 9.0]) == 3  # outside the box: the nearest edge cell
    assert agent.render().startswith("uniform grid 2 x 4")
