"""Issue 9, part 18 (development): does a greedy choice that reads *where in its leaf* a state
lies rank Acrobot's actions better than the leaf's Q-bar?

Part 12 found the tree's greedy Acrobot actions wrong by 10 steps or more at about half the
states it measured, and the better action mostly holding stored epochs with a Q-bar within a
few steps of the greedy one's: an aggregation bias. This probe trains the general preset
(1,000 episodes, first reset seed SEED, saved to OUT_DIR so later probes reuse it), then scores
the trained agent greedily over 20 episodes (reset seeds 10^6 + 1000 SEED + i) with:

- ``leaf``: the agent's own ``predict`` (Q-bar of the leaf);
- ``knn-k``: per action, the mean eq. (8) target ``R + D V-bar(l')`` of the k stored epochs of
  (leaf, action) whose first inputs are nearest the state (distances in units of the leaf's
  widths); an action with fewer than k epochs keeps its Q-bar;
- ``linear``: per action, a ridge fit of those targets on the first inputs (leaf-scaled).

Nothing in the agent changes; the choosers read its model. One JSON line per (seed, chooser)::

    python docs/results/issue9_part18_dev/local_greedy.py TASK SEED OUT.jsonl [MODEL_DIR]
"""

from __future__ import annotations

import json
import sys
import time
import warnings
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "issue9_part16_dev"))

from tasks_dev import episode_return  # noqa: E402

from agent import adapt_env, general_as_of  # noqa: E402
from agent.tree_ensemble import tree_agent_class  # noqa: E402


def trained(task: str, seed: int, model_dir: str) -> tuple[Any, gym.Env]:
    """``general_as_of(17)`` trained on ``task`` (1,000 episodes, first reset seed ``seed``),
    loaded from ``model_dir`` when an earlier probe saved it there; and the env."""
    path = Path(model_dir) / f"{task}-seed{seed}.npz"
    env = adapt_env(gym.make(task))
    config = general_as_of(17)
    cls = tree_agent_class(config)
    if path.exists():
        return cls.load(path), env
    agent = cls(env.observation_space, env.action_space, "adaptive+tabu", seed, config)
    agent.learn(env, 1000, reset_seed=seed)
    path.parent.mkdir(parents=True, exist_ok=True)
    agent.save(path)
    return agent, env


def local_chooser(agent: Any, kind: str, k: int) -> Any:
    model, q, n = agent.model, agent.q, agent.n_actions
    cache: dict[int, Any] = {}

    def leaf_data(leaf: int) -> Any:
        if leaf not in cache:
            low, high = agent.partition.leaf_bounds(leaf)
            low, high = np.asarray(low, float), np.asarray(high, float)
            width = np.where(np.isfinite(high - low) & (high - low > 0), high - low, 1.0)
            rows = []
            for a in range(n):
                firsts, values = model.targets(leaf, a, q)
                rows.append((np.asarray(firsts, float).reshape(len(firsts), len(low)), np.asarray(values, float)))
            cache[leaf] = (low, width, rows)
        return cache[leaf]

    def act(obs: Any) -> int:
        x = np.asarray(obs, float).reshape(-1)
        leaf = agent.leaf_of(x)
        low, width, rows = leaf_data(leaf)
        scores = list(q[leaf])
        for a, (firsts, values) in enumerate(rows):
            if len(values) < max(k, 2):
                continue
            z = (firsts - low) / width
            zx = (x - low) / width
            if kind == "knn":
                d = np.sum((z - zx) ** 2, axis=1)
                scores[a] = float(np.mean(values[np.argsort(d, kind="stable")[:k]]))
            else:
                design = np.hstack([np.ones((len(values), 1)), z - 0.5])
                reg = 1.0 * np.eye(design.shape[1])
                reg[0, 0] = 0.0
                w = np.linalg.solve(design.T @ design + reg, design.T @ values)
                scores[a] = float(w[0] + (zx - 0.5) @ w[1:])
        return int(np.argmax(scores))

    return act


def main(task: str, seed: int, out: str, model_dir: str) -> None:
    warnings.simplefilter("ignore")
    agent, env = trained(task, seed, model_dir)
    choosers = {"leaf": agent.predict}
    for k in (4, 8, 16):
        choosers[f"knn-{k}"] = local_chooser(agent, "knn", k)
    choosers["linear"] = local_chooser(agent, "linear", 4)
    with Path(out).open("a") as f:
        for name, act in choosers.items():
            start = time.process_time()
            greedy = [episode_return(env, 10**6 + 1000 * seed + i, act) for i in range(20)]
            f.write(json.dumps({"task": task, "seed": seed, "chooser": name,
                                "greedy": round(float(np.mean(greedy)), 2),
                                "cpu": round(time.process_time() - start, 1)}) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), sys.argv[3],
         sys.argv[4] if len(sys.argv) > 4 else "/tmp/part18_models")
