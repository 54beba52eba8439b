"""TreeConfig.novelty_cells: epochs that end in an unseen cell bootstrap from q_init until the
first terminals (agent/novelty.py)."""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from agent import TreeAgent, TreeConfig, preset
from agent.leaf_model import LeafModel
from agent.novelty import NoveltyGrid, cells_per_dimension
from agent.tree_ensemble import tree_agent_class

SWEEP = TreeConfig(planning="sweep", split_min_samples=10**6)


def test_the_cell_of_an_input_by_hand() -> None:
    grid = NoveltyGrid([0.0, 0.0], [10.0, 1.0], 5)  # cells 2.0 wide and 0.2 high
    assert grid.cell([0.0, 0.0]) == (0, 0)
    assert grid.cell([3.9, 0.41]) == (1, 2)
    assert grid.cell([10.0, 1.0]) == (4, 4)  # the upper bound is in the last cell
    assert grid.cell([-3.0, 7.0]) == (0, 4)  # outside: the edge cells
    assert grid.cell([math.inf, -math.inf]) == (4, 0)
    assert grid.cell([math.nan, 0.5]) == (0, 2)


def test_unbounded_dimensions_are_left_out() -> None:
    grid = NoveltyGrid([0.0, -math.inf, 0.0], [1.0, math.inf, 2.0], 4)
    assert grid.cell([0.3, 1e9, 1.9]) == (1, 3)


@pytest.mark.parametrize(
    ("dims", "cells"),
    [(0, 64), (1, 64), (2, 64), (3, 16), (4, 8), (5, 5), (6, 4), (7, 3), (8, 2), (16, 2)],
)
def test_a_bound_on_all_cells_sets_the_cells_per_dimension(dims: int, cells: int) -> None:
    # the largest c <= 64 with c^dims <= 4,096, at least 2 (5^5 = 3,125 and 6^5 = 7,776)
    assert cells_per_dimension(64, dims, 4096) == cells
    assert cells_per_dimension(64, dims, None) == 64
    grid = NoveltyGrid([0.0] * dims, [1.0] * dims, 64, 4096)
    assert grid.cells == cells
    assert len(grid.dims) == dims


def test_the_bound_counts_only_bounded_dimensions() -> None:
    # two bounded inputs and four unbounded (CartPole-like): the grid is the unbounded 64 x 64
    grid = NoveltyGrid([0.0, -math.inf, 0.0, -math.inf], [1.0, math.inf, 1.0, math.inf], 64, 4096)
    assert grid.cells == 64
    assert grid.cell([0.99, 5.0, 0.0, -5.0]) == (63, 0)
    six = NoveltyGrid([0.0] * 6, [8.0] * 6, 64, 4096)  # 4 cells of 2.0 along each input
    assert six.cell([0.0, 1.9, 2.0, 3.9, 4.0, 8.0]) == (0, 0, 1, 1, 2, 3)


@pytest.mark.parametrize("cells", [1, 0, True, 2.5, "8"])
def test_a_bad_cell_count_is_refused(cells: Any) -> None:
    with pytest.raises(ValueError, match="cells"):
        NoveltyGrid([0.0], [1.0], cells)


def test_a_novel_end_takes_the_novel_value_until_it_is_pointed_at_its_leaf() -> None:
    model = LeafModel(2, 8)
    model.novel_value = 0.5
    q = [[0.0, 0.0], [-2.0, -3.0]]
    end = [0.9]
    model.add(0, 1, [0.1], -0.4, 0.8, end, 1, novel=True)
    # R + D * novel_value, whatever leaf 1's values are
    assert model.value(0, 1, q) == pytest.approx(-0.4 + 0.8 * 0.5)
    assert model.targets(0, 1, q)[1] == [pytest.approx(-0.4 + 0.8 * 0.5)]
    model.add(0, 1, [0.2], -0.1, 0.9, end, 1)
    assert model.value(0, 1, q) == pytest.approx(((-0.4 + 0.4) + (-0.1 + 0.9 * -2.0)) / 2)
    # a change of leaf 1 reaches (0, 1) through the ordinary epoch only
    assert model._preds[1] == {1: 1}
    assert model.end_novelty(lambda x: 1) == [1]
    assert model.value(0, 1, q) == pytest.approx(((-0.4 - 1.6) + (-0.1 - 1.8)) / 2)
    assert model._preds[1] == {1: 2}
    assert model.end_novelty(lambda x: 1) == []


def test_a_terminal_epoch_is_never_novel(make_corridor: Callable[..., Any]) -> None:
    model = LeafModel(2, 8)
    model.add(0, 0, [0.1], 5.0, 0.0, None, 0, novel=True)
    assert model.value(0, 0, [[-9.0, -9.0]]) == 5.0
    assert model.terminals == 1


def _novel_ends(model: LeafModel | None) -> int:
    """How many of the model's stored epochs end at a novel end."""
    assert model is not None
    return sum(r[4] == -2 for bucket in model._records.values() for r in bucket)


def _agent(env: Any, config: TreeConfig, seed: int = 0) -> TreeAgent:
    return TreeAgent(env.observation_space, env.action_space, "epsilon-greedy", seed, config)


def test_the_agent_counts_cells_and_stores_novel_ends(make_corridor: Callable[..., Any]) -> None:
    env = make_corridor(max_steps=30, goal_radius=0.0)
    config = dataclasses.replace(SWEEP, novelty_cells=10)
    agent = _agent(env, config)
    agent.learn(env, 1, reset_seed=3)  # 30 steps, no goal: nothing ends the novelty
    model = agent.model
    assert model is not None
    assert model.terminals == 0
    assert sum(model.seen.values()) == 30  # every input of every epoch counted once
    assert set(model.seen) <= {(i, j) for i in range(10) for j in range(10)}
    records = [r for bucket in model._records.values() for r in bucket]
    novel = [r for r in records if r[4] == -2]
    assert novel
    assert len(novel) < len(records)
    # a cell is novel once: at most one novel end per cell (the last end is never counted)
    grid = agent.novelty
    assert grid is not None
    cells = [grid.cell(r[3]) for r in novel if r[3] is not None]
    assert len(cells) == len(set(cells)) == len(novel)


def test_novel_ends_lift_the_values_that_lead_to_unseen_cells(
    make_corridor: Callable[..., Any],
) -> None:
    # no goal, rewards <= 0: every V-bar is <= q_init = 0, so an end valued at q_init lifts
    # its (leaf, action) and pointing it at its leaf lowers it again
    env = make_corridor(max_steps=60, goal_radius=0.0)
    agent = _agent(env, dataclasses.replace(SWEEP, novelty_cells=20, initial_depth=3))
    agent.learn(env, 2, reset_seed=1)
    model = agent.model
    assert model is not None
    keys = list(model._records)

    def values() -> list[float]:
        found = [model.value(*divmod(key, agent.n_actions), agent.q) for key in keys]
        return [v for v in found if v is not None]

    lifted = values()
    changed = model.end_novelty(agent.partition.leaf_of)
    lowered = values()
    assert changed
    assert all(a >= b for a, b in zip(lifted, lowered, strict=True))
    # strictly where the end leaf has learnt a value below q_init (not where it has an untried
    # action, whose value is q_init too)
    assert 0 < sum(a > b for a, b in zip(lifted, lowered, strict=True)) <= len(changed)


def test_the_first_terminal_ends_the_novelty(make_corridor: Callable[..., Any]) -> None:
    env = make_corridor(max_steps=400, noise=0.0)
    agent = _agent(env, dataclasses.replace(SWEEP, novelty_cells=20))
    history = agent.learn(env, 3, reset_seed=0)
    assert any(h.steps < 400 for h in history)  # the goal was reached
    model = agent.model
    assert model is not None
    assert model.terminals >= 1
    records = [r for bucket in model._records.values() for r in bucket]
    assert all(r[4] != -2 for r in records)  # every novel end points at its leaf
    counted = sum(model.seen.values())
    agent.learn(env, 1, reset_seed=9)
    assert sum(model.seen.values()) == counted  # nothing counted after the limit


def test_novelty_terminals_waits_for_more_terminals(make_corridor: Callable[..., Any]) -> None:
    env = make_corridor(max_steps=400, noise=0.0)
    agent = _agent(env, dataclasses.replace(SWEEP, novelty_cells=20, novelty_terminals=10**6))
    history = agent.learn(env, 3, reset_seed=0)
    model = agent.model
    assert model is not None
    assert model.terminals >= 1
    # every input of every episode counted: the terminal did not stop the count
    assert sum(model.seen.values()) == sum(h.steps for h in history)


def test_novelty_episodes_ends_the_novelty_without_a_terminal(
    make_corridor: Callable[..., Any],
) -> None:
    # no goal: episodes end only by the time limit, so no terminal would ever end the novelty
    env = make_corridor(max_steps=30, goal_radius=0.0)
    agent = _agent(env, dataclasses.replace(SWEEP, novelty_cells=10, novelty_episodes=2))
    agent.learn(env, 1, reset_seed=3)
    model = agent.model
    assert model is not None
    assert _novel_ends(model) > 0
    agent.learn(env, 1, reset_seed=4)  # the second episode ends it
    assert model.terminals == 0
    assert _novel_ends(model) == 0
    counted = sum(model.seen.values())
    assert counted == 60
    agent.learn(env, 2, reset_seed=5)
    assert sum(model.seen.values()) == counted  # nothing counted after the limit
    assert _novel_ends(model) == 0
    # without the limit the same runs keep counting
    open_ended = _agent(env, dataclasses.replace(SWEEP, novelty_cells=10))
    for seed in (3, 4, 5):
        open_ended.learn(env, 1 if seed < 5 else 2, reset_seed=seed)
    assert open_ended.model is not None
    assert sum(open_ended.model.seen.values()) == 120


def test_novelty_episodes_changes_nothing_when_the_terminals_come_first(
    make_corridor: Callable[..., Any],
) -> None:
    env = make_corridor(max_steps=400, noise=0.0)
    runs = []
    for limit in (None, 3):
        agent = _agent(env, dataclasses.replace(SWEEP, novelty_cells=20, novelty_episodes=limit))
        history = agent.learn(env, 5, reset_seed=0)
        assert history[0].steps < 400  # the first episode ends at the goal: the terminal
        runs.append((agent.q, [h.steps for h in history], agent.model))
    assert runs[0][0] == runs[1][0]
    assert runs[0][1] == runs[1][1]


def test_saved_counts_continue_bit_for_bit(
    tmp_path: Path, make_corridor: Callable[..., Any]
) -> None:
    env = make_corridor(max_steps=60, goal_radius=0.0)
    config = dataclasses.replace(SWEEP, novelty_cells=10)
    agent = _agent(env, config)
    agent.learn(env, 2, reset_seed=0)
    loaded = TreeAgent.load(agent.save(tmp_path / "a.npz"))
    assert loaded.model is not None
    assert agent.model is not None
    assert loaded.model.seen == agent.model.seen
    a = agent.learn(env, 2, reset_seed=5)
    b = loaded.learn(env, 2, reset_seed=5)
    assert [h.steps for h in a] == [h.steps for h in b]
    assert loaded.q == agent.q


@pytest.mark.parametrize(
    "entries",
    [
        "cells",
        [[[0, 1]]],
        [[[0, -1], 2]],
        [[[0, 1], 0]],
        [[[0, 1], True]],
        [[[0, 1.5], 2]],
        [[[0, 1], 2], [[0, 1], 3]],
    ],
)
def test_damaged_counts_are_refused(entries: Any) -> None:
    state = LeafModel(2, 4).state()
    state["seen"] = entries
    with pytest.raises(ValueError, match="seen cell"):
        LeafModel.from_state(2, state)


@pytest.mark.parametrize(
    ("fields", "match"),
    [
        ({"novelty_cells": 1}, "novelty_cells"),
        ({"novelty_cells": True}, "novelty_cells"),
        ({"novelty_cells": 2.5}, "novelty_cells"),
        ({"novelty_cells": "8"}, "novelty_cells"),
        ({"novelty_cells": 1 << 21}, "novelty_cells"),
        ({"novelty_terminals": 0}, "novelty_terminals"),
        ({"novelty_terminals": True}, "novelty_terminals"),
        ({"novelty_episodes": 0}, "novelty_episodes"),
        ({"novelty_episodes": -5}, "novelty_episodes"),
        ({"novelty_episodes": True}, "novelty_episodes"),
        ({"novelty_episodes": 2.0}, "novelty_episodes"),
        ({"novelty_episodes": "100"}, "novelty_episodes"),
        ({"novelty_cells": 8, "planning": "none"}, "needs planning"),
        ({"novelty_cells": 8, "novelty_max_cells": 1}, "novelty_max_cells"),
        ({"novelty_cells": 8, "novelty_max_cells": True}, "novelty_max_cells"),
        ({"novelty_cells": 8, "novelty_max_cells": 4096.0}, "novelty_max_cells"),
        ({"novelty_cells": 8, "novelty_max_cells": 2**41}, "novelty_max_cells"),
    ],
)
def test_bad_values_are_refused_by_name(fields: dict[str, Any], match: str) -> None:
    base = {"planning": "sweep", **fields}
    with pytest.raises(ValueError, match=match):
        TreeConfig(**base)


def test_the_paper_presets_leave_it_off_and_the_ensemble_loop_runs_it(
    make_corridor: Callable[..., Any],
) -> None:
    for name in ("paper", "paper-literal"):
        assert preset(name).config.novelty_cells is None
    env = make_corridor(max_steps=50, goal_radius=0.0)
    config = dataclasses.replace(preset("general").config, novelty_cells=16)
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, preset("general").make_exploration(), 0, config
    )
    agent.learn(env, 2, reset_seed=0)
    models = [m.model for m in getattr(agent, "members", [agent])]
    assert all(m is not None and sum(m.seen.values()) == 100 for m in models)
    assert np.isfinite(np.asarray(agent.q, dtype=float)).all()


@pytest.mark.parametrize(
    "entries", [[[[0, 1], 0]], [[[0, -2], 3]], [[["0", 1], 3]], "seen", [[[0, 1], 2, 3]]]
)
def test_damaged_counts_in_a_file_are_refused_by_name(
    tmp_path: Path, make_corridor: Callable[..., Any], entries: Any
) -> None:
    env = make_corridor(max_steps=30, goal_radius=0.0)
    agent = _agent(env, dataclasses.replace(SWEEP, novelty_cells=10))
    agent.learn(env, 1, reset_seed=0)
    with np.load(agent.save(tmp_path / "good.npz"), allow_pickle=False) as data:
        arrays = {key: data[key].copy() for key in data.files}
    meta = json.loads(arrays.pop("metadata").tobytes())
    assert meta["learner"]["model"]["seen"]  # the counts are in the file
    meta["learner"]["model"]["seen"] = entries
    bad = tmp_path / "bad.npz"
    np.savez(bad, metadata=np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8), **arrays)
    with pytest.raises(ValueError, match="seen cell") as error:
        TreeAgent.load(bad)
    assert str(bad) in str(error.value)


def test_novelty_episodes_ends_every_trees_novelty(make_corridor: Callable[..., Any]) -> None:
    env = make_corridor(max_steps=30, goal_radius=0.0)
    config = dataclasses.replace(
        SWEEP, novelty_cells=10, novelty_episodes=2, ensemble_trees=3, presplit_each_dimension=True
    )
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, "epsilon-greedy", 0, config
    )
    agent.learn(env, 1, reset_seed=0)
    members = agent.members  # type: ignore[attr-defined]
    assert len(members) == 3
    assert all(_novel_ends(m.model) > 0 for m in members)
    agent.learn(env, 1, reset_seed=1)
    assert [_novel_ends(m.model) for m in members] == [0, 0, 0]
