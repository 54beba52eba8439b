"""Named agents: the paper's method as printed, as the project reads it, and the general learner.

A preset is a :class:`TreeConfig` and an exploration strategy (name and parameters), so that an
experiment file can spell it out field by field (``[[strategy]] config = {...}``) and a script
can build it by name::

    agent = preset("general").agent(env.observation_space, env.action_space, seed=0)

* ``"paper"``: Table I with the five reading choices of docs/paper-notes.md ("What makes every
  seed learn"): ``TreeConfig()`` and ``"adaptive+tabu"``, the proposed method exactly as
  ``paper_fig4`` runs it.
* ``"paper-literal"``: the paper's text read literally (no held exploration, a split restarts
  the adaptive epsilon, the tabu list shrinks by one per success, its deviations are not
  held, aspiration when every action is listed): ``paper_fig4``'s ``adaptive+tabu-literal``.
* ``"general"``: the project's best agent, one set of defaults for every task (issue 9): the
  proposed method's strategy, with every threshold in a measured unit, an SMDP model over the
  leaves with prioritized sweeping (64 backups an epoch, issue 9 part 4), a root split once in
  every dimension, the split test's settings chosen on the development cases
  (docs/paper-notes.md, "Beyond the paper: a learner that is fast everywhere"), and a leaf cap
  of 16,384 instead of 4,096 (issue 9, part 7: a tree at the cap cannot split the leaf whose
  aliasing breaks a learnt path; docs/paper-notes.md, "The leaf cap"), and exploratory
  actions held only until 100 terminal transitions have been seen (issue 9, part 8: after
  that a held run is a long detour from a greedy path that is already good;
  docs/paper-notes.md, "Held exploration until n terminals"), leaves split where one action's
  stored epochs disagree (part 9, "Model-driven splits"), and epochs that end where no input
  has been bootstrap from ``q_init`` until 10 terminal epochs (part 10, "Novel ends"), and a
  discount of 0.999 instead of Table I's 0.99 with the measured unit kept at its 0.99 value
  (part 11, "A longer discount"), and novel ends that also stop after 100 episodes, for a task
  whose episodes never terminate (part 12, "Tasks without terminal states"), and leaves cut
  where one action's collided and free stored epochs part (part 14, "Collision splits"; an
  env that reports no collisions runs as before), and a tree that starts as a table of the
  inputs when they are integers and the cells fit the leaf cap (part 15, "A table for integer
  inputs"; float inputs run as before), and untried actions valued at the largest return an
  epoch has paid (part 16, "Optimism for untried actions"; a task that pays at most 0 a step
  runs as before), and a presplit along at most the first 4 of more than 8 inputs (part 17,
  "Inputs with many dimensions"), and a discount of 0.9995 from the episode after every
  terminal so far is measured a failure (parts 19 and 20, "A discount gated on failure"; a
  task whose episodes can end at a goal runs as before). It runs on
  :class:`agent.tree_ensemble.TreeEnsembleAgent`'s loop, which those options need.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from gymnasium import spaces

from agent.config import TreeConfig
from agent.exploration import Exploration, make_exploration
from agent.tree_agent import TreeAgent
from agent.tree_ensemble import tree_agent_class


@dataclass(frozen=True)
class Preset:
    """A tree agent's configuration and exploration strategy, by name."""

    name: str
    description: str
    config: TreeConfig
    exploration: str
    exploration_params: Mapping[str, Any] = field(default_factory=dict)

    def make_exploration(self) -> Exploration:
        """A fresh strategy object (strategies hold per-agent state)."""
        return make_exploration(self.exploration, **self.exploration_params)

    def agent(
        self,
        observation_space: spaces.Space,
        action_space: spaces.Space,
        seed: int = 0,
        bounds: tuple[Sequence[float], Sequence[float]] | None = None,
    ) -> TreeAgent:
        """A new :class:`TreeAgent` with this preset."""
        cls = tree_agent_class(self.config)
        return cls(
            observation_space, action_space, self.make_exploration(), seed, self.config, bounds
        )


PAPER = Preset(
    "paper",
    "Table I and the project's five reading choices (the proposed method of paper_fig4)",
    TreeConfig(),
    "adaptive+tabu",
)
PAPER_LITERAL = Preset(
    "paper-literal",
    "Table I, the paper's text read literally (paper_fig4's adaptive+tabu-literal)",
    TreeConfig(hold_exploration=False),
    "adaptive+tabu",
    {
        "inherit_on_split": False,
        "shrink_every": 1,
        "deviation_explores": False,
        "all_listed": "greedy",
    },
)
GENERAL = Preset(
    "general",
    "one set of defaults for every task: measured units, a split test on 50 new pairs, a model "
    "over the leaves, sweeping, held exploration until 100 terminals, model-driven splits, "
    "novel ends until 10 terminals or 100 episodes, gamma 0.999, collision splits, a table for "
    "integer inputs, optimism for untried actions, a presplit of at most the first 4 of more "
    "than 8 inputs, gamma 0.9995 once every terminal is measured a failure, a greedy choice "
    "among actions with two stored epochs (one in a table's cell), where the tree's ancestors, "
    "compared leaf by leaf, break the actions' statistical ties, and from episode 300 one "
    "training episode in 4 that breaks them at twice the width (never remaking, in an episode, "
    "a choice that collided without leaving its leaf), which the greedy choice takes up where "
    "those episodes earn more",
    TreeConfig(
        threshold_units="scale",
        scale_rule="reward_median",
        split_min_samples=50,
        split_max_abs_mean=0.5,
        split_min_variance=0.0002,
        planning="sweep",
        sweep_backups=64,
        presplit_each_dimension=True,
        max_leaves=16384,
        hold_terminals=100,
        model_split_epochs=8,
        novelty_cells=64,
        novelty_terminals=10,
        gamma=0.999,
        scale_horizon=100.0,
        novelty_episodes=100,
        collision_splits=True,
        table_cells=16384,
        optimistic_untried=True,
        presplit_max_dimensions=8,
        presplit_beyond_dimensions=4,
        failure_gamma=0.9995,
        failure_measure="every",
        greedy_min_epochs=2,
        greedy_cell_epochs=1,
        greedy_tie_errors=1.0,
        greedy_tie_ancestors=1.0,
        greedy_tie_trial=2.0,
        greedy_tie_trial_episodes=300,
        greedy_tie_trial_every=4,
        greedy_tie_trial_margin=2.0,
        greedy_tie_trial_avoid_collided=True,
    ),
    "adaptive+tabu",
)
PRESETS: dict[str, Preset] = {p.name: p for p in (PAPER, PAPER_LITERAL, GENERAL)}

GENERAL_CHANGES: dict[int, dict[str, Any]] = {
    8: {"hold_terminals": None},
    9: {"model_split_epochs": None},
    10: {"novelty_cells": None, "novelty_terminals": 1},
    11: {"gamma": 0.99, "scale_horizon": None},
    12: {"novelty_episodes": None},
    14: {"collision_splits": False},
    15: {"table_cells": None},
    16: {"optimistic_untried": False},
    17: {"presplit_max_dimensions": None, "presplit_beyond_dimensions": 0},
    19: {"failure_gamma": None},
    20: {"failure_measure": "mean"},
    23: {"greedy_min_epochs": 0},
    24: {"greedy_min_epochs": 1, "greedy_cell_epochs": None},
    25: {"greedy_smoothing": 0.0, "greedy_smoothing_links": False, "greedy_tie_errors": None},
    27: {
        "greedy_smoothing": 1.0,
        "greedy_smoothing_links": True,
        "greedy_tie_errors": 0.5,
        "greedy_tie_ancestors": None,
    },
    30: {"greedy_tie_trial": None},
    32: {"greedy_tie_trial_avoid_collided": False},
    36: {"split_min_samples": 100},
}
"""The fields that issue 9's parts 8 and later changed in the general preset, each with its value
before that part (docs/results.md, "A learner that is fast everywhere"; part 13 changed none).
Part 17 changes only inputs of more than 8 dimensions, which part 16's preset refused above 16
and presplit into 512 to 65,536 leaves from 9 to 16. Part 18 changed none; part 19 changes only
runs whose terminals are measured failures (CartPole's fall, never a goal); part 20 keeps the
latch shut where any terminal paid more than going on (FrozenLake's goal). Part 21's policy
splits were adopted on 20 dev seeds and withdrawn on 20 more (docs/paper-notes.md, "Policy
splits"), so it changed none. Part 22 changed none; parts 23, 24, 25 and 27 change only the
greedy choice of ``predict``, never a training step (for part 24's, part 23's value of
``greedy_min_epochs`` is 1). Part 26 changed none; parts 28 and 29 changed none. Part 30's
changes training from episode 300 on (one episode in 4 breaks its greedy ties at z 2), and
``predict``'s width where those episodes earn more. Part 31 changed none; part 32 changes only
trial episodes (from episode 300 on) where the env reports collisions. Parts 33 to 35 changed
none; part 36 halves the paper's N_th (eqs. 12-13's split test runs on 50 new pairs, not 100),
which changes every run's tree."""


def general_as_of(part: int) -> TreeConfig:
    """The general preset's config as it was after issue 9's part ``part`` (7 or later): today's,
    with every field a later part changed back at its earlier value (for a field changed by
    several later parts, the value before the first of them). The held-out comparisons
    spell these out (``experiments/*.toml``), and the benches time them."""
    if isinstance(part, bool) or not isinstance(part, int) or part < 7:
        raise ValueError(f"general_as_of: part must be an int >= 7, got {part!r}")
    earlier: dict[str, Any] = {}
    for n in sorted(GENERAL_CHANGES, reverse=True):  # a field changed twice: the first change wins
        if n > part:
            earlier.update(GENERAL_CHANGES[n])
    return dataclasses.replace(GENERAL.config, **earlier)


def preset(name: str) -> Preset:
    """The preset called ``name`` (ValueError listing the names otherwise)."""
    if name not in PRESETS:
        raise ValueError(f"unknown preset {name!r}; choose one of {sorted(PRESETS)}")
    return PRESETS[name]
