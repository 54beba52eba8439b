"""Agents compared on several tasks at once: classic control and maze layouts (issue 9).

The harness's experiment files describe one maze each; this script runs a list of agents on a
list of tasks (Gymnasium ids with their standard time limits, or maze layouts) and seeds::

    python experiments/task_suite.py classic                      # the classic-control suite
    python experiments/task_suite.py classic --agents general,tile --seeds 100-109
    python experiments/task_suite.py maze --tasks experiments/layouts/rooms4_door30.toml

Each finished run is ``<out>/runs/<task>__<agent>__<seed>.csv`` (the harness's columns,
:data:`experiments.store.COLUMNS`) with a ``.json`` sidecar (the greedy evaluation, timing,
the agent's size); a run whose CSV exists is not run again, so the same command resumes.
``<out>/summary.md`` is rebuilt from every finished run. A seed gives the same CSV bit for bit.

Scores: on a classic task, the mean return of ``--eval-episodes`` greedy episodes after
training (the issue's "greedy return"), each episode reset with seed ``10^6 + 1000 seed + i``;
on a maze, the mean steps of the last 100 training episodes (over the layout's optimum), the
mean steps per episode over the run (area under the curve) and the convergence episode
(:func:`experiments.statistics.convergence_episode`). Seeds 0-9 are development seeds
(choices were made on them); report on others (the default is 100-109).
"""

from __future__ import annotations

import argparse
import json
import math
import multiprocessing
import sys
import time
from collections.abc import Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

if __package__ in (None, ""):  # run as a script: make the project importable
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from experiments import store
from experiments.statistics import convergence_episode


@dataclass(frozen=True)
class Task:
    """One environment of the suite."""

    name: str
    """Short label used in file names."""
    env_id: str
    kwargs: tuple[tuple[str, Any], ...] = ()
    """Keyword arguments of ``gymnasium.make``."""
    kind: str = "classic"
    """"classic" (scored by greedy return) or "maze" (scored by steps)."""
    target: float = math.nan
    """Classic: the greedy return to reach; maze: the largest final steps / optimum."""
    r_max: float = 1.0
    """Largest reward (what the adaptive Q-learning baseline needs to know)."""
    reward_range: float = 1.0
    """Largest minus smallest reward (the same)."""


CLASSIC_TASKS = {
    "mc": Task("mc", "MountainCar-v0", target=-110.0, r_max=0.0, reward_range=1.0),
    "acro": Task("acro", "Acrobot-v1", target=-100.0, r_max=0.0, reward_range=1.0),
    "cp": Task("cp", "CartPole-v1", target=475.0, r_max=1.0, reward_range=1.0),
}
"""Issue 9's classic tasks and targets (each with Gymnasium's own time limit)."""


def maze_task(layout: str, cap: int = 5000) -> Task:
    """A maze layout (a shipped name or a TOML path) with the 5,000-step cap."""
    name = Path(layout).stem
    return Task(
        name,
        "BulletMaze-v0",
        (("maze", layout), ("max_episode_steps", cap)),
        kind="maze",
        target=1.2,
        r_max=5.0,
        reward_range=6.0,
    )


def make_env(task: Task) -> Any:
    """The task's environment."""
    import gymnasium as gym

    if task.kind == "maze":
        import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
    return gym.make(task.env_id, **dict(task.kwargs))


def make_agent(name: str, task: Task, env: Any, seed: int) -> Any:
    """An agent by name: a preset (``general``, ``paper``, ``paper-literal``), a preset's config
    with another strategy (``general+boltzmann``; ``optimistic`` starts at the task's
    ``r_max / (1 - gamma)``), ``tile``, ``adaptive-q`` or ``grid<N>``."""
    from agent import PRESETS, AdaptiveQAgent, GridAgent, TileCodingAgent, make_exploration

    space, actions = env.observation_space, env.action_space
    if name in PRESETS:
        return PRESETS[name].agent(space, actions, seed)
    base, _, strategy = name.partition("+")
    if base in PRESETS and strategy:
        from agent import TreeAgent

        params = {"r_max": task.r_max} if strategy.split("+")[0] == "optimistic" else {}
        exploration = make_exploration(strategy, **params)
        return TreeAgent(space, actions, exploration, seed, PRESETS[base].config)
    if name == "tile":
        return TileCodingAgent(space, actions, seed)
    if name == "adaptive-q":
        return AdaptiveQAgent(
            space, actions, seed, r_max=task.r_max, reward_range=task.reward_range
        )
    if name.startswith("grid") and name[4:].isdigit():
        return GridAgent(
            space, actions, make_exploration("epsilon-greedy"), seed, resolution=int(name[4:])
        )
    raise ValueError(
        f"unknown agent {name!r}: a preset ({', '.join(sorted(PRESETS))}), "
        "<preset>+<strategy>, tile, adaptive-q or grid<N>"
    )


def greedy_returns(agent: Any, env: Any, episodes: int, seed: int) -> list[float]:
    """Returns of ``episodes`` greedy episodes, reset with seeds ``10^6 + 1000 seed + i``."""
    out = []
    for i in range(episodes):
        obs, _ = env.reset(seed=1_000_000 + 1000 * seed + i)
        total, done = 0.0, False
        while not done:
            obs, reward, terminated, truncated, _ = env.step(agent.predict(obs))
            total += float(reward)
            done = terminated or truncated
        out.append(total)
    return out


def run_one(job: tuple[Task, str, int, int, int, str]) -> str:
    """Train one agent on one task and write its CSV and sidecar; returns the run's name."""
    task, agent_name, seed, episodes, eval_episodes, out = job
    runs = Path(out) / "runs"
    name = f"{task.name}__{agent_name}__{seed}"
    if (runs / f"{name}.csv").exists():
        return name
    env = make_env(task)
    try:
        agent = make_agent(agent_name, task, env, seed)
        start = time.perf_counter()
        history = agent.learn(env, episodes, reset_seed=seed)
        wall = time.perf_counter() - start
        rows = [
            (
                i + 1,
                s.steps,
                s.episode_return,
                s.success,
                s.truncated,
                s.leaves,
                s.collisions,
            )
            for i, s in enumerate(history)
        ]
        meta: dict[str, Any] = {
            "task": task.name,
            "env_id": task.env_id,
            "agent": agent_name,
            "seed": seed,
            "episodes": episodes,
            "wall_time_s": wall,
            "leaves": agent.n_leaves,
            "optimal_steps": float(getattr(env.unwrapped, "optimal_steps", math.nan) or math.nan),
        }
        if task.kind == "classic":
            meta["greedy_returns"] = greedy_returns(agent, env, eval_episodes, seed)
    finally:
        env.close()
    runs.mkdir(parents=True, exist_ok=True)
    store.atomic_write_text(runs / f"{name}.json", json.dumps(meta, indent=1) + "\n")
    store.atomic_write_text(runs / f"{name}.csv", store.format_rows(rows))
    return name


def summary(out: Path, tasks: Sequence[Task], agents: Sequence[str]) -> str:
    """The Markdown table of every finished run under ``out``."""
    lines = ["# Task suite", ""]
    for task in tasks:
        if task.kind == "classic":
            lines += [
                f"## {task.env_id} (target: greedy return >= {task.target:g})",
                "",
                "| agent | runs | greedy return, mean | per seed | seeds >= target | "
                "training return, mean over the run | leaves |",
                "|---|---:|---:|---|---:|---:|---:|",
            ]
        else:
            lines += [
                f"## maze {task.name} (target: final <= {task.target:g} x the optimum)",
                "",
                "| agent | runs | final steps (last 100), mean | / optimum | worst / optimum | "
                "mean steps over the run | converged (10% rule) | success | leaves |",
                "|---|---:|---:|---:|---:|---:|---|---:|---:|",
            ]
        for agent_name in agents:
            found = sorted((out / "runs").glob(f"{task.name}__{agent_name}__*.json"))
            if not found:
                continue
            metas = [json.loads(p.read_text()) for p in found]
            data = [store.read_run(out / "runs", p.stem) for p in found]
            leaves = np.mean([m["leaves"] for m in metas])
            if task.kind == "classic":
                scores = [float(np.mean(m["greedy_returns"])) for m in metas]
                met = sum(s >= task.target for s in scores)
                train = np.mean([d.columns["return"].mean() for d in data])
                per_seed = ", ".join(f"{s:.0f}" for s in scores)
                lines.append(
                    f"| {agent_name} | {len(metas)} | {np.mean(scores):.1f} | {per_seed} | "
                    f"{met}/{len(metas)} | {train:.1f} | {leaves:.0f} |"
                )
            else:
                optimum = metas[0]["optimal_steps"]
                final = [float(d.steps[-100:].mean()) for d in data]
                auc = [float(d.steps.mean()) for d in data]
                conv = [
                    convergence_episode(
                        d.steps,
                        50,
                        0.1,
                        100,
                        final_success=float(d.columns["success"][-100:].mean()),
                    )
                    for d in data
                ]
                success = np.mean([d.columns["success"].mean() for d in data])
                conv_text = ", ".join("-" if c is None else str(c) for c in conv)
                lines.append(
                    f"| {agent_name} | {len(metas)} | {np.mean(final):.1f} | "
                    f"{np.mean(final) / optimum:.2f} | {max(final) / optimum:.2f} | "
                    f"{np.mean(auc):.0f} | {conv_text} | {success:.3f} | {leaves:.0f} |"
                )
        lines.append("")
    return "\n".join(lines)


def parse_seeds(text: str) -> list[int]:
    """``"100-109"`` or ``"0,1,5"`` as a list of seeds (ValueError naming the text)."""
    seeds: list[int] = []
    for part in text.split(","):
        low, dash, high = part.strip().partition("-")
        if not low.isdigit() or (dash and not high.isdigit()):
            raise ValueError(f"--seeds: expected N, N-M or a list of them, got {text!r}")
        seeds += list(range(int(low), int(high) + 1)) if dash else [int(low)]
    return seeds


def main(argv: Sequence[str] | None = None) -> int:
    """The command line; returns the exit code."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("suite", choices=("classic", "maze"))
    parser.add_argument("--tasks", help="classic: mc,acro,cp (default all); maze: layouts")
    parser.add_argument("--agents", default="general,paper,tile,adaptive-q")
    parser.add_argument("--seeds", default="100-109", help="N-M or a list (default 100-109)")
    parser.add_argument("--episodes", type=int, default=None, help="classic 1000, maze 1000")
    parser.add_argument("--eval-episodes", type=int, default=20)
    parser.add_argument("--workers", type=int, default=1)
    parser.add_argument("--out", type=Path, default=None)
    args = parser.parse_args(argv)
    try:
        seeds = parse_seeds(args.seeds)
    except ValueError as error:
        parser.error(str(error))
    if args.suite == "classic":
        names = (args.tasks or "mc,acro,cp").split(",")
        unknown = [n for n in names if n not in CLASSIC_TASKS]
        if unknown:
            parser.error(f"--tasks: unknown {unknown}; choose from {sorted(CLASSIC_TASKS)}")
        tasks = [CLASSIC_TASKS[n] for n in names]
    else:
        if not args.tasks:
            parser.error("--tasks: the maze suite needs layouts (names or TOML paths)")
        tasks = [maze_task(layout) for layout in args.tasks.split(",")]
    episodes = args.episodes if args.episodes is not None else 1000
    if episodes < 1 or args.eval_episodes < 1 or args.workers < 1:
        parser.error("--episodes, --eval-episodes and --workers must be >= 1")
    agents = args.agents.split(",")
    for task in tasks:  # bad names fail here, by name, before any run starts
        env = make_env(task)
        try:
            for name in agents:
                make_agent(name, task, env, 0)
        except (TypeError, ValueError) as error:
            parser.error(f"--agents: {error}")
        finally:
            env.close()
    out = args.out or Path("results") / f"task_suite_{args.suite}"
    jobs = [
        (task, name, seed, episodes, args.eval_episodes, str(out))
        for task in tasks
        for name in agents
        for seed in seeds
    ]
    if args.workers == 1:
        for job in jobs:
            print(run_one(job), flush=True)
    else:
        context = multiprocessing.get_context("spawn")
        with ProcessPoolExecutor(args.workers, mp_context=context) as pool:
            for name in pool.map(run_one, jobs):
                print(name, flush=True)
    text = summary(out, tasks, agents)
    store.atomic_write_text(out / "summary.md", text + "\n")
    print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
