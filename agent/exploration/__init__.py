"""Exploration strategies behind one interface (section III), composable and seeded."""

from agent.exploration.adaptive import (
    AdaptiveEpsilon,
    action_probabilities,
    adaptive_epsilon,
    entropy,
    normalized_entropy,
)
from agent.exploration.base import Exploration, greedy_action
from agent.exploration.boltzmann import Boltzmann, boltzmann_probabilities
from agent.exploration.count_bonus import CountBonus, bonus_values
from agent.exploration.decaying_epsilon import DecayingEpsilon, decayed_epsilon
from agent.exploration.epsilon_greedy import EpsilonGreedy, Greedy
from agent.exploration.factory import (
    STRATEGY_NAMES,
    exploration_from_spec,
    exploration_spec,
    make_exploration,
)
from agent.exploration.optimistic import OptimisticInit
from agent.exploration.tabu import Tabu, tabu_capacity
from agent.exploration.vdbe import VDBE, vdbe_epsilon
from agent.exploration.vdbe_softmax import VDBESoftmax

__all__ = [
    "STRATEGY_NAMES",
    "VDBE",
    "AdaptiveEpsilon",
    "Boltzmann",
    "CountBonus",
    "DecayingEpsilon",
    "EpsilonGreedy",
    "Exploration",
    "Greedy",
    "OptimisticInit",
    "Tabu",
    "VDBESoftmax",
    "action_probabilities",
    "adaptive_epsilon",
    "boltzmann_probabilities",
    "bonus_values",
    "decayed_epsilon",
    "entropy",
    "exploration_from_spec",
    "exploration_spec",
    "greedy_action",
    "make_exploration",
    "normalized_entropy",
    "tabu_capacity",
    "vdbe_epsilon",
]
