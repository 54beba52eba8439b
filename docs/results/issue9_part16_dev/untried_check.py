"""Issue 9, part 16: how many (leaf, action) pairs are still untried when the goal first pays
on a maze (the general preset, 3 episodes). Output quoted in ``README.md``::

    python docs/results/issue9_part16_dev/untried_check.py paper 0
"""

import sys, gymnasium as gym, bullet_maze  # noqa
from agent import preset
from agent.optimism import UntriedOptimism
seen = {}
orig = UntriedOptimism.paid
def paid(self, value, q):
    if value > self.best and "first" not in seen:
        seen["first"] = (value, len(self.untried), sorted(self.untried))
    return orig(self, value, q)
UntriedOptimism.paid = paid
maze, seed = sys.argv[1], int(sys.argv[2])
env = gym.make("BulletMaze-v0", maze=maze, max_episode_steps=5000)
agent = preset("general").agent(env.observation_space, env.action_space, seed=seed)
h = agent.learn(env, 3, reset_seed=seed)
print(maze, seed, "bound first raised to", seen.get("first", (None,))[0], "untried then:", seen.get("first", (0, 0))[1], [x.steps for x in h])
