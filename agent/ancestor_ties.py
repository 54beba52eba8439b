"""The tree's ancestors break the greedy choice's ties (``TreeConfig.greedy_tie_ancestors``;
beyond the paper, issue 9 part 27).

Where ``TreeConfig.greedy_tie_errors`` finds several of a leaf's actions tied (their Q-bar of
eq. (8) within z standard errors of the best's), a coarser region of the same tree may still
tell them apart: a rule on one velocity's sign, say, that the leaf's own few epochs cannot
resolve. An ancestor compares two actions a, b only inside the leaves below it where both have
a stored epoch, by the mean over those leaves of
Q-bar(l, a) - Q-bar(l, b) and its standard error (each leaf counted once). Comparing within
each leaf, rather than pooling every epoch below the ancestor, keeps a difference between the
places where each action happened to be tried out of the comparison.

The sums behind those means are kept per node, built on demand from the leaves up, and
dropped after every training episode (:meth:`PairedSums.clear`), so a choice never reads
values older than the agent's.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Protocol


class _Tree(Protocol):
    def parent(self, node: int) -> int: ...

    def children(self, node: int) -> tuple[int, int] | None: ...


class PairedSums:
    """Per node of one tree, for every action pair a < b: the number of leaves below it where
    both actions have a stored epoch, and the sum and sum of squares of
    Q-bar(l, a) - Q-bar(l, b) over them."""

    def __init__(self, n_actions: int) -> None:
        self.pairs = [(a, b) for a in range(n_actions) for b in range(a + 1, n_actions)]
        self._index = {pair: i for i, pair in enumerate(self.pairs)}
        self._sums: dict[int, list[float]] = {}

    def clear(self) -> None:
        """Forget every node's sums (the values or the tree changed)."""
        self._sums.clear()

    def at(
        self,
        node: int,
        tree: _Tree,
        q: list[list[float]],
        support: Callable[[int], list[int]],
    ) -> list[float]:
        """``[n, sum, sum of squares]`` per pair, flattened, for the leaves below ``node``
        (``support(leaf)``: each action's stored epochs there)."""
        sums = self._sums
        stack = [node]
        while stack:  # post-order, children before their parent
            top = stack[-1]
            if top in sums:
                stack.pop()
                continue
            halves = tree.children(top)
            if halves is None:
                sums[top] = self._leaf(q[top], support(top))
                stack.pop()
                continue
            missing = [child for child in halves if child not in sums]
            if missing:
                stack.extend(missing)
                continue
            left, right = sums[halves[0]], sums[halves[1]]
            sums[top] = [x + y for x, y in zip(left, right, strict=True)]
            stack.pop()
        return sums[node]

    def _leaf(self, row: list[float], counts: list[int]) -> list[float]:
        out = [0.0] * (3 * len(self.pairs))
        for i, (a, b) in enumerate(self.pairs):
            if counts[a] > 0 and counts[b] > 0:
                d = row[a] - row[b]
                out[3 * i : 3 * i + 3] = [1.0, d, d * d]
        return out

    def difference(self, sums: list[float], a: int, b: int) -> tuple[float, float]:
        """Mean of Q-bar(a) - Q-bar(b) over the node's shared leaves and its standard error
        (0 and infinity below two leaves)."""
        i = self._index[(min(a, b), max(a, b))]
        n, s, ss = sums[3 * i : 3 * i + 3]
        if n < 2:
            return 0.0, math.inf
        mean = s / n
        spread = max(ss - s * s / n, 0.0) / (n - 1)
        return (mean if a < b else -mean), math.sqrt(spread / n)


def ancestors_choice(
    tied: list[int],
    starts: Sequence[int],
    parent: Callable[[int, int], int],
    difference: Callable[[int, int, int, int], tuple[float, float]],
    z: float,
) -> int:
    """The action the ancestors choose among ``tied`` (the leaf's best first).

    ``starts[t]`` is tree t's leaf, ``parent(t, node)`` its parent there (-1 above the root) and
    ``difference(t, node, a, b)`` the mean and standard error of Q-bar(a) - Q-bar(b) over the
    node's shared leaves (:meth:`PairedSums.difference`). Each round asks every tree's next
    ancestor (a tree already at its root asks the root again): means are averaged over the
    trees, standard errors combined as sqrt(sum se^2) / trees. The best is the action with
    the largest summed mean difference to the other tied actions (the earlier in ``tied`` on
    equal sums); an action stays tied unless the best's mean lead over it exceeds ``z``
    standard errors. The rounds end when one action is left or every tree has asked its root;
    then the first action left is chosen."""
    nodes = list(starts)
    while len(tied) > 1:
        ups = [parent(t, node) for t, node in enumerate(nodes)]
        if all(up < 0 for up in ups):
            break
        nodes = [node if up < 0 else up for node, up in zip(nodes, ups, strict=True)]
        diff: dict[tuple[int, int], tuple[float, float]] = {}
        for i, a in enumerate(tied):  # each pair once; the reverse is its negation
            for b in tied[i + 1 :]:
                mean, se = _combined([difference(t, node, a, b) for t, node in enumerate(nodes)])
                diff[(a, b)], diff[(b, a)] = (mean, se), (-mean, se)
        score = {a: sum(diff[(a, b)][0] for b in tied if b != a) for a in tied}
        best = max(tied, key=score.__getitem__)
        kept = [best]
        for a in tied:
            if a != best:
                lead, se = diff[(best, a)]
                if not lead > z * se:
                    kept.append(a)
        tied = kept
    return tied[0]


def _combined(each: list[tuple[float, float]]) -> tuple[float, float]:
    """The trees' mean differences averaged, their standard errors combined."""
    k = len(each)
    return sum(m for m, _ in each) / k, math.sqrt(sum(e * e for _, e in each)) / k
