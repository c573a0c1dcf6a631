"""Fuzz 43: a legal ``len()`` of ``sys.maxsize`` is refused by name as any other lying ``len()`` (C3), a window
longer than the samples (C1), a producer's covariances symmetric for its reader (C4) and a super-linear run cost
counted as such (C2)."""

from __future__ import annotations

import sys
import time
from collections.abc import Mapping

import numpy as np
import pytest


def _refused_fast(f, *args, match: str, **kw) -> None:
    t = time.process_time()
    with pytest.raises(ValueError, match=match):
        f(*args, **kw)
    assert time.process_time() - t < 1.0


class _HugeLen(Mapping):
    """Two items, ``len()`` ``sys.maxsize`` (a legal length: islice's stop ``len()`` + 1 overflowed)."""

    def __len__(self):
        return sys.maxsize

    def __iter__(self):
        return iter(["a", "b"])

    def __getitem__(self, k):
        return 1


def test_c3_read_mapping_len_maxsize_is_the_documented_value_error():
    from fusion._validation import read_mapping
    _refused_fast(read_mapping, _HugeLen(), "m", match=r"m has len\(\) .* beyond the input budget")


def test_c3_public_caller_len_maxsize():
    from fusion.scenarios.lecture_weighting.readings_benchmark import seed_stability
    _refused_fast(seed_stability, _HugeLen(), match=r"results has len\(\) .* beyond the input budget")


def _fast(f, *args, **kw):
    t = time.process_time()
    out = f(*args, **kw)
    assert time.process_time() - t < 1.0
    return out


def test_c1_window_beyond_samples_same_numbers_without_padding():
    from fusion.readings import wavelet as wv
    rng = np.random.default_rng(0)
    X = rng.normal(size=(100, 64))
    Y = X + 0.1 * rng.normal(size=X.shape)
    same = wv.variance_estimates(X, Y, np.ones(100), "window", window=64)
    for w in (65, 10**7):   # 10**7 padded each row to 10**7 samples: a raw MemoryError (7.45 GiB)
        got = _fast(wv.variance_estimates, X, Y, np.ones(100), "window", window=w)
        np.testing.assert_array_equal(got, same)


def test_c1_fuse_denoised_window_beyond_samples():
    from fusion.readings import wavelet as wv
    rng = np.random.default_rng(1)
    X = rng.normal(size=(60, 3, 32))
    D = X + 0.1 * rng.normal(size=X.shape)
    a = wv.fuse_denoised(X, D, variance="window", window=32)
    b = _fast(wv.fuse_denoised, X, D, variance="window", window=10**7)
    np.testing.assert_array_equal(a.fused, b.fused)


def test_c1_variance_study_window_beyond_samples():
    import dataclasses
    from fusion.scenarios import wavelet_sensors as ws
    kw = dict(length=64, runs=20, readings=("window",), seed=3)
    a = ws.variance_study(window=64, **kw)
    b = _fast(ws.variance_study, window=10**7, **kw)   # a raw MemoryError (5.96 GiB) before
    for f in dataclasses.fields(a):
        if f.name != "window":
            np.testing.assert_array_equal(getattr(a, f.name), getattr(b, f.name), err_msg=f.name)
    assert b.window == 10**7


@pytest.mark.parametrize("seed, sigma_range", [(1, 5000.0), (2, 5000.0), (1, 50000.0)])
def test_c4_cartesian_round_trip_at_a_large_range_noise(seed, sigma_range):
    # was "P1i must be symmetric" ("P1 ..." at 50,000 m); since fuzz 45a C3 refused by the producer naming sim: the
    # radar's Cartesian track is not accurate there (its split off by 4.7e-6 of its scale at 5,000 m, 1.4e-3 at 50,000
    # m; against the recursion in long double its Pd is off by 3.1e-6 and 1.1e-3, above 1e-6)
    from fusion.scenarios import infrared_radar as m
    sim = m.simulate(np.random.default_rng(seed), runs=20, sigma_range=sigma_range)
    with pytest.raises(ValueError, match=r"^sim \(its sigma_range\) and velocity_sigma too large for the model's noise"):
        m.cartesian_tracks(sim)


def test_c4_symmetrised_only_where_a_reader_refuses():
    # the accepted range noises no longer reach an asymmetry above 1e-9 (2,000 m: 1.2e-10), so one step of a track at
    # 1,000 m is made asymmetric by 1e-8 of its largest entry: that step alone is symmetrised, the others kept
    from fusion._results import trusted
    from fusion.filtering.tracks import _symmetric_parts
    from fusion.scenarios import infrared_radar as m
    sim = m.simulate(np.random.default_rng(1), runs=5, sigma_range=1000.0)
    radar = m.cartesian_tracks(sim).radar
    Pd = np.array(radar.Pd)
    Pd[3, 0, 1] += 1e-8 * np.abs(Pd[3]).max()
    # the private constructor: the class itself refuses the asymmetric part a recursion can return
    t = _symmetric_parts(trusted(type(radar), z=radar.z, gains=radar.gains, est=radar.est, Pd=Pd, Pi=radar.Pi))
    for P in (t.Pd, t.Pi, t.gains.P):
        asym = np.abs(P - np.swapaxes(P, -1, -2)).max(axis=(-2, -1))
        assert (asym <= 1e-9 * np.abs(P).max(axis=(-2, -1))).all()
    assert (t.Pd[3] == t.Pd[3].T).all()
    np.testing.assert_array_equal(np.delete(t.Pd, 3, axis=0), np.delete(radar.Pd, 3, axis=0))


class _Ran(Exception):
    pass


def _ran(*a, **k):
    raise _Ran


def test_c2_scaling_study_counts_its_dense_algebra(monkeypatch):
    """At n = 1,000 a run of rs = (2, 3) ran 9.6 CPU-s but was counted 0.3 s: 30 runs (about 290 CPU-s) were accepted.
    Refused at once now; n = 700 (counted 4.9e8 a run): two runs accepted, three refused; the book's call accepted."""
    from fusion.book.chapters import chernoff_scaling as cs

    _refused_fast(cs.scaling_study, 1, rs=(2, 3), n=1000, runs=30, match=r"^rs, n and runs ask for")
    _refused_fast(cs.scaling_study, 1, rs=(2, 3), n=700, runs=3, match=r"^rs, n and runs ask for")
    monkeypatch.setattr(cs.np.random, "default_rng", _ran)
    for call in (lambda: cs.scaling_study(1, rs=(2, 3), n=700, runs=2), lambda: cs.scaling_study(1)):
        with pytest.raises(_Ran):
            call()


@pytest.mark.parametrize("value", [np.longdouble("1e-400"), __import__("fractions").Fraction(1, 10**400),
                                   __import__("decimal").Decimal("1e-400")])
def test_d1_formatters_state_the_float_range_at_the_lower_end(value):
    """The printing formatters apply no rule-2 bound (they print 1e-200 and 5e-324): a value below the float range
    is refused stating the float range's lower end, not rule 2's 1e-150."""
    from fusion.book import tables
    from fusion.book.chapters.lecture import sci
    assert sci(1e-200) and sci(5e-324)
    for f in (sci, tables.sci):
        with pytest.raises(ValueError,
                           match=r"magnitude at least 2\.2e-308 \(or zero\), the float range.s normal numbers") as info:
            f(value)
        assert "1e-150" not in str(info.value)
    assert tables.rounded(value) == 0.0  # rounded to decimals, it is exactly zero (fuzz 45 D1)


@pytest.mark.parametrize("value, shown", [
    (np.clongdouble(np.longdouble("1e400")), r"np\.clongdouble\('1e\+400\+0j'\)"),
    (np.clongdouble(np.longdouble("1e-400") + 1j), r"np\.clongdouble\('1e-400\+1j'\)"),
    (np.longdouble("1e400"), r"np\.longdouble\('1e\+400'\)"),
])
def test_d2_glue_all_refuses_a_longdouble_beyond_float_range_by_its_range(value, shown):
    """A finite (complex) longdouble beyond the float range is refused by the range rule, showing the value given
    (the complex one was refused as "must be finite", or showing its real part)."""
    from fusion.book.glue import glue_all
    with pytest.raises(ValueError, match=r"^values\['k'\] must be a number within float's range .*got " + shown):
        glue_all({"k": value})
