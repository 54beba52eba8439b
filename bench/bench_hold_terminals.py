"""Cost of ending held exploration after n terminals (issue 9, part 8: the general preset).

``TreeConfig.hold_terminals`` moved the general preset onto
:class:`agent.tree_ensemble.TreeEnsembleAgent`'s loop, which part 6 measured about 11 %
slower per step than ``TreeAgent``'s on a maze, and it changes how many steps a run takes (an
exploratory detour ends sooner). This prints, for part 8's general preset (today's without
``model_split_epochs`` and novel ends) and for part 7's (that without ``hold_terminals``, on
``TreeAgent``'s loop), the CPU seconds per 1,000 environment steps and per learning episode
over ``--episodes`` episodes, on MountainCar-v0 and on the ``paper`` maze, in interleaved
rounds (CPU time of this process, the agent built before the clock starts), and the ratios
part 8 / part 7 (median over rounds, with their range). The two agents learn differently, so
they take different steps.

    python bench/bench_hold_terminals.py                 # 3 rounds, about 30 seconds
    python bench/bench_hold_terminals.py --rounds 1 --episodes 100
"""

from __future__ import annotations

from bench_general import compare_main  # the same tasks and timing (bench/)

from agent import general_as_of


def main() -> None:
    compare_main(__doc__.split("\n\n")[0], "part 7", general_as_of(7), general_as_of(8))


if __name__ == "__main__":
    main()
