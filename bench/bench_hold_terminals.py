"""Cost of ending held exploration after n terminals (issue 9, part 8: the general preset).

``TreeConfig.hold_terminals`` moves the general preset onto
:class:`agent.tree_ensemble.TreeEnsembleAgent`'s loop, which part 6 measured about 11 %
slower per step than ``TreeAgent``'s on a maze, and it changes how many steps a run takes (an
exploratory detour ends sooner). This prints, for the general preset and for part 7's (the
same without ``hold_terminals``, on ``TreeAgent``'s loop), the CPU seconds per 1,000
environment steps and per learning episode over ``--episodes`` episodes, on MountainCar-v0 and
on the ``paper`` maze, in interleaved rounds (CPU time of this process, the agent built before
the clock starts), and the ratios preset / part 7 (median over rounds, with their range). The
two agents learn differently, so they take different steps.

    python bench/bench_hold_terminals.py                 # 3 rounds, about 30 seconds
    python bench/bench_hold_terminals.py --rounds 1 --episodes 100
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics

from bench_general import TASKS, learning_cost  # the same tasks and timing (bench/)

from agent import preset


def cost(task: str, part7: bool, episodes: int, seed: int) -> tuple[float, float]:
    """CPU seconds per 1,000 steps and per episode of ``episodes`` learning episodes of the
    general preset (``part7=True``: without ``hold_terminals``)."""
    config = preset("general").config
    if part7:
        config = dataclasses.replace(config, hold_terminals=None)
    cpu, steps = learning_cost(task, config, episodes, seed)
    return 1000.0 * cpu / steps, cpu / episodes


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--episodes", type=int, default=300)
    args = parser.parse_args()
    if args.rounds < 1 or args.episodes < 1:
        parser.error("--rounds and --episodes must be at least 1")
    for task in TASKS:
        rows: dict[bool, list[tuple[float, float]]] = {False: [], True: []}
        for seed in range(args.rounds):
            for part7 in (True, False):
                rows[part7].append(cost(task, part7, args.episodes, seed))
        step_ratio = [a[0] / b[0] for a, b in zip(rows[False], rows[True], strict=True)]
        episode_ratio = [a[1] / b[1] for a, b in zip(rows[False], rows[True], strict=True)]
        print(
            f"{task}: CPU-s / 1,000 steps {statistics.median(r[0] for r in rows[False]):.3f}"
            f" (part 7: {statistics.median(r[0] for r in rows[True]):.3f}), ratio"
            f" {statistics.median(step_ratio):.2f}x ({min(step_ratio):.2f}-{max(step_ratio):.2f});"
            f" CPU-s / episode {statistics.median(r[1] for r in rows[False]):.4f}"
            f" (part 7: {statistics.median(r[1] for r in rows[True]):.4f}), ratio"
            f" {statistics.median(episode_ratio):.2f}x"
            f" ({min(episode_ratio):.2f}-{max(episode_ratio):.2f})"
        )


if __name__ == "__main__":
    main()
