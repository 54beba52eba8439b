"""Part 14: part 13's separating-cut prototype (``../issue9_part13_dev/collision_cut.py``,
label ``ccut``) against the preset (label ``preset``) on more agent seeds of the four dev
forests, one run after another, each in its own process (the prototype patches
``SMDPAgent``). Appends to ``maze_collision_seeds.jsonl``; a failed run's stderr goes to
``maze_collision_seeds.err``::

    PYTHONPATH=. python docs/results/issue9_part14_dev/collision_seeds.py 2,3,4
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
OUT = HERE / "maze_collision_seeds.jsonl"
FORESTS = [
    "forest:seed=0",
    "forest:seed=1,count=70,radius_max=8,gap=11",
    "forest:seed=2,count=70,radius_max=8,gap=11",
    "forest:seed=3,count=70,radius_max=8,gap=11",
]
CURVES = ROOT / "docs/results/issue9_hold_terminals_dev/curves.py"
CUT = (
    "import sys; from pathlib import Path; sys.path.insert(0, {folder!r}); "
    "import collision_cut as c; c.patch(); c.curves.run({maze!r}, {seed}, 'ccut', {{}}, "
    "Path({out!r}))"
)


def main(seeds: list[int]) -> None:
    for seed in seeds:
        for maze in FORESTS:
            jobs = [
                [sys.executable, str(CURVES), maze, str(seed), "preset", "{}", str(OUT)],
                [
                    sys.executable,
                    "-c",
                    CUT.format(
                        folder=str(HERE.parent / "issue9_part13_dev"),
                        maze=maze,
                        seed=seed,
                        out=str(OUT),
                    ),
                ],
            ]
            for job in jobs:
                done = subprocess.run(job, cwd=ROOT, capture_output=True, text=True, check=False)
                if done.returncode != 0:
                    with OUT.with_suffix(".err").open("a") as errors:
                        errors.write(f"== {maze} {seed} {job[-3:]}\n{done.stderr[-3000:]}\n")


if __name__ == "__main__":
    main([int(s) for s in sys.argv[1].split(",")])
