"""Every threshold of the learner in one dataclass; the defaults are the paper's Table I.

Hwang, Li and Jiang, "Adaptive Exploration Strategies for Reinforcement Learning": section IV
(eqs. 6-13) and Table I. Where the paper is silent the default is the reading documented in
``docs/paper-notes.md``; every alternative reading is a field here.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any, Literal

from agent.scale import HORIZON_RANGE
from agent.value_checks import check_value, plain_scalar, type_hints

ErrorBuffer = Literal["clear", "window"]
RangeNormalization = Literal["root", "none"]
SplitPointRule = Literal["quest", "midpoint"]
ThresholdUnits = Literal["reward", "scale"]
Planning = Literal["none", "sweep"]
ScaleRule = Literal["reward_median", "return_std", "return_iqr"]

MAX_TABLE = 1 << 16
"""Most cells ``TreeConfig.table_cells`` may allow (the tree's presplit limit, 2^16 leaves)."""


@dataclass(frozen=True)
class TreeConfig:
    """Learning, epoch and split parameters of the adaptive decision tree (section IV)."""

    alpha: float = 0.3
    """Learning rate of eq. (10) (Table I: 0.3)."""
    gamma: float = 0.99
    """Discount rate of eqs. (6), (7), (9) (Table I: 0.99)."""
    q_init: float = 0.0
    """Initial Q-bar of every (leaf, action) of a fresh partition (not given by the paper)."""
    max_epoch_steps: int | None = 50
    """An epoch (section IV.A) ends after this many steps; None holds it until the leaf changes."""
    hold_exploration: bool = True
    """An exploratory (random) action is held across leaf boundaries until a collision, the end
    of the episode or ``max_epoch_steps``; learning still sees one epoch per leaf crossed.
    Not in the paper (False is the literal reading): without it the robot chatters across leaf
    boundaries and most seeds never learn (docs/paper-notes.md, "Held exploration")."""
    end_epoch_on_collision: bool = True
    """An epoch also ends when the env reports a collision (``info[collision_key]``)."""
    collision_key: str = "collision"
    """Key of the env's ``info`` dict that reports a collision (counted in EpisodeStats)."""
    split_min_samples: int = 500
    """Split condition 1, N_th: state-error pairs a leaf must hold before it is tested (Table I)."""
    split_max_abs_mean: float = 0.5
    """Split condition 2, mu_th: split only if |mean error| < this (Table I: threshold mean)."""
    split_min_variance: float = 0.03
    """Split condition 3, sigma_th^2: split only if the error variance > this (Table I)."""
    error_buffer: ErrorBuffer = "clear"
    """State-error pairs per leaf: "clear" (emptied after each split test) or "window" (FIFO)."""
    range_normalization: RangeNormalization = "root"
    """range_i of eq. (12): the leaf's width divided by the root's ("root") or raw ("none")."""
    split_point: SplitPointRule = "quest"
    """Eq. (13): where the count-weighted group densities cross ("quest", Loh and Shih 1997,
    the midpoint of the group means when they do not cross between them) or always the
    midpoint of the two group means ("midpoint")."""
    inherit_q: bool = True
    """Children of a split start with the parent's Q-bar (else with q_init)."""
    reset_counts_on_split: bool = True
    """Children's visit counts restart at 0 (else they copy the parent's)."""
    children_inherit_samples: bool = True
    """A split divides the parent's stored state-error pairs between the children (else dropped)."""
    min_leaf_fraction: float = 1.0 / 256.0
    """No leaf narrower than this fraction of the root's width in the split dimension (a guard)."""
    max_leaves: int = 4096
    """The tree stops splitting at this many leaves, which bounds memory (a guard)."""

    # Beyond the paper: every field below defaults to the paper's behaviour (docs/paper-notes.md,
    # "Beyond the paper: a learner that is fast everywhere").
    threshold_units: ThresholdUnits = "reward"
    """Units of ``split_max_abs_mean``, ``split_min_variance`` and ``sweep_tolerance`` and
    ``model_bonus``: "reward" (as printed: Table I's values are in the maze's reward units) or
    "scale" (multiples of the value unit the agent measures, the median nonzero |reward| seen so
    far times ``scale_horizon`` (1 / (1 - gamma) unless set), :class:`agent.scale.RewardScale`:
    1 on the paper's maze, 100 on MountainCar; the variance threshold is a multiple of its
    square), so that one set of values fits any reward scale."""
    scale_rule: ScaleRule = "return_std"
    """The measured unit of ``threshold_units="scale"``: "return_std", the standard deviation of
    every eq. (9) return so far (:class:`agent.scale.ReturnScale`), or "reward_median", the
    median nonzero |reward| times ``scale_horizon`` (:class:`agent.scale.RewardScale`)."""
    scale_horizon: float | None = None
    """With ``scale_rule="reward_median"``: the horizon H of the unit ``median |r| x H``. None
    (the default) is ``1 / (1 - gamma)``, so the unit follows the discount. A number keeps the
    split test's unit fixed while ``gamma`` moves: the general preset uses ``gamma`` 0.999 with
    H = 100, the unit of ``gamma`` 0.99 (docs/paper-notes.md, "A longer discount"). Steps, so
    it needs no scale; in :data:`agent.scale.HORIZON_RANGE`."""
    split_min_t: float = 0.0
    """A fourth split condition, a significance gate: split only if, in some dimension, the
    inputs with positive errors and those with negative errors lie apart by at least this Welch
    t statistic (eq. (12) without its range weight; dimensionless, so it needs no scale). It
    refines fast where the values differ clearly (deterministic tasks) and waits for more
    evidence where the returns are noisy. 0: off (the paper's three conditions)."""
    planning: Planning = "none"
    """"none": eq. (10) alone (the paper). "sweep": an empirical SMDP model of each (leaf, action)
    over its last ``model_window`` epochs gives Q-bar, and prioritized sweeping pushes each
    change back to the leaves whose epochs end there (:mod:`agent.leaf_model`)."""
    model_window: int = 32
    """Epochs kept per (leaf, action) by ``planning="sweep"`` (the model follows a changing
    policy by forgetting older epochs)."""
    sweep_backups: int = 16
    """Backups of prioritized sweeping after each epoch (``planning="sweep"``)."""
    sweep_tolerance: float = 1e-3
    """A leaf whose V-bar moved by more than this queues its predecessors (``threshold_units``)."""
    model_bonus: float = 0.0
    """MBIE-EB bonus (Strehl and Littman 2008) ``beta / sqrt(n(leaf, a))`` added to every model
    backup, ``beta`` in ``threshold_units``, n the epochs recorded for (leaf, a); it propagates
    through the sweeps, so the greedy policy heads for what is least tried (0: none)."""
    initial_depth: int = 0
    """The tree starts with its root split at the midpoints ``initial_depth`` levels deep, one
    dimension after the other (2^initial_depth leaves); an unbounded dimension is split at 0
    once. 0: a single root (the paper)."""
    presplit_each_dimension: bool = False
    """The root starts split once in every dimension, at its midpoint (0 for an unbounded one):
    2^d leaves, as ``initial_depth = d`` (added to ``initial_depth``). It gives the tree the
    sign of every input from the start, where a task's values are uniform until its goal is
    first reached (Acrobot) and the split test alone never leaves the root."""
    presplit_max_dimensions: int | None = None
    """Beyond the paper: ``presplit_each_dimension`` splits every dimension of an input of at
    most this many dimensions (2^n leaves at most); None: of any input (the tree refuses more
    than 2^16 leaves). An input with more dimensions (a lidar's 38, stacked frames) splits only
    its first ``presplit_beyond_dimensions``. ``initial_depth`` is not affected."""
    presplit_beyond_dimensions: int = 0
    """Beyond the paper: how many dimensions ``presplit_each_dimension`` splits, in the order of
    the observation, of an input with more than ``presplit_max_dimensions`` (0: the root stays
    whole, the paper's start)."""
    table_cells: int | None = None
    """A table for integer inputs (beyond the paper): when the observation box is integer-typed
    (:func:`agent.spaces.integer_inputs`: FrozenLake's, Taxi's or Blackjack's states through
    :func:`agent.adapt_env`, a user's grid coordinates) and holds at most this many cells (the
    product over its dimensions of the integers in each), the tree starts with one leaf per
    cell, in place of ``initial_depth`` and ``presplit_each_dimension``. Such inputs are
    already discrete: the split test would need about log2(n) splits of ``split_min_samples``
    errors each to isolate one of n states. A box with more cells, or a float one, is
    partitioned as before. None: off (the paper)."""

    leaves_per_terminal: int = 0
    """A leaf budget that grows with what the agent has reached (beyond the paper): until the
    first terminal transition (the goal on a maze; a success or a failure on a classic task)
    the tree keeps its initial leaves, and after n terminal transitions it holds at most its
    initial leaves + ``leaves_per_terminal`` x n (and ``max_leaves``). Splitting before any
    episode has ended fragments the explored region on errors of step costs alone and can fill
    the leaf cap before the goal's value arrives. 0: off (the paper: split whenever the test
    passes). Measured on the development cases and not adopted by the general preset
    (docs/paper-notes.md, "A leaf budget that grows with the terminals")."""

    model_bonus_terminals: int = 0
    """Directed exploration before the goal is found (beyond the paper): with ``model_bonus``
    > 0 and this field n > 0, the bonus applies only until the agent has seen n terminal
    transitions (the goal on a maze); then every Q-bar the model holds is recomputed without
    it and the sweeps go on as usual. Before any terminal transition the rewards carry no
    information about where the goal is, so the bonus can only steer the greedy policy
    towards the least-tried (leaf, action) pairs; afterwards the learner is the one without
    a bonus. 0: the bonus (if any) applies for ever."""
    model_lambda: float = 0.0
    """Lambda-returns in the model (beyond the paper; needs ``planning="sweep"``, one tree): at
    the end of each episode every epoch it stored (eq. 9's inputs) has its bootstrap
    ``D V-bar(s')`` replaced by ``D [(1 - lambda) V-bar(s') + lambda G]``, G the episode's own
    lambda-return after the epoch (over its later epochs, eq. 6's discounting, under the
    values at the episode's end; 0 after a terminal state, V-bar at a truncation). Inside a
    leaf the states are aliased, so the model's one-step backups converge to the fixed point
    of an aggregated chain; returns actually observed are not aliased (Sutton and Barto 2018,
    section 12, and the tile coder's Sarsa(lambda), ``agent.tile_coding``). 0: off (one-step
    backups only)."""
    model_lambda_watkins: bool = False
    """With ``model_lambda``: the return before an epoch whose action was exploratory is cut
    there, as Watkins's Q(lambda) cuts its traces (the return then is V-bar where the
    exploratory action began). False: the episode's return as it happened, exploratory
    actions included (the on-policy reading, as Sarsa(lambda) and Peng's Q(lambda))."""
    model_lambda_tried_only: bool = False
    """With ``model_lambda``: the return is cut at the end of an epoch whose end leaf has an
    action the model holds no epoch of (G after it is that leaf's V-bar), so the optimism of
    an untried action (``q_init`` above every value learnt) reaches the leaves before it
    through the one-step backups as without the option."""
    model_lambda_episodes: int | None = None
    """With ``model_lambda``: each blended epoch gets its one-step form ``R, D`` back after
    this many later episodes, while it is still stored (beyond the paper; None: a blend stays
    as long as its epoch). A lambda-return is a sample of the policy that made it: early in
    learning that policy is poor and its returns low, and a blend kept for the epoch's whole
    time in the window (``model_window`` epochs of its leaf and action) holds the leaf's value
    down after the policy has improved. Recent blends carry a new return back fast; the
    one-step backups then take over."""
    model_lambda_lower_bound: bool = False
    """With ``model_lambda``: the return after an epoch is never taken below the value where
    the epoch ended, ``G_after = max(G_after, V-bar(s'))`` at each step of the backward pass
    (beyond the paper). A return longer than the value the model already holds for its end
    state is then a sample of a worse policy (an exploratory detour, a failed run), not
    evidence against the value; a return shorter than it still pulls the leaf's value up at
    once. False: the return as it happened."""
    model_split_epochs: int | None = None
    """Model-driven splits (beyond the paper; :mod:`agent.model_split`): once the model of
    ``planning = "sweep"`` stores at least this many epochs of one (leaf, action), the leaf is
    split where those epochs' first inputs best separate their eq. (8) targets under the
    current values, if the two sides differ by ``model_split_gap`` and ``model_split_t``
    standard errors. A leaf that the greedy path avoids is seldom tested by section IV.B's
    test, which needs N_th new pairs, so a leaf where one action sometimes hits a wall and
    sometimes passes (a door, a pillar's edge) keeps one averaged value and is avoided for
    good; its stored epochs say so after a few visits. Tested after each epoch of (leaf,
    action) in which the paper's test did not split. None: off. Needs the model; at least 4
    (two epochs a side) and at most ``model_window``."""
    model_split_gap: float = 0.1
    """With ``model_split_epochs``: least difference between the mean targets of the two sides
    of a model split, in threshold units (``threshold_units``; with the measured unit 0.1 is a
    tenth of a maze's collision or ten steps' reward, and 10 on classic control's -1 or +1 a
    step). Chosen on development cases (docs/paper-notes.md, "Model-driven splits")."""
    model_split_t: float = 3.0
    """With ``model_split_epochs``: least difference between the mean targets of the two sides
    of a model split, in pooled standard errors of that difference."""
    model_split_from_terminal: bool = False
    """With ``model_split_epochs``: model splits start only once the model has recorded a
    terminal epoch (the goal on a maze, MountainCar and Acrobot; the first fall on CartPole).
    Before it every target differs only by discounting, and on a MountainCar dev seed the
    splits of that time left the car short of the flag for 1,000 episodes (beyond the paper;
    docs/paper-notes.md, "Model-driven splits", the probe for the next step). False: from
    the first epoch."""
    model_split_drops_pairs: bool = False
    """With ``model_split_epochs``: a model split drops the leaf's state-error pairs (section
    IV.B's buffer) instead of handing them to the children as ``children_inherit_samples``
    does for the paper's splits. The prototype did this; measured in docs/paper-notes.md,
    "Model-driven splits"."""
    policy_splits: bool = False
    """Policy splits (beyond the paper; :func:`agent.model_split.choose_policy_split`): when
    the model split of (leaf, a) finds no cut, the leaf is also cut where the greedy choice
    between a and another action b flips. The stored epochs of both (each at least
    ``model_split_epochs``) are valued by eq. (8) under the current values; a cut along one
    input is taken if the advantage of a over b has opposite signs on its two sides and
    changes by at least ``model_split_gap`` units and ``model_split_t`` pooled standard
    errors (Munos and Moore's policy-disagreement splits, 2002). One leaf's average otherwise
    ranks the actions for the whole leaf, where the better action changes inside it (the
    moment to reverse on MountainCar). Needs ``model_split_epochs``. False: off; measured and
    not adopted in the general preset (docs/paper-notes.md, "Policy splits": no gain shown
    over 40 MountainCar dev seeds)."""
    collision_splits: bool = False
    """Collision splits (beyond the paper; :mod:`agent.collision_split`): the model of
    ``planning = "sweep"`` marks each stored epoch that ended on a collision (the env's
    ``info[collision_key]``), and after such an epoch, when no other test split its leaf, the
    leaf is cut where the stored epochs of that action that collided and those that did not
    best separate. A leaf beside a pillar or a door post otherwise keeps one averaged value
    for an action that collides from one part of it and passes from the other. Needs the
    model. Runs on :class:`agent.tree_ensemble.TreeEnsembleAgent`'s loop. An env that reports
    no collisions never triggers it. False: off."""
    collision_splits_collided_only: bool = False
    """With ``collision_splits`` (beyond the paper;
    :func:`agent.collision_split.choose_collided_only_split`): where every stored epoch of
    (leaf, a) collided, so that no cut separates collided from free epochs, the leaf is cut so
    that its larger part holds none of those epochs' first inputs. False: such a leaf is not
    cut (part 14)."""
    optimistic_untried: bool = False
    """Optimism for untried actions (beyond the paper): an action never tried in a leaf or in
    any leaf it was split from is valued at the largest return the rewards have paid inside
    one epoch so far (eq. (9) without its bootstrap, over every input), when that is above
    its Q-bar. It is R-max's optimism (Brafman and Tennenholtz 2002) with the bound measured
    instead of known: ``q_init`` = 0 is optimistic only where rewards are at most 0, and on
    FrozenLake, whose only reward is +1 at the goal, an untried action looked like the worst
    there is. Until a positive return is paid nothing changes. False: off (the paper)."""
    greedy_min_epochs: int = 0
    """A greedy choice among supported actions (beyond the paper): the greedy action of
    ``predict`` is the best, by eq. (11)'s Q-bar, of the actions with at least this many
    epochs stored in the model of ``planning = "sweep"`` for the leaf that holds the state
    (every action competes when none has). Training is unchanged; only the policy the agent
    reports is. After a split a child keeps its parent's Q-bar for an action until an epoch of
    that action starts inside the child, so an action never tried there can lead on a value
    learnt in the other half of the parent. On MountainCar, half of one dev run's lost steps
    came from such choices (docs/paper-notes.md, "A greedy choice among supported actions").
    It is the support constraint of batch-constrained Q-learning (Fujimoto, Meger and Precup
    2019) read on the tree's stored epochs. 0: off (the paper). At most ``model_window``."""
    greedy_cell_epochs: int | None = None
    """With ``greedy_min_epochs`` (beyond the paper): the count asked instead in a leaf that
    holds a single input, one integer per dimension of an integer-typed box (a table's cell,
    ``table_cells``). There every stored epoch starts from the same state, so one epoch is a
    sample of that state and action; in a leaf over a region it is a sample of one point of
    it, and an action whose value rests on one lucky point can lead the leaf. On a
    deterministic table (Taxi) two epochs asked in every cell left a good action out where it
    had one, and the taxi looped (docs/paper-notes.md, "A greedy choice among supported
    actions"). None: ``greedy_min_epochs`` in every leaf. At most ``model_window``."""
    greedy_smoothing: float = 0.0
    """A greedy choice over a smoothed Q-bar (beyond the paper): ``predict``
    ranks the actions by the mean Q-bar row over the leaves of up to 2d + 1 points, the state
    and the state moved by +-h times its leaf's width along each dimension the leaf bounds (h is
    this value). A leaf gives one value to every state in it, so near a face where the best
    action changes the state's own row is the row of the wrong side as often as not; the
    neighbours' rows say which way it changes. The allowed actions stay those of
    ``greedy_min_epochs``, a leaf that holds a single input (a table's cell) is not smoothed,
    and training is unchanged. ``leaf_info`` reports the leaf's own greedy action. 0: off. At
    most 1 (a neighbour one leaf width away)."""
    greedy_smoothing_links: bool = False
    """With ``greedy_smoothing`` (beyond the paper): a moved point's row counts only where it
    lies in another leaf that the model links to the state's (an epoch stored from one of the
    two leaves ended in the other: the agent has moved between them, so no wall lies between
    them in a maze). A moved point in the state's own leaf, or in a leaf the agent never moved
    to or from, is left out. In an ensemble, every tree whose leaf the point changes must link
    the two. Needs ``planning = "sweep"``. False: every moved point counts (part 24's probe)."""
    greedy_tie_errors: float | None = None
    """With ``greedy_smoothing`` or ``greedy_tie_ancestors`` (beyond the paper): the smoothed
    row (or the ancestors) only breaks ties. The leaf's
    own Q-bar picks the greedy action unless another allowed action's Q-bar lies within this
    many standard errors of it, sqrt(se_best^2 + se_a^2), where an action's standard error is
    the sample deviation of its stored epochs' eq. (8) targets over the root of their count
    (infinite below two epochs; in an ensemble, the mean over the trees). Only then do the tied
    actions compete on the smoothed row. Where a leaf's evidence separates its actions (a
    maze's corridor) its choice stands; where it cannot, the neighbours decide. Needs
    ``planning = "sweep"``. None: every allowed action competes on the smoothed row."""
    greedy_tie_ancestors: float | None = None
    """With ``greedy_tie_errors`` (beyond the paper), instead of ``greedy_smoothing``: the tree's
    ancestors break the leaf's ties, nearest first. An ancestor compares two tied actions a, b leaf
    by leaf over the leaves below it where both have a stored epoch: the mean of Q-bar(l, a) -
    Q-bar(l, b) over those leaves, each counted once (a paired comparison, so a difference between
    the places where each action was tried does not count), with the standard error of that mean.
    The ancestor's best tied action is the one with the largest summed mean difference to the
    others; the actions whose mean difference from it is not above this many standard errors stay
    tied, and the next ancestor is asked. The first ancestor that leaves one action decides; if even
    the root leaves several, the root's best among them is chosen. In an ensemble, the trees'
    ancestors at the same height are asked together (means averaged over the trees, standard errors
    combined). Needs a tree, reads only Q-bar and the stored-epoch counts (which a policy-only file
    keeps). None: off."""
    greedy_tie_trial: float | None = None
    """With ``greedy_tie_ancestors`` (beyond the paper; :mod:`agent.tie_trial`): a wider tie
    width z' that the run tries. From episode ``greedy_tie_trial_episodes`` on, one episode in
    ``greedy_tie_trial_every`` breaks its greedy choices' ties at z' (the others train as
    without it), and
    ``predict`` uses z' for the leaf's test and the ancestors' only while those episodes' mean
    return exceeds the others' by more than ``greedy_tie_trial_margin`` standard errors. Runs
    the tree ensemble's loop. None: off."""
    greedy_tie_trial_episodes: int = 300
    """``greedy_tie_trial``: the episode (0-based, over the agent's life) from which trial
    episodes run."""
    greedy_tie_trial_margin: float = 2.0
    """``greedy_tie_trial``: how many standard errors of the difference the trial episodes'
    mean return must exceed the plain ones' by."""
    greedy_tie_trial_every: int = 4
    """``greedy_tie_trial``: from the start, one episode in this many is a trial episode (the
    last of each group; 2: every second), so training runs as without the option in the
    others. Part 30 measured 2 and chose 4 (docs/paper-notes.md, "Tie width chosen by the
    run")."""
    greedy_tie_trial_follow: bool = False
    """``greedy_tie_trial`` (beyond the paper): while ``predict`` uses z', training follows it.
    The roles of the episodes swap: from the start, every episode but the last of each group of
    ``greedy_tie_trial_every`` breaks its greedy choices' ties at z', and the last trains as
    without the option, so the comparison goes on with the kinds' shares reversed. Returns are
    kept by kind, not by position in the group. False: one episode in ``every`` tries z'
    whatever the comparison says (part 30)."""
    greedy_tie_trial_avoid_collided: bool = False
    """``greedy_tie_trial`` (beyond the paper): in a trial episode, a choice the trial made
    (one the strategy did not make) whose epoch ended in a collision (``info[collision_key]``)
    without leaving the leaf is not made again from that leaf in that episode; the strategy's
    choice stands there. The trial's standard errors and ancestors' sums are cached for the
    episode, so without this a tie that sends the robot into a wall can hold for the whole
    episode (part 32). Changes nothing where the env reports no collision. False: the trial
    remakes its choice each time (part 30)."""
    novelty_cells: int | None = None
    """Novel ends until the first terminals (beyond the paper; :mod:`agent.novelty`): the
    model of ``planning = "sweep"`` counts the inputs it has seen on a grid of this many cells
    along each bounded input dimension, and an epoch that ends in a cell no input has been in
    is stored with the value of an untried action (``q_init``) after it instead of V-bar of its
    end leaf, until ``novelty_terminals`` terminal epochs have been recorded; then every such
    epoch is pointed at its end leaf. A tree refines where the agent has been, so a leaf that
    reaches into an unvisited room looks as known as the room it was learnt in, and the
    optimism of untried actions (eq. 10's start value) never reaches the new room; the counts
    see it at a fixed resolution (R-max's "unknown" states, Brafman and Tennenholtz 2002).
    None: off. At least 2; needs the model."""
    novelty_terminals: int = 1
    """With ``novelty_cells``: how many terminal epochs end the novel ends (at least 1)."""
    novelty_max_cells: int | None = None
    """With ``novelty_cells``: the grid's cells in all, at most (beyond the paper; issue 9,
    part 38; None: no bound). Each bounded dimension then gets the largest count c, at most
    ``novelty_cells``, with c^d within the bound (d the bounded dimensions), and at least 2. A
    grid of 64 cells along each of Acrobot's six inputs has 6.9e10 cells: nearly every epoch
    ends in one never seen, and the agent chases them until ``novelty_episodes`` ends the
    novel ends, reaching the goal first at episodes 101-110 (dev seeds 60-63); with 4,096 cells
    in all (4 along each input) it reached it at episode 9. On one or two bounded inputs (the
    mazes, MountainCar) a bound of 4,096 leaves 64 cells a dimension, so it changes nothing.
    Off in every preset: the earlier goal did not lift Acrobot's greedy return after 1,000
    episodes (+0.97 steps over 20 dev seeds, higher on 11). At least 2 (docs/paper-notes.md,
    "A novelty grid bounded in total cells")."""
    novelty_episodes: int | None = None
    """With ``novelty_cells``: the novel ends also end once this many episodes have ended,
    whatever the count of terminals (beyond the paper; issue 9, part 12). A task whose
    episodes end only by the time limit (Pendulum) has no terminal epoch, and there ``q_init``
    after every novel end stays the best value there is (its rewards are all negative), so the
    agent chases unseen cells for ever. None: no limit (at least 1 otherwise)."""
    decision_steps: int | None = None
    """An epoch of an action that is not a held exploratory run ends after this many steps
    (beyond the paper; None: ``max_epoch_steps``, which then caps held runs only). A greedy
    action is otherwise kept until the leaf changes, for up to 50 steps: on a task whose state
    moves through a leaf in a few steps while the right action changes within it (Acrobot's
    swing, CartPole's balance) the agent re-decides this often, while an exploratory action
    is still held as long as ``max_epoch_steps`` allows (the maze's reading A). The action
    after an epoch cut inside the same leaf is the greedy one (the strategy is asked only
    where it would be without this option: a leaf change, a split, a collision, the end of a
    held run), so the tabu list does not force a switch at every cut. Runs on
    :class:`agent.tree_ensemble.TreeEnsembleAgent`'s loop."""
    decision_from_terminal: bool = False
    """``decision_steps`` applies only once the agent has seen a terminal transition (the goal
    on MountainCar, Acrobot and a maze; the first fall on CartPole), from the episode after
    it; before, a greedy action is kept until the leaf changes, as without the option (beyond
    the paper). Re-deciding at
    every step before any value has formed left MountainCar's car rocking in the valley
    (never at the flag in 1,000 episodes on two dev seeds)."""
    decision_on_failure: bool = False
    """``decision_steps`` applies only while the agent's terminal transitions are failures,
    measured (beyond the paper): the mean reward of the terminal steps seen so far is below
    the mean one-step target ``r + gamma max_a Q(s', a)`` of the steps that ended a
    non-terminal epoch, so ending the episode is worth less than going on. CartPole's fall
    (+1, against 1 + gamma Q with Q > 0) is one; MountainCar's and Acrobot's goal (-1, against
    -1 + gamma Q with Q < 0) and a maze's goal (+5) are not, and there the option changes
    nothing. Read at the start of each episode, from the episode after the first terminal
    (so it implies ``decision_from_terminal``). Needs ``decision_steps``."""
    failure_gamma: float | None = None
    """A longer discount for tasks whose terminals are failures (beyond the paper; None: off).
    From the episode after ``decision_on_failure``'s measure first finds the terminal steps'
    mean reward below the mean one-step target, eqs. (6), (7), (9) discount by this instead of
    ``gamma``, for the rest of the run (a latch, so the values are not rescaled back and
    forth). Where the terminal is a goal (a maze, MountainCar, Acrobot) the measure stays shut
    and the run is the one without this option, bit for bit. Where ending the episode is the
    loss (CartPole's fall; with ``failure_measure`` "mean" also FrozenLake's holes and
    Blackjack's lost hands, which outweigh their goals) a longer horizon weighs a loss that
    comes long after its cause:
    gamma 0.9995 from the start solved 17 of 20 CartPole dev seeds against 13 of 20, but
    moved the dense dev mazes from 1.12x to 1.89x the optimum (docs/paper-notes.md, "A
    discount gated on failure"). The model's stored epochs keep the discount they were
    stored with until they leave its window; the reward unit (``scale_horizon`` None) and an
    optimistic start stay at ``gamma``. Runs on
    :class:`agent.tree_ensemble.TreeEnsembleAgent`'s loop."""
    failure_measure: str = "mean"
    """When ``failure_gamma`` counts the terminals as failures (beyond the paper): ``"mean"``,
    ``decision_on_failure``'s measure (their mean reward below the mean one-step target);
    ``"every"``, every terminal so far (the largest terminal reward below the mean one-step
    target), so a task whose episodes also end at a goal that pays more than going on
    (FrozenLake's +1, Blackjack's won hand) never opens the latch. Where every terminal pays
    alike (CartPole's fall) the two agree to the bit (docs/paper-notes.md, "A discount gated
    on failure"). Needs ``failure_gamma``."""
    hold_steps: int | None = None
    """A held exploratory run ends after this many steps (beyond the paper; None:
    ``max_epoch_steps``, which then caps unheld epochs only). Runs on
    :class:`agent.tree_ensemble.TreeEnsembleAgent`'s loop."""
    hold_crossings: float | None = None
    """A held exploratory run ends after this many times the mean length, in steps, of the
    agent's leaf crossings so far (its unheld epochs that ended on a change of leaf, over every
    episode), rounded up, at least one step (beyond the paper; None: off). The cap follows the
    task's own step scale: a leaf of Acrobot is crossed in a few steps, a maze cell in tens.
    Before the first crossing ``max_epoch_steps`` applies. Exclusive with ``hold_steps``. Runs
    on :class:`agent.tree_ensemble.TreeEnsembleAgent`'s loop."""
    hold_terminals: int | None = None
    """Held exploration (``hold_exploration``) stops once the agent has seen this many terminal
    transitions, from the episode after the n-th (beyond the paper; None: held for ever, the
    maze's reading A). A held random action is how the agent first crosses a maze or reaches
    MountainCar's flag, where values say nothing yet; once a terminal has been reached and the
    model carries its value back, every held run is a long detour from a greedy path that is
    already good: on the dev layout ``paper_narrow`` the greedy policy was within 1.1x of the
    optimum from episode 50 while the training episodes stayed at 1.4x through episode 600
    (docs/paper-notes.md, "Held exploration until n terminals"). An exploratory action
    after that lasts one epoch, as a greedy one does. Runs on
    :class:`agent.tree_ensemble.TreeEnsembleAgent`'s loop."""
    hold_after_truncation: bool = False
    """With ``hold_terminals``: an episode that follows one cut by the time limit (truncated,
    not terminal) holds its exploratory actions again, whatever the count of terminals
    (beyond the paper). A greedy policy that loops between two leaves repeats its loop in every
    episode, and a one-epoch random action rarely breaks it; a held run does. Needs
    ``hold_terminals``. Runs on :class:`agent.tree_ensemble.TreeEnsembleAgent`'s loop."""
    ensemble_trees: int = 1
    """Several trees whose Q-bar values are averaged, as tile coding averages offset tilings
    (beyond the paper; :class:`agent.tree_ensemble.TreeEnsembleAgent`): tree k's presplit
    points move from the midpoints by Sutton's asymmetric offsets ((2d + 1) k / K, mod 1, of
    half the width in dimension d), every tree learns its own SMDP epochs (and model) from the
    one trajectory, and the actions follow the mean of the trees' rows. A decision point is
    any tree's leaf change, so the composite cells are finer than any one tree's leaves.
    1: one tree (the paper). Needs ``presplit_each_dimension`` or ``initial_depth`` (else the
    trees start alike and stay alike)."""
    ensemble_unbounded_offsets: bool = False
    """With ``ensemble_trees`` > 1, also move each tree's presplit cut of an unbounded dimension
    (beyond the paper). In the squashed coordinate ``y = x / (1 + |x|)`` (the tile coder's rule
    for unbounded inputs, :func:`agent.spaces.squash`; it assumes inputs of order 1), whose
    range (-1, 1) has half-width 1, tree k's cut moves from ``y = 0`` by its offset ``s`` for
    that dimension, so it lies at ``x = s / (1 - |s|)``, in [-1, 1). Off: an unbounded
    dimension keeps its cut at 0 in every tree, and a box with no bounded dimension is refused
    (its trees would all be one tree)."""
    ensemble_decisions: str = "any"
    """With ``ensemble_trees`` > 1, where the agent decides (beyond the paper): ``"any"``, at
    any tree's leaf change (the composite cells); ``"first"``, only at tree 0's, so the agent
    decides as often as one tree does while its choice still follows the mean of the rows.
    Then every other tree learns the stretch between two decisions as one epoch per run of
    its own leaves, as a held exploratory run is learnt (:meth:`SMDPAgent._end_held_run`)."""

    def __post_init__(self) -> None:
        for field in dataclasses.fields(self):  # a numpy scalar: the Python number it holds
            value = getattr(self, field.name)
            plain = plain_scalar(value)
            if plain is not value:
                object.__setattr__(self, field.name, plain)
        try:
            self._check_values()
        except (TypeError, ValueError) as error:
            if "TreeConfig." not in str(error):  # a comparison tripped over a wrong type
                self._check_types()
            raise
        self._check_types()

    def _check_values(self) -> None:
        """Each field's range and how the fields go together (a field's own message)."""
        _check_range("alpha", self.alpha, 0.0, 1.0, low_open=True)
        _check_range("gamma", self.gamma, 0.0, 1.0)
        if self.failure_gamma is not None:
            if isinstance(self.failure_gamma, bool) or not isinstance(
                self.failure_gamma, int | float
            ):
                raise TypeError(
                    f"TreeConfig.failure_gamma must be a number or None, got {self.failure_gamma!r}"
                )
            _check_range("failure_gamma", self.failure_gamma, 0.0, 1.0)
        if not math.isfinite(self.q_init):
            raise ValueError(f"TreeConfig.q_init must be finite, got {self.q_init!r}")
        for name in ("max_epoch_steps", "hold_steps", "decision_steps", "hold_terminals"):
            steps = getattr(self, name)
            if steps is not None and (
                isinstance(steps, bool) or not isinstance(steps, int) or steps < 1
            ):
                raise ValueError(f"TreeConfig.{name} must be a positive int or None, got {steps!r}")
        crossings = self.hold_crossings
        if crossings is not None:
            if (
                isinstance(crossings, bool)
                or not isinstance(crossings, int | float)
                or not math.isfinite(crossings)
                or crossings <= 0
            ):
                raise ValueError(
                    "TreeConfig.hold_crossings must be a positive number or None, "
                    f"got {crossings!r}"
                )
            if self.hold_steps is not None:
                raise ValueError(
                    f"TreeConfig.hold_crossings = {crossings!r} and hold_steps = "
                    f"{self.hold_steps!r}: set one of them (both cap a held run)"
                )
        lam = self.model_lambda
        if isinstance(lam, bool) or not isinstance(lam, int | float) or not 0.0 <= lam <= 1.0:
            raise ValueError(f"TreeConfig.model_lambda must be a number in [0, 1], got {lam!r}")
        if lam > 0.0 and self.planning != "sweep":
            raise ValueError(
                f"TreeConfig.model_lambda = {lam!r} needs planning = 'sweep' (it changes the "
                f"model's stored epochs), got planning = {self.planning!r}"
            )
        if lam > 0.0 and self.ensemble_trees > 1:
            raise ValueError(
                f"TreeConfig.model_lambda = {lam!r} works with one tree only, got "
                f"ensemble_trees = {self.ensemble_trees!r}"
            )
        kept = self.model_lambda_episodes
        if kept is not None and (isinstance(kept, bool) or not isinstance(kept, int) or kept < 1):
            raise ValueError(
                f"TreeConfig.model_lambda_episodes must be a positive int or None, got {kept!r}"
            )
        if kept is not None and lam == 0.0:
            raise ValueError(
                f"TreeConfig.model_lambda_episodes = {kept!r} needs model_lambda > 0 "
                "(it undoes the blends model_lambda makes)"
            )
        for name in (
            "model_lambda_watkins",
            "model_lambda_tried_only",
            "model_lambda_lower_bound",
        ):
            if getattr(self, name) is True and lam == 0.0:
                raise ValueError(
                    f"TreeConfig.{name} = True needs model_lambda > 0 "
                    "(it cuts the returns model_lambda blends in)"
                )
        for name in (
            "decision_from_terminal",
            "decision_on_failure",
            "hold_after_truncation",
            "model_lambda_watkins",
            "model_lambda_tried_only",
            "model_lambda_lower_bound",
        ):
            if not isinstance(getattr(self, name), bool):
                raise TypeError(f"TreeConfig.{name} must be a bool, got {getattr(self, name)!r}")
        if self.hold_after_truncation and self.hold_terminals is None:
            raise ValueError(
                "TreeConfig.hold_after_truncation = True needs hold_terminals (it brings back "
                "the holds hold_terminals ends)"
            )
        self._check_model_split()
        if not isinstance(self.collision_splits, bool):
            raise ValueError(
                f"TreeConfig.collision_splits must be a bool, got {self.collision_splits!r}"
            )
        if self.collision_splits and self.planning != "sweep":
            raise ValueError(
                "TreeConfig.collision_splits = True needs planning = 'sweep' (it cuts between "
                f"the model's stored epochs), got planning = {self.planning!r}"
            )
        only = self.collision_splits_collided_only
        if not isinstance(only, bool):
            raise ValueError(
                f"TreeConfig.collision_splits_collided_only must be a bool, got {only!r}"
            )
        if only and not self.collision_splits:
            raise ValueError(
                "TreeConfig.collision_splits_collided_only = True needs collision_splits = True "
                "(it cuts where the collision split finds no cut)"
            )
        if not isinstance(self.optimistic_untried, bool):
            raise ValueError(
                f"TreeConfig.optimistic_untried must be a bool, got {self.optimistic_untried!r}"
            )
        self._check_novelty()
        self._check_greedy_min_epochs()
        self._check_greedy_smoothing()
        _check_choice("failure_measure", self.failure_measure, ("mean", "every"))
        if self.failure_measure != "mean" and self.failure_gamma is None:
            raise ValueError(
                f"TreeConfig.failure_measure = {self.failure_measure!r} needs failure_gamma "
                "(it says when failure_gamma latches)"
            )
        if self.decision_on_failure and self.decision_steps is None:
            raise ValueError(
                "TreeConfig.decision_on_failure = True needs decision_steps (it gates them)"
            )
        if not isinstance(self.split_min_samples, int) or self.split_min_samples < 2:
            raise ValueError(
                f"TreeConfig.split_min_samples must be an int >= 2, got {self.split_min_samples!r}"
            )
        for name in ("split_max_abs_mean", "split_min_variance"):
            value = getattr(self, name)
            if not value >= 0.0:  # also rejects NaN
                raise ValueError(f"TreeConfig.{name} must be >= 0, got {value!r}")
        _check_choice("error_buffer", self.error_buffer, ("clear", "window"))
        _check_choice("range_normalization", self.range_normalization, ("root", "none"))
        _check_choice("split_point", self.split_point, ("quest", "midpoint"))
        _check_range("min_leaf_fraction", self.min_leaf_fraction, 0.0, 0.5, low_open=True)
        if not isinstance(self.max_leaves, int) or self.max_leaves < 1:
            raise ValueError(f"TreeConfig.max_leaves must be an int >= 1, got {self.max_leaves!r}")
        _check_choice("threshold_units", self.threshold_units, ("reward", "scale"))
        _check_choice("planning", self.planning, ("none", "sweep"))
        _check_choice("scale_rule", self.scale_rule, ("reward_median", "return_std", "return_iqr"))
        horizon, (least, most) = self.scale_horizon, HORIZON_RANGE
        if horizon is not None and (
            isinstance(horizon, bool)
            or not isinstance(horizon, int | float)
            or not least <= horizon <= most
        ):
            raise ValueError(
                f"TreeConfig.scale_horizon must be None or a number in [{least:g}, {most:,.0f}], "
                f"got {horizon!r}"
            )
        for name, least in (
            ("model_window", 1),
            ("sweep_backups", 0),
            ("initial_depth", 0),
            ("leaves_per_terminal", 0),
            ("model_bonus_terminals", 0),
            ("ensemble_trees", 1),
        ):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or value < least:
                raise ValueError(f"TreeConfig.{name} must be an int >= {least}, got {value!r}")
        if not isinstance(self.presplit_each_dimension, bool):
            raise TypeError(
                f"TreeConfig.presplit_each_dimension must be a bool, "
                f"got {self.presplit_each_dimension!r}"
            )
        presplit = self.presplit_max_dimensions
        if presplit is not None and (
            isinstance(presplit, bool) or not isinstance(presplit, int) or not 0 <= presplit <= 16
        ):
            raise ValueError(
                "TreeConfig.presplit_max_dimensions must be None or an int in [0, 16] "
                f"(2^16 leaves), got {presplit!r}"
            )
        beyond = self.presplit_beyond_dimensions
        if isinstance(beyond, bool) or not isinstance(beyond, int) or not 0 <= beyond <= 16:
            raise ValueError(
                f"TreeConfig.presplit_beyond_dimensions must be an int in [0, 16], got {beyond!r}"
            )
        cells = self.table_cells
        if cells is not None and (
            isinstance(cells, bool) or not isinstance(cells, int) or not 1 <= cells <= MAX_TABLE
        ):
            raise ValueError(
                f"TreeConfig.table_cells must be None or an int in [1, {MAX_TABLE:,}], "
                f"got {cells!r}"
            )
        if self.ensemble_trees > 64:
            raise ValueError(
                f"TreeConfig.ensemble_trees must be at most 64, got {self.ensemble_trees!r}"
            )
        if self.ensemble_trees > 1 and self.initial_depth == 0 and not self.presplit_each_dimension:
            raise ValueError(
                f"TreeConfig.ensemble_trees = {self.ensemble_trees} needs a presplit "
                "(presplit_each_dimension = True or initial_depth > 0): the offsets move the "
                "presplit points, and unsplit trees would stay identical"
            )
        if self.ensemble_unbounded_offsets is True and self.ensemble_trees < 2:
            raise ValueError(
                "TreeConfig.ensemble_unbounded_offsets = True needs ensemble_trees >= 2, got "
                f"{self.ensemble_trees!r}"
            )
        _check_choice("ensemble_decisions", self.ensemble_decisions, ("any", "first"))
        if self.ensemble_decisions != "any" and self.ensemble_trees < 2:
            raise ValueError(
                f"TreeConfig.ensemble_decisions = {self.ensemble_decisions!r} needs "
                f"ensemble_trees >= 2, got {self.ensemble_trees!r}"
            )
        if self.ensemble_trees > 1 and self.leaves_per_terminal > 0:
            raise ValueError(
                "TreeConfig.ensemble_trees > 1 and leaves_per_terminal > 0 cannot be combined "
                f"(got {self.ensemble_trees} and {self.leaves_per_terminal})"
            )
        if self.initial_depth > 16:
            raise ValueError(
                f"TreeConfig.initial_depth must be at most 16 (65,536 leaves), "
                f"got {self.initial_depth!r}"
            )
        for name in ("sweep_tolerance", "model_bonus", "split_min_t"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | float) or not value >= 0.0:
                raise ValueError(f"TreeConfig.{name} must be a number >= 0, got {value!r}")
            if not math.isfinite(value):
                raise ValueError(f"TreeConfig.{name} must be finite, got {value!r}")

    def _check_types(self) -> None:
        """Every field against its annotation (:func:`agent.value_checks.check_value`): a
        wrong type or a float that is not finite is a ``SettingError`` (a ``TypeError`` and a
        ``ValueError``) naming the field, where no check of its own refused it (``alpha=True``,
        ``hold_exploration="no"``, ``collision_key=None`` used to pass)."""
        hints = type_hints(type(self))  # a subclass's own fields too
        for field in dataclasses.fields(self):
            check_value(
                getattr(self, field.name),
                hints[field.name],
                f"TreeConfig.{field.name}",
                python=True,
            )

    def _check_novelty(self) -> None:
        cells = self.novelty_cells
        limit = self.novelty_terminals
        if isinstance(limit, bool) or not isinstance(limit, int) or limit < 1:
            raise ValueError(f"TreeConfig.novelty_terminals must be an int >= 1, got {limit!r}")
        episodes = self.novelty_episodes
        if episodes is not None and (
            isinstance(episodes, bool) or not isinstance(episodes, int) or episodes < 1
        ):
            raise ValueError(
                f"TreeConfig.novelty_episodes must be an int >= 1 or None, got {episodes!r}"
            )
        bound = self.novelty_max_cells
        if bound is not None and (
            isinstance(bound, bool) or not isinstance(bound, int) or not 2 <= bound <= 1 << 40
        ):
            raise ValueError(
                f"TreeConfig.novelty_max_cells must be an int in [2, 2^40] or None, got {bound!r}"
            )
        if cells is None:
            return
        if isinstance(cells, bool) or not isinstance(cells, int) or not 2 <= cells <= 1 << 20:
            raise ValueError(
                f"TreeConfig.novelty_cells must be an int in [2, 2^20] or None, got {cells!r}"
            )
        if self.planning != "sweep":
            raise ValueError(
                f"TreeConfig.novelty_cells = {cells!r} needs planning = 'sweep' (the model "
                f"stores the novel ends), got planning = {self.planning!r}"
            )

    @property
    def greedy_reads_support(self) -> bool:
        """Whether ``predict`` reads the model's stored-epoch counts (``greedy_min_epochs``,
        ``greedy_tie_ancestors``), which a policy-only file then keeps."""
        return self.greedy_min_epochs > 0 or self.greedy_tie_ancestors is not None

    def _check_tie_trial(self) -> None:
        trial = self.greedy_tie_trial
        start = self.greedy_tie_trial_episodes
        if isinstance(start, bool) or not isinstance(start, int) or start < 0:
            raise ValueError(
                f"TreeConfig.greedy_tie_trial_episodes must be an int >= 0, got {start!r}"
            )
        every = self.greedy_tie_trial_every
        if isinstance(every, bool) or not isinstance(every, int) or not 2 <= every <= 1000:
            raise ValueError(
                f"TreeConfig.greedy_tie_trial_every must be an int in [2, 1000], got {every!r}"
            )
        margin = self.greedy_tie_trial_margin
        if (
            isinstance(margin, bool)
            or not isinstance(margin, int | float)
            or not math.isfinite(margin)
            or margin < 0
        ):
            raise ValueError(
                f"TreeConfig.greedy_tie_trial_margin must be a finite number >= 0, got {margin!r}"
            )
        follow = self.greedy_tie_trial_follow
        if not isinstance(follow, bool):
            raise ValueError(f"TreeConfig.greedy_tie_trial_follow must be a bool, got {follow!r}")
        avoid = self.greedy_tie_trial_avoid_collided
        if not isinstance(avoid, bool):
            raise ValueError(
                f"TreeConfig.greedy_tie_trial_avoid_collided must be a bool, got {avoid!r}"
            )
        if trial is None:
            return
        if (
            isinstance(trial, bool)
            or not isinstance(trial, int | float)
            or not math.isfinite(trial)
            or trial <= 0
        ):
            raise ValueError(
                f"TreeConfig.greedy_tie_trial must be a number > 0 or None, got {trial!r}"
            )
        if self.greedy_tie_ancestors is None:
            raise ValueError(
                f"TreeConfig.greedy_tie_trial = {trial!r} needs greedy_tie_ancestors (the ties "
                "it widens are those the ancestors break), got greedy_tie_ancestors = None"
            )

    def _check_greedy_smoothing(self) -> None:
        h = self.greedy_smoothing
        if (
            isinstance(h, bool)
            or not isinstance(h, int | float)
            or not math.isfinite(h)
            or not 0.0 <= h <= 1.0
        ):
            raise ValueError(f"TreeConfig.greedy_smoothing must be a number in [0, 1], got {h!r}")
        if not isinstance(self.greedy_smoothing_links, bool):
            raise ValueError(
                "TreeConfig.greedy_smoothing_links must be a bool, got "
                f"{self.greedy_smoothing_links!r}"
            )
        z = self.greedy_tie_errors
        if z is not None and (
            isinstance(z, bool) or not isinstance(z, int | float) or not math.isfinite(z) or z <= 0
        ):
            raise ValueError(
                f"TreeConfig.greedy_tie_errors must be a number > 0 or None, got {z!r}"
            )
        za = self.greedy_tie_ancestors
        if za is not None and (
            isinstance(za, bool)
            or not isinstance(za, int | float)
            or not math.isfinite(za)
            or za <= 0
        ):
            raise ValueError(
                f"TreeConfig.greedy_tie_ancestors must be a number > 0 or None, got {za!r}"
            )
        if za is not None:
            if z is None:
                raise ValueError(
                    f"TreeConfig.greedy_tie_ancestors = {za!r} needs greedy_tie_errors (the "
                    "leaf's test for tied actions), got greedy_tie_errors = None"
                )
            if h != 0.0:
                raise ValueError(
                    f"TreeConfig.greedy_tie_ancestors = {za!r} and greedy_smoothing = {h!r} "
                    "are two ways to break the same ties: set greedy_smoothing = 0"
                )
        self._check_tie_trial()
        for name, on in (
            ("greedy_smoothing_links", self.greedy_smoothing_links),
            ("greedy_tie_errors", z is not None),
        ):
            if not on:
                continue
            value = getattr(self, name)
            if h == 0.0 and not (name == "greedy_tie_errors" and za is not None):
                how = (
                    "greedy_smoothing > 0 or greedy_tie_ancestors (a way to break the ties it "
                    "finds)"
                    if name == "greedy_tie_errors"
                    else "greedy_smoothing > 0 (it shapes the smoothed greedy choice)"
                )
                raise ValueError(
                    f"TreeConfig.{name} = {value!r} needs {how}, got greedy_smoothing = 0"
                )
            if self.planning != "sweep":
                raise ValueError(
                    f"TreeConfig.{name} = {value!r} needs planning = 'sweep' (it reads the "
                    f"model's stored epochs), got planning = {self.planning!r}"
                )

    def _check_greedy_min_epochs(self) -> None:
        k = self.greedy_min_epochs
        if isinstance(k, bool) or not isinstance(k, int) or k < 0:
            raise ValueError(f"TreeConfig.greedy_min_epochs must be an int >= 0, got {k!r}")
        if k > 0:
            self._check_stored_epochs("greedy_min_epochs", k, "it counts the model's stored epochs")
        cell = self.greedy_cell_epochs
        if cell is None:
            return
        if isinstance(cell, bool) or not isinstance(cell, int) or cell < 0:
            raise ValueError(
                f"TreeConfig.greedy_cell_epochs must be an int >= 0 or None, got {cell!r}"
            )
        if k == 0:
            raise ValueError(
                f"TreeConfig.greedy_cell_epochs = {cell!r} needs greedy_min_epochs > 0 (it "
                "replaces that count in single-input leaves), got greedy_min_epochs = 0"
            )
        self._check_stored_epochs("greedy_cell_epochs", cell, "it counts the model's stored epochs")

    def _check_stored_epochs(self, name: str, count: int, why: str) -> None:
        """A count of the model's stored epochs of one (leaf, action): it needs the model and
        at most ``model_window`` epochs."""
        if self.planning != "sweep":
            raise ValueError(
                f"TreeConfig.{name} = {count!r} needs planning = 'sweep' ({why}), "
                f"got planning = {self.planning!r}"
            )
        if isinstance(self.model_window, int) and count > self.model_window:
            raise ValueError(
                f"TreeConfig.{name} = {count!r} is more than model_window = "
                f"{self.model_window!r}, the most epochs the model stores for one (leaf, action)"
            )

    def _check_model_split(self) -> None:
        epochs = self.model_split_epochs
        for name in ("model_split_gap", "model_split_t"):
            value = getattr(self, name)
            if (
                isinstance(value, bool)
                or not isinstance(value, int | float)
                or not math.isfinite(value)
                or value < 0.0
            ):
                raise ValueError(f"TreeConfig.{name} must be a finite number >= 0, got {value!r}")
        dependent = ("model_split_drops_pairs", "model_split_from_terminal", "policy_splits")
        for name in dependent:
            if not isinstance(getattr(self, name), bool):
                raise TypeError(f"TreeConfig.{name} must be a bool, got {getattr(self, name)!r}")
        if epochs is None:
            for name in dependent:
                if getattr(self, name):
                    raise ValueError(
                        f"TreeConfig.{name} = True needs model_split_epochs (it changes the "
                        "model splits)"
                    )
            return
        if isinstance(epochs, bool) or not isinstance(epochs, int) or epochs < 4:
            raise ValueError(
                f"TreeConfig.model_split_epochs must be an int >= 4 (two epochs on each side) "
                f"or None, got {epochs!r}"
            )
        self._check_stored_epochs(
            "model_split_epochs", epochs, "it tests the model's stored epochs"
        )

    def loop_options(self) -> dict[str, Any]:
        """The options set here that only the tree ensemble's loop runs
        (``agent.tree_ensemble.TreeEnsembleAgent``), each with its value; empty when the plain
        loop runs this configuration. The one list of them (:data:`LOOP_OPTIONS`)."""
        return {
            name: getattr(self, name)
            for name, off in LOOP_OPTIONS.items()
            if getattr(self, name) != off
        }

    def to_dict(self) -> dict[str, Any]:
        """The fields as a JSON-ready dict."""
        return dataclasses.asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> TreeConfig:
        """Rebuild from :meth:`to_dict`; unknown keys raise a ValueError naming them."""
        known = {f.name for f in dataclasses.fields(cls)}
        unknown = sorted(set(data) - known)
        if unknown:
            raise ValueError(f"unknown TreeConfig fields {unknown}; known: {sorted(known)}")
        return cls(**data)


LOOP_OPTIONS: dict[str, Any] = {
    "ensemble_trees": 1,
    "decision_steps": None,
    "hold_steps": None,
    "hold_crossings": None,
    "hold_terminals": None,
    "hold_after_truncation": False,
    "model_lambda": 0.0,
    "collision_splits": False,
    "failure_gamma": None,
    "greedy_tie_trial": None,
}
"""Each ``TreeConfig`` option that only the tree ensemble's loop runs, with its off value."""


def _check_range(
    name: str, value: float, low: float, high: float, *, low_open: bool = False
) -> None:
    ok = (low < value if low_open else low <= value) and value <= high
    if not ok:
        bracket = "(" if low_open else "["
        raise ValueError(f"TreeConfig.{name} must be in {bracket}{low}, {high}], got {value!r}")


def _check_choice(name: str, value: str, choices: tuple[str, ...]) -> None:
    if value not in choices:
        raise ValueError(f"TreeConfig.{name} must be one of {list(choices)}, got {value!r}")
