"""Part 36's held-out rows: today's preset (N_th 50, ``split_min_samples``) against part 35's
(``general_as_of(35)``, spelt out as ``general-part35``), both arms trained on the same fresh
experiment seeds. A pair is two runs with the same run seed (the same agent seed and reset
seeds); every run changes, since the split test's pair count shapes the tree from the start.

Classic control (36101): per task, each arm's runs at the target, mean greedy return (20 greedy
episodes a run), the paired change with a bootstrap 95 % interval and a sign test. Mazes (the
suite's test split, 36102): per layout, each arm's final (last 100 training episodes) over the
optimum, area under the curve over the optimum, converged runs and their median episode, and
greedy steps, with the best uniform grid's area; the latest convergence; the geometric means.
Paper (36103, today's preset only) is read from its own report.md.

    python pair.py            (from anywhere; writes pair.txt beside this file)
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

HERE = Path(__file__).resolve().parent
RESULTS = HERE.parent


def _load(name: str, path: Path):  # type: ignore[no-untyped-def]
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None
    assert spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_PART30 = _load("part30_pair", RESULTS / "issue9_part30_heldout_rows" / "pair.py")
TARGET = _PART30.TARGET
greedy_means = _PART30.greedy_means
CLASSIC = RESULTS / "issue9_part36_heldout_classic_seed36101"
MAZES = RESULTS / "issue9_part36_heldout_mazes_seed36102"
ARMS = ("general-part35", "general")
LABELS = ("part 35", "part 36")
_PART30.MAZES, _PART30.ARMS = MAZES, ARMS  # its mazes() reads these


def _relabel(text: str) -> str:
    """Part 30's lines name its arms "part 29" and "part 30"; here they are parts 35 and 36."""
    return text.replace("part 29", LABELS[0]).replace("part 30", LABELS[1])


def classic(lines: list[str]) -> None:
    if not (CLASSIC / "evaluation.csv").exists():
        lines.append("classic 36101: not run")
        return
    means = greedy_means(CLASSIC)
    for task in TARGET:
        old, new = means.get((task, ARMS[0]), {}), means.get((task, ARMS[1]), {})
        runs = sorted(set(old) & set(new))
        if len(runs) < 10:
            lines.append(f"36101 {task}: {len(runs)} pairs finished")
            continue
        a, b = [old[r] for r in runs], [new[r] for r in runs]
        lines.append("36101 " + _relabel(_PART30._pairs(task, a, b)))
        lines.append(f"  {LABELS[0]}: " + ", ".join(f"{v:.2f}" for v in a))
        lines.append(f"  {LABELS[1]}: " + ", ".join(f"{v:.2f}" for v in b))


def mazes(lines: list[str]) -> None:
    """Part 30's maze table, read from this part's folder and arms."""
    if not (MAZES / "summary.csv").exists():
        lines.append("mazes 36102: not run")
        return
    table: list[str] = []
    _PART30.mazes(table)
    table[0] = _relabel(table[0])
    lines.extend(table)


def main() -> None:
    lines = ["# Part 36's held-out rows (pair.py)", ""]
    classic(lines)
    lines.append("")
    mazes(lines)
    (HERE / "pair.txt").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
