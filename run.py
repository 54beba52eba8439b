"""Train and compare the agents of ``agent/`` in the mazes of ``bullet_maze/``.

With no arguments, the quick default job: the paper's proposed agent (adaptive decision tree,
adaptive epsilon + decreasing tabu search) trained in the default maze for a few minutes, with a
summary and a results folder (per-episode CSV, learning curve, learned partition). Subcommands:

    python run.py train [--strategy NAME] [--seed N] ...    one agent, saved with its CSV
    python run.py experiment CONFIG [--runs N] ...          strategies x runs, with a report
    python run.py evaluate AGENT [--mode dynamic --robot husky]
    python run.py render AGENT                              a GIF of one greedy episode
    python run.py layouts MAZE... | --suite NAME            layouts and shortest paths (PNG)

``python run.py SUBCOMMAND --help`` explains every option; docs/experiments.md the config files.
"""

from __future__ import annotations

import argparse
import dataclasses
import logging
import math
import sys
import time
import tomllib
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from experiments import config as config_module
from experiments.backends import BACKENDS, default_workers, make_backend
from experiments.config import ConfigError, ExperimentConfig, StrategySpec
from experiments.seeding import run_seed

DEFAULT_CONFIG = "quick"
RESULTS_DIR = Path("results")


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
        return COMMANDS[command](args)
    except (ConfigError, FileNotFoundError) as error:
        parser.exit(2, f"run.py {command}: error: {error}\n")
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
    parser.set_defaults(
        command=None,
        config=DEFAULT_CONFIG,
        strategy=None,
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
        "--workers",
        type=_positive,
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
        "--episodes", type=_positive, default=20, metavar="N", help="greedy episodes (default: 20)"
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
    render.add_argument("--fps", type=_positive, default=15, help="frames per second")
    render.add_argument(
        "--max-frames",
        type=_positive,
        default=150,
        metavar="N",
        help="longest GIF; long episodes are subsampled (default: 150)",
    )
    _add_config_source(render)
    _add_env_options(render)
    _add_layouts_parser(sub)
    return parser


def _add_config_source(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--config",
        default=DEFAULT_CONFIG,
        metavar="CONFIG",
        help="experiment file giving the environment and agent settings "
        f"(default: {DEFAULT_CONFIG}; for a saved agent, the config.toml "
        "beside it when there is one)",
    )


def _add_env_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--maze", metavar="NAME", help="maze layout name or TOML path")
    parser.add_argument("--robot", metavar="NAME", help="disc, husky or a URDF path")
    parser.add_argument(
        "--mode", choices=config_module.MODES, help="kinematic (fast) or dynamic (physics)"
    )
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
    if not value >= 0:  # also rejects NaN
        raise argparse.ArgumentTypeError(f"expected a number of seconds >= 0, got {text!r}")
    return value


def _integer(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer, got {text!r}") from None


def _key_values(items: Sequence[str], option: str) -> dict[str, Any]:
    """``KEY=VALUE`` options with TOML values (``0.05``, ``true``, ``"text"``, bare text)."""
    values = {}
    for item in items:
        key, sep, raw = item.partition("=")
        if not sep or not key.strip():
            raise ConfigError(f"option {option}: expected KEY=VALUE, got {item!r}")
        try:
            values[key.strip()] = tomllib.loads(f"v = {raw}")["v"]
        except tomllib.TOMLDecodeError:
            values[key.strip()] = raw
    return values


def _train_setup(args: argparse.Namespace) -> tuple[ExperimentConfig, StrategySpec, int]:
    """The one-strategy experiment that ``train`` and the default job run."""
    config = config_module.load_config(args.config)
    strategy = config.strategy(args.strategy) if args.strategy else config.strategies[0]
    if args.exploration or args.param:
        strategy = dataclasses.replace(
            strategy,
            exploration=args.exploration or strategy.exploration,
            exploration_params=(
                _key_values(args.param, "--param")
                if args.exploration
                else {**strategy.exploration_params, **_key_values(args.param, "--param")}
            ),
        )
        if args.exploration and not args.strategy:
            strategy = dataclasses.replace(strategy, name=args.exploration)
    if args.agent_param:
        strategy = dataclasses.replace(
            strategy, config={**strategy.config, **_key_values(args.agent_param, "--agent-param")}
        )
    env_changes = {
        k: v
        for k, v in (("maze", args.maze), ("robot", args.robot), ("mode", args.mode))
        if v is not None
    }
    env = dataclasses.replace(config.env, **env_changes)
    budget = config.time_budget_s if args.time_budget is None else (args.time_budget or None)
    config = dataclasses.replace(
        config, strategies=(strategy,), baseline=None, runs=1, env=env, time_budget_s=budget
    )
    config = config_module.with_overrides(
        config, episodes=args.episodes, max_episode_steps=args.max_episode_steps
    )
    seed = run_seed(config.seed, 0) if args.seed is None else args.seed
    return config, strategy, seed


def cmd_train(args: argparse.Namespace) -> int:
    """Train one agent with a progress bar, save it, print a summary."""
    from tqdm import tqdm

    from experiments.single_run import train_and_save

    config, strategy, seed = _train_setup(args)
    out = args.out or RESULTS_DIR / f"{Path(config.env.maze).stem}__{strategy.name}__{seed}"
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
            bar.write(
                f"training {strategy.name} in maze {config.env.maze!r} "
                f"({config.env.robot}, {config.env.mode}), seed {seed}: up to "
                f"{config.episodes} episodes"
                + (f" or {budget:g} s" if budget else "")
                + f"; optimal {optimal:g} steps",
                file=sys.stdout,
            )

        def on_episode(row: tuple) -> None:
            recent.append(row[1])
            bar.update(1)
            bar.set_postfix(avg_steps=f"{np.mean(recent[-100:]):.0f}", leaves=row[5], refresh=False)

        result = train_and_save(config, seed, out, on_start, on_episode)
    _print_training_summary(result)
    return 0


def _print_training_summary(result: Any) -> None:
    rows, training, optimal = result.training.rows, result.training, result.optimal_steps
    steps = np.array([r[1] for r in rows])
    success = np.array([r[3] for r in rows], dtype=bool)
    last, count = slice(-100, None), min(100, len(rows))
    stop = "stopped by the time budget" if training.stopped_by_budget else "all episodes done"
    print(
        f"\n{len(rows)} episodes in {training.wall_time_s:.1f} s ({stop}), "
        f"{training.steps_per_second:,.0f} steps/s (env + agent)"
    )
    print(
        f"success rate: {success.mean():.1%} overall, {success[last].mean():.1%} in the "
        f"last {count} episodes"
    )
    ratio = f" ({steps[last].mean() / optimal:.2f}x)" if optimal > 0 else ""
    print(
        f"average steps, last {count} episodes: {steps[last].mean():.1f}{ratio} vs optimal "
        f"{optimal:g}"
    )
    outcome = "reached the goal" if result.greedy.success else "did not reach the goal"
    print(f"greedy policy: {outcome} in {result.greedy.steps} steps")
    print(f"leaves: {result.leaves}")
    print(f"results: {result.out}/ (episodes.csv, learning_curve.png, partition.png, agent.npz)")


def cmd_default(args: argparse.Namespace) -> int:
    """The README's main job: ``train`` with the quick config's first strategy."""
    return cmd_train(args)


def cmd_experiment(args: argparse.Namespace) -> int:
    """Run (or resume) an experiment file in parallel, then write its report."""
    config = config_module.load_config(args.config)
    from tqdm import tqdm

    from experiments import factory, runner
    from experiments.report import write_report

    file_config = config
    config = config_module.with_overrides(
        config,
        runs=args.runs,
        episodes=args.episodes,
        seed=args.seed,
        max_episode_steps=args.max_episode_steps,
    )
    out = args.out or RESULTS_DIR / _experiment_folder(file_config, config)
    if not args.report_only:
        factory.check_agent_params(config)
        optimal = factory.check_env(config)
        runner.prepare_folder(config, out)
        only = runner.select_strategies(config, args.only)
        todo = runner.pending_runs(config, out, only)
        total = len(runner.plan(config, only))
        workers = args.workers or default_workers()
        backend = make_backend(args.backend, workers, args.address)
        chosen = len(only) if only is not None else len(config.strategies)
        print(
            f"{config.name}: {chosen} strategies x {config.runs} runs x "
            f"{config.episodes} episodes (cap {config.env.max_episode_steps}, optimal "
            f"{optimal:g} steps); {total - len(todo)} of {total} runs already done; "
            f"backend {args.backend}, {backend.workers} workers; results in {out}/"
        )
        start = time.perf_counter()
        with tqdm(
            total=total,
            initial=total - len(todo),
            unit="run",
            disable=not args.progress,
            dynamic_ncols=True,
        ) as bar:

            def on_result(result: Any) -> None:
                bar.update(1)
                bar.set_postfix(last=result.name, steps_per_s=f"{result.steps_per_second:,.0f}")

            computed = runner.run_experiment(config, out, backend, on_result=on_result, only=only)
        elapsed = time.perf_counter() - start
        if computed:
            rate = sum(r.env_steps for r in computed) / sum(r.wall_time_s for r in computed)
            print(
                f"computed {len(computed)} runs in {elapsed:.1f} s; {rate:,.0f} steps/s per "
                f"worker (env + agent)"
            )
    try:
        report = write_report(config, out)
    except ValueError as error:
        raise ConfigError(str(error)) from None
    _print_experiment_summary(report)
    return 0


def _experiment_folder(file_config: ExperimentConfig, config: ExperimentConfig) -> str:
    """``<name>``, with suffixes for overrides that change results (runs may be added)."""
    name = config.name
    if config.episodes != file_config.episodes:
        name += f"__{config.episodes}ep"
    if config.env.max_episode_steps != file_config.env.max_episode_steps:
        name += f"__cap{config.env.max_episode_steps}"
    if config.seed != file_config.seed:
        name += f"__seed{config.seed}"
    return name


def _print_experiment_summary(report: Any) -> None:
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


def _load_for_playback(args: argparse.Namespace) -> tuple[Any, ExperimentConfig, Path]:
    """The saved agent and the environment settings to play it in (its own, then options)."""
    from experiments import factory

    path = Path(args.agent)
    if path.is_dir():
        path = path / "agent.npz"
    if not path.is_file():
        raise FileNotFoundError(f"agent file not found: {path}")
    beside = path.parent / "config.toml"
    config = config_module.load_config(
        beside if beside.is_file() and args.config == DEFAULT_CONFIG else args.config
    )
    env_changes = {
        k: v
        for k, v in (("maze", args.maze), ("robot", args.robot), ("mode", args.mode))
        if v is not None
    }
    config = dataclasses.replace(config, env=dataclasses.replace(config.env, **env_changes))
    config = config_module.with_overrides(config, max_episode_steps=args.max_episode_steps)
    try:
        agent = factory.load_agent(path)
    except (ValueError, OSError) as error:
        raise ConfigError(f"{path}: cannot load the agent: {error}") from None
    return agent, config, path


def _playback_env(agent: Any, config: ExperimentConfig, render_mode: str | None = None) -> Any:
    """The environment, projected to the agent's observation dimensions when it has more."""
    from experiments import factory

    env = factory.make_experiment_env(config, render_mode)
    dims = agent.observation_space.shape[0]
    given = int(np.prod(env.observation_space.shape or ()))
    if given > dims:
        env = factory.ProjectObservation(env, dims)
    elif given < dims:
        env.close()
        raise ConfigError(
            f"the agent observes {dims} values but robot {config.env.robot!r} gives {given}"
        )
    return env


def cmd_evaluate(args: argparse.Namespace) -> int:
    """Greedy episodes of a saved agent; success rate and steps."""
    from experiments import factory
    from experiments.evaluation import evaluate

    agent, config, path = _load_for_playback(args)
    env = _playback_env(agent, config)
    projected = isinstance(env, factory.ProjectObservation)
    try:
        optimal = factory.optimal_steps(env)
        start = time.perf_counter()
        result = evaluate(env, agent, args.episodes, seed=args.seed)
        elapsed = time.perf_counter() - start
    finally:
        env.close()
    steps = result.steps
    print(
        f"{path}: {args.episodes} greedy episodes in maze {config.env.maze!r}, robot "
        f"{config.env.robot!r}, mode {config.env.mode!r} (cap {config.env.max_episode_steps})"
        + ("; observation projected to (x, y), heading dropped" if projected else "")
    )
    print(f"success rate: {result.success_rate:.1%}")
    reached = result.successful_steps
    if reached.size:
        print(
            f"steps to goal (successful episodes): mean {reached.mean():.1f}, median "
            f"{np.median(reached):.0f}, min {reached.min()}, max {reached.max()}; optimal "
            f"{optimal:g}"
        )
    print(f"steps, capped episodes counted at the cap: mean {steps.mean():.1f}")
    print(
        f"collisions per episode: {np.mean([e.collisions for e in result.episodes]):.1f}; "
        f"{steps.sum() / elapsed:,.0f} steps/s"
    )
    return 0


def cmd_render(args: argparse.Namespace) -> int:
    """A GIF of one greedy episode over the partition."""
    from experiments import factory
    from experiments.animation import render_gif
    from experiments.evaluation import greedy_episode

    agent, config, path = _load_for_playback(args)
    env = _playback_env(agent, config)
    try:
        episode = greedy_episode(env, agent, seed=args.seed)
        layout, directions = factory.maze_geometry(env)
    finally:
        env.close()
    out = args.out or path.parent / "episode.gif"
    outcome = "reached the goal" if episode.success else "did not reach the goal"
    render_gif(
        agent,
        layout,
        directions,
        episode.positions,
        out,
        fps=args.fps,
        max_frames=args.max_frames,
        title=f"{agent.n_leaves} leaves,",
    )
    print(f"{out}: {episode.steps} steps, {outcome} ({config.env.robot}, {config.env.mode})")
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
    """A contact sheet of layouts (``experiments.layout_sheet``)."""
    from experiments.layout_sheet import layout_sheet, suite_sheet

    if bool(args.mazes) == bool(args.suite) or (args.split and not args.suite):
        raise ConfigError("layouts: give MAZE names or --suite NAME (--split goes with --suite)")
    try:
        if args.suite:
            path = suite_sheet(args.suite, args.out, args.split)
        else:
            path = layout_sheet(args.mazes, args.out)
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
    "layouts": cmd_layouts,
}


if __name__ == "__main__":
    sys.exit(main())
