"""The reward scale an agent measures itself, so that thresholds need no hand scaling.

Table I's split thresholds (mu_th = 0.5, sigma_th^2 = 0.03) are in the maze's reward units
(-0.01 a step); a task paying -1 a step needs thresholds 100 times larger. With
``TreeConfig(threshold_units="scale")`` every constant in reward units is instead a multiple of
the value unit measured here from the agent's own experience:

    unit = median of |r| over the nonzero rewards seen so far x H,  H = 1 / (1 - gamma),

the value of receiving the typical reward for ever (with gamma = 1, the median itself), or with
``TreeConfig.scale_horizon`` a fixed H, so that the discount can move without moving the
split test's thresholds (the general preset: gamma 0.999, H = 100). On the
paper's maze (-0.01 a step, with rarer -1 collisions and one +5 at the goal) the median is 0.01
and the unit is 1: Table I's values in this unit are Table I's values. On MountainCar, Acrobot
and CartPole (|r| = 1 a step) the unit is 100. A median ignores the rare large rewards (the
goal, collisions), so the unit does not jump when the goal is first found. Multiplying every
reward by c > 0 multiplies the unit by c, so the same multipliers give the same tree and the
same actions (exactly so for c a power of two, where every product is exact in binary floating
point).

The median is exact while at most :data:`EXACT_VALUES` distinct magnitudes have been seen (a
count per magnitude); past that (continuous rewards) the counts move to logarithmic bins of
1/16 octave and the median is its bin's geometric centre (within 2.2 %, still homogeneous
under powers of two).
"""

from __future__ import annotations

import bisect
import math
from typing import Any

EXACT_VALUES = 64
"""Distinct reward magnitudes counted exactly before the counts move to log bins."""
BINS_PER_OCTAVE = 16
HORIZON_RANGE = (1.0, 1e6)
"""The horizons H a unit may have (``TreeConfig.scale_horizon``): one step to a million."""


class RewardScale:
    """Running median of the nonzero reward magnitudes as a value unit, ``median x H`` with
    ``H = 1 / (1 - gamma)`` or a given horizon (``TreeConfig.scale_horizon``)."""

    __slots__ = ("_binned", "_counts", "_horizon", "_unit", "gamma", "horizon", "total")

    def __init__(self, gamma: float, horizon: float | None = None) -> None:
        if not 0.0 <= gamma <= 1.0:
            raise ValueError(f"RewardScale: gamma must be in [0, 1], got {gamma!r}")
        least, most = HORIZON_RANGE
        if horizon is not None and not least <= horizon <= most:
            raise ValueError(
                f"RewardScale: horizon must be in [{least:g}, {most:,.0f}], got {horizon!r}"
            )
        self.gamma = gamma
        self.horizon = horizon
        """``TreeConfig.scale_horizon``: the unit's H, or None for ``1 / (1 - gamma)``."""
        self._horizon = _horizon(gamma, horizon)
        self.total = 0
        self._counts: dict[float, int] = {}
        """magnitude -> count (exact), or log-bin index (as a float) -> count (binned)."""
        self._binned = False
        self._unit = 0.0

    def add(self, rewards: list[float]) -> None:
        """Count the nonzero magnitudes of an epoch's rewards and refresh the unit."""
        counts = self._counts
        added = False
        for r in rewards:
            if r == 0.0 or not math.isfinite(r):
                continue
            key = _bin(abs(r)) if self._binned else abs(r)
            counts[key] = counts.get(key, 0) + 1
            added = True
            self.total += 1
        if not added:
            return
        if not self._binned and len(counts) > EXACT_VALUES:
            binned: dict[float, int] = {}
            for magnitude, n in counts.items():
                key = _bin(magnitude)
                binned[key] = binned.get(key, 0) + n
            self._counts = binned
            self._binned = True
        self._unit = self._median() * self._horizon

    def _median(self) -> float:
        """The lower median of the counted magnitudes."""
        half = (self.total + 1) // 2
        seen = 0
        for key in sorted(self._counts):
            seen += self._counts[key]
            if seen >= half:
                return 2.0 ** ((key + 0.5) / BINS_PER_OCTAVE) if self._binned else key
        raise AssertionError("unreachable: counts sum to total")

    @property
    def value(self) -> float:
        """The value unit (0 before any nonzero reward)."""
        return self._unit

    def state(self) -> dict[str, Any]:
        """JSON-ready state."""
        return {
            "gamma": self.gamma,
            "total": self.total,
            "binned": self._binned,
            "counts": [[k, n] for k, n in self._counts.items()],
        }

    def restore(self, state: dict[str, Any]) -> None:
        """Inverse of :meth:`state`; a ValueError names the first field that is wrong."""
        gamma = _number(state["gamma"], "the reward unit's gamma")
        if not 0.0 <= gamma <= 1.0:
            raise ValueError(f"the reward unit's gamma {gamma!r} is not in [0, 1]")
        binned = state["binned"]
        if not isinstance(binned, bool):
            raise ValueError(f"the reward unit's binned flag {binned!r} is not a bool")
        counts, total = _counts(state, "the reward unit", positive_keys=not binned)
        self.gamma = gamma
        self._horizon = _horizon(self.gamma, self.horizon)  # the horizon is the config's
        self.total, self._binned, self._counts = total, binned, counts
        self._unit = self._median() * self._horizon if self.total else 0.0

    def __repr__(self) -> str:
        return f"RewardScale(rewards={self.total}, value={self.value:.6g})"


def _number(value: Any, what: str) -> float:
    """``value`` as a float if it is a finite number (not a bool)."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ValueError(f"{what} {value!r} is not a finite number")
    return float(value)


def _counts(state: dict[str, Any], what: str, positive_keys: bool) -> tuple[dict[float, int], int]:
    """A saved ``counts`` list of ``[key, count >= 1]`` pairs (keys > 0 where
    ``positive_keys``, distinct) and its ``total``, which must be their sum."""
    entries = state["counts"]
    if not isinstance(entries, list) or not all(
        isinstance(e, list) and len(e) == 2 for e in entries
    ):
        raise ValueError(f"{what}'s counts must be a list of [value, count] pairs")
    counts: dict[float, int] = {}
    for key, n in entries:
        value = _number(key, f"{what}'s counted value")
        if positive_keys and value <= 0.0:
            raise ValueError(f"{what}'s counted magnitude {key!r} is not > 0")
        if isinstance(n, bool) or not isinstance(n, int) or n < 1:
            raise ValueError(f"{what}'s count of {key!r} is {n!r}, not an int >= 1")
        if value in counts:
            raise ValueError(f"{what} counts {key!r} twice")
        counts[value] = n
    total = state["total"]
    if isinstance(total, bool) or not isinstance(total, int) or total != sum(counts.values()):
        raise ValueError(f"{what}'s total {total!r} is not the sum of its counts")
    return counts, total


def _horizon(gamma: float, horizon: float | None) -> float:
    """The unit's H: ``horizon`` when given, else ``1 / (1 - gamma)`` (1 at gamma = 1)."""
    if horizon is not None:
        return horizon
    return 1.0 / (1.0 - gamma) if gamma < 1.0 else 1.0


def _bin(magnitude: float) -> float:
    """Index of the 1/16-octave bin of a positive magnitude (as a float key)."""
    mantissa, exponent = math.frexp(magnitude)  # exact: magnitude = mantissa * 2^exponent
    return float(exponent * BINS_PER_OCTAVE + math.floor(math.log2(mantissa) * BINS_PER_OCTAVE))


class ReturnScale:
    """Running standard deviation of the eq. (9) returns the agent has learnt from.

    The other rule (``TreeConfig(scale_rule="return_std")``): the spread of the values the
    tree is fitting, rather than the size of one reward. It is 0 before two returns differ, and
    it grows when the goal is first found (the returns then span the goal's reward).
    Welford's update; homogeneous like :class:`RewardScale`.
    """

    __slots__ = ("count", "m2", "mean")

    def __init__(self) -> None:
        self.count = 0
        self.mean = 0.0
        self.m2 = 0.0

    def add(self, returns: list[float]) -> None:
        """Welford's update with each return of one epoch."""
        count, mean, m2 = self.count, self.mean, self.m2
        for g in returns:
            count += 1
            delta = g - mean
            mean += delta / count
            m2 += delta * (g - mean)
        self.count, self.mean, self.m2 = count, mean, m2

    @property
    def value(self) -> float:
        """The population standard deviation of the returns so far (0 before two returns)."""
        if self.count < 2:
            return 0.0
        return math.sqrt(max(0.0, self.m2 / self.count))

    def state(self) -> dict[str, Any]:
        """JSON-ready state."""
        return {"count": self.count, "mean": self.mean, "m2": self.m2}

    def restore(self, state: dict[str, Any]) -> None:
        """Inverse of :meth:`state`; a ValueError names the first field that is wrong."""
        count = state["count"]
        if isinstance(count, bool) or not isinstance(count, int) or count < 0:
            raise ValueError(f"the return scale's count {count!r} is not an int >= 0")
        mean = _number(state["mean"], "the return scale's mean")
        m2 = _number(state["m2"], "the return scale's m2")
        if m2 < 0.0:
            raise ValueError(f"the return scale's m2 {m2!r} is negative")
        self.count, self.mean, self.m2 = count, mean, m2

    def __repr__(self) -> str:
        return f"ReturnScale(returns={self.count}, value={self.value:.6g})"


class ReturnSpread:
    """Interquartile range of the eq. (9) returns, over 1.349 (the IQR of a unit normal).

    ``TreeConfig(scale_rule="return_iqr")``: the spread of the values the tree is fitting, like
    :class:`ReturnScale`, but robust: a few leaves stuck at the value of colliding for ever
    (-100 on the maze) do not move it. The returns are counted in signed logarithmic bins of
    1/16 octave (and a bin for 0), and each quartile is its bin's geometric centre (within
    2.2 %); homogeneous under multiplication by a power of two.
    """

    __slots__ = ("_counts", "_dirty", "_keys", "_unit", "total")

    def __init__(self) -> None:
        self.total = 0
        self._counts: dict[float, int] = {}
        """signed bin key -> count; key 0 is the exact zero, +-(bin + 2^20) the magnitudes."""
        self._keys: list[float] = []
        """The keys in increasing order."""
        self._unit = 0.0
        self._dirty = False

    def add(self, returns: list[float]) -> None:
        """Count an epoch's returns (the unit is refreshed when next read)."""
        counts = self._counts
        for g in returns:
            if not math.isfinite(g):
                continue
            key = 0.0 if g == 0.0 else math.copysign(_bin(abs(g)) + _OFFSET, g)
            n = counts.get(key)
            if n is None:
                bisect.insort(self._keys, key)
                n = 0
            counts[key] = n + 1
            self.total += 1
            self._dirty = True

    def _quantile(self, q: float) -> float:
        rank = max(1, math.ceil(q * self.total))
        seen = 0
        for key in self._keys:
            seen += self._counts[key]
            if seen >= rank:
                if key == 0.0:
                    return 0.0
                magnitude = 2.0 ** ((abs(key) - _OFFSET + 0.5) / BINS_PER_OCTAVE)
                return math.copysign(magnitude, key)
        raise AssertionError("unreachable: counts sum to total")

    @property
    def value(self) -> float:
        """The robust spread (0 before the returns differ)."""
        if self._dirty:
            self._unit = (self._quantile(0.75) - self._quantile(0.25)) / _NORMAL_IQR
            self._dirty = False
        return self._unit

    def state(self) -> dict[str, Any]:
        """JSON-ready state."""
        return {"total": self.total, "counts": [[k, n] for k, n in self._counts.items()]}

    def restore(self, state: dict[str, Any]) -> None:
        """Inverse of :meth:`state`; a ValueError names the first field that is wrong."""
        self._counts, self.total = _counts(state, "the return spread", positive_keys=False)
        self._keys = sorted(self._counts)
        self._unit = 0.0
        self._dirty = self.total > 0

    def __repr__(self) -> str:
        return f"ReturnSpread(returns={self.total}, value={self.value:.6g})"


_OFFSET = float(1 << 20)
"""Added to a magnitude's bin index so that every signed key is away from 0 (bins of tiny
magnitudes are negative numbers)."""
_NORMAL_IQR = 1.3489795003921634
"""Interquartile range of the standard normal distribution."""
