"""Part 31: find the first capped training episode after episode 300 of a dev maze run and log its
first decisions (position, leaf, action, Q-bar row, stored epochs, explored, reward, collision).
Ran at commit d885de3 (it sets greedy_tie_trial_on_entry, since removed):

    python stuck_probe.py "rooms:seed=2,door=14,loops=0" 0 0
"""
import dataclasses, json, sys, warnings
import gymnasium as gym
import numpy as np
sys.path.insert(0, str(__import__("pathlib").Path(__file__).resolve().parents[3]))
warnings.simplefilter("ignore")
import bullet_maze  # noqa
from agent import preset
from agent.tree_ensemble import tree_agent_class

layout, seed, entry = sys.argv[1], int(sys.argv[2]), sys.argv[3] == "1"

class Log(gym.Wrapper):
    def __init__(self, env):
        super().__init__(env)
        self.episode = -1
        self.watch = None
        self.rows = []
        self.agent = None
        self.obs = None
    def reset(self, **kw):
        self.episode += 1
        obs, info = self.env.reset(**kw)
        self.obs = obs
        return obs, info
    def step(self, action):
        if self.episode == self.watch and len(self.rows) < 400:
            a = self.agent
            leaves = a._leaves([float(v) for v in self.obs])
            row = a.mean_row(leaves)
            counts = a.fewest_epochs(a.members, leaves)
            self.rows.append((len(self.rows), [round(float(v), 1) for v in self.obs[:2]], leaves[0], int(action),
                              [round(q, 3) for q in row], counts, a.exploration.explored))
        obs, r, term, trunc, info = self.env.step(action)
        if self.episode == self.watch and len(self.rows) <= 400 and self.rows:
            self.rows[-1] = self.rows[-1] + (round(float(r), 3), bool(info.get("collision", False)))
        self.obs = obs
        return obs, r, term, trunc, info

def make(env):
    general = preset("general")
    config = dataclasses.replace(general.config, greedy_tie_trial_on_entry=entry)
    return tree_agent_class(config)(env.observation_space, env.action_space, general.make_exploration(), seed, config)

base = gym.make("BulletMaze-v0", maze=layout, max_episode_steps=5000)
env = Log(base)
agent = make(env)
env.agent = agent
history = []
for b in range(12):
    history += agent.learn(env, 50, reset_seed=seed * 1000 + b)
late = [e for e in range(300, 600) if history[e].steps >= 5000]
print("late capped", late, flush=True)
if not late:
    sys.exit()
e = late[0]
env = Log(base)
agent = make(env)
env.agent = agent
env.watch = e
for b in range(e // 50 + 1):
    agent.learn(env, 50, reset_seed=seed * 1000 + b)
print("trial slot", (e - 300) % 4 == 3, "steps", history[e].steps, "epochs", history[e].epochs)
for r in env.rows[:120]:
    print(r)
