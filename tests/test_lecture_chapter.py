"""Tests of chapter 02's package code (lecture notes §§2.1-2.4): guards, spread formula, learning limit, row-sum
weights, detection curve, operation counts, the scenarios and the chapter's claims."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from _helpers import one_computation
from fusion import readings as rd
from fusion.readings import weighting as wt
from fusion.scenarios import lecture_weighting as sc
from fusion.scenarios.lecture_weighting import CHECKED, LECTURE_GUARD_METHODS as GUARD_KEY, AwfMethod as M
from fusion.scenarios.lecture_weighting import BeliefKind as BK, RegimeMethod as RM, RegimeScenario as RS


# --------------------------------------------------------------------------- guards
def test_guards_on_a_row_with_a_negative_estimate():
    v = np.array([-0.5, 1.0, 2.0, 4.0])
    none = wt.inverse_variance_weights(v, guard="none")
    np.testing.assert_allclose(none, (1 / v) / np.sum(1 / v))
    assert np.any(none < 0) and np.isclose(none.sum(), 1.0)  # weights leave [0, 1]
    np.testing.assert_allclose(wt.inverse_variance_weights(v, guard="abs"), wt.optimal_weights(np.abs(v)))
    np.testing.assert_allclose(wt.inverse_variance_weights(v, guard="equal"), np.full(4, 0.25))
    floor = wt.inverse_variance_weights(v, guard="floor")
    assert floor[0] > 1 - 1e-9  # the floored sensor takes almost all the weight
    np.testing.assert_array_equal(floor, wt.inverse_variance_weights(v))  # floor is the default


@given(st.lists(st.floats(0.01, 100.0), min_size=2, max_size=6))
@settings(max_examples=50, deadline=None)
def test_all_guards_agree_on_positive_estimates(vals):
    v = np.array(vals)
    ref = wt.optimal_weights(v)
    for g in wt.GUARDS:
        np.testing.assert_allclose(wt.inverse_variance_weights(v, guard=g), ref, rtol=1e-12)


def test_guard_validation():
    with pytest.raises(ValueError, match="guard"):
        wt.inverse_variance_weights([1.0, 2.0], guard="clip")
    with pytest.raises(ValueError, match="zero"):
        wt.inverse_variance_weights([0.0, 2.0], guard="none")
    with pytest.raises(ValueError, match="sum to zero"):
        wt.inverse_variance_weights([-1.0, 1.0], guard="none")


def test_awf_passes_the_guard():
    X = 900 + np.random.default_rng(0).normal(size=(50, 4)) * [0.5, 1, 2, 4]
    r = wt.awf(X, "lecture", guard="abs")
    np.testing.assert_allclose(r.weights, wt.inverse_variance_weights(r.variances, guard="abs"))


# --------------------------------------------------------------------------- spread formula
def test_lecture_variance_sd_matches_monte_carlo_at_large_level():
    sig = np.array([0.5, 1.0, 2.0, 4.0])
    k, X = 100, 1000.0
    est = wt.running_variances(X + np.random.default_rng(1).normal(size=(2000, k, 4)) * sig, "lecture")[:, -1]
    pred = wt.lecture_variance_sd(X, k, sig**2)
    np.testing.assert_allclose(est.std(axis=0), pred, rtol=0.08)


def test_lecture_variance_sd_is_linear_in_level_and_validates():
    V = [1.0, 4.0, 9.0]
    np.testing.assert_allclose(wt.lecture_variance_sd(-20.0, 10, V), 2 * wt.lecture_variance_sd(10.0, 10, V))
    assert wt.lecture_variance_sd(0.0, [10, 20], V).shape == (2, 3)
    with pytest.raises(ValueError, match="k"):
        wt.lecture_variance_sd(1.0, 0, V)
    with pytest.raises(ValueError, match="n >= 2"):
        wt.lecture_variance_sd(1.0, 10, [1.0])


# --------------------------------------------------------------------------- learning limit
def test_learned_variance_limit_closed_form_and_monte_carlo():
    R = np.array([1.0, 4.0, 9.0])
    lim = wt.learned_variance_limit(R)
    np.testing.assert_allclose(lim, (1 - 2 / 3) * R + R.sum() / 9)
    Y = np.random.default_rng(2).normal(size=(400, 500, 3)) * np.sqrt(R)
    np.testing.assert_allclose(wt.learned_variances(Y)[:, -1].mean(axis=0), lim, rtol=0.03)
    # two sensors: both limits equal (the method reduces to the mean)
    l2 = wt.learned_variance_limit([1.0, 4.0])
    assert l2[0] == l2[1]
    # the corrected variances invert the limit exactly
    np.testing.assert_allclose(wt.corrected_variances(lim), R)


# --------------------------------------------------------------------------- row sums
def test_row_sum_weights_and_stacked_belief_matrices():
    x = np.random.default_rng(3).normal(size=(20, 4))
    B = rd.belief_matrices(x)
    np.testing.assert_allclose(B[5], rd.belief_matrix(x[5]))
    w = rd.row_sum_weights(B)
    np.testing.assert_allclose(w.sum(axis=1), 1.0)
    perm = np.array([2, 0, 3, 1])
    np.testing.assert_allclose(rd.row_sum_weights(rd.belief_matrix(x[0][perm])), w[0][perm])
    np.testing.assert_allclose(rd.row_sum_weights(np.ones((3, 3))), np.full(3, 1 / 3))
    with pytest.raises(ValueError, match="non-negative"):
        rd.row_sum_weights(-np.eye(2))
    with pytest.raises(ValueError, match="zero matrix"):
        rd.row_sum_weights(np.zeros((2, 2)))


# --------------------------------------------------------------------------- detection curve
def test_rejection_probability_rises_to_one():
    snap = np.random.default_rng(4).normal(size=(5000, 5)) * [0.5, 1, 1.5, 2, 4]
    eps = 3 * np.sqrt(2) * 4
    p = rd.rejection_probability(snap, 2, np.array([0.0, eps, 3 * eps]), eps)
    assert p[0] < 0.01 and p[2] > 0.99 and p[0] <= p[1] <= p[2]
    with pytest.raises(TypeError, match="sensor"):
        rd.rejection_probability(snap, 2.0, [0.0], eps)
    with pytest.raises(ValueError, match="sensor"):
        rd.rejection_probability(snap, 5, [0.0], eps)


# --------------------------------------------------------------------------- operation counts
def test_operation_counts():
    c = rd.operation_counts(6, 2)
    assert c == {"explicit": 776.0, "cholesky": 272.0, "ldl": 236.0, "eigen": 2216.0}
    big = rd.operation_counts(10**5, 2)
    assert big["explicit"] / big["ldl"] == pytest.approx(6.0, rel=1e-3)
    assert big["cholesky"] / big["ldl"] == pytest.approx(1.0, rel=1e-3)
    # the route as the lecture writes it (M = L⁻¹ formed): twice a Cholesky solve, a third of the explicit inverse
    w = rd.ldl_as_written_count(10**5, 2)
    assert big["explicit"] / w == pytest.approx(3.0, rel=1e-3) and big["cholesky"] / w == pytest.approx(0.5, rel=1e-3)
    assert rd.ldl_as_written_count(6, 2) == 6**3 / 3 * 2 + 36 * 3 + 2 * 6 * 4 + 8
    with pytest.raises(ValueError, match="N"):
        rd.ldl_as_written_count(0, 2)
    with pytest.raises(ValueError, match="N"):
        rd.operation_counts(0, 2)
    with pytest.raises(TypeError, match="d"):
        rd.operation_counts(6, 2.0)


# --------------------------------------------------------------------------- scenarios
def test_awf_study_oracle_and_guards():
    s = sc.awf_study(levels=(0.0, 100.0, 900.0), k_max=100, runs=200, ks=(10, 100), k_compare=100)
    bound = wt.minimum_variance(s.variances) / 100
    assert abs(s.mse[0.0][M.ORACLE][1] / bound - 1) < 3 * np.sqrt(2 / 200)
    for g in (*wt.GUARDS, "delete"):
        assert s.sq[900.0][GUARD_KEY[g]].shape == (200,)
    # the centred AWF does not depend on the level
    np.testing.assert_allclose(s.mse[0.0][M.AWF_CENTRED], s.mse[900.0][M.AWF_CENTRED], rtol=1e-6)
    # Graybill-Deal: the means weighted by their own sample variances, shift invariant, near the oracle
    np.testing.assert_allclose(s.err[0.0][M.GRAYBILL_DEAL], s.err[900.0][M.GRAYBILL_DEAL], atol=1e-9)
    assert np.mean(s.sq[900.0][M.GRAYBILL_DEAL]) < 0.5 * np.mean(s.sq[900.0][M.MEAN_OF_MEANS])


def test_benchmark_and_seed_stability():
    res = sc.benchmark(seeds=(1, 2), runs=30, samples=20)
    assert set(res) == {(sd, X, f) for sd in (1, 2) for X in (0.0, 900.0) for f in (False, True)}
    st_ = sc.seed_stability(res)
    n_m = len(st_.methods)
    for r in st_.ranks.values():
        assert r.shape == (2, n_m)
        for row in np.sort(r, axis=1):  # competition ranks: 1, then each the one before (a tie) or its place
            assert row[0] == 1 and all(row[i] in (row[i - 1], i + 1) for i in range(1, n_m))
    assert 0 <= st_.n_rev <= st_.n_sig
    # results keyed by method keys, in BenchMethod's order, each with a display label in the style registry
    from fusion.book.style import METHOD_LABELS

    assert list(res[1, 0.0, False]) == list(sc.BenchMethod) == list(st_.methods)
    assert all(m in METHOD_LABELS and METHOD_LABELS[m] != m for m in sc.BenchMethod)
    # shift invariance: every method but the lecture's AWF gives the same errors at 0 and 900
    a, b = res[1, 0.0, False], res[1, 900.0, False]
    np.testing.assert_allclose(a[sc.BenchMethod.AWF_CENTRED], b[sc.BenchMethod.AWF_CENTRED], rtol=1e-6, atol=1e-9)


def test_seed_stability_ranks_methods_equal_up_to_round_off_as_tied():
    """One tie rule (``fusion._limits.ROUND_OFF_TIE``, the rulebook's): two methods whose MSEs differ by round-off
    share the better rank, whatever the order of their round-off; a real difference still orders them."""
    res = sc.benchmark(seeds=(1,), runs=30, samples=20, levels=(900.0,), faults=(False,))
    m = list(res[1, 900.0, False])
    a, b = m[0], m[1]
    base = res[1, 900.0, False]
    ranks = []
    for eps in (1e-13, -1e-13, 1e-3):
        tweaked = {1: dict(base)}
        tweaked[1][b] = base[a] * (1.0 + eps)
        st_ = sc.seed_stability({(1, 900.0, False): tweaked[1]})
        ranks.append(st_.ranks[(900.0, False)][0])
    i, j = 0, 1
    assert ranks[0][i] == ranks[0][j] == ranks[1][i] == ranks[1][j]  # tied either way round
    assert ranks[2][j] == ranks[2][i] + 1  # 1e-3 apart: ordered


def test_chapter_records_cover_every_critique_box():
    from fusion.book.claims import claims_dir, load
    from fusion.book.ledger import SOURCES

    cf = load(claims_dir() / "lecture003.yaml")
    chapters = list(SOURCES["lecture003"].chapters)
    assert [sum(r.headline for r in cf.records if r.chapter == c) for c in chapters] == [1, 0, 0]
    boxes = {"notebooks/02_lecture_weighting": ("lec-crit-awf-var", "lec-crit-ls-bias", "lec-crit-consistency",
                                                "lec-crit-belief"),
             "notebooks/03_lecture_wavelets": ("lec-crit-wavelet",)}
    for chapter, want in boxes.items():
        recs = [r for r in cf.records if r.chapter == chapter]
        labels = {r.link for r in recs} | {x for r in recs for x in r.critiques}
        assert set(want) <= labels, chapter


def _small_studies() -> dict:
    return {"s21": sc.awf_study(levels=(0.0, 900.0), k_max=100, runs=100, ks=(10, 100)),
            "s22": sc.learning_study(epochs=200, runs=20), "s23": sc.consistency_study(runs=100, curve_draws=500),
            "s24": sc.belief_study(snapshots=200), "sreg": sc.regime_study(samples=200, runs=100, change_at=100),
            "s24b": sc.belief_parameter_study(snapshots=200), "bench": sc.benchmark(seeds=(9001, 9002, 9003), runs=100,
                                                                                  samples=20),
            "llc": sc.learned_limit_check(draws=200), "slumv": sc.lumv_study(runs=400),
            "schg": sc.variance_change_study(samples=200, runs=100, change_at=100), "ssym": sc.symmetry_study(runs=20)}


def test_chapter_02_ledger_from_the_claims_file():
    from fusion.book.chapters import lecture_weighting as ch
    from fusion.book.claims import build_ledger

    st = _small_studies()
    tail = sc.tail_study(runs=2000, chunk=1000)
    ev = ch.evidence(st)
    led = build_ledger("lecture003", "notebooks/02_lecture_weighting", ev,
                       values={**ch.ledger_values(st), **ch.glue_tail(tail)})
    byid = {c.id: c for c in led.claims}
    assert set(byid) == set(ch.EVIDENCE)
    # the literal AWF is judged on the lecture's criterion, its MSE infinite (declared), the guards on finite MSEs
    est = ev["lec-awf-estimated"]
    assert est["primary"].infinite_mean == ("a",) and est["primary"].judgement().statistic == "infinite mean"
    assert all(est[f"guard-{g}"].infinite_mean == () for g in ch.READING_GUARDS)
    # the deletion guard's evidence is the study's deletion column, paired with the same baseline
    ft = ev["lec-awf-fault-tolerance"]["guard-delete"]
    np.testing.assert_allclose(ft.a, st["s23"].sq[sc.FaultCase.FAULT][M.AWF_LECTURE_DELETE])
    np.testing.assert_allclose(ft.b, st["s23"].sq[sc.FaultCase.FAULT][M.MEAN_OF_MEANS])
    with pytest.raises(ValueError, match="studies"):
        ch.evidence({})


def test_delete_weights():
    w = sc.delete_weights([[1.0, -2.0, 4.0], [-1.0, -1.0, -3.0], [0.0, 2.0, 2.0]])
    np.testing.assert_allclose(w[0], [0.8, 0.0, 0.2])
    np.testing.assert_allclose(w[1], [1 / 3] * 3)                     # none left: equal weights
    np.testing.assert_allclose(w[2], [0.0, 0.5, 0.5])                 # a zero estimate is dropped too
    w = sc.delete_weights([[1.0, 1.0, -1.0], [-1.0, -1.0, 2.0]], mask=[[False, True, True], [True, True, False]])
    np.testing.assert_allclose(w, [[0.0, 1.0, 0.0], [0.5, 0.5, 0.0]])  # only kept sensors, equal over the kept
    with pytest.raises(ValueError, match="mask"):
        sc.delete_weights([[1.0, 2.0]], mask=[[False, False]])
    with pytest.raises(ValueError, match="estimates"):
        sc.delete_weights([[np.nan, 1.0]])


def test_tail_study_shows_a_one_over_t_tail():
    t = sc.tail_study(runs=20000, chunk=5000, thresholds=(1.0, 10.0, 100.0))
    te = t.t_exceed
    assert np.all(te > 0) and te.max() / te.min() < 3           # t·P(|e| > t) flat: a 1/t tail, E|e| = ∞
    assert t.hill < 2                                         # heavy: no variance
    assert t.block_mse.max() / t.block_mse.min() > 3       # block MSEs do not settle
    with pytest.raises(ValueError, match="thresholds"):
        sc.tail_study(runs=100, thresholds=(0.0,))


def test_deletion_guard_hands_the_faulty_sensor_the_weight():
    s = sc.consistency_study(runs=100, curve_draws=200)
    f = s.sq[sc.FaultCase.FAULT]
    assert np.all(f[M.AWF_LECTURE_DELETE] > f[M.MEAN_OF_MEANS])        # the fault wins every run
    assert np.mean(f[M.CHECK_AWF_LECTURE_DELETE]) < np.mean(f[M.MEAN_OF_MEANS])   # the check repairs it


def test_awf_log_comparison_is_the_ratio_of_geometric_means():
    from fusion.book.chapters import lecture_weighting as ch

    s = sc.awf_study(levels=(0.0, 900.0), k_max=100, runs=120, ks=(10, 100), k_compare=100)
    c = ch.awf_log_comparison(s)
    a, b = s.sq[900.0][M.AWF_LECTURE_NONE], s.sq[900.0][M.MEAN_OF_MEANS]
    gm = np.exp(np.mean(np.log(a))) / np.exp(np.mean(np.log(b)))
    assert np.exp(c.interval()[0]) == pytest.approx(gm, rel=1e-9)
    assert c.runs == 120


# --------------------------------------------------------------------------- memory and regime (E2.1b)
def test_running_average_closed_forms():
    z = np.random.default_rng(5).normal(size=(30, 3))
    k = np.arange(1, 31)[:, None]
    np.testing.assert_allclose(wt.running_average(z, "growing", axis=0), np.cumsum(z, axis=0) / k)
    win = wt.running_average(z, "window", window=7, axis=0)
    for i in (0, 5, 6, 20, 29):
        np.testing.assert_allclose(win[i], z[max(0, i - 6):i + 1].mean(axis=0))
    lam = 0.8
    fg = wt.running_average(z, "forgetting", forgetting=lam, axis=0)
    for i in (0, 3, 29):
        a = lam ** np.arange(i, -1, -1.0)
        np.testing.assert_allclose(fg[i], a @ z[:i + 1] / a.sum())
    # the time axis can be any axis
    np.testing.assert_allclose(wt.running_average(z.T, "window", window=7, axis=-1), win.T)
    with pytest.raises(ValueError, match="forgetting"):
        wt.running_average(z, "forgetting", forgetting=1.0)
    with pytest.raises(ValueError, match="window"):
        wt.running_average(z, "window", window=0)


def test_tracking_variances_growing_matches_the_lecture_and_sample_is_the_variance():
    X = 3.0 + np.random.default_rng(6).normal(size=(2, 40, 4)) * np.array([0.5, 1.0, 2.0, 4.0])
    for e in ("lecture", "centred"):
        np.testing.assert_allclose(wt.tracking_variances(X, e), wt.running_variances(X, e), atol=1e-9)
    samp = wt.tracking_variances(X, "sample")
    np.testing.assert_allclose(samp[:, 24], X[:, :25].var(axis=1), atol=1e-9)
    win = wt.tracking_variances(X, "sample", "window", window=10)
    np.testing.assert_allclose(win[:, 39], X[:, 30:40].var(axis=1), atol=1e-9)


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 10_000), st.sampled_from(["growing", "forgetting", "window"]))
def test_cross_moments_cancel_a_common_signal_the_sample_variance_does_not(seed, memory):
    # noise-free sensors that all read the same time-varying signal: every cross-moment estimate
    # is exactly 0, while each sensor's own sample variance is the signal's variance
    s = np.random.default_rng(seed).normal(size=50).cumsum()
    X = np.repeat(s[:, None], 3, axis=1)
    for e in ("lecture", "centred"):
        np.testing.assert_allclose(wt.tracking_variances(X, e, memory, window=9), 0.0, atol=1e-9 * (1 + s.var() + s.mean() ** 2))
    samp = wt.tracking_variances(X, "sample", memory, window=9)
    np.testing.assert_allclose(samp[:, 0], wt.running_average(s**2, memory, window=9, axis=0)
                               - wt.running_average(s, memory, window=9, axis=0) ** 2, atol=1e-8 * (1 + s.var() + s.mean() ** 2))


def test_fuse_current_weights():
    X = np.random.default_rng(7).normal(size=(5, 4))
    np.testing.assert_allclose(wt.fuse_current(X, np.ones(4)), X.mean(axis=-1))
    V = np.array([0.25, 1.0, 4.0, 16.0])
    np.testing.assert_allclose(wt.fuse_current(X, V), X @ wt.optimal_weights(V))
    np.testing.assert_allclose(wt.fuse_current(X, 3 * V), wt.fuse_current(X, V))
    with pytest.raises(ValueError, match="variances"):
        wt.fuse_current(X, np.ones(3))


def test_growing_memory_lags_a_variance_change_forgetting_follows_it():
    # sensor 1: SD 0.5 for 100 samples, then 4; E[growing estimate at k] = (100·0.25 + (k−100)·16)/k
    rng = np.random.default_rng(8)
    sd = np.where(np.arange(200)[:, None] < 100, [0.5, 1.0, 2.0], [4.0, 1.0, 2.0])
    X = rng.normal(size=(400, 200, 3)) * sd
    grow = wt.tracking_variances(X, "centred")[:, -1, 0].mean()
    forget = wt.tracking_variances(X, "centred", "forgetting", forgetting=0.95)[:, -1, 0].mean()
    assert grow == pytest.approx((100 * 0.25 + 100 * 16.0) / 200, rel=0.05)
    assert forget == pytest.approx(16.0, rel=0.08)


def test_regime_study_oracle_and_scenarios():
    r = sc.regime_study(samples=200, runs=100, change_at=100, period=80.0, window=20, forgetting=0.9)
    assert r.scenarios == tuple(s[0] for s in sc.REGIME_SCENARIOS)
    smin = float(wt.minimum_variance(r.variances))
    constant = {name for name, sig, _ in sc.REGIME_SCENARIOS if sig == "constant"}
    for scen in r.scenarios:
        want = set(sc.REGIME_METHODS) - (set() if scen in constant else set(sc.REGIME_CONSTANT_ONLY))
        assert set(r.sq[scen]) == want
        assert r.sq[scen][RM.ORACLE].shape == (100,)
        # the oracle fuses current readings with the true weights: MSE = σ²min in every scenario
        assert np.mean(r.sq[scen][RM.ORACLE]) == pytest.approx(smin, rel=0.1)
    # at constant X nothing but the noise enters: the sample-variance weights do as well as the oracle
    assert np.mean(r.sq[RS.CONSTANT][RM.SAMPLE_GROWING]) == pytest.approx(smin, rel=0.15)
    # the oracle's weight of sensor 1 drops at the swap
    w = r.w_best[RS.SINE_SWAP][RM.ORACLE]
    assert w[50] > 0.5 > 0.05 > w[150]
    # the per-sample BLUE at constant X: its MSE at k is 1/Σ_i Σ_p σ_p(i)⁻² (the swap keeps Σ_p σ_p⁻²)
    k = np.arange(1, 201)[100:]
    analytic = np.mean(1.0 / (k * np.sum(1.0 / r.variances)))
    assert np.mean(r.sq[RS.CONSTANT_SWAP][RM.PER_SAMPLE_BLUE]) == pytest.approx(analytic, rel=0.2)
    # the shift-invariant estimators do not see the level of the sine; the lecture's does
    for m in (RM.CENTRED_GROWING, RM.DIFFERENCE_GROWING, RM.SAMPLE_GROWING):
        np.testing.assert_allclose(r.sq[RS.SINE_LEVEL][m], r.sq[RS.SINE][m], rtol=1e-6)
    assert np.mean(r.sq[RS.SINE_LEVEL][RM.LECTURE_GROWING]) > 2 * np.mean(r.sq[RS.SINE][RM.LECTURE_GROWING])
    # the lecture's estimates of the running means are positive in the window at X = 0: every guard agrees there
    assert set(r.n_nonpositive) == constant


def test_consistency_awf_guard_matches_awf_without_rejections():
    from fusion.readings import consistency as cs

    X = 900.0 + np.random.default_rng(9).normal(size=(3, 60, 4)) * np.array([0.5, 1.0, 2.0, 4.0])
    for g in ("floor", "abs", "equal"):
        # eps = inf keeps every reading: the check + AWF is the AWF with the same guard
        np.testing.assert_allclose(cs.consistency_awf(X, np.inf, "lecture", guard=g).awf.value,
                                   wt.awf(X, "lecture", guard=g).value, rtol=1e-9)
    assert not np.allclose(cs.consistency_awf(X, np.inf, guard="abs").awf.value,
                           cs.consistency_awf(X, np.inf, guard="floor").awf.value)


def test_belief_parameter_study_spreads():
    from fusion.book.chapters import lecture_weighting as ch

    r = sc.belief_parameter_study(snapshots=100, params=(0.5, 1.0, 2.0), grid=(0.5, 2.0))
    for kind in sc.BELIEF_KINDS:
        f = r.fused[kind]
        assert f.shape == (100, 3)
        np.testing.assert_allclose(r.spread[kind], np.abs(f[:, 0] - f[:, 2]))
        np.testing.assert_allclose(sc.belief_spread(r, kind, (0.5, 1.0, 2.0)), np.ptp(f, axis=1))
        assert np.all(np.isfinite(f))
    with pytest.raises(ValueError, match="values"):
        sc.belief_spread(r, BK.FUZZY, (4.0,))
    with pytest.raises(ValueError, match="grid"):
        sc.belief_parameter_study(snapshots=4, params=(0.5,), grid=(1.0,))
    # a very large scale, threshold or upper limit makes every reading trust every other: the plain mean
    big = sc.belief_parameter_study(snapshots=100, params=(1e6,), grid=(1e6,), seed=3, limit_scale=1e6)
    np.testing.assert_allclose(big.fused[BK.BINARY][:, 0], big.fused[BK.FUZZY][:, 0], atol=1e-4)
    np.testing.assert_allclose(big.fused[BK.FUZZY_LIMIT][:, 0], big.fused[BK.FUZZY][:, 0], atol=1e-4)
    c = ch.belief_parameter_comparison(r)
    assert c.runs == 100 and c.b_name.startswith("binary deletion rule")
    # with every reading trusting every other the fusion is the plain mean, whose squared error is sq_mean
    np.testing.assert_allclose(big.sq[BK.FUZZY][:, 0], big.sq_mean, atol=1e-4)
    # the unanimous deletion rule returns the plain mean almost always: its accuracy is reported beside the spread,
    # not used as a gate (review 1, F8): the rulebook judges the spread (R2), and here it contradicts the claim
    full = sc.belief_parameter_study(snapshots=200, seed=2404)
    unanimous = ch.belief_objectivity(full, BK.DELETION_ALL)
    assert unanimous.status() == "contradicted" and "reported, not a gate" in unanimous.metric
    ok = ch.belief_objectivity(full)
    assert ok.status() != "cannot be checked" and "RMSE" in ok.metric
    assert ch.belief_accuracy(full, BK.FUZZY, (0.5, 1.0, 2.0, 4.0)).status() == "reproduced"
    c2 = ch.belief_parameter_comparison(r, BK.DELETION, ((0.5, 1.0), (1.0, 2.0)), kind=BK.FUZZY_LIMIT)
    np.testing.assert_allclose(c2.a, sc.belief_spread(r, BK.FUZZY_LIMIT, (0.5, 1.0)))


def test_awf_sweep_matches_the_main_study_and_the_table_reads_its_intervals():
    """The level sweep reuses the study's noise: at X = 0 and 900 it reproduces the per-run errors of sq."""
    from fusion.book.chapters import lecture_weighting as ch2

    s = sc.awf_study(levels=(0.0, 900.0), k_max=100, runs=120, ks=(10, 100), k_compare=100)
    for X in (0.0, 900.0):
        for g in ("abs", "none"):
            np.testing.assert_allclose(s.sweep[X][GUARD_KEY[g]], s.sq[X][GUARD_KEY[g]], rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(s.sweep[X][M.MEAN_OF_MEANS], s.sq[X][M.MEAN_OF_MEANS], rtol=1e-9, atol=1e-12)
    tab = ch2.table_sweep(s)
    assert list(tab.index) == list(sc.SWEEP_LEVELS)
    assert set(tab["|σ̂²|"]) <= {"better", "worse", "not distinguishable"}
    c = ch2.sweep_comparisons(s)[900.0, "abs"]
    assert tab.loc[900.0, "|σ̂²|"] == {"reproduced": "better", "contradicted": "worse",
                                        "not distinguishable": "not distinguishable"}[c.status()]



# --------------------------------------------------------------------------- round-off in records
def test_roundoff_reports_the_bound_not_the_round_off():
    from fusion.book.tables import roundoff
    assert roundoff(1.7486e-15) == roundoff(1.7764e-15) == "less than 10⁻¹²"  # two BLAS kernels, one text
    assert roundoff(0.0) == "less than 10⁻¹²" and roundoff(3e-10, -9) == "less than 10⁻⁹"
    assert roundoff(3e-9) == "3×10⁻⁹" and roundoff(-3.1e-9) == "3.1×10⁻⁹"  # a failed check shows its size


# --------------------------------------------------------------------------- review fixes (E2.1b, E2.1c, §2.2, §2.4)
def test_difference_variances_closed_form_and_drift():
    X = np.random.default_rng(11).normal(size=(3, 40, 2)) * [0.5, 2.0]
    d = wt.difference_variances(X)
    assert np.all(d[:, 0] == 0.0)
    np.testing.assert_allclose(d[:, 9], 0.5 * np.mean(np.diff(X[:, :10], axis=1) ** 2, axis=1))
    fg = wt.difference_variances(X, "forgetting", forgetting=0.8)
    a = 0.8 ** np.arange(38, -1, -1.0)
    np.testing.assert_allclose(fg[:, -1], np.einsum("i,rin->rn", a, 0.5 * np.diff(X, axis=1) ** 2) / a.sum())
    # unbiased at constant X; a common linear drift adds (ΔX)²/2 to every sensor
    big = np.random.default_rng(12).normal(size=(400, 200, 2)) * [0.5, 2.0]
    np.testing.assert_allclose(wt.difference_variances(big)[:, -1].mean(axis=0), [0.25, 4.0], rtol=0.03)
    ramp = big + 0.3 * np.arange(200)[:, None]
    np.testing.assert_allclose(wt.difference_variances(ramp)[:, -1] - wt.difference_variances(big)[:, -1],
                               0.5 * 0.3**2 + np.zeros((400, 2)), atol=0.03)


def test_cumulative_fusion_is_the_per_sample_blue_with_true_variances():
    rng = np.random.default_rng(13)
    sd = np.where(np.arange(60)[:, None] < 30, [0.5, 1.0, 4.0], [4.0, 1.0, 0.5])
    X = 7.0 + rng.normal(size=(5, 60, 3)) * sd
    P = 1 / sd**2
    blue = np.cumsum((X * P).sum(-1), axis=-1) / np.cumsum(P.sum(-1))
    np.testing.assert_allclose(wt.cumulative_fusion(X, sd**2, time_weights="precision"), blue, rtol=1e-12)
    # equal time weights: the running mean of the current-reading fusion
    np.testing.assert_allclose(wt.cumulative_fusion(X, sd**2), np.cumsum(wt.fuse_current(X, sd**2), axis=-1)
                               / np.arange(1, 61), rtol=1e-12)
    # a convex combination of all readings so far
    f = wt.cumulative_fusion(X, np.abs(rng.normal(size=X.shape)))
    lo, hi = np.minimum.accumulate(X.min(-1), axis=-1), np.maximum.accumulate(X.max(-1), axis=-1)
    assert np.all((f >= lo - 1e-12) & (f <= hi + 1e-12))
    with pytest.raises(ValueError, match="guard"):
        wt.cumulative_fusion(X, sd**2, guard="none")
    with pytest.raises(ValueError, match="equal"):
        wt.cumulative_fusion(X, sd**2, guard="equal", time_weights="precision")


def test_variance_estimates_are_the_last_running_estimates():
    X = 900.0 + np.random.default_rng(14).normal(size=(4, 30, 3))
    for e in ("lecture", "centred"):
        np.testing.assert_allclose(wt.variance_estimates(X, e), wt.running_variances(X, e)[:, -1], rtol=1e-9, atol=1e-9)


@given(st.lists(st.floats(0.01, 100.0), min_size=3, max_size=8))
@settings(max_examples=60, deadline=None)
def test_learned_weights_never_lose_to_the_mean_from_three_sensors(vals):
    R = np.array(vals)
    v = wt.learned_fused_variance(R)
    assert v <= R.sum() / R.size**2 * (1 + 1e-12)
    assert v >= wt.minimum_variance(R) * (1 - 1e-12)


def test_learned_weights_are_the_mean_for_two_sensors_and_the_random_check():
    assert wt.learned_fused_variance([1.0, 4.0]) == pytest.approx(5.0 / 4)
    chk = sc.learned_limit_check(ns=(3, 5), draws=500, seed=1)
    assert chk.sets == 1000 and chk.above_mean == 0 and chk.max_ratio_mean <= 1 + 1e-12
    assert 0 < chk.above_best < chk.sets


def test_belief_upper_limit():
    x = np.array([900.0, 900.4, 903.0, 908.0])
    np.testing.assert_allclose(rd.belief_matrix(x, limit=1e9), rd.belief_matrix(x))
    B = rd.belief_matrix(x, limit=1.0)
    assert B[0, 1] > 0 and B[0, 2] == 0 and B[2, 3] == 0 and np.all(np.diag(B) == 1)
    # every reading distrusted by every other: B = I, uniform weights (projection of 1 on the eigenspace)
    np.testing.assert_allclose(rd.belief_degree(x, limit=0.1).weights, 0.25)
    with pytest.raises(ValueError, match="limit"):
        rd.belief_degree(x, limit=-1.0)


def test_lumv_study_and_its_three_properties():
    from fusion.book.chapters import lecture_weighting as ch

    s = sc.lumv_study(runs=3000, chunk=700)
    assert all(e.shape == (3000,) for e in s.err.values())
    assert s.pairs == 1500 and all(v.shape == (1500,) for v in s.pair_mean.values())
    # the second half of the runs mirrors the first: e(-V) = -e(V) for the oracle and the centred weights
    for name in ch.EVEN_WEIGHTS:
        e = s.err[name]
        np.testing.assert_allclose(e[1500:], -e[:1500], atol=1e-9)
    assert s.odd_residual[M.AWF_LECTURE_ABS] > 1e-3      # the lecture's estimator is not even at X = 900
    r = ch.lumv_readings(s)
    assert r[M.ORACLE].linear and r[M.ORACLE].unbiased and r[M.ORACLE].minvar
    assert not any(v.linear for k, v in r.items() if k != M.ORACLE)
    assert r[M.AWF_LECTURE_FLOOR].unbiased is False      # the floor biases the fusion (about −0.18)
    assert r[M.AWF_LECTURE_NONE].unbiased is None         # no mean
    assert not r[M.AWF_LECTURE_DELETE].linear
    assert r[M.ORACLE].unbiased and r[M.AWF_CENTRED].unbiased
    b, lo, hi = ch.lumv_bias(s, M.AWF_LECTURE_ABS)
    assert hi < 0 and b == pytest.approx(-0.0021, abs=0.0004)   # a real bias, about 2 % of the RMSE
    assert ch.lumv_bias(s, M.ORACLE) == (0.0, 0.0, 0.0)
    assert np.mean(s.sq[M.ORACLE]) == pytest.approx(s.bound, rel=0.1)
    with pytest.raises(ValueError, match="runs"):
        sc.lumv_study(runs=11)


def test_symmetry_study_finds_odd_errors_where_the_weights_are_even():
    s = sc.symmetry_study(runs=30, k=40)
    from fusion.book.style import METHOD_LABELS

    odd = {m for m in s.methods if s.even[m]}
    # only the lecture's uncentred estimator at a level X != 0 has weights that are not even in the noise
    assert odd == set(s.methods) - {"lec_sym_awf_lecture_abs", "lec_sym_awf_lecture_floor"}
    tab = __import__("fusion.book.chapters.lecture_weighting", fromlist=["x"]).table_symmetry(s)
    assert list(tab.index) == [METHOD_LABELS[m] for m in s.methods]


def test_lecture_samples_needed_inverts_the_sd_formula():
    V = np.array([0.25, 1.0, 4.0, 16.0])
    k = wt.lecture_samples_needed(900.0, V, 0.5)
    np.testing.assert_allclose(np.diag(wt.lecture_variance_sd(900.0, k, V)), 0.5 * V, rtol=1e-12)
    assert k[0] == pytest.approx((900 / 0.125) ** 2 * (0.25 + 21 / 9))
    np.testing.assert_array_equal(wt.lecture_samples_needed(0.0, V), 0.0)
    with pytest.raises(ValueError, match="rel_sd"):
        wt.lecture_samples_needed(900.0, V, 0.0)


def test_perron_gap():
    x = np.array([900.0, 900.4, 903.0, 903.3])
    assert rd.perron_gap(rd.belief_matrix(x, binary_eps=1.0)) == 0.0     # two equal blocks: a repeated root
    g = rd.perron_gap(rd.belief_matrix(x))
    assert 0 < g < 1 and rd.perron_gap(3.0 * rd.belief_matrix(x)) == pytest.approx(g)
    stack = rd.perron_gap(np.stack([rd.belief_matrix(x), np.eye(4)]))
    assert stack.shape == (2,) and stack[1] == 0.0
    assert rd.perron_gap(np.array([[2.0]])) == 1.0
    with pytest.raises(ValueError, match="spectral radius"):
        rd.perron_gap(np.zeros((2, 2)))
    with pytest.raises(ValueError, match="symmetric"):
        rd.perron_gap(np.array([[1.0, 0.5], [0.0, 1.0]]))


def test_variance_change_study_reproduces_the_swap_of_the_regime_study():
    kw = dict(samples=200, runs=100, change_at=100)
    v = sc.variance_change_study(**kw)
    r = sc.regime_study(**kw)
    swap = v.changes[0]
    for m in v.methods:
        np.testing.assert_allclose(v.sq[swap][m], r.sq[RS.CONSTANT_SWAP][m], rtol=1e-9)
    np.testing.assert_array_equal(v.sd_after[sc.VarianceChange.DEGRADE], [4.0, 1.0, 2.0, 4.0])
    with pytest.raises(ValueError, match="changes"):
        sc.variance_change_study(changes=(("x", {7: 1.0}),), **kw)
    from fusion.book.chapters import lecture_weighting as ch
    assert len(ch.change_comparisons(v)) == 3 * 4 and ch.table_changes(v).shape[0] == 3
    # keys in the studies, display labels only in the tables (from the style registry)
    from fusion.book.style import METHOD_LABELS
    assert list(ch.table_changes(v).index) == [METHOD_LABELS[k] for k in sc.VarianceChange]
    assert list(ch.table_regime(r).columns) == [METHOD_LABELS[k] for k in sc.RegimeScenario]
    assert all(c.metric.endswith(METHOD_LABELS[k]) for (k, _), c in ch.change_comparisons(v).items())
    # a study without one of the named changes
    one = sc.variance_change_study(changes=(("x", {0: 1.0}),), **kw)
    assert list(ch.table_changes(one).index) == ["x"]


def test_consistency_study_runs_every_guard():
    s = sc.consistency_study(runs=100, curve_draws=200, samples=60, window=(20, 40))
    for g in sc.CC_GUARDS:
        assert GUARD_KEY[g] in s.names and CHECKED[GUARD_KEY[g]] in s.names
    # the equal fallback at 900 °C is the mean of means whenever an estimate is negative (always, here)
    np.testing.assert_allclose(s.sq[sc.FaultCase.NONE][M.AWF_LECTURE_EQUAL], s.sq[sc.FaultCase.NONE][M.MEAN_OF_MEANS], rtol=1e-9)
    d = s.diag[sc.FaultCase.FAULT]
    assert 0 < d.abs_mse_faulty_term <= d.abs_mse * 1.5


def test_e23_cases_are_keys_shown_by_their_labels():
    """E2.3's data sets are keyed by FaultCase (issue 36); the table shows their labels, a label is not a key."""
    from fusion.book.chapters import lecture_weighting as ch

    s = sc.consistency_study(runs=100, curve_draws=200, samples=60, window=(20, 40))
    assert set(s.sq) == set(s.mask) == set(s.diag) == set(sc.FaultCase)
    assert list(ch.table_23(s).columns) == ["no fault", "fault"]
    c = ch.cc_log_comparison(s, M.AWF_LECTURE_FLOOR, M.MEAN_OF_MEANS, sc.FaultCase.FAULT)
    assert c.metric.endswith(", fault")
    with pytest.raises(ValueError, match="case"):
        ch.cc_log_comparison(s, M.AWF_LECTURE_FLOOR, M.MEAN_OF_MEANS, "fault")


def test_centred_estimator_is_more_efficient_than_grubbs_three_instrument_form():
    """k·Var of C₁₁ − (C₁₂ + C₁₃)/2 is 2σ₁⁴ + (σ₁²σ₂² + σ₁²σ₃²)/4; of Grubbs's C₁₁ − C₁₂ − C₁₃ + C₂₃, 2σ₁⁴ + σ₁²σ₂² + σ₁²σ₃² + σ₂²σ₃²."""
    sig = np.array([0.5, 1.0, 2.0])
    k = 200
    X = np.random.default_rng(15).normal(size=(6000, k, 3)) * sig
    avg = wt.variance_estimates(X, "centred")[:, 0]
    D = X - X.mean(axis=1, keepdims=True)
    C = np.einsum("rki,rkj->rij", D, D) / k
    grubbs = C[:, 0, 0] - C[:, 0, 1] - C[:, 0, 2] + C[:, 1, 2]
    s1, s2, s3 = sig**2
    assert k * avg.var() == pytest.approx(2 * s1**2 + (s1 * s2 + s1 * s3) / 4, rel=0.06)
    assert k * grubbs.var() == pytest.approx(2 * s1**2 + s1 * s2 + s1 * s3 + s2 * s3, rel=0.06)


def test_glue_offset_reads_the_fault_from_the_start():
    from fusion.book.chapters import lecture_weighting as ch

    r = sc.benchmark(seeds=(5,), runs=40, samples=30, levels=(900.0,), fault_from=0, faults=(True,))
    assert set(r) == {(5, 900.0, True)}
    g = ch.glue_offset(r)
    v = r[5, 900.0, True]
    assert g["lec_bo_cen"] == round(float(np.mean(v[sc.BenchMethod.AWF_CENTRED])), 2) and g["lec_bo_runs"] == 40
    # a constant offset from the first sample: the centred variances cannot see it, the median resists it
    assert np.mean(v[sc.BenchMethod.AWF_CENTRED]) > np.mean(v[sc.BenchMethod.MEDIAN])
    with pytest.raises(ValueError, match="one faulty setup"):
        ch.glue_offset(sc.benchmark(seeds=(5, 6), runs=10, samples=10, levels=(900.0,)))
    with pytest.raises(ValueError, match="faults"):
        sc.benchmark(seeds=(5,), runs=10, samples=10, faults=())


def test_ar1_study_variance_factor_and_estimator_bias():
    a = sc.ar1_study(phi=0.6, k=50, runs=4000, seed=1)
    h = np.arange(1, 50)
    assert a.c == pytest.approx(1 + 2 * np.sum((1 - h / 50) * 0.6**h))
    assert a.mse_oracle == pytest.approx(a.c * a.bound, rel=0.1)   # c·σ²min/k, not σ²min/k
    np.testing.assert_allclose(a.ratio_lecture, 1.0, atol=0.05)          # uncentred: unbiased at X = 0
    np.testing.assert_allclose(a.ratio_centred, 1 - a.c / 50, atol=0.05)  # centred: biased by c/k
    with pytest.raises(ValueError, match="phi"):
        sc.ar1_study(phi=1.0)


def _plain(x: object) -> object:
    """A ledger record's evidence as stored: tuples as lists, non-finite numbers as null."""
    import json
    import math

    def fix(v: object) -> object:
        if isinstance(v, float) and not math.isfinite(v):
            return None
        if isinstance(v, dict):
            return {k: fix(w) for k, w in v.items()}
        if isinstance(v, (list, tuple)):
            return [fix(w) for w in v]
        return v

    return fix(json.loads(json.dumps(x)))


def test_stochastic_record_reseeds_through_the_claims_file() -> None:
    import json

    from fusion.book import stability
    from fusion.book.chapters import lecture_weighting as ch
    from fusion.book.claims import claims_dir, evaluate, load
    from fusion.book.ledger import Comparison, ledger_dir

    cf = load(claims_dir() / "lecture003.yaml")
    rid = "lec-awf-fault-tolerance"
    spec = cf.record(rid)
    assert spec.evidence.endswith(":ev_awf_fault_tolerance") and ch.STOCHASTIC[rid] == 100
    led = {r["id"]: r for r in json.loads((ledger_dir() / "lecture003-02.json").read_text(encoding="utf-8"))["claims"]}
    rec = led[rid]
    # the chapter's seed and runs give the committed record: status and numbers, primary and a reading
    prim = stability._judged(evaluate(spec, "primary", ch.SEED, rec["runs"]), cf.margin(spec))
    assert prim.status() == rec["primary_status"] and _plain(prim.to_dict()) == _plain(rec["evidence"])
    keys = [r.key for r in spec.readings if r.key != "primary"]
    alt = rec["alternatives"][keys.index("guard-delete")]
    ev = stability._judged(evaluate(spec, "guard-delete", ch.SEED, rec["runs"]), cf.margin(spec))
    assert ev.status() == alt["status"] and _plain(ev.to_dict()) == _plain(alt["evidence"])
    # the study is the chapter's, from the cache
    assert one_computation(ch.study("s23"), ch.study("s23", ch.SEED, 100))
    # another seed: a valid Comparison of other runs, the benchmark's setups at the seed's offsets
    other = evaluate(spec, "primary", seed=7, runs=100)
    assert isinstance(other, Comparison) and other.runs == 100 and other.seed == 7 + ch.SEED_OFFSETS["s23"][0]
    assert other.status() in {"reproduced", "contradicted", "not distinguishable"}
    b = evaluate(cf.record("lec-awf-accuracy"), "bench-9002", seed=7, runs=100)
    assert isinstance(b, Comparison) and b.runs == 100 and b.seed == 7 + ch.SEED_OFFSETS["bench"][1]
    with pytest.raises(ValueError, match="settings"):
        ch.ev_awf_fault_tolerance({"reading": "no-such-reading"}, seed=7, runs=100)
    # every reading of every stochastic record names its reading in its settings
    for r in ch.STOCHASTIC:
        assert all(x.settings == {"reading": x.key} for x in cf.record(r).readings if x.key != "primary")


def test_undefined_literal_weights_give_an_infinite_run_judged_by_the_rulebook() -> None:
    """Issue 34: where the literal AWF's weights are undefined (an estimate exactly 0) the run is infinite, not an error."""
    from fusion.book.ledger import Comparison
    from fusion.readings import consistency as cs
    from fusion.scenarios.lecture_weighting.consistency import _literal_check_awf, _window_mse

    rng = np.random.default_rng(34)
    data = 900.0 + rng.normal(size=(6, 12, 5)) * np.array([0.5, 1.0, 1.5, 2.0, 4.0])
    data[:3, 0, :] = 900.0  # identical first readings: every lecture estimate is exactly 0 at k = 1 in runs 0-2
    with pytest.raises(ValueError):
        cs.consistency_awf(data, 10.0, "lecture", guard="none")
    v = _literal_check_awf(data, 10.0)
    assert np.isnan(v[:3, 0]).all() and np.isfinite(v[3:]).all() and np.isfinite(v[:, 1:]).all()
    # where defined, the literal value is the package's on the runs it accepts
    np.testing.assert_allclose(v[3:], cs.consistency_awf(data[3:], 10.0, "lecture", guard="none").awf.value)
    mse = _window_mse(v, 900.0, slice(0, 12))
    assert np.isinf(mse[:3]).all() and np.isfinite(mse[3:]).all()
    c = Comparison(mse, np.full(6, 1.0), "check + AWF (lecture, no guard)", "mean of means", "less", "window MSE", seed=34,
                   reason="a unit test of six runs")
    assert c.judgement().statistic == "infinite mean" and c.status() == "contradicted"


def test_robustness_tables_of_the_2026_12_05_review() -> None:
    """F9, F7, F17 and §7 of the external review: the appendix's robustness tables (no record reads them)."""
    from fusion.book.chapters import lecture_weighting as ch

    # F9: the shifted reading's weight over draws; the one-draw figure's draw is one of the kind counted
    sw = ch.shift_weight_draws(draws=6, seed=1)
    assert sw.W.shape == (6, 201) and np.all((sw.W > 0) & (sw.W <= 1))
    np.testing.assert_allclose(sw.mean, sw.W.mean(axis=0))
    assert 0 <= sw.n_nonmonotone <= 6 and np.all(sw.rebound >= 0) and isinstance(sw.mean_monotone, bool)
    assert sw.n_nonmonotone == int(np.sum(sw.rebound > 1e-12))
    np.testing.assert_array_equal(ch.shift_weight_draws(draws=6, seed=1).W, sw.W)
    one = sc.belief_study(snapshots=2)  # the chapter's single draw is non-monotone
    assert np.any(np.diff(one.W[:, 0]) > 1e-12)
    tab = ch.table_shift_weight(sw, at=(0.0, 20.0))
    assert list(tab.index) == ["0", "20"] and float(tab.iloc[0, 0]) > float(tab.iloc[1, 0])
    with pytest.raises(ValueError):
        ch.shift_weight_draws(draws=1)
    # F7: a = 4 at the chapter's draws and seed is the chapter's own check; the share grows with the spread here
    sp = ch.spread_check(log_ranges=(0.5, 4.0, 6.0))
    llc = sc.learned_limit_check()
    assert sp.loc["4", "above best sensor by > 5 % (%)"] == f"{100 * llc.above_best / llc.sets:.1f}"
    shares = [float(v) for v in sp["above best sensor by > 5 % (%)"]]
    assert shares == sorted(shares) and set(sp["above the mean (%)"]) == {"0.0"}
    # F17: one row per (ε, bias), ε ascending; a sub-ε fault is not rejected, a huge one always
    g = ch.check_grid(eps_factors=(1.0, 0.5), biases=(1.0, 200.0), runs=5, seed=3)
    assert len(g) == 4 and [float(e) for e in g.index.get_level_values(0)] == sorted(float(e) for e in g.index.get_level_values(0))
    eps0 = f"{3 * np.sqrt(2) * 4.0:.2f}"
    assert g.loc[(eps0, "200"), "sensor 3 rejected (%)"] == "100.0"
    assert float(g.loc[(eps0, "1"), "sensor 3 rejected (%)"]) < 50
    with pytest.raises(ValueError):
        ch.check_grid(runs=1)


def test_estimator_table_is_rows_of_the_regime_table() -> None:
    """§7 of the review: the variance-estimator table repeats the regime table's numbers, no new runs."""
    from fusion.book.chapters import lecture_weighting as ch

    s = sc.regime_study(runs=3, samples=200, change_at=100, window=20)
    full, est = ch.table_regime(s), ch.table_estimators(s)
    from fusion.book.style import METHOD_LABELS

    rows = [METHOD_LABELS[m] for m in ch.ESTIMATOR_ROWS]
    assert list(est.index) == [m for m in rows if m in full.index] and METHOD_LABELS[RM.ORACLE] in est.index
    assert est.equals(full.loc[est.index])


def test_reseeding_glue_uses_each_records_runs_factor(tmp_path) -> None:
    """A record swept at 10x keeps its factor when a later --merge sweep ran others at 3x."""
    import json as _json

    from fusion.book.chapters import lecture_weighting as lw

    d = tmp_path / "book" / "ledger"
    d.mkdir(parents=True)
    (tmp_path / "_toc.yml").write_text("root: intro\n", encoding="utf-8")   # marks the repository root
    rec = {"k": 4, "K": 5, "flag": True, "scaled": "reproduced", "runs_factor": 10,
           "reseeds": ["not distinguishable"] * 4 + ["reproduced"]}
    (d / "stability.json").write_text(_json.dumps({"runs_factor": 3, "records": {"lec-x": rec}}), encoding="utf-8")
    out = lw.reseeding_glue([{"id": "lec-x", "status": "not distinguishable", "runs": 200}], root=tmp_path)
    assert "reproduced at 10× the runs" in out["lec_rs_x"] and "3×" not in out["lec_rs_x"]


def test_chapter_02_stochastic_evidence_functions_from_one_reader():
    """The eight stochastic records' evidence functions, made by one reader: each is the function its record's
    ``evidence`` field names, named from the record id, with the record's run count as its default."""
    import importlib
    import inspect

    from fusion.book.chapters import lecture_weighting as ch
    from fusion.book.claims import claims_dir, load

    cf = load(claims_dir() / "lecture003.yaml")
    for rid, runs in ch.STOCHASTIC.items():
        mod, name = cf.record(rid).evidence.split(":")
        fn = getattr(importlib.import_module(mod), name)
        assert fn is ch.EVIDENCE[rid] and fn.__name__ == name == "ev_" + rid.removeprefix("lec-").replace("-", "_")
        params = inspect.signature(fn).parameters
        assert params["runs"].default == runs and params["seed"].default == ch.SEED
        assert inspect.getdoc(fn).startswith(f"``{rid}``, one reading: ")
    assert len({ch.EVIDENCE[r] for r in ch.STOCHASTIC}) == len(ch.STOCHASTIC)
