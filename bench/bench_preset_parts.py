"""Cost of each change issue 9 made to the general preset from part 8 on, one part at a time.

For part N, the general preset as it was after part N (``agent.general_as_of(N)``) against
the preset after part N - 1 (the fields of ``agent.presets.GENERAL_CHANGES[N]`` at their
earlier values): CPU seconds per 1,000 environment steps and per learning episode over
``--episodes`` episodes, on MountainCar-v0, on the ``paper`` maze and on Taxi-v4, in
interleaved rounds (agent and reset seed = the round; CPU time of this process, the agent
built before the clock starts), and the ratios part N / part N - 1 (median over rounds, with
their range). The two agents learn differently, so they take different steps; what each part
changed is in :data:`PARTS`.

    python bench/bench_preset_parts.py --part 11          # 3 rounds, about a minute
    python bench/bench_preset_parts.py --part 9 --rounds 1 --episodes 100
    python bench/bench_preset_parts.py                    # every part, in order
"""

from __future__ import annotations

import argparse

from bench_general import compare  # the same tasks and timing (bench/)

from agent import general_as_of
from agent.presets import GENERAL_CHANGES

PARTS: dict[int, str] = {
    8: "hold_terminals: held exploration ends after 100 terminals; the preset moves onto "
    "TreeEnsembleAgent's loop (part 6 measured it about 11 % slower per step on a maze), and an "
    "exploratory detour ends sooner",
    9: "model_split_epochs: after each epoch that did not split, the stored epochs of its "
    "(leaf, action) are valued and the best cut along every input is tested, in Python; the "
    "tree grown changes with it",
    10: "novelty_cells: every input counted on a grid until the 10th terminal epoch "
    "(agent/novelty.py), and the novel ends it stores change the values, the paths and the tree",
    11: "gamma 0.999 with the unit's horizon kept at 100: the discount costs nothing itself; "
    "the tree it grows differs",
    12: "novelty_episodes: the novel ends also stop after 100 episodes; on these two tasks the "
    "10th terminal comes first, so the runs should be the same",
    14: "collision_splits: after an epoch that ended on a collision, that (leaf, action)'s "
    "stored epochs are searched for a separating cut, in Python; MountainCar reports no "
    "collisions, so its runs should be the same, and on the maze the tree grown changes",
    15: "table_cells: Taxi's 500 integer states start as a table (built before the clock "
    "starts); MountainCar and the maze have float inputs, so their runs should be the same",
    16: "optimistic_untried: each epoch's largest return is computed and untried actions are "
    "raised when it sets a new bound; MountainCar pays at most 0, so its runs should be the "
    "same; on the maze the goal's +5 sets the bound once the actions are tried",
    17: "presplit_max_dimensions 8, presplit_beyond_dimensions 4: only an input of more than 8 "
    "dimensions is presplit differently (part 16's preset refused more than 16); MountainCar, "
    "the maze and Taxi have at most 2, so their runs should be the same",
    19: "failure_gamma 0.9995: each epoch's one-step target is summed for the failure measure "
    "(one max over the next row); MountainCar's, the maze's and Taxi's terminals are goals, so "
    "the latch stays shut and their runs should be the same",
    20: "failure_measure 'every': the largest terminal reward is kept beside the sum; the latch "
    "stays shut on all three tasks, so their runs should be the same",
    23: "greedy_min_epochs 1: only predict's greedy choice reads the model's counts; no training "
    "step changes, so every run should be the same (bench/bench_greedy_choice.py times predict)",
    24: "greedy_min_epochs 2, greedy_cell_epochs 1: predict's greedy choice asks two stored "
    "epochs (one in a single-input leaf); no training step changes, so every run should be the "
    "same",
    25: "greedy_smoothing 1 with links and greedy_tie_errors 0.5: predict's greedy choice reads "
    "the leaf's standard errors and, at a tie, its linked neighbours' rows; no training step "
    "changes, so every run should be the same",
    27: "greedy_tie_ancestors 1 in place of part 25's neighbours: predict's ties are broken by "
    "the tree's ancestors, leaf by leaf; no training step changes, so every run should be the "
    "same",
    30: "greedy_tie_trial 2: from episode 300, one training episode in 4 breaks its greedy "
    "ties at z 2 (the leaf's standard errors and the ancestors' sums at each decision); a run "
    "of at most 300 episodes is the same run, so time it with --episodes 600",
    32: "greedy_tie_trial_avoid_collided: a trial episode keeps a set of the choices that "
    "collided without leaving their leaf; only runs past episode 300 on a maze change, so time "
    "it with --episodes 600",
    36: "split_min_samples 50: the eqs. (12)-(13) split test runs on half as many new pairs, so "
    "the tree grows sooner and larger; every run changes, and its cost is the larger tree's "
    "(part 35 measured training CPU at 0.95-1.14x on its dev cases)",
}
"""What part N changed in the preset, and where its cost was expected to come from."""

assert set(PARTS) == set(GENERAL_CHANGES), "a part of GENERAL_CHANGES has no description"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--part", type=int, choices=sorted(PARTS), help="one part (default: every part)"
    )
    parser.add_argument("--rounds", type=int, default=3, help="interleaved rounds (3)")
    parser.add_argument("--episodes", type=int, default=300, help="episodes a run (300)")
    args = parser.parse_args()
    if args.rounds < 1 or args.episodes < 1:
        parser.error("--rounds and --episodes must be at least 1")
    for part in [args.part] if args.part is not None else sorted(PARTS):
        print(f"part {part} against part {part - 1}: {PARTS[part]}")
        compare(
            f"part {part - 1}",
            general_as_of(part - 1),
            general_as_of(part),
            args.rounds,
            args.episodes,
        )


if __name__ == "__main__":
    main()
