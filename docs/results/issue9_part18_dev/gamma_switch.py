"""Issue 9, part 18 (development): does a discount raised *during* a run keep gamma 0.9995's
CartPole gain? A prototype of the failure-gated discount named in ``docs/paper-notes.md``
("Probes against the classic misses"): CartPole's terminals are all failures, and the measure
of ``decision_on_failure`` opens at episode 23-39 there, so this probe trains
``general_as_of(17)`` for SWITCH episodes with its gamma 0.999, then sets the agent's config
to gamma 0.9995 for the rest of the 1,000 (the model's stored epochs keep the discounts they
were stored with until they leave its window); then part 4's 20 greedy episodes::

    python docs/results/issue9_part18_dev/gamma_switch.py SEED SWITCH OUT.jsonl
"""

from __future__ import annotations

import dataclasses
import json
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "issue9_classic_dev"))

from dev import greedy  # noqa: E402

from agent import general_as_of, preset  # noqa: E402
from agent.tree_ensemble import tree_agent_class  # noqa: E402


def main(seed: int, switch: int, out: str) -> None:
    warnings.simplefilter("ignore")
    config = general_as_of(17)
    env = gym.make("CartPole-v1")
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, preset("general").make_exploration(), seed,
        config,
    )
    start = time.process_time()
    history = agent.learn(env, switch, reset_seed=seed)
    agent.config = dataclasses.replace(agent.config, gamma=0.9995)
    history += agent.learn(env, 1000 - switch)
    returns = greedy(agent, env, 20, seed)
    with Path(out).open("a") as f:
        f.write(json.dumps({
            "task": "CartPole-v1", "label": f"switch{switch}", "seed": seed,
            "greedy": round(float(np.mean(returns)), 1),
            "train_last100": round(float(np.mean([h.episode_return for h in history[-100:]])), 1),
            "leaves": agent.n_leaves, "cpu": round(time.process_time() - start, 1),
            "greedy_all": [round(v) for v in returns],
        }) + "\n")


if __name__ == "__main__":
    main(int(sys.argv[1]), int(sys.argv[2]), sys.argv[3])
