"""Memory of the general preset's learner on a wide input (the lidar: x, y and 36 ranges).

One run of ``agent.preset("general")`` on a layout seen through the lidar (``observation=
"lidar"``, 38 inputs), ``--episodes`` learning episodes, agent and reset seed ``--seed``. Then,
in the same process, what the two largest stores hold against a reference measured beside them:

* the model's stored inputs (:mod:`agent.leaf_model`, one compact ``array('d')`` per epoch
  boundary, shared by an epoch's end and the next epoch's start) against the same inputs as the
  lists of Python floats the learner makes of each observation (``ndarray.tolist()``, the form
  stored before), and against their raw size (8 bytes a value);
* the leaves' split-test buffers (:class:`agent.error_buffer.ErrorBuffer`, grown with the pairs
  until the ring first wraps) against buffers allocated at full capacity (N_th pairs), the
  form before;

and the process's resident memory (``VmRSS``) at the end. Ratios below 1 are memory saved::

    python bench/bench_wide_memory.py                       # rooms:seed=0, 50 episodes, ~1 min
    python bench/bench_wide_memory.py --episodes 150 --maze forest:seed=0
"""

from __future__ import annotations

import argparse
import sys
import time
from array import array
from pathlib import Path

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from agent import preset
from agent.tree_ensemble import tree_agent_class


def resident_mb() -> float:
    """The process's resident set (``VmRSS``) in MB; NaN where /proc is missing."""
    status = Path("/proc/self/status")
    if not status.exists():
        return float("nan")
    for line in status.read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return float("nan")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--maze", default="rooms:seed=0")
    parser.add_argument("--episodes", type=int, default=50)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    if args.episodes < 1:
        parser.error(f"--episodes must be >= 1, got {args.episodes}")

    try:
        env = gym.make("BulletMaze-v0", maze=args.maze, max_episode_steps=5000, observation="lidar")
    except ValueError as error:
        parser.error(f"--maze {args.maze!r}: {error}")
    general = preset("general")
    config = general.config
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, general.make_exploration(), args.seed, config
    )
    start = time.process_time()
    agent.learn(env, args.episodes, reset_seed=args.seed)
    cpu = time.process_time() - start
    model = agent.model
    assert model is not None  # the general preset plans over the model

    dims = int(np.prod(env.observation_space.shape))
    stored: dict[int, object] = {}
    epochs = 0
    for records in model._records.values():
        for record in records:
            epochs += 1
            for value in (record[0], record[3]):
                if value is not None:
                    stored[id(value)] = value
    compact = sum(sys.getsizeof(value) for value in stored.values())
    as_lists = 0
    for value in stored.values():
        floats = np.frombuffer(value, dtype=np.float64).tolist()  # type: ignore[call-overload]
        as_lists += sys.getsizeof(floats) + sum(sys.getsizeof(v) for v in floats)
    raw = 8 * dims * len(stored)

    buffers = list(agent.partition._buffers.values())  # type: ignore[attr-defined]
    held = sum(sys.getsizeof(b.inputs) + sys.getsizeof(b.errors) for b in buffers)
    header = sys.getsizeof(array("d"))  # an empty array; a full one adds 8 bytes a value
    full = sum(2 * header + 8 * (dims + 1) * b.capacity for b in buffers)
    pairs = sum(b.count for b in buffers)
    capacity = sum(b.capacity for b in buffers)

    print(
        f"{args.maze}, lidar ({dims} inputs), general preset, {args.episodes} episodes, "
        f"seed {args.seed}: {agent.n_leaves:,} leaves, {epochs:,} stored epochs, "
        f"{cpu:.0f} CPU-s, resident {resident_mb():,.0f} MB"
    )
    print(f"{'store':<58} {'MB':>8} {'reference MB':>13} {'ratio':>6}")
    rows = [
        (f"stored inputs ({len(stored):,} copies) vs float lists", compact, as_lists),
        ("stored inputs vs their raw 8-byte values", compact, raw),
        (f"split buffers ({pairs:,} of {capacity:,} pairs) vs full size", held, full),
    ]
    for label, value, reference in rows:
        print(f"{label:<58} {value / 1e6:>8.1f} {reference / 1e6:>13.1f} {value / reference:>6.2f}")


if __name__ == "__main__":
    main()
