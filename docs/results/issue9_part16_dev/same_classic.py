"""Issue 9, part 16: MountainCar and Acrobot pay at most 0 a step, so the optimism's bound
never rises and the general preset with and without ``optimistic_untried`` must take the same
run. Checked at the held-out scale (1,000 episodes, agent seed 0): returns, Q-bar and leaves::

    python docs/results/issue9_part16_dev/same_classic.py
"""

import gymnasium as gym

from agent import general_as_of
from agent.tree_ensemble import tree_agent_class


def run(task: str, part: int) -> tuple[list[float], list[list[float]], int]:
    env = gym.make(task)
    config = general_as_of(part)
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, "adaptive+tabu", 0, config
    )
    history = agent.learn(env, 1000, reset_seed=0)
    return [h.episode_return for h in history], agent.q, agent.n_leaves


for task in ("MountainCar-v0", "Acrobot-v1"):
    now, before = run(task, 16), run(task, 15)
    print(task, "same run:", now == before, "leaves", now[2], "last return", now[0][-1])
