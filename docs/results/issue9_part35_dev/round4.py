"""Part 35, round 4's test (decision.md): paired differences (N_th 50 minus today's preset) of
the mean greedy return over the fresh Acrobot seeds 10-39, with a 95 % bootstrap interval
(10,000 resamples of the seeds, numpy generator seeded 35); the runs at -100 per arm.

    python round4.py
"""

import json
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent


def rows(name):
    return {r["seed"]: r for r in map(json.loads, (HERE / name).open())}


base = rows("b0_ac_seeds10_19.jsonl") | rows("r4_ac_base.jsonl")
new = rows("r2a_ac_nth50_seeds10_19.jsonl") | rows("r4_ac_nth50.jsonl")
seeds = sorted(set(base) & set(new))
d = np.array([new[s]["mean"] - base[s]["mean"] for s in seeds])
rng = np.random.default_rng(35)
boot = d[rng.integers(0, len(d), size=(10_000, len(d)))].mean(axis=1)
low, high = np.percentile(boot, [2.5, 97.5])
print(f"seeds {seeds[0]}-{seeds[-1]} ({len(seeds)}): mean difference {d.mean():+.2f} "
      f"[{low:+.2f}, {high:+.2f}], higher on {int((d > 0).sum())} of {len(d)}")
for label, arm in (("today", base), ("N_th 50", new)):
    m = [arm[s]["mean"] for s in seeds]
    print(f"{label}: mean {np.mean(m):.2f}, {sum(x >= -100 for x in m)} of {len(m)} at -100, "
          f"long greedy episodes {sum(arm[s]['long'] for s in seeds)}, "
          f"CPU {sum(arm[s]['cpu'] for s in seeds):.0f} s")
for s in seeds:
    print(s, base[s]["mean"], new[s]["mean"])
