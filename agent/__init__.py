"""The adaptive decision-tree RL agent of Hwang, Li and Jiang and its baselines.

Works on any Gymnasium env with a bounded Box observation and Discrete actions; it never imports
the simulation. See ``docs/paper-notes.md`` for which function implements which equation.
"""

from agent import fast_loop  # noqa: F401  (registers the fast loop with the learner)
from agent.config import TreeConfig
from agent.episode_stats import EpisodeStats
from agent.exploration import (
    STRATEGY_NAMES,
    VDBE,
    AdaptiveEpsilon,
    EpsilonGreedy,
    Exploration,
    Greedy,
    Tabu,
    make_exploration,
)
from agent.grid_agent import GridAgent
from agent.inspection import LeafInfo
from agent.learner import SMDPAgent
from agent.tree_agent import TreeAgent

__all__ = [
    "STRATEGY_NAMES",
    "VDBE",
    "AdaptiveEpsilon",
    "EpisodeStats",
    "EpsilonGreedy",
    "Exploration",
    "Greedy",
    "GridAgent",
    "LeafInfo",
    "SMDPAgent",
    "Tabu",
    "TreeAgent",
    "TreeConfig",
    "make_exploration",
]
