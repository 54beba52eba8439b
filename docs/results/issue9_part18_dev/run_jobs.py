"""Run the jobs of a file two at a time (development only): each line is a JSON list, the
arguments of ``python`` (a driver beside this file and its arguments)::

    python run_jobs.py JOBS_FILE
"""

from __future__ import annotations

import json
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

HERE = Path(__file__).resolve().parent

if __name__ == "__main__":
    lines = Path(sys.argv[1]).read_text().splitlines()
    jobs = [json.loads(line) for line in lines if line.strip()]

    def go(argv: list[str]) -> None:
        subprocess.run([sys.executable, str(HERE / argv[0]), *argv[1:]], check=False)

    with ThreadPoolExecutor(2) as pool:
        list(pool.map(go, jobs))
