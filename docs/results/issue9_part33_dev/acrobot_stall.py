"""Part 33, d2's follow-up: the 500-step greedy episode of dev Acrobot seed 2 (the general
preset, 1,000 episodes; reset seed 1,000,000 + 2,000): its leaf period up to 200 steps, the
nearest earlier state to its last one, the tip's greatest height in each 50 steps (the goal is
above 1.0), its last 60 actions, and the ten leaves it visits most over its last 300 steps
(visits, widths as fractions of the observation box, Q-bar per action, stored epochs per
action)::

    python acrobot_stall.py
"""

import warnings, numpy as np, gymnasium as gym
from agent import adapt_env, preset
warnings.simplefilter("ignore")
seed=2
env = adapt_env(gym.make("Acrobot-v1"))
agent = preset("general").agent(env.observation_space, env.action_space, seed)
agent.learn(env, 1000, reset_seed=seed)
obs,_ = env.reset(seed=1_000_000 + 1000*seed + 0)
S=[np.asarray(obs,float)]; L=[agent.leaf_of(obs)]; A=[]
done=False
while not done:
    a=agent.predict(obs); A.append(a)
    obs,r,t,tr,_=env.step(a); done=t or tr
    S.append(np.asarray(obs,float)); L.append(agent.leaf_of(obs))
S=np.array(S); print(len(S)-1)
tail=L[-300:]
for p in range(1,201):
    if all(tail[t]==tail[t-p] for t in range(p,len(tail))): print("leaf period",p); break
else: print("no leaf period <=200")
# state near-recurrence: min distance between last state and states 20..250 steps before
last=S[-1]; d=[(k, float(np.abs(S[-1-k]-last).max())) for k in range(10,250)]
d.sort(key=lambda x:x[1]); print("nearest earlier states", d[:5])
# heights: -cos(t1) - cos(t1+t2)
c1,s1,c2,s2=S[:,0],S[:,1],S[:,2],S[:,3]
h=-c1-(c1*c2-s1*s2)
for k in range(0,500,50): print(k, round(float(h[k:k+50].max()),3), end="; ")
print()
print("distinct leaves last 300:", len(set(tail)), "actions last 60:", A[-60:])
# the stall's leaves: widths relative to the root box, epochs stored, Q gaps
import collections
cnt = collections.Counter(L[-300:])
space = env.observation_space
rng_ = np.asarray(space.high, float) - np.asarray(space.low, float)
rows=[]
for leaf, n in cnt.most_common(10):
    lo, hi = agent.partition.leaf_bounds(leaf)
    w = (np.asarray(hi) - np.asarray(lo)) / rng_
    q = agent.q[leaf]
    ep = [len(agent.model._records.get(leaf * agent.n_actions + a, ())) for a in range(agent.n_actions)]
    rows.append((leaf, n, np.round(w, 3).tolist(), [round(x, 2) for x in q], ep))
for r in rows: print(r)
print("leaves", agent.n_leaves)
