"""Issue 9, part 15 (development): FrozenLake-v1's true values (value iteration on the env's
own table, gamma 0.999) against the Q-bar of the general preset of part 15 after 1,000
episodes (agent seeds 1 and 2), per cell and action, with the epoch counts. Output in
``fl_values.txt``::

    python docs/results/issue9_part15_dev/fl_values.py
"""

import warnings

import gymnasium as gym
import numpy as np

from agent import adapt_env, general_as_of
from agent.tree_ensemble import tree_agent_class

GAMMA = 0.999


def values(table, policy=None):
    """Value iteration (policy=None) or policy evaluation on FrozenLake's table."""
    v = np.zeros(16)
    for _ in range(2000):
        q = np.array(
            [
                [
                    sum(p * (r + GAMMA * v[s2] * (not d)) for p, s2, r, d in table[s][a])
                    for a in range(4)
                ]
                for s in range(16)
            ]
        )
        v = q.max(1) if policy is None else q[np.arange(16), policy]
    return q, v


def main() -> None:
    warnings.simplefilter("ignore")
    env = adapt_env(gym.make("FrozenLake-v1"))
    table = env.unwrapped.P
    q_true, v_true = values(table)
    print("opt", q_true.argmax(1).reshape(4, 4).tolist(), v_true.round(2).reshape(4, 4).tolist())
    config = general_as_of(15)  # the preset of the runs (part 16 added optimism)
    for seed in (1, 2):
        agent = tree_agent_class(config)(
            env.observation_space, env.action_space, "adaptive+tabu", seed, config
        )
        agent.learn(env, 1000, reset_seed=seed)
        greedy = np.array([agent.predict(np.array([s])) for s in range(16)])
        print("seed", seed, "greedy", greedy.reshape(4, 4).tolist())
        _, v_greedy = values(table, greedy)
        print("  V(greedy) start", v_greedy[0].round(3), "opt", v_true[0].round(3))
        for s in range(16):
            leaf = agent.partition.leaf_of([float(s)])
            print(
                "  s",
                s,
                "q",
                np.round(agent.q[leaf], 3),
                "Qopt",
                np.round(q_true[s], 3),
                "n",
                agent.visits[leaf],
            )


if __name__ == "__main__":
    main()
