"""The prototype of model-driven splits as it was first run (2026-12-04, 23:33-23:58 UTC),
before ``agent/model_split.py`` existed: it wraps ``SMDPAgent._end_epoch`` and, after an epoch
that did not split, splits the leaf where the stored epochs of its action disagree (parameters
from the ``MS`` environment variable: k epochs, gap delta in units, t statistic, m a side).
It differs from the committed option in one way: a split here drops the leaf's error buffer
(``PartitionTree.split``), where the committed one hands it to the children. Kept for the
record of ``maze_prototype.jsonl`` and ``classic_prototype.jsonl``; with today's code it also
replaces the committed ``SMDPAgent._model_split``.
"""

import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", ".."))
from agent.learner import SMDPAgent

P = json.loads(os.environ.get("MS") or "{}")  # {"k":8,"delta":0.05,"t":3,"m":2}


def _model_split(self, leaf, action):
    model = self.model
    part = self.partition
    key = leaf * self.n_actions + action
    recs = model._records.get(key)
    k = P.get("k", 8)
    if recs is None or len(recs) < k or part.n_leaves >= self.config.max_leaves:
        return None
    q = self.q
    y = np.array([r + (0.0 if e is None else d * max(q[t])) for _, r, d, e, t in recs])
    X = np.array([f for f, *_ in recs])
    unit = self.scale.value if self._track_scale else 1.0
    delta = P.get("delta", 0.05) * unit
    if y.max() - y.min() < delta:
        return None
    low, high = np.asarray(part._low[leaf]), np.asarray(part._high[leaf])
    root_width = part._root_width
    if part._grown:
        low, high, root_width = part._grown_box(low, high)
    min_width = root_width * self.config.min_leaf_fraction
    m = P.get("m", 2)
    n = len(y)
    best = None
    for d in range(X.shape[1]):
        order = np.argsort(X[:, d], kind="stable")
        xs, ys = X[order, d], y[order]
        cs = np.cumsum(ys)
        cs2 = np.cumsum(ys * ys)
        tot, tot2 = cs[-1], cs2[-1]
        for i in range(m - 1, n - m):
            if xs[i] == xs[i + 1]:
                continue
            v = 0.5 * (xs[i] + xs[i + 1])
            if not (v - low[d] >= min_width[d] and high[d] - v >= min_width[d]):
                continue
            nl, nr = i + 1, n - i - 1
            ml, mr = cs[i] / nl, (tot - cs[i]) / nr
            diff = abs(ml - mr)
            if diff < delta:
                continue
            sse = (cs2[i] - nl * ml * ml) + (tot2 - cs2[i] - nr * mr * mr)
            s = math.sqrt(max(sse, 0.0) / max(n - 2, 1))
            tstat = math.inf if s == 0 else diff / (s * math.sqrt(1 / nl + 1 / nr))
            if tstat < P.get("t", 3.0):
                continue
            gain = nl * nr / n * diff * diff
            if best is None or gain > best[0]:
                best = (gain, d, v)
    if best is None:
        return None
    children = part.split(leaf, best[1], float(best[2]))
    self._grow(leaf, children)
    return children


_orig = SMDPAgent._end_epoch


def _end_epoch(self, leaf, action, xs, rs, bootstrap, end_x=None, terminated=False):
    split = _orig(self, leaf, action, xs, rs, bootstrap, end_x, terminated)
    if split or self.model is None or end_x is None or not P:
        return split
    return self._model_split(leaf, action) is not None


SMDPAgent._model_split = _model_split
SMDPAgent._end_epoch = _end_epoch
