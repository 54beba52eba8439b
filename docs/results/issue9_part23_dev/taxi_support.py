"""Prototype check on Taxi-v4 (integer inputs through ``adapt_env``, the general preset's
table): one training run (600 episodes, the protocol of
``tests/agent/test_integer_table.py``, strategy "adaptive+tabu"), greedy returns from 10 starts
(reset seeds 10,000 + i) under each k of ``supported_greedy.KS``.

    python taxi_support.py OUT SEED [SEED ...]
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

from supported_greedy import KS, greedy_returns
from tasks_support import trained

if __name__ == "__main__":
    warnings.simplefilter("ignore")
    out = Path(sys.argv[1])
    for seed in map(int, sys.argv[2:]):
        agent, env = trained("Taxi-v4", 600, seed, exploration="adaptive+tabu")
        for k in KS:
            returns = greedy_returns(agent, env, k, [10_000 + i for i in range(10)])
            with out.open("a") as f:
                f.write(json.dumps({"task": "Taxi-v4", "seed": seed, "k": k, "returns": returns, "delivered": sum(r > 0 for r in returns)}) + "\n")
