"""Part 40 dev: score greedy rules that read where in its leaf an input lies, on saved agents.

    python slope_probe.py TASK AGENT_DIR OUT SEED [SEED ...]

Each (leaf, action) of a trained agent keeps its last ``model_window`` epochs: where each began
(its first input) and its eq. (8) target ``R + D V-bar(l')`` under today's values
(``LeafModel.targets``). Q-bar(leaf, action) is their mean, one value for the whole leaf. A rule
here fits a line instead, a ridge regression of the targets on the first inputs,

    Q(x, a) = mean(y) + w . u(x),   u_j(x) = (x_j - mean_j) / width_j,
    w = argmin sum_e (y_e - mean(y) - w . u_e)^2 + ridge * m * |w|^2,

with each input measured in its leaf's widths (a dimension with an unbounded edge or no spread is
left out), so that the line through the window's mean agrees with Q-bar there. A key with fewer
than ``2 d + 2`` stored epochs keeps its Q-bar. The rules (each compared with today's
``predict`` on the same agent and the same 20 greedy episodes of part 39's ``protocol.py``):

- ``all-R``: the argmax of the lines over the actions ``predict`` allows
  (``TreeConfig.greedy_min_epochs``), ridge R;
- ``ties-R``: today's ``predict`` unless its leaf test ties several actions
  (``TreeConfig.greedy_tie_errors``), then the argmax of the lines among the tied ones;
- ``all-1e9`` and ``ties-1e9``: the controls, whose ridge flattens every line to its Q-bar (the
  plain argmax of Q-bar over the allowed actions, and among the tied ones).

One JSON line per (seed, rule): the mean greedy return and each episode's length.
"""

from __future__ import annotations

import sys
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "issue9_part39_dev"))
from protocol import greedy_episodes  # (part 39's folder)
from train_full import append_scored  # this folder

from agent import adapt_env, preset
from agent.env_checks import observation_vector
from agent.tree_ensemble import tree_agent_class

RULES = ("today", "all-0.1", "all-1", "ties-0.1", "all-1e9", "ties-1e9")


def line_fits(agent: Any, leaf: int, ridge: float) -> list[Callable[[list[float]], float]]:
    """Each action's fitted Q(x, a) in ``leaf`` (a constant Q-bar where the window is short)."""
    low, high = agent.partition.leaf_bounds(leaf)
    d = len(low)
    fits: list[Callable[[list[float]], float]] = []
    for a in range(agent.n_actions):
        firsts, ys = agent.model.targets(leaf, a, agent.q)
        qbar = agent.q[leaf][a]
        if len(ys) < 2 * d + 2:
            fits.append(lambda x, v=qbar: v)
            continue
        xs = np.array([list(f) for f in firsts])
        y = np.array(ys)
        dims = [
            j
            for j in range(d)
            if np.isfinite(low[j]) and np.isfinite(high[j]) and np.ptp(xs[:, j]) > 0
        ]
        if not dims:
            fits.append(lambda x, v=qbar: v)
            continue
        width = np.array([high[j] - low[j] for j in dims])
        centre = xs[:, dims].mean(axis=0)
        u = (xs[:, dims] - centre) / width
        m = len(y)
        w = np.linalg.solve(u.T @ u + ridge * m * np.eye(len(dims)), u.T @ (y - y.mean()))
        mean = float(y.mean())
        fits.append(
            lambda x, mean=mean, w=w, dims=dims, centre=centre, width=width: (
                mean + float(w @ ((np.asarray(x)[dims] - centre) / width))
            )
        )
    return fits


def rule(agent: Any, name: str) -> Callable[[Any], int]:
    """The greedy action of rule ``name`` for an observation."""
    if name == "today":
        return agent.predict
    kind, ridge = name.split("-")
    cache: dict[int, list[Callable[[list[float]], float]]] = {}
    member = agent.members[0] if hasattr(agent, "members") else agent
    d = len(member.bounds[0])

    def act(obs: Any) -> int:
        x = observation_vector(obs, d, "probe")
        leaf = member.partition.leaf_of(x)
        fits = cache.get(leaf)
        if fits is None:
            fits = cache[leaf] = line_fits(member, leaf, float(ridge))
        row = member.q[leaf]
        allowed = member._supported([member], [leaf])
        if kind == "ties":
            candidates = member._tied(
                [member], [leaf], row, allowed, member.config.greedy_tie_errors
            )
            if len(candidates) == 1:
                return int(agent.predict(obs))
        else:
            candidates = list(range(member.n_actions)) if allowed is None else allowed
        values = [fits[a](x) for a in candidates]
        return candidates[int(np.argmax(values))]

    return act


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, agent_dir, out = argv[1], Path(argv[2]), Path(argv[3])
    config = preset("general").config
    for seed in map(int, argv[4:]):
        env = adapt_env(gym.make(task))
        for name in RULES:
            agent = tree_agent_class(config).load(agent_dir / f"{task}-{seed}.npz")
            returns, lengths = greedy_episodes(env, rule(agent, name), seed)
            append_scored(out, {"task": task, "seed": seed, "rule": name}, returns, lengths)


if __name__ == "__main__":
    main(sys.argv)
