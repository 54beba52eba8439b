"""The named agents: the paper's presets are exactly what paper_fig4 runs."""

from __future__ import annotations

import dataclasses
import importlib.util
import tomllib
from pathlib import Path

import pytest
from gymnasium import spaces

from agent import PRESETS, TreeConfig, general_as_of, preset, presets
from agent.presets import GENERAL_CHANGES
from agent.tree_ensemble import TreeEnsembleAgent
from experiments import EXPERIMENT_DIR

BOX = spaces.Box(0.0, 1.0, shape=(2,))


def fig4_strategy(name: str) -> dict:
    data = tomllib.loads((EXPERIMENT_DIR / "paper_fig4.toml").read_text())
    return next(s for s in data["strategy"] if s["name"] == name)


def test_paper_presets_are_paper_fig4s_strategies() -> None:
    paper, literal = preset("paper"), preset("paper-literal")
    assert paper.config == TreeConfig()
    assert paper.exploration == fig4_strategy("adaptive+tabu")["exploration"]
    spec = fig4_strategy("adaptive+tabu-literal")
    assert literal.exploration == spec["exploration"]
    assert literal.config == TreeConfig(**spec["config"])
    expected = {k: v for k, v in spec["exploration_params"].items() if k not in ("c_n", "c_h")}
    assert dict(literal.exploration_params) == expected


def test_general_preset_goes_beyond_the_paper_by_named_fields_only() -> None:
    general = preset("general").config
    changed = {k for k, v in general.to_dict().items() if v != getattr(TreeConfig(), k)}
    beyond = {"threshold_units", "scale_rule", "planning", "model_window", "sweep_backups"}
    table_one = {"split_min_samples", "split_max_abs_mean", "split_min_variance"}
    others = {"initial_depth", "presplit_each_dimension", "model_bonus", "sweep_tolerance"}
    others |= {"max_leaves"}  # a guard of memory; 16,384 in the general preset
    others |= {"hold_terminals"}  # issue 9, part 8
    others |= {"model_split_epochs"}  # issue 9, part 9
    others |= {"novelty_cells", "novelty_terminals"}  # issue 9, part 10
    others |= {"gamma", "scale_horizon"}  # issue 9, part 11
    others |= {"novelty_episodes"}  # issue 9, part 12
    others |= {"collision_splits"}  # issue 9, part 14
    others |= {"table_cells"}  # issue 9, part 15
    others |= {"optimistic_untried"}  # issue 9, part 16
    others |= {"presplit_max_dimensions", "presplit_beyond_dimensions"}  # issue 9, part 17
    others |= {"failure_gamma"}  # issue 9, part 19
    others |= {"failure_measure"}  # issue 9, part 20
    others |= {"greedy_min_epochs"}  # issue 9, part 23
    others |= {"greedy_cell_epochs"}  # issue 9, part 24
    others |= {"greedy_smoothing", "greedy_smoothing_links", "greedy_tie_errors"}  # part 25
    others |= {"greedy_tie_ancestors"}  # part 27
    others |= {"greedy_tie_trial"}  # part 30 (its companions stay at their defaults)
    others |= {"greedy_tie_trial_avoid_collided"}  # part 32
    assert changed <= beyond | table_one | others
    assert general.threshold_units == "scale"
    assert general.sweep_backups == 64  # issue 9, part 4 (docs/paper-notes.md)
    assert general.max_leaves == 16384  # issue 9, part 7 (docs/paper-notes.md, "The leaf cap")
    assert general.hold_terminals == 100  # issue 9, part 8 ("Held exploration until n terminals")
    assert general.model_split_epochs == 8  # issue 9, part 9 ("Model-driven splits")
    assert (general.novelty_cells, general.novelty_terminals) == (64, 10)  # part 10 ("Novel ends")
    assert (general.gamma, general.scale_horizon) == (0.999, 100.0)  # part 11 ("A longer discount")
    assert general.novelty_episodes == 100  # part 12 ("Tasks without terminal states")
    assert general.collision_splits is True  # part 14 ("Collision splits")
    assert general.table_cells == general.max_leaves  # part 15 ("A table for integer inputs")
    assert general.optimistic_untried is True  # part 16 ("Optimism for untried actions")
    # part 17 ("Inputs with many dimensions")
    assert (general.presplit_max_dimensions, general.presplit_beyond_dimensions) == (8, 4)
    assert general.failure_gamma == 0.9995  # part 19 ("A discount gated on failure")
    assert general.failure_measure == "every"  # part 20 (the same section)
    assert general.policy_splits is False  # part 21: withdrawn on more dev seeds
    # parts 23 and 24 ("A greedy choice among supported actions")
    assert (general.greedy_min_epochs, general.greedy_cell_epochs) == (2, 1)
    # part 27 ("Ancestors compare leaf by leaf"), in place of part 25's neighbours
    assert (general.greedy_smoothing, general.greedy_smoothing_links) == (0.0, False)
    assert (general.greedy_tie_errors, general.greedy_tie_ancestors) == (1.0, 1.0)
    # part 30 ("Tie width chosen by the run")
    assert general.greedy_tie_trial == 2.0
    assert (general.greedy_tie_trial_episodes, general.greedy_tie_trial_every) == (300, 4)
    assert general.greedy_tie_trial_margin == 2.0
    assert general.split_min_samples == 50  # part 36 (Table I's N_th is 500; parts 1-35 used 100)
    assert type(preset("general").agent(BOX, spaces.Discrete(4))) is TreeEnsembleAgent


@pytest.mark.parametrize("name", sorted(PRESETS))
def test_each_preset_builds_fresh_agents(name: str) -> None:
    one = preset(name).agent(BOX, spaces.Discrete(4), seed=1)
    two = preset(name).agent(BOX, spaces.Discrete(4), seed=1)
    assert one.exploration is not two.exploration
    assert one.config == preset(name).config


def test_unknown_preset_lists_the_names() -> None:
    with pytest.raises(ValueError, match=r"'fastest'.*general"):
        preset("fastest")


def test_general_paper_experiment_spells_out_the_general_preset() -> None:
    data = tomllib.loads((EXPERIMENT_DIR / "general_paper.toml").read_text())
    spec = next(s for s in data["strategy"] if s["name"] == "general")
    general = preset("general")
    assert spec["exploration"] == general.exploration
    assert TreeConfig(**{**data["agent"], **spec["config"]}) == general.config


@pytest.mark.parametrize("kind", ["classic", "mazes", "paper"])
def test_part8_comparisons_set_the_preset_against_part_7s(kind: str) -> None:
    data = tomllib.loads((EXPERIMENT_DIR / f"hold_terminals_{kind}.toml").read_text())
    by_name = {s["name"]: s for s in data["strategy"]}
    assert by_name["general"]["preset"] == "general"
    old = by_name["general-part7"]
    assert old["exploration"] == preset("general").exploration
    assert TreeConfig(**{**data.get("agent", {}), **old["config"]}) == general_as_of(7)


@pytest.mark.parametrize("kind", ["classic", "mazes", "paper"])
def test_part9_comparisons_set_the_preset_against_part_8s(kind: str) -> None:
    data = tomllib.loads((EXPERIMENT_DIR / f"model_split_{kind}.toml").read_text())
    by_name = {s["name"]: s for s in data["strategy"]}
    assert by_name["general"]["preset"] == "general"
    if "general-part8" not in by_name:
        return  # the paper comparison runs the preset alone (part 8's runs: its own file)
    old = by_name["general-part8"]
    assert old["exploration"] == preset("general").exploration
    assert TreeConfig(**{**data.get("agent", {}), **old["config"]}) == general_as_of(8)


@pytest.mark.parametrize("kind", ["classic", "mazes", "paper"])
@pytest.mark.parametrize(
    ("prefix", "part", "first_seed"),
    [("novelty", 10, 90901), ("horizon", 11, 11101), ("novelty_episodes", 12, 12101)],
)
def test_each_part_sets_the_preset_against_the_part_before(
    kind: str, prefix: str, part: int, first_seed: int
) -> None:
    """Parts 10 to 12: ``general`` is the preset by name, ``general-partN`` the preset as it was
    before the part (``general_as_of``), spelt out; a fresh seed for each case."""
    data = tomllib.loads((EXPERIMENT_DIR / f"{prefix}_{kind}.toml").read_text())
    by_name = {s["name"]: s for s in data["strategy"]}
    assert by_name["general"] == {"name": "general", "preset": "general"}
    old = by_name[f"general-part{part - 1}"]
    assert old["exploration"] == preset("general").exploration
    assert TreeConfig(**{**data.get("agent", {}), **old["config"]}) == general_as_of(part - 1)
    offset = {"classic": 0, "mazes": 1, "paper": 2}[kind]
    assert data["experiment"]["seed"] == first_seed + offset


@pytest.mark.parametrize("kind", ["mazes", "paper"])
def test_part14_comparisons_set_the_preset_against_part_13s(kind: str) -> None:
    """Part 14 (collision splits) runs where collisions happen: classic control reports none,
    so there both arms would be one run (tests/agent/test_collision_split.py)."""
    data = tomllib.loads((EXPERIMENT_DIR / f"collision_splits_{kind}.toml").read_text())
    by_name = {s["name"]: s for s in data["strategy"]}
    assert by_name["general"] == {"name": "general", "preset": "general"}
    old = by_name["general-part13"]
    assert old["exploration"] == preset("general").exploration
    assert TreeConfig(**{**data.get("agent", {}), **old["config"]}) == general_as_of(13)
    assert data["experiment"]["seed"] == {"mazes": 14102, "paper": 14103}[kind]


@pytest.mark.parametrize(
    ("name", "part", "seed"),
    [("table_tasks", 14, 15101), ("optimism_classic", 15, 16101), ("optimism_tasks", 15, 16102)],
)
def test_parts_15_and_16_set_the_preset_against_the_part_before(
    name: str, part: int, seed: int
) -> None:
    """Each held-out comparison spells the earlier preset out field by field: it must be
    ``general_as_of(part)`` exactly, so that the report's baseline is what it says."""
    data = tomllib.loads((EXPERIMENT_DIR / f"{name}.toml").read_text())
    by_name = {s["name"]: s for s in data["strategy"]}
    assert by_name["general"] == {"name": "general", "preset": "general"}
    old = by_name[f"general-part{part}"]
    assert old["exploration"] == preset("general").exploration
    assert TreeConfig(**{**data.get("agent", {}), **old["config"]}) == general_as_of(part)
    assert data["experiment"]["seed"] == seed


def test_part17_lidar_comparison_sets_the_preset_against_part_16s_without_a_presplit() -> None:
    """Part 16's preset refuses the lidar's 38 inputs; its arm is that preset with the presplit
    off, what a user could run then."""
    data = tomllib.loads((EXPERIMENT_DIR / "presplit_lidar_mazes.toml").read_text())
    by_name = {s["name"]: s for s in data["strategy"]}
    assert by_name["general"] == {"name": "general", "preset": "general"}
    old = by_name["general-part16-no-presplit"]
    assert old["exploration"] == preset("general").exploration
    expected = dataclasses.replace(general_as_of(16), presplit_each_dimension=False)
    assert TreeConfig(**{**data.get("agent", {}), **old["config"]}) == expected
    assert data["env"]["params"] == {"observation": "lidar"}
    assert data["experiment"]["seed"] == 17102


@pytest.mark.parametrize(
    ("name", "seed"), [("classic", 19101), ("cartpole", 19102), ("tasks", 19104)]
)
def test_part19_comparisons_set_the_preset_against_part_18s(name: str, seed: int) -> None:
    data = tomllib.loads((EXPERIMENT_DIR / f"failure_gamma_{name}.toml").read_text())
    by_name = {s["name"]: s for s in data["strategy"]}
    assert by_name["general"] == {"name": "general", "preset": "general"}
    old = by_name["general-part18"]
    assert old["exploration"] == preset("general").exploration
    assert TreeConfig(**{**data.get("agent", {}), **old["config"]}) == general_as_of(18)
    assert general_as_of(18) != preset("general").config
    assert data["experiment"]["seed"] == seed


@pytest.mark.parametrize(("name", "seed"), [("classic", 21101), ("mountaincar", 21102)])
def test_part21_comparisons_add_policy_splits_to_the_preset(name: str, seed: int) -> None:
    """Part 21's option, withdrawn from the preset: each file's candidate is the preset with
    the one field, its baseline the preset (the configs its stored runs were made with)."""
    data = tomllib.loads((EXPERIMENT_DIR / f"policy_splits_{name}.toml").read_text())
    by_name = {s["name"]: s for s in data["strategy"]}
    assert by_name["general"] == {"name": "general", "preset": "general"}
    candidate = by_name["general-policy-splits"]
    assert candidate == {
        "name": "general-policy-splits",
        "preset": "general",
        "config": {"policy_splits": True},
    }
    assert general_as_of(22) == general_as_of(20)  # the preset its stored runs were made with
    assert data["experiment"]["baseline"] == "general"
    assert data["experiment"]["seed"] == seed


@pytest.mark.parametrize("kind", ["classic", "mazes"])
def test_the_from_terminal_candidate_changes_one_field_of_the_preset(kind: str) -> None:
    data = tomllib.loads((EXPERIMENT_DIR / f"model_split_from_terminal_{kind}.toml").read_text())
    by_name = {s["name"]: s for s in data["strategy"]}
    assert by_name["general"] == {"name": "general", "preset": "general"}
    candidate = by_name["general-from-terminal"]
    assert candidate["preset"] == "general"
    assert candidate["config"] == {"model_split_from_terminal": True}


def test_general_as_of_turns_back_each_later_part() -> None:
    now = preset("general").config
    assert general_as_of(36) == now
    now = dataclasses.replace(now, split_min_samples=100)
    assert general_as_of(35) == general_as_of(34) == general_as_of(33) == general_as_of(32) == now
    now = dataclasses.replace(now, greedy_tie_trial_avoid_collided=False)
    assert general_as_of(31) == general_as_of(30) == now
    now = dataclasses.replace(now, greedy_tie_trial=None, greedy_tie_trial_avoid_collided=False)
    assert general_as_of(29) == general_as_of(28) == general_as_of(27) == now
    now = dataclasses.replace(
        now,
        greedy_smoothing=1.0,
        greedy_smoothing_links=True,
        greedy_tie_errors=0.5,
        greedy_tie_ancestors=None,
    )
    assert general_as_of(26) == general_as_of(25) == now
    now = dataclasses.replace(
        now, greedy_smoothing=0.0, greedy_smoothing_links=False, greedy_tie_errors=None
    )
    assert general_as_of(24) == now
    now = dataclasses.replace(now, greedy_min_epochs=1, greedy_cell_epochs=None)
    assert general_as_of(23) == now
    now = dataclasses.replace(now, greedy_min_epochs=0)
    assert general_as_of(22) == general_as_of(21) == general_as_of(20) == now
    assert general_as_of(19) == dataclasses.replace(now, failure_measure="mean")
    now = dataclasses.replace(now, failure_gamma=None, failure_measure="mean")
    assert general_as_of(18) == general_as_of(17) == now
    now = dataclasses.replace(now, presplit_max_dimensions=None, presplit_beyond_dimensions=0)
    assert general_as_of(16) == now
    assert general_as_of(15) == dataclasses.replace(now, optimistic_untried=False)
    assert general_as_of(14) == dataclasses.replace(now, optimistic_untried=False, table_cells=None)
    before = dataclasses.replace(
        now, optimistic_untried=False, table_cells=None, collision_splits=False
    )
    assert general_as_of(13) == general_as_of(12) == before
    assert general_as_of(11) == dataclasses.replace(before, novelty_episodes=None)
    assert general_as_of(10) == dataclasses.replace(
        before, gamma=0.99, scale_horizon=None, novelty_episodes=None
    )
    assert general_as_of(9).novelty_cells is None
    assert general_as_of(9).gamma == 0.99
    assert general_as_of(7).hold_terminals is None
    assert general_as_of(8).hold_terminals == 100
    for bad in (6, True, "9", 8.0):
        with pytest.raises(ValueError, match="general_as_of: part must be an int >= 7"):
            general_as_of(bad)  # type: ignore[arg-type]


def test_general_as_of_takes_the_value_before_the_first_later_change(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A field that two later parts changed (gamma: 0.99 until part 11, 0.995 until a part 99,
    then today's) goes back to the value it had at the part asked for, whatever the order the
    changes were listed in."""
    later = {99: {"gamma": 0.995}}
    for changes in ({**later, **presets.GENERAL_CHANGES}, {**presets.GENERAL_CHANGES, **later}):
        monkeypatch.setattr(presets, "GENERAL_CHANGES", changes)
        assert general_as_of(99).gamma == preset("general").config.gamma
        assert general_as_of(98).gamma == general_as_of(11).gamma == 0.995
        assert general_as_of(10).gamma == general_as_of(7).gamma == 0.99


def _spelt_out(arm: dict[str, object]) -> TreeConfig:
    """The config of an arm written field by field (no preset, the paper's agent)."""
    assert set(arm) == {"name", "exploration", "config"}
    assert arm["exploration"] == "adaptive+tabu"
    return TreeConfig(**arm["config"])  # type: ignore[arg-type]


@pytest.mark.parametrize(("name", "seed"), [("classic", 23101), ("mountaincar", 11101)])
@pytest.mark.parametrize(("prefix", "part"), [("greedy_support", 22), ("greedy_two_epochs", 23)])
def test_greedy_choice_comparisons_set_the_preset_against_the_part_before(
    prefix: str, part: int, name: str, seed: int
) -> None:
    """Parts 23 and 24 change only the greedy choice: ``general`` is the preset by name
    (today's), and ``general-partN`` the preset of the part before, spelt out field by field."""
    data = tomllib.loads((EXPERIMENT_DIR / f"{prefix}_{name}.toml").read_text())
    by_name = {s["name"]: s for s in data["strategy"]}
    assert by_name["general"] == {"name": "general", "preset": "general"}
    assert _spelt_out(by_name[f"general-part{part}"]) == general_as_of(part)
    assert data["experiment"]["baseline"] == f"general-part{part}"
    assert data["experiment"]["seed"] == seed


@pytest.mark.parametrize(
    ("prefix", "part", "seed"),
    [
        ("greedy_ties_classic", 24, 25101),
        ("greedy_ties_mountaincar", 24, 25101),
        ("greedy_ancestors_classic", 26, 27101),
        ("greedy_ancestors_mountaincar", 26, 27102),
        ("tie_trial_classic", 29, 30101),
        ("tie_trial_mazes", 29, 30102),
        ("trial_avoid_mazes", 31, 31108),
        ("split_pairs_classic", 35, 36101),
        ("split_pairs_mazes", 35, 36102),
    ],
)
def test_greedy_tie_comparisons_set_the_preset_against_the_part_before(
    prefix: str, part: int, seed: int
) -> None:
    """Parts 25 and 27: ``general`` is the preset by name, ``general-partN`` the preset of the
    part before, spelt out field by field; each file's default seed is its fresh set."""
    data = tomllib.loads((EXPERIMENT_DIR / f"{prefix}.toml").read_text())
    by_name = {s["name"]: s for s in data["strategy"]}
    assert by_name["general"] == {"name": "general", "preset": "general"}
    assert _spelt_out(by_name[f"general-part{part}"]) == general_as_of(part)
    assert data["experiment"]["baseline"] == f"general-part{part}"
    assert data["experiment"]["seed"] == seed


def test_every_preset_change_has_the_bench_s_description(monkeypatch: pytest.MonkeyPatch) -> None:
    """``bench/bench_preset_parts.py`` times each part of ``GENERAL_CHANGES`` and refuses to run
    when one has no description (it did so after part 27 until part 30)."""
    bench = Path(__file__).resolve().parents[2] / "bench"
    monkeypatch.syspath_prepend(str(bench))  # the bench imports its neighbour bench_general
    path = bench / "bench_preset_parts.py"
    spec = importlib.util.spec_from_file_location("bench_preset_parts", path)
    assert spec is not None
    assert spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert set(module.PARTS) == set(GENERAL_CHANGES)
    assert all(isinstance(text, str) and text for text in module.PARTS.values())
