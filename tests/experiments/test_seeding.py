"""Common random seeds."""

from __future__ import annotations

from experiments.seeding import derive_seeds, run_seed


def test_run_seed_is_stable_and_independent_of_run_count():
    seeds = [run_seed(7, i) for i in range(5)]
    assert seeds == [run_seed(7, i) for i in range(5)]
    assert len(set(seeds)) == 5
    assert run_seed(8, 0) != run_seed(7, 0)


def test_derived_seeds_differ_and_repeat():
    seeds = derive_seeds(123)
    assert seeds == derive_seeds(123)
    assert seeds.env != seeds.agent
    assert derive_seeds(124) != seeds
