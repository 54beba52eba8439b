"""Saving and loading agents: one ``.npz`` of plain arrays plus a JSON metadata string.

Never pickle: the file is read with ``np.load(..., allow_pickle=False)``. Arrays: ``q`` and
``visits`` (one row per leaf id) and the partition's arrays (``partition.<name>``; for the tree
its nodes and the leaves' state-error buffers). The ``metadata`` entry is a JSON document with
the agent kind, config, spaces, exploration strategy (name, parameters, learned state) and the
generator's bit-generator state, so that a loaded agent acts and continues learning identically.
"""

from __future__ import annotations

import json
from os import PathLike
from pathlib import Path
from typing import Any

import numpy as np
from gymnasium import spaces

from agent.config import TreeConfig
from agent.exploration import exploration_from_spec, exploration_spec
from agent.learner import SMDPAgent

FORMAT = "bullet_maze.agent"
VERSION = 1


def _space_to_json(space: spaces.Space) -> dict[str, Any]:
    if not isinstance(space, spaces.Box):
        raise TypeError(f"only a Box observation space is saved, got {space!r}")
    return {
        "low": np.asarray(space.low, dtype=np.float64).tolist(),
        "high": np.asarray(space.high, dtype=np.float64).tolist(),
        "dtype": str(space.dtype),
    }


def save_agent(agent: SMDPAgent, path: str | PathLike[str]) -> None:
    """Write ``agent`` to ``path`` (NumPy adds ``.npz`` if missing)."""
    partition_arrays, partition_meta = agent.partition.to_arrays()
    metadata = {
        "format": FORMAT,
        "version": VERSION,
        "kind": agent.kind,
        "config": agent.config.to_dict(),
        "observation_space": _space_to_json(agent.observation_space),
        "n_actions": agent.n_actions,
        "bounds": [list(agent.bounds[0]), list(agent.bounds[1])],
        "seed": agent.seed,
        "episodes_done": agent.episodes_done,
        "exploration": exploration_spec(agent.exploration),
        "rng": agent.uniform.state(),
        "partition": partition_meta,
    }
    arrays: dict[str, Any] = {
        "metadata": np.asarray(json.dumps(metadata)),
        "q": np.asarray(agent.q, dtype=np.float64),
        "visits": np.asarray(agent.visits, dtype=np.int64),
    }
    arrays.update({f"partition.{k}": v for k, v in partition_arrays.items()})
    np.savez(Path(path), **arrays)


def load_agent(path: str | PathLike[str]) -> SMDPAgent:
    """Read an agent written by :func:`save_agent`."""
    from agent.grid_agent import GridAgent
    from agent.partition_tree import PartitionTree
    from agent.tree_agent import TreeAgent

    path = Path(path)
    if not path.exists() and path.with_name(path.name + ".npz").exists():
        path = path.with_name(path.name + ".npz")  # np.savez added the suffix
    with np.load(path, allow_pickle=False) as data:
        arrays = {k: data[k] for k in data.files}
    if "metadata" not in arrays:
        raise ValueError(f"{path}: not an agent file (no 'metadata' entry)")
    meta = json.loads(str(arrays["metadata"]))
    if meta.get("format") != FORMAT or meta.get("version") != VERSION:
        raise ValueError(
            f"{path}: format {meta.get('format')!r} version {meta.get('version')!r}, "
            f"expected {FORMAT!r} version {VERSION}"
        )
    box = meta["observation_space"]
    observation_space = spaces.Box(
        low=np.asarray(box["low"]), high=np.asarray(box["high"]), dtype=np.dtype(box["dtype"])
    )
    action_space = spaces.Discrete(int(meta["n_actions"]))
    config = TreeConfig.from_dict(meta["config"])
    strategy = exploration_from_spec(meta["exploration"])
    bounds = (meta["bounds"][0], meta["bounds"][1])
    kind = meta["kind"]
    agent: SMDPAgent
    if kind == "tree":
        agent = TreeAgent(observation_space, action_space, strategy, meta["seed"], config, bounds)
        part = {k[len("partition.") :]: v for k, v in arrays.items() if k.startswith("partition.")}
        agent.partition = PartitionTree.from_arrays(part, meta["partition"], config)
    elif kind == "grid":
        resolution = meta["partition"]["resolution"]
        agent = GridAgent(
            observation_space, action_space, strategy, meta["seed"], config, bounds, resolution
        )
    else:
        raise ValueError(f"{path}: unknown agent kind {kind!r}")
    strategy.load_state_dict(meta["exploration"]["state"])
    agent.q = arrays["q"].tolist()
    agent.visits = arrays["visits"].tolist()
    agent.episodes_done = int(meta["episodes_done"])
    agent.uniform.restore(meta["rng"])
    return agent
