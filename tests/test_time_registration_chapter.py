"""Chapter 07 (time registration): scenario module, causal/look-ahead labels, chapter recipes, ledger."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from fusion.book.style import METHOD_LABELS
from fusion.book.tables import mismatches

from fusion import registration as reg
from fusion.book.chapters import time_registration as ch
from fusion.book.chapters import time_registration_ledger as lg
from fusion.scenarios import time_registration as sc
from fusion.scenarios.time_registration import RegMethod

T1, T2 = sc.instants()


def test_scenario_truth_and_instants() -> None:
    np.testing.assert_allclose(sc.truth([0.0, 1.0, 2.0]), [0.0, 2.0, 6.0])  # t + t^2
    assert T1.size == 20 and T2.size == 8
    t1, t2 = sc.instants(4.0)
    assert np.array_equal(t1, T1) and t2[0] == 3.0 and np.all(np.diff(t2) == 4.0)
    with pytest.raises(ValueError, match="period_2"):
        sc.instants(0.0)


def test_two_point_causal_is_exact_on_lines_and_returns_samples() -> None:
    t = np.array([0.0, 1.0, 2.5, 4.0, 6.0])
    z = 3.0 - 2.0 * t
    q = np.array([0.5, 2.6, 5.0, 7.0])
    np.testing.assert_allclose(reg.two_point(t, z, q, causal=True), 3.0 - 2.0 * q)
    zn = np.random.default_rng(0).normal(size=t.size)
    np.testing.assert_allclose(reg.two_point(t, zn, t[1:], causal=True), zn[1:])


@pytest.mark.parametrize("name", list(sc.METHODS))
def test_information_label_is_what_the_method_uses(name: str) -> None:
    """A causal method ignores samples after the instant; a look-ahead one does not."""
    rng = np.random.default_rng(5)
    z = sc.truth(T1) + rng.normal(size=T1.size)
    q = T2[1:]  # from 8 s on every method has three past samples
    base = sc.register(name, T1, z, q, 1.0)
    changed = []
    for k, tk in enumerate(q):
        z2 = z.copy()
        z2[T1 > tk] += 50.0
        changed.append(not np.isclose(sc.register(name, T1, z2, q, 1.0)[k], base[k]))
    assert any(changed) == (sc.METHODS[name] != sc.Information.CAUSAL)


@pytest.mark.parametrize("causal", [False, True])
@pytest.mark.parametrize("sigma", [0.1, 1.0, 10.0])
def test_chapter_improved_path_is_improved_register_up_to_the_vectorised_filter(sigma: float, causal: bool) -> None:
    """The chapter runs the source's proposal as kalman_runs + three_point (vectorised over runs, with the
    chapter's filter options), not reg.improved_register (kalman_filter + three_point, one run). Each path is
    bitwise its own two steps; they differ only where the two filters' arithmetic differs (a few ulps of the
    positions), which three_point, linear in them, carries to the registered values."""
    z = sc.truth(T1) + sigma * np.random.default_rng(3).normal(size=T1.size)
    name = ch.CAUSAL_IMPROVED if causal else ch.IMPROVED
    chapter_path = sc.register(name, T1, z, T2, sigma)
    source_api = reg.improved_register(T1, z, T2, sigma, causal=causal)
    runs = reg.kalman_runs(T1, z, sigma, sc.Q_V, sc.Q_A).x[:, 0]
    single = reg.kalman_filter(T1, z, sigma, sc.Q_V, sc.Q_A).x[:, 0]
    np.testing.assert_array_equal(chapter_path, reg.three_point(T1, runs, T2, causal=causal))
    np.testing.assert_array_equal(source_api, reg.three_point(T1, single, T2, causal=causal))
    scale = np.max(np.abs(z))
    np.testing.assert_allclose(runs, single, rtol=0, atol=1e-13 * scale)
    np.testing.assert_allclose(chapter_path, source_api, rtol=0, atol=1e-12 * scale)


def test_register_dispatch_and_predict_to() -> None:
    z = sc.truth(T1) + np.random.default_rng(1).normal(size=T1.size)
    np.testing.assert_allclose(sc.register(RegMethod.TWO_POINT, T1, z, T2, 1.0), reg.two_point(T1, z, T2))
    np.testing.assert_allclose(sc.register(RegMethod.KALMAN_PREDICT, T1, z, T2, 1.0), reg.kalman_register(T1, z, T2, 1.0))
    np.testing.assert_allclose(sc.register(ch.IMPROVED, T1, z, T2, 1.0), reg.improved_register(T1, z, T2, 1.0))
    np.testing.assert_allclose(sc.register(ch.CAUSAL_IMPROVED, T1, z, T2, 1.0),
                               reg.improved_register(T1, z, T2, 1.0, causal=True))
    f = sc.registrar(RegMethod.LEAST_SQUARES, T1, T2, 1.0)
    np.testing.assert_allclose(f(z), reg.least_squares(T1, z, T2, 5.0))
    xs = reg.kalman_filter(T1, z, 1.0).x
    np.testing.assert_allclose(reg.predict_to(T1, xs, T1), xs[:, 0])  # zero step: the filtered value
    with pytest.raises(ValueError, match="states"):
        reg.predict_to(T1, xs[:, :2], T2)
    with pytest.raises(ValueError, match="name"):
        sc.register("spline", T1, z, T2, 1.0)


def test_two_point_remainder() -> None:
    np.testing.assert_allclose(sc.two_point_remainder(T1, T2),
                               sc.register(RegMethod.TWO_POINT, T1, sc.truth(T1), T2, 1.0) - sc.truth(T2), atol=1e-9)
    with pytest.raises(ValueError, match="inside"):
        sc.two_point_remainder(T1, [40.0])


@pytest.mark.parametrize("sigma", [0.3, 3.0])
def test_expected_mse_matches_simulated_runs(sigma: float) -> None:
    mc = sc.monte_carlo(list(sc.METHODS), sigma, 400, seed=11)
    for name, v in mc.per_run.items():
        se = v.std(ddof=1) / np.sqrt(v.size)
        # 4 standard errors: a false failure has probability < 1e-4 per method
        assert abs(v.mean() - sc.expected(name, sigma)) < 4 * se, name


def test_monte_carlo_pairs_runs_and_validates() -> None:
    a = sc.monte_carlo([RegMethod.TWO_POINT, ch.IMPROVED], 1.0, 5, seed=3)
    b = sc.monte_carlo([RegMethod.TWO_POINT], 1.0, 5, seed=3)
    np.testing.assert_array_equal(a.per_run[RegMethod.TWO_POINT], b.per_run[RegMethod.TWO_POINT])  # same draws
    z = sc.truth(T1) + 1.0 * np.random.default_rng(3).standard_normal((5, T1.size))
    direct = [np.mean((sc.register(ch.IMPROVED, T1, zi, T2, 1.0) - sc.truth(T2)) ** 2) for zi in z]
    np.testing.assert_allclose(a.per_run[ch.IMPROVED], direct)
    with pytest.raises(ValueError, match="runs"):
        sc.monte_carlo([RegMethod.TWO_POINT], 1.0, 1, seed=0)
    with pytest.raises(ValueError, match="sigma"):
        sc.monte_carlo([RegMethod.TWO_POINT], 0.0, 5, seed=0)


def test_noise_free_and_axes_tables() -> None:
    nf = ch.noise_free_table(T1, T2)
    np.testing.assert_allclose(nf[RegMethod.TWO_POINT], nf["derived two-point error"], atol=5e-4)
    assert nf[RegMethod.THREE_POINT].abs().max() == 0.0
    counts, axes = ch.axes_tables(T1, T2)
    assert counts["reproduced"].tolist() == [20, 8]
    assert counts.dtypes.map(lambda d: d.kind).tolist() == ["i", "i"]     # counts shown as integers
    assert mismatches(counts, 0)["reproduced"].tolist() == [False, True]
    assert axes.loc["Fig. 2 after", "largest value in the scenario (m)"] == pytest.approx(38 + 38**2)


def test_mc_and_noise_level_tables() -> None:
    per = {ch.TWO: np.array([1.0, 3.0, 1.0, 3.0]), ch.IMPROVED: np.array([0.5, 1.0, 2.5, 0.5])}
    mc = sc.MonteCarlo(per_run=per, sigma=1.0, runs=4, seed=0)
    t = ch.noise_level_table({1.0: mc}, axis_max=2.0, block=2)
    assert t.loc[1.0, "both inside the axis"] == 0.25        # run 1 only
    assert t.loc[1.0, "P(improved wins a run)"] == 0.75
    assert t.loc[1.0, "P(all 2 runs ordered)"] == 0.5        # blocks (1,2) yes, (3,4) no
    m = ch.mc_table(mc, {ch.TWO: 2.0, ch.IMPROVED: 1.0})
    assert m.loc[ch.TWO, "difference / s.e."] == 0.0
    assert m.loc[ch.TWO, "information"] == METHOD_LABELS[sc.Information.LOOK_AHEAD] == "look-ahead"


@pytest.fixture(scope="module")
def study() -> dict:
    return lg.cached_study(1, 120)


def test_study_runs_every_reading_at_the_primary_count(study) -> None:  # noqa: ANN001
    runs = [study.mc.runs] + [m.runs for k in ("sweep", "stress", "robust", "s3", "s3_fair")
                              for m in getattr(study, k).values()]
    runs += [m.runs for m in study.s3_pc.values()]
    runs += [getattr(study, k).runs for k in ("s3_period", "realtime", "stress_tuned")]
    assert set(runs) == {120}                                             # rule R4: no underpowered reading
    # the stress runs draw the manoeuvre truth for every method alike (rule R6)
    m = study.stress["manoeuvre-stop"]
    assert m.per_run[RegMethod.QLS_NEXT].mean() > 20 * m.per_run[ch.TWO].mean()


def test_ledger_evidence_builds_with_the_claim_file(study, tmp_path) -> None:  # noqa: ANN001
    import re
    from pathlib import Path

    from fusion.book.claims import build_ledger, claims_dir

    ev = lg.ledger_evidence(1, 120)              # the fixture's cached study
    text = (claims_dir(Path(__file__).parent) / "shi2023time.yaml").read_text(encoding="utf-8")
    values = {k: 1.0 for k in re.findall(r"\{([a-z_0-9]+)(?::[^}]*)?\}", text)}
    led = build_ledger("shi2023time", None, ev, values=values)   # every reading key of the file has evidence
    assert len(led.claims) == 16 and led.write(tmp_path)
    # the primary comparisons compute what the records say they compute
    imp = ev["shi-improved"]["primary"]
    assert (imp.a_name, imp.b_name, imp.claim) == (METHOD_LABELS[ch.IMPROVED], METHOD_LABELS[ch.TWO], "less")
    assert np.mean(imp.a) < np.mean(imp.b)
    fair = ev["shi-improved-fair"]["primary"]
    assert fair.b_name == METHOD_LABELS[lg.FIXED_LAG] and np.mean(fair.a) > np.mean(fair.b)  # the smoother does better
    three = ev["shi-three-noise"]
    # exact (R9): 比较大 is a comparison with two-point: the noise adds 55/64 σ² against 3/4 σ² (14.6 % more, 43.75 %
    # between samples); it is not amplified beyond a raw sample's σ² (a counted reading)
    assert (three["primary"].claim, three["primary"].b) == ("greater", pytest.approx(0.75))
    assert three["primary"].a == pytest.approx(55 / 64) and three["primary"].status() == "reproduced"
    assert three["amplifies"].b == 1.0 and three["amplifies"].status() == "contradicted"
    assert (three["interpolating-instants"].a, three["interpolating-instants"].b) == (pytest.approx(46 / 64),
                                                                                      pytest.approx(0.5))
    assert not any(k.startswith("sigma-") for k in three)   # the ratio gσ²/gσ² does not depend on σ: no such reading
    assert three["total-mse"].a < three["total-mse"].b
    assert three["extrapolation"].parts[0][1].holds                          # extrapolation amplifies the noise
    assert ev["shi-metric"]["primary"].holds and not ev["shi-metric"]["literal-covariance"].holds
    assert ev["shi-simplifies"]["primary"].parts[0][1].status() == "reproduced"      # 1578 against 1734 operations
    assert ev["shi-simplifies"]["s3-period-unchanged"].parts[0][1].status() == "not distinguishable"  # 1578 vs 1518
    # the counting convention is a counted reading: dense with precomputed weights 1524, structure used 563 against
    # 577 (within 5 %), structure used and precomputed weights 536 against 577
    simp = {k: ev["shi-simplifies"][k].parts[0][1].status() for k in
            ("ops-dense-weights", "ops-structured", "ops-structured-weights")}
    assert simp == {"ops-dense-weights": "reproduced", "ops-structured": "not distinguishable",
                    "ops-structured-weights": "reproduced"}
    # 内插外推法 read as the source's two-point interpolation at every noise level (a counted reading each)
    ivl = ev["shi-interp-vs-ls"]
    assert {f"interpolation-{k}" for k in ("sigma-0-1", "sigma-0-3", "sigma-3", "sigma-10")} <= set(ivl)
    assert ivl["interpolation-sigma-3"].a_name == METHOD_LABELS[ch.TWO]
    # least squares fused with sensor 2: against fusing the stale sample, and against sensor 2 alone (its bias)
    ls = ev["shi-ls-info"]["primary"]
    assert ls.b_name == "fused, unregistered (last sample)" and np.mean(ls.a) < np.mean(ls.b) / 100
    alone = ev["shi-ls-info"]["sensor-2-alone"]
    assert alone.b_name == "sensor 2 alone" and np.mean(alone.a) > np.mean(alone.b)
    reg = ev["shi-ls-info"]["registration-mse"]
    assert reg.b_name == lg.UNREGISTERED and np.mean(reg.a) < np.mean(reg.b) / 100
    # simulations 1-2 re-run noise-free: both methods far better than no registration (exact)
    assert all(c.status() == "reproduced" for _, c in ev["shi-validated"]["primary"].parts)
    assert not ev["shi-validated"]["published-figures"].holds
    fus = ev["shi-fusion"]["primary"]
    assert fus.b_name == "fused, unregistered (last sample)"


def test_unregistered_runs_draw_the_monte_carlo_samples() -> None:
    m = sc.monte_carlo([RegMethod.TWO_POINT_EXTRAPOLATION], 1.0, 6, seed=11)
    z = sc.truth(T1) + np.random.default_rng(11).standard_normal((6, T1.size))
    last = np.searchsorted(T1, T2, side="right") - 1
    assert np.allclose(lg.unregistered_runs(m, T1, T2), np.mean((z[:, last] - sc.truth(T2)) ** 2, axis=1))
    # two-point extrapolation returns the sample at the sample-time instants: equal there, by construction
    assert lg.unregistered_runs(m, T1, T2).shape == (6,)


def test_evidence_functions_serve_one_reading_for_a_reseeding_sweep(study) -> None:  # noqa: ANN001
    from pathlib import Path

    from fusion.book.claims import claims_dir, evaluate, load

    cf = load(claims_dir(Path(__file__).parent) / "shi2023time.yaml")
    spec = cf.record("shi-improved")
    ev = evaluate(spec, "sigma-3", seed=1, runs=120)          # the study of the fixture, from the cache
    assert ev.a == tuple(study.sweep[3.0].per_run[ch.IMPROVED])
    other = evaluate(spec, "sigma-3", seed=2, runs=120)       # a reseed: other runs, the same reading
    assert other.seed != ev.seed and other.a != ev.a
    with pytest.raises(ValueError, match="settings"):
        lg.ev_improved({"reading": "no-such-reading"}, seed=1, runs=120)
    assert evaluate(cf.record("shi-samples"), "primary", seed=1, runs=120).holds is False


def test_cost_count_counts_the_period_changes() -> None:
    cc = lg.cost_count(T1, T2)
    # four instants (8, 18, 28, 38 s) fall between samples: §3 steps there and on, at a second period (1 s)
    assert (cc["improved_steps"], cc["s3_steps"]) == (T1.size - 1, T1.size - 1 + 4)
    assert (cc["improved_periods"], cc["s3_periods"]) == (1, 2)
    assert cc["three_point_evals"] == T2.size
    n = T1.size - 1   # every route filters at the samples; §3 adds a full prediction (or a state-only one) at 4 instants
    assert cc["improved_ops"] == n * 78 + T2.size * 12
    assert (cc["s3_ops"], cc["s3_unchanged_ops"]) == (n * 78 + 4 * 63, n * 78 + 4 * 9)
    # the filter's structure (triangular F, symmetric P, H = [1 0 0]): F x 3, F P Fᵀ 12, the update 3 + 3 + 6
    assert lg.structured_ops() == {"predict": 15, "update": 12, "state": 3}
    assert (cc["weight_sets"], cc["weight_sets_between"], cc["three_point_evals_between"]) == (2, 1, 4)
    assert cc["improved_ops_weights"] == n * 78 + T2.size * 3 + 2 * 9
    assert cc["improved_ops_structured"] == n * 27 + 4 * 12 + 2
    assert cc["improved_ops_structured_weights"] == n * 27 + 4 * 3 + 9 + 2
    assert cc["s3_ops_structured"] == n * 27 + 4 * 15 + 2 * 2


def test_noise_gain_by_instant_is_one_at_samples_and_46_64_between() -> None:
    g = lg.noise_gain_by_instant(T1, T2)
    assert (g.loc[g["sample time"], ["g three-point", "g two-point"]] == 1.0).all().all()
    between = g.loc[~g["sample time"]]
    assert np.allclose(between["g three-point"], 46 / 64) and np.allclose(between["g two-point"], 0.5)
    assert g["g three-point"].mean() == pytest.approx(55 / 64) and g["g two-point"].mean() == pytest.approx(0.75)


def test_closed_form_constants_are_the_derived_fractions() -> None:
    # derived in the chapter (reg-closed): 3/4 and 1/2, 55/64 and 0, 27/16 and 31/6
    b2, g2 = sc.mse_coefficients(RegMethod.TWO_POINT)
    b3, g3 = sc.mse_coefficients(RegMethod.THREE_POINT)
    bl, gl = sc.mse_coefficients(RegMethod.LEAST_SQUARES)
    assert (g2, b2) == pytest.approx((3 / 4, 1 / 2), abs=1e-12)
    assert (g3, b3) == pytest.approx((55 / 64, 0.0), abs=1e-12)
    assert (gl, bl) == pytest.approx((27 / 16, 31 / 6), abs=1e-12)


def test_fixed_lag_smoother_uses_the_next_sample_only() -> None:
    z = sc.truth(T1) + np.random.default_rng(3).standard_normal(T1.size)
    a = sc.register(lg.FIXED_LAG, T1, z, T2, 1.0)
    z2 = z.copy()
    z2[-1] += 100.0                 # the last sample lies beyond the lag of every instant but the last
    b = sc.register(lg.FIXED_LAG, T1, z2, T2, 1.0)
    assert np.allclose(a[:-1], b[:-1]) and not np.isclose(a[-1], b[-1])
    assert sc.expected(lg.FIXED_LAG, 1.0) < sc.expected(ch.IMPROVED, 1.0)
    with pytest.raises(ValueError, match="lag_one"):
        reg.kalman_runs(T1, z, 1.0, smooth=True, lag_one=True)


def test_local_quadratic_uses_its_window_and_is_exact_on_the_quadratic() -> None:
    x = sc.truth(T1)
    assert np.allclose(reg.quadratic_ls(T1, x, T2, lookahead=1, past=4), sc.truth(T2))
    z = x.copy()
    z[0] += 50.0                    # far outside the window of the late instants
    late = T2 > T1[5]
    assert np.allclose(reg.quadratic_ls(T1, z, T2, lookahead=1, past=4)[late], sc.truth(T2)[late])
    with pytest.raises(ValueError, match="past"):
        reg.quadratic_ls(T1, x, T2, past=0)


def test_vectorised_monte_carlo_equals_running_each_method() -> None:
    m = sc.monte_carlo(list(sc.METHODS), 1.0, 4, seed=9)
    z = sc.truth(T1) + np.random.default_rng(9).standard_normal((4, T1.size))
    for n in sc.METHODS:
        runs = [np.mean((sc.register(n, T1, z[r], T2, 1.0) - sc.truth(T2)) ** 2) for r in range(4)]
        assert np.allclose(m.per_run[n], runs, atol=1e-9), n


def test_stress_and_nees_tables() -> None:
    st = lg.stress_table(1.0, (ch.TWO, ch.IMPROVED, lg.QLS))
    assert st.loc[lg.QLS, "manoeuvre-stop"] > st.loc[ch.IMPROVED, "manoeuvre-stop"] > st.loc[ch.TWO, "manoeuvre-stop"]
    assert np.isnan(st.loc[ch.TWO, "manoeuvre-stop, q_v = 1, q_a = 0.1"])
    nees = lg.nees_table(1.0, 200, seed=1)
    assert nees.loc[("acceleration 2 → 0 m/s² at 20 s", "q_v = 10⁻², q_a = 10⁻³"), "mean NEES"] > 10 * 3
    assert nees.loc[("source's truth", "q_v = 10⁻², q_a = 10⁻³"), "mean NEES"] < 3


def test_noise_free_mse_matches_the_derived_remainder() -> None:
    # two-point: mean of the squared interpolation remainder; three-point is exact on the quadratic
    assert sc.noise_free_mse(RegMethod.TWO_POINT) == pytest.approx(np.mean(sc.two_point_remainder(T1, T2) ** 2))
    assert sc.noise_free_mse(RegMethod.THREE_POINT) == pytest.approx(0.0, abs=1e-18)
    with pytest.raises(ValueError, match="name"):
        sc.noise_free_mse("spline")


def test_noise_gain_and_crossing_follow_the_exact_mse() -> None:
    for n in (RegMethod.TWO_POINT, RegMethod.THREE_POINT, RegMethod.LEAST_SQUARES):
        b, g = sc.noise_free_mse(n), sc.noise_gain(n)
        assert g > 0
        assert sc.expected(n, 3.0) == pytest.approx(b + 9.0 * g)   # E[MSE] = b + g sigma^2
    s = sc.crossing_sigma(RegMethod.THREE_POINT, RegMethod.TWO_POINT)
    assert 1.0 < s < 3.0
    assert sc.expected(RegMethod.THREE_POINT, s) == pytest.approx(sc.expected(RegMethod.TWO_POINT, s))
    assert np.isnan(sc.crossing_sigma(RegMethod.TWO_POINT, RegMethod.TWO_POINT))
    with pytest.raises(ValueError, match="Kalman"):
        sc.noise_gain(RegMethod.KALMAN_PREDICT)


# ---------------------------------------------------------------- issue 17


@pytest.mark.parametrize("q_model", reg.Q_MODELS)
@pytest.mark.parametrize("init", reg.INITS)
@pytest.mark.parametrize("extra", [False, True])
def test_vectorised_filter_equals_filterpy(q_model: str, init: str, extra: bool) -> None:
    Z = sc.truth(T1) + np.random.default_rng(2).normal(size=(4, T1.size))
    kw = dict(q_model=q_model, init=init, t_extra=T2 if extra else None, p0=(10.0, 3.0))
    batch = reg.kalman_runs(T1, Z, 1.5, 0.02, 0.004, **kw)
    for r in range(Z.shape[0]):
        ref = reg.kalman_filter(T1, Z[r], 1.5, 0.02, 0.004, **kw)
        np.testing.assert_allclose(batch.x[r], ref.x, rtol=1e-10, atol=1e-9)
        np.testing.assert_allclose(batch.P, ref.P, rtol=1e-10, atol=1e-12)


def test_rts_smoother_equals_filterpy() -> None:
    from filterpy.kalman import KalmanFilter
    z = sc.truth(T1) + np.random.default_rng(3).normal(size=T1.size)
    f = reg.kalman_filter(T1, z, 1.0)
    kf = KalmanFilter(dim_x=3, dim_z=1)
    Fs = [np.eye(3)] + [reg.ca_transition(d) for d in np.diff(T1)]   # filterpy uses Fs[k+1] from k to k+1
    Qs = [np.zeros((3, 3))] + [reg.process_noise(d, 1e-2, 1e-3) for d in np.diff(T1)]
    xs, Ps, _, _ = kf.rts_smoother(np.array(f.x), np.array(f.P), Fs=Fs, Qs=Qs)
    ours = reg.kalman_runs(T1, z, 1.0, smooth=True)
    np.testing.assert_allclose(ours.x, xs, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(ours.P, Ps, rtol=1e-6, atol=1e-8)  # filterpy inverts, we solve


def test_period_change_is_neutral_only_for_the_white_noise_jerk_q() -> None:
    z = sc.truth(T1) + np.random.default_rng(4).normal(size=T1.size)
    for model, neutral in (("white-noise jerk", True), ("per-step", False), ("Wiener-process acceleration", False)):
        a = reg.kalman_runs(T1, z, 1.0, q_model=model)
        b = reg.kalman_runs(T1, z, 1.0, q_model=model, t_extra=T2)
        assert np.allclose(a.P, b.P, rtol=1e-10, atol=1e-12) == neutral, model
    # exact additivity of the properly discretised model
    F = reg.ca_transition(1.3)
    q = lambda T: reg.process_noise(T, 0.0, 0.02, "white-noise jerk")  # noqa: E731
    np.testing.assert_allclose(F @ q(0.7) @ F.T + q(1.3), q(2.0), rtol=1e-12)


def test_quadratic_ls_and_spline_are_exact_on_the_quadratic() -> None:
    x1 = sc.truth(T1)
    np.testing.assert_allclose(reg.quadratic_ls(T1, x1, T2), sc.truth(T2), atol=1e-9)
    np.testing.assert_allclose(reg.spline_register(T1, x1, T2), sc.truth(T2), atol=1e-9)
    # lookahead=0 ignores every later sample; lookahead=1 uses the next one
    z = x1 + np.random.default_rng(5).normal(size=T1.size)
    z2 = z.copy()
    z2[T1 > 20.0] += 9.0
    q = np.array([19.5])
    assert reg.quadratic_ls(T1, z, q, lookahead=0)[0] == pytest.approx(reg.quadratic_ls(T1, z2, q, lookahead=0)[0])
    assert reg.quadratic_ls(T1, z, q, lookahead=1)[0] != pytest.approx(reg.quadratic_ls(T1, z2, q, lookahead=1)[0])


@pytest.mark.parametrize("name", [ch.IMPROVED, RegMethod.KALMAN_PREDICT, RegMethod.RTS_SMOOTHER, RegMethod.THREE_POINT])
def test_closed_form_matches_monte_carlo_with_the_filter_fixed(name: str) -> None:
    """E[MSE] = b + g sigma^2 with the filter tuned for 1 m, checked by running the method at sigma = 3 m."""
    b, g = sc.mse_coefficients(name, 1.0)
    assert sc.expected(name, 3.0, sigma_filter=1.0) == pytest.approx(b + 9.0 * g)
    v = sc.monte_carlo([name], 3.0, 400, seed=21, sigma_filter=1.0).per_run[name]
    lo, hi = ch._paired(v, np.zeros_like(v))[1:]
    se = v.std(ddof=1) / np.sqrt(v.size)
    assert abs(v.mean() - (b + 9.0 * g)) < 4 * se
    assert lo < hi


def test_crossing_table_gives_equal_expectations() -> None:
    cf = ch.closed_form_table(1.0, 1.0)
    cr = ch.crossing_table(cf)
    assert len(cr) > 0
    for _, row in cr.iterrows():
        a, b, s = row["better below σ*"], row["better above σ*"], row["σ* (m)"]
        ea = cf.loc[a, "b (m²)"] + cf.loc[a, "g"] * s**2
        eb = cf.loc[b, "b (m²)"] + cf.loc[b, "g"] * s**2
        assert ea == pytest.approx(eb, abs=0.02 * max(ea, eb) + 1e-3)
        lo = max(s - 0.2, s / 2)
        assert cf.loc[a, "b (m²)"] + cf.loc[a, "g"] * lo**2 <= cf.loc[b, "b (m²)"] + cf.loc[b, "g"] * lo**2 + 1e-9


def test_delay_shifts_the_truth_and_fusion_runs() -> None:
    assert sc.expected(RegMethod.THREE_POINT, 1.0, delay=0.01) > sc.expected(RegMethod.THREE_POINT, 1.0)
    fr = sc.fusion_runs([ch.TWO], 1.0, 50, seed=1)
    assert set(fr.fused) == {ch.TWO}
    assert fr.alone.shape == fr.unregistered.shape == fr.fused[ch.TWO].shape == (50,)
    t = ch.fusion_table(fr)
    assert t.loc[ch.FUSION_ALONE, "minus sensor 2 alone"] == 0.0
    shown = ch.labelled(t, template="fused, {}")
    assert list(shown.index) == ["sensor 2 alone", "fused, unregistered (last sample)", "fused, two-point"]
    assert shown.loc["fused, two-point", "mean MSE (m²)"] == t.loc[ch.TWO, "mean MSE (m²)"]


def test_labelled_maps_method_keys_everywhere_and_keeps_the_rest() -> None:
    tab = pd.DataFrame({("A", ""): [ch.TWO, "other"], (ch.IMPROVED, "bias (m)"): [1.0, 2.0]},
                       index=pd.Index([RegMethod.LEAST_SQUARES, "row"], name="method"))
    out = ch.labelled(tab)
    assert list(out.index) == [METHOD_LABELS[RegMethod.LEAST_SQUARES], "row"] and out.index.name == "method"
    assert list(out[("A", "")]) == ["two-point", "other"]
    assert list(out.columns) == [("A", ""), (METHOD_LABELS[ch.IMPROVED], "bias (m)")]
    assert list(tab.index) == [RegMethod.LEAST_SQUARES, "row"]      # the input is not changed
    assert set(METHOD_LABELS[m] for m in sc.RegMethod) == set(ch.labelled(pd.DataFrame(index=list(sc.METHODS))).index)
    with pytest.raises(TypeError, match="table"):
        ch.labelled({"a": 1})  # type: ignore[arg-type]


def test_manoeuvre_truth_is_continuous_and_changes_the_acceleration() -> None:
    t = np.linspace(0.0, 40.0, 401)
    np.testing.assert_allclose(sc.manoeuvre_truth(t, None), sc.truth(t))
    x = sc.manoeuvre_truth(t, -2.0)
    np.testing.assert_allclose(x[t <= 20.0], sc.truth(t[t <= 20.0]))
    dt = t[1] - t[0]
    acc = np.diff(x, 2) / dt**2                      # exact on piecewise quadratics away from the change
    assert np.allclose(acc[t[1:-1] < 19.9], 2.0) and np.allclose(acc[t[1:-1] > 20.1], -2.0)
    h = 1e-6                                         # velocity continuous at the change
    assert (sc.manoeuvre_truth(20.0 + h, 0.0) - sc.manoeuvre_truth(20.0, 0.0)) / h == pytest.approx(41.0, rel=1e-6)
    assert sc.expected(ch.TWO, 1.0, a_after=2.0) == pytest.approx(sc.expected(ch.TWO, 1.0))
    mc = sc.monte_carlo([ch.TWO], 1.0, 2000, seed=5, a_after=0.0)
    e = sc.expected(ch.TWO, 1.0, a_after=0.0)
    assert abs(mc.per_run[ch.TWO].mean() - e) < 4 * mc.per_run[ch.TWO].std() / np.sqrt(2000)


def test_causal_quadratic_ls_is_exact_on_the_quadratic_and_causal() -> None:
    z = sc.truth(T1)
    est = sc.register(RegMethod.QLS_CAUSAL, T1, z, T2, 1.0)
    np.testing.assert_allclose(est, sc.truth(T2), atol=1e-8)
    z2 = z.copy()
    z2[T1 > T2[3]] += 100.0                          # later samples do not move the instant T2[3]
    est2 = sc.register(RegMethod.QLS_CAUSAL, T1, z2, T2, 1.0)
    assert est2[3] == pytest.approx(est[3])
    e3 = sc.register(RegMethod.THREE_POINT_EXTRAPOLATION, T1, z, T2, 1.0)
    np.testing.assert_allclose(e3, sc.truth(T2), atol=1e-8)
    e3b = sc.register(RegMethod.THREE_POINT_EXTRAPOLATION, T1, z2, T2, 1.0)
    assert e3b[3] == pytest.approx(e3[3])


def test_delay_break_even_equalises_the_expectations_and_table_sign() -> None:
    d = ch.delay_break_even(1.0)
    assert 0.0 < d < 0.05
    assert sc.expected(ch.IMPROVED, 1.0, delay=d) == pytest.approx(sc.expected(ch.TWO, 1.0, delay=d), abs=5e-3)   # d rounded to 0.1 ms
    t = ch.delay_table([0.0, 0.05], [1.0])
    assert t.iloc[0, 0] < 0 < t.iloc[1, 0]
    with pytest.raises(ValueError, match="upper"):
        ch.delay_break_even(1.0, upper=0.005)


def test_fig4_compatibility_matches_simulated_runs() -> None:
    c = ch.fig4_compatibility([1.0], 4000, 7, 2.0)
    mc = sc.monte_carlo(list(ch.FIG4), 1.0, 400, seed=8)
    p_mc = np.mean((mc.per_run[ch.IMPROVED] <= 2.0) & (mc.per_run[ch.TWO] <= 2.0))
    p = c.loc[1.0, "P(run inside the axis)"]
    assert abs(p - p_mc) < 4 * np.sqrt(p * (1 - p) / 400) + 0.01
    assert c.loc[1.0, "95 % CI low"] <= c.loc[1.0, "P(20 runs inside)"] <= c.loc[1.0, "95 % CI high"]
    r = ch.fig4_reading_table([1.0], 2000, 9, 2.0)
    assert r.iloc[0, 1] >= r.iloc[0, 0]             # RMSE <= MSE wherever MSE >= 1, so more runs fit
    assert r.loc[1.0, "(iii) per instant: largest E[sq. error], two-point (m²)"] == pytest.approx(1.5, abs=1e-3)


def test_whole_record_blue_bounds_every_unbiased_method() -> None:
    blue = lg.blue_whole_record(1.0)
    assert blue == pytest.approx(lg.blue_whole_record(2.0) / 4)        # unbiased on the quadratic: g σ² only
    for n in (lg.QLS, lg.FIXED_LAG, ch.IMPROVED, RegMethod.RTS_SMOOTHER, RegMethod.CUBIC_SPLINE):
        assert blue < sc.expected(n, 1.0), n


def test_no_program_hypothesis_draws_all_four_panels_of_figs_2_3() -> None:
    fits = {label: lg.figs23_fits(a, end, d) for label, a, end, d in lg.FIG23_HYPOTHESES}
    assert not any(all(f.values()) for f in fits.values())
    assert fits["acceleration halved (x = t + t²/2)"] == {"fig2_before_y": False, "fig2_after_y": True,
                                                          "fig3_before_y": False, "fig3_after_y": False}


def test_named_crossings_keep_the_four_pairs_the_text_names() -> None:
    cr = ch.crossing_table(ch.closed_form_table(1.0, 1.0))
    named = ch.named_crossings(cr)
    assert list(zip(named["better below σ*"], named["better above σ*"])) == list(ch.NAMED_CROSSINGS)
    assert named["σ* (m)"].iloc[0] == pytest.approx(sc.crossing_sigma(RegMethod.THREE_POINT, ch.TWO), abs=0.01)
    assert set(named["σ* (m)"]) <= set(cr["σ* (m)"])
    with pytest.raises(ValueError, match="pairs"):
        ch.named_crossings(cr, [(ch.TWO, RegMethod.THREE_POINT)])          # the other order does not cross


def test_tuning_by_noise_reruns_the_study_draws_and_the_exact_difference(study) -> None:  # noqa: ANN001
    tb = ch.tuning_by_noise([1.0, 3.0], 120, 1)
    assert len(tb) == 2 * len(ch.TUNING_READINGS)
    robust = ch.robustness_table(study)                                # the study's runs (seed 1, 120 runs)
    at1 = tb.xs(1.0, level="σ (m)")
    for idx, row in at1.iterrows():
        assert row["Monte-Carlo difference (m²)"] == pytest.approx(robust.loc[idx, "improved minus two-point (m²)"], abs=1e-4)
    kw = dict(kf={"p0": (1.0, 1.0)})
    ex = sc.expected(ch.IMPROVED, 3.0, **kw) - sc.expected(ch.TWO, 3.0, **kw)
    assert tb.loc[("initial covariance", "P0 = diag(σ², 1, 1)", 3.0), "exact difference (m²)"] == pytest.approx(ex, abs=1e-4)
    f2 = tb.loc[("filter's noise level", "filter assumes 2σ", 3.0), "exact difference (m²)"]
    assert f2 == pytest.approx(sc.expected(ch.IMPROVED, 3.0, sigma_filter=6.0) - sc.expected(ch.TWO, 3.0), abs=1e-4)


def test_transient_table_splits_the_exact_mse_and_finds_the_steady_state() -> None:
    tr = ch.transient_table(40.0, 1.0)
    assert list(tr.index) == list(T2)
    for n in ch.KALMAN_METHODS:
        sq = tr[(n, "bias (m)")] ** 2 + tr[(n, "variance (m²)")]
        assert np.allclose(sq, tr[(n, "E[sq. error] (m²)")], atol=2e-4)
        assert tr[(n, "E[sq. error] (m²)")].mean() == pytest.approx(sc.expected(n, 1.0), abs=1e-3)
    tr2 = ch.transient_table(40.0, 2.0)                                  # variance scales with σ² only if the filter is fixed
    assert (tr2.xs("variance (m²)", axis=1, level=1) > tr.xs("variance (m²)", axis=1, level=1)).all().all()
    long = ch.transient_table(100.0, 1.0)
    assert np.allclose(long.loc[list(T2)], tr, atol=1e-4)               # a longer run does not change the first 40 s
    end = ch.transient_end(long)
    assert end in long.index and 3.0 < end < 40.0
    sq = long.xs("E[sq. error] (m²)", axis=1, level=1)
    late = sq.loc[sq.index >= end]
    assert np.allclose(late.iloc[:-2].to_numpy(), late.iloc[2:].to_numpy(), rtol=0.02)   # periodic once steady
    with pytest.raises(ValueError, match="horizon"):
        ch.transient_table(2.0, 1.0)


def test_benchmark_table_is_keyed_by_class_and_method_and_labelled_for_display() -> None:
    names = sorted({m for ms in ch.CLASSES.values() for m in ms})
    mc = sc.monte_carlo(names, 0.5, 40, 3)
    exact = {n: sc.expected(n, 0.5) for n in names}
    bench = ch.benchmark_table(mc, exact)
    assert set(bench.index.get_level_values("class")) == set(ch.BenchClass)
    for cls, ms in ch.CLASSES.items():
        assert set(bench.loc[cls].index) == set(ms)
        ref = RegMethod.KALMAN_PREDICT if cls == ch.BenchClass.REAL_TIME else ch.IMPROVED
        assert bench.loc[(cls, ref), "vs the source's method"] == "reference"
        assert bench.loc[(cls, ref), "minus reference (m²)"] == 0.0
    shown = ch.labelled(bench)
    assert list(dict.fromkeys(shown.index.get_level_values("class"))) == [METHOD_LABELS[c] for c in ch.CLASSES]
    assert set(shown.index.get_level_values("method")) == {METHOD_LABELS[m] for m in names}
    v = ch.benchmark_numbers(bench)
    assert v["reg_b_qls"] == bench.loc[(ch.BenchClass.OFFLINE, RegMethod.QLS_NEXT), "exact E[MSE] (m²)"]
    assert v["reg_b_causal_lo"] <= v["reg_b_causal_hi"]
