"""Issue 9, part 15 (development): FrozenLake-v1's true values (value iteration on the env's
own table, gamma 0.999) against the general preset's Q-bar after 1,000 episodes (agent seeds
1 and 2), per cell and action, with the model's epoch counts. Output in ``fl_values.txt``::

    python docs/results/issue9_part15_dev/fl_values.py
"""
import gymnasium as gym, numpy as np, warnings
from agent import adapt_env, preset
from agent.tree_ensemble import tree_agent_class
warnings.simplefilter("ignore")
env = adapt_env(gym.make("FrozenLake-v1"))
P = env.unwrapped.P
V = np.zeros(16)
for _ in range(2000):
    Q = np.array([[sum(p*(r+0.999*V[s2]*(not d)) for p,s2,r,d in P[s][a]) for a in range(4)] for s in range(16)])
    V = Q.max(1)
opt = Q.argmax(1)
print("opt", opt.reshape(4,4).tolist(), V.round(2).reshape(4,4).tolist())
cfg = preset("general").config
for seed in (1, 2):
    a = tree_agent_class(cfg)(env.observation_space, env.action_space, "adaptive+tabu", seed, cfg)
    a.learn(env, 1000, reset_seed=seed)
    g = [a.predict(np.array([s])) for s in range(16)]
    print("seed", seed, "greedy", np.array(g).reshape(4,4).tolist())
    # value of greedy policy
    Vg = np.zeros(16)
    for _ in range(2000):
        Vg = np.array([sum(p*(r+0.999*Vg[s2]*(not d)) for p,s2,r,d in P[s][g[s]]) for s in range(16)])
    print("  V(greedy) start", Vg[0].round(3), "opt", V[0].round(3))
    for s in range(16):
        leaf = a.partition.leaf_of([float(s)])
        print("  s", s, "q", np.round(a.q[leaf], 3), "Qopt", np.round(Q[s], 3), "n", a.visits[leaf] if hasattr(a,'visits') else None)
