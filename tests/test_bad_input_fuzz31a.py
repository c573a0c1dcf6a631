"""Fuzz 31a, cases C1-C5 and D1 (issue 35), by class.

* C1: a number has its own dtype's precision and a list its least precise entry's (``fusion._validation.given_dtype``,
  ``fusion._limits.entry_dtypes``): an ``np.float16``/``np.float32`` scalar beside Python numbers is not held to
  float64's tolerance (``PublishedValues`` per entry; weights by the whole list: ``check_simplex``,
  ``effective_sample_size``, ``GaussianMixture``, ``fuse_mixtures_batch``'s ``eps0``, ``grid_log_normaliser``).
* C2, C3: a mapping argument is read once (``fusion._guards.read_mapping``) and its checked values are what the
  function computes with (``late_means``, ``glue_all``).
* C4: ``fusion._guards.read_once`` reads a ``collections.abc.Sequence`` that is not a list, tuple or array once, as the
  list of its entries (its functions, and ``record_status``, ``belief_study``'s ``sigma``).
* C5: mixtures whose objective leaves the range are refused naming ``gms`` (``means``/``covs``), every optimiser.
* D1: entries whose numerics underflow by design run under their own ``np.errstate(under="ignore")``
  (``fusion._guards.own_underflow``: ``run_network_study``, ``run_tracking_batch``).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion._guards import read_once
from fusion._validation import given_dtype

HYP = settings(max_examples=15, deadline=None)


class Flip(Mapping):
    """Valid values on the first read of each key, NaN afterwards (a mapping read twice)."""

    def __init__(self, d):
        self.d, self.seen = d, set()

    def __getitem__(self, k):
        if k in self.seen:
            return np.full_like(np.asarray(self.d[k], float), np.nan)[()]
        self.seen.add(k)
        return self.d[k]

    def __iter__(self):
        return iter(self.d)

    def __len__(self):
        return len(self.d)


class FlipSeq(Sequence):
    """A sequence without ``__array__`` whose entries turn NaN after one full pass (a sequence read twice)."""

    def __init__(self, items):
        self.items, self.seen = list(items), set()

    def __len__(self):
        return len(self.items)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[j] for j in range(*i.indices(len(self)))]
        if i < 0:
            i += len(self)
        if i >= len(self):
            raise IndexError(i)
        if len(self.seen) == len(self.items):
            v = self.items[i]
            return [float("nan")] * len(v) if isinstance(v, list) else float("nan")
        self.seen.add(i)
        return self.items[i]


# --- C1: each number its own precision, a list its least precise entry's ------------------------------------------

def test_c1_given_dtype_is_the_least_precise_float_entry():
    f16, f32 = np.float16(1), np.float32(1)
    assert given_dtype([f16, 2.0]) == np.float16
    assert given_dtype([f32, 2, 3.0]) == np.float32
    assert given_dtype([f32, [f16, 1.0]]) == np.float16
    assert given_dtype([f32, np.float64(1)]) == np.float32
    assert given_dtype([1.0, 2]) is None
    assert given_dtype([np.int32(1), np.int64(2)]) == np.int64
    assert given_dtype([f16, "x"]) is None


@HYP
@given(st.integers(1, 300), st.sampled_from([np.float16, np.float32]), st.booleans())
def test_c1_published_scalar_beside_python_numbers(k, kind, as_int):
    from fusion.book.ledger import PublishedValues as PV

    q = k / 10
    other = 7 if as_int else 7.5
    pv = PV([kind(q), other], [q, other], [1, 1])  # refused on float64's tolerance before (fuzz 31a C1)
    assert pv.status() == "reproduced"
    assert pv.published[1] == other


def test_c1_published_entries_keep_their_own_precision():
    from fusion.book.ledger import PublishedValues as PV

    h = np.float16(1.1)
    assert PV([h, 2], [1.1, 2], 1).published == (float(h), 2.0)
    assert PV([h, 1234.56], [1.1, 1234.56], [1, 2]).published[1] == 1234.56  # a Python float: float64's rule
    with pytest.raises(ValueError, match=r"published\[1\] = 1.15 has more decimals than decimals\[1\]"):
        PV([h, 1.15], [1.1, 1.2], 1)
    with pytest.raises(ValueError, match=r"published\[0\] = .* is a float16 that cannot hold"):
        PV([np.float16(1234.5), 1.5], [1234.5, 1.5], 1)


def test_c1_weights_mixing_short_floats_and_python_numbers():
    from fusion.estimates.mixtures import GaussianMixture
    from fusion.filtering.particles import effective_sample_size
    from fusion.optimise.simplex import check_simplex
    from fusion.scenarios.two_mixtures import grid_log_normaliser

    e = check_simplex([np.float32(0.1)] * 9 + [0.1])
    assert e.sum() == pytest.approx(1.0, abs=1e-15)
    third = [np.float16(1 / 3), np.float16(1 / 3), 1 / 3]
    ess = effective_sample_size(third)
    assert 2.99 < ess <= 3.0
    gm = GaussianMixture(third, np.zeros((3, 1)), np.ones((3, 1, 1)))
    assert float(np.sum(gm.weights)) == pytest.approx(1.0, abs=1e-15)
    gms = [GaussianMixture([1.0], np.zeros((1, 2)), np.eye(2)[None]) for _ in range(2)]
    ln = grid_log_normaliser(gms, [[np.float16(0.3), 0.7]], limit=3.0, n=8)
    assert np.isfinite(ln.log_z).all()
    with pytest.raises(ValueError, match="eps must lie on the simplex"):
        check_simplex([np.float16(0.5), 0.6])  # off by 0.1: refused at every precision
    with pytest.raises(ValueError, match="eps0 must lie on the simplex"):
        from fusion.estimates.chernoff import fuse_mixtures_batch
        fuse_mixtures_batch(np.ones((1, 2, 1)), np.zeros((1, 2, 1, 2)), np.broadcast_to(np.eye(2), (1, 2, 1, 2, 2)),
                            [np.random.default_rng(0)], 20, eps0=[np.float16(0.5), 0.6], optimiser="none")


def test_c1_fuse_mixtures_batch_eps0_mixed_list_is_exact():
    from fusion.estimates.chernoff import fuse_mixtures_batch

    w, m = np.ones((1, 2, 1)), np.zeros((1, 2, 1, 2))
    c = np.broadcast_to(np.eye(2), (1, 2, 1, 2, 2))
    r = fuse_mixtures_batch(w, m, c, [np.random.default_rng(0)], 20, eps0=[np.float16(0.3), 0.7], optimiser="none")[0]
    h = float(np.float16(0.3))
    assert r.eps0.tolist() == pytest.approx([h / (h + 0.7), 0.7 / (h + 0.7)], abs=1e-15)  # 0.7 not rounded to float16


# --- C2, C3: a mapping read once, its checked values used ---------------------------------------------------------

def test_c2_late_means_computes_with_the_checked_arrays():
    from fusion.scenarios.infrared_radar import late_means

    t, r = np.arange(5.0), np.arange(20.0).reshape(5, 4)
    want = late_means({"a": r}, t)
    assert late_means({"a": pd.DataFrame(r)}, t) == want
    assert late_means({"a": r.tolist()}, t) == want
    assert late_means(Flip({"a": r}), t) == want


def test_c3_glue_all_glues_what_it_checked(monkeypatch):
    import myst_nb

    from fusion.book.glue import glue_all

    got = []
    monkeypatch.setattr(myst_nb, "glue", lambda k, v, display=True: got.append((k, v)))
    glue_all(Flip({"x-a": 1.5, "x-b": 2}))
    glue_all(Flip({"x-c": 1.25}), decimals=1)
    assert got == [("x-a", 1.5), ("x-b", 2), ("x-c", 1.2)]


def test_c3_read_mapping():
    from fusion._guards import read_mapping

    d = {"a": 1}
    assert read_mapping(d, "m") is d
    assert read_mapping([1], "m") == [1]
    f = Flip({"a": 1.0})
    out = read_mapping(f, "m")
    assert type(out) is dict and out == {"a": 1.0}

    class Bad(Flip):
        def __getitem__(self, k):
            raise RuntimeError("boom")

    with pytest.raises(TypeError, match="m could not be read as a mapping"):
        read_mapping(Bad({"a": 1}), "m")


# --- C4: a sequence read once --------------------------------------------------------------------------------------

def test_c4_read_once_materialises_sequences_only():
    lst, tup = [1.0, 2.0], (1.0, 2.0)
    assert read_once(lst, "x") is lst and read_once(tup, "x") is tup
    assert read_once("ab", "x") == "ab"
    assert read_once(FlipSeq([1.0, 2.0]), "x") == [1.0, 2.0]
    assert read_once(FlipSeq([[1.0], [2.0]]), "x") == [[1.0], [2.0]]
    assert read_once(range(3), "x") == [0, 1, 2]
    with pytest.raises(ValueError, match="x has 1e\\+12 entries, beyond the input budget"):
        read_once(range(10**12), "x")


def test_c4_functions_read_a_sequence_once():
    from fusion.book.rulebook import record_status
    from fusion.readings.correlated import gauss_markov_gap
    from fusion.scenarios import time_registration as tr

    assert np.array_equal(tr.truth(FlipSeq([1.0, 2.0, 3.0])), tr.truth([1.0, 2.0, 3.0]))
    src, dst = [0.0, 1.0, 2.0], [0.5, 1.5]
    want = tr.two_point_remainder(np.array(src), np.array(dst))
    assert np.array_equal(tr.two_point_remainder(FlipSeq(src), np.array(dst)), want)
    assert np.array_equal(tr.two_point_remainder(np.array(src), FlipSeq(dst)), want)
    H = [[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]
    R = np.diag([1.0, 2.0, 3.0])
    assert gauss_markov_gap(FlipSeq(H), R, np.random.default_rng(0), 5) == gauss_markov_gap(
        np.array(H), R, np.random.default_rng(0), 5)
    readings = [("open-choice", "reproduced", None)]
    assert record_status("reproduced", FlipSeq(readings), None, False) == record_status("reproduced", readings, None,
                                                                                        False)


# --- C5: an objective beyond the range names the mixtures ---------------------------------------------------------

def _far(scale):
    from fusion.estimates.mixtures import GaussianMixture

    cov = np.stack([np.eye(2)] * 2)
    return [GaussianMixture([0.5, 0.5], np.array([[scale, 0.0], [-scale, 0.0]]), cov),
            GaussianMixture([0.5, 0.5], np.array([[0.0, scale], [0.0, -scale]]), cov)]


@pytest.mark.parametrize("optimiser", ["pso", "slsqp"])
def test_c5_fuse_mixtures_names_gms(optimiser):
    from fusion.estimates.chernoff import fuse_mixtures
    from fusion.optimise.swarm import SwarmOptions

    with pytest.raises(ValueError, match=r"^gms gives a derived quantity that is refused: the mixtures' log-densities"):
        fuse_mixtures(_far(1e100), np.random.default_rng(0), 50, optimiser=optimiser,
                      swarm_options=SwarmOptions(iterations=3))
    r = fuse_mixtures(_far(3.0), np.random.default_rng(0), 50, optimiser=optimiser,
                      swarm_options=SwarmOptions(iterations=3))
    assert np.isfinite(r.objective)


@pytest.mark.parametrize("optimiser", ["pso", "slsqp", "newton", "none"])
def test_c5_fuse_mixtures_batch_names_means(optimiser):
    from fusion.estimates.chernoff import fuse_mixtures_batch
    from fusion.optimise.swarm import SwarmOptions

    w = np.full((1, 2, 2), 0.5)
    m = np.array([[[[1e100, 0], [-1e100, 0]], [[0, 1e100], [0, -1e100]]]])
    c = np.broadcast_to(np.eye(2), (1, 2, 2, 2, 2))
    with pytest.raises(ValueError, match=r"^means gives a derived quantity that is refused"):
        fuse_mixtures_batch(w, m, c, [np.random.default_rng(0)], 50, optimiser=optimiser,
                            swarm_options=SwarmOptions(iterations=3))


# --- D1: underflow by design, whatever the caller's error state ---------------------------------------------------

def test_d1_network_study_under_a_raising_errstate():
    from fusion.scenarios import fusion_networks as fnw

    nodes = (fnw.NetworkNode((800.0, 700.0), "bearing"), fnw.NetworkNode((1000.0, 1050.0), "range"))
    sc = fnw.NetworkScenario("tiny", nodes, n_particles=30, n_samples=30, n_components=2, em_iterations=2, stages=1)
    want = fnw.run_network_study(sc, 1, 2)
    with np.errstate(all="raise"):
        got = fnw.run_network_study(sc, 1, 2)
        assert np.geterr()["under"] == "raise"  # the caller's state is restored
    assert repr(got) == repr(want)


def test_c3_every_mapping_checked_then_read_is_read_once():
    from fusion.book.chapters.ofs.readings import FAMILIES, family_mae
    from fusion.book.chapters.ofs_fair import fault_shapes_table
    from fusion.scenarios.wavelet_sensors import CONFIGS, config_label

    cfg = dict(CONFIGS[0] if isinstance(CONFIGS, (list, tuple)) else next(iter(CONFIGS.values())))
    assert config_label(Flip(cfg)) == config_label(cfg)
    z = np.random.default_rng(0).normal(900.0, 1.0, (2, 5, 12))
    want = family_mae(z)
    got = family_mae(z, Flip(dict(FAMILIES)))
    assert list(got) == list(want) and all(np.array_equal(got[k], want[k]) for k in want)
    rng = np.random.default_rng(1)
    errs = {m: rng.normal(1.0, 0.1, 120) for m in ("optimal_fusion_set", "mean", "median", "ew_variance")}
    table = fault_shapes_table({"s": errs}, seed=1)
    assert fault_shapes_table(Flip({"s": Flip(errs)}), seed=1).equals(table)
    assert fault_shapes_table({"s": {k: v.tolist() for k, v in errs.items()}}, seed=1).equals(table)  # C2: lists


def test_c4_scenario_entries_read_a_sequence_once():
    from fusion.scenarios.thermocouples import inject_failure

    z = np.full((100, 10), 900.0)
    want = inject_failure(z, [4, 10], (50, 80), (4.0, 8.0))
    assert np.array_equal(inject_failure(z, [4, 10], FlipSeq([50, 80]), (4.0, 8.0)), want)
