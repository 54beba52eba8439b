"""Cost of novel ends in the general agent (issue 9, part 10).

``TreeConfig.novelty_cells`` counts every input on a grid until ``novelty_terminals`` terminal
epochs (``agent/novelty.py``), then stops; the novel ends it stores change the values, the
paths and so the tree. This prints, for the general preset and for part 9's (the same without
novel ends), the CPU seconds per 1,000 environment steps and per learning episode over
``--episodes`` episodes, on MountainCar-v0 and on the ``paper`` maze, in interleaved rounds,
and the ratios preset / part 9 (median over rounds, with their range).

    python bench/bench_novelty.py                 # 3 rounds, about a minute
    python bench/bench_novelty.py --rounds 1 --episodes 100
"""

from __future__ import annotations

from bench_general import compare_main  # the same tasks and timing (bench/)

from agent import general_as_of


def main() -> None:
    compare_main(__doc__.split("\n\n")[0], "part 9", general_as_of(9), general_as_of(10))


if __name__ == "__main__":
    main()
