"""The fast learning loop: ``SMDPAgent.learn``'s episodes run by a compiled kernel, same numbers.

``learn(fast=True)`` (the default) asks :func:`episode_runner` for the function that runs one
episode. It returns a :class:`FastRunner` when the kernel implements everything the run needs,
else the reference :meth:`~agent.learner.SMDPAgent._run_episode`; both give the same episodes,
Q-tables, trees, strategy states and random streams bit for bit (``tests/agent/
test_fast_loop.py`` compares them; ``tests/golden`` checks the fast path against files recorded
from the reference code). The reference runs instead, automatically, when

* the env is not ours: ``env.unwrapped`` must be a ``BulletMazeEnv`` whose ``fast_core()``
  accessor (its contract with this module) answers, i.e. kinematic mode, a robot without a
  heading, no render mode, wrapped by nothing but ``TimeLimit``, ``OrderEnforcing`` and
  ``PassiveEnvChecker`` (what ``gymnasium.make`` adds);
* the compiled kernel (:mod:`agent.fast_kernel`, numba) is missing or fails to compile;
* the agent or its strategy is not one the kernel implements: an explicit whitelist of the
  agent classes, the ``TreeConfig`` fields and values, the strategy classes, their attributes
  and parameter values (:func:`ineligible_reason`), so that a field or a class added later
  falls back instead of running wrongly;
* a function the kernel mirrors, or whose effects the driver re-reads, has changed: each one's
  source (without docstrings and comments) is fingerprinted in :data:`FINGERPRINTS`; a
  mismatch is logged once and turns the fast loop off until the kernel is checked against the
  new code and the fingerprint renewed (``tests/agent/test_fast_loop.py`` fails meanwhile).

How it works. The kernel runs the reference's episode loop on arrays mirroring the agent
(tree, Q-bar, counts, strategy state, tabu list, error buffers, the uniform block) and the env
(position, noise block, cached cell bounds and safe ball of ``World.certified_free``). It takes
a step itself only when the cached bounds prove the move free and the goal test is certain; any
other step (a collision, a pybullet sweep, an unseen cell, a new noise block, the checker's
first steps) is ``env.step`` itself, through the wrappers, so pybullet, the noise stream and
``TimeLimit`` truncation are the env's own. A split test (a leaf's buffer fills) runs the
reference's ``partition.record`` and ``_grow``. Before each of these calls, and at the end of
every episode (before ``learn``'s callback), the driver writes what the kernel changed back into
the Python objects, so a callback, ``save`` or ``predict`` sees exactly the reference's state.
A callback that changes the agent's tables in place is not seen by the kernel: use
``fast=False`` for that (replacing the strategy, the config or the tables is detected).
"""

from __future__ import annotations

import ast
import ctypes
import dataclasses
import gc
import hashlib
import inspect
import itertools
import logging
import math
import sys
import textwrap
import time
from collections.abc import Callable
from typing import Any, Literal

import numpy as np
from gymnasium.wrappers import OrderEnforcing, PassiveEnvChecker, TimeLimit

from agent import smdp, split_statistics
from agent.config import TreeConfig
from agent.episode_stats import EpisodeStats
from agent.error_buffer import ErrorBuffer
from agent.exploration import VDBE, AdaptiveEpsilon, EpsilonGreedy, Greedy, Tabu
from agent.exploration import adaptive as adaptive_module
from agent.exploration import base as base_module
from agent.exploration import tabu as tabu_module
from agent.exploration import vdbe as vdbe_module
from agent.exploration.base import Exploration
from agent.grid_agent import GridAgent
from agent.learner import SMDPAgent, register_fast_runner
from agent.partition_tree import PartitionTree
from agent.random_stream import UniformStream
from agent.tree_agent import TreeAgent
from agent.uniform_grid import UniformGrid

logger = logging.getLogger(__name__)

RunEpisode = Callable[[Any, Any], EpisodeStats]

MAX_ACTIONS = 62
"""The tabu list keeps each leaf's listed actions as bits of one int64."""
MAX_TABU_CAPACITY = 1 << 20

# -- What the kernel implements ---------------------------------------------------------------

CONFIG_FIELDS: dict[str, tuple[Any, ...] | type | tuple[type, ...]] = {
    "alpha": float,
    "gamma": float,
    "q_init": (float, int),
    "max_epoch_steps": (int, type(None)),
    "hold_exploration": bool,
    "end_epoch_on_collision": bool,
    "collision_key": ("collision",),
    "split_min_samples": int,
    "split_max_abs_mean": (float, int),
    "split_min_variance": (float, int),
    "error_buffer": ("clear",),
    "range_normalization": ("root", "none"),
    "split_point": ("quest", "midpoint"),
    "inherit_q": bool,
    "reset_counts_on_split": bool,
    "children_inherit_samples": bool,
    "min_leaf_fraction": float,
    "max_leaves": int,
    # Beyond the paper (issue 9): the kernel runs none of these, so only the values that leave
    # the learner as the paper's. The split test runs in Python, so its options take any value;
    # the others matter only with a measured unit or the model, which turn the loop off here.
    "threshold_units": ("reward",),
    "scale_rule": ("return_std", "return_iqr", "reward_median"),
    "scale_horizon": (float, int, type(None)),
    "split_min_t": (float, int),
    "planning": ("none",),
    "model_window": int,
    "sweep_backups": int,
    "sweep_tolerance": (float, int),
    "model_bonus": (float, int),
    "initial_depth": int,
    "presplit_each_dimension": bool,
    "presplit_max_dimensions": (int, type(None)),
    "presplit_beyond_dimensions": int,
    # the kernel keeps no record of untried actions: True turns the loop off (ineligible_reason)
    "optimistic_untried": bool,
    # changes only predict's greedy choice, never a training step; needs the model
    "greedy_min_epochs": int,
    "greedy_cell_epochs": (int, type(None)),
    "greedy_smoothing": (float, int),
    "greedy_smoothing_links": bool,
    "greedy_tie_errors": (float, int, type(None)),
    "greedy_tie_ancestors": (float, int, type(None)),
    # makes the agent a TreeEnsembleAgent, whose class turns the loop off
    "greedy_tie_trial": (type(None),),
    "greedy_tie_trial_episodes": int,
    "greedy_tie_trial_margin": (float, int),
    "greedy_tie_trial_every": int,
    "greedy_tie_trial_follow": bool,
    "greedy_tie_trial_avoid_collided": bool,
    # a table needs integer inputs, which turn the loop off (the kernel's inputs are positions)
    "table_cells": (int, type(None)),
    # a positive value makes the tree a GatedPartitionTree, whose type turns the loop off
    "leaves_per_terminal": int,
    # matters only with the model (model_bonus), which turns the loop off
    "model_bonus_terminals": int,
    # matters only with the model, which turns the loop off; a positive value also makes
    # the agent a TreeEnsembleAgent
    "model_lambda": (float, int),
    "model_lambda_watkins": bool,
    "model_lambda_tried_only": bool,
    "model_lambda_episodes": (int, type(None)),
    "model_lambda_lower_bound": bool,
    # matter only with the model, which turns the loop off
    "model_split_epochs": (int, type(None)),
    "model_split_gap": (float, int),
    "model_split_t": (float, int),
    "model_split_drops_pairs": bool,
    "model_split_from_terminal": bool,
    "policy_splits": bool,
    "novelty_cells": (int, type(None)),
    "novelty_max_cells": (int, type(None)),  # matters only with novelty_cells (the model)
    "novelty_terminals": int,
    "novelty_episodes": (int, type(None)),
    # these make the agent a TreeEnsembleAgent, whose class turns the loop off
    "ensemble_trees": int,
    "ensemble_decisions": ("any",),
    "ensemble_unbounded_offsets": bool,
    "decision_steps": (int, type(None)),
    "hold_steps": (int, type(None)),
    "hold_crossings": (float, int, type(None)),
    "decision_from_terminal": bool,
    "decision_on_failure": bool,
    "failure_gamma": (type(None),),
    "failure_measure": ("mean", "every"),  # read only with failure_gamma, refused above
    "hold_terminals": (int, type(None)),
    "hold_after_truncation": bool,
    # needs the model, which turns the loop off (and it makes the agent a TreeEnsembleAgent)
    "collision_splits": bool,
    "collision_splits_collided_only": bool,  # needs collision_splits, refused above
}
"""Every ``TreeConfig`` field the fast loop knows, with the types or values it supports (the
split fields run in Python, so any valid value). A field not listed here turns it off."""

_EXPLORATION_ATTRIBUTES = {"n_actions", "explored"}
STRATEGY_ATTRIBUTES: dict[type, set[str]] = {
    EpsilonGreedy: {"_epsilon"} | _EXPLORATION_ATTRIBUTES,
    Greedy: {"_epsilon"} | _EXPLORATION_ATTRIBUTES,
    AdaptiveEpsilon: {"c_n", "c_h", "variant", "inherit_on_split", "_counts", "_epsilon"}
    | _EXPLORATION_ATTRIBUTES,
    VDBE: {"sigma", "delta", "form", "inherit_on_split", "_epsilon"} | _EXPLORATION_ATTRIBUTES,
    Tabu: {
        "base",
        "initial_capacity",
        "shrink_every",
        "min_capacity",
        "on_split_policy",
        "random_respects_list",
        "deviation_explores",
        "all_listed",
        "successes",
        "_capacity",
        "_fifo",
        "_by_leaf",
    }
    | _EXPLORATION_ATTRIBUTES,
}
"""The strategy classes the kernel implements (exactly these classes, not subclasses) and the
instance attributes each may have; a class or attribute not listed turns the fast loop off."""

STRATEGY_PARAMETERS: dict[type, dict[str, tuple[Any, ...] | type | tuple[type, ...]]] = {
    EpsilonGreedy: {"epsilon": float},
    Greedy: {},
    AdaptiveEpsilon: {
        "c_n": float,
        "c_h": float,
        "variant": ("literal", "cn_exponent"),
        "inherit_on_split": bool,
    },
    VDBE: {
        "sigma": float,
        "delta": (float, type(None)),
        "form": ("boltzmann", "exponential"),
        "inherit_on_split": bool,
    },
    Tabu: {
        "initial_capacity": int,
        "shrink_every": int,
        "min_capacity": int,
        "on_split": ("drop", "inherit"),
        "random_respects_list": bool,
        "deviation_explores": bool,
        "all_listed": ("greedy", "random"),
    },
}
"""``params()`` of each strategy class: the types or values the kernel implements."""

AGENT_ATTRIBUTES = {
    "n_actions",
    "observation_space",
    "action_space",
    "bounds",
    "config",
    "exploration",
    "seed",
    "rng",
    "uniform",
    "partition",
    "q",
    "visits",
    "episodes_done",
    "scale",
    "_track_scale",
    "model",
    "novelty",
    "q_init",
    "integer_inputs",
    "optimism",
    "saved_support",  # read by predict alone (TreeConfig.greedy_min_epochs)
    "saved_errors",  # read by predict alone (TreeConfig.greedy_tie_errors)
    "saved_links",  # read by predict alone (TreeConfig.greedy_smoothing_links)
    "paired_sums",  # read by predict alone (TreeConfig.greedy_tie_ancestors)
    "leaf_errors",  # read by predict alone (TreeConfig.greedy_tie_errors)
    "leaf_choices",  # read by predict alone (TreeConfig.greedy_tie_ancestors)
    "_choices_config",  # the configuration leaf_choices were made under
    "_choices_widths",  # the tie widths leaf_choices were made at
    "tie_trial",  # None here: TreeConfig.greedy_tie_trial makes a TreeEnsembleAgent
}
AGENT_CLASSES: dict[type, tuple[type, set[str]]] = {
    TreeAgent: (PartitionTree, AGENT_ATTRIBUTES),
    GridAgent: (UniformGrid, AGENT_ATTRIBUTES | {"resolution"}),
}
WRAPPERS = (TimeLimit, OrderEnforcing, PassiveEnvChecker)

# -- The reference code the kernel mirrors ----------------------------------------------------


def _agent_functions() -> dict[str, Any]:
    return {
        "SMDPAgent._run_episode": SMDPAgent._run_episode,
        "SMDPAgent._end_epoch": SMDPAgent._end_epoch,
        "SMDPAgent.discount": vars(SMDPAgent)["discount"].fget,
        "SMDPAgent._end_held_run": SMDPAgent._end_held_run,
        "SMDPAgent._grow": SMDPAgent._grow,
        "PartitionTree.leaf_of": PartitionTree.leaf_of,
        "PartitionTree.record": PartitionTree.record,
        "PartitionTree._try_split": PartitionTree._try_split,
        "PartitionTree.may_split": PartitionTree.may_split,
        "PartitionTree.split_box": PartitionTree.split_box,
        "PartitionTree.split_with_samples": PartitionTree.split_with_samples,
        "PartitionTree.split": PartitionTree.split,
        "UniformGrid.leaf_of": UniformGrid.leaf_of,
        "ErrorBuffer.__init__": ErrorBuffer.__init__,
        "ErrorBuffer.add": ErrorBuffer.add,
        "ErrorBuffer._exact_sums": ErrorBuffer._exact_sums,
        "ErrorBuffer.mean_variance": ErrorBuffer.mean_variance,
        "ErrorBuffer.clear": ErrorBuffer.clear,
        "ErrorBuffer.arrays": ErrorBuffer.arrays,
        "should_split": split_statistics.should_split,
        "t_statistics": split_statistics.t_statistics,
        "density_crossing": split_statistics.density_crossing,
        "split_point": split_statistics.split_point,
        "choose_split": split_statistics.choose_split,
        "UniformStream.random": UniformStream.random,
        "epoch_returns": smdp.epoch_returns,
        "leaf_update": smdp.leaf_update,
        "greedy_action": base_module.greedy_action,
        "Exploration.select": Exploration.select,
        "Exploration.update": Exploration.update,
        "Exploration.on_epoch_end": Exploration.on_epoch_end,
        "Exploration.on_episode_end": Exploration.on_episode_end,
        "Exploration.on_split": Exploration.on_split,
        "EpsilonGreedy.epsilon": EpsilonGreedy.epsilon,
        "adaptive_epsilon": adaptive_module.adaptive_epsilon,
        "AdaptiveEpsilon.epsilon": AdaptiveEpsilon.epsilon,
        "AdaptiveEpsilon.update": AdaptiveEpsilon.update,
        "AdaptiveEpsilon.on_split": AdaptiveEpsilon.on_split,
        "vdbe_epsilon": vdbe_module.vdbe_epsilon,
        "VDBE.epsilon": VDBE.epsilon,
        "VDBE.update": VDBE.update,
        "VDBE.on_split": VDBE.on_split,
        "tabu_capacity": tabu_module.tabu_capacity,
        "Tabu.epsilon": Tabu.epsilon,
        "Tabu.select": Tabu.select,
        "Tabu.update": Tabu.update,
        "Tabu.on_epoch_end": Tabu.on_epoch_end,
        "Tabu.on_episode_end": Tabu.on_episode_end,
        "Tabu.on_split": Tabu.on_split,
        "Tabu._set_entries": Tabu._set_entries,
        "Tabu._trim": Tabu._trim,
        "TimeLimit.step": TimeLimit.step,
        "OrderEnforcing.step": OrderEnforcing.step,
        "PassiveEnvChecker.step": PassiveEnvChecker.step,
    }


def _env_functions(base: Any) -> dict[str, Any]:
    env_type = type(base)
    world_type = type(base.world)
    bounds_type = getattr(sys.modules[world_type.__module__], "_CellBounds", None)
    return {
        "BulletMazeEnv.step": env_type.step,
        "BulletMazeEnv.fast_core": env_type.fast_core,
        "World.certified_free": world_type.certified_free,
        "World.sweep_collides": world_type.sweep_collides,
        "World._closest": world_type._closest,
        "World.place_probe": world_type.place_probe,
        "_CellBounds.clear": getattr(bounds_type, "clear", None),
    }


FINGERPRINTS = {
    "SMDPAgent._run_episode": "0c3f07fce917b80a",
    "SMDPAgent._end_epoch": "1e888688f9464870",  # part 19: self.discount (config.gamma here)
    "SMDPAgent.discount": "b7470042f10fdf1a",
    "SMDPAgent._end_held_run": "d869d34667c3067f",
    "SMDPAgent._grow": "df200e3fc423ac39",
    "PartitionTree.leaf_of": "6a1300d763454473",  # a Sequence annotation (stored copies)
    "PartitionTree.record": "c6ca80ffc6949cf0",
    "PartitionTree._try_split": "47296a89935ec01a",
    "PartitionTree.may_split": "6e07498ec05bb032",
    "PartitionTree.split_box": "bef2291ad37355c8",  # part 15: integer inputs (refused here)
    "PartitionTree.split_with_samples": "a42416998727ec06",
    "PartitionTree.split": "d41c976a347495ae",
    "UniformGrid.leaf_of": "5480bacdb78c6fc5",  # a Sequence annotation
    "ErrorBuffer.__init__": "5055312c1e4acf17",  # storage grown on demand (allocate())
    "ErrorBuffer.add": "6edcfbf061842124",
    "ErrorBuffer._exact_sums": "449e23fee4655dca",
    "ErrorBuffer.mean_variance": "ccbf03f39d469108",
    "ErrorBuffer.clear": "971d49be875d6831",
    "ErrorBuffer.arrays": "0df57f67b4d317d9",
    "should_split": "f92a49ed5e2bc1b4",
    "t_statistics": "4f6215544c013169",
    "density_crossing": "262ff1e7150804f2",
    "split_point": "3339785ebec57ee4",
    "choose_split": "74c2c03de5123666",
    "UniformStream.random": "8991e422a2b3f799",
    "epoch_returns": "8f2bfb5777511e81",
    "leaf_update": "1aa0af332e5cc0c6",
    "greedy_action": "c43bc5b9cbb79b19",
    "Exploration.select": "b2109fc92c7a3fb8",
    "Exploration.update": "589163276cb10827",
    "Exploration.on_epoch_end": "2a01ca4b36cedde8",
    "Exploration.on_episode_end": "6bf65031d32947e1",
    "Exploration.on_split": "175a17efdbde8865",
    "EpsilonGreedy.epsilon": "14f180e6c73b2563",
    "adaptive_epsilon": "5efac9ca19ae2f00",
    "AdaptiveEpsilon.epsilon": "9ba4c0e190b56a89",
    "AdaptiveEpsilon.update": "5c6f2fd556d10a19",
    "AdaptiveEpsilon.on_split": "069b7bb541ea2745",
    "vdbe_epsilon": "4ed44ee07531fec3",
    "VDBE.epsilon": "9ba4c0e190b56a89",
    "VDBE.update": "711e03bc6e124029",
    "VDBE.on_split": "5af4d87122d6ac93",
    "tabu_capacity": "083948ac4f6c1898",
    "Tabu.epsilon": "1ee7eb40149dc2db",
    "Tabu.select": "d7f68ee05b2f61f9",
    "Tabu.update": "457351dc2f9d8346",
    "Tabu.on_epoch_end": "4523ff8830426e8c",
    "Tabu.on_episode_end": "83eece081c3a7c60",
    "Tabu.on_split": "f5548097fe94595f",
    "Tabu._set_entries": "2fe8129b9a3d0fbb",
    "Tabu._trim": "9531e620c13b05c6",
    "TimeLimit.step": "f58ba6b39e92c509",
    "OrderEnforcing.step": "392ca0c995845830",
    "PassiveEnvChecker.step": "c00068accb0b439f",
    "BulletMazeEnv.step": "9f1c1dd21ffee0e5",  # part 38: dynamic mode reports a fall
    "BulletMazeEnv.fast_core": "7936da0308bf1673",
    "World.certified_free": "4e09b0d9feccf14f",
    "World.sweep_collides": "ab65a80ae4b18e9e",
    "World._closest": "f159013e903d93e3",
    "World.place_probe": "108f3db2a31e5627",
    "_CellBounds.clear": "70e9511f5b4adbf8",
}
"""Hash of each mirrored function's source (docstrings and comments removed, :func:`fingerprint`)
as the kernel was checked against it."""


def fingerprint(function: Any) -> str:
    """First 16 hex digits of the SHA-256 of the function's source, parsed and unparsed without
    its docstrings (so comments, formatting and docstrings do not count)."""
    source = textwrap.dedent(inspect.getsource(function))
    tree = ast.parse(source)
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if (
            isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef | ast.Module)
            and body
            and isinstance(body[0], ast.Expr)
            and isinstance(body[0].value, ast.Constant)
            and isinstance(body[0].value.value, str)
        ):
            node.body = body[1:] or [ast.Pass()]
    return hashlib.sha256(ast.unparse(tree).encode()).hexdigest()[:16]


def current_fingerprints(base_env: Any) -> dict[str, str]:
    """:func:`fingerprint` of every mirrored function, the env's taken from ``base_env``."""
    functions = {**_agent_functions(), **_env_functions(base_env)}
    return {
        name: fingerprint(function) if function is not None else "missing"
        for name, function in functions.items()
    }


_checked_types: dict[tuple[type, type], str | None] = {}


def _changed_code(base_env: Any) -> str | None:
    key = (type(base_env), type(base_env.world))
    if key not in _checked_types:
        current = current_fingerprints(base_env)
        changed = sorted(name for name, value in current.items() if FINGERPRINTS.get(name) != value)
        reason = None
        if changed:
            reason = f"mirrored code changed since the kernel was checked: {', '.join(changed)}"
            logger.warning("fast learning loop off: %s (the reference loop runs)", reason)
        _checked_types[key] = reason
    return _checked_types[key]


# -- Eligibility -----------------------------------------------------------------------------


@dataclasses.dataclass(frozen=True)
class _Chain:
    base: Any
    time_limit: TimeLimit | None
    order: OrderEnforcing | None
    checker: PassiveEnvChecker | None


def _wrapper_chain(env: Any) -> _Chain | str:
    found: dict[type, Any] = {}
    layer = env
    while type(layer) in WRAPPERS:
        if type(layer) in found:
            return f"two {type(layer).__name__} wrappers"
        found[type(layer)] = layer
        layer = layer.env
    if layer is not getattr(env, "unwrapped", None):
        return f"wrapper {type(layer).__name__} is not one the fast loop knows"
    if type(layer).__name__ != "BulletMazeEnv" or type(layer).__module__ != "bullet_maze.env":
        return f"env {type(layer).__name__} is not bullet_maze's BulletMazeEnv"
    return _Chain(
        layer, found.get(TimeLimit), found.get(OrderEnforcing), found.get(PassiveEnvChecker)
    )


def _value_ok(value: Any, allowed: Any) -> bool:
    if isinstance(allowed, tuple) and allowed and not isinstance(allowed[0], type):
        return isinstance(value, str) and value in allowed
    if isinstance(value, bool) and allowed is not bool and bool not in _as_tuple(allowed):
        return False
    return isinstance(value, allowed)


def _as_tuple(allowed: Any) -> tuple[Any, ...]:
    return allowed if isinstance(allowed, tuple) else (allowed,)


def _strategy_reason(strategy: Any, top: bool = True) -> str | None:
    kind = type(strategy)
    if kind not in STRATEGY_ATTRIBUTES:
        return f"exploration class {kind.__name__} is not one the fast loop implements"
    extra = set(vars(strategy)) - STRATEGY_ATTRIBUTES[kind]
    if extra:
        return f"{kind.__name__} has attributes the fast loop does not know: {sorted(extra)}"
    params = strategy.params()
    allowed = STRATEGY_PARAMETERS[kind]
    if set(params) != set(allowed):
        return f"{kind.__name__} parameters {sorted(params)} are not {sorted(allowed)}"
    for name, value in params.items():
        if not _value_ok(value, allowed[name]):
            return f"{kind.__name__} parameter {name}={value!r} is not implemented"
    if kind is Tabu:
        if not top:
            return "a tabu list inside a tabu list"
        if max(strategy.initial_capacity, strategy.min_capacity) > MAX_TABU_CAPACITY:
            return f"tabu capacity above {MAX_TABU_CAPACITY}"
        return _strategy_reason(strategy.base, top=False)
    return None


def ineligible_reason(agent: Any, env: Any) -> str | None:
    """Why the fast loop cannot run ``agent`` on ``env`` (None when it can)."""
    kind: type = type(agent)
    if kind not in AGENT_CLASSES:
        return f"agent class {kind.__name__} is not TreeAgent or GridAgent"
    partition_type, attributes = AGENT_CLASSES[kind]
    extra = set(vars(agent)) - attributes
    if extra:
        return f"{kind.__name__} has attributes the fast loop does not know: {sorted(extra)}"
    if agent._track_scale or agent.model is not None:
        return "a measured reward unit or the model over the leaves (beyond the paper)"
    if agent.q_init != agent.config.q_init:
        return "an initial Q-bar other than TreeConfig.q_init (optimistic initialisation)"
    if agent.integer_inputs:
        return "integer inputs (an integer-typed observation box)"
    if agent.config.optimistic_untried:
        return "optimism for untried actions (TreeConfig.optimistic_untried)"
    partition: Any = agent.partition
    if type(partition) is not partition_type:
        return f"partition {type(partition).__name__} is not {partition_type.__name__}"
    if getattr(partition, "_grown", None) or getattr(partition, "scale", None) is not None:
        return "a partition with unbounded dimensions or thresholds in a measured unit"
    dims = getattr(partition, "dims", None)
    if dims != 2:
        return f"{dims}-dimensional inputs (the kernel takes 2)"
    if type(agent.uniform) is not UniformStream:
        return "the agent's uniform source is not a UniformStream"
    config = agent.config
    if type(config) is not TreeConfig:
        return f"config {type(config).__name__} is not TreeConfig"
    fields = {f.name for f in dataclasses.fields(config)}
    if fields != set(CONFIG_FIELDS):
        return (
            f"TreeConfig fields differ from the fast loop's: {sorted(fields ^ set(CONFIG_FIELDS))}"
        )
    for name, allowed in CONFIG_FIELDS.items():
        if not _value_ok(getattr(config, name), allowed):
            return f"TreeConfig.{name}={getattr(config, name)!r} is not implemented"
    if not 1 <= agent.n_actions <= MAX_ACTIONS:
        return f"{agent.n_actions} actions (the kernel takes 1 to {MAX_ACTIONS})"
    reason = _strategy_reason(agent.exploration)
    if reason:
        return reason
    chain = _wrapper_chain(env)
    if isinstance(chain, str):
        return chain
    core = chain.base.fast_core()
    if core is None:
        return "the env is not kinematic with a heading-free robot and no render mode"
    if len(core.moves) != agent.n_actions:
        return f"the env has {len(core.moves)} moves, the agent {agent.n_actions} actions"
    return _changed_code(chain.base)


MAX_KERNEL_BUFFER = 4096
"""The kernel runs the split test for buffers of at most this many pairs (NumPy's reductions
along axis 0, which it mirrors, were checked up to there); larger ones run it in Python."""


def _split_in_kernel(partition: Any, config: TreeConfig) -> bool:
    """Whether the kernel runs this tree's split test (else ``partition.record`` in Python)."""
    widths = partition._root_width.tolist()
    numbers = (
        config.split_max_abs_mean,
        config.split_min_variance,
        config.split_min_t,
        config.q_init,
    )
    return (
        config.error_buffer == "clear"
        and 2 <= config.split_min_samples <= MAX_KERNEL_BUFFER
        and all(math.isfinite(w) and w > 0.0 for w in widths)
        and all(math.isfinite(float(v)) and float(v) == v for v in numbers)
        and not partition._grown
        and partition.scale is None
    )


# -- The kernel ----------------------------------------------------------------------------

_kernel: Any = None


def load_kernel() -> Any:
    """:mod:`agent.fast_kernel`, compiled (or loaded from numba's cache) on first use; None
    when numba is missing or compiling fails (logged once)."""
    global _kernel
    if _kernel is None:
        try:
            from agent import fast_kernel

            runner = FastRunner.__new__(FastRunner)
            runner.k = fast_kernel
            runner._dummy_arrays(fast_kernel)
            runner._sweep_callback = fast_kernel.SWEEP_CALLBACK(lambda *move: 0)
            runner.st[fast_kernel.I_SWEEP] = _address(runner._sweep_callback)
            event = fast_kernel.run_pooled(*runner._args())
            if event != fast_kernel.EV_DONE:
                raise RuntimeError(f"the kernel's warm-up returned event {event}")
            _kernel = fast_kernel
        except Exception as error:  # ImportError without numba, numba's errors when compiling
            logger.warning("fast learning loop unavailable (%s): the reference loop runs", error)
            _kernel = False
    return _kernel or None


def episode_runner(agent: SMDPAgent, env: Any) -> RunEpisode:
    """The function that runs one episode of ``agent.learn`` on ``env``: a :class:`FastRunner`
    when the fast loop applies, else the reference ``agent._run_episode``."""
    reason = ineligible_reason(agent, env)
    if reason is None:
        kernel = load_kernel()
        if kernel is not None:
            return FastRunner(agent, env, kernel)
        reason = "the compiled kernel is unavailable"
    logger.debug("fast learning loop off: %s", reason)
    return agent._run_episode


# -- The driver ------------------------------------------------------------------------------


class FastRunner:
    """Runs ``agent``'s episodes on ``env`` with the kernel; see the module docstring.

    Holds the arrays that mirror the agent and the env between episodes of one ``learn`` call;
    after each episode and before every call into Python code the Python objects are brought
    up to date, so they are the truth whenever anything else can look.
    """

    agent: Any
    env: Any
    k: Any
    chain: _Chain
    base: Any
    world: Any
    cell_table: dict[tuple[int, int], Any]
    tabu: Any
    strategy_base: Any
    goal: tuple[float, float]
    goal_radius: float
    n_ids: int
    nslots: int
    ncells: int
    nbounds: int
    npieces: int
    ubase: int
    new_block: bool
    _argtuple: tuple[Any, ...] | None
    _cell_views: tuple[Any, ...] | None = None
    _noise_list: list[float] | None
    _q_list: Any
    _visits_list: Any
    _partition: Any
    _strategy: Any
    _config: Any
    _uniform: Any
    st: np.ndarray
    fs: np.ndarray
    li: np.ndarray
    lf: np.ndarray
    q: np.ndarray
    visits: np.ndarray
    counts: np.ndarray
    fifo: np.ndarray
    ubuf: np.ndarray
    grid_f: np.ndarray
    grid_i: np.ndarray
    xs: np.ndarray
    rs: np.ndarray
    held: np.ndarray
    errs: np.ndarray
    bufi: np.ndarray
    buff: np.ndarray
    bctr: np.ndarray
    bsum: np.ndarray
    free: np.ndarray
    dirty: np.ndarray
    log: np.ndarray
    moves: np.ndarray
    noise: np.ndarray
    cells: np.ndarray
    bounds_c: np.ndarray
    bounds_r: np.ndarray
    pieces: np.ndarray

    _ARRAYS = frozenset(
        [
            "st",
            "fs",
            "li",
            "lf",
            "q",
            "visits",
            "counts",
            "fifo",
            "ubuf",
            "grid_f",
            "grid_i",
            "xs",
            "rs",
            "held",
            "errs",
            "bufi",
            "buff",
            "bctr",
            "bsum",
            "free",
            "dirty",
            "log",
            "moves",
            "noise",
            "cells",
            "bounds_c",
            "bounds_r",
            "pieces",
        ]
    )
    """The kernel's array arguments, in order."""

    def __setattr__(self, name: str, value: Any) -> None:
        if name in self._ARRAYS:  # a replaced array: the argument tuple is rebuilt
            object.__setattr__(self, "_argtuple", None)
        object.__setattr__(self, name, value)

    def __init__(self, agent: SMDPAgent, env: Any, kernel: Any) -> None:
        chain = _wrapper_chain(env)
        assert isinstance(chain, _Chain)
        self.agent = agent
        self.env = env
        self.k = kernel
        self.chain = chain
        self.base = chain.base
        self.env_seconds: float | None = None
        """CPU seconds spent in the env's Python code (sweeps, ``env.step``) once a benchmark
        sets this to 0.0 (``bench/bench_agent.py``); None: not measured."""
        self._pending = False
        self._error: BaseException | None = None
        self._queries: Callable[[float, float, float, float, int], bool] | None = None
        self._queries_made: tuple[Any, Callable[[float, float, float, float, int], bool]] | None
        self._queries_made = None
        self._sweep_callback = kernel.SWEEP_CALLBACK(self._sweep_function())
        self.sums_events = [0, 0, 0]
        """Rings the kernel filled (exact sums asked of NumPy), for the tests: a leaf's own
        (index 0) and a child's at a split (index 2)."""
        self.lazy = True
        """Leave the Python objects behind the kernel after an episode until :meth:`sync`
        (``learn`` calls it before each callback and at its end); False: sync after each."""
        self._export()

    # -- one episode ---------------------------------------------------------------------

    def __call__(self, env: Any, obs: Any) -> EpisodeStats:
        agent = self.agent
        if env is not self.env or not self._agent_unchanged():
            if env is self.env and ineligible_reason(agent, env) is None:
                self._export()
            else:
                return agent._run_episode(env, obs)
        k = self.k
        st, fs = self.st, self.fs
        x = obs.tolist() if type(obs) is np.ndarray else [float(v) for v in obs]
        if len(x) != 2:
            return agent._run_episode(env, obs)
        fs[k.F_X], fs[k.F_Y] = x
        core = self._import_env()
        self._queries = self._queries_for(self.world)
        self.goal, self.goal_radius = core.goal, core.goal_radius
        fs[k.F_GX], fs[k.F_GY] = core.goal
        fs[k.F_GR] = core.goal_radius
        st[k.I_PHASE] = k.PH_START
        run = k.run_pooled
        self._pending = True
        # No cyclic collection during the episode: the kernel and the env's sweeps make no
        # reference cycles (their objects die by reference counting), and a collection here,
        # set off by allocations elsewhere, would traverse the process's heap for nothing (a
        # full one is about 50 ms). The collector is on again when the episode ends or raises.
        collecting = gc.isenabled()
        if collecting:
            gc.disable()
        try:
            while True:
                event = run(*self._args())
                if event == k.EV_DONE:
                    break
                if len(self.cell_table) != self.ncells:  # cells the sweeps could not import
                    self._import_cells(self.cell_table)
                if event == k.EV_SUMS:
                    self._exact_sums()
                    self.sums_events[int(self.st[k.I_REC_STAGE])] += 1
                elif event == k.EV_PY_STEP:
                    self._python_step()
                elif event == k.EV_RECORD:
                    self._record()
                elif event == k.EV_UNIFORM:
                    self._next_uniform_block()
                elif event == k.EV_GROW:
                    self._grow_epoch_arrays()
                elif event == k.EV_POOL:
                    self._make_room()
                elif event == k.EV_PY_TAIL:
                    self._split_fails()
                elif event == k.EV_CALLBACK_ERROR:
                    error, self._error = self._error, None
                    assert error is not None
                    raise error
                else:
                    raise RuntimeError(f"fast loop: unknown kernel event {event}")
        except BaseException:
            self.sync()
            raise
        finally:
            if collecting:
                gc.enable()
            self._commit_env()
        if not self.lazy:
            self.sync()
        st, fs = self.st, self.fs  # (views of the pools as they are now)
        terminated = bool(st[k.I_TERMINATED])
        epochs = int(st[k.I_EPOCHS])
        stats = EpisodeStats(
            episode=agent.episodes_done,
            steps=int(st[k.I_STEPS]),
            episode_return=float(fs[k.F_TOTAL]),
            success=bool(st[k.I_SUCCESS]),
            truncated=bool(st[k.I_TRUNCATED]) and not terminated,
            leaves=int(st[k.I_NLEAVES]),
            collisions=int(st[k.I_COLLISIONS]),
            epochs=epochs,
            mean_epsilon=float(fs[k.F_EPS_SUM]) / epochs,
        )
        agent.episodes_done += 1
        return stats

    @property
    def kernel_steps(self) -> int:
        """Steps the kernel took itself so far (the rest went through ``env.step``)."""
        return int(self.st[self.k.I_KERNEL_STEPS])

    @property
    def python_steps(self) -> int:
        """Steps taken by ``env.step`` so far."""
        return int(self.st[self.k.I_PY_STEPS])

    def _agent_unchanged(self) -> bool:
        agent = self.agent
        return (
            agent.q is self._q_list
            and agent.visits is self._visits_list
            and agent.partition is self._partition
            and agent.exploration is self._strategy
            and agent.config is self._config
            and agent.uniform is self._uniform
            and len(agent.q) == self.n_ids
            and agent.partition.n_ids == self.n_ids
        )

    # -- events --------------------------------------------------------------------------

    def _python_step(self) -> None:
        k, st, fs = self.k, self.st, self.fs
        self._commit_env()
        start = time.process_time()
        obs, reward, terminated, truncated, info = self.env.step(int(st[k.I_ACTION]))
        if self.env_seconds is not None:
            self.env_seconds += time.process_time() - start
        x = obs.tolist() if type(obs) is np.ndarray else [float(v) for v in obs]
        fs[k.F_OX], fs[k.F_OY] = x
        fs[k.F_OR] = float(reward)
        st[k.I_TERMINATED] = bool(terminated)
        st[k.I_TRUNCATED] = bool(truncated)
        st[k.I_COLLIDED] = bool(info.get(self.agent.config.collision_key, False))
        st[k.I_SUCCESS] = bool(info["is_success"]) if "is_success" in info else bool(terminated)
        st[k.I_PY_STEPS] += 1
        self._import_env()

    def _sweep_function(self) -> Callable[[float, float, float, float, int], int]:
        """The sweep the kernel calls (through a ctypes callback) for a move it could not
        decide: ``env.step``'s call ``world.sweep_collides(x0, y0, x1, y1)`` and goal test, the
        safe ball and any new cell written into the kernel's arrays; returns collided + 2 *
        success (the kernel does the rest of the step), -1 when it raised (the exception cannot
        cross the callback: it is kept and raised once the kernel has returned).

        ``known`` = 1 (the kernel's ``certified_free`` found the move not proved free on a cell
        it holds, so the world's own ``certified_free`` returns False with no side effect) or 2
        (the safe ball does not hold the move, the cell is unseen in the kernel's table):
        :func:`_sweep_queries`, ``sweep_collides`` from the line the kernel reached, when the
        world's methods are its class's (see :meth:`_queries_for`)."""
        k = self.k
        sx, sy, sr = k.F_SX, k.F_SY, k.F_SR
        hypot, clock = math.hypot, time.process_time
        runner = self
        written: list[Any] = [None]  # the safe ball last written into fs

        def sweep(x0: float, y0: float, x1: float, y1: float, known: int) -> int:
            try:
                world = runner.world
                mirrored = runner._queries if known else None
                if runner.env_seconds is None:
                    if mirrored is not None:
                        collided = mirrored(x0, y0, x1, y1, known)
                    else:
                        collided = world.sweep_collides(x0, y0, x1, y1)
                else:
                    start = clock()
                    if mirrored is not None:
                        collided = mirrored(x0, y0, x1, y1, known)
                    else:
                        collided = world.sweep_collides(x0, y0, x1, y1)
                    runner.env_seconds += clock() - start
                gx, gy = runner.goal
                if collided:
                    success = hypot(x0 - gx, y0 - gy) <= runner.goal_radius
                else:
                    success = hypot(x1 - gx, y1 - gy) <= runner.goal_radius
                # the sweep renews the safe ball and may have seen a new cell (FastCore's
                # safe_ball is World._safe, its cells the live World._cells)
                safe = world._safe
                if safe is not written[0]:
                    fs = runner.fs
                    fs[sx], fs[sy], fs[sr] = safe
                    written[0] = safe
                if len(runner.cell_table) != runner.ncells:
                    runner._import_cells_in_call(runner.cell_table)
                return (2 if success else 0) + (1 if collided else 0)
            except BaseException as error:
                runner._error = error
                return -1

        return sweep

    def _queries_for(self, world: Any) -> Callable[[float, float, float, float, int], bool] | None:
        """:func:`_sweep_queries` for ``world`` (made once per world), or None when one of the
        methods it mirrors or calls is replaced on the instance (then ``world.sweep_collides``
        itself is called)."""
        if any(name in vars(world) for name in _MIRRORED_WORLD_METHODS):
            return None
        made = self._queries_made
        if made is None or made[0] is not world:
            made = self._queries_made = (world, _sweep_queries(world))
        return made[1]

    def _record(self) -> None:
        """The tail of ``_end_epoch`` in Python (when the kernel does not run the split test):
        ``partition.record`` and, after a split, ``_grow``."""
        k, st = self.k, self.st
        agent = self.agent
        leaf = int(st[k.I_REC_LEAF])
        self._write_back()
        start, end = int(st[k.I_REC_START]), int(st[k.I_REC_END])
        xs = self.xs[start:end].tolist()
        errors = self.errs[: end - start].tolist()
        partition = agent.partition
        old_ids = partition.n_ids
        children = partition.record(leaf, xs, errors)
        if children is None:  # the test ran and the buffer was cleared: nothing else changed
            st[k.I_SPLIT] = 0
            self._import_buffer(leaf, partition._buffers.get(leaf))
            return
        agent._grow(leaf, children)
        st[k.I_SPLIT] = 1
        self._import_leaves([leaf, *range(old_ids, partition.n_ids)])

    def _exact_sums(self) -> None:
        """``ErrorBuffer._exact_sums`` of a slot whose ring the kernel filled: NumPy's pairwise
        sum and BLAS's dot product, on the same values in the same order."""
        k, st = self.k, self.st
        slot = int(st[k.I_SUM_SLOT])
        errs = self.buff[slot, : int(self.bctr[slot, k.B_COUNT])]
        self.bsum[slot, 0] = float(errs.sum())
        self.bsum[slot, 1] = float(np.dot(errs, errs))

    def _split_fails(self) -> None:
        """The kernel's split point is not strictly inside the leaf: ``PartitionTree.split``
        raises there, so let it raise, on the state the reference has at that moment."""
        k, st = self.k, self.st
        self._write_back()
        self.agent.partition.split(
            int(st[k.I_REC_LEAF]), int(st[k.I_SPLIT_DIM]), float(self.fs[k.F_SPLIT_VALUE])
        )
        raise RuntimeError("fast loop: the kernel's split check and PartitionTree.split disagree")

    def _make_room(self) -> None:
        """The kernel needs room in its log, its buffer slots or its id table (event EV_POOL)."""
        k, st = self.k, self.st
        if int(st[k.I_NLOG]) + k.LOG_ROOM > self.log.shape[0]:
            self.log = _resized(self.log, 2 * self.log.shape[0] + k.LOG_ROOM)
        if int(st[k.I_NFREE]) < 3:
            self._grow_pool(self.nslots + max(16, self.nslots // 2))
        if int(st[k.I_NIDS]) + 2 > self.li.shape[0]:
            self._ensure_capacity(int(st[k.I_NIDS]) + 2)

    def _next_uniform_block(self) -> None:
        """``UniformStream.random`` found its block spent: draw the next one now, exactly as it
        would, after the draws of this choice not yet committed."""
        k, st = self.k, self.st
        stream = self.agent.uniform
        tail = self.ubuf[int(st[k.I_UPOS]) : int(st[k.I_ULEN])].copy()
        block = stream.generator.random(stream.block)
        size = tail.shape[0] + block.shape[0]
        if size <= self.ubuf.shape[0]:  # in place: the pools stay as they are
            self.ubuf[: tail.shape[0]] = tail
            self.ubuf[tail.shape[0] : size] = block
        else:
            self.ubuf = np.concatenate((tail, block, np.zeros(64)))
        st[k.I_UPOS] = 0
        st[k.I_ULEN] = size
        self.ubase = tail.shape[0]
        self.new_block = True

    def _grow_epoch_arrays(self) -> None:
        size = 2 * self.xs.shape[0]
        self.xs = _resized(self.xs, size)
        self.rs = _resized(self.rs, size)
        self.held = _resized(self.held, size)
        self.errs = _resized(self.errs, size)

    # -- env state -----------------------------------------------------------------------

    def _import_env(self) -> Any:
        """Read the env's state (after a reset or a step taken by ``env.step``)."""
        k, st, fs = self.k, self.st, self.fs
        core = self.base.fast_core()
        fs[k.F_EX], fs[k.F_EY] = core.position
        if core.noise is not self._noise_list:
            self._noise_list = core.noise
            values = core.noise if core.noise else [0.0, 0.0]
            if len(values) <= self.noise.shape[0]:  # in place: the pools stay as they are
                self.noise[: len(values)] = values
            else:
                self.noise = np.array(values, dtype=np.float64)
            st[k.I_NOISE_LEN] = len(core.noise)
        st[k.I_NOISE] = core.noise_index
        fs[k.F_SX], fs[k.F_SY], fs[k.F_SR] = core.safe_ball
        if len(core.cells) != self.ncells:
            self._import_cells(core.cells)
        chain = self.chain
        elapsed = chain.time_limit._elapsed_steps if chain.time_limit is not None else None
        st[k.I_ELAPSED] = elapsed or 0  # None before the first reset
        checker, order = chain.checker, chain.order
        st[k.I_CHECKER_OK] = (
            checker is None or (checker.checked_step and checker.checked_data_reuse)
        ) and (order is None or order._has_reset)
        st[k.I_MOVED] = st[k.I_BODY_MOVED] = 0
        return core

    def _commit_env(self) -> None:
        """Hand the env what the kernel's own steps changed (position, noise, elapsed steps)."""
        k, st, fs = self.k, self.st, self.fs
        if st[k.I_MOVED]:
            position = fs[k.F_EX : k.F_EY + 1].tolist()
            self.base.fast_core(commit=(*position, int(st[k.I_NOISE]), bool(st[k.I_BODY_MOVED])))
            st[k.I_MOVED] = st[k.I_BODY_MOVED] = 0
        if self.chain.time_limit is not None:
            self.chain.time_limit._elapsed_steps = int(st[k.I_ELAPSED])  # type: ignore[assignment]

    def _import_cells(self, cells: dict[tuple[int, int], Any], grow: bool = True) -> None:
        """The world's new cell bounds into the kernel's tables. ``grow=False`` (inside the
        kernel's call, where no array may be replaced): nothing when they do not fit, and the
        next return to Python imports them."""
        k = self.k
        table = self.cells
        new = len(cells) - self.ncells
        index, first = self.nbounds, self.npieces
        if not grow and index + new > self.bounds_c.shape[0]:
            return
        for (cx, cy), bounds in itertools.islice(reversed(cells.items()), new):
            if not (0 <= cx < table.shape[0] and 0 <= cy < table.shape[1]):
                continue  # left unseen: the kernel lets env.step take such moves
            if bounds is None:
                table[cx, cy] = k.CELL_USELESS
                continue
            if index == self.bounds_c.shape[0]:
                self.bounds_c = _resized(self.bounds_c, 2 * index)
                self.bounds_r = _resized(self.bounds_r, 2 * index)
            pieces = bounds.pieces
            count = len(pieces)
            if first + count > self.pieces.shape[0]:
                if not grow:  # ncells stays: the next return imports them all (again)
                    self.nbounds, self.npieces = index, first
                    return
                self.pieces = _resized(self.pieces, 2 * (first + count))
            rows = self.pieces
            for j, (distance, nx, ny) in enumerate(pieces, first):
                rows[j, 0] = distance
                rows[j, 1] = nx
                rows[j, 2] = ny
            centres, ranges = self.bounds_c, self.bounds_r
            centres[index, 0] = bounds.cx
            centres[index, 1] = bounds.cy
            ranges[index, 0] = first
            ranges[index, 1] = count
            table[cx, cy] = index
            index += 1
            first += count
        self.nbounds, self.npieces = index, first
        self.ncells = len(cells)

    def _import_cells_in_call(self, cells: dict[tuple[int, int], Any]) -> None:
        """:meth:`_import_cells` with ``grow=False`` (inside the kernel's call, where no array
        may be replaced), writing through flat memoryviews of the tables (about half the cost
        of NumPy's item assignment; the sweep of a cell's first visit pays it). Nothing when
        they do not fit: the next return to Python imports the cells."""
        views = self._cell_views
        if views is None:
            views = self._cell_views = (
                _flat(self.cells, "q"),
                _flat(self.bounds_c, "d"),
                _flat(self.bounds_r, "q"),
                _flat(self.pieces, "d"),
                self.cells.shape[0],
                self.cells.shape[1],
                self.bounds_c.shape[0],
                self.pieces.shape[0],
            )
        table, centres, ranges, rows, width, height, max_bounds, max_pieces = views
        total = len(cells)
        new = total - self.ncells
        index, first = self.nbounds, self.npieces
        if index + new > max_bounds:
            return
        useless = self.k.CELL_USELESS
        for (cx, cy), bounds in itertools.islice(reversed(cells.items()), new):
            if not (0 <= cx < width and 0 <= cy < height):
                continue  # left unseen: the kernel lets env.step take such moves
            if bounds is None:
                table[cx * height + cy] = useless
                continue
            pieces = bounds.pieces
            count = len(pieces)
            if first + count > max_pieces:  # ncells stays: the next return imports them all
                self.__dict__.update(nbounds=index, npieces=first)
                return
            j = 3 * first
            for distance, nx, ny in pieces:
                rows[j] = distance
                rows[j + 1] = nx
                rows[j + 2] = ny
                j += 3
            centres[2 * index] = bounds.cx
            centres[2 * index + 1] = bounds.cy
            ranges[2 * index] = first
            ranges[2 * index + 1] = count
            table[cx * height + cy] = index
            index += 1
            first += count
        self.__dict__.update(nbounds=index, npieces=first, ncells=total)

    # -- agent state ---------------------------------------------------------------------

    def _export(self) -> None:
        """Copy the whole agent into fresh arrays (at the start, or after a callback replaced
        part of it)."""
        k = self.k
        agent = self.agent
        config = agent.config
        partition = agent.partition
        strategy = agent.exploration
        tabu = strategy if type(strategy) is Tabu else None
        base: Any = tabu.base if tabu is not None else strategy
        actions = agent.n_actions
        self._q_list, self._visits_list = agent.q, agent.visits
        self._partition, self._strategy = partition, strategy
        self._config, self._uniform = config, agent.uniform
        self.tabu, self.strategy_base = tabu, base

        st = self.st = np.zeros(k.N_INT, dtype=np.int64)
        fs = self.fs = np.zeros(k.N_FLOAT, dtype=np.float64)
        st[k.I_SWEEP] = _address(self._sweep_callback)
        is_tree = type(partition) is PartitionTree
        st[k.C_KIND] = 0 if is_tree else 1
        st[k.C_ACTIONS] = actions
        st[k.C_EPOCH_CAP] = (
            config.max_epoch_steps if config.max_epoch_steps is not None else 1 << 62
        )
        st[k.C_HOLD_EXPLORATION] = config.hold_exploration
        st[k.C_END_ON_COLLISION] = config.end_epoch_on_collision
        st[k.C_RECORDS] = partition.records_errors
        st[k.C_BUFFER_CAP] = config.split_min_samples
        fs[k.F_ALPHA] = config.alpha
        fs[k.F_GAMMA] = config.gamma
        if type(base) is AdaptiveEpsilon:
            st[k.C_STRATEGY] = k.S_ADAPTIVE
            st[k.C_VARIANT] = base.variant == "cn_exponent"
            fs[k.F_CN], fs[k.F_CH] = base.c_n, base.c_h
        elif type(base) is VDBE:
            st[k.C_STRATEGY] = k.S_VDBE
            st[k.C_VARIANT] = base.form == "exponential"
            fs[k.F_SIGMA] = base.sigma
            fs[k.F_DELTA] = base.delta if base.delta is not None else 1.0 / base.n_actions
        else:
            st[k.C_STRATEGY] = k.S_EPSILON
            fs[k.F_EPSILON] = base._epsilon
        st[k.I_EXPLORED] = getattr(strategy, "explored", False)
        st[k.I_BASE_EXPLORED] = getattr(base, "explored", False)
        st[k.C_STRATEGY_INHERIT] = bool(getattr(base, "inherit_on_split", False))
        st[k.C_TABU_INHERIT] = tabu is not None and tabu.on_split_policy == "inherit"
        # the split test (PartitionTree.record, _try_split, split) and _grow
        st[k.C_KREC] = is_tree and _split_in_kernel(partition, config)
        if st[k.C_KREC]:
            fs[k.F_RW0], fs[k.F_RW1] = partition._root_width.tolist()
            fs[k.F_MIN_FRACTION] = config.min_leaf_fraction
            fs[k.F_MAX_ABS_MEAN] = config.split_max_abs_mean
            fs[k.F_MIN_VARIANCE] = config.split_min_variance
            fs[k.F_MIN_T] = config.split_min_t
            fs[k.F_Q_INIT] = agent.q_init
            st[k.C_MAX_LEAVES] = config.max_leaves
            st[k.C_MIDPOINT] = config.split_point == "midpoint"
            st[k.C_ROOT_NORM] = config.range_normalization == "root"
            st[k.C_INHERIT_SAMPLES] = config.children_inherit_samples
            st[k.C_INHERIT_Q] = config.inherit_q
            st[k.C_RESET_COUNTS] = config.reset_counts_on_split

        n_ids = self.n_ids = partition.n_ids
        st[k.I_NIDS] = n_ids
        st[k.I_NLEAVES] = partition.n_leaves
        capacity = max(64, 2 * n_ids)
        self.li = np.zeros((capacity, k.N_LI), dtype=np.int64)
        self.lf = np.zeros((capacity, k.N_LF), dtype=np.float64)
        self.li[:, k.L_DIM] = -1
        self.li[:, k.L_SLOT] = -1
        self.q = np.zeros((capacity, actions), dtype=np.float64)
        self.visits = np.zeros((capacity, actions), dtype=np.int64)
        self.counts = np.zeros((capacity, actions), dtype=np.int64)
        self.dirty = np.zeros(capacity, dtype=np.int64)
        self.log = np.zeros((256, 2), dtype=np.int64)
        self.grid_f = np.zeros((2, 2), dtype=np.float64)
        self.grid_i = np.ones((2, 2), dtype=np.int64)
        if not is_tree:
            for i, low, scale, cells, stride in partition._terms:
                self.grid_f[i] = (low, scale)
                self.grid_i[i] = (cells, stride)

        ring = 4
        if tabu is not None:
            ring = max(tabu.initial_capacity, tabu.min_capacity, len(tabu._fifo)) + actions + 4
            st[k.C_TABU] = 1
            st[k.C_TABU_INITIAL] = tabu.initial_capacity
            st[k.C_TABU_SHRINK] = tabu.shrink_every
            st[k.C_TABU_MIN] = tabu.min_capacity
            st[k.C_TABU_RESPECTS] = tabu.random_respects_list
            st[k.C_TABU_DEVIATION] = tabu.deviation_explores
            st[k.C_TABU_ALL_RANDOM] = tabu.all_listed == "random"
        self.fifo = np.zeros((ring, 2), dtype=np.int64)

        buffer_cap = config.split_min_samples
        self.nslots = 0
        self.bufi = np.zeros((0, 2 * buffer_cap), dtype=np.float64)
        self.buff = np.zeros((0, buffer_cap), dtype=np.float64)
        self.bctr = np.zeros((0, k.N_BCTR), dtype=np.int64)
        self.bsum = np.zeros((0, 2), dtype=np.float64)
        self.free = np.zeros(0, dtype=np.int64)
        self._grow_pool((partition.n_leaves if is_tree else 0) + 16)
        self._import_all()

        stream = agent.uniform
        self.ubuf = np.zeros(max(len(stream._buffer), stream.block) + 64, dtype=np.float64)
        self.ubuf[: len(stream._buffer)] = stream._buffer
        st[k.I_UPOS] = stream._position
        st[k.I_ULEN] = len(stream._buffer)
        self.ubase = 0
        self.new_block = False

        size = config.max_epoch_steps if config.max_epoch_steps is not None else 1024
        size = max(8, min(size, 1 << 16))
        self.xs = np.zeros((size, 2), dtype=np.float64)
        self.rs = np.zeros(size, dtype=np.float64)
        self.held = np.zeros(size, dtype=np.int64)
        self.errs = np.zeros(size, dtype=np.float64)

        core = self.base.fast_core()
        limit = self.chain.time_limit
        max_steps = limit._max_episode_steps if limit is not None else None
        st[k.C_MAX_STEPS] = -1 if max_steps is None else max_steps
        self.moves = np.array(core.moves, dtype=np.float64).reshape(-1, 2)
        fs[k.F_R_GOAL] = core.goal_reward
        fs[k.F_R_STEP] = core.step_reward
        fs[k.F_R_COLLISION] = core.collision_reward
        self.world = core.world
        self.cell_table = core.cells
        fs[k.F_CELL] = core.cell
        fs[k.F_CELL_REACH] = core.cell_reach
        fs[k.F_TOLERANCE] = core.tolerance
        width, height = core.arena
        self.cells = np.full(
            (int(width // core.cell) + 2, int(height // core.cell) + 2),
            k.CELL_UNSEEN,
            dtype=np.int64,
        )
        rows = max(64, min(self.cells.size, 1 << 16))  # room for most cells at once
        self.bounds_c = np.zeros((rows, 2), dtype=np.float64)
        self.bounds_r = np.zeros((rows, 2), dtype=np.int64)
        self.pieces = np.zeros((4 * rows, 3), dtype=np.float64)
        self.nbounds = self.npieces = self.ncells = 0
        self._noise_list = None
        self.noise = np.zeros(2, dtype=np.float64)
        self._import_env()

    def _ensure_capacity(self, rows: int) -> None:
        """Room for ``rows`` ids in the per-id tables."""
        capacity = self.li.shape[0]
        if rows > capacity:
            size = max(2 * capacity, rows)
            li = _resized(self.li, size)
            li[capacity:, self.k.L_DIM] = -1
            li[capacity:, self.k.L_SLOT] = -1
            self.li = li
            self.lf = _resized(self.lf, size)
            self.q = _resized(self.q, size)
            self.visits = _resized(self.visits, size)
            self.counts = _resized(self.counts, size)
            self.dirty = _resized(self.dirty, size)

    def _grow_pool(self, size: int) -> None:
        old = self.nslots
        if size <= old:
            return
        self.bufi = _resized(self.bufi, size)
        self.buff = _resized(self.buff, size)
        self.bctr = _resized(self.bctr, size)
        self.bsum = _resized(self.bsum, size)
        k = self.k
        nfree = int(self.st[k.I_NFREE])
        free = np.zeros(size, dtype=np.int64)
        free[:nfree] = self.free[:nfree]
        added = np.arange(size - 1, old - 1, -1, dtype=np.int64)  # lowest slot on top
        free[nfree : nfree + added.shape[0]] = added
        self.free = free
        self.st[k.I_NFREE] = nfree + added.shape[0]
        self.nslots = size

    def _import_leaves(self, ids: Any) -> None:
        """Copy these ids' tree node, Q-bar, counts, strategy state and error buffer from the
        Python objects (they are the truth after Python code ran)."""
        k = self.k
        agent = self.agent
        partition = agent.partition
        self._ensure_capacity(partition.n_ids + 2)
        li, lf = self.li, self.lf
        base = self.strategy_base
        is_tree = type(partition) is PartitionTree
        adaptive = type(base) is AdaptiveEpsilon
        vdbe = type(base) is VDBE
        for i in ids:
            if is_tree:
                li[i, k.L_DIM] = partition._dim[i]
                li[i, k.L_LEFT] = partition._left[i]
                li[i, k.L_PARENT] = partition._parent[i]
                li[i, k.L_DEPTH] = partition._depth[i]
                lf[i, k.LF_THRESHOLD] = partition._threshold[i]
                lf[i, k.LF_LO0 : k.LF_LO1 + 1] = partition._low[i]
                lf[i, k.LF_HI0 : k.LF_HI1 + 1] = partition._high[i]
            self.q[i] = agent.q[i]
            self.visits[i] = agent.visits[i]
            li[i, k.L_COUNTS_HAS] = li[i, k.L_EPS_HAS] = 0
            if adaptive:
                counts = base._counts.get(i)
                if counts is not None:
                    self.counts[i] = counts
                    li[i, k.L_COUNTS_HAS] = 1
            if adaptive or vdbe:
                eps = base._epsilon.get(i)
                if eps is not None:
                    lf[i, k.LF_EPS] = eps
                    li[i, k.L_EPS_HAS] = 1
            if is_tree:
                self._import_buffer(i, partition._buffers.get(i))
            li[i, k.L_DIRTY] = 0
        self.n_ids = partition.n_ids
        self.st[k.I_NIDS] = partition.n_ids
        self.st[k.I_NLEAVES] = partition.n_leaves
        if is_tree:
            live = int(np.count_nonzero(li[: self.n_ids, k.L_SLOT] >= 0))
            needed = partition.n_leaves - live
            if int(self.st[k.I_NFREE]) < needed + 3:
                self._grow_pool(self.nslots + needed + 16)
        self._import_tabu()

    def _import_all(self) -> None:
        """:meth:`_import_leaves` of every id, in bulk."""
        k, li, lf = self.k, self.li, self.lf
        agent = self.agent
        partition: Any = agent.partition
        n = self.n_ids
        self.q[:n] = agent.q
        self.visits[:n] = agent.visits
        if type(partition) is PartitionTree:
            li[:n, k.L_DIM] = partition._dim
            li[:n, k.L_LEFT] = partition._left
            li[:n, k.L_PARENT] = partition._parent
            li[:n, k.L_DEPTH] = partition._depth
            lf[:n, k.LF_THRESHOLD] = partition._threshold
            lf[:n, k.LF_LO0 : k.LF_LO1 + 1] = partition._low
            lf[:n, k.LF_HI0 : k.LF_HI1 + 1] = partition._high
            for leaf, buf in partition._buffers.items():
                self._import_buffer(leaf, buf)
        base = self.strategy_base
        if type(base) is AdaptiveEpsilon:
            for leaf, counts in base._counts.items():
                self.counts[leaf] = counts
                li[leaf, k.L_COUNTS_HAS] = 1
        if type(base) is AdaptiveEpsilon or type(base) is VDBE:
            for leaf, eps in base._epsilon.items():
                lf[leaf, k.LF_EPS] = eps
                li[leaf, k.L_EPS_HAS] = 1
        self._import_tabu()

    def _import_buffer(self, leaf: int, buf: ErrorBuffer | None) -> None:
        k, st, li = self.k, self.st, self.li
        slot = int(li[leaf, k.L_SLOT])
        if buf is None:
            if slot >= 0:  # the leaf split: its buffer was dropped
                self.free[st[k.I_NFREE]] = slot
                st[k.I_NFREE] += 1
                li[leaf, k.L_SLOT] = -1
            return
        if slot < 0:
            if st[k.I_NFREE] == 0:
                self._grow_pool(self.nslots + 16)
            st[k.I_NFREE] -= 1
            slot = int(self.free[st[k.I_NFREE]])
            li[leaf, k.L_SLOT] = slot
        buf.allocate()  # the pool's row is the buffer at full size
        self.bufi[slot] = np.frombuffer(buf.inputs, dtype=np.float64)
        self.buff[slot] = np.frombuffer(buf.errors, dtype=np.float64)
        self.bctr[slot] = (buf.count, buf.head, buf.capacity, 0)  # nothing to copy back
        self.bsum[slot] = (buf.sum, buf.sum_sq)

    def _import_tabu(self) -> None:
        k, st, li = self.k, self.st, self.li
        tabu = self.tabu
        if tabu is None:
            return
        li[: self.n_ids, k.L_TABU_MASK] = 0
        pairs = list(tabu._fifo)
        if len(pairs) + self.agent.n_actions + 4 > self.fifo.shape[0]:
            self.fifo = np.zeros((len(pairs) + self.agent.n_actions + 4, 2), dtype=np.int64)
        for j, (leaf, action) in enumerate(pairs):
            self.fifo[j] = (leaf, action)
            li[leaf, k.L_TABU_MASK] |= 1 << action
        st[k.I_TABU_HEAD] = 0
        st[k.I_TABU_LEN] = len(pairs)
        st[k.I_TABU_CAPACITY] = tabu._capacity
        st[k.I_TABU_SUCCESSES] = tabu.successes
        st[k.I_TABU_DIRTY] = 0

    def sync(self) -> None:
        """Write what the kernel changed into the Python objects.

        ``learn`` calls this before each callback and when it returns (or raises); the kernel's
        arrays are the truth in between. The tree's new nodes, the dicts' entries in the order
        the reference creates and drops them (the kernel's log), then every changed id's values.
        Nothing happens when the kernel has not run since the last call.
        """
        if self._pending:
            self._write_back()
            self._pending = False

    def _write_back(self) -> None:
        k, st = self.k, self.st
        agent = self.agent
        partition = agent.partition
        n_ids = int(st[k.I_NIDS])
        nlog = int(st[k.I_NLOG])
        log = self.log[:nlog].tolist() if nlog else []
        if type(partition) is PartitionTree and (nlog or n_ids != len(partition._dim)):
            self._write_tree(log, n_ids)
        if n_ids > len(agent.q):
            width = agent.n_actions
            agent.q.extend([0.0] * width for _ in range(n_ids - len(agent.q)))
            agent.visits.extend([0] * width for _ in range(n_ids - len(agent.visits)))
        if log:
            self._replay_log(log)
            st[k.I_NLOG] = 0
        n = int(st[k.I_NDIRTY])
        if n:
            st[k.I_NDIRTY] = 0
            self._write_leaves(self.dirty[:n].copy())
        self.n_ids = n_ids
        tabu = self.tabu
        if tabu is not None and st[k.I_TABU_DIRTY]:
            ring = self.fifo.shape[0]
            head, length = int(st[k.I_TABU_HEAD]), int(st[k.I_TABU_LEN])
            order = [(head + j) % ring for j in range(length)]
            pairs = [(leaf, action) for leaf, action in self.fifo[order].tolist()]
            tabu._fifo.clear()
            tabu._fifo.extend(pairs)
            by_leaf: dict[int, set[int]] = {}
            for leaf, action in pairs:
                by_leaf.setdefault(leaf, set()).add(action)
            tabu._by_leaf = by_leaf
            tabu._capacity = int(st[k.I_TABU_CAPACITY])
            tabu.successes = int(st[k.I_TABU_SUCCESSES])
            if length:  # compact the ring so that it starts at 0 again
                self.fifo[:length] = self.fifo[order]
            st[k.I_TABU_HEAD] = 0
            st[k.I_TABU_DIRTY] = 0
        if st[k.I_EXPLORED_DIRTY]:
            self.agent.exploration.explored = bool(st[k.I_EXPLORED])
            if tabu is not None and st[k.I_BASE_SELECTED]:
                tabu.base.explored = bool(st[k.I_BASE_EXPLORED])
            st[k.I_EXPLORED_DIRTY] = st[k.I_BASE_SELECTED] = 0
        stream = self.agent.uniform
        if self.new_block:
            stream._buffer = self.ubuf[self.ubase : int(st[k.I_ULEN])].tolist()
            self.new_block = False
        stream._position = int(st[k.I_UPOS]) - self.ubase

    def _write_tree(self, log: list[list[int]], n_ids: int) -> None:
        """The nodes the kernel split and the ones it added, into the tree's lists."""
        k = self.k
        partition: Any = self.agent.partition
        li, lf = self.li, self.lf
        old = len(partition._dim)
        for kind, i in log:
            if kind == k.LOG_SPLIT and i < old:
                partition._dim[i] = int(li[i, k.L_DIM])
                partition._threshold[i] = float(lf[i, k.LF_THRESHOLD])
                partition._left[i] = int(li[i, k.L_LEFT])
        if n_ids > old:
            rows = li[old:n_ids].tolist()
            values = lf[old:n_ids].tolist()
            for row, value in zip(rows, values, strict=True):
                partition._dim.append(row[k.L_DIM])
                partition._threshold.append(value[k.LF_THRESHOLD])
                partition._left.append(row[k.L_LEFT])
                partition._parent.append(row[k.L_PARENT])
                partition._low.append([value[k.LF_LO0], value[k.LF_LO1]])
                partition._high.append([value[k.LF_HI0], value[k.LF_HI1]])
                partition._depth.append(row[k.L_DEPTH])
        partition.n_leaves = int(self.st[k.I_NLEAVES])

    def _replay_log(self, log: list[list[int]]) -> None:
        """Create and drop the dicts' entries in the kernel's order (values come after)."""
        k = self.k
        partition: Any = self.agent.partition
        buffers = partition._buffers if type(partition) is PartitionTree else {}
        base = self.strategy_base
        counts: dict[int, Any] = base._counts if type(base) is AdaptiveEpsilon else {}
        epsilon: dict[int, Any] = (
            base._epsilon if type(base) is AdaptiveEpsilon or type(base) is VDBE else {}
        )
        dims, capacity = 2, self.agent.config.split_min_samples
        for kind, i in log:
            if kind == k.LOG_BUFFER:
                buffers[i] = ErrorBuffer(dims, capacity)
            elif kind == k.LOG_COUNTS:
                counts[i] = None
            elif kind == k.LOG_EPS:
                epsilon[i] = None
            else:
                buffers.pop(i, None)
                row = counts.pop(i, None)
                if row is not None:  # the list the reference stops updating here
                    row[:] = self.counts[i].tolist()
                epsilon.pop(i, None)

    def _write_leaves(self, ids: np.ndarray) -> None:
        k = self.k
        agent = self.agent
        id_list = ids.tolist()
        q, visits = agent.q, agent.visits
        for i, row, counts in zip(
            id_list, self.q[ids].tolist(), self.visits[ids].tolist(), strict=True
        ):
            q[i][:] = row
            visits[i][:] = counts
        flags = self.li[ids].tolist()
        base = self.strategy_base
        if type(base) is AdaptiveEpsilon or type(base) is VDBE:
            eps_table = base._epsilon
            eps_values = self.lf[ids, k.LF_EPS].tolist()
            if type(base) is AdaptiveEpsilon:
                table = base._counts
                for i, f, row, eps in zip(
                    id_list, flags, self.counts[ids].tolist(), eps_values, strict=True
                ):
                    if f[k.L_COUNTS_HAS]:
                        current = table.get(i)
                        if current is None:
                            table[i] = row
                        else:
                            current[:] = row
                    if f[k.L_EPS_HAS]:
                        eps_table[i] = eps
            else:
                for i, f, eps in zip(id_list, flags, eps_values, strict=True):
                    if f[k.L_EPS_HAS]:
                        eps_table[i] = eps
        partition = agent.partition
        if type(partition) is PartitionTree:
            buffers = partition._buffers
            bufi, buff, bctr, bsum = self.bufi, self.buff, self.bctr, self.bsum
            slots = self.li[ids, k.L_SLOT]
            counters = bctr[slots].tolist()
            sums = bsum[slots].tolist()
            capacity = agent.config.split_min_samples
            for i, slot, (count, head, low, high), (total, total_sq) in zip(
                id_list, slots.tolist(), counters, sums, strict=True
            ):
                if slot < 0:
                    continue
                buf = buffers[i]
                if high > low:  # the stretch of storage the kernel wrote since the last copy
                    buf.allocate()
                    inputs = np.frombuffer(buf.inputs, dtype=np.float64)
                    inputs[2 * low : 2 * high] = bufi[slot, 2 * low : 2 * high]
                    np.frombuffer(buf.errors, dtype=np.float64)[low:high] = buff[slot, low:high]
                    bctr[slot, k.B_LOW] = capacity
                    bctr[slot, k.B_HIGH] = 0
                buf.count, buf.head = count, head
                buf.sum, buf.sum_sq = total, total_sq
        self.li[ids, k.L_DIRTY] = 0

    # -- plumbing ------------------------------------------------------------------------

    def _args(self) -> tuple[Any, ...]:
        """The kernel's arguments (rebuilt after any array was replaced)."""
        if self._argtuple is None:
            self._argtuple = self._build_args()
        return self._argtuple

    def _build_args(self) -> tuple[Any, ...]:
        """``fast_kernel.run_pooled``'s arguments: the arrays of POOLED_INT and POOLED_FLOAT
        copied into two pools (the attributes become views of them) and their layout. Handlers
        must read the arrays from ``self`` (a replaced array moves every view)."""
        k = self.k
        names = (*k.POOLED_INT, *k.POOLED_FLOAT)
        lay = np.zeros((len(names), 3), dtype=np.int64)
        sizes = {np.dtype(np.int64): 0, np.dtype(np.float64): 0}
        arrays = [getattr(self, name) for name in names]
        for i, array in enumerate(arrays):
            rows = array.shape[0]
            columns = array.shape[1] if array.ndim == 2 else 1
            lay[i] = (sizes[array.dtype], rows, columns)
            sizes[array.dtype] += rows * columns
        pools = {dtype: np.zeros(max(size, 1), dtype=dtype) for dtype, size in sizes.items()}
        for i, (name, array) in enumerate(zip(names, arrays, strict=True)):
            start, size = int(lay[i, 0]), array.size
            view = pools[array.dtype][start : start + size].reshape(array.shape)
            view[...] = array
            object.__setattr__(self, name, view)
        self._cell_views = None
        return (pools[np.dtype(np.int64)], pools[np.dtype(np.float64)], lay)

    def _dummy_arrays(self, k: Any) -> None:
        """Arrays of the kernel's types for a call that returns at once (the warm-up)."""
        self.st = np.zeros(k.N_INT, dtype=np.int64)
        self.st[k.I_PHASE] = k.PH_DONE
        self.fs = np.zeros(k.N_FLOAT, dtype=np.float64)
        self.li = np.zeros((1, k.N_LI), dtype=np.int64)
        self.lf = np.zeros((1, k.N_LF), dtype=np.float64)
        self.q = np.zeros((1, 1), dtype=np.float64)
        self.visits = self.counts = np.zeros((1, 1), dtype=np.int64)
        self.fifo = np.zeros((1, 2), dtype=np.int64)
        self.ubuf = self.rs = self.errs = np.zeros(1, dtype=np.float64)
        self.grid_f = np.zeros((2, 2), dtype=np.float64)
        self.grid_i = np.ones((2, 2), dtype=np.int64)
        self.xs = np.zeros((1, 2), dtype=np.float64)
        self.held = self.free = self.dirty = np.zeros(1, dtype=np.int64)
        self.bufi = self.buff = np.zeros((1, 2), dtype=np.float64)
        self.bctr = np.zeros((1, k.N_BCTR), dtype=np.int64)
        self.log = np.zeros((1, 2), dtype=np.int64)
        self.bsum = np.zeros((1, 2), dtype=np.float64)
        self.li = np.zeros((1, k.N_LI), dtype=np.int64)
        self.moves = np.zeros((1, 2), dtype=np.float64)
        self.noise = np.zeros(2, dtype=np.float64)
        self.cells = np.zeros((1, 1), dtype=np.int64)
        self.bounds_c = np.zeros((1, 2), dtype=np.float64)
        self.bounds_r = np.zeros((1, 2), dtype=np.int64)
        self.pieces = np.zeros((1, 3), dtype=np.float64)


_MIRRORED_WORLD_METHODS = (
    "sweep_collides",
    "certified_free",
    "_closest",
    "place_probe",
    "clear_within",
    "_cell_bounds",
)
"""The world's methods :func:`_sweep_queries` mirrors or calls: replaced on the instance (a test,
a wrapper), the world's own ``sweep_collides`` runs instead."""


def _sweep_queries(world: Any) -> Callable[[float, float, float, float, int], bool]:
    """``world.sweep_collides(x0, y0, x1, y1)`` from where the kernel stopped: ``known`` = 1,
    after its first line, for a move its ``certified_free`` does not prove free (the kernel
    knows that, with no side effect to make); ``known`` = 2, ``certified_free`` from the cell
    lookup on (its safe ball does not hold the move). The same statements in the same order
    (fingerprints ``World.sweep_collides``, ``World.certified_free``, ``World._closest``,
    ``World.place_probe``), so the same answer, safe ball, cell cache and pybullet queries,
    without the Python calls around them. A world of one solid body gets ``_closest``'s lines
    inline (the footprint's shape placed by the query); any other calls ``world._closest``."""
    module = sys.modules[type(world).__module__]
    cell_size, unseen = module.CELL, module._UNSEEN
    pb = module.pb
    metres = module.METRES_PER_UNIT
    tolerance = module.CONTACT_TOLERANCE
    half_tolerance = tolerance / 2
    safe_reach = module.SAFE_REACH
    max_queries = module.MAX_SWEEP_QUERIES
    height = module.WALL_HEIGHT / 4 * metres
    hypot, inf = math.hypot, math.inf
    release = world.contact_release
    closest: Callable[[float, float, float], Any]
    single = world._single
    if single is not None:
        shape, client = world._probe_shape, world.client
        points_of = pb.getClosestPoints

        def closest_single(x: float, y: float, reach: float) -> Any:
            far = (reach + tolerance) * metres
            return points_of(
                -1,
                single,
                far,
                collisionShapeA=shape,
                collisionShapePositionA=(x * metres, y * metres, height),
                physicsClientId=client,
            )

        closest = closest_single
    else:
        closest = world._closest

    def queries(x0: float, y0: float, x1: float, y1: float, known: int) -> bool:
        if known == 2:  # certified_free's last lines
            cell = (int(x0 // cell_size), int(y0 // cell_size))
            cells = world._cells
            bounds = cells.get(cell, unseen)
            if bounds is unseen:
                bounds = cells[cell] = world._cell_bounds(cell)
            if bounds is not None and bounds.clear(x0, y0, x1, y1):
                return False
        length = hypot(x1 - x0, y1 - y0)
        if length == 0.0:
            return not world.clear_within(x0, y0, 0.0)
        ux, uy = (x1 - x0) / length, (y1 - y0) / length
        look = max(length, safe_reach)
        points = closest(x0, y0, look)
        gap = min((p[8] for p in points), default=inf) / metres
        world._safe = (x0, y0, min(gap, look) - tolerance)
        travelled = 0.0
        for _ in range(max_queries):
            advance = inf
            for point in points:
                distance = point[8] / metres
                normal = point[7]
                rate = ux * normal[0] + uy * normal[1]
                if distance < tolerance and (rate < 0.0 or not release):
                    return True
                if rate < 0.0:
                    advance = min(advance, (distance - half_tolerance) / -rate)
            travelled += advance
            if travelled >= length:
                return False
            points = closest(x0 + travelled * ux, y0 + travelled * uy, length - travelled)
        return True

    return queries


def _flat(array: np.ndarray, code: Literal["d", "q"]) -> memoryview[Any]:
    """A flat memoryview of a C-contiguous array's own memory (``cast`` raises otherwise)."""
    return array.data.cast("B").cast(code)


def _address(callback: Any) -> int:
    """The C address of a ctypes callback (the kernel calls it there; the caller keeps the
    callback alive)."""
    address = ctypes.cast(callback, ctypes.c_void_p).value
    assert address is not None
    return address


def _resized(array: np.ndarray, rows: int) -> np.ndarray:
    """A copy of ``array`` with ``rows`` rows (the first ones kept, new ones zero)."""
    out = np.zeros((rows, *array.shape[1:]), dtype=array.dtype)
    keep = min(rows, array.shape[0])
    out[:keep] = array[:keep]
    return out


register_fast_runner(episode_runner)
