"""Issue 9, part 18 (development): does the greedy policy gain when the model's values are
planned to convergence before it acts?

During training the model's values get at most ``sweep_backups`` prioritized backups an epoch
(:mod:`agent.leaf_model`), so at the end of a run some leaves may still carry values the model
no longer supports. This probe takes a trained agent (``local_greedy.trained``: 1,000
episodes of ``general_as_of(17)``, saved and reused), scores it greedily over 20 episodes
(reset seeds 10^6 + 1000 SEED + i), then repeats ``LeafModel.backup_all`` (value iteration over
the stored epochs) until no V-bar moves by more than 1e-9 of the largest |Q-bar|, or 20,000
passes, and scores it again. One JSON line per agent::

    python docs/results/issue9_part18_dev/converge_values.py TASK SEED OUT.jsonl [MODEL_DIR]
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from local_greedy import episode_return, trained  # noqa: E402


def main(task: str, seed: int, out: str, model_dir: str) -> None:
    warnings.simplefilter("ignore")
    agent, env = trained(task, seed, model_dir)
    before = [episode_return(env, 10**6 + 1000 * seed + i, agent.predict) for i in range(20)]
    scale = max(abs(v) for row in agent.q for v in row) or 1.0
    passes, largest = 0, float("inf")
    while passes < 20000 and largest > 1e-9 * scale:
        changes = agent.model.backup_all(agent.q)
        largest = max(changes.values(), default=0.0)
        passes += 1
    after = [episode_return(env, 10**6 + 1000 * seed + i, agent.predict) for i in range(20)]
    with Path(out).open("a") as f:
        f.write(json.dumps({"task": task, "seed": seed, "leaves": agent.n_leaves,
                            "greedy": round(float(np.mean(before)), 2),
                            "converged": round(float(np.mean(after)), 2),
                            "passes": passes, "last_change": largest}) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), sys.argv[3],
         sys.argv[4] if len(sys.argv) > 4 else "/tmp/part18_models")
