"""Part 31's dev runs: the general preset (part 30's) with ``greedy_tie_trial_follow`` on.

Part 30's driver (``issue9_part30_dev/trial_runs.py``) with its candidate replaced: the same
training protocols and the same three scores (``sel``, ``z1``, ``z2``).

    python follow_runs.py TASK OUT SEED [SEED ...]
    python follow_runs.py maze:LAYOUT OUT SEED [SEED ...]
"""

from __future__ import annotations

import dataclasses
import os
import sys
from pathlib import Path

from agent import preset
from agent.tree_ensemble import tree_agent_class

os.environ.setdefault("TRIAL_EVERY", "4")  # the preset's; the driver writes it in each row
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "issue9_part30_dev"))
import trial_runs  # noqa: E402


def candidate(env, seed: int):
    general = preset("general")
    config = dataclasses.replace(general.config, greedy_tie_trial_follow=True)
    return tree_agent_class(config)(
        env.observation_space, env.action_space, general.make_exploration(), seed, config
    )


if __name__ == "__main__":
    trial_runs.candidate = candidate
    trial_runs.main(sys.argv)
