"""Save and load: a non-executable file after which the agent acts and learns identically."""

from __future__ import annotations

import json
import zipfile
from collections.abc import Callable
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

from agent import GridAgent, TreeAgent, TreeConfig
from agent.learner import SMDPAgent


def build(kind: str, env: gym.Env, strategy: str) -> SMDPAgent:
    config = TreeConfig(split_min_samples=100, error_buffer="window")
    if kind == "tree":
        return TreeAgent(env.observation_space, env.action_space, strategy, 4, config)
    return GridAgent(env.observation_space, env.action_space, strategy, 4, config, resolution=7)


@pytest.mark.parametrize(
    ("kind", "strategy"),
    [("tree", "adaptive+tabu"), ("tree", "vdbe"), ("tree", "epsilon-greedy"), ("grid", "tabu")],
)
def test_round_trip_acts_and_continues_identically(
    tmp_path: Path, make_corridor: Callable[..., gym.Env], kind: str, strategy: str
) -> None:
    agent = build(kind, make_corridor(), strategy)
    agent.learn(make_corridor(), 25, reset_seed=1)
    path = tmp_path / "agent.npz"
    agent.save(path)
    loaded = type(agent).load(path)

    assert type(loaded) is type(agent)
    assert loaded.q == agent.q
    assert loaded.visits == agent.visits
    assert repr(loaded.exploration) == repr(agent.exploration)
    assert loaded.render() == agent.render()
    probe = np.random.default_rng(0).uniform(0, 1, size=(200, 2))
    assert [loaded.predict(x) for x in probe] == [agent.predict(x) for x in probe]

    later = agent.learn(make_corridor(), 15, reset_seed=9)
    later_loaded = loaded.learn(make_corridor(), 15, reset_seed=9)
    assert later_loaded == later
    assert loaded.q == agent.q
    assert loaded.n_leaves == agent.n_leaves


def test_file_is_plain_arrays_and_json(
    tmp_path: Path, make_corridor: Callable[..., gym.Env]
) -> None:
    agent = build("tree", make_corridor(), "adaptive+tabu")
    agent.learn(make_corridor(), 10)
    agent.save(tmp_path / "a.npz")
    with np.load(tmp_path / "a.npz", allow_pickle=False) as data:
        meta = json.loads(data["metadata"].tobytes().decode("utf-8"))
        assert data["q"].shape == (agent.partition.n_ids, 4)
    assert meta["kind"] == "tree"
    assert meta["exploration"]["name"] == "adaptive+tabu"
    assert meta["config"]["split_min_samples"] == 100


def test_suffix_is_optional(tmp_path: Path, make_corridor: Callable[..., gym.Env]) -> None:
    agent = build("tree", make_corridor(), "greedy")
    agent.save(tmp_path / "plain")
    assert (tmp_path / "plain.npz").is_file()
    assert TreeAgent.load(tmp_path / "plain").q == agent.q


def test_loading_the_wrong_kind_or_file_fails(
    tmp_path: Path, make_corridor: Callable[..., gym.Env]
) -> None:
    build("grid", make_corridor(), "greedy").save(tmp_path / "grid.npz")
    with pytest.raises(ValueError, match="GridAgent, not a TreeAgent"):
        TreeAgent.load(tmp_path / "grid.npz")
    np.savez(tmp_path / "other.npz", x=np.zeros(2))
    with pytest.raises(ValueError, match="metadata"):
        TreeAgent.load(tmp_path / "other.npz")


# --- the policy-only file ------------------------------------------------------------------


def grown_tree(make_corridor: Callable[..., gym.Env]) -> TreeAgent:
    """A tree agent that has split many times (small buffers, so that it grows fast)."""
    config = TreeConfig(split_min_samples=60, error_buffer="window")
    env = make_corridor()
    agent = TreeAgent(env.observation_space, env.action_space, "adaptive+tabu", 3, config)
    agent.learn(env, 30, reset_seed=2)
    assert agent.n_leaves >= 8
    return agent


def test_policy_only_file_is_small_and_acts_like_the_full_one(
    tmp_path: Path, make_corridor: Callable[..., gym.Env]
) -> None:
    agent = grown_tree(make_corridor)
    full = agent.save(tmp_path / "agent.npz")
    policy = agent.save(tmp_path / "policy", policy_only=True)
    assert policy == tmp_path / "policy.npz"
    assert policy.stat().st_size < full.stat().st_size / 2
    from_full, from_policy = TreeAgent.load(full), TreeAgent.load(policy)
    probe = np.random.default_rng(1).uniform(0, 1, size=(500, 2))
    assert [from_policy.predict(x) for x in probe] == [agent.predict(x) for x in probe]
    assert from_policy.render() == from_full.render() == agent.render()
    assert from_policy.leaves() == agent.leaves()
    explored = [from_policy.predict(x, deterministic=False) for x in probe]
    assert explored == [from_full.predict(x, deterministic=False) for x in probe]
    with np.load(policy, allow_pickle=False) as data:
        assert not [name for name in data.files if "buffer" in name]
        assert json.loads(data["metadata"].tobytes())["policy_only"] is True
    assert from_policy.partition.buffer(from_policy.leaf_of([0.5, 0.5])) is None
    assert len(from_policy.learn(make_corridor(), 2, reset_seed=0)) == 2  # it still learns


# --- tampered files: each refused by name, before anything is built -------------------------


def _rewrite(source: Path, target: Path, edit: Callable[[dict, dict], None]) -> Path:
    """Copy an agent file with ``edit(metadata, arrays)`` applied (arrays as NumPy loads them)."""
    with np.load(source, allow_pickle=False) as data:
        arrays = {name: data[name].copy() for name in data.files}
    meta = json.loads(arrays.pop("metadata").tobytes())
    edit(meta, arrays)
    np.savez(target, metadata=np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8), **arrays)
    return target


def _set(name: str, index: object, value: object) -> Callable[[dict, dict], None]:
    def edit(meta: dict, arrays: dict) -> None:
        arrays[name][index] = value

    return edit


def _meta(*keys: str, value: object) -> Callable[[dict, dict], None]:
    def edit(meta: dict, arrays: dict) -> None:
        table = meta
        for key in keys[:-1]:
            table = table[key]
        table[keys[-1]] = value

    return edit


def _first_internal(arrays: dict) -> int:
    return int(np.flatnonzero(arrays["partition.dim"] >= 0)[1])


def _loop_to_root(meta: dict, arrays: dict) -> None:
    arrays["partition.left"][_first_internal(arrays)] = 0  # its children would be the root


def _child_out_of_range(meta: dict, arrays: dict) -> None:
    arrays["partition.left"][0] = len(arrays["partition.dim"]) + 5


def _extra_array(meta: dict, arrays: dict) -> None:
    arrays["extra"] = np.zeros(3)


def _object_array(meta: dict, arrays: dict) -> None:
    arrays["q"] = np.array([{"x": 1}] * len(arrays["q"]), dtype=object)


def _fortran_q(meta: dict, arrays: dict) -> None:
    arrays["q"] = np.asfortranarray(arrays["q"])


def _drop_q_row(meta: dict, arrays: dict) -> None:
    arrays["q"] = arrays["q"][:-1]


def _drop_buffers(meta: dict, arrays: dict) -> None:
    del arrays["partition.buffer_errors"]


def _buffer_on_internal_node(meta: dict, arrays: dict) -> None:
    arrays["partition.buffer_leaf"][0] = 0


def _epsilon_seven(meta: dict, arrays: dict) -> None:
    leaves = np.flatnonzero(arrays["partition.dim"] == -1).tolist()
    meta["exploration"]["state"]["base"]["epsilon"] = [[leaf, 7.0] for leaf in leaves]


TAMPERED = [
    ("cycle", _loop_to_root, r"not after its parent \(a cycle\)"),
    ("child out of range", _child_out_of_range, r"not after its parent"),
    ("split dimension out of range", _set("partition.dim", 0, 7), r"dimension outside -1\.\.1"),
    ("nan Q", _set("q", (0, 0), np.nan), r"'q' holds values that are not finite"),
    ("inf threshold", _set("partition.threshold", 0, np.inf), r"'threshold' .*not finite"),
    ("threshold outside box", _set("partition.threshold", 0, 5.0), r"threshold outside"),
    ("negative visits", _set("visits", (0, 1), -3), r"negative counts"),
    ("wrong Q shape", _drop_q_row, r"'q' has shape"),
    ("depth", _set("partition.depth", 1, 4), r"'depth' contradicts"),
    ("parent", _set("partition.parent", 1, 2), r"'parent' contradicts"),
    ("buffer on internal node", _buffer_on_internal_node, r"not a leaf"),
    ("buffer count", _set("partition.buffer_counters", (0, 0), 10**6), r"count or head"),
    ("buffer missing", _drop_buffers, r"missing entries \['partition.buffer_errors'\]"),
    ("unknown entry", _extra_array, r"unknown entries \['extra'\]"),
    ("pickled entry", _object_array, r"'q' has dtype object"),
    ("fortran entry", _fortran_q, r"Fortran order"),
    ("gamma true", _meta("config", "gamma", value=True), r"config gamma: expected a number"),
    ("max_leaves true", _meta("config", "max_leaves", value=True), r"max_leaves: expected an"),
    ("huge buffers", _meta("config", "split_min_samples", value=10**8), r"at most 1,000,000"),
    ("unknown config", _meta("config", "alphaa", value=0.1), r"'alphaa' is not a field"),
    ("nan parameter", _meta("exploration", "params", "c_n", value=float("nan")), r"not valid JSON"),
    ("inf parameter", _meta("exploration", "params", "c_n", value=float("inf")), r"not finite"),
    (
        "string for bool",
        _meta("exploration", "params", "deviation_explores", value="false"),
        r"deviation_explores: expected true or false, got 'false'",
    ),
    ("unknown strategy", _meta("exploration", "name", value="boltzmann!"), r"boltzmann!"),
    ("bad epsilon state", _epsilon_seven, r"epsilon 7\.0"),
    ("actions", _meta("n_actions", value=10**9), r"n_actions must be an integer"),
    ("low above high", _meta("observation_space", "low", value=[2.0, 0.0]), r"low > high"),
    ("unknown dtype", _meta("observation_space", "dtype", value="complex64"), r"dtype .complex64."),
    (
        "integer box, fractional bound",
        _meta("observation_space", value={"low": [0.0, 0.0], "high": [3.5, 1.0], "dtype": "int64"}),
        r"dtype int64 has bounds that are not integers",
    ),
    ("unknown key", _meta("comment", value="hi"), r"unknown keys \['comment'\]"),
    ("version", _meta("version", value=3), r"version 3"),
    ("kind", _meta("kind", value="bogus"), r"unknown agent kind 'bogus'"),
    (
        "generator",
        _meta("rng", "bit_generator", value={"bit_generator": "MT19937"}),
        r"cannot be restored",
    ),
    ("pending draws", _meta("rng", "pending", value=[2.0]), r"pending draws"),
    ("seed", _meta("seed", value=-1), r"seed -1"),
    ("policy file with buffers", _meta("policy_only", value=True), r"unknown entries"),
]


@pytest.mark.parametrize(
    ("edit", "defect"), [c[1:] for c in TAMPERED], ids=[c[0] for c in TAMPERED]
)
def test_tampered_file_is_refused_by_name(
    tmp_path: Path,
    make_corridor: Callable[..., gym.Env],
    edit: Callable[[dict, dict], None],
    defect: str,
) -> None:
    agent = grown_tree(make_corridor)
    good = agent.save(tmp_path / "good.npz")
    bad = _rewrite(good, tmp_path / "bad.npz", edit)
    with pytest.raises(ValueError, match=defect) as error:
        TreeAgent.load(bad)
    assert str(bad) in str(error.value)
    assert "allow_pickle" not in str(error.value)


@pytest.mark.parametrize(
    ("content", "defect"),
    [
        (b"", "not a .npz archive"),
        (b"q = 1\nhello\n", "not a .npz archive"),
        (b"\x93NUMPY\x01\x00garbage", "not a .npz archive"),
    ],
    ids=["empty", "text", "bare npy"],
)
def test_a_file_that_is_no_archive_is_refused(tmp_path: Path, content: bytes, defect: str) -> None:
    path = tmp_path / "agent.npz"
    path.write_bytes(content)
    with pytest.raises(ValueError, match=defect) as error:
        TreeAgent.load(path)
    assert str(path) in str(error.value)
    assert "allow_pickle" not in str(error.value)


def test_truncated_files_are_refused_at_every_length(
    tmp_path: Path, make_corridor: Callable[..., gym.Env]
) -> None:
    data = build("tree", make_corridor(), "adaptive+tabu").save(tmp_path / "a.npz").read_bytes()
    cut = tmp_path / "cut.npz"
    for length in np.linspace(0, len(data) - 1, 40).astype(int):
        cut.write_bytes(data[:length])
        with pytest.raises(ValueError, match=str(cut)):
            TreeAgent.load(cut)


def test_an_unknown_compressed_entry_is_not_read(tmp_path: Path) -> None:
    """A small file declaring a large unknown member is refused from the zip directory alone."""
    import tracemalloc
    import zipfile

    path = tmp_path / "bomb.npz"
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED, compresslevel=1) as archive:
        with archive.open("metadata.npy", "w") as handle:
            np.lib.format.write_array(handle, np.asarray('{"format": "bullet_maze.agent"}'))
        with archive.open("big.npy", "w", force_zip64=True) as handle:
            np.lib.format.write_array_header_1_0(
                handle, {"descr": "<f8", "fortran_order": False, "shape": (8 << 20,)}
            )
            block = bytes(1 << 20)
            for _ in range(64):
                handle.write(block)
    assert path.stat().st_size < 1 << 20
    tracemalloc.start()
    with pytest.raises(ValueError, match=str(path)):
        TreeAgent.load(path)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert peak < 4 << 20


@pytest.mark.parametrize(
    ("old", "new"), [(b"'shape': (", b"'shape': (("), (b"'shape': (", b"'shape': {")]
)
def test_an_unbalanced_array_header_is_refused_by_name(
    tmp_path: Path, make_corridor: Callable[..., gym.Env], old: bytes, new: bytes
) -> None:
    """A header whose brackets do not close (numpy's parser raises a tokenizer error, not a
    ValueError, for the first) is a damaged entry, not a traceback."""
    agent = build("tree", make_corridor(), "adaptive+tabu")
    saved = agent.save(tmp_path / "a.npz")
    damaged = tmp_path / "damaged.npz"
    with zipfile.ZipFile(saved) as source, zipfile.ZipFile(damaged, "w") as target:
        for info in source.infolist():
            data = source.read(info.filename)
            if info.filename == "q.npy":
                assert old in data
                data = data.replace(old, new, 1)
            target.writestr(info, data)
    with pytest.raises(ValueError, match=r"damaged\.npz.*entry 'q' is not a NumPy array"):
        TreeAgent.load(damaged)


def test_random_byte_flips_are_refused_or_harmless(
    tmp_path: Path, make_corridor: Callable[..., gym.Env]
) -> None:
    """Every flip of a byte gives a ValueError naming the file, or an agent that acts the same."""
    agent = build("tree", make_corridor(), "adaptive+tabu")
    agent.learn(make_corridor(), 5, reset_seed=1)
    data = bytearray(agent.save(tmp_path / "a.npz").read_bytes())
    probe = np.random.default_rng(0).uniform(0, 1, size=(50, 2))
    expected = [agent.predict(x) for x in probe]
    flipped = tmp_path / "flipped.npz"
    rng = np.random.default_rng(7)
    refusals: list[str] = []
    for position in rng.integers(0, len(data), 60):
        copy = bytearray(data)
        copy[position] ^= 0xFF
        flipped.write_bytes(bytes(copy))
        try:
            loaded = TreeAgent.load(flipped)
        except ValueError as error:
            refusals.append(str(error))
            continue
        assert [loaded.predict(x) for x in probe] == expected
    assert refusals
    assert all(str(flipped) in message for message in refusals)


HOSTILE = [
    True,
    False,
    None,
    -1,
    0,
    2**70,
    1e308,
    -1e-300,
    "",
    "x" * 10_000,
    [],
    {},
    [1.5],
    {"a": 1},
]


def _json_paths(value: object, path: tuple = ()) -> list[tuple]:
    if isinstance(value, dict):
        return [path, *(p for k, v in value.items() for p in _json_paths(v, (*path, k)))]
    if isinstance(value, list) and len(value) <= 8:
        return [path, *(p for i, v in enumerate(value) for p in _json_paths(v, (*path, i)))]
    return [path]


def test_random_metadata_edits_are_refused_by_name_or_harmless(
    tmp_path: Path, make_corridor: Callable[..., gym.Env]
) -> None:
    """Any value anywhere in the metadata: a ValueError naming the file, or an agent whose
    greedy policy is the original's (the policy lives in the arrays, which are checked)."""
    agent = grown_tree(make_corridor)
    good = agent.save(tmp_path / "good.npz")
    with np.load(good, allow_pickle=False) as data:
        meta = json.loads(data["metadata"].tobytes())
    paths = [p for p in _json_paths(meta) if p]
    probe = np.random.default_rng(2).uniform(0, 1, size=(100, 2))
    expected = [agent.predict(x) for x in probe]
    rng = np.random.default_rng(9)
    refusals: list[str] = []
    bad = tmp_path / "bad.npz"
    for _ in range(120):
        path = paths[int(rng.integers(len(paths)))]
        value = HOSTILE[int(rng.integers(len(HOSTILE)))]
        _rewrite(good, bad, _meta(*path, value=value))
        try:
            loaded = TreeAgent.load(bad)
        except ValueError as error:
            refusals.append(str(error))
            continue
        assert [loaded.predict(x) for x in probe] == expected, path
    assert len(refusals) > 60
    assert all(str(bad) in message and "allow_pickle" not in message for message in refusals)


@pytest.mark.parametrize("env_id", ["CartPole-v1", "MountainCar-v0"])
def test_the_general_agent_round_trips_with_its_unit_model_and_unbounded_dimensions(
    tmp_path: Path, env_id: str
) -> None:
    """The general preset saves what it learns beyond the paper (the measured reward unit, the
    model over the leaves, the range each unbounded dimension showed) and continues bit for
    bit; CartPole's velocities are unbounded, so its tree's boxes are infinite there."""
    from agent import preset

    env = gym.make(env_id)
    agent = preset("general").agent(env.observation_space, env.action_space, seed=0)
    agent.learn(env, 30, reset_seed=0)
    path = agent.save(tmp_path / "agent.npz")
    loaded = TreeAgent.load(path)
    assert loaded.scale.value == agent.scale.value
    assert loaded.model is not None
    assert loaded.model.state() == agent.model.state()  # type: ignore[union-attr]
    assert loaded.partition.seen_bounds == agent.partition.seen_bounds
    later = agent.learn(env, 30, reset_seed=5)
    assert loaded.learn(env, 30, reset_seed=5) == later
    assert loaded.q == agent.q
    assert TreeAgent.load(agent.save(tmp_path / "p.npz", policy_only=True)).q == agent.q


def test_infinite_bounds_where_the_space_is_bounded_are_refused(tmp_path: Path) -> None:
    from agent import preset

    env = gym.make("CartPole-v1")
    agent = preset("general").agent(env.observation_space, env.action_space, seed=0)
    agent.learn(env, 3, reset_seed=0)
    path = agent.save(tmp_path / "agent.npz")
    with np.load(path, allow_pickle=False) as data:
        arrays = {k: data[k] for k in data.files}
    meta = json.loads(arrays["metadata"].tobytes().decode("utf-8"))
    meta["bounds"][0][0] = float("-inf")  # the cart's position is bounded (+-4.8)
    meta["partition"]["root_low"][0] = float("-inf")
    arrays["metadata"] = np.frombuffer(json.dumps(meta).encode("utf-8"), dtype=np.uint8)
    np.savez(tmp_path / "bad.npz", **arrays)
    with pytest.raises(ValueError, match=r"bad\.npz: metadata bounds are infinite where"):
        TreeAgent.load(tmp_path / "bad.npz")


def _refusal(tmp_path: Path, edit: Callable[[dict], None]) -> str:
    """The error of loading a general MountainCar agent's file (3 episodes learnt) after
    ``edit`` changed its JSON metadata; the undamaged file loads."""
    from agent import preset

    env = gym.make("MountainCar-v0")
    agent = preset("general").agent(env.observation_space, env.action_space, seed=0)
    agent.learn(env, 3, reset_seed=0)
    path = agent.save(tmp_path / "agent.npz")
    assert TreeAgent.load(path).model is not None
    arrays = dict(np.load(path, allow_pickle=False))
    metadata = json.loads(bytes(arrays["metadata"]).decode())
    edit(metadata)
    arrays["metadata"] = np.frombuffer(json.dumps(metadata).encode(), dtype=np.uint8)
    np.savez(tmp_path / "damaged.npz", **arrays)
    with pytest.raises(ValueError, match=r"damaged\.npz") as refused:
        TreeAgent.load(tmp_path / "damaged.npz")
    return str(refused.value)


def _records(m: dict) -> list:
    return m["learner"]["model"]["records"]


@pytest.mark.parametrize(
    ("change", "named"),
    [
        (lambda r: r[0][1][0].__setitem__(0, [0.1]), "must be a list of 2 numbers"),
        (lambda r: r[0][1][0].__setitem__(0, [0.1, 0.2, 0.3]), "must be a list of 2 numbers"),
        (lambda r: r[0][1][0].__setitem__(0, "abc"), "must be a list of 2 numbers"),
        (lambda r: r[0][1][0].__setitem__(0, None), "must be a list of 2 numbers"),
        (lambda r: r[0][1][0].__setitem__(0, [True, 0.0]), "must be a list of 2 numbers"),
        (lambda r: r[0][1][0].__setitem__(1, "x"), "its R 'x' is not a number"),
        (lambda r: r[0][1][0].__setitem__(2, None), "its D None is not a number"),
        (lambda r: r[0][1][0].__setitem__(2, -7), "its D -7 is not in [0, 1]"),
        (lambda r: r[0][1][0].__setitem__(2, 1.5), "its D 1.5 is not in [0, 1]"),
        (lambda r: r[0][1][0].__setitem__(4, 10**6), "end leaf 1000000 is not a leaf"),
        (lambda r: r[0][1][0].__setitem__(4, -7), "is not an int >= -2"),
        (lambda r: r[0][1][0].__setitem__(4, 1.5), "is not an int >= -2"),
        (lambda r: r[0][1][0].__setitem__(3, None), "disagree on terminal"),
        (lambda r: r[0].__setitem__(0, 3 * 10**6), "is not a leaf's"),
        (lambda r: r[0].__setitem__(0, "7"), "key is '7', not an int"),
    ],
)
def test_a_damaged_model_epoch_in_an_agent_file_is_refused_by_name(
    tmp_path: Path, change: Callable[[list], None], named: str
) -> None:
    """Fuzz cases: a stored epoch's input of the wrong length used to load and fail later (or
    never); each damage is now refused at load, naming the file, the key and the field."""
    assert named in _refusal(tmp_path, lambda m: change(_records(m)))


@pytest.mark.parametrize(
    ("field", "value", "named"),
    [
        ("window", 2.5, "window is 2.5, not an int >= 1"),
        ("window", True, "window is True, not an int >= 1"),
        ("window", "x", "window is 'x', not an int >= 1"),
        ("epochs", [[0, -5]], "epoch count of key 0 is -5"),
        ("epochs", [["a", 1]], "epoch count's key is 'a'"),
        ("epochs", 5, "epoch counts must be a list of pairs"),
        ("heap", [[5.0, 1]], "has priority -5.0, not a number > 0"),
        ("heap", [["x", 1]], "has priority 'x'"),
        ("heap", [[-1.0, -1]], "sweep queue's leaf is -1"),
        ("priority", [[1, -2.0]], "queued leaf 1 has priority -2.0"),
        ("priority", [[0, 2.0]], "queues leaves that are not leaves: [0]"),
        ("records", 7, "records must be a list of pairs"),
        ("records", [[1]], "records must be a list of pairs"),
        ("preds", [[0, [["a", 1]]]], "predecessor of leaf 0 is 'a'"),
        ("preds", [[0, [[1, 0]]]], "link 0 <- 1 is 0, not an int >= 1"),
    ],
)
def test_a_damaged_model_field_in_an_agent_file_is_refused_by_name(
    tmp_path: Path, field: str, value: object, named: str
) -> None:
    """Fuzz cases: a fractional window, negative counts and priorities, and a queued node that
    is not a leaf used to load silently; each is now refused at load, by field."""
    assert named in _refusal(tmp_path, lambda m: m["learner"]["model"].__setitem__(field, value))


def _scale(m: dict) -> dict:
    return m["learner"]["scale"]


def _tabu(m: dict) -> dict:
    return m["exploration"]["state"]


@pytest.mark.parametrize(
    ("edit", "named"),
    [
        (lambda m: _scale(m).__setitem__("total", -5), "total -5 is not the sum of its counts"),
        (lambda m: _scale(m).__setitem__("total", 99), "total 99 is not the sum of its counts"),
        (lambda m: _scale(m).__setitem__("gamma", 2.0), "gamma 2.0 is not in [0, 1]"),
        (lambda m: _scale(m).__setitem__("binned", "no"), "binned flag 'no' is not a bool"),
        (lambda m: _scale(m).__setitem__("counts", [["x", 3]]), "counted value 'x'"),
        (lambda m: _scale(m).__setitem__("counts", [[1.0, 0]]), "count of 1.0 is 0"),
        (lambda m: _scale(m).__setitem__("counts", [[-1.0, 3]]), "magnitude -1.0 is not > 0"),
        (lambda m: _tabu(m).__setitem__("successes", 2.5), "tabu successes 2.5"),
        (lambda m: _tabu(m).__setitem__("successes", -7), "tabu successes -7"),
        (lambda m: _tabu(m).__setitem__("fifo", [[1, 9]]), "tabu list entry [1, 9]"),
        (lambda m: _tabu(m).__setitem__("fifo", [[-3, 1]]), "tabu list entry [-3, 1]"),
        (lambda m: _tabu(m).__setitem__("fifo", "x"), "the tabu list 'x' is not a list"),
        (lambda m: _tabu(m)["base"].__setitem__("counts", [[72, [-1, 2, 3]]]), "of leaf 72"),
        (lambda m: _tabu(m)["base"].__setitem__("counts", [[72, [1]]]), "not 3 ints >= 0"),
        (lambda m: _tabu(m)["base"].__setitem__("counts", [[2.5, [1, 2, 3]]]), "[2.5, [1, 2, 3]]"),
        (lambda m: _tabu(m)["base"].__setitem__("epsilon", [[True, 0.5]]), "[True, 0.5] is not"),
        (lambda m: _tabu(m)["base"].__setitem__("epsilon", [[0, 0.5], [0, 0.4]]), "leaf 0 twice"),
        (lambda m: _tabu(m)["base"].__setitem__("epsilon", [[72, True]]), "72's epsilon True"),
    ],
)
def test_a_damaged_unit_or_exploration_state_is_refused_by_name(
    tmp_path: Path, edit: Callable[[dict], None], named: str
) -> None:
    """Fuzz cases: these used to load (a count of successes of 2.5, an action 9 of 3 in the
    tabu list) or to fail later inside learning (negative or short counts: a math domain
    error, an IndexError); each is now refused at load, naming the field."""
    assert named in _refusal(tmp_path, edit)
