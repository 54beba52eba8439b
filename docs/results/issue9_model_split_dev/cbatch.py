"""Run the classic-control dev driver over tasks x seeds x arms (``W`` workers)::

python cbatch.py OUT TASKS SEEDS 'label=PROTOTYPE_JSON|OVERRIDES_JSON' ...
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
    out, tasks, seeds = argv[0], argv[1].split(","), [int(s) for s in argv[2].split(",")]
    arms = []
    for arm in argv[3:]:
        label, rest = arm.split("=", 1)
        prototype, overrides = rest.split("|")
        arms.append((label, prototype, overrides or "{}"))
    jobs = [(task, seed, arm) for task in tasks for seed in seeds for arm in arms]

    def go(job: tuple[str, int, tuple[str, str, str]]) -> None:
        task, seed, (label, prototype, overrides) = job
        command = [sys.executable, str(HERE / "classic.py"), task, str(seed), label, overrides, out]
        subprocess.run(
            command,
            env=dict(os.environ, MS=prototype),
            cwd=ROOT,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            timeout=3600,
            check=False,
        )

    with ThreadPoolExecutor(int(os.environ.get("W", "2"))) as pool:
        list(pool.map(go, jobs))


if __name__ == "__main__":
    main(sys.argv[1:])
