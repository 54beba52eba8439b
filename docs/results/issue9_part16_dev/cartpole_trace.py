"""Issue 9, part 16: where on CartPole (dev agent seed SEED, 60 episodes) the runs with and
without ``optimistic_untried`` first differ, and each rise of the bound (old, new, untried
pairs then, leaves moved). Output quoted in ``README.md``::

    python docs/results/issue9_part16_dev/cartpole_trace.py 0
"""

import dataclasses, gymnasium as gym, sys
from agent import general_as_of
from agent.optimism import UntriedOptimism
from agent.tree_ensemble import tree_agent_class
raised = []
orig = UntriedOptimism.paid
def paid(self, value, q):
    before = self.best
    moved = orig(self, value, q)
    if self.best > before:
        raised.append((round(before, 3), round(self.best, 3), len(self.untried), len(moved)))
    return moved
UntriedOptimism.paid = paid
seed = int(sys.argv[1])
runs = {}
for part in (16, 15):
    env = gym.make("CartPole-v1")
    cfg = general_as_of(part)
    a = tree_agent_class(cfg)(env.observation_space, env.action_space, "adaptive+tabu", seed, cfg)
    h = a.learn(env, 60, reset_seed=seed)
    runs[part] = [x.episode_return for x in h]
    if part == 16:
        print("untried at start:", 16 * 2, "after 60 eps:", len(a.optimism.untried), "bound", a.optimism.best)
first = next((i for i, (x, y) in enumerate(zip(runs[16], runs[15])) if x != y), None)
print("first differing episode:", first, "raises:", raised[:12])
