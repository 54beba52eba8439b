"""Does the general agent's greedy Acrobot policy pick the best action under its own policy?
(issue 9, part 12; development seeds only).

Trains the general preset on ``Acrobot-v1`` (agent seed s, first reset seed s, 1,000 episodes),
then, on 3 greedy episodes (reset seeds 10^6 + 1000 s + i, the dev protocol), takes every 7th
state and rolls out each action exactly: Acrobot is deterministic after its reset, so the state
is set and each action is held until the leaf changes (at most 50 steps, as an epoch), then
the greedy policy runs to the end (500 steps in all). It prints how often another action
beats the greedy one and by how much, the states with the largest gaps (the leaf's Q-bar,
visits and model epochs per action), a chaos check (the greedy rollout from the same state
perturbed by N(0, 1e-4)), and the greedy return of three fixed rules::

    PYTHONPATH=. python docs/results/issue9_part12_dev/acrobot_rollouts.py 0
"""

from __future__ import annotations

import sys
from typing import Any

import gymnasium as gym
import numpy as np

from agent import preset


def rollout(agent: Any, env: Any, state: np.ndarray, t0: int, first: int | None) -> float:
    """Return from ``state`` at step ``t0``: ``first`` held while in its leaf (<= 50 steps),
    then greedy, to step 500 or the goal."""
    env.state = np.array(state, dtype=float)
    o = env._get_ob()
    leaf, t, total, held = agent.leaf_of(o), t0, 0.0, 0
    while t < 500:
        if first is not None and held < 50 and agent.leaf_of(o) == leaf:
            action, held = first, held + 1
        else:
            first, action = None, int(agent.predict(o))
        o, r, terminated, _, _ = env.step(action)
        total, t = total + float(r), t + 1
        if terminated:
            break
    return total


def main(seed: int) -> None:
    train = gym.make("Acrobot-v1")
    agent = preset("general").agent(train.observation_space, train.action_space, seed=seed)
    agent.learn(train, 1000, reset_seed=seed)
    env: Any = gym.make("Acrobot-v1").unwrapped
    rows, chaos = [], []
    rng = np.random.default_rng(0)
    greedy_returns = []
    for episode in range(3):
        env.reset(seed=10**6 + 1000 * seed + episode)
        states, o, t = [], env._get_ob(), 0
        while t < 500:
            states.append((env.state.copy(), t))
            o, _, terminated, _, _ = env.step(int(agent.predict(o)))
            t += 1
            if terminated:
                break
        greedy_returns.append(-t + (1 if t < 500 else 0))
        for state, t0 in states[::7]:
            env.state = np.array(state)
            o = env._get_ob()
            greedy = int(agent.predict(o))
            returns = [rollout(agent, env, state, t0, a) for a in range(3)]
            leaf = agent.leaf_of(o)
            info = agent.leaf_info(leaf)
            epochs = [agent.model.count(leaf, a) for a in range(3)]
            q = [round(v, 2) for v in info.q_values]
            rows.append(
                (
                    max(returns) - returns[greedy],
                    greedy,
                    int(np.argmax(returns)),
                    q,
                    info.visits,
                    epochs,
                )
            )
            base = rollout(agent, env, state, t0, None)
            perturbed = [
                rollout(agent, env, state + rng.normal(0, 1e-4, 4), t0, None) for _ in range(2)
            ]
            chaos.append(max(perturbed) - base)
    gains = [r[0] for r in rows]
    print(f"seed {seed}: greedy episodes {greedy_returns}, {agent.n_leaves} leaves")
    print(
        f"states {len(rows)}; another action better at {sum(g > 0 for g in gains)}, "
        f"by >= 10 steps at {sum(g >= 10 for g in gains)}; mean gain where better "
        f"{np.mean([g for g in gains if g > 0]) if any(g > 0 for g in gains) else 0.0:.1f}"
    )
    print(
        f"chaos check: perturbed greedy rollouts (max of two) minus the greedy one: mean "
        f"{np.mean(chaos):.2f}, >= 10 steps at {sum(c >= 10 for c in chaos)} of {len(chaos)}"
    )
    print("largest gaps: (gain, greedy action, best action, Q-bar, visits, model epochs)")
    for row in sorted(rows, key=lambda r: -r[0])[:10]:
        print(" ", row)
    rules = {
        "torque with d(theta2)": lambda o: 2 if o[5] > 0 else 0,
        "torque against d(theta1)": lambda o: 0 if o[4] > 0 else 2,
        "torque with d(theta1)": lambda o: 2 if o[4] > 0 else 0,
    }
    for name, rule in rules.items():
        totals = []
        for episode in range(20):
            o, _ = env.reset(seed=10**6 + 1000 * seed + episode)
            total, t = 0.0, 0
            while t < 500:
                o, r, terminated, _, _ = env.step(rule(o))
                total, t = total + float(r), t + 1
                if terminated:
                    break
            totals.append(total)
        print(f"rule '{name}': greedy return over 20 episodes {np.mean(totals):.1f}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 0)
