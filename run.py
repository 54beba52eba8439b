"""Train and compare the agents of ``agent/`` in the mazes of ``bullet_maze/``.

With no arguments, the quick default job: the paper's proposed agent (adaptive decision tree,
adaptive epsilon + decreasing tabu search) trained in the default maze for a few minutes, with a
summary and a results folder (per-episode CSV, learning curve, learned partition). Subcommands:

    python run.py train [--strategy NAME] [--seed N] ...    one agent, saved with its CSV
    python run.py experiment CONFIG [--runs N] ...          strategies x runs, with a report
    python run.py evaluate AGENT [--mode dynamic --robot husky]
    python run.py transfer [CONFIG] [--agents PATH...] ... agents x robots x modes x levels
    python run.py render AGENT                              a GIF of one greedy episode
    python run.py layouts MAZE... | --suite NAME            layouts and shortest paths (PNG)

``python run.py SUBCOMMAND --help`` explains every option; docs/experiments.md the config files.
"""

from __future__ import annotations

import argparse
import logging
import math
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from experiments import (
    BACKENDS,
    MODES,
    ConfigError,
    EnvOptions,
    Experiment,
    FolderState,
    ModuleError,
    Playback,
    RunFailed,
    TasksLost,
    TrainJob,
    Transfer,
    default_workers,
    import_env_modules,
    interval_text,
    make_backend,
)

DEFAULT_CONFIG = "quick"
RESULTS_DIR = Path("results")
MAX_WORKERS = 1024
MAX_EVALUATION_EPISODES = 1_000_000
MAX_FPS = 100
MAX_FRAMES = 10_000
MAX_SECONDS = 1e7


def main(argv: Sequence[str] | None = None) -> int:
    """Parse ``argv`` and run the chosen job; returns the exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if getattr(args, "address", None) and args.backend != "ray":
        parser.error("argument --address: only applies to --backend ray")
    logging.basicConfig(
        level=logging.DEBUG if args.verbose else logging.WARNING,
        format="%(levelname)s %(name)s: %(message)s",
    )
    command = args.command or "default"
    try:
        args.allow_env = [*(args.allow_env or ()), *sorted(import_env_modules(_modules(args)))]
        return COMMANDS[command](args)
    except (ConfigError, FileNotFoundError, ModuleError) as error:
        parser.exit(2, f"run.py {command}: error: {error}\n")
    except TasksLost as error:
        print(f"run.py {command}: {error}; finished runs are kept.", file=sys.stderr)
        return 1
    except RunFailed as error:
        logging.getLogger(__name__).debug("the failed run's traceback", exc_info=error.__cause__)
        cause = str(error).rstrip(".")
        print(
            f"run.py {command}: error: {cause}. Finished runs are kept; the same command "
            "resumes once the cause is fixed (-v shows the traceback).",
            file=sys.stderr,
        )
        return 1
    except KeyboardInterrupt:
        print("\ninterrupted: finished runs are kept; the same command resumes.", file=sys.stderr)
        return 130
    return 0


def build_parser() -> argparse.ArgumentParser:
    """The command line: the default job and the four subcommands."""
    parser = argparse.ArgumentParser(
        prog="run.py", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("-v", "--verbose", action="store_true", help="debug logging")
    _add_env_sources(parser)
    parser.set_defaults(
        command=None,
        config=DEFAULT_CONFIG,
        strategy=None,
        task=None,
        seed=None,
        episodes=None,
        time_budget=None,
        out=None,
        progress=True,
        maze=None,
        robot=None,
        mode=None,
        max_episode_steps=None,
        exploration=None,
        param=[],
        agent_param=[],
        allow_env=[],
        env_module=[],
    )
    sub = parser.add_subparsers(dest="command", metavar="SUBCOMMAND")

    train = sub.add_parser(
        "train",
        help="train one agent (one strategy, one seed, one maze) and save it",
        description="Train one agent and write its folder: episodes.csv, agent.npz, "
        "config.toml, learning_curve.png, partition.png.",
    )
    _add_config_source(train)
    train.add_argument(
        "--strategy",
        metavar="NAME",
        help="strategy of the config file to train (default: its first)",
    )
    train.add_argument(
        "--task",
        metavar="NAME",
        help="task of an experiment over tasks to train in (default: its first); an "
        "experiment's run <task>/<strategy>__<seed> is reproduced by --task, --strategy and "
        "--seed",
    )
    train.add_argument(
        "--exploration",
        metavar="NAME",
        help="replace the strategy's exploration (epsilon-greedy, adaptive, tabu, "
        "adaptive+tabu, vdbe, ...); its parameters come from --param",
    )
    train.add_argument(
        "--param",
        action="append",
        metavar="KEY=VALUE",
        help="exploration parameter, e.g. --param epsilon=0.05 (repeatable)",
    )
    train.add_argument(
        "--agent-param",
        action="append",
        metavar="KEY=VALUE",
        help="agent config field (TreeConfig), e.g. --agent-param alpha=0.2",
    )
    train.add_argument(
        "--seed",
        type=_non_negative,
        metavar="N",
        help="run seed (default: run 0 of the config's seed); an experiment's "
        "run <strategy>__<seed> is reproduced by --strategy and --seed",
    )
    train.add_argument(
        "--episodes", type=_positive, metavar="N", help="episodes to train (default: the config's)"
    )
    train.add_argument(
        "--time-budget",
        type=_seconds,
        metavar="SECONDS",
        help="stop after the episode that passes this wall time (default: the "
        "config's time_budget_s; 0: no budget)",
    )
    _add_env_options(train)
    _add_output_options(train, "results/<maze>__<strategy>__<seed>/")

    experiment = sub.add_parser(
        "experiment",
        help="run an experiment file (strategies x runs) and write its report",
        description="Run every (strategy, run) of an experiment file in parallel, store each "
        "finished run atomically (an interrupted experiment resumes where it "
        "stopped) and write report.md, figure4.png, leaves.png, summary.csv.",
    )
    experiment.add_argument(
        "config",
        metavar="CONFIG",
        help="experiment TOML: a path or a name in experiments/ (paper_fig4, quick)",
    )
    experiment.add_argument(
        "--runs", type=_positive, metavar="N", help="runs per strategy (default: the file's)"
    )
    experiment.add_argument(
        "--episodes", type=_positive, metavar="N", help="episodes per run (default: the file's)"
    )
    experiment.add_argument(
        "--max-episode-steps", type=_positive, metavar="N", help="episode cap (default: the file's)"
    )
    experiment.add_argument(
        "--seed", type=_non_negative, metavar="N", help="experiment seed (default: the file's)"
    )
    experiment.add_argument(
        "--split",
        type=_names,
        metavar="SPLIT[,SPLIT]",
        help="splits of the layout suite to run: dev, test or dev,test (default: the file's "
        "[env] split; only for an experiment over a suite)",
    )
    experiment.add_argument(
        "--workers",
        type=_at_most(MAX_WORKERS),
        metavar="N",
        help=f"parallel runs (default: all cores, here {default_workers()})",
    )
    experiment.add_argument(
        "--backend",
        choices=BACKENDS,
        default="process",
        help="process: local process pool (default); ray: Ray (local "
        "instance, or --address); serial: in this process",
    )
    experiment.add_argument(
        "--address",
        metavar="ADDRESS",
        help="Ray cluster to join (e.g. auto, ray://host:10001); without it "
        "--backend ray starts a local instance",
    )
    experiment.add_argument(
        "--only",
        type=_names,
        metavar="NAME[,NAME...]",
        help="compute only these strategies' runs (comma-separated names "
        "from the file); the report covers every finished run, and a "
        "later run without --only completes the experiment",
    )
    experiment.add_argument(
        "--report-only",
        action="store_true",
        help="compute nothing; write the report of the finished runs",
    )
    experiment.add_argument(
        "--accept-code-change",
        action="store_true",
        help="count finished runs whose only difference is the code version (another "
        "version of agent/, bullet_maze/ or the training path); they are listed in the "
        "report. Without it such runs are refused",
    )
    _add_output_options(experiment, "results/<name>[__<episodes>ep][__cap<N>]/")

    evaluate = sub.add_parser(
        "evaluate",
        help="run a saved agent's greedy policy, possibly in another mode or robot",
        description="Run a saved agent's greedy policy for N episodes and report its success "
        "rate and steps. A disc-trained agent observes (x, y); with a robot that "
        "also observes its heading (husky) the heading is dropped (the policy is a "
        "function of position).",
    )
    evaluate.add_argument(
        "agent", metavar="AGENT", help="agent.npz file, or a train folder that holds one"
    )
    evaluate.add_argument(
        "--episodes",
        type=_at_most(MAX_EVALUATION_EPISODES),
        default=20,
        metavar="N",
        help="greedy episodes (default: 20)",
    )
    evaluate.add_argument(
        "--seed",
        type=_non_negative,
        default=0,
        metavar="N",
        help="seed of the first reset (default: 0)",
    )
    _add_config_source(evaluate)
    _add_env_options(evaluate)

    render = sub.add_parser(
        "render",
        help="GIF of one greedy episode, top-down, over the learned partition",
        description="Write a GIF of one greedy episode seen from above, with the agent's "
        "partition (value colours, greedy arrows) drawn underneath.",
    )
    render.add_argument(
        "agent", metavar="AGENT", help="agent.npz file, or a train folder that holds one"
    )
    render.add_argument(
        "--out",
        type=Path,
        metavar="FILE",
        help="GIF to write (default: episode.gif beside the agent)",
    )
    render.add_argument(
        "--seed", type=_non_negative, default=0, metavar="N", help="seed of the reset (default: 0)"
    )
    render.add_argument(
        "--fps", type=_at_most(MAX_FPS), default=15, help=f"frames per second (1 to {MAX_FPS})"
    )
    render.add_argument(
        "--max-frames",
        type=_at_most(MAX_FRAMES),
        default=150,
        metavar="N",
        help="longest GIF; long episodes are subsampled (default: 150)",
    )
    _add_config_source(render)
    _add_env_options(render)
    _add_transfer_parser(sub)
    _add_layouts_parser(sub)
    return parser


def _add_transfer_parser(sub: Any) -> None:
    transfer = sub.add_parser(
        "transfer",
        help="evaluate saved agents in a grid of robots x modes x layouts x perturbation levels",
        description="Evaluate every agent (an agent.npz, a train folder, or an experiment "
        "folder whose runs saved their agents) greedily in every condition of the grid "
        "that applies to it (its own layout; every robot, mode and perturbation level; and "
        "its training condition), in parallel, each finished cell stored and verified (an "
        "interrupted transfer resumes); then write report.md, cells.csv, summary.csv, "
        "success.png and steps_ratio.png. Options replace the file's values.",
    )
    transfer.add_argument(
        "config",
        metavar="CONFIG",
        nargs="?",
        help="transfer TOML: a path or a name in experiments/ (transfer_study); optional "
        "when --agents is given",
    )
    transfer.add_argument(
        "--agents", nargs="+", metavar="PATH", help="agent files or folders (replace the file's)"
    )
    for key, what in (
        ("robots", "robot names or robot files (disc, husky, racecar, rover)"),
        ("modes", "modes (kinematic, dynamic)"),
        ("layouts", "layouts whose agents are evaluated (default: every agent's own)"),
        ("levels", "perturbation levels (none, moderate, strong)"),
    ):
        transfer.add_argument(
            f"--{key}", type=_names, metavar="NAME[,NAME...]", help=f"comma-separated {what}"
        )
    transfer.add_argument(
        "--episodes",
        type=_at_most(MAX_EVALUATION_EPISODES),
        metavar="N",
        help="greedy episodes per agent and condition (default: the file's, else 10)",
    )
    transfer.add_argument(
        "--max-episode-steps",
        type=_positive,
        metavar="N",
        help="episode cap of every cell (default: the file's, else each agent's training cap)",
    )
    transfer.add_argument(
        "--workers",
        type=_at_most(MAX_WORKERS),
        metavar="N",
        help=f"parallel cells (default: all cores, here {default_workers()})",
    )
    transfer.add_argument("--backend", choices=BACKENDS, default="process", help="as experiment")
    transfer.add_argument("--address", metavar="ADDRESS", help="Ray cluster to join")
    transfer.add_argument(
        "--report-only", action="store_true", help="compute nothing; report the finished cells"
    )
    transfer.add_argument(
        "--traces",
        type=_at_most(24),
        default=0,
        metavar="N",
        help="also draw N failing episodes (failures.png): the first of each training recipe "
        "and robot in dynamic mode at the moderate level, else the strong one, replayed "
        "(default: 0)",
    )
    transfer.add_argument(
        "--accept-code-change",
        action="store_true",
        help="count finished cells whose only difference is the code version",
    )
    _add_output_options(transfer, "results/<name>/")


ENV_SOURCE_OPTIONS = {
    "--allow-env": (
        "ID",
        "also accept this registered Gymnasium id in experiment files (repeatable); by default "
        "only this project's ids and Gymnasium's own are, and never an import path (module:Id)",
    ),
    "--env-module": (
        "MODULE",
        "import this module first, here and in every worker, and accept the Gymnasium ids it "
        "registers (repeatable): your own envs, for experiment files and --config; it must be "
        "importable (on PYTHONPATH, or installed)",
    ),
}
"""The options that admit environments beyond this project's and Gymnasium's: metavar, help."""


def _add_env_sources(parser: argparse.ArgumentParser) -> None:
    for flag, (metavar, text) in ENV_SOURCE_OPTIONS.items():
        parser.add_argument(flag, action="append", metavar=metavar, help=text)


def _add_config_source(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--config",
        default=DEFAULT_CONFIG,
        metavar="CONFIG",
        help="experiment file giving the environment and agent settings "
        f"(default: {DEFAULT_CONFIG}; for a saved agent, the config.toml "
        "beside it, or the results folder's for an experiment's saved agent, when there is one)",
    )


def _add_env_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--maze", metavar="NAME", help="maze layout name or TOML path")
    parser.add_argument("--robot", metavar="NAME", help="disc, husky or a URDF path")
    parser.add_argument("--mode", choices=MODES, help="kinematic (fast) or dynamic (physics)")
    parser.add_argument(
        "--max-episode-steps",
        type=_positive,
        metavar="N",
        help="episode cap (default: the config's, 5000)",
    )


def _add_output_options(parser: argparse.ArgumentParser, default: str) -> None:
    parser.add_argument(
        "--out", type=Path, metavar="DIR", help=f"results folder (default: {default})"
    )
    parser.add_argument(
        "--no-progress", dest="progress", action="store_false", help="no progress bar"
    )


def _names(text: str) -> list[str]:
    """A comma-separated list of names (empty items dropped)."""
    return [name.strip() for name in text.split(",") if name.strip()]


def _positive(text: str) -> int:
    value = _integer(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}")
    return value


def _at_most(high: int) -> Any:
    def integer(text: str) -> int:
        value = _positive(text)
        if value > high:
            raise argparse.ArgumentTypeError(
                f"expected an integer from 1 to {high:,}, got {text!r}"
            )
        return value

    return integer


def _non_negative(text: str) -> int:
    value = _integer(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f"expected an integer >= 0, got {text!r}")
    return value


def _seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not 0 <= value <= MAX_SECONDS:  # also rejects NaN
        raise argparse.ArgumentTypeError(
            f"expected a number of seconds from 0 to {MAX_SECONDS:g}, got {text!r}"
        )
    return value


def _integer(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer, got {text!r}") from None


def _env_options(args: argparse.Namespace) -> EnvOptions:
    return EnvOptions(args.maze, args.robot, args.mode, args.max_episode_steps)


def _allowed(args: argparse.Namespace) -> tuple[str, ...]:
    return tuple(args.allow_env or ())


def _modules(args: argparse.Namespace) -> tuple[str, ...]:
    return tuple(args.env_module or ())


def cmd_train(args: argparse.Namespace) -> int:
    """Train one agent with a progress bar, save it, print a summary."""
    from tqdm import tqdm

    job = TrainJob.from_options(
        config=args.config,
        strategy=args.strategy,
        task=args.task,
        exploration=args.exploration,
        params=args.param or (),
        agent_params=args.agent_param or (),
        env=_env_options(args),
        episodes=args.episodes,
        time_budget_s=args.time_budget,
        seed=args.seed,
        out=args.out,
        allowed_env_ids=_allowed(args),
        results_dir=RESULTS_DIR,
    )
    config, strategy, seed = job.config, job.strategy, job.seed
    budget = config.time_budget_s
    recent: list[int] = []
    with tqdm(
        total=config.episodes,
        unit="ep",
        disable=not args.progress,
        dynamic_ncols=True,
        mininterval=0.5,
        delay=0.1,
    ) as bar:

        def on_start(optimal: float) -> None:
            where = (
                f"maze {config.env.maze!r} ({config.env.robot}, {config.env.mode})"
                if config.env.is_maze
                else f"{config.env.id}"
            )
            bar.write(
                f"training {strategy.name} in {where}, seed {seed}: up to "
                f"{config.episodes} episodes"
                + (f" or {budget:g} s" if budget else "")
                + _optimum_text(optimal, "; optimal {} steps"),
                file=sys.stdout,
            )

        def on_episode(row: tuple) -> None:
            recent.append(row[1])
            bar.update(1)
            bar.set_postfix(avg_steps=f"{np.mean(recent[-100:]):.0f}", leaves=row[5], refresh=False)

        result = job.run(on_start, on_episode)
    _print_training_summary(result, config.env.is_maze)
    return 0


def _optimum_text(optimal: float, form: str) -> str:
    """``form`` with the optimum's steps, or nothing where there is none (a task other than a
    maze has no known optimum: its ``optimal_steps`` is nan)."""
    return form.format(f"{optimal:g}") if math.isfinite(optimal) and optimal > 0 else ""


def _print_training_summary(result: Any, is_maze: bool) -> None:
    """A maze run's success rate and steps against the optimum; any other task's returns and
    how its episodes ended (its ``terminated`` need not be a success: CartPole's is a fall)."""
    rows, training, optimal = result.training.rows, result.training, result.optimal_steps
    steps = np.array([r[1] for r in rows])
    returns = np.array([r[2] for r in rows])
    success = np.array([r[3] for r in rows], dtype=bool)
    truncated = np.array([r[4] for r in rows], dtype=bool)
    last, count = slice(-100, None), min(100, len(rows))
    stop = "stopped by the time budget" if training.stopped_by_budget else "all episodes done"
    print(
        f"\n{len(rows)} episodes in {training.wall_time_s:.1f} s ({stop}), "
        f"{training.steps_per_second:,.0f} steps/s (env + agent)"
    )
    greedy = result.greedy
    if is_maze:
        print(
            f"success rate: {success.mean():.1%} overall, {success[last].mean():.1%} in the "
            f"last {count} episodes"
        )
        ratio = f" ({steps[last].mean() / optimal:.2f}x)" if optimal > 0 else ""
        print(
            f"average steps, last {count} episodes: {steps[last].mean():.1f}{ratio}"
            + _optimum_text(optimal, " vs optimal {}")
        )
        outcome = "reached the goal" if greedy.success else "did not reach the goal"
        print(f"greedy policy: {outcome} in {greedy.steps} steps")
    else:
        print(
            f"return per episode: mean {returns.mean():g} overall, {returns[last].mean():g} in "
            f"the last {count} episodes; steps per episode, last {count}: "
            f"{steps[last].mean():.1f}; cut by the time limit: {truncated[last].mean():.0%} "
            f"of the last {count}"
        )
        ending = "cut by the time limit" if greedy.truncated else "ended by the task"
        print(f"greedy policy: return {greedy.episode_return:g} in {greedy.steps} steps ({ending})")
    print(f"leaves: {result.leaves}")
    written = ", ".join(sorted(p.name for p in result.out.iterdir() if p.is_file()))
    print(f"results: {result.out}/ ({written})")


def cmd_default(args: argparse.Namespace) -> int:
    """The README's main job: ``train`` with the quick config's first strategy."""
    return cmd_train(args)


def cmd_experiment(args: argparse.Namespace) -> int:
    """Run (or resume) an experiment file in parallel, then write its report."""
    from tqdm import tqdm

    experiment = Experiment.from_file(
        args.config,
        runs=args.runs,
        episodes=args.episodes,
        max_episode_steps=args.max_episode_steps,
        seed=args.seed,
        out=args.out,
        only=args.only,
        accept_code_change=args.accept_code_change,
        allowed_env_ids=_allowed(args),
        results_dir=RESULTS_DIR,
        splits=args.split,
    )
    config, out = experiment.config, experiment.out
    if not args.report_only:
        optimal = experiment.check()
        workers = args.workers or default_workers()
        backend = make_backend(args.backend, workers, args.address, env_modules=_modules(args))
        bars: list[Any] = []

        def on_start(state: FolderState) -> None:
            chosen = len(experiment.only) if experiment.only is not None else len(config.strategies)
            total, done = len(state.planned), len(state.finished)
            if config.tasks:
                suite = (
                    f" (suite {config.suite}, {'+'.join(config.splits)})" if config.suite else ""
                )
                what = f"{len(config.tasks)} tasks{suite} x "
                where = "caps " + ", ".join(
                    sorted({str(t.env.max_episode_steps) for t in config.tasks})
                )
            else:
                what = ""
                where = f"cap {config.env.max_episode_steps}" + _optimum_text(
                    optimal[None], ", optimal {} steps"
                )
            print(
                f"{config.name}: {chosen} strategies x {what}{config.runs} runs x "
                f"{config.episodes} episodes ({where}); {done} of {total} runs already done; "
                f"backend {args.backend}, {backend.workers} workers; results in {out}/"
            )
            _print_checks("recomputed, their files do not verify", state.invalid)
            _print_checks("accepted from another code version", state.code_changed)
            bars.append(
                tqdm(
                    total=total,
                    initial=done,
                    unit="run",
                    disable=not args.progress,
                    dynamic_ncols=True,
                )
            )

        def on_result(result: Any) -> None:
            bars[0].update(1)
            bars[0].set_postfix(last=result.name, steps_per_s=f"{result.steps_per_second:,.0f}")

        start = time.perf_counter()
        try:
            computed = experiment.run(backend, on_start=on_start, on_result=on_result)
        finally:
            for bar in bars:
                bar.close()
        elapsed = time.perf_counter() - start
        if computed:
            rate = sum(r.env_steps for r in computed) / sum(r.wall_time_s for r in computed)
            print(
                f"computed {len(computed)} runs in {elapsed:.1f} s; {rate:,.0f} steps/s per "
                f"worker (env + agent)"
            )
    report = experiment.report()
    _print_experiment_summary(report)
    if report.not_run:
        print(
            f"{len(report.not_run)} planned run(s) not run yet: the report covers the finished "
            "ones; episodes.csv and evaluation.csv are written once every planned run is finished"
        )
    return 0


def _print_checks(what: str, items: Sequence[tuple[Any, Any]]) -> None:
    if items:
        print(f"{len(items)} run(s) {what}:")
        for spec, check in items[:20]:
            print(f"  {spec.name}: {check.reason}")
        if len(items) > 20:
            print(f"  ... and {len(items) - 20} more")


def _print_experiment_summary(report: Any) -> None:
    if hasattr(report, "aggregates"):
        _print_task_summary(report)
        return
    width = max([len("strategy"), *(len(s.strategy) for s in report.summaries)])
    print(
        f"\n{'strategy':<{width}} {'runs':>4} {'final steps':>11} {'/optimal':>8} "
        f"{'success':>7} {'converged':>9} {'P(impr.)':>8}"
    )
    for s in report.summaries:
        final = float(np.mean(s.final_steps))
        ratio = final / report.optimal_steps if report.optimal_steps > 0 else math.nan
        print(
            f"{s.strategy:<{width}} {s.runs:>4} {final:>11.1f} {ratio:>8.2f} "
            f"{np.mean(s.success_rate):>7.1%} {s.converged_runs:>5}/{s.runs:<3} "
            f"{s.p_improvement:>8.2f}"
        )
    print(
        f"\nreport: {report.markdown} (figures: "
        f"{', '.join(p.name for p in report.figures)}; table: {report.summary_csv.name})"
    )
    if report.excluded:
        print(f"{len(report.excluded)} run(s) left out of the report (listed in it):")
        for check in report.excluded[:20]:
            print(f"  {check.name}: {check.status}: {check.reason}")


def _print_task_summary(report: Any) -> None:
    if report.aggregates:
        print(f"\n{len(report.tasks)} tasks with finished runs; aggregate over tasks and runs:")
    else:
        print(
            f"\n{len(report.tasks)} tasks with finished runs; no aggregate over them (no task "
            "has a normalised score; the report says why): see its per-task tables"
        )
    width = max([len("strategy"), *(len(row.strategy) for row in report.aggregates)])
    group = None
    for row in report.aggregates:
        if row.group != group:
            group = row.group
            print(
                f"\n{group}\n{'strategy':<{width}} {'score':<22} {'runs':>5} "
                f"{'IQM [95% CI]':>24} {'P(impr.)':>8}"
            )
        estimate = row.iqm
        interval = f"{estimate.value:.3f} {interval_text(estimate.low, estimate.high, '.3f')}"
        improvement = "-" if row.p_improvement is None else f"{row.p_improvement.value:.2f}"
        print(
            f"{row.strategy:<{width}} {row.score.label:<22} {row.runs:>5} {interval:>24} "
            f"{improvement:>8}"
        )
    print(
        f"\nreport: {report.markdown} (figures: "
        f"{', '.join(p.name for p in report.figures)}; tables: {report.summary_csv.name}, "
        f"{report.aggregate_csv.name})"
    )
    if report.excluded:
        print(f"{len(report.excluded)} run(s) left out of the report (listed in it):")
        for check in report.excluded[:20]:
            print(f"  {check.name}: {check.status}: {check.reason}")


def _playback(args: argparse.Namespace) -> Playback:
    return Playback.from_options(
        args.agent,
        config=None if args.config == DEFAULT_CONFIG else args.config,
        env=_env_options(args),
        allowed_env_ids=_allowed(args),
    )


def cmd_evaluate(args: argparse.Namespace) -> int:
    """Greedy episodes of a saved agent; success rate and steps."""
    playback = _playback(args)
    measured = playback.evaluate(args.episodes, seed=args.seed)
    result, env, optimal = measured.evaluation, playback.env_spec, measured.optimal_steps
    steps = result.steps
    where = f"maze {env.maze!r}, robot {env.robot!r}, mode {env.mode!r}" if env.is_maze else env.id
    projected = measured.projected
    print(
        f"{playback.path}: {args.episodes} greedy episodes in {where} "
        f"(cap {env.max_episode_steps})"
        + ("; the robot's heading dropped from the observation" if projected else "")
    )
    if env.is_maze:
        print(f"success rate: {result.success_rate:.1%}")
        reached = result.successful_steps
        if reached.size:
            print(
                f"steps to goal (successful episodes): mean {reached.mean():.1f}, median "
                f"{np.median(reached):.0f}, min {reached.min()}, max {reached.max()}"
                + _optimum_text(optimal, "; optimal {}")
            )
    else:  # a task's terminated need not be a success (CartPole's is a fall): its returns
        returns = np.array([e.episode_return for e in result.episodes])
        cut = sum(e.truncated for e in result.episodes)
        print(
            f"return per episode: mean {returns.mean():g}, min {returns.min():g}, max "
            f"{returns.max():g}; cut by the time limit in {cut} of {len(returns)} episodes"
        )
    print(f"steps, capped episodes counted at the cap: mean {steps.mean():.1f}")
    if result.tipped:
        print(
            f"the robot tipped over (info['tipped']) in {result.tipped} of "
            f"{len(result.episodes)} episodes and lay there until the cap"
        )
    rate = f"{steps.sum() / max(measured.wall_time_s, 1e-9):,.0f} steps/s"
    if env.is_maze:  # (another task reports no collisions: its count would always read 0)
        collisions = np.mean([e.collisions for e in result.episodes])
        rate = f"collisions per episode: {collisions:.1f}; {rate}"
    print(rate)
    return 0


def cmd_transfer(args: argparse.Namespace) -> int:
    """Agents x conditions, evaluated, stored and reported."""
    from tqdm import tqdm

    if args.config is None and not args.agents:
        raise ConfigError("give a transfer file (CONFIG) or the agents (--agents)")
    job = Transfer.from_options(
        args.config,
        agents=args.agents,
        robots=args.robots,
        modes=args.modes,
        layouts=args.layouts,
        levels=args.levels,
        episodes=args.episodes,
        max_episode_steps=args.max_episode_steps,
        out=args.out,
        allowed_env_ids=_allowed(args),
        accept_code_change=args.accept_code_change,
        results_dir=RESULTS_DIR,
    )
    if not args.report_only:
        workers = args.workers or default_workers()
        backend = make_backend(args.backend, workers, args.address, env_modules=_modules(args))
        bars: list[Any] = []

        def on_start(state: Any) -> None:
            done = len(state.finished)
            print(
                f"{job.spec.name}: {len(job.agents)} agents, {len(state.cells)} cells "
                f"({len(state.skipped)} conditions do not apply), {job.spec.episodes} episodes "
                f"each; {done} already done; backend {args.backend}, {backend.workers} "
                f"workers; results in {job.out}/"
            )
            bars.append(
                tqdm(
                    total=len(state.cells),
                    initial=done,
                    unit="cell",
                    disable=not args.progress,
                    dynamic_ncols=True,
                )
            )

        def on_result(result: Any) -> None:
            bars[0].update(1)

        start = time.perf_counter()
        try:
            computed = job.run(backend, on_start=on_start, on_result=on_result)
        finally:
            for bar in bars:
                bar.close()
        if computed:
            steps = sum(r.env_steps for r in computed)
            busy = sum(r.wall_time_s for r in computed)
            print(
                f"computed {len(computed)} cells in {time.perf_counter() - start:.1f} s; "
                f"{steps / max(busy, 1e-9):,.0f} steps/s per worker"
            )
    report = job.report(traces=args.traces)
    print(
        f"report: {report.path} ({len(report.summary)} rows; figures: "
        f"{', '.join(f.name for f in report.figures)})"
    )
    return 0


def cmd_render(args: argparse.Namespace) -> int:
    """A GIF of one greedy episode over the partition."""
    playback = _playback(args)
    out, episode = playback.render(args.out, args.seed, args.fps, args.max_frames)
    outcome = "reached the goal" if episode.success else "did not reach the goal"
    if episode.tipped:
        outcome += ", the robot having tipped over"
    env = playback.env_spec
    print(f"{out}: {episode.steps} steps, {outcome} ({env.robot}, {env.mode})")
    return 0


def _add_layouts_parser(sub: Any) -> None:
    layouts = sub.add_parser(
        "layouts",
        help="draw layouts (or a suite) with start, goal and shortest path as a PNG",
        description="Write a contact sheet of maze layouts: each with its start square, goal "
        "circle, shortest collision-free path and least number of steps.",
    )
    layouts.add_argument(
        "mazes", nargs="*", metavar="MAZE", help="layout names, files or generator specs"
    )
    layouts.add_argument(
        "--suite", metavar="NAME", help="draw a layout suite (a name in assets/suites/ or a file)"
    )
    layouts.add_argument("--split", choices=("dev", "test"), help="only this split of the suite")
    layouts.add_argument(
        "--out", type=Path, default=Path("layouts.png"), metavar="FILE", help="PNG to write"
    )


def cmd_layouts(args: argparse.Namespace) -> int:
    """A contact sheet of layouts (``experiments.draw_layout_sheet`` / ``draw_suite_sheet``)."""
    from experiments import draw_layout_sheet, draw_suite_sheet

    if bool(args.mazes) == bool(args.suite) or (args.split and not args.suite):
        raise ConfigError("layouts: give MAZE names or --suite NAME (--split goes with --suite)")
    try:
        if args.suite:
            path = draw_suite_sheet(args.suite, args.out, args.split)
        else:
            path = draw_layout_sheet(args.mazes, args.out)
    except (TypeError, ValueError) as error:
        raise ConfigError(str(error)) from None
    print(f"wrote {path}")
    return 0


COMMANDS = {
    "default": cmd_default,
    "train": cmd_train,
    "experiment": cmd_experiment,
    "evaluate": cmd_evaluate,
    "render": cmd_render,
    "transfer": cmd_transfer,
    "layouts": cmd_layouts,
}


if __name__ == "__main__":
    sys.exit(main())
