"""The probe for the next step as it was run, before the option existed: ``job.py`` with model
splits held until the model has recorded its first terminal epoch (the goal on a maze,
MountainCar and Acrobot; the first fall on CartPole). ``TreeConfig.model_split_from_terminal``
is the option it became (the same runs)::

    python gate_probe.py classic MountainCar-v0 2 gate '{"model_split_epochs": 8}' out.jsonl

It wraps ``SMDPAgent._model_split`` in this process only. Its runs are in ``gate_maze.jsonl``
and ``gate_classic.jsonl`` (docs/paper-notes.md, "Model-driven splits").
"""

from __future__ import annotations

import runpy
import sys
from pathlib import Path
from typing import Any

from agent import learner

_model_split = learner.SMDPAgent._model_split


def _after_first_terminal(self: Any, leaf: int, action: int) -> Any:
    if self.model is None or self.model.terminals == 0:
        return None
    return _model_split(self, leaf, action)


if __name__ == "__main__":
    learner.SMDPAgent._model_split = _after_first_terminal  # type: ignore[method-assign]
    sys.argv = ["job.py", *sys.argv[1:]]
    runpy.run_path(str(Path(__file__).with_name("job.py")), run_name="__main__")
