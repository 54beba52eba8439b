"""Compare two `paper` run folders of the general preset run by run (the report's convergence
rule from ``experiments.statistics``): runs converged, median episode, runs by episode 300,
final mean and worst final / optimum, AUC, and how many runs' finals are the same.

    python compare_part16.py NEW_FOLDER OLD_FOLDER   (from the project root, PYTHONPATH=.)

Part 30 wrote ``compare_part16.txt`` (part 30's preset against part 16's runs, which parts 17-29
left the same) and part 31 ``../issue9_part31_heldout_paper/compare_old_sweep.txt`` (part 30's
preset with today's sweep against the old one).
"""
import csv, sys, statistics
from pathlib import Path
import numpy as np
from experiments.statistics import convergence_episode
def load(folder):
    out = {}
    for f in sorted(Path(folder, "runs").glob("general__*.csv")):
        rows = list(csv.DictReader(open(f)))
        steps = np.array([float(r["steps"]) for r in rows])
        succ = np.array([float(r["success"]) for r in rows])
        c = convergence_episode(steps, final_success=float(succ[-100:].mean()))
        out[f.stem] = (c, steps[-100:].mean(), steps.mean())
    return out
a = load(sys.argv[1]); b = load(sys.argv[2])
print("runs", len(a), len(b), "same keys", set(a) == set(b))
for name, d in (("new", a), ("old", b)):
    cs = [v[0] for v in d.values()]
    fin = [v[1] for v in d.values()]
    print(name, "converged", sum(c is not None for c in cs), "median", statistics.median([c for c in cs if c is not None]),
          "by300", sum(c is not None and c <= 300 for c in cs), "final mean", round(statistics.mean(fin), 2),
          "max final/63", round(max(fin) / 63, 3), "auc", round(statistics.mean(v[2] for v in d.values()), 1))
same = sum(np.isclose(a[k][1], b[k][1]) for k in a)
print("same final", same, "new lower final", sum(a[k][1] < b[k][1] for k in a))
