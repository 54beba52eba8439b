"""The run tries a wider tie width and keeps it only where it earns more (beyond the paper).

``predict``'s greedy choice (eq. 11 among the allowed actions) breaks statistical ties between
a leaf's actions: actions whose Q-bar lies within z standard errors of the best are tied
(``TreeConfig.greedy_tie_errors``), and the tree's ancestors choose among them
(``TreeConfig.greedy_tie_ancestors``). Issue 9's part 27 measured the width z that suits each
task and found no single one: Acrobot gains 15 to 20 steps at z = 2, where CartPole and the
narrow-door mazes lose at it (docs/paper-notes.md, "Tie width chosen by the run").

``TreeConfig.greedy_tie_trial`` = z' lets each run measure which width its own task wants.
From episode ``greedy_tie_trial_episodes`` on, one episode in ``greedy_tie_trial_every`` (the
last of each group; with 2 they alternate, the first plain) is a trial episode:

* a *plain* episode trains as without the option;
* a *trial* episode's greedy choices (those the strategy did not explore, where the chosen
  action and at least one other allowed action have ``greedy_min_epochs`` stored epochs and are
  not on the strategy's list) break their ties as ``predict`` would at z' (the leaf's test and
  the ancestors' both at z').

Both kinds learn as usual. The returns of each kind are kept as a running mean and variance
(Welford's update), and ``predict`` uses z' for both tests only while the trial episodes' mean
return exceeds the plain episodes' by more than ``greedy_tie_trial_margin`` standard errors of
the difference, sqrt(s_p^2 / n_p + s_t^2 / n_t) (at least two episodes of each kind); otherwise
the configured widths. The rule needs no knowledge of the run's length: the comparison grows
with the run, and a run shorter than the start never tries z'.

``TreeConfig.greedy_tie_trial_follow`` lets training follow the width ``predict`` uses: while
z' is adopted, the kinds swap places in each group (every episode but the last breaks its
ties at z', the last is plain), so most of training acts as the greedy policy will. An
episode's kind is fixed at its start (adoption changes only when an episode ends) and its
return goes to its kind's moments.
"""

from __future__ import annotations

import math
from typing import Any


class RunningMoments:
    """Count, mean and sum of squared deviations of a stream of numbers (Welford, 1962)."""

    __slots__ = ("count", "m2", "mean")

    def __init__(self, count: int = 0, mean: float = 0.0, m2: float = 0.0) -> None:
        self.count = count
        self.mean = mean
        self.m2 = m2

    def add(self, value: float) -> None:
        """Fold ``value`` into the moments."""
        self.count += 1
        delta = value - self.mean
        self.mean += delta / self.count
        self.m2 += delta * (value - self.mean)

    @property
    def variance(self) -> float:
        """The sample variance (ddof 1); infinite below two values."""
        return self.m2 / (self.count - 1) if self.count > 1 else math.inf


class TieTrial:
    """``TreeConfig.greedy_tie_trial``'s bookkeeping: which episodes try the width, the returns
    of each kind of episode, and the widths ``predict`` uses now."""

    def __init__(
        self,
        base: tuple[float, float],
        trial: float,
        start: int,
        margin: float,
        every: int,
        *,
        follow: bool = False,
    ) -> None:
        self.base = base
        """The configured widths: (``greedy_tie_errors``, ``greedy_tie_ancestors``)."""
        self.trial = trial
        self.start = start
        self.margin = margin
        self.every = every
        self.follow = follow
        """``TreeConfig.greedy_tie_trial_follow``: the kinds swap while z' is adopted."""
        self.plain = RunningMoments()
        """Returns of the plain episodes from the start on."""
        self.tried = RunningMoments()
        """Returns of the trial episodes."""

    def tries(self, episode: int) -> bool:
        """Whether episode ``episode`` (0-based over the run) is a trial episode: from the start,
        the last of each group of ``every``; with ``follow`` while z' is adopted, every other
        one. Asked at the episode's start and again by :meth:`record`, before anything of the
        episode is kept, so both see the same moments."""
        if episode < self.start:
            return False
        last = (episode - self.start) % self.every == self.every - 1
        return not last if self.follow and self.adopted else last

    def record(self, episode: int, episode_return: float) -> None:
        """Keep the return of episode ``episode``; an episode before the start is not kept."""
        if episode < self.start:
            return
        (self.tried if self.tries(episode) else self.plain).add(float(episode_return))

    def difference(self) -> tuple[float, float]:
        """The trial episodes' mean return minus the plain ones', and its standard error
        (infinite below two episodes of either kind)."""
        a, b = self.plain, self.tried
        if a.count < 2 or b.count < 2:
            return 0.0, math.inf
        return b.mean - a.mean, math.sqrt(a.variance / a.count + b.variance / b.count)

    @property
    def adopted(self) -> bool:
        """Whether the trial width earns more by more than ``margin`` standard errors."""
        diff, se = self.difference()
        return diff > self.margin * se

    def widths(self) -> tuple[float, float]:
        """The widths ``predict`` uses now: (leaf test, ancestors' test)."""
        return (self.trial, self.trial) if self.adopted else self.base

    def state(self) -> dict[str, Any]:
        """The moments, JSON-ready (an agent file's ``tie_trial`` entry)."""
        return {
            kind: [m.count, m.mean, m.m2]
            for kind, m in (("plain", self.plain), ("tried", self.tried))
        }

    def restore(self, state: Any, where: str) -> None:
        """Load :meth:`state`'s output, checked (a ValueError naming ``where`` otherwise)."""
        if not isinstance(state, dict) or set(state) != {"plain", "tried"}:
            raise ValueError(f"{where}: expected keys ['plain', 'tried'], got {state!r}")
        loaded = []
        for kind in ("plain", "tried"):
            value = state[kind]
            ok = isinstance(value, list) and len(value) == 3
            if ok:
                count, mean, m2 = value
                ok = (
                    isinstance(count, int)
                    and not isinstance(count, bool)
                    and count >= 0
                    and all(
                        isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)
                        for v in (mean, m2)
                    )
                    and m2 >= 0
                )
            if not ok:
                raise ValueError(
                    f"{where} {kind}: expected [count >= 0, finite mean, finite m2 >= 0], "
                    f"got {value!r}"
                )
            loaded.append(RunningMoments(count, float(mean), float(m2)))
        self.plain, self.tried = loaded
