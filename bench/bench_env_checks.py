"""The cost of checking what a user's env hands an agent (issue 9, part 39; ``agent.env_checks``).

``learn`` wraps a user's env in :class:`agent.env_checks.CheckedEnv`, which checks every
``reset`` and ``step`` result before the agent reads it. This prints, per learner and task, the
CPU seconds of ``--episodes`` learning episodes with the check and with it taken out, in
interleaved rounds (agent and reset seed = the round; CPU time of this process, the agent built
before the clock starts), their ratio (median over rounds, with its range), and whether the two
runs of each round ended the same (they must: the check only reads). The tile coder is the
fastest learner per step, so its ratio is the upper bound of the check's cost.

    python bench/bench_env_checks.py                 # 3 rounds, about 2 minutes
    python bench/bench_env_checks.py --rounds 1 --episodes 20
"""

from __future__ import annotations

import argparse
import dataclasses
import gc
import time
from typing import Any

import gymnasium as gym
from ab_rounds import ab_rounds  # bench/ is the script's folder
from bench_agent import TrivialEnv

import agent.adaptive_q
import agent.learner
import agent.tile_coding
from agent import TileCodingAgent, TreeAgent, adapt_env, preset
from agent.env_checks import CheckedEnv

CASES = (
    ("general", "Acrobot-v1", 100),
    ("tile", "CartPole-v1", 300),
    ("tile", "Acrobot-v1", 100),
    ("paper", "trivial", 20),
)
"""(learner, task, default episodes). ``trivial`` is ``bench_agent.TrivialEnv`` (a pure-Python
point in a box at about a million steps/s, 5,000-step episodes): the check's cost per step
beside an env that costs almost nothing, the paper's tree capped at 500 leaves."""
MODULES = (agent.learner, agent.tile_coding, agent.adaptive_q)


def _unchecked(env: Any, n_inputs: int, bounds: Any = None) -> Any:
    return env


def learning_run(
    kind: str, task: str, checked: bool, episodes: int, seed: int
) -> tuple[float, Any]:
    """CPU seconds of ``episodes`` learning episodes, and what the run ended with."""
    for module in MODULES:
        module.CheckedEnv = CheckedEnv if checked else _unchecked  # type: ignore[attr-defined]
    try:
        env = TrivialEnv() if task == "trivial" else adapt_env(gym.make(task))
        if task == "trivial":
            config = dataclasses.replace(preset(kind).config, max_leaves=500)
            learner: Any = TreeAgent(
                env.observation_space, env.action_space, "adaptive+tabu", seed, config
            )
        elif kind == "tile":
            learner = TileCodingAgent(env.observation_space, env.action_space, seed)
        else:
            learner = preset(kind).agent(env.observation_space, env.action_space, seed)
        gc.collect()
        start = time.process_time()
        history = learner.learn(env, episodes, reset_seed=seed)
        cpu = time.process_time() - start
        if task != "trivial":
            env.close()
    finally:
        for module in MODULES:
            module.CheckedEnv = CheckedEnv  # type: ignore[attr-defined]
    return cpu, ([h.steps for h in history], [h.episode_return for h in history])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument(
        "--episodes", type=int, default=None, help="episodes a run (default: per case)"
    )
    args = parser.parse_args()
    print(f"{args.rounds} interleaved rounds")
    print(
        "learner, task | episodes | CPU-s unchecked | checked | ratio (median, range) | same runs"
    )
    for kind, task, default_episodes in CASES:
        episodes = args.episodes or default_episodes

        def run(
            checked: bool, seed: int, kind: str = kind, task: str = task, episodes: int = episodes
        ) -> Any:
            return learning_run(kind, task, checked, episodes, seed)

        row = ab_rounds(run, args.rounds)
        print(f"{kind}, {task} | {episodes} | {row.cells(digits=3)}")


if __name__ == "__main__":
    main()
