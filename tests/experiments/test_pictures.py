"""The partition figure and the GIF, drawn from a real tree agent with hand-made leaves."""

from __future__ import annotations

from pathlib import Path

import gymnasium
import numpy as np
import pytest

import agent as agent_module
from bullet_maze import layout as layout_module
from experiments.partition import greedy_actions, partition_figure

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
DIRECTIONS = np.array([(0.0, 1.0), (0.0, -1.0), (-1.0, 0.0), (1.0, 0.0)])


@pytest.fixture
def split_agent():
    """A tree agent over the 300 x 300 arena split by hand into three leaves with set values."""
    space = gymnasium.spaces.Box(np.zeros(2, np.float32), np.full(2, 300, np.float32))
    agent = agent_module.TreeAgent(space, gymnasium.spaces.Discrete(4), seed=0)
    left, right = agent.split_leaf(0, 0, 150.0)
    low, high = agent.split_leaf(right, 1, 100.0)
    agent.q[left] = [1.0, 0.0, 0.0, 0.0]  # up
    agent.q[low] = [0.0, 0.0, 0.0, 2.0]  # right
    agent.q[high] = [0.0] * 4  # nothing learned
    return agent, (left, low, high)


def test_greedy_actions_of_leaves(split_agent):
    agent, (left, low, high) = split_agent
    leaves = {info.leaf: info for info in agent.leaves()}
    actions = greedy_actions([leaves[left], leaves[low], leaves[high]])
    assert actions.tolist() == [0, 3, -1]


def test_partition_figure_is_a_png(split_agent, tmp_path: Path):
    agent, _ = split_agent
    layout = layout_module.load_layout("paper")
    track = np.array([[150.0, 30.0], [150.0, 35.0], [155.0, 35.0]])
    path = partition_figure(agent, layout, DIRECTIONS, tmp_path / "partition.png", trajectory=track)
    data = path.read_bytes()
    assert data[:8] == PNG_SIGNATURE
    assert len(data) > 10_000


def test_gif_has_one_frame_per_sampled_step(split_agent, tmp_path: Path):
    import imageio.v3 as iio

    from experiments.animation import frame_indices, render_gif

    agent, _ = split_agent
    layout = layout_module.load_layout("paper")
    positions = np.column_stack([np.full(41, 150.0), np.linspace(30, 230, 41)])
    path = render_gif(agent, layout, DIRECTIONS, positions, tmp_path / "episode.gif", max_frames=12)
    frames = iio.imread(path, index=None)
    assert path.read_bytes()[:6] == b"GIF89a"
    assert frames.shape[0] == 12
    assert frames.shape[-1] in (3, 4)
    assert not np.array_equal(frames[0], frames[-1])
    assert frame_indices(40, 12)[[0, -1]].tolist() == [0, 40]
    assert frame_indices(5, 100).tolist() == [0, 1, 2, 3, 4, 5]
