"""Run dev jobs (``job.py``) over cases x seeds x arms, ``W`` at a time (default 2)::

    python batch.py maze OUT LAYOUT_FILE SEEDS 'label=PROTOTYPE_JSON|OVERRIDES_JSON' ...
    python batch.py classic OUT TASK,TASK SEEDS 'label=PROTOTYPE_JSON|OVERRIDES_JSON' ...

An empty PROTOTYPE_JSON runs the committed code with the TreeConfig overrides. A job that
fails writes no line; its exit code and the end of its stderr go to ``OUT.err``.
"""

from __future__ import annotations

import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]


def main(argv: list[str]) -> None:
    kind, out, cases, seeds = argv[0], argv[1], argv[2], [int(s) for s in argv[3].split(",")]
    if kind == "maze":
        names = [line.strip() for line in Path(cases).read_text().splitlines() if line.strip()]
    else:
        names = cases.split(",")
    arms = []
    for arm in argv[4:]:
        label, rest = arm.split("=", 1)
        prototype, overrides = rest.split("|")
        arms.append((label, prototype, overrides or "{}"))
    jobs = [(name, seed, arm) for seed in seeds for name in names for arm in arms]

    def go(job: tuple[str, int, tuple[str, str, str]]) -> None:
        name, seed, (label, prototype, overrides) = job
        command = [sys.executable, str(HERE / "job.py"), kind, name, str(seed), label]
        done = subprocess.run(
            [*command, overrides, out],
            env=dict(os.environ, MS=prototype),
            cwd=ROOT,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
            timeout=3600,
            check=False,
        )
        if done.returncode != 0:  # a failed job writes no line: say which, and why
            with open(f"{out}.err", "a") as errors:
                errors.write(f"== {kind} {name} seed {seed} {label}: exit {done.returncode}\n")
                errors.write(done.stderr[-4000:] + "\n")

    with ThreadPoolExecutor(int(os.environ.get("W", "2"))) as pool:
        list(pool.map(go, jobs))


if __name__ == "__main__":
    main(sys.argv[1:])
