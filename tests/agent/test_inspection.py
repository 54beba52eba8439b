"""Depth, leaf count, per-leaf bounds, Q values, counts and the text rendering."""

from __future__ import annotations

import math

import numpy as np
import pytest
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


@pytest.mark.parametrize("node", [-1, 0, 2, 5, 10**6, True, "1", 1.0, None])
def test_leaf_info_refuses_what_is_not_a_current_leaf(node: object) -> None:
    """-1 used to give the last node's box (Python's indexing), an internal node's id that
    node's box, as if they were leaves."""
    agent = TreeAgent(BOX, spaces.Discrete(3), "greedy")
    _, right = agent.split_leaf(0, 0, 1.0)
    agent.split_leaf(right, 1, 3.0)  # nodes: 0 and 2 internal; leaves 1, 3, 4
    with pytest.raises(ValueError, match=r"leaf_info: .* is not the id of a current leaf"):
        agent.leaf_info(node)  # type: ignore[arg-type]
    assert agent.leaf_info(np.int64(3)).leaf == 3


@pytest.mark.parametrize("cell", [-1, 8, True])
def test_grid_leaf_info_refuses_ids_outside_the_grid(cell: object) -> None:
    agent = GridAgent(BOX, spaces.Discrete(2), "greedy", resolution=(2, 4))
    with pytest.raises(ValueError, match="is not the id of a current leaf"):
        agent.leaf_info(cell)  # type: ignore[arg-type]


def test_save_refuses_a_policy_only_that_is_not_a_bool(tmp_path) -> None:
    agent = TreeAgent(BOX, spaces.Discrete(3), "greedy")
    with pytest.raises(ValueError, match="policy_only must be True or False, got 'yes'"):
        agent.save(tmp_path / "a.npz", policy_only="yes")  # type: ignore[arg-type]
    assert not (tmp_path / "a.npz").exists()


@pytest.mark.parametrize("resolution", [True, 2.5, None, "44", [2, True], [2, 3.0], [2]])
def test_a_grid_resolution_that_is_not_whole_cell_counts_is_refused(resolution: object) -> None:
    """``True`` and ``[2, True]`` used to give one-cell dimensions, ``[2, 3.0]`` was rounded,
    and ``2.5`` or ``None`` failed with "object is not iterable"."""
    with pytest.raises(ValueError, match="resolution must be a positive int or 2 positive ints"):
        GridAgent(BOX, spaces.Discrete(2), "greedy", resolution=resolution)  # type: ignore[arg-type]
    assert GridAgent(BOX, spaces.Discrete(2), "greedy", resolution=np.array([2, 3])).n_leaves == 6
