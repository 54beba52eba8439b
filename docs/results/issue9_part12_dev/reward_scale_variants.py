import json
import sys
import time

import gymnasium as gym
import numpy as np
from gymnasium.wrappers import TransformReward

from agent import preset

name, seed = sys.argv[1], int(sys.argv[2])


def make():
    if name == "cp0":
        return gym.make("CartPole-v0")
    if name == "mc_x100":
        return TransformReward(gym.make("MountainCar-v0"), lambda r: 100 * r)
    if name == "mc_500":
        return gym.make("MountainCar-v0", max_episode_steps=500)
    if name == "acro_x001":
        return TransformReward(gym.make("Acrobot-v1"), lambda r: 0.01 * r)
    if name == "acro_x025":
        return TransformReward(gym.make("Acrobot-v1"), lambda r: 0.25 * r)
    if name == "acro_x100":
        return TransformReward(gym.make("Acrobot-v1"), lambda r: 100 * r)
    if name == "cp_shift":
        return TransformReward(gym.make("CartPole-v1"), lambda r: r + 10)


env = make()
ag = preset("general").agent(env.observation_space, env.action_space, seed=seed)
t = time.process_time()
h = ag.learn(env, 1000, reset_seed=seed)
cpu = time.process_time() - t
env2 = make()
rets = []
for i in range(20):
    o, _ = env2.reset(seed=10**6 + 1000 * seed + i)
    R = 0
    done = False
    n = 0
    while not done:
        o, r, te, tr, _ = env2.step(ag.predict(o))
        R += r
        n += 1
        done = te or tr
    rets.append(n)
print(
    json.dumps(
        {
            "v": name,
            "seed": seed,
            "greedy_steps": float(np.mean(rets)),
            "leaves": ag.n_leaves,
            "cpu": round(cpu, 1),
        }
    ),
    flush=True,
)
