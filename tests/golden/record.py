"""Record the golden files: what today's code computes, kept so that later changes are checked.

    python tests/golden/record.py [--only env,limits,agents,fig4]

Recorded at commit 3bdcf5f (2026-12-01), before any change of agent or env behaviour, so that
the issues that require the paper's method to reproduce bit for bit (the fast learning loop,
the learner's new defaults) and the simulation's rewrites (many solids, robots) are checked
against the code they replace. Re-run it only to record a *deliberate* change, and say so in
the commit.

* ``paper_fig4_short/``: the run CSVs of ``run.py experiment paper_fig4 --runs 2 --episodes 40
  --max-episode-steps 1500`` (every strategy, tree and grid agents); checked in the default
  test run.
* ``paper_fig4_medium/``: the same at ``--runs 2 --episodes 400`` (the default cap of 5,000),
  long enough for splits, tabu shrinking and learning; checked by a slow test.
* ``env_rollouts.csv``: seeded random-action rollouts of the env, every shipped layout, disc in
  both modes and the husky in dynamic mode (obs, reward, terminated, collision per step).
* ``physical_limits.json``: ``shortest_path`` of every shipped layout for its robot radius.
* ``agent_rollouts.csv``: ``TreeAgent`` and ``GridAgent`` on ``MountainCar-v0`` (the agent on
  an env that is not ours), per-episode statistics.
"""

from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
import tempfile
from collections.abc import Iterable
from pathlib import Path

import gymnasium as gym
import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent

FIG4_RUNS = {
    "paper_fig4_short": ["--runs", "2", "--episodes", "40", "--max-episode-steps", "1500"],
    "paper_fig4_medium": ["--runs", "2", "--episodes", "400"],
    "paper_fig4_short_release": ["--runs", "2", "--episodes", "40", "--max-episode-steps", "1500"],
}
"""Folder name -> the ``run.py experiment paper_fig4`` options that made it."""

FIG4_LEGACY = frozenset({"paper_fig4_short", "paper_fig4_medium"})
"""The folders recorded at 3bdcf5f, before ``PhysicsParams.contact_release``: they run with
``contact_release = false``, the sweep of that time (two of the short runs held a robot against
a wall, every action a collision, until the episode's cap). ``paper_fig4_short_release`` is
the same short run with today's sweep (2026-12-07, issue 9, part 31)."""


def run_fig4(folder: str, out: Path) -> None:
    """``run.py experiment paper_fig4`` with ``FIG4_RUNS[folder]``'s options into ``out`` (a
    legacy folder's config, with ``contact_release = false``, is written beside ``out``)."""
    config = "paper_fig4"
    if folder in FIG4_LEGACY:
        legacy = out.parent / "paper_fig4_legacy.toml"
        text = (ROOT / "experiments" / "paper_fig4.toml").read_text()
        legacy.write_text(text + "\n[env.params]\ncontact_release = false\n")
        config = str(legacy)
    subprocess.run(
        [
            sys.executable,
            str(ROOT / "run.py"),
            "experiment",
            config,
            *FIG4_RUNS[folder],
            "--workers",
            "2",
            "--out",
            str(out),
            "--no-progress",
        ],
        check=True,
        cwd=ROOT,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )


ROLLOUT_CASES = (
    # (layout, robot, mode, steps)
    ("paper", "disc", "kinematic", 3000),
    ("paper_narrow", "disc", "kinematic", 3000),
    ("open", "disc", "kinematic", 3000),
    ("corridors", "disc", "kinematic", 3000),
    ("paper", "disc", "dynamic", 600),
    ("corridors", "disc", "dynamic", 600),
    ("open", "husky", "dynamic", 40),
    ("paper", "husky", "kinematic", 600),
)
"""The env rollouts recorded in ``env_rollouts.csv``."""

ROLLOUT_COLUMNS = (
    "case",
    "step",
    "action",
    "x",
    "y",
    "heading",
    "reward",
    "terminated",
    "collision",
)


def record_fig4(folders: Iterable[str] = FIG4_RUNS) -> None:
    for folder in folders:
        options = FIG4_RUNS[folder]
        with tempfile.TemporaryDirectory() as tmp:
            out = Path(tmp) / "out"
            run_fig4(folder, out)
            target = HERE / folder
            shutil.rmtree(target, ignore_errors=True)
            target.mkdir()
            for csv in sorted((out / "runs").glob("*.csv")):
                shutil.copyfile(csv, target / csv.name)
            (target / "OPTIONS").write_text(
                "python run.py experiment paper_fig4 "
                + " ".join(options)
                + (" (with [env.params] contact_release = false)" if folder in FIG4_LEGACY else "")
                + "\n"
            )


def rollout_rows() -> list[tuple]:
    """The env rollouts of :data:`ROLLOUT_CASES` (what ``env_rollouts.csv`` holds)."""
    import bullet_maze  # noqa: F401

    rows = []
    for case, (layout, robot, mode, steps) in enumerate(ROLLOUT_CASES):
        env = gym.make("BulletMaze-v0", maze=layout, robot=robot, mode=mode)
        actions = np.random.default_rng(case).integers(0, 4, size=steps)
        try:
            obs, _ = env.reset(seed=100 + case)
            for step, action in enumerate(actions.tolist()):
                obs, reward, terminated, truncated, info = env.step(action)
                heading = float(obs[2]) if obs.shape[0] > 2 else 0.0
                rows.append(
                    (
                        case,
                        step,
                        action,
                        float(obs[0]),
                        float(obs[1]),
                        heading,
                        float(reward),
                        int(terminated),
                        int(info["collision"]),
                    )
                )
                if terminated or truncated:
                    obs, _ = env.reset()
        finally:
            env.close()
    return rows


def record_rollouts() -> None:
    from experiments.store import format_rows

    (HERE / "env_rollouts.csv").write_text(format_rows(rollout_rows(), ROLLOUT_COLUMNS))


def physical_limits() -> dict[str, dict[str, float | int | None]]:
    """``shortest_path`` of every shipped layout (what ``physical_limits.json`` holds)."""
    from bullet_maze import available_layouts, load_layout, shortest_path

    out = {}
    for name in available_layouts():
        limit = shortest_path(load_layout(name))
        out[name] = {
            "length": limit.length,
            "l1_length": limit.l1_length,
            "steps": limit.steps,
            "lattice_steps": limit.lattice_steps,
        }
    return out


def record_limits() -> None:
    (HERE / "physical_limits.json").write_text(
        json.dumps(physical_limits(), indent=2, sort_keys=True) + "\n"
    )


AGENT_CASES = (
    # (agent kind, exploration, seed, episodes)
    ("tree", "epsilon-greedy", 0, 60),
    ("tree", "adaptive+tabu", 1, 60),
    ("grid", "epsilon-greedy", 2, 60),
)
AGENT_COLUMNS = ("case", "episode", "steps", "return", "success", "leaves", "epochs")


def agent_rows() -> list[tuple]:
    """MountainCar-v0 learning statistics of :data:`AGENT_CASES` with the example's config."""
    from agent import GridAgent, TreeAgent, TreeConfig

    config = TreeConfig(split_max_abs_mean=5.0, split_min_variance=1.0, split_min_samples=200)
    rows = []
    for case, (kind, exploration, seed, episodes) in enumerate(AGENT_CASES):
        env = gym.make("MountainCar-v0")
        try:
            if kind == "tree":
                agent = TreeAgent(
                    env.observation_space, env.action_space, exploration, seed, config
                )
            else:
                agent = GridAgent(
                    env.observation_space,
                    env.action_space,
                    exploration,
                    seed,
                    config,
                    resolution=12,
                )
            for stats in agent.learn(env, episodes, reset_seed=seed):
                rows.append(
                    (
                        case,
                        stats.episode,
                        stats.steps,
                        stats.episode_return,
                        int(stats.success),
                        stats.leaves,
                        stats.epochs,
                    )
                )
        finally:
            env.close()
    return rows


def record_agents() -> None:
    from experiments.store import format_rows

    (HERE / "agent_rollouts.csv").write_text(format_rows(agent_rows(), AGENT_COLUMNS))


RECORDERS = {
    "env": record_rollouts,
    "limits": record_limits,
    "agents": record_agents,
    "fig4": record_fig4,
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--only",
        default=",".join(RECORDERS),
        help=f"comma-separated subset of {', '.join(RECORDERS)}",
    )
    args = parser.parse_args()
    for name in args.only.split(","):
        RECORDERS[name]()


if __name__ == "__main__":
    main()
