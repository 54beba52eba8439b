"""Cost of model-driven splits in the general agent (issue 9, part 9).

``TreeConfig.model_split_epochs`` tests, after each epoch that did not split, the stored epochs
of the epoch's (leaf, action): their targets under the current values and the best cut along
every input dimension (``agent/model_split.py``), in Python. It also changes the tree the agent
grows, and so the cost of everything else. This prints, for part 9's general preset (today's
without novel ends) and for part 8's (that without ``model_split_epochs``), the CPU seconds per
1,000 environment steps and per learning episode over ``--episodes`` episodes, on
MountainCar-v0 and on the ``paper`` maze, in interleaved rounds, and the ratios part 9 / part 8
(median over rounds, with their range).

    python bench/bench_model_split.py                 # 3 rounds, about a minute
    python bench/bench_model_split.py --rounds 1 --episodes 100
"""

from __future__ import annotations

from bench_general import compare_main  # the same tasks and timing (bench/)

from agent import general_as_of


def main() -> None:
    compare_main(__doc__.split("\n\n")[0], "part 8", general_as_of(8), general_as_of(9))


if __name__ == "__main__":
    main()
