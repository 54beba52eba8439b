"""Layouts at scale: what the number of solids and the arena's size cost.

``--only solids``: for N = 10, 50, 200, 1,000 solids, the world's build time (``gymnasium.make``
and the first reset, wall clock), kinematic steps per CPU second (random actions; a reset to a
random free start every 1,000 steps, so that the walk covers the arena), pybullet distance
queries per step and the CPU time of one query, dynamic steps per CPU second, and the time of a
256 x 256 image. Three series: forests of N cylinders and perfect mazes of about N walls at a
constant density (the arena grows with N, so a step meets as many solids whatever N), and
forests of N cylinders in a fixed 1,000 x 1,000 arena (denser with N). Every round builds and
runs every case, alternately forwards and backwards; rates are medians over the rounds and each
ratio (to the N = 10 case of its series) the median of the ratios within the rounds.

Each case also gets the share of the N = 10 speed that the per-cell certificates allow it, from
the same round (``certificate_bound``, ``step_bound``): the N = 10 step with its queries replaced
by the case's, at the N = 10 cost per query; plus the pieces each query reports, at the N = 10
cost per piece; and both at their whole cost to the N = 10 step (pybullet and the Python that
uses the answers, ``step_fit``); and those with each query's pybullet time at what that very
query costs replayed alone after the walk (``replay_bound``: a piece's cost depends on its shape,
not only on the count). A verdict per series at the largest N compares with the last, within
``NOISE``. The walk runs twice per round on fresh worlds: plain for the steps/s, then timed for
the counts and fits (the timers' own cost, ``timer_cost``, is taken off the fitted cost per query);
each several times, the fastest counting (``measure`` says why).

Each measurement runs in a fresh process. ``--compare-with DIR`` measures, in the same rounds, the
package found in DIR, an export of an older tree (``git archive COMMIT | tar -x -C DIR``), for a
before/after.

``--only limit``: the physical limit (``shortest_path``) of 200-tree forests in arenas of 300 to
2,000 units and of a 200-wall maze, each case in a fresh process: wall time and the growth of the
resident set (peak RSS after minus before), against the ``paper`` layout in the same run.
With ``--compare-with DIR`` the older tree runs the same cases (arenas up to 1,000).

Run: ``python bench/bench_layouts.py`` (``--quick`` for a smoke test).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import gymnasium as gym
import numpy as np

import bullet_maze
from bullet_maze.geometry import clearance

COUNTS = (10, 50, 200, 1000)
NOISE = 0.05
"""How far a ratio moves between idle runs of the bench (measured: about 0.05; more under load)."""


@dataclass(frozen=True)
class Case:
    series: str
    count: int
    spec: str


def cases(counts: tuple[int, ...]) -> list[Case]:
    """The three series of ``--only solids``."""
    found = []
    for n in counts:
        side = 2000.0 * math.sqrt(n / 1000.0)
        found.append(
            Case(
                "forest, constant density",
                n,
                f"forest:seed=0,count={n},width={side:.0f},height={side:.0f},gap=11",
            )
        )
        cells = max(3, round(math.sqrt(n / 0.46)))  # a perfect maze has about 0.46 walls a cell
        found.append(
            Case("maze, constant density", n, f"maze:seed=0,rows={cells},cols={cells},cell=40")
        )
        found.append(
            Case(
                "forest, 1000 x 1000",
                n,
                f"forest:seed=0,count={n},width=1000,height=1000,radius_min=2,radius_max=6,gap=11",
            )
        )
    return found


PLAIN_WALKS = 3
"""Plain walks per case and round, each on a fresh world; the fastest counts (see ``measure``)."""

TIMED_WALKS = 2
"""Timed walks per case and round, each on a fresh world; the fastest gives the counts and fits."""


def measure(case: Case, steps: int, dynamic_steps: int) -> dict[str, float]:
    """One round of one case: the kinematic walk on fresh worlds (each with its cells unseen),
    ``PLAIN_WALKS`` times as it is (the fastest is the steps/s reported) and ``TIMED_WALKS`` times
    with its queries and steps timed (the fastest gives the counts, fits and replay; the timers
    cost the step time of their own). The fastest, because on this shared machine the same walk
    runs either at its speed or, while another process shares the core and its caches, about 1.5
    times slower (2026-12-02: 5.2-5.7 against 7.0-8.5 us a step, nothing else changed): a
    contended walk only ever reads slower."""
    start = time.perf_counter()
    env = gym.make("BulletMaze-v0", maze=case.spec, render_mode="rgb_array")
    env.reset(seed=0)
    build = time.perf_counter() - start
    layout = env.unwrapped.layout
    rng = np.random.default_rng(0)
    starts = free_points(layout, rng, 1 + steps // 1000)
    actions = rng.integers(0, 4, steps).tolist()
    kinematic = 0.0
    for walk in range(PLAIN_WALKS):
        if walk:
            env = gym.make("BulletMaze-v0", maze=case.spec, render_mode="rgb_array")
            env.reset(seed=0)
        kinematic = max(kinematic, plain_walk(env, starts, actions))
        env.close()
    best: dict[str, float] = {}
    for _ in range(TIMED_WALKS):
        env = gym.make("BulletMaze-v0", maze=case.spec, render_mode="rgb_array")
        env.reset(seed=0)
        row = timed_walk(env, starts, actions)
        if row["timed_kinematic"] > best.get("timed_kinematic", 0.0):
            best = row
        if _ < TIMED_WALKS - 1:
            env.close()
    render_begin = time.perf_counter()
    for _ in range(3):
        env.render()
    render = (time.perf_counter() - render_begin) / 3
    env.close()
    dynamic_env = gym.make("BulletMaze-v0", maze=case.spec, mode="dynamic")
    dynamic_env.reset(seed=0)
    begin = time.process_time()
    for action in actions[:dynamic_steps]:
        _, _, terminated, truncated, _ = dynamic_env.step(action)
        if terminated or truncated:
            dynamic_env.reset()
    dynamic = dynamic_steps / (time.process_time() - begin)
    dynamic_env.close()
    return {
        "solids": layout.solid_count,
        "arena": layout.arena[0],
        "build_ms": build * 1e3,
        "kinematic": kinematic,
        **best,
        "dynamic": dynamic,
        "render_ms": render * 1e3,
    }


def plain_walk(env: gym.Env, starts: list, actions: list[int]) -> float:
    """The walk's kinematic steps per CPU second: a reset to the next start every 1,000 steps."""
    begin = time.process_time()
    for i, action in enumerate(actions):
        if i % 1000 == 0:
            env.reset(options={"start": starts[i // 1000]})
        _, _, terminated, truncated, _ = env.step(action)
        if terminated or truncated:
            env.reset()
    return len(actions) / (time.process_time() - begin)


def timed_walk(env: gym.Env, starts: list, actions: list[int]) -> dict[str, float]:
    """The walk with its queries and steps timed: its rate, the queries per step and the pieces
    per query, a query's CPU time and its fit against the pieces, the step fit (``step_fit``),
    the timers' own cost (``timer_cost``) and the replay (``replayed``)."""
    steps = len(actions)
    world = env.unwrapped.world
    # Per query: its CPU time t and the pieces it reported p; sums for the fit t = a + b p.
    sums = {"n": 0.0, "t": 0.0, "p": 0.0, "pp": 0.0, "pt": 0.0}
    closest = world._closest
    found_by_query: list[int] = []
    asked: list[tuple[float, float, float]] = []
    world._closest = timed(closest, sums, found_by_query, asked)
    wrapper_us = timer_cost()
    # Per step: the clock after it and the queries made so far (for ``step_fit``; about 0.1 us).
    ends, made, resets = [0] * steps, [0] * steps, [False] * steps
    clock = time.perf_counter_ns
    begin = time.process_time()
    first = clock()
    for i, action in enumerate(actions):
        if i % 1000 == 0:
            env.reset(options={"start": starts[i // 1000]})
            resets[i] = True
        _, _, terminated, truncated, _ = env.step(action)
        if terminated or truncated:
            env.reset()
            resets[i] = True
        ends[i] = clock()
        made[i] = len(found_by_query)
    timed_kinematic = steps / (time.process_time() - begin)
    base_us, query_step_us, piece_step_us = step_fit(first, ends, made, resets, found_by_query)
    world._closest = closest
    replay_us, replay_base_us, replay_piece_us = replayed(closest, asked)
    n = max(sums["n"], 1.0)
    mean_p, mean_t = sums["p"] / n, sums["t"] / n
    spread = sums["pp"] / n - mean_p * mean_p
    per_piece = (sums["pt"] / n - mean_p * mean_t) / spread if spread > 1e-12 else 0.0
    return {
        "timed_kinematic": timed_kinematic,
        "timer_us": wrapper_us,
        "queries": sums["n"] / steps,
        "query_us": mean_t * 1e6,
        "pieces": mean_p,
        "piece_us": per_piece * 1e6,
        "step_base_us": base_us,
        "step_query_us": query_step_us,
        "step_piece_us": piece_step_us,
        "replay_us": replay_us,
        "replay_base_us": replay_base_us,
        "replay_piece_us": replay_piece_us,
    }


def timed(
    closest: Callable[[float, float, float], list[tuple]],
    sums: dict[str, float],
    found_by_query: list[int],
    asked: list[tuple[float, float, float]],
) -> Callable[[float, float, float], list[tuple]]:
    """``closest`` that records each query's place and reach, its time and the pieces it reports
    (``sums`` for the fit of the time against the pieces)."""
    clock = (
        time.process_time
    )  # CPU time: a pause of the machine in a query would count in wall time

    def counted(x: float, y: float, reach: float) -> list[tuple]:
        asked.append((x, y, reach))
        begin = clock()
        points = closest(x, y, reach)
        spent, found = clock() - begin, len(points)
        sums["n"] += 1
        sums["t"] += spent
        sums["p"] += found
        sums["pp"] += found * found
        sums["pt"] += found * spent
        found_by_query.append(found)
        return points

    return counted


def timer_cost(calls: int = 20_000) -> float:
    """What ``timed`` adds to a query (microseconds, best of 3): a step of the timed walk pays it
    per query, the plain walk does not, so ``step_bound`` takes it off the fitted cost per query."""
    answer: list[tuple] = [()]

    def bare(x: float, y: float, reach: float) -> list[tuple]:
        return answer

    wrapped = timed(bare, {"n": 0.0, "t": 0.0, "p": 0.0, "pp": 0.0, "pt": 0.0}, [], [])
    best = math.inf
    for _ in range(3):
        begin = time.perf_counter_ns()
        for _ in range(calls):
            bare(1.0, 2.0, 3.0)
        middle = time.perf_counter_ns()
        for _ in range(calls):
            wrapped(1.0, 2.0, 3.0)
        best = min(best, (time.perf_counter_ns() - 2 * middle + begin) / calls / 1e3)
    return best


def step_fit(
    first: int, ends: list[int], made: list[int], resets: list[bool], found: list[int]
) -> tuple[float, float, float]:
    """A step's time against the queries q it made and the pieces p they reported, t = t0 + a q +
    b p (microseconds), everything a query costs the step: pybullet's answer and the Python that
    turns it into a certificate or a sweep's advance. Fitted, weighted by count, to the median
    time of the steps of each (q, p) seen at least 10 times (medians: a step the machine paused is
    an outlier), leaving out steps with a reset."""
    starts = np.array([first, *ends[:-1]])
    spent = (np.array(ends) - starts) / 1e3
    queries = np.diff(np.array([0, *made]))
    cumulative = np.concatenate(([0], np.cumsum(found)))
    pieces = cumulative[np.array(made)] - cumulative[np.array([0, *made[:-1]])]
    keep = ~np.array(resets)
    groups: dict[tuple[int, int], list[float]] = {}
    for q, p, t in zip(queries[keep], pieces[keep], spent[keep], strict=True):
        groups.setdefault((int(q), int(p)), []).append(float(t))
    rows = [
        (q, p, statistics.median(ts), len(ts)) for (q, p), ts in groups.items() if len(ts) >= 10
    ]
    if len({(q, p) for q, p, _, _ in rows}) < 3:
        return math.nan, math.nan, math.nan
    table = np.array(rows, dtype=float)
    weight = np.sqrt(table[:, 3])
    design = np.column_stack((np.ones(len(table)), table[:, 0], table[:, 1])) * weight[:, None]
    (t0, a, b), *_ = np.linalg.lstsq(design, table[:, 2] * weight, rcond=None)
    return float(t0), float(a), float(b)


def free_points(layout: bullet_maze.MazeLayout, rng: np.random.Generator, n: int) -> list:
    """``n`` random starts where the robot is clear of every solid and outside the goal."""
    points = []
    radius = layout.robot_radius
    while len(points) < n:
        x, y = rng.uniform(radius, np.array(layout.arena) - radius)
        if clearance(layout, np.array((x, y))) > radius + 0.5 and (
            math.dist((x, y), layout.goal) > layout.goal_radius
        ):
            points.append((float(x), float(y)))
    return points


def measure_in(package: str, case: Case, steps: int, dynamic_steps: int) -> dict[str, float]:
    """``measure`` in a fresh process that imports the package found in ``package``."""
    env = dict(os.environ, PYTHONPATH=package)
    command = [sys.executable, str(Path(__file__).resolve()), "--one", case.series, case.spec]
    command += ["--steps", str(steps), "--dynamic-steps", str(dynamic_steps)]
    out = subprocess.run(command, cwd=package, check=True, capture_output=True, text=True, env=env)
    return json.loads(out.stdout.strip().splitlines()[-1])


def bench_solids(
    counts: tuple[int, ...], rounds: int, steps: int, dynamic_steps: int, compare: str | None
) -> None:
    here = str(Path(bullet_maze.__file__).resolve().parent.parent)
    packages = [("this tree", here)] + ([("compared tree", compare)] if compare else [])
    found = cases(counts)
    results: dict[tuple[Case, str], list[dict[str, float]]] = {}
    for r in range(rounds):
        order = found if r % 2 == 0 else found[::-1]
        for case in order:
            for name, package in packages if r % 2 == 0 else packages[::-1]:
                row = measure_in(package, case, steps, dynamic_steps)
                results.setdefault((case, name), []).append(row)
        print(f"round {r + 1}/{rounds} done", file=sys.stderr)
    print(
        "| series | code | solids | arena | build (ms) | kinematic steps/s | vs N=10 | "
        "certificates' bound: queries | and pieces | and their handling | "
        "and the queries' own cost | queries/step | pieces/query | us/query | us/query replayed | "
        "dynamic steps/s | vs N=10 | render (ms) |"
    )
    print("| --- " * 18 + "|")
    verdicts = []
    for case in found:
        for name, _ in packages:
            rows = results[case, name]
            first = next(c for c in found if c.series == case.series)
            reference = results[first, name]
            med = {key: statistics.median(row[key] for row in rows) for key in rows[0]}
            pairs = list(zip(rows, reference, strict=True))
            ratios = [a["kinematic"] / b["kinematic"] for a, b in pairs]
            kin = statistics.median(ratios)
            low, high = np.percentile(ratios, [25, 75]) if len(ratios) > 1 else (kin, kin)
            dyn = statistics.median(a["dynamic"] / b["dynamic"] for a, b in pairs)
            by_count = statistics.median(certificate_bound(a, b, pieces=False) for a, b in pairs)
            by_pieces = statistics.median(certificate_bound(a, b, pieces=True) for a, b in pairs)
            by_steps = statistics.median(step_bound(a, b) for a, b in pairs)
            by_replay = statistics.median(replay_bound(a, b) for a, b in pairs)
            print(
                f"| {case.series} | {name} | {med['solids']:.0f} | {med['arena']:.0f} | "
                f"{med['build_ms']:.0f} | {med['kinematic']:,.0f} | {kin:.2f} | "
                f"{by_count:.2f} | {by_pieces:.2f} | {by_steps:.2f} | {by_replay:.2f} | "
                f"{med['queries']:.3f} | {med['pieces']:.2f} | {med['query_us']:.1f} | "
                f"{med['replay_us']:.1f} | {med['dynamic']:,.0f} | "
                f"{dyn:.2f} | {med['render_ms']:.0f} |"
            )
            if case.count == max(counts) and name == "this tree":
                verdicts.append(
                    f"{case.series}, N = {case.count}: kinematic {kin:.2f} of the N = 10 speed "
                    f"(rounds' quartiles {low:.2f}-{high:.2f}); "
                    f"the certificates' query count allows {by_count:.2f}, with the pieces each "
                    f"query reports {by_pieces:.2f}, with the whole cost of handling them in the "
                    f"step {by_steps:.2f}, with the queries at their own replayed cost "
                    f"{by_replay:.2f}: "
                    + (
                        "met"
                        if kin >= by_replay - NOISE
                        else f"short of that by {by_replay - kin:.2f}"
                    )
                    + f" (within {NOISE} counts as met: the ratios' run-to-run spread)"
                )
    print()
    for line in verdicts:
        print(f"- {line}")


def replayed(
    closest: Callable[[float, float, float], list[tuple]], asked: list[tuple[float, float, float]]
) -> tuple[float, float, float]:
    """Every query of the run asked again after it, alone, each the best of 3 (microseconds of
    wall time: the best of 3 drops a pause of the machine): the mean, and the fit t = c + d p of a
    query's time against the pieces p it reports. What the certificates' own queries cost pybullet
    with nothing else between them (the shapes they meet, not only their number)."""
    clock = time.perf_counter_ns
    rows = []
    for x, y, reach in asked:
        best = math.inf
        for _ in range(3):
            begin = clock()
            found = len(closest(x, y, reach))
            best = min(best, clock() - begin)
        rows.append((found, best / 1e3))
    if not rows:
        return math.nan, math.nan, math.nan
    table = np.array(rows, dtype=float)
    mean = float(table[:, 1].mean())
    if np.ptp(table[:, 0]) == 0:
        return mean, mean, 0.0
    design = np.column_stack((np.ones(len(table)), table[:, 0]))
    (c, d), *_ = np.linalg.lstsq(design, table[:, 1], rcond=None)
    return mean, float(c), float(d)


def replay_bound(row: dict[str, float], reference: dict[str, float]) -> float:
    """``step_bound`` with the pybullet time of the case's queries at what they cost replayed alone
    (``replayed``) instead of the N = 10 model at their pieces: ``step_bound`` charges a query the
    N = 10 cost of as many pieces, but a piece's cost depends on its shape (a cylinder's test costs
    more than a box's) and on the pieces pybullet tests without reporting; the replay measures the
    very queries the certificates asked. The same correction is zero for the reference (the fit's
    mean residual)."""
    step = 1e6 / reference["kinematic"]
    a, b = reference["step_query_us"] - reference["timer_us"], reference["step_piece_us"]
    extra = a * (row["queries"] - reference["queries"]) + b * (
        row["queries"] * row["pieces"] - reference["queries"] * reference["pieces"]
    )
    modelled = reference["replay_base_us"] + reference["replay_piece_us"] * row["pieces"]
    extra += row["queries"] * (row["replay_us"] - modelled)
    return step / (step + extra)


def step_bound(row: dict[str, float], reference: dict[str, float]) -> float:
    """As ``certificate_bound`` with pieces, at what a query and a piece cost the whole N = 10 step
    (``step_fit`` of the reference's timed walk: pybullet and the Python that uses the answer;
    less the timer's own cost per query, ``timer_cost``, which the plain walk does not pay)."""
    step = 1e6 / reference["kinematic"]
    a, b = reference["step_query_us"] - reference["timer_us"], reference["step_piece_us"]
    extra = a * (row["queries"] - reference["queries"]) + b * (
        row["queries"] * row["pieces"] - reference["queries"] * reference["pieces"]
    )
    return step / (step + extra)


def certificate_bound(row: dict[str, float], reference: dict[str, float], pieces: bool) -> float:
    """The share of the N = 10 case's speed (``reference``, same series, code and round) that a
    case keeps if only the certificates' pybullet work grows: its step time is the reference's,
    with the reference's queries per step replaced by the case's at the reference's cost per
    query; with ``pieces``, a query costs the reference's fit ``a + b p`` of its time against the
    pieces p it reports (a query that must report more pieces costs more: each is a closest-point
    computation and a result), evaluated at the case's mean p."""
    step = 1e6 / reference["kinematic"]  # microseconds
    cost = reference["query_us"]
    if pieces:
        cost += reference["piece_us"] * (row["pieces"] - reference["pieces"])
    return step / (step + row["queries"] * cost - reference["queries"] * reference["query_us"])


LIMIT_CODE = """
import json, resource, sys, time
from bullet_maze import load_layout, shortest_path
layout = load_layout(sys.argv[1])
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
start = time.perf_counter()
limit = shortest_path(layout)
seconds = time.perf_counter() - start
after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print(json.dumps({"seconds": seconds, "mb": (after - before) / 1024, "steps": limit.steps}))
"""


def limit_cases(quick: bool) -> list[tuple[str, str]]:
    sides = (300, 1000) if quick else (300, 600, 1000, 2000)
    found = [("paper (reference)", "paper")]
    # 200 trees of radius 1-3 fit a 300 x 300 arena (the default 4-12 jam there).
    found += [
        (
            f"forest, 200 trees, {s} x {s}",
            f"forest:seed=0,count=200,width={s},height={s},radius_min=1,radius_max=3,gap=10.5",
        )
        for s in sides
    ]
    found.append(
        (
            "maze, 21 x 21 cells (about 200 walls), 1000 x 1000",
            "maze:seed=0,rows=21,cols=21,cell=47.6",
        )
    )
    return found


def run_limit(path: Path, package: str) -> dict[str, float]:
    env = dict(os.environ, PYTHONPATH=package)
    # Run from the package's folder: ``python -c`` puts the working directory first on the path.
    out = subprocess.run(
        [sys.executable, "-c", LIMIT_CODE, str(path)],
        cwd=package,
        check=True,
        capture_output=True,
        text=True,
        env=env,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def bench_limit(rounds: int, quick: bool, compare: str | None) -> None:
    here = str(Path(bullet_maze.__file__).resolve().parent.parent)
    packages = [("this tree", here)] + ([("compared tree", compare)] if compare else [])
    with tempfile.TemporaryDirectory() as tmp:
        files = []
        for label, spec in limit_cases(quick):
            path = Path(tmp) / f"{len(files)}.toml"
            path.write_text(bullet_maze.layout_to_toml(bullet_maze.load_layout(spec)))
            files.append((label, path, bullet_maze.load_layout(spec).arena[0]))
        results: dict[tuple[str, str], list[dict[str, float]]] = {}
        for r in range(rounds):
            order = files if r % 2 == 0 else files[::-1]
            for label, path, side in order:
                for name, package in packages:
                    if name != "this tree" and side > 1000:
                        continue  # the old grid needs about 8 GB at 2,000 x 2,000
                    results.setdefault((label, name), []).append(run_limit(path, package))
            print(f"round {r + 1}/{rounds} done", file=sys.stderr)
    print("| layout | code | time (s) | vs paper | RSS growth (MB) | least steps |")
    print("| --- | --- | --- | --- | --- | --- |")
    for (label, name), rows in results.items():
        reference = results[("paper (reference)", name)]
        ratio = statistics.median(
            a["seconds"] / b["seconds"] for a, b in zip(rows, reference, strict=True)
        )
        seconds = statistics.median(row["seconds"] for row in rows)
        mb = statistics.median(row["mb"] for row in rows)
        print(
            f"| {label} | {name} | {seconds:.2f} | {ratio:.2f} | {mb:.0f} | "
            f"{rows[0]['steps']:.0f} |"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", choices=("solids", "limit"), help="one part only")
    parser.add_argument("--rounds", type=int, default=5, help="interleaved rounds (default 5)")
    parser.add_argument("--steps", type=int, default=20_000, help="kinematic steps per case")
    parser.add_argument("--dynamic-steps", type=int, default=2_000, help="dynamic steps per case")
    parser.add_argument("--compare-with", metavar="DIR", help="an older tree to compare with")
    parser.add_argument("--one", nargs=2, metavar=("SERIES", "SPEC"), help=argparse.SUPPRESS)
    parser.add_argument("--quick", action="store_true", help="a smoke test: small and short")
    args = parser.parse_args()
    if args.one:  # one measurement, for measure_in
        case = Case(args.one[0], 0, args.one[1])
        print(json.dumps(measure(case, args.steps, args.dynamic_steps)))
        return
    jobs: dict[str, Callable[[], None]] = {
        "solids": lambda: bench_solids(
            (10, 200) if args.quick else COUNTS,
            1 if args.quick else args.rounds,
            2_000 if args.quick else args.steps,
            200 if args.quick else args.dynamic_steps,
            args.compare_with,
        ),
        "limit": lambda: bench_limit(
            1 if args.quick else args.rounds, args.quick, args.compare_with
        ),
    }
    for name, job in jobs.items():
        if args.only in (None, name):
            job()


if __name__ == "__main__":
    main()
