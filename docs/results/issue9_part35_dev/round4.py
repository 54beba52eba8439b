"""Part 35, rounds 4 and 5's test (decision.md): paired differences (N_th 50 minus today's
preset) of the mean greedy return over the fresh Acrobot seeds 10-39 (round 4) and 10-59
(round 5, once its lines exist), with a 95 % bootstrap interval (10,000 resamples of the seeds,
numpy generator seeded 35); the runs at -100 per arm.

    python round4.py
"""

import json
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent


def rows(*names):
    out = {}
    for name in names:
        if (HERE / name).exists():
            out |= {r["seed"]: r for r in map(json.loads, (HERE / name).open())}
    return out


def report(label, base, new, last):
    seeds = sorted(s for s in set(base) & set(new) if s <= last)
    d = np.array([new[s]["mean"] - base[s]["mean"] for s in seeds])
    rng = np.random.default_rng(35)
    boot = d[rng.integers(0, len(d), size=(10_000, len(d)))].mean(axis=1)
    low, high = np.percentile(boot, [2.5, 97.5])
    print(f"{label}: seeds {seeds[0]}-{seeds[-1]} ({len(seeds)}): mean difference "
          f"{d.mean():+.2f} [{low:+.2f}, {high:+.2f}], higher on {int((d > 0).sum())} of {len(d)}")
    for name, arm in (("  today", base), ("  N_th 50", new)):
        m = [arm[s]["mean"] for s in seeds]
        print(f"{name}: mean {np.mean(m):.2f}, {sum(x >= -100 for x in m)} of {len(m)} at -100, "
              f"long greedy episodes {sum(arm[s]['long'] for s in seeds)}, "
              f"CPU {sum(arm[s]['cpu'] for s in seeds):.0f} s")
    return seeds


base = rows("b0_ac_seeds10_19.jsonl", "r4_ac_base.jsonl", "r5_ac_base.jsonl")
new = rows("r2a_ac_nth50_seeds10_19.jsonl", "r4_ac_nth50.jsonl", "r5_ac_nth50.jsonl")
report("round 4", base, new, 39)
seeds = report("round 5", base, new, 59)
print("seed, today, N_th 50")
for s in seeds:
    print(s, base[s]["mean"], new[s]["mean"])
