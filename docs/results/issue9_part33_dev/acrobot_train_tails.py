"""Part 33, d2's second follow-up: do training episodes stall too? The general preset on dev
Acrobot seeds 2 and 8 (the two with long greedy episodes in d2; 1,000 episodes, reset seed =
seed): the training episodes longer than 200 steps, per block of 100 and over episodes 500-999::

    python acrobot_train_tails.py
"""

import warnings, numpy as np, gymnasium as gym, json
from agent import adapt_env, preset
warnings.simplefilter("ignore")
out={}
for seed in (2, 8):
    env = adapt_env(gym.make("Acrobot-v1"))
    agent = preset("general").agent(env.observation_space, env.action_space, seed)
    h = agent.learn(env, 1000, reset_seed=seed)
    steps = np.array([x.steps for x in h])
    late = steps[500:]
    trial = agent.tie_trial
    out[seed] = {"late_mean": round(float(late.mean()),1), "late_over_200": int((late > 200).sum()),
                 "late_max": int(late.max()), "over_200_by_block": [int((steps[i:i+100] > 200).sum()) for i in range(0,1000,100)]}
    print(seed, out[seed], flush=True)
