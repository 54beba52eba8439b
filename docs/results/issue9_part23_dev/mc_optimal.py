"""MountainCar-v0's optimal steps-to-goal by value iteration on a fine grid (bilinear
interpolation), saved to ``mc_optimal.npz``; ``qstar(x, v)`` gives the three actions' optimal
steps-to-go (one step plus the interpolated value of the next state)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

NX, NV = 901, 701
XS = np.linspace(-1.2, 0.6, NX)
VS = np.linspace(-0.07, 0.07, NV)
OUT = Path(__file__).with_name("mc_optimal.npz")


def step(x: np.ndarray, v: np.ndarray, a: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    v2 = np.clip(v + (a - 1) * 0.001 + np.cos(3 * x) * (-0.0025), -0.07, 0.07)
    x2 = np.clip(x + v2, -1.2, 0.6)
    v2 = np.where((x2 == -1.2) & (v2 < 0), 0.0, v2)
    done = (x2 >= 0.5) & (v2 >= 0)
    return x2, v2, done


def interp(table: np.ndarray, x: np.ndarray, v: np.ndarray) -> np.ndarray:
    fx = (x - XS[0]) / (XS[1] - XS[0])
    fv = (v - VS[0]) / (VS[1] - VS[0])
    i = np.clip(np.floor(fx).astype(int), 0, NX - 2)
    j = np.clip(np.floor(fv).astype(int), 0, NV - 2)
    tx, tv = fx - i, fv - j
    return (
        table[i, j] * (1 - tx) * (1 - tv)
        + table[i + 1, j] * tx * (1 - tv)
        + table[i, j + 1] * (1 - tx) * tv
        + table[i + 1, j + 1] * tx * tv
    )


def solve() -> np.ndarray:
    gx, gv = np.meshgrid(XS, VS, indexing="ij")
    nxt = [step(gx, gv, a) for a in range(3)]
    value = np.zeros((NX, NV))
    for _ in range(400):
        q = np.stack([1.0 + np.where(d, 0.0, interp(value, x2, v2)) for x2, v2, d in nxt])
        new = q.min(axis=0)
        if np.max(np.abs(new - value)) < 1e-6:
            break
        value = new
    return value


_TABLE: np.ndarray | None = None


def qstar(x: float, v: float) -> list[float]:
    global _TABLE
    if _TABLE is None:
        if not OUT.exists():
            np.savez(OUT, value=solve())
        _TABLE = np.load(OUT)["value"]
    out = []
    for a in range(3):
        x2, v2, d = step(np.array([x]), np.array([v]), a)
        out.append(1.0 if d[0] else 1.0 + float(interp(_TABLE, x2, v2)[0]))
    return out


if __name__ == "__main__":
    import time

    t = time.time()
    print([round(min(qstar(x, 0.0)), 1) for x in np.linspace(-0.6, -0.4, 11)], time.time() - t)
    assert math.isfinite(qstar(-0.5, 0.0)[0])
