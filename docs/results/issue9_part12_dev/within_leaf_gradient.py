"""Prototype: the bootstrap V-bar(l', s') of a model backup reads a within-leaf linear correction
fitted to the stored epochs of l''s greedy action (targets regressed on first inputs)."""

import os

import numpy as np

from agent import leaf_model as LM

RIDGE = float(os.environ.get("GP_RIDGE", "0.01"))
MINF = int(os.environ.get("GP_MIN", "2"))  # records needed per dim: m >= MINF*d+2
REFIT = int(os.environ.get("GP_REFIT", "200"))
CLIPF = float(os.environ.get("GP_CLIP", "1.0"))

_orig_add = LM.LeafModel.add
_orig_split = LM.LeafModel.split


def _state(self):
    st = self.__dict__.get("_gp")
    if st is None:
        st = self.__dict__["_gp"] = {"cache": {}, "adds": 0}
    return st


def add(self, leaf, action, *a, **k):
    _orig_add(self, leaf, action, *a, **k)
    st = _state(self)
    st["adds"] += 1
    st["cache"].pop(leaf, None)


def split(self, parent, children, leaf_of):
    out = _orig_split(self, parent, children, leaf_of)
    c = _state(self)["cache"]
    c.pop(parent, None)
    for ch in children:
        c.pop(ch, None)
    return out


def _fit(self, leaf, q):
    st = _state(self)
    hit = st["cache"].get(leaf)
    if hit is not None and st["adds"] - hit[0] < REFIT:
        return hit[1]
    row = q[leaf]
    best = max(range(len(row)), key=row.__getitem__)
    firsts, ys = LM.LeafModel.targets(self, leaf, best, q)
    fit = None
    if firsts:
        d = len(firsts[0])
        m = len(firsts)
        if m >= MINF * d + 2:
            X = np.asarray(firsts, dtype=float)
            y = np.asarray(ys, dtype=float)
            c = X.mean(axis=0)
            sd = X.std(axis=0)
            ok = sd > 1e-12
            if ok.any():
                Z = (X[:, ok] - c[ok]) / sd[ok]
                yc = y - y.mean()
                A = Z.T @ Z + RIDGE * m * np.eye(int(ok.sum()))
                w = np.linalg.solve(A, Z.T @ yc)
                g = np.zeros(d)
                g[ok] = w / sd[ok]
                half = CLIPF * (y.max() - y.min()) / 2.0
                fit = (g.tolist(), c.tolist(), half)
    st["cache"][leaf] = (st["adds"], fit)
    return fit


def value(self, leaf, action, q):
    key = leaf * self.n_actions + action
    records = self._records.get(key)
    if not records:
        return None
    total = 0.0
    novel = self.novel_value
    for _first, reward, discount, end, end_leaf in records:
        total += reward
        if end is None:
            continue
        if end_leaf == LM._NOVEL:
            total += discount * novel
            continue
        v = max(q[end_leaf])
        fit = _fit(self, end_leaf, q)
        if fit is not None:
            g, c, half = fit
            corr = 0.0
            for gi, si, ci in zip(g, end, c, strict=False):
                corr += gi * (si - ci)
            if corr > half:
                corr = half
            elif corr < -half:
                corr = -half
            v += corr
        total += discount * v
    return total / len(records)


LM.LeafModel.add = add
LM.LeafModel.split = split
LM.LeafModel.value = value
