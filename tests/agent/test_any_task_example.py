"""examples/any_task.py: the general agent on a task with other spaces, and its command line's
errors (one line, exit code 2, no traceback)."""

from __future__ import annotations

from collections.abc import Callable
from types import ModuleType

import pytest

Load = Callable[[str], ModuleType]


def test_it_learns_cliff_walking_through_the_index(load_example: Load) -> None:
    result = load_example("any_task").train(
        "CliffWalking-v1", episodes=100, seed=0, eval_episodes=2
    )
    assert len(result.history) == 100
    # the edge path, the optimum: the 48 cells start as a table (TreeConfig.table_cells)
    assert result.eval_returns == [-13.0, -13.0]


def test_a_box_action_task_runs_on_the_grid(
    load_example: Load, capsys: pytest.CaptureFixture[str]
) -> None:
    assert (
        load_example("any_task").main(["Pendulum-v1", "--episodes", "2", "--action-bins", "3"]) == 0
    )
    out = capsys.readouterr().out
    assert out.startswith("Pendulum-v1: 2 episodes")
    assert "greedy return over 20 episodes" in out


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["NoSuchTask-v9"], "NoSuchTask-v9: Environment `NoSuchTask` doesn't exist"),
        (["Pendulum-v1", "--action-bins", "1"], "every bin count must be an int >= 2, got 1"),
        (["Pendulum-v1", "--action-bins", "5000"], "5,000 actions, more than 4,096"),
        (
            ["CliffWalking-v1", "--action-bins", "3"],
            "action_bins = 3 only applies to a task with Box actions",
        ),
    ],
)
def test_bad_arguments_are_one_line_errors(
    argv: list[str], message: str, load_example: Load, capsys: pytest.CaptureFixture[str]
) -> None:
    assert load_example("any_task").main([*argv, "--episodes", "1"]) == 2
    err = capsys.readouterr().err
    assert message in err
    assert "Traceback" not in err
    assert err.count("\n") == 1


@pytest.mark.parametrize(
    "argv", [["Pendulum-v1", "--episodes", "0"], ["Pendulum-v1", "--seed", "x"]]
)
def test_bad_numbers_are_refused_by_argparse(argv: list[str], load_example: Load) -> None:
    with pytest.raises(SystemExit) as stop:
        load_example("any_task").main(argv)
    assert stop.value.code == 2
