"""Fuzz 42a (the package outside the book layer): a caller's ``len()`` bounds what is read (C1), a budget counts every
loop a function runs, weighted by its measured cost (C2-C7), a valid producer's output is a valid reader's input (C8),
and an in-range input never raises a raw OverflowError (C9)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from functools import partial

import numpy as np
import pytest

from _helpers import ShrinkingLen as _ShrinkingLen  # one helper for fuzz 41a and 42a
from _helpers import refused_quickly

from fusion._limits import MAX_WORK


class _Lying(Sequence):
    """``len()`` is 3; ``__getitem__`` answers up to index ``n`` (never raising for ``n=None``)."""

    def __init__(self, n):
        self.n = n

    def __len__(self):
        return 3

    def __getitem__(self, i):
        if self.n is not None and i >= self.n:
            raise IndexError(i)
        return 1.0


@pytest.mark.parametrize("n", [10**8, None])
def test_lying_sequence_read_at_most_one_past_its_len(n):
    """C1: read_once read a Sequence whose len() is 3 through its __getitem__ until IndexError (1e8 entries, 24 CPU-s;
    an endless one for ever); now one entry past len() is read and the call refused naming the argument."""
    from fusion.readings.fusion_set import fuse_epochs
    from fusion.scenarios import infrared_radar

    refused_quickly(partial(infrared_radar.late_means, {"a": np.ones((3, 4))}, _Lying(n)), ValueError, r"^t has len\(\) 3 but more")
    refused_quickly(partial(fuse_epochs, _Lying(n), "mean"), ValueError, r"^x has len\(\) 3 but more")


def test_honest_and_short_sequences():
    """C1: an honest Sequence is read as its list; one with fewer items than its len() is refused by name."""
    from fusion.readings.fusion_set import fuse_epochs

    assert fuse_epochs(_Lying(3), "mean").values.tolist() == [1.0]
    refused_quickly(partial(fuse_epochs, _Lying(2), "mean"), ValueError, r"^x has len\(\) 3 but 2 items")


def test_lying_mapping_read_at_most_one_past_its_len():
    """C1: read_mapping read a Mapping's items until its iterator ended (an endless one for ever)."""
    from fusion._guards import read_mapping

    class Endless(Mapping):
        def __len__(self):
            return 1

        def __iter__(self):
            i = 0
            while True:
                yield i
                i += 1

        def __getitem__(self, k):
            return 1.0

    refused_quickly(partial(read_mapping, Endless(), "scenarios"), ValueError, r"^scenarios has len\(\) 1 but more")


def test_variance_change_study_counts_each_change_step():
    """C2: a change's fixed ~0.7 ms step was not counted: 50,000 changes at the smallest draws (1 run x 20 samples x 3
    sensors) were accepted and ran 36.9 CPU-s. Now 14,000 are refused at once; 13,500 (9.3 CPU-s) pass the budget
    and reach the next check (a change_at outside the samples, named)."""
    from fusion.scenarios.lecture_weighting.regime import variance_change_study

    def changes(c):
        return [(f"c{i}", {0: 2.0}) for i in range(c)]

    kw = dict(sigma=(1.0, 1.0, 1.0), samples=20, runs=1)
    refused_quickly(partial(variance_change_study, changes=changes(14_000), change_at=10, **kw), ValueError, r"^runs, samples, sigma and changes ask for 1.02e\+09 units")
    refused_quickly(partial(variance_change_study, changes=changes(13_500), change_at=20, **kw), ValueError, r"^change_at")


class _Flip:
    """An ``own`` whose ``__array__`` gives 3 SDs on its first call and ``N`` after."""

    def __init__(self, N):
        self.calls, self.N = 0, N

    def __array__(self, dtype=None, copy=None):
        self.calls += 1
        a = np.ones(3 if self.calls == 1 else self.N)
        return a if dtype is None else a.astype(dtype)


def test_coupling_study_runs_the_case_it_counted():
    """C3: own was converted 1 + grid + 1 times: counted at N = 3, run at N = 2,000 (46.5 CPU-s). Now converted once
    and run as counted."""
    from fusion.scenarios.correlated_sensors import coupling_study

    own = _Flip(2000)
    s = coupling_study({"a": {"own": own, "coupling": np.ones(3), "env": 1.0}}, runs=2, env_grid=(0.0, 1.0))
    assert own.calls == 1 and s.rows[0]["N"] == 3


class _Growing(Mapping):
    """A mapping of 1 case on its first iteration and 60 after."""

    def __init__(self):
        self.iters = 0

    def _n(self):
        return 1 if self.iters <= 1 else 60

    def __iter__(self):
        self.iters += 1
        return iter([f"c{i}" for i in range(self._n())])

    def __len__(self):
        return self._n()

    def __getitem__(self, k):
        return {"own": (1.0, 2.0, 3.0), "coupling": (0.5, 0.5, 0.5), "env": 1.0}


@pytest.mark.parametrize("study", ["coupling_study", "estimated_covariance_study"])
def test_correlated_studies_read_the_mapping_once(study):
    """C3 (and C6, which shares the reader): the mapping was iterated again after its cases were counted, so 60 cases
    of N = 1,000 counted as one ran 48.6 CPU-s. Now its cases are read once and what runs is what was counted."""
    from fusion.scenarios import correlated_sensors as cs

    m = _Growing()
    kw = dict(runs=2, env_grid=(0.0, 1.0)) if study == "coupling_study" else dict(ns=(10,), reps=2)
    s = getattr(cs, study)(m, **kw)
    assert m.iters == 1 and len(s.rows) == 1


def _cases(c, N=3):
    return {f"c{i}": {"own": np.linspace(1.0, 3.0, N), "coupling": np.ones(N), "env": 1.0} for i in range(c)}


def test_estimated_covariance_study_sums_its_cases():
    """C6 (a): each case was counted alone and without its fixed ~0.76 ms step: 20,000 cases of N = 3 (ns=(10, 30),
    reps=400) were accepted and ran 38.6 CPU-s. Now 253,000 units a case (since fix 72b, a step over ns weighed 17
    LOOP_STEP: 221,000 before), summed: 3,953 are refused at once; 3,952 (about 7.3 CPU-s at 1.85 ms a case) pass the
    budget and reach a bad 3,953rd case, named."""
    from fusion.scenarios.correlated_sensors import estimated_covariance_study

    kw = dict(ns=(10, 30), reps=400)
    refused_quickly(partial(estimated_covariance_study, _cases(3953), **kw), ValueError, r"^scenarios \(their sensors\), ns and reps ask for 1e\+09 units")
    refused_quickly(partial(estimated_covariance_study, {**_cases(3952), "wide": _cases(1, N=10)["c0"]}, **kw), ValueError, r"^ns must exceed the number of sensors \(10\) of case 'wide'")


def test_estimated_covariance_study_counts_before_any_covariance():
    """C6 (b): every case's N x N covariance was built before the first count: 16 cases of N = 9,400 were refused
    after 6.5 CPU-s. Now the first case is refused, before its covariance."""
    from fusion.scenarios.correlated_sensors import estimated_covariance_study

    refused_quickly(partial(estimated_covariance_study, _cases(16, N=9400), ns=(9401,), reps=2), ValueError, r"^scenarios \(their sensors\), ns and reps ask for 1.66e\+12 units")


class _Ran(Exception):
    pass


def _ran(*args, **kwargs):
    raise _Ran


def test_benchmark_counts_every_key_pair_work(monkeypatch):
    """C4: the checked AWF's n x n pair work (6 units a pair element) was counted for one key only: 12 keys of 1 run x
    3,300 samples x 100 sensors were accepted (1.8e8 units by the readings) and ran 32.8 CPU-s. Now every key's: 6
    keys (1.19e9 units) are refused at once, 5 (9.9e8, about 5-13 CPU-s) pass the budget and reach their first key."""
    from fusion.scenarios.lecture_weighting import readings_benchmark as rbm

    kw = dict(runs=1, samples=3300, levels=(0.0,), sigma=tuple(np.linspace(1.0, 2.0, 100)))
    refused_quickly(partial(rbm.benchmark, seeds=(1, 2, 3), faults=(False, True), **kw), ValueError, r"^seeds, levels, faults, runs, samples and sigma ask for 1.19e\+09 units .*6 x 1 x 3,300")
    monkeypatch.setattr(rbm, "_snapshot_errors", _ran)
    with pytest.raises(_Ran):
        rbm.benchmark(seeds=(1, 2, 3, 4, 5), faults=(False,), **kw)


class _ArrayOnly:
    """Variances with only ``__array__`` (no len, no shape)."""

    def __init__(self, v):
        self.v = np.asarray(v, dtype=float)

    def __array__(self, dtype=None, copy=None):
        return self.v if dtype is None else self.v.astype(dtype)


class _Growing2:
    """``len()`` 2; ``__array__`` gives 2 variances on its first call and ``N`` after."""

    def __init__(self, N):
        self.calls, self.N = 0, N

    def __len__(self):
        return 2

    def __array__(self, dtype=None, copy=None):
        self.calls += 1
        a = np.array([1.0, 4.0]) if self.calls == 1 else np.linspace(1.0, 4.0, self.N)
        return a if dtype is None else a.astype(dtype)


def test_learning_study_reads_each_set_once():
    """C5: each r_sets entry was read 4 times (_sigmas, asarray, len, array): one with only __array__ raised a raw
    TypeError "has no len()"; one giving 2 variances and then 3,000 was counted at 2 and drew (200, 2000, 3000) (raw
    MemoryError). Now each is converted once and run as converted."""
    from fusion.scenarios.lecture_weighting.learning import learning_study

    kw = dict(runs=2, epochs=20, last=10)
    s = learning_study(r_sets=(_ArrayOnly([1.0, 4.0]), (1.0, 2.0, 3.0)), **kw)
    assert repr(s.rows) == repr(learning_study(r_sets=((1.0, 4.0), (1.0, 2.0, 3.0)), **kw).rows)  # NaN: by repr
    g = _Growing2(5)
    assert list(learning_study(r_sets=(g,), **kw).learned) == [2] and g.calls == 1


def test_learning_study_counts_each_set_by_its_variances():
    """C5 (the same reading): a set's work was counted as runs x epochs whatever its variances, so 1,000 sensors of 2
    runs x 2,000 epochs counted 1e5 units (0.33 CPU-s run). Now 15 units a reading of each set: 17 sets of 1,000 to
    1,016 sensors (1.03e9 units) are refused at once; 16 (9.7e8, about 5 CPU-s) pass the budget and reach the next
    check (two sets of one size, named)."""
    from fusion.scenarios.lecture_weighting.learning import learning_study

    def sets(k):
        return [np.linspace(1.0, 4.0, n) for n in range(1000, 1000 + k)]

    refused_quickly(partial(learning_study, r_sets=sets(17), runs=2, epochs=2000), ValueError, r"^r_sets, runs and epochs ask for 1.03e\+09 units")
    refused_quickly(partial(learning_study, r_sets=sets(16) + [(1.0, 2.0), (1.0, 3.0)], runs=2, epochs=2000), ValueError, r"^r_sets must hold sets of different sizes")


def test_awf_study_counts_the_length_of_ks():
    """C7: len(ks) sets the (runs, len(ks), n) running means and every curve at two levels, uncounted: ks = [100] *
    200,000 of 500 runs raised a raw MemoryError after 17.6 CPU-s. Now its memory and work (12 units a level, run and
    entry, measured) are counted: refused at once; 416,666 entries of 100 runs pass the budget and reach the next
    check (a k_compare outside ks, named)."""
    from fusion.scenarios.lecture_weighting.estimators import awf_study

    refused_quickly(partial(awf_study, ks=[100] * 200_000, runs=500), ValueError, r"^runs, ks and sigma ask for an array")
    refused_quickly(partial(awf_study, ks=[100] * 416_667, runs=100), ValueError, r"^ks and runs ask for 1e\+09 units")
    refused_quickly(partial(awf_study, ks=[100] * 416_666, runs=100, k_compare=99), ValueError, r"^k_compare must be one of ks")


def test_infrared_readers_take_a_negative_range_estimate():
    """C8: a valid simulation at sigma_range = 1,000 m has range estimates below 0 (min about -1,220 m); rule_errors,
    rmse_by_rule and cartesian_tracks refused it naming an inner "r (range)" (none of their arguments), position its
    range_est likewise. A negative range estimate is a filter's valid output: the position formula applies (the point
    through the origin), its error is large and finite."""
    from fusion.scenarios import infrared_radar as ir

    sim = ir.simulate(np.random.default_rng(0), runs=50, sigma_range=1000.0)
    assert sim.radar_range.est[..., 0].min() < 0 and sim.radar_range.z[..., 0].min() < 0
    errors = ir.rule_errors(sim)
    assert all(np.isfinite(e).all() for e in errors.values())
    assert all(np.isfinite(e).all() for e in ir.rmse_by_rule(sim).values())
    assert np.isfinite(ir.cartesian_tracks(sim).radar.est).all()
    p = ir.position(np.array([[-5.0, 0.0]]), np.array([[0.1, 0.0, 0.2, 0.0]]))
    np.testing.assert_allclose(p, -ir.position(np.array([[5.0, 0.0]]), np.array([[0.1, 0.0, 0.2, 0.0]])))
    with pytest.raises(ValueError, match=r"r \(range\) must be non-negative"):  # a coordinate: still refused
        ir.spherical_to_cartesian(-5.0, 0.1, 0.2)


def test_slip_steps_band_squares_beyond_the_float_range():
    """C9: (r / (p - h))**2 on floats raised a raw OverflowError at in-range inputs (rmse 1e150, published just above
    half a unit; decimals 17 with rmse 1e145). The band is now computed exactly beyond the float range."""
    from fractions import Fraction

    from fusion.scenarios.two_sensor import slip_steps_band

    lo, hi = slip_steps_band(1e150, 0.5000001)
    assert lo <= hi and hi == int(Fraction(1e150 / (0.5000001 - 0.5)) ** 2)
    lo, hi = slip_steps_band(1e145, 1.5e-17, decimals=17)
    assert 0 < lo <= hi
    assert slip_steps_band(3.0, 1.0) == (5, 36)  # within the float range: as before


def test_wavelet_studies_count_the_list_they_run():
    """C12 and C14: mechanism_study counted configs by a second len() and iterated the argument (600 configs counted
    as 1 ran 35.2 CPU-s); signal_study likewise its signals. Now the list read is what is counted and run."""
    from fusion.scenarios import wavelet_sensors as ws

    refused_quickly(partial(ws.mechanism_study, configs=_ShrinkingLen(list(ws.CONFIGS) * 60)), ValueError, r"^configs, runs, gains and length ask for")
    refused_quickly(partial(ws.signal_study, signals=_ShrinkingLen(list(ws.SIGNALS) * 20)), ValueError, r"^signals, modes, normalisers, runs, gains and length ask for")


def test_variance_study_counts_its_readings():
    """C14: each reading runs a pass over the draws (93 us a reading at 2 runs x 4 sensors x 64 samples, up to ~10
    units a sample), uncounted: 450,000 readings were accepted and ran 46.2 CPU-s. Now refused at once by their
    number; with the draws, 83,000 passes (82,999 readings and the oracle, about 8 CPU-s) are accepted and reach the
    next check (a bad mode, named), one more is refused."""
    from fusion.scenarios.wavelet_sensors import variance_study

    kw = dict(runs=2, length=64)
    refused_quickly(partial(variance_study, readings=["batch"] * 450_000, **kw), ValueError, r"^readings ask for 4.5e\+09 units")
    refused_quickly(partial(variance_study, readings=["batch"] * 83_000, **kw), ValueError, r"^readings, runs, gains and length ask for 1e\+09 units")
    refused_quickly(partial(variance_study, readings=["batch"] * 82_999, mode="medium", **kw), ValueError, r"^mode")


class _Window(Sequence):
    """A pair (first, last) of samples: ``a`` on its first read, ``b`` after."""

    def __init__(self, a, b):
        self.a, self.b, self.n = a, b, 0

    def __len__(self):
        return 2

    def __getitem__(self, i):
        if i == 0:
            self.n += 1
        return (self.a if self.n <= 1 else self.b)[i]


def test_paired_study_reads_the_failure_once():
    """C11: failure["samples"] was read by random_failure (the failure injected on samples 50-80) and again for the
    record (window (1, 100) and the member shares of that window: plausible wrong numbers). Now read once."""
    from fusion.scenarios import thermocouples as T

    M = {"o": {"method": "optimal_fusion_set"}, "m": {"method": "mean"}}
    plain = T.paired_study(1, 3, M, failure={"samples": (50, 80)})
    r = T.paired_study(1, 3, M, failure={"samples": _Window((50, 80), (1, 100))})
    assert r.window == plain.window == (50, 80) and r.failed_member_share == plain.failed_member_share


def test_late_means_counts_a_converted_value_not_its_shape():
    """C13: a value whose class says shape (2, 4) and whose __array__ gives (2**22, 4) was counted as 8 entries: 100
    such methods ended in a raw MemoryError after 17.1 CPU-s. Now every value that is not an ndarray, list or tuple is
    counted as converted: refused naming rmse once the arrays held pass the memory budget."""
    from fusion.scenarios import infrared_radar as ir

    K = 2**20
    B = np.ones((K, 4))

    class Lying:
        shape = (2, 4)

        def __array__(self, dtype=None, copy=None):
            return B

    refused_quickly(partial(ir.late_means, {f"a{i}": Lying() for i in range(70)}, np.arange(K) * 0.1), ValueError, r"^rmse \(its methods and scans\) ask for an array of 2.73e\+08 elements")


def _bench_results(seeds, methods):
    a = np.ones(3)
    return {(s, 0.0, False): {f"m{i}": a for i in range(methods)} for s in range(1, seeds + 1)}


def test_seed_stability_has_a_budget(monkeypatch):
    """C10: seed_stability had no budget and looped over the pairs of methods in Python (3,500 methods of 2 seeds ran
    51.4 CPU-s). Now vectorised and counted before any array is converted (3 units a pair, 1,000 a method, 2,000 a
    seed, measured): 14 seeds of 5,000 methods (1.12e9 units) are refused at once, 12 (9.6e8) pass; 7,000 methods
    are refused by the memory of their (m, m) pair arrays."""
    from fusion.scenarios.lecture_weighting import readings_benchmark as rbm

    refused_quickly(partial(rbm.seed_stability, _bench_results(14, 5000)), ValueError, r"^results \(its scenarios, seeds and methods\) ask for 1.12e\+09 units")
    refused_quickly(partial(rbm.seed_stability, _bench_results(2, 7000)), ValueError, r"^results \(its methods\) ask for an array")
    monkeypatch.setattr(rbm, "_tied_ranks", _ran)
    with pytest.raises(_Ran):
        rbm.seed_stability(_bench_results(12, 5000))


def test_seed_stability_is_unchanged_by_the_vectorised_pairs():
    """C10: the pairs' counts, computed by a Python loop before, are the same numbers vectorised (a small case
    counted by hand: m0 < m1 < m2 resolved at the first seed, the second seed reverses m1 and m2)."""
    from fusion.scenarios.lecture_weighting.readings_benchmark import seed_stability

    z = np.zeros(4)
    res = {(1, 0.0, False): {"m0": z + 1.0, "m1": z + 2.0, "m2": z + 3.0},
           (2, 0.0, False): {"m0": z + 1.0, "m1": z + 3.0, "m2": z + 2.0}}
    s = seed_stability(res)
    assert (s.n_sig, s.n_rev, s.n_stable, s.seeds) == (3, 1, 0, (1, 2))
    np.testing.assert_array_equal(s.ranks[(0.0, False)], [[1, 2, 3], [1, 3, 2]])


def test_variance_change_study_reads_a_change_mapping_within_its_len():
    """Fuzz 42a D1 (the class of C1): a change's {sensor: SD} Mapping was iterated to its end (an endless one for
    ever); now at most len() + 1 pairs are read and a len() that lies is refused by name."""
    from fusion.scenarios.lecture_weighting.regime import variance_change_study

    class Endless(Mapping):
        def __len__(self):
            return 1

        def __iter__(self):
            while True:
                yield 0

        def __getitem__(self, k):
            return 2.0

    refused_quickly(partial(variance_change_study, sigma=(1.0, 1.0, 1.0), samples=20, runs=1, change_at=10, changes=[("c", Endless())]), ValueError, r"^changes has len\(\) 1 but more")


def test_scale_sweep_accepts_the_sweep_reading_it_serves(monkeypatch):
    """Fuzz 42b C6: the optimal fusion set's measured cost (42-385,151 units an epoch at 3-900 readings) was counted
    1.6-2.1x (20 a reading, 1 a pair), so the reseeding sweep's 10x reading of yang-weights-reasonable (9 scales of
    5,000 runs, 6.7 CPU-s) was refused. At 14 a reading and 1/2 a pair it passes (8.6e8 units); 5,001 runs are
    refused at once (by fuse_epochs' own limit of each method, 20 units a pair)."""
    from fusion.scenarios import thermocouples as tc

    scales = (0.125, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0)  # chapter 01's SCALES
    refused_quickly(partial(tc.scale_sweep, 777, 5001, scales), ValueError, r"^n_runs, n_samples, n_sensors and methods")
    monkeypatch.setattr(tc, "simulate", _ran)
    for failure, window in ((None, None), ({}, (50, 80))):
        with pytest.raises(_Ran):
            tc.scale_sweep(777, 5000, scales, failure=failure, window=window)


def test_architecture_study_counts_its_steps():
    """Fuzz 42b D1: architecture_study's steps (6.3-6.6 ms each whatever the runs, measured) were not counted, so 2
    runs at T = 0.01 s (26,100 steps, about 170 CPU-s) counted 1e8 units. Now counted, within the function's entry of
    STUDY_WORK (the sweep's 10x reading of ci-fig4-convex-part, 1.08e9 units, 10.9 CPU-s), named by its key."""
    from fusion.scenarios.two_sensor import architecture

    R = np.diag([2500.0, 900.0])
    Q = np.diag([0.0, 1.0, 0.0, 1.0])
    refused_quickly(partial(architecture.architecture_study, np.random.default_rng(0), R, R, Q, runs=2, nees_runs=2, T=0.01), ValueError, r"^runs, nees_runs and T ask for 1.83e\+10 units .*STUDY_WORK: the reseeding sweep's primary "
                        r"of ci-fig4-convex-part")
