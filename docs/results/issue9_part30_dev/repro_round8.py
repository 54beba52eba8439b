"""Does the library's greedy_tie_trial reproduce round 8's probe on a maze run?"""
import dataclasses, json, sys, warnings
import gymnasium as gym, numpy as np
import bullet_maze  # noqa
from agent import preset
from agent.tree_ensemble import tree_agent_class
warnings.simplefilter("ignore")
layout, seed = sys.argv[1], int(sys.argv[2])
env = gym.make("BulletMaze-v0", maze=layout, max_episode_steps=5000)
g = preset("general")
cfg = dataclasses.replace(g.config, greedy_tie_trial=2.0, greedy_tie_trial_episodes=300)
agent = tree_agent_class(cfg)(env.observation_space, env.action_space, g.make_exploration(), seed, cfg)
for b in range(12):
    agent.learn(env, 50, reset_seed=seed * 1000 + b)
diff, se = agent.tie_trial.difference()
greedy = []
for i in range(10):
    obs, _ = env.reset(seed=10**6 + i); n, done = 0, False
    while not done:
        obs, _, te, tr, _ = env.step(agent.predict(obs)); n += 1; done = te or tr
    greedy.append(n)
print(json.dumps({"diff": round(diff, 4), "se": round(se, 4), "adopted": agent.tie_trial.adopted,
  "sel": round(float(np.mean(greedy)) / env.unwrapped.optimal_steps, 3)}))
