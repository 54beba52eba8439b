"""Run the maze dev driver over layouts x seeds x arms, two jobs at a time (``W`` workers)::

    python batch.py OUT LAYOUT_FILE SEEDS 'label=PROTOTYPE_JSON|OVERRIDES_JSON' ...

An empty PROTOTYPE_JSON runs the committed code with the TreeConfig overrides.
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
    out, layout_file, seeds = argv[0], argv[1], [int(s) for s in argv[2].split(",")]
    arms = []
    for arm in argv[3:]:
        label, rest = arm.split("=", 1)
        prototype, overrides = rest.split("|")
        arms.append((label, prototype, overrides or "{}"))
    layouts = [line.strip() for line in Path(layout_file).read_text().splitlines() if line.strip()]
    jobs = [(maze, seed, arm) for seed in seeds for maze in layouts for arm in arms]

    def go(job: tuple[str, int, tuple[str, str, str]]) -> None:
        maze, seed, (label, prototype, overrides) = job
        command = [sys.executable, str(HERE / "maze.py"), maze, str(seed), label, overrides, out]
        subprocess.run(
            command,
            env=dict(os.environ, MS=prototype),
            cwd=ROOT,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            timeout=1800,
            check=False,
        )

    with ThreadPoolExecutor(int(os.environ.get("W", "2"))) as pool:
        list(pool.map(go, jobs))


if __name__ == "__main__":
    main(sys.argv[1:])
