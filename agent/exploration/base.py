"""The interface every exploration strategy implements, and the greedy choice they share.

A strategy is told about the learner's events through hooks (all no-ops by default) and picks
the action at each decision point (the start of an SMDP epoch, section IV.A). Strategies compose:
:class:`~agent.exploration.tabu.Tabu` wraps any other strategy. Every random draw is a
``rng.random()`` on the source the agent passes in: a ``numpy.random.Generator``, or the agent's
:class:`~agent.random_stream.UniformStream` that draws from its seeded generator in blocks.
"""

from __future__ import annotations

from typing import Any, Protocol


class RewardUnit(Protocol):
    """Anything with a ``value`` in reward units, e.g. :class:`agent.scale.RewardScale`."""

    @property
    def value(self) -> float:
        """The unit."""
        ...


class UniformSource(Protocol):
    """Anything with ``random() -> float`` uniform in [0, 1), e.g. ``numpy.random.Generator``."""

    def random(self) -> float:
        """One uniform draw."""
        ...


def greedy_action(q_row: list[float], rng: UniformSource) -> int:
    """Index of the largest value of ``q_row``; ties are broken uniformly with ``rng``.

    A draw is made only when there is a tie, so the draws depend on the values alone.
    """
    best = max(q_row)
    if q_row.count(best) == 1:
        return q_row.index(best)
    ties = [a for a, v in enumerate(q_row) if v == best]
    return ties[int(rng.random() * len(ties))]


class Exploration:
    """Base class: an exploration strategy over leaves (states) and discrete actions.

    Subclasses set :attr:`name` and override :meth:`epsilon` (epsilon-style strategies) or
    :meth:`select`, plus the hooks they need. ``params()`` returns the constructor arguments and
    ``state_dict()`` the learned state, both JSON-ready, for ``save``/``load``.
    """

    name: str = "exploration"
    n_actions: int = 0
    explored: bool = False
    """Whether the last :meth:`select` chose at random (an exploratory action): the learner may
    hold such an action across leaf boundaries (``TreeConfig.hold_exploration``)."""
    scale: RewardUnit | None = None
    """Set by :meth:`use_scale`: parameters in reward units are multiples of ``scale.value``."""

    def bind(self, n_actions: int) -> None:
        """Called once by the agent with the number of actions before any other hook."""
        if n_actions < 1:
            raise ValueError(f"{self.name}: n_actions must be >= 1, got {n_actions!r}")
        self.n_actions = n_actions

    def use_scale(self, scale: RewardUnit) -> None:
        """Read every parameter in reward units as a multiple of ``scale.value`` from now on
        (the agent calls this when ``TreeConfig.threshold_units == "scale"``)."""
        self.scale = scale

    def unit(self) -> float:
        """The current reward unit: ``scale.value``, or 1 without a scale."""
        return 1.0 if self.scale is None else self.scale.value

    def initial_value(self, gamma: float) -> float | None:
        """Initial Q-bar the strategy asks for (optimistic initialisation), or None: the
        agent's ``TreeConfig.q_init``."""
        return None

    def epsilon(self, leaf: int) -> float:
        """The probability of a uniformly random action in ``leaf``."""
        return 0.0

    def select(self, leaf: int, q_row: list[float], rng: UniformSource) -> int:
        """Epsilon-greedy choice with :meth:`epsilon` (section III): random with probability
        epsilon, else the greedy action of ``q_row`` (one draw, plus one per random action or tie).
        """
        if rng.random() < self.epsilon(leaf):
            self.explored = True
            return int(rng.random() * len(q_row))
        self.explored = False
        return greedy_action(q_row, rng)

    def listed(self, leaf: int) -> frozenset[int]:
        """The actions the strategy keeps off in ``leaf`` (a tabu list's); none here."""
        return frozenset()

    def update(self, leaf: int, action: int, delta_q: float) -> None:
        """After eq. (10) changed Q-bar(leaf, action) by ``delta_q``."""

    def on_epoch_end(self, leaf: int, action: int) -> None:
        """An SMDP epoch that held ``action`` in ``leaf`` has ended (after :meth:`update`)."""

    def on_episode_end(self, success: bool) -> None:
        """An episode has ended; ``success`` says whether the goal was reached."""

    def on_split(self, parent: int, children: tuple[int, int]) -> None:
        """Leaf ``parent`` was split into ``children`` (new leaf ids)."""

    def params(self) -> dict[str, Any]:
        """Constructor arguments, JSON-ready (``make_exploration(name, **params)`` rebuilds it)."""
        return {}

    def state_dict(self) -> dict[str, Any]:
        """Learned state, JSON-ready."""
        return {}

    def load_state_dict(self, state: dict[str, Any]) -> None:
        """Restore :meth:`state_dict`."""

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self.params().items())
        return f"{type(self).__name__}({args})"


def leaf_table_to_json(table: dict[int, Any]) -> list[list[Any]]:
    """A per-leaf dict as a JSON-ready list of ``[leaf, value]`` pairs (JSON keys are strings)."""
    return [[leaf, value] for leaf, value in table.items()]


def leaf_table_from_json(pairs: list[list[Any]]) -> dict[int, Any]:
    """Inverse of :func:`leaf_table_to_json`; a ValueError names an entry that is not
    ``[leaf, value]`` with a leaf id that is an int >= 0, or a leaf listed twice."""
    if not isinstance(pairs, list):
        raise ValueError(f"a per-leaf table must be a list of [leaf, value] pairs, got {pairs!r}")
    table: dict[int, Any] = {}
    for entry in pairs:
        ok = isinstance(entry, list) and len(entry) == 2
        leaf = entry[0] if ok else None
        if not ok or isinstance(leaf, bool) or not isinstance(leaf, int) or leaf < 0:
            raise ValueError(f"per-leaf entry {entry!r} is not [leaf id >= 0, value]")
        if leaf in table:
            raise ValueError(f"a per-leaf table lists leaf {leaf} twice")
        table[leaf] = entry[1]
    return table


def epsilon_from_json(leaf: int, value: Any) -> float:
    """A leaf's saved exploration rate: a number in [0, 1] (not a bool), as a float."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not 0.0 <= value <= 1.0:
        raise ValueError(f"leaf {leaf}'s epsilon {value!r} is not a number in [0, 1]")
    return float(value)


def action_counts_from_json(leaf: int, row: Any, n_actions: int) -> list[int]:
    """A leaf's saved per-action counts: ``n_actions`` ints >= 0 (any length before bind())."""
    ok = isinstance(row, list) and (not n_actions or len(row) == n_actions)
    ok = ok and all(isinstance(n, int) and not isinstance(n, bool) and n >= 0 for n in row)
    if not ok:
        raise ValueError(f"the counts of leaf {leaf} are {row!r}, not {n_actions} ints >= 0")
    return list(row)
