"""Agent files of the fixed baselines (``agent.baseline_files``): the tile coder and adaptive
Q-learning save and load as the tree agents do; a loaded agent acts and learns on exactly as
the saved one; and a damaged or hostile file is refused naming the file and the defect (the
fuzz cases are kept as a table)."""

from __future__ import annotations

import json
import zipfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

from agent import AdaptiveQAgent, SMDPAgent, TileCodingAgent
from agent.baseline_files import baseline_kind
from experiments.factory import load_agent

KINDS = [TileCodingAgent, AdaptiveQAgent]


def _trained(cls: type, task: str = "CartPole-v1", **kwargs: Any) -> tuple[Any, gym.Env]:
    env = gym.make(task)
    agent = cls(env.observation_space, env.action_space, seed=3, **kwargs)
    agent.learn(env, 12, reset_seed=1)
    return agent, env


@pytest.mark.parametrize("cls", KINDS, ids=lambda c: c.kind)
@pytest.mark.parametrize("task", ["CartPole-v1", "MountainCar-v0"])
def test_a_loaded_baseline_acts_and_learns_on_exactly_as_the_saved_one(
    cls: type, task: str, tmp_path: Path
) -> None:
    agent, env = _trained(cls, task)
    path = agent.save(tmp_path / "agent")
    assert path == tmp_path / "agent.npz"
    loaded = cls.load(path)
    assert type(loaded) is cls
    assert loaded.params() == agent.params()
    assert loaded.episodes_done == agent.episodes_done == 12
    for seed in range(5):
        obs, _ = env.reset(seed=seed)
        assert loaded.predict(obs) == agent.predict(obs)
        if cls is TileCodingAgent:
            assert loaded.q_values(obs) == agent.q_values(obs)
    if cls is AdaptiveQAgent:
        assert [t.q for t in loaded.trees] == [t.q for t in agent.trees]
    before = [h.steps for h in agent.learn(env, 4, reset_seed=7)]
    after = [h.steps for h in loaded.learn(env, 4, reset_seed=7)]
    assert before == after  # the random stream and every weight came back
    assert agent.save(tmp_path / "p.npz", policy_only=True).read_bytes() == (
        agent.save(tmp_path / "q.npz").read_bytes()
    )


def test_the_harness_loads_whichever_agent_a_file_holds(tmp_path: Path) -> None:
    tile, _ = _trained(TileCodingAgent, epsilon=0.1)
    adaptive, _ = _trained(AdaptiveQAgent)
    assert baseline_kind(tile.save(tmp_path / "t")) == "tile"
    assert baseline_kind(adaptive.save(tmp_path / "a")) == "adaptive-q"
    assert type(load_agent(tmp_path / "t.npz")) is TileCodingAgent
    assert type(load_agent(tmp_path / "a.npz")) is AdaptiveQAgent
    with pytest.raises(ValueError, match=r"t\.npz: holds a 'tile' agent, not a 'adaptive-q'"):
        AdaptiveQAgent.load(tmp_path / "t.npz")
    with pytest.raises(ValueError, match=r"format 'bullet_maze\.baseline' version 1, expected"):
        SMDPAgent.load(tmp_path / "t.npz")
    env = gym.make("CartPole-v1")
    tree = SMDPAgent.load(
        __import__("agent")
        .preset("paper")
        .agent(env.observation_space, env.action_space, bounds=([-5] * 4, [5] * 4))
        .save(tmp_path / "tree")
    )
    assert baseline_kind(tmp_path / "tree.npz") is None
    assert type(load_agent(tmp_path / "tree.npz")) is type(tree)
    with pytest.raises(ValueError, match=r"format 'bullet_maze\.agent' version 2, expected"):
        TileCodingAgent.load(tmp_path / "tree.npz")


def _rewrite(path: Path, edit: Callable[[dict[str, Any], dict[str, np.ndarray]], None]) -> None:
    """Open an agent file, let ``edit`` change its metadata and arrays, write it back."""
    with np.load(path, allow_pickle=False) as data:
        arrays = {name: data[name] for name in data.files}
    meta = json.loads(arrays.pop("metadata").tobytes().decode("utf-8"))
    edit(meta, arrays)
    text = json.dumps(meta).encode("utf-8")
    np.savez(path, metadata=np.frombuffer(text, dtype=np.uint8), **arrays)


def _meta(key: str, value: Any) -> Callable[[dict, dict], None]:
    return lambda meta, arrays: meta.__setitem__(key, value)


def _param(key: str, value: Any) -> Callable[[dict, dict], None]:
    return lambda meta, arrays: meta["params"].__setitem__(key, value)


def _array(name: str, change: Callable[[np.ndarray], np.ndarray]) -> Callable[[dict, dict], None]:
    return lambda meta, arrays: arrays.__setitem__(name, change(arrays[name]))


def _drop(name: str) -> Callable[[dict, dict], None]:
    return lambda meta, arrays: arrays.pop(name)


def _swap_tiles(tiles: np.ndarray) -> np.ndarray:
    out = tiles.copy()
    out[0, -1] = out[1, -1]
    return out


def _twice(tiles: np.ndarray) -> np.ndarray:
    out = tiles.copy()
    out[1, :-1] = out[0, :-1]
    return out


def _nan_first(values: np.ndarray) -> np.ndarray:
    out = values.astype(np.float64).copy()
    out.reshape(-1)[0] = np.nan
    return out


HOSTILE_TILE: list[tuple[str, Callable[[dict, dict], None], str]] = [
    ("other format", _meta("format", "x"), "format 'x' version 1, expected"),
    ("other version", _meta("version", 9), "version 9, expected"),
    ("unknown key", _meta("extra", 1), "metadata keys"),
    ("kind", _meta("kind", "adaptive-q"), "holds a 'adaptive-q' agent, not a 'tile'"),
    ("actions", _meta("n_actions", 0), "n_actions must be an integer in"),
    ("episodes", _meta("episodes_done", -1), "episodes_done -1 is not an integer >= 0"),
    ("episodes bool", _meta("episodes_done", True), "episodes_done True"),
    ("space", _meta("observation_space", {"low": [0], "high": [1]}), "observation_space: bad"),
    ("params", _meta("params", []), "params is not an object"),
    ("param type", _param("tilings", "8"), "metadata params: TileCodingAgent: tilings"),
    ("param value", _param("alpha", 2.0), "metadata params: TileCodingAgent: alpha"),
    ("param unknown", _param("warp", 1), "metadata params: .*unexpected keyword"),
    ("rng", _meta("rng", {"block": 1}), "rng must hold"),
    (
        "rng state",
        lambda m, a: m["rng"].__setitem__("bit_generator", {"x": 1}),
        r"metadata rng is not a random generator's state",
    ),
    (
        "rng inner state",
        lambda m, a: m["rng"]["bit_generator"].__setitem__("state", 5),
        r"metadata rng is not a random generator's state",
    ),
    ("missing array", _drop("weights"), r"entries \['tiles'\] differ"),
    ("extra array", lambda m, a: a.__setitem__("more", np.zeros(1)), r"entries .*more.* differ"),
    ("weights dtype", _array("weights", lambda w: w.astype(np.float32)), "has dtype"),
    ("weights ndim", _array("weights", lambda w: w.reshape(-1)), "has 1 dimensions"),
    ("weights shape", _array("weights", lambda w: w[:, :-1]), "entry 'weights' has shape"),
    ("weights nan", _array("weights", _nan_first), "'weights' holds values that are not finite"),
    ("tiles shape", _array("tiles", lambda t: t[:, 1:]), "entry 'tiles' has shape"),
    ("tiles index", _array("tiles", _swap_tiles), "number the used tiles 0 .. n - 1 once"),
    (
        "tiles tiling",
        _array("tiles", lambda t: t + np.eye(1, t.shape[1], 0, dtype=t.dtype) * 99),
        "names a tiling outside",
    ),
    ("tiles twice", _array("tiles", _twice), "lists one tile twice"),
]

HOSTILE_ADAPTIVE: list[tuple[str, Callable[[dict, dict], None], str]] = [
    ("param", _param("max_depth", -1), "metadata params: AdaptiveQAgent: max_depth"),
    ("q nan", _array("action0.q", _nan_first), "'action0.q' holds values that are not finite"),
    ("root", _array("action1.low", lambda x: x + 0.5), "action 1's root box differs"),
    ("visits", _array("action0.visits", lambda v: v - 10**6), "holds negative counts"),
    ("depth", _array("action0.depth", lambda d: d + 1), "is not each box's depth"),
    (
        "child",
        _array("action0.first_child", lambda c: np.where(c >= 0, c + 1, c)),
        "children|child of two|no parent|halve",
    ),
    (
        "loop",
        _array("action0.first_child", lambda c: np.where(np.arange(c.size) == 0, 0, c)),
        "children lie outside",
    ),
    (
        "halves",
        _array("action0.high", lambda h: np.where(np.arange(h.shape[0])[:, None] > 0, h * 1.01, h)),
        "do not halve it",
    ),
    ("shapes", _array("action0.depth", lambda d: d[:-1]), "entry 'action0.depth' has shape"),
]


@pytest.mark.parametrize(
    ("cls", "edit", "message"),
    [(TileCodingAgent, e, m) for _, e, m in HOSTILE_TILE]
    + [(AdaptiveQAgent, e, m) for _, e, m in HOSTILE_ADAPTIVE],
    ids=[f"tile-{n}" for n, _, _ in HOSTILE_TILE] + [f"aq-{n}" for n, _, _ in HOSTILE_ADAPTIVE],
)
def test_a_hostile_file_is_refused_naming_it_and_the_defect(
    cls: type, edit: Callable[[dict, dict], None], message: str, tmp_path: Path
) -> None:
    agent, _ = _trained(cls)
    if cls is AdaptiveQAgent:  # enough boxes to split
        assert agent.n_leaves > 2 * agent.n_actions
    path = agent.save(tmp_path / "agent.npz")
    _rewrite(path, edit)
    with pytest.raises(ValueError, match=message) as error:
        cls.load(path)
    assert str(path) in str(error.value)


@pytest.mark.parametrize("cls", KINDS, ids=lambda c: c.kind)
def test_damaged_archives_are_refused_by_name(cls: type, tmp_path: Path) -> None:
    agent, _ = _trained(cls)
    path = agent.save(tmp_path / "agent.npz")
    data = path.read_bytes()
    cut = tmp_path / "cut.npz"
    cut.write_bytes(data[: len(data) // 2])
    garbage = tmp_path / "garbage.npz"
    garbage.write_bytes(b"not an archive")
    pickled = tmp_path / "pickled.npz"
    with zipfile.ZipFile(pickled, "w") as archive:
        archive.writestr("metadata.pkl", b"cos\nsystem\n(S'echo'\ntR.")
    for bad, message in (
        (cut, "not an agent file|damaged"),
        (garbage, "not an agent file"),
        (pickled, "unexpected entry 'metadata.pkl'"),
    ):
        with pytest.raises(ValueError, match=message):
            cls.load(bad)
    with pytest.raises(FileNotFoundError):
        cls.load(tmp_path / "nowhere.npz")
    with pytest.raises(ValueError, match="policy_only must be True or False"):
        agent.save(tmp_path / "x.npz", policy_only="yes")
