"""Layout suites: the shipped suite loads with a held-out split of other seeds, and bad suites are
refused by file and entry."""

from __future__ import annotations

from pathlib import Path

import pytest

from bullet_maze import FAMILIES, available_layouts, available_suites, load_layout, load_suite
from bullet_maze.suites import LayoutSuite


def test_the_shipped_suite_has_every_family_in_both_splits() -> None:
    assert "mazes" in available_suites()
    suite = load_suite("mazes")
    assert isinstance(suite, LayoutSuite)
    assert set(available_layouts()) <= set(suite.dev)
    for family in FAMILIES:
        assert sum(spec.startswith(f"{family}:") for spec in suite.dev) >= 2
        assert sum(spec.startswith(f"{family}:") for spec in suite.test) >= 2
    assert suite.split("dev") == suite.dev
    assert suite.split("test") == suite.test


def test_the_test_split_is_drawn_from_other_seeds() -> None:
    suite = load_suite("mazes")
    dev, test = suite.layouts("dev"), suite.layouts("test")
    assert not set(dev) & set(test)
    seeds = {
        split: {(lay.name.split(":")[0], lay.name.split(",")[0]) for lay in layouts}
        for split, layouts in (("dev", dev), ("test", test))
    }
    assert not seeds["dev"] & seeds["test"]
    # The same families and variants: a test layout differs from a dev one by its seed only.
    variants = {
        split: {_without_seed(s) for s in suite.split(split) if ":" in s} for split in seeds
    }
    assert variants["test"] <= variants["dev"]


def _without_seed(spec: str) -> str:
    family, _, rest = spec.partition(":")
    return family + ":" + ",".join(p for p in rest.split(",") if not p.startswith("seed="))


def test_a_suite_from_a_path_with_relative_layout_files(tmp_path: Path) -> None:
    (tmp_path / "mine.toml").write_text(
        "[arena]\nsize = [100.0, 100.0]\n[start]\nposition = [20.0, 20.0]\n"
        "[goal]\nposition = [80.0, 80.0]\nradius = 5.0\n"
    )
    path = tmp_path / "suite.toml"
    path.write_text('dev = ["mine.toml", "maze:seed=1"]\ntest = ["maze:seed=2"]\n')
    suite = load_suite(path)
    assert suite.name == "suite"
    assert load_layout(suite.dev[0]).arena == (100.0, 100.0)
    assert load_suite(str(path)) == suite


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ('dev = ["paper"]', r"missing field 'test'"),
        ('dev = ["paper"]\ntest = []', r"'test' must be a non-empty array"),
        ('dev = ["paper"]\ntest = "open"', r"'test' must be a non-empty array"),
        ('dev = ["paper"]\ntest = [3]', r"test\[0\] must be a layout spec \(a string\), got 3"),
        ('dev = ["paper"]\ntest = [""]', r"test\[0\] must be a layout spec"),
        ('dev = ["paper"]\ntest = ["open"]\ntrain = ["x"]', r"unknown field 'train'"),
        ('name = 3\ndev = ["paper"]\ntest = ["open"]', r"field 'name' must be a string"),
        ('dev = ["paper"]\ntest = ["nowhere"]', r"test\[0\] = 'nowhere': unknown maze"),
        ('dev = ["paper"]\ntest = ["rooms:door=3"]', r"test\[0\].*'door' = 3 must be"),
        ('dev = ["paper", "paper"]\ntest = ["open"]', r"dev\[1\] = 'paper' is the same layout"),
        (
            'dev = ["maze:seed=1"]\ntest = ["maze:seed=1,rows=6"]',
            r"test\[0\] = 'maze:seed=1,rows=6' is the same layout as dev\[0\]",
        ),
        (
            'dev = ["maze:seed=1"]\ntest = ["maze:seed=1,rows=7"]',
            r"test split's maze layouts reuse the development split's seed\(s\) \[1\]",
        ),
        ('dev = ["paper"]\ntest = ["missing.toml"]', r"test\[0\].*maze file not found"),
        ("dev = [", r"not valid TOML"),
    ],
)
def test_bad_suites_are_refused_by_file_and_entry(tmp_path: Path, text: str, match: str) -> None:
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(ValueError, match=match) as err:
        load_suite(path)
    assert str(path) in str(err.value)


@pytest.mark.parametrize(
    ("name", "error", "match"),
    [
        ("nowhere", ValueError, r"unknown suite 'nowhere': choose one of \['mazes'\]"),
        ("../mazes", ValueError, r"a suite name has no path separator"),
        ("", ValueError, r"a suite name"),
        (3, TypeError, r"suite must be a name or a path"),
        ("missing.toml", FileNotFoundError, r"suite file not found"),
    ],
)
def test_bad_suite_names(name: object, error: type[Exception], match: str) -> None:
    with pytest.raises(error, match=match):
        load_suite(name)  # type: ignore[arg-type]


def test_an_unknown_split_is_named() -> None:
    with pytest.raises(ValueError, match=r"unknown split 'train' of suite 'mazes'"):
        load_suite("mazes").split("train")
