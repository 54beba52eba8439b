"""Part 17's classic driver (development only): part 4's ``dev.run`` on a task whose
observation is its last ``k`` frames (``gymnasium.wrappers.FrameStackObservation``, flattened
by ``agent.adapt_env``: CartPole with k = 4 has 16 inputs), from ``general_as_of(16)`` with
``overrides``, 1,000 episodes, 20 greedy episodes::

    python docs/results/issue9_part17_dev/frame_stack.py TASK K SEED LABEL OVERRIDES_JSON OUT
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import gymnasium as gym

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "issue9_classic_dev"))

from dev import run  # noqa: E402

from agent import adapt_env, general_as_of  # noqa: E402


def stacked(k: int):  # noqa: ANN201
    """The wrapper: the last ``k`` observations, flattened into one Box."""
    return lambda env: adapt_env(gym.wrappers.FrameStackObservation(env, k), None)


if __name__ == "__main__":
    task, k, seed, label, overrides, out = sys.argv[1:7]
    run(
        task,
        f"{label}",
        {**json.loads(overrides)},
        int(seed),
        out=Path(out),
        wrap=stacked(int(k)),
        base=general_as_of(16),
    )
