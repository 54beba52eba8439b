"""Part 35, d1: how often the sweep budget binds on Acrobot (today's preset with BACKUPS sweep
backups, seed 0, four blocks of 100 episodes from reset seeds 0-3). Per block: sweeps, backups,
sweeps that ended with the budget spent and leaves still queued ("bound"), the queued leaves
left at those sweeps (summed, "left"), and the leaves.

    python sweep_budget_probe.py 64
"""

import dataclasses, warnings, sys, collections
import gymnasium as gym
from agent import adapt_env, preset
from agent.tree_ensemble import tree_agent_class
from agent import leaf_model
warnings.simplefilter("ignore")
stats = collections.Counter()
orig = leaf_model.LeafModel.sweep
def sweep(self, q, budget, tol, bonus=None):
    done = orig(self, q, budget, tol, bonus)
    stats["sweeps"] += 1
    stats["backups"] += done
    if self._queue and done >= budget:
        stats["bound"] += 1
        stats["left"] += len(self._priority)
    return done
leaf_model.LeafModel.sweep = sweep
g = preset("general")
cfg = dataclasses.replace(g.config, sweep_backups=int(sys.argv[1]))
env = adapt_env(gym.make("Acrobot-v1"))
agent = tree_agent_class(cfg)(env.observation_space, env.action_space, g.make_exploration(), 0, cfg)
for block in range(4):
    agent.learn(env, 100, reset_seed=block)
    print(block, dict(stats), agent.n_leaves, flush=True)
    stats.clear()
