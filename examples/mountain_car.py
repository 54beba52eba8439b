"""The tree agent on Gymnasium's MountainCar-v0: the agent is not tied to the maze.

    python examples/mountain_car.py [--episodes 1000] [--preset general] [--seed 0]

``train`` is what the tests call; it returns the per-episode statistics and the greedy policy's
score on a few evaluation episodes.

The default is the ``"general"`` preset, whose thresholds are multiples of a reward unit the
agent measures itself, so nothing is scaled by hand. The split thresholds of Table I (preset
``"paper"``) are in the maze's reward units (-0.01 a step); MountainCar pays -1 a step, so
:data:`MOUNTAIN_CAR_CONFIG` is the hand-scaled configuration used before the general preset
existed (``--preset hand-scaled``; the golden files of tests/golden record it).
"""

from __future__ import annotations

import argparse
import logging
from dataclasses import dataclass

import gymnasium as gym

from agent import PRESETS, EpisodeStats, Exploration, TreeAgent, TreeConfig
from agent.tree_ensemble import tree_agent_class

logger = logging.getLogger(__name__)

MOUNTAIN_CAR_CONFIG = TreeConfig(
    split_max_abs_mean=5.0, split_min_variance=1.0, split_min_samples=200
)


@dataclass(frozen=True)
class MountainCarResult:
    """Training history and the greedy policy's evaluation."""

    agent: TreeAgent
    history: list[EpisodeStats]
    eval_steps: list[int]
    """Steps of each greedy evaluation episode (200 = the time limit, goal not reached)."""
    eval_successes: int


def evaluate(agent: TreeAgent, env: gym.Env, episodes: int, seed: int) -> list[tuple[int, bool]]:
    """Run the greedy policy; (steps, reached the goal) per episode."""
    out = []
    for i in range(episodes):
        obs, _ = env.reset(seed=seed + i)
        steps, terminated, truncated = 0, False, False
        while not (terminated or truncated):
            obs, _, terminated, truncated, _ = env.step(agent.predict(obs))
            steps += 1
        out.append((steps, bool(terminated)))
    return out


def train(
    episodes: int = 1000,
    exploration: str | None = None,
    seed: int = 0,
    config: TreeConfig | None = None,
    eval_episodes: int = 10,
    preset: str = "general",
) -> MountainCarResult:
    """Train a TreeAgent on MountainCar-v0 and evaluate its greedy policy.

    ``preset`` is a name of :data:`agent.PRESETS` or ``"hand-scaled"``
    (:data:`MOUNTAIN_CAR_CONFIG` with epsilon-greedy); ``exploration`` and ``config`` replace
    the preset's.
    """
    env = gym.make("MountainCar-v0")
    base_exploration: str | Exploration
    if preset == "hand-scaled":
        base_config, base_exploration = MOUNTAIN_CAR_CONFIG, "epsilon-greedy"
    elif preset in PRESETS:
        base_config, base_exploration = PRESETS[preset].config, PRESETS[preset].make_exploration()
    else:
        raise ValueError(f"unknown preset {preset!r}: {sorted(PRESETS)} or 'hand-scaled'")
    chosen = config if config is not None else base_config
    # the general preset's loop options need TreeEnsembleAgent; tree_agent_class picks the class
    agent = tree_agent_class(chosen)(
        env.observation_space,
        env.action_space,
        exploration if exploration is not None else base_exploration,
        seed,
        chosen,
    )
    history = agent.learn(env, episodes, reset_seed=seed)
    results = evaluate(agent, env, eval_episodes, seed=10_000 + seed)
    env.close()
    return MountainCarResult(
        agent=agent,
        history=history,
        eval_steps=[steps for steps, _ in results],
        eval_successes=sum(ok for _, ok in results),
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--episodes", type=int, default=1000)
    parser.add_argument("--preset", default="general", help="general, paper or hand-scaled")
    parser.add_argument("--exploration", default=None, help="replaces the preset's strategy")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    result = train(args.episodes, args.exploration, args.seed, preset=args.preset)
    history = result.history
    for start in range(0, len(history), max(1, len(history) // 10)):
        chunk = history[start : start + max(1, len(history) // 10)]
        logger.info(
            "episodes %4d-%4d: mean steps %6.1f, successes %3d/%d, leaves %d",
            chunk[0].episode,
            chunk[-1].episode,
            sum(s.steps for s in chunk) / len(chunk),
            sum(s.success for s in chunk),
            len(chunk),
            chunk[-1].leaves,
        )
    logger.info(
        "greedy policy: %d/%d episodes reach the goal, steps %s",
        result.eval_successes,
        len(result.eval_steps),
        result.eval_steps,
    )


if __name__ == "__main__":
    main()
