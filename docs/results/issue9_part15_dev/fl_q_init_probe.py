"""Issue 9, part 15 (development probe, nothing built): the general preset of part 15 with a
hand-set ``q_init`` on TASK, agent seeds 0-2, 1,000 episodes, greedy return over 100
episodes::

    python docs/results/issue9_part15_dev/fl_q_init_probe.py FrozenLake-v1 1.0
"""

import dataclasses
import sys
import warnings

import gymnasium as gym
import numpy as np

from agent import adapt_env, general_as_of
from agent.tree_ensemble import tree_agent_class


def main(task: str, q_init: float) -> None:
    warnings.simplefilter("ignore")
    env = adapt_env(gym.make(task))
    config = dataclasses.replace(general_as_of(15), q_init=q_init)
    for seed in (0, 1, 2):
        agent = tree_agent_class(config)(
            env.observation_space, env.action_space, "adaptive+tabu", seed, config
        )
        history = agent.learn(env, 1000, reset_seed=seed)
        returns = []
        for i in range(100):
            obs, _ = env.reset(seed=10**6 + 1000 * seed + i)
            done, total = False, 0.0
            while not done:
                obs, reward, terminated, truncated, _ = env.step(agent.predict(obs))
                total += float(reward)
                done = terminated or truncated
            returns.append(total)
        last = np.mean([h.episode_return for h in history[-100:]])
        print(
            task, "q_init", q_init, "seed", seed, "greedy", np.mean(returns), "train last100", last
        )


if __name__ == "__main__":
    main(sys.argv[1], float(sys.argv[2]))
