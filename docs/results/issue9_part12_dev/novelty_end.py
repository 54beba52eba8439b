"""When does the general preset's novelty end (its ``novelty_terminals``-th terminal epoch)?
(issue 9, part 12; development cases.) Trains until that moment, or for at most the run's
episodes, and prints the episode it ended in (None: never)::

    PYTHONPATH=. python docs/results/issue9_part12_dev/novelty_end.py classic MountainCar-v0 0
    PYTHONPATH=. python docs/results/issue9_part12_dev/novelty_end.py maze "forest:seed=0" 0
"""

from __future__ import annotations

import sys
import warnings

import gymnasium as gym

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from agent import adapt_env, preset
from agent.learner import SMDPAgent


class Ended(Exception):
    pass


def main(kind: str, case: str, seed: int) -> None:
    warnings.simplefilter("ignore")
    if kind == "maze":
        env, episodes = gym.make("BulletMaze-v0", maze=case, max_episode_steps=5000), 600
    else:
        env, episodes = adapt_env(gym.make(case)), 1000
    agent = preset("general").agent(env.observation_space, env.action_space, seed=seed)

    def stop(self: SMDPAgent) -> None:
        raise Ended(self.episodes_done)

    SMDPAgent._stop_novelty = stop  # type: ignore[method-assign]
    try:
        agent.learn(env, episodes, reset_seed=seed)
        ended = None
    except Ended as done:
        ended = int(done.args[0]) + 1  # the episode under way (1-based)
    print(f"{kind} {case} seed {seed}: novelty ended in episode {ended} of {episodes}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]))
