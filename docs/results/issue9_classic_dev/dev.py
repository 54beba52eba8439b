"""The driver of issue 9's part 4 (classic control, development seeds only).

One job: the general preset's config with ``overrides``, agent seed s, first reset seed s,
1,000 episodes, then 20 greedy episodes reset with seeds 10^6 + 1000 s + i (the protocol of
tests/agent/test_classic_learning.py). Each job appends one JSON line to ``results.jsonl``
(greedy mean, training mean of the last 100 episodes, leaves, CPU seconds, steps, and from
the third batch on every greedy episode's return; a second argument names another output
file; a job's optional "x" names another exploration strategy and its parameters)::

    PYTHONPATH=. nice -n 10 python docs/results/issue9_classic_dev/dev.py \
        '[{"task": "CartPole-v1", "label": "dec1gT", "seed": 0,
           "o": {"decision_steps": 1, "decision_from_terminal": true}}]'
"""

from __future__ import annotations

import dataclasses
import json
import sys
import time
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from agent import preset
from agent.exploration import make_exploration
from agent.tree_ensemble import tree_agent_class

OUT = Path(__file__).with_name("results.jsonl")


def greedy(agent: Any, env: gym.Env, episodes: int, seed: int) -> list[float]:
    """Returns of greedy episodes, reset with seeds 10^6 + 1000 seed + i."""
    out = []
    for i in range(episodes):
        obs, _ = env.reset(seed=1_000_000 + 1000 * seed + i)
        total, done = 0.0, False
        while not done:
            obs, reward, terminated, truncated, _ = env.step(agent.predict(obs))
            total += float(reward)
            done = terminated or truncated
        out.append(total)
    return out


def run(
    task: str,
    label: str,
    overrides: dict[str, Any],
    seed: int,
    episodes: int = 1000,
    out: Path = OUT,
    exploration: dict[str, Any] | None = None,
    wrap: Any = None,
    base: Any = None,
) -> None:
    """``wrap`` (part 17) turns the env into the one learnt (``adapt_env`` of a frame stack);
    ``base`` is the config the overrides apply to (default: today's general preset)."""
    general = preset("general")
    config = dataclasses.replace(base or general.config, **overrides)
    env = gym.make(task) if wrap is None else wrap(gym.make(task))
    if exploration is None:
        strategy = general.make_exploration()
    else:
        params = dict(exploration)
        strategy = make_exploration(params.pop("name"), **params)
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, strategy, seed, config
    )
    start = time.process_time()
    history = agent.learn(env, episodes, reset_seed=seed)
    cpu = time.process_time() - start
    returns = greedy(agent, env, 20, seed)
    record = {
        "task": task,
        "label": label,
        "overrides": overrides,
        **({} if exploration is None else {"exploration": exploration}),
        "seed": seed,
        "greedy": round(float(np.mean(returns)), 1),
        "train_last100": round(float(np.mean([h.episode_return for h in history[-100:]])), 1),
        "leaves": agent.n_leaves,
        "cpu": round(cpu, 1),
        "steps": sum(h.steps for h in history),
        "greedy_all": [round(v) for v in returns],
    }
    with out.open("a") as f:
        f.write(json.dumps(record) + "\n")


if __name__ == "__main__":
    target = Path(sys.argv[2]) if len(sys.argv) > 2 else OUT
    for job in json.loads(sys.argv[1]):
        run(
            job["task"],
            job["label"],
            job.get("o", {}),
            job["seed"],
            out=target,
            exploration=job.get("x"),
        )
