"""Fuzz 35a (issue 35), fixed in fix36a: the study cache's views, object arrays' precision, swarm options, EM init.

* C1/D2: a cached result never shares memory with anything a caller can write: an array that does not own its
  data (a view of an argument, a column of a local array) is kept as a read-only copy (in process and on disk).
* C4: an object array (or object Series) of numbers has the precision of its entries read as a list
  (``fusion._entries.given_dtype``; ``fusion._limits.entry_dtypes``/``integer_entries`` likewise).
* C5: a SwarmOptions subclass is read by the fields SwarmOptions declares (check_swarm_options, keywords).
* C6: the swarm's work budget is checked at the mixture fusion's entry, naming ``swarm_options``.
* D4 (decided: refuse): a fit with dropped components as ``init`` of more components is refused, saying why."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion.book import study_cache as sc_mod
from fusion.book.study_cache import study_cache


@study_cache(8)
def _tail(x):
    return x[1:]


@study_cache(8)
def _first_col(n):
    a = np.arange(float(2 * n)).reshape(n, 2)
    return {"col": a[:, 0], "t": [a.T]}


@pytest.mark.parametrize("disk", [False, True])
def test_c1_a_view_of_the_argument_is_not_shared_with_the_caller(tmp_path, monkeypatch, disk):
    monkeypatch.delenv(sc_mod.LOG_ENV, raising=False)
    if disk:
        monkeypatch.setenv(sc_mod.ENV, str(tmp_path / "c"))
    else:
        monkeypatch.delenv(sc_mod.ENV, raising=False)
    _tail.cache_clear()
    x = np.array([1.0, 2.0, 3.0])
    _tail(x)
    x[1] = 99.0                                # the caller's own array stays writeable, its edit stays its own
    again = _tail(np.array([1.0, 2.0, 3.0]))
    assert again.tolist() == [2.0, 3.0] and not again.flags.writeable
    assert not np.shares_memory(again, x)
    if disk:
        _tail.cache_clear()                    # loaded from the disk: the values computed
        assert _tail(np.array([1.0, 2.0, 3.0])).tolist() == [2.0, 3.0]


def test_d2_the_base_of_a_returned_view_is_not_writeable_through_the_result(monkeypatch):
    monkeypatch.delenv(sc_mod.ENV, raising=False)
    _first_col.cache_clear()
    for _ in range(3):   # each caller writes through what it was given (the first gets the function's own dict)
        r = _first_col(3)
        for arr in (r["col"], r["t"][0]):
            for owner in (arr, arr.base):
                if isinstance(owner, np.ndarray) and owner.flags.writeable:   # a bytes base (fuzz 37a C1): immutable
                    owner.flat[0] = -1.0
        assert _first_col(3)["col"].tolist() == [0.0, 2.0, 4.0]


# ---------------------------------------------------------------- C4: object arrays' numbers keep their own precision
_SCALARS = st.lists(st.sampled_from([np.float16(1 / 3), np.float32(0.1), 0.25, np.float64(0.5), 3, np.int32(2)]),
                    min_size=1, max_size=6)


@settings(max_examples=40, deadline=None, derandomize=True)
@given(_SCALARS)
def test_c4_an_object_array_has_its_list_precision(entries):
    from fusion._entries import given_dtype, input_eps

    as_list = given_dtype(entries)
    for boxed in (np.array(entries + [None], dtype=object)[:-1], pd.Series(entries, dtype=object)):
        assert given_dtype(boxed) == as_list and input_eps(boxed) == input_eps(entries)


@pytest.mark.parametrize("box", [lambda v: np.array(v, dtype=object), lambda v: pd.Series(v, dtype=object)])
def test_c4_object_arrays_of_float32_judged_as_their_list(box):
    from fusion.book.rulebook import judge_paired
    from fusion.filtering.particles import effective_sample_size
    from fusion.optimise.simplex import check_simplex

    a, b = [np.float32(0.3)] * 100, [np.float32(0.2)] * 100
    assert judge_paired(box(a), box(b), "equal", 0.1).status == judge_paired(a, b, "equal", 0.1).status == "reproduced"
    assert np.allclose(np.asarray(check_simplex(box([np.float32(0.1)] * 10)), float), 0.1)
    assert effective_sample_size(box([np.float16(1 / 3)] * 3)) == pytest.approx(3.0)


def test_c4_published_entries_of_an_object_array_keep_their_dtypes():
    from fusion._limits import entry_dtypes, integer_entries

    given = np.array([np.float32(0.1), 0.1, 3], dtype=object)
    assert entry_dtypes(given, 3) == [np.dtype(np.float32), np.dtype(np.float64), np.dtype(np.float64)]
    assert integer_entries(given, 3) == [False, False, True]


# ---------------------------------------------------------------- C5: a SwarmOptions subclass is read by its declared fields
def _mixtures():
    from fusion.estimates.mixtures import GaussianMixture

    gA = GaussianMixture(np.array([0.4, 0.6]), np.array([[0.0, 0.0], [1.0, 1.0]]), np.stack([np.eye(2)] * 2))
    gB = GaussianMixture(np.array([1.0]), np.array([[0.5, 0.0]]), np.eye(2)[None] * 1.5)
    return [gA, gB]


def test_c5_a_subclass_with_an_extra_field_is_read_by_the_declared_fields():
    import dataclasses

    from fusion.estimates.chernoff import fuse_mixtures
    from fusion.optimise.swarm import SwarmOptions, check_swarm_options

    @dataclasses.dataclass(frozen=True)
    class MyOptions(SwarmOptions):
        note: str = "tuned"

    @dataclasses.dataclass(frozen=True)
    class Lax(SwarmOptions):   # skips the checks of its base
        def __post_init__(self) -> None:
            pass

    mine = MyOptions(n_particles=4, iterations=2)
    assert check_swarm_options(mine) == SwarmOptions(n_particles=4, iterations=2)
    assert "note" not in mine.keywords()
    fu = fuse_mixtures(_mixtures(), np.random.default_rng(0), 40, optimiser="pso", swarm_options=mine)
    assert np.isfinite(fu.eps).all() and fu.swarm is not None
    with pytest.raises(ValueError, match=r"^swarm_options\.iterations"):
        check_swarm_options(Lax(iterations=-3))


# ---------------------------------------------------------------- C6: the swarm's budget names swarm_options
@pytest.mark.parametrize("field, size", [("iterations", 10**6), ("n_particles", 10**7)])
def test_c6_the_swarm_budget_refusal_names_swarm_options(field, size):
    from fusion.estimates.chernoff import fuse_mixtures, fuse_mixtures_batch
    from fusion.optimise.swarm import SwarmOptions

    big = SwarmOptions(**{field: size})
    gms = _mixtures()
    with pytest.raises(ValueError, match=rf"^swarm_options\.iterations and swarm_options\.n_particles"):
        fuse_mixtures(gms, np.random.default_rng(0), 50, optimiser="pso", swarm_options=big)
    w, m, c = (np.stack([x, x]) for x in (np.array([0.5, 0.5]), np.zeros((2, 2)), np.stack([np.eye(2)] * 2)))
    with pytest.raises(ValueError, match=rf"^swarm_options\.iterations and swarm_options\.n_particles"):
        fuse_mixtures_batch(w[None], m[None], c[None], [np.random.default_rng(0)], 50, swarm_options=big)


# ---------------------------------------------------------------- D4: a fit with dropped components as init
def test_d4_a_fit_with_dropped_components_is_refused_as_init_saying_why():
    from fusion.estimates.mixtures import weighted_em, weighted_em_batch

    x = np.random.default_rng(1).normal(size=(100, 2))
    w = np.full(100, 1e-300)
    w[0] = 1.0
    fit = weighted_em(x, w, 3, np.random.default_rng(0))
    k = fit.mixture.weights.size
    assert k < 3   # the documented drop
    with pytest.raises(ValueError, match=rf"^init must have 3 components, got {k}: a fit whose components were dropped"):
        weighted_em(x, np.ones(100), 3, np.random.default_rng(0), init=fit.mixture)
    with pytest.raises(ValueError, match=r"^init\[0\] must have 3 components, got .*dropped"):
        weighted_em_batch(x[None], np.ones((1, 100)), 3, [np.random.default_rng(0)], init=[fit.mixture])
    again = weighted_em(x, np.ones(100), k, np.random.default_rng(0), init=fit.mixture)   # the documented way on
    assert again.mixture.weights.size <= k
