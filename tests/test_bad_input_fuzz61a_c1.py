"""Fuzz 61a C1: a sequence whose LENGTH alone sets the budget is counted by len() before any entry is read.

Each function below converted (and hashed for a repeat check) every entry before its budget, which needs only the
number of entries: 10**7 entries (the input ceiling, ``fusion._counts.MAX_COUNT``) were refused only after 25-48
CPU-s. The budget now comes first ("length -> budget -> entries"); the inputs are built outside the timing.
"""

from __future__ import annotations

import numpy as np
import pytest

from _helpers import refused_quickly

N = 10**7   # MAX_COUNT: the most entries a sequence argument may hold


@pytest.fixture(scope="module")
def many() -> list[float]:
    """10**7 distinct weights in (0, 1), built once, outside every timing."""
    return np.linspace(0.001, 0.999, N).tolist()


@pytest.fixture(scope="module")
def paired_inputs():
    from fusion.book.chapters.ci import studies as S
    Q, R1, R2 = S.printed_covariances()
    return (R1, R2, Q, S.step_weights(S.SEED), S.unequal_pair(S.SEED), S.aniso_pair(S.SEED, 20)), S


def test_paired_studies_counts_fig6_omegas_by_length(many, paired_inputs):
    """47.5 CPU-s before (every weight read by unit_scalar and hashed by distinct): refused at once, by its names."""
    from fusion.book.chapters.ci.constants import W_GRID, W_PUB
    from fusion.book.chapters.ci.paired import paired_studies
    args, S = paired_inputs
    om = [W_PUB, W_GRID] + many[:N - 2]
    refused_quickly(lambda: paired_studies(*args, runs=20, seeds=(1, 2, 3), weight_seed=S.SEED, fig6_omegas=om,
                                           T=S.SOURCE_T), ValueError, "runs, fig6_omegas, T and aniso")


def test_paired_studies_parts_closed_form():
    """The fixed weights' CI fusions counted as (omegas + 1) times one, the sum the per-weight tuple gave; the book's
    two weights at 20 runs accepted, 10**7 weights counted at once."""
    import time

    from fusion.book._study_budget import studies_first
    from fusion.book.chapters.ci.paired import _STUDY_RULES, _paired_studies_parts
    from fusion.filtering.tracks import _fuse_tracks_units
    parts = _paired_studies_parts(20, 21, 20, 21, 5, "runs")
    fused = 2 * _STUDY_RULES + ("ci",) * 6
    assert parts[3]() == sum(_fuse_tracks_units(21, 20, 4, rule) for rule in fused)
    assert studies_first(_paired_studies_parts(20, 21, 20, 21, 2, "runs"), "runs") > 0
    t = time.process_time()
    assert parts[3]() > 0 and _paired_studies_parts(20, 21, 20, 21, N, "runs")[3]() > 0
    assert time.process_time() - t < 0.1


def test_architecture_studies_counts_fixed_omegas_by_length(many):
    """32.8 CPU-s before (every weight read by scalar and compared): refused at once, by its names; the book's
    two further weights accepted by the same budget."""
    from fusion.book.chapters.ci import studies as S
    from fusion.book.chapters.ci.architecture import _arch_budget, architecture_studies
    Q, R1, R2 = S.printed_covariances()
    assert _arch_budget(1.0, 20, 20, 2, "runs") > 0
    refused_quickly(lambda: architecture_studies(R1, R2, Q, (1, 2), 0.9999, 20, 20, fixed_omegas=many),
                    ValueError, "runs, nees_runs, T and fixed_omegas")


@pytest.mark.parametrize("sweep", ["sizes", "opposite", "spreads"])
def test_fair_study_counts_sweeps_by_length(many, sweep):
    """25.6 CPU-s a sweep before (every point read by scalar and hashed by distinct): refused at once naming the
    sweeps (spreads take points >= 1: the same count, read after the budget)."""
    from fusion.book.chapters.ofs_fair import fair_study
    refused_quickly(lambda: fair_study(1, n_runs=2, n_samples=2, **{sweep: many}), ValueError,
                    "n_runs, n_samples, n_sensors, the sweeps and methods")


def test_fair_study_counts_counts_by_length():
    """counts read as integers one by one: 10**7 of them refused by their number."""
    from fusion.book.chapters.ofs_fair import fair_study
    counts = [0] * N
    refused_quickly(lambda: fair_study(1, n_runs=2, n_samples=2, counts=counts), ValueError,
                    "n_runs, n_samples, n_sensors, the sweeps and methods")


def test_fair_study_entry_checks_kept():
    """The entries are still read after the budget: a negative size and a repeat refused by name."""
    from fusion.book.chapters.ofs_fair import fair_study
    with pytest.raises(ValueError, match=r"sizes\[1\]"):
        fair_study(1, n_runs=2, n_samples=2, sizes=(0, -1))
    with pytest.raises(ValueError, match="sizes"):
        fair_study(1, n_runs=2, n_samples=2, sizes=(1, 1))


def test_alpha_methods_counts_alphas_by_length(many):
    """30 CPU-s before (10**7 - 1 alphas read, printed and hashed, a repeat refused): refused at once naming alphas;
    the edge of its budget (450 units an alpha) accepted by the budget alone, one more refused."""
    from fusion._limits import MAX_WORK, work
    from fusion.book.chapters.ofs.readings import _ALPHA_UNITS, alpha_methods
    refused_quickly(lambda: alpha_methods(many), ValueError, "alphas")
    refused_quickly(lambda: alpha_methods(np.asarray(many)), ValueError, "alphas", cpu=2.0)
    edge = MAX_WORK // _ALPHA_UNITS
    assert work((edge,), "alphas", weight=_ALPHA_UNITS) <= MAX_WORK
    with pytest.raises(ValueError, match="alphas"):
        work((edge + 1,), "alphas", weight=_ALPHA_UNITS)
    assert len(alpha_methods((0.1, 0.5))) == 3


@pytest.mark.parametrize("which", ["ns", "ss"])
def test_cost_table_counts_cells_by_length(which):
    """2.8-3.2 CPU-s before (10**7 entries read by counts and hashed by distinct): refused at once naming ns and ss;
    the book's table accepted."""
    from fusion.book.chapters.chernoff_scaling import cost_table
    ints = list(range(1, N + 1))
    kw = {"ns": ints, "ss": (1,)} if which == "ns" else {"ns": (2,), "ss": ints}
    refused_quickly(lambda: cost_table(**kw), ValueError, "ns and ss")
    assert cost_table().shape == (4, 3)
    with pytest.raises(ValueError, match=r"ns\[1\]"):
        cost_table(ns=(2, 0))
