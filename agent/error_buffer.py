"""A leaf's bounded store of state-error pairs ``(s_k, delta_k)`` (section IV.B).

A ring buffer of fixed capacity N_th in flat ``array('d')`` storage (8 bytes a value), with
running sums of the errors so that the split test's mean and variance cost O(1) per epoch. The
sums are recomputed exactly each time the ring wraps, so rounding cannot drift.
"""

from __future__ import annotations

from array import array
from operator import mul

import numpy as np
from numpy.typing import NDArray


class ErrorBuffer:
    """At most ``capacity`` state-error pairs of one leaf; the oldest is overwritten first."""

    __slots__ = ("capacity", "count", "dims", "errors", "head", "inputs", "sum", "sum_sq")

    def __init__(self, dims: int, capacity: int) -> None:
        self.dims = dims
        self.capacity = capacity
        self.inputs = array("d", bytes(8 * dims * capacity))
        self.errors = array("d", bytes(8 * capacity))
        self.count = 0
        self.head = 0
        self.sum = 0.0
        self.sum_sq = 0.0

    def add(self, xs: list[list[float]], deltas: list[float]) -> None:
        """Append the pairs ``(xs[k], deltas[k])``."""
        dims, capacity, inputs, errors = self.dims, self.capacity, self.inputs, self.errors
        head, count, total, total_sq = self.head, self.count, self.sum, self.sum_sq
        n = len(deltas)
        if head + n < capacity and count + n <= capacity:
            # the usual case, no wrap and nothing overwritten: two slice copies
            inputs[head * dims : (head + n) * dims] = array("d", [v for x in xs for v in x])
            errors[head : head + n] = array("d", deltas)
            self.head = head + n
            self.count = count + n
            self.sum = total + sum(deltas)
            self.sum_sq = total_sq + sum(map(mul, deltas, deltas))
            return
        for x, e in zip(xs, deltas, strict=True):
            base = head * dims
            inputs[base : base + dims] = array("d", x)
            if count == capacity:
                old = errors[head]
                total -= old
                total_sq -= old * old
            else:
                count += 1
            errors[head] = e
            total += e
            total_sq += e * e
            head += 1
            if head == capacity:
                head = 0
                self.count = count
                total, total_sq = self._exact_sums()
        self.head, self.count, self.sum, self.sum_sq = head, count, total, total_sq

    def _exact_sums(self) -> tuple[float, float]:
        errs = np.frombuffer(self.errors, dtype=np.float64)[: self.count]
        return float(errs.sum()), float(np.dot(errs, errs))

    def mean_variance(self) -> tuple[float, float]:
        """Mean and (population) variance of the stored errors; (0, 0) when empty."""
        if self.count == 0:
            return 0.0, 0.0
        mean = self.sum / self.count
        return mean, max(0.0, self.sum_sq / self.count - mean * mean)

    def clear(self) -> None:
        """Drop every pair."""
        self.count = 0
        self.head = 0
        self.sum = 0.0
        self.sum_sq = 0.0

    def arrays(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Copies of the stored inputs ``(count, dims)`` and errors ``(count,)``, oldest first."""
        inputs = np.frombuffer(self.inputs, dtype=np.float64).reshape(self.capacity, self.dims)
        errors = np.frombuffer(self.errors, dtype=np.float64)
        if self.count < self.capacity:
            order = np.arange(self.count)
        else:
            order = (np.arange(self.capacity) + self.head) % self.capacity
        return inputs[order].copy(), errors[order].copy()

    def state(self) -> tuple[NDArray[np.float64], NDArray[np.float64], list[int | float]]:
        """Raw storage and counters, for saving (restored exactly by :meth:`restore`)."""
        return (
            np.frombuffer(self.inputs, dtype=np.float64).copy(),
            np.frombuffer(self.errors, dtype=np.float64).copy(),
            [self.count, self.head, self.sum, self.sum_sq],
        )

    @classmethod
    def restore(
        cls,
        dims: int,
        capacity: int,
        inputs: NDArray[np.float64],
        errors: NDArray[np.float64],
        counters: list[int | float],
    ) -> ErrorBuffer:
        """Inverse of :meth:`state`."""
        buf = cls(dims, capacity)
        buf.inputs = array("d", np.asarray(inputs, dtype=np.float64).tobytes())
        buf.errors = array("d", np.asarray(errors, dtype=np.float64).tobytes())
        buf.count, buf.head = int(counters[0]), int(counters[1])
        buf.sum, buf.sum_sq = float(counters[2]), float(counters[3])
        return buf
