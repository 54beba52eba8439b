"""Cost of the longer discount in the general agent (issue 9, part 11).

``gamma`` 0.999 with ``TreeConfig.scale_horizon`` 100 keeps the split test's unit but changes
every value, so the tree and the paths change with it. This prints, for the general preset and
for part 10's (gamma 0.99), the CPU seconds per 1,000 environment steps and per learning
episode over ``--episodes`` episodes, on MountainCar-v0 and on the ``paper`` maze, in
interleaved rounds, and the ratios preset / part 10 (median over rounds, with their range).

    python bench/bench_horizon.py                 # 3 rounds, about a minute
    python bench/bench_horizon.py --rounds 1 --episodes 100
"""

from __future__ import annotations

from bench_general import compare_main  # the same tasks and timing (bench/)

from agent import general_as_of


def main() -> None:
    compare_main(__doc__.split("\n\n")[0], "part 10", general_as_of(10), general_as_of(11))


if __name__ == "__main__":
    main()
