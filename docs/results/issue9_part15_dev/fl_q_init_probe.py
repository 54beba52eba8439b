"""Issue 9, part 15 (development probe, nothing built): the general preset with a hand-set
``q_init`` on TASK, agent seeds 0-2, 1,000 episodes, greedy return over 100 episodes::

    python docs/results/issue9_part15_dev/fl_q_init_probe.py FrozenLake-v1 1.0
"""
import gymnasium as gym, numpy as np, warnings, dataclasses, sys
from agent import adapt_env, preset
from agent.tree_ensemble import tree_agent_class
warnings.simplefilter("ignore")
env = adapt_env(gym.make(sys.argv[1]))
qi = float(sys.argv[2])
cfg = dataclasses.replace(preset("general").config, q_init=qi)
for seed in (0, 1, 2):
    a = tree_agent_class(cfg)(env.observation_space, env.action_space, "adaptive+tabu", seed, cfg)
    h = a.learn(env, 1000, reset_seed=seed)
    rets = []
    for i in range(100):
        obs, _ = env.reset(seed=10**6 + 1000*seed + i); done=False; tot=0
        while not done:
            obs, r, te, tr, _ = env.step(a.predict(obs)); tot += r; done = te or tr
        rets.append(tot)
    print(sys.argv[1], "q_init", qi, "seed", seed, "greedy", np.mean(rets), "train last100", np.mean([x.episode_return for x in h[-100:]]), flush=True)
