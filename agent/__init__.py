"""The adaptive decision-tree RL agent of Hwang, Li and Jiang and its baselines.

Works on any Gymnasium env with a Box observation and Discrete actions (the tree grows unbounded
dimensions from the data), and on other spaces through ``adapt_env`` (a documented rule for
Discrete, Tuple or Dict observations and Box actions); it never imports the simulation.
``preset("paper")`` is the paper's method as the project reads it, ``preset("general")`` the
one set of defaults for every task. See ``docs/paper-notes.md`` for which function implements
which equation.
"""

from agent import fast_loop  # noqa: F401  (registers the fast loop with the learner)
from agent.adaptive_q import AdaptiveQAgent
from agent.config import TreeConfig
from agent.episode_stats import EpisodeStats
from agent.exploration import (
    STRATEGY_NAMES,
    VDBE,
    AdaptiveEpsilon,
    Boltzmann,
    CountBonus,
    DecayingEpsilon,
    EpsilonGreedy,
    Exploration,
    Greedy,
    OptimisticInit,
    Tabu,
    VDBESoftmax,
    make_exploration,
)
from agent.grid_agent import GridAgent
from agent.inspection import LeafInfo
from agent.learner import SMDPAgent
from agent.presets import PRESETS, Preset, general_as_of, preset
from agent.task_wrappers import BoxObservation, DiscreteActions, adapt_env
from agent.tile_coding import TileCodingAgent
from agent.tree_agent import TreeAgent

__all__ = [
    "PRESETS",
    "STRATEGY_NAMES",
    "VDBE",
    "AdaptiveEpsilon",
    "AdaptiveQAgent",
    "Boltzmann",
    "BoxObservation",
    "CountBonus",
    "DecayingEpsilon",
    "DiscreteActions",
    "EpisodeStats",
    "EpsilonGreedy",
    "Exploration",
    "Greedy",
    "GridAgent",
    "LeafInfo",
    "OptimisticInit",
    "Preset",
    "SMDPAgent",
    "Tabu",
    "TileCodingAgent",
    "TreeAgent",
    "TreeConfig",
    "VDBESoftmax",
    "adapt_env",
    "general_as_of",
    "make_exploration",
    "preset",
]
