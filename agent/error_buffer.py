"""A leaf's bounded store of state-error pairs ``(s_k, delta_k)`` (section IV.B).

A ring buffer of fixed capacity N_th in flat ``array('d')`` storage (8 bytes a value), with
running sums of the errors so that the split test's mean and variance cost O(1) per epoch. The
sums are recomputed exactly each time the ring wraps, so rounding cannot drift. The storage grows
with the pairs until the ring first wraps (:meth:`ErrorBuffer.allocate` fills it to capacity),
so a leaf that splits before its buffer fills holds only what it was given: most of a tree's
leaves, and with wide inputs (38 for the lidar) most of its memory.
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
        self.inputs = array("d")
        self.errors = array("d")
        self.count = 0
        self.head = 0
        self.sum = 0.0
        self.sum_sq = 0.0

    def add(self, xs: list[list[float]], deltas: list[float]) -> None:
        """Append the pairs ``(xs[k], deltas[k])``."""
        head, count, total, total_sq = self.head, self.count, self.sum, self.sum_sq
        n = len(deltas)
        if head + n >= self.capacity or count + n > self.capacity:
            self.allocate()  # the ring wraps or overwrites: it is indexed at full size
        dims, capacity, inputs, errors = self.dims, self.capacity, self.inputs, self.errors
        if head + n < capacity and count + n <= capacity:
            # the usual case, no wrap and nothing overwritten: two slice copies that grow
            # the storage while it is shorter than the capacity
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

    def allocate(self) -> None:
        """Grow the storage to the full capacity, zeros after what was written (the ring
        indexes it at full size; the fast loop's kernel mirrors it at full size)."""
        missing = self.capacity - len(self.errors)
        if missing > 0:
            self.errors.frombytes(bytes(8 * missing))
        missing = self.capacity * self.dims - len(self.inputs)
        if missing > 0:
            self.inputs.frombytes(bytes(8 * missing))

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
        inputs = np.frombuffer(self.inputs, dtype=np.float64)
        errors = np.frombuffer(self.errors, dtype=np.float64)
        count, dims = self.count, self.dims
        if count < self.capacity:  # not wrapped: the first count pairs, in order
            return inputs[: count * dims].reshape(count, dims).copy(), errors[:count].copy()
        order = (np.arange(self.capacity) + self.head) % self.capacity
        return inputs.reshape(self.capacity, dims)[order], errors[order]

    def state(self) -> tuple[NDArray[np.float64], NDArray[np.float64], list[int | float]]:
        """Raw storage at full size (zeros after what was written) and counters, for saving
        (restored exactly by :meth:`restore`)."""
        inputs = np.zeros(self.capacity * self.dims, dtype=np.float64)
        errors = np.zeros(self.capacity, dtype=np.float64)
        inputs[: len(self.inputs)] = np.frombuffer(self.inputs, dtype=np.float64)
        errors[: len(self.errors)] = np.frombuffer(self.errors, dtype=np.float64)
        return inputs, errors, [self.count, self.head, self.sum, self.sum_sq]

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
