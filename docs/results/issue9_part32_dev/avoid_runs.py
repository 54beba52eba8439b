"""Part 32's round 1 dev runs: the general preset (part 30's) with
``greedy_tie_trial_avoid_collided`` on. Rows and protocol are part 31's ``entry_runs.py``'s
(``ENTRY=0`` there is the preset as it stands, option off).

    python avoid_runs.py maze:LAYOUT OUT SEED [SEED ...]
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "issue9_part31_dev"))
import entry_runs  # noqa: E402

from agent import preset  # noqa: E402
from agent.tree_ensemble import tree_agent_class  # noqa: E402


def make_agent(env, seed: int):
    general = preset("general")
    config = dataclasses.replace(general.config, greedy_tie_trial_avoid_collided=True)
    return tree_agent_class(config)(
        env.observation_space, env.action_space, general.make_exploration(), seed, config
    )


if __name__ == "__main__":
    entry_runs.ENTRY = False
    entry_runs.make_agent = make_agent
    entry_runs.main(sys.argv)
