"""Cost of the greedy choice's options in ``predict``: among supported actions
(``TreeConfig.greedy_min_epochs`` and ``greedy_cell_epochs``, issue 9, parts 23 and 24), with
neighbours breaking the actions' ties (``greedy_smoothing``, ``greedy_smoothing_links`` and
``greedy_tie_errors``, part 25) and with the tree's ancestors breaking them
(``greedy_tie_ancestors``, part 27).

One agent of the general preset learns MountainCar-v0 (and one the ``paper`` maze, and one Taxi-v4,
whose integer input makes every leaf a single-input cell); then ``predict`` is timed on the same
random states with the general preset as it was after part 22 (no option), after part 24 (2 epochs,
1 in a cell), after part 25 (the neighbours) and now (``agent.general_as_of``), in interleaved
rounds (CPU time of this process). What ``predict`` caches (part 27's per-node sums, part 28's
choices and leaf standard errors) is dropped before each timing, so every round pays for building
it, as a first evaluation after training does; today's preset is also timed with its choice and
the standard errors computed afresh at every call (``27-uncached``: ``predict`` before part 28's
caches). Training is the same either way (the options change no training step), so only
``predict`` is timed. Prints microseconds per call and the ratios to part 22's (median over
rounds, with its range). Random states reach leaves
the agent barely visited, where most actions are statistical ties; so it also times what a user
sees, whole greedy episodes (the environment's steps included, ``experiments.evaluation.evaluate``
from reset seed 0), per part and round.

    python bench/bench_greedy_choice.py             # 5 rounds, about two minutes
    python bench/bench_greedy_choice.py --rounds 3 --episodes 100
"""

from __future__ import annotations

import argparse
import statistics
import time
from typing import Any

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa: F401 (registers BulletMaze-v0)
from agent import TreeConfig, adapt_env, general_as_of, preset
from agent.tree_ensemble import tree_agent_class
from experiments.evaluation import evaluate

TASKS = {
    "MountainCar-v0": {},
    "BulletMaze-v0": {"maze": "paper", "max_episode_steps": 5000},
    "Taxi-v4": {},
}


def _bypass_caches(agent: Any) -> None:
    """``27-uncached``: ``predict`` as before part 28, every choice and standard error computed
    afresh (instance attributes over the class's cached methods)."""
    z = agent.config.greedy_tie_ancestors

    def choice(x: Any, agents: Any, leaves: Any, row: Any, *_: Any) -> int:
        return int(agent._ancestors_rule(agents, leaves, row, z))

    agent.cached_errors = agent.action_errors
    agent._greedy_choice = choice


def _restore_caches(agent: object) -> None:
    """Undo the ``27-uncached`` round's overrides (the class's cached methods again)."""
    for name in ("cached_errors", "_greedy_choice"):
        vars(agent).pop(name, None)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=5, help="interleaved rounds (5)")
    parser.add_argument("--episodes", type=int, default=200, help="training episodes (200)")
    parser.add_argument("--calls", type=int, default=20000, help="predict calls a round (20,000)")
    parser.add_argument(
        "--eval-episodes", type=int, default=10, help="greedy episodes timed a round (10)"
    )
    args = parser.parse_args()
    if min(args.rounds, args.episodes, args.calls, args.eval_episodes) < 1:
        parser.error("--rounds, --episodes, --calls and --eval-episodes must be at least 1")
    general = preset("general")
    for task, kwargs in TASKS.items():
        env = adapt_env(gym.make(task, **kwargs))  # Taxi's index as one integer input
        agent = tree_agent_class(general.config)(
            env.observation_space, env.action_space, general.make_exploration(), 0, general.config
        )
        agent.learn(env, args.episodes, reset_seed=0)
        space = env.observation_space
        low = np.maximum(space.low, -10.0)  # type: ignore[attr-defined]
        high = np.minimum(space.high, 10.0)  # type: ignore[attr-defined]
        states = np.random.default_rng(0).uniform(low, high, size=(args.calls, len(low)))
        if np.issubdtype(space.dtype, np.integer):  # type: ignore[arg-type]
            states = np.rint(states).astype(space.dtype)
        configs: dict[int | str, TreeConfig] = {
            22: general_as_of(22),
            24: general_as_of(24),
            25: general_as_of(26),
            27: general.config,
            "27-uncached": general.config,
        }
        times: dict[int | str, list[float]] = {part: [] for part in configs}
        episode_ms: dict[int | str, list[float]] = {part: [] for part in configs}
        steps = dict.fromkeys(configs, 0)
        changed = dict.fromkeys(configs, 0)
        for _ in range(args.rounds):
            chosen = {}
            for part, config in configs.items():
                agent.config = config
                if part == "27-uncached":  # every call computes its choice and errors afresh
                    _bypass_caches(agent)
                else:
                    _restore_caches(agent)
                agent.forget_greedy_cache()
                start = time.process_time()
                chosen[part] = [agent.predict(s) for s in states]
                times[part].append((time.process_time() - start) / args.calls * 1e6)
                agent.forget_greedy_cache()
                start = time.process_time()
                greedy = evaluate(env, agent, args.eval_episodes, seed=0)
                episode_ms[part].append((time.process_time() - start) / args.eval_episodes * 1e3)
                steps[part] = sum(e.steps for e in greedy.episodes)
            for part in configs:
                changed[part] = sum(a != b for a, b in zip(chosen[22], chosen[part], strict=True))
        agent.config = general.config
        _restore_caches(agent)
        cells, episodes = [], []
        for part in (24, 25, "27-uncached", 27):
            ratios = [new / old for new, old in zip(times[part], times[22], strict=True)]
            cells.append(
                f"part {part}'s {statistics.median(times[part]):.1f} us, ratio "
                f"{statistics.median(ratios):.3f} [{min(ratios):.3f}, {max(ratios):.3f}], "
                f"{changed[part]} states choose another action"
            )
            ratios = [new / old for new, old in zip(episode_ms[part], episode_ms[22], strict=True)]
            episodes.append(
                f"part {part}'s {statistics.median(episode_ms[part]):.2f} ms "
                f"({steps[part] / args.eval_episodes:.0f} steps), ratio "
                f"{statistics.median(ratios):.3f} [{min(ratios):.3f}, {max(ratios):.3f}]"
            )
        print(
            f"{task}: {agent.n_leaves} leaves after {args.episodes} episodes; predict: part 22's "
            f"{statistics.median(times[22]):.1f} us; "
            + "; ".join(cells)
            + f" (of {args.calls:,} random states)"
        )
        print(
            f"{task}: a greedy episode with the environment's steps: part 22's "
            f"{statistics.median(episode_ms[22]):.2f} ms "
            f"({steps[22] / args.eval_episodes:.0f} steps); " + "; ".join(episodes)
        )
        cache = [
            statistics.median(
                new / old for new, old in zip(series[27], series["27-uncached"], strict=True)
            )
            for series in (times, episode_ms)
        ]
        print(
            f"{task}: part 28's caches (choices and errors): predict {cache[0]:.3f}x and a greedy "
            f"episode {cache[1]:.3f}x the time without it (median over rounds)"
        )
        env.close()


if __name__ == "__main__":
    main()
