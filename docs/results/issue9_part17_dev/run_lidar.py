"""Run ``lidar_maze.py`` over layouts x seeds x arms, two at a time (development only)::

    python run_lidar.py OUT LAYOUTS_FILE SEEDS 'label=OVERRIDES_JSON' ...
"""

from __future__ import annotations

import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

HERE = Path(__file__).resolve().parent

if __name__ == "__main__":
    out, layouts, seeds = sys.argv[1], Path(sys.argv[2]).read_text().split(), sys.argv[3]
    arms = [arm.split("=", 1) for arm in sys.argv[4:]]
    jobs = [(m, s, a) for s in seeds.split(",") for m in layouts for a in arms]

    def go(job: tuple[str, str, list[str]]) -> None:
        layout, seed, (label, overrides) = job
        script = str(HERE / "lidar_maze.py")
        subprocess.run([sys.executable, script, layout, seed, label, overrides, out], check=False)

    with ThreadPoolExecutor(2) as pool:
        list(pool.map(go, jobs))
