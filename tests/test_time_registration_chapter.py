"""Chapter 07 (time registration): scenario module, causal/look-ahead labels, chapter recipes, ledger."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from fusion import registration as reg
from fusion.book.chapters import time_registration as ch
from fusion.scenarios import time_registration as sc

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
    assert any(changed) == (sc.METHODS[name] != "causal")


def test_register_dispatch_and_predict_to() -> None:
    z = sc.truth(T1) + np.random.default_rng(1).normal(size=T1.size)
    np.testing.assert_allclose(sc.register("two-point", T1, z, T2, 1.0), reg.two_point(T1, z, T2))
    np.testing.assert_allclose(sc.register("Kalman, predict (§3)", T1, z, T2, 1.0), reg.kalman_register(T1, z, T2, 1.0))
    np.testing.assert_allclose(sc.register(ch.IMPROVED, T1, z, T2, 1.0), reg.improved_register(T1, z, T2, 1.0))
    np.testing.assert_allclose(sc.register(ch.CAUSAL_IMPROVED, T1, z, T2, 1.0),
                               reg.improved_register(T1, z, T2, 1.0, causal=True))
    f = sc.registrar("least squares", T1, T2, 1.0)
    np.testing.assert_allclose(f(z), reg.least_squares(T1, z, T2, 5.0))
    xs = reg.kalman_filter(T1, z, 1.0).x
    np.testing.assert_allclose(reg.predict_to(T1, xs, T1), xs[:, 0])  # zero step: the filtered value
    with pytest.raises(ValueError, match="states"):
        reg.predict_to(T1, xs[:, :2], T2)
    with pytest.raises(ValueError, match="name"):
        sc.register("spline", T1, z, T2, 1.0)


def test_two_point_remainder() -> None:
    np.testing.assert_allclose(sc.two_point_remainder(T1, T2),
                               sc.register("two-point", T1, sc.truth(T1), T2, 1.0) - sc.truth(T2), atol=1e-9)
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
    a = sc.monte_carlo(["two-point", ch.IMPROVED], 1.0, 5, seed=3)
    b = sc.monte_carlo(["two-point"], 1.0, 5, seed=3)
    np.testing.assert_array_equal(a.per_run["two-point"], b.per_run["two-point"])  # same draws
    z = sc.truth(T1) + 1.0 * np.random.default_rng(3).standard_normal((5, T1.size))
    direct = [np.mean((sc.register(ch.IMPROVED, T1, zi, T2, 1.0) - sc.truth(T2)) ** 2) for zi in z]
    np.testing.assert_allclose(a.per_run[ch.IMPROVED], direct)
    with pytest.raises(ValueError, match="runs"):
        sc.monte_carlo(["two-point"], 1.0, 1, seed=0)
    with pytest.raises(ValueError, match="sigma"):
        sc.monte_carlo(["two-point"], 0.0, 5, seed=0)


def test_noise_free_and_axes_tables() -> None:
    nf = ch.noise_free_table(T1, T2)
    np.testing.assert_allclose(nf["two-point"], nf["derived two-point error"], atol=5e-4)
    assert nf["three-point"].abs().max() == 0.0
    counts, axes = ch.axes_tables(T1, T2)
    assert counts["in the 40 s window"].tolist() == [20, 8]
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
    assert m.loc[ch.TWO, "information"] == "look-ahead"


def test_claims_ledger(tmp_path) -> None:  # noqa: ANN001
    mc = sc.monte_carlo(list(sc.METHODS), 1.0, 100, seed=1)
    sweep = {10.0: sc.monte_carlo(list(sc.METHODS), 10.0, 100, seed=2)}
    rt = sc.monte_carlo([ch.CAUSAL_IMPROVED, "two-point extrapolation"], 1.0, 100, seed=3, t_dst=T2[1:])
    tun = sc.monte_carlo(list(ch.FIG4), 1.0, 100, seed=4, q_v=1.0, q_a=0.1)
    exact = {n: sc.expected(n, 1.0) for n in sc.METHODS}
    led = ch.claims(T1, T2, mc, sweep, rt, tun, exact)
    assert sum(c.headline for c in led.claims) == 1
    labels = {c.link for c in led.claims} | {x for c in led.claims for x in c.critiques}
    assert {"reg-crit-eqs", "reg-crit-axes", "reg-crit-metric", "reg-crit-claim", "reg-crit-info",
            "reg-crit-noise"} <= labels
    byid = {c.id: c for c in led.claims}
    assert byid["shi-samples"].status == "not reproduced"   # 8 samples, not 20, from sensor 2
    assert byid["shi-metric"].status == "contradicted"      # a covariance ignores an offset
    head = byid["shi-improved"]
    assert "look-ahead" in head.claim
    assert isinstance(led.table(), pd.DataFrame)
    led.write(tmp_path)
    rec = json.loads((tmp_path / "shi2023time.json").read_text(encoding="utf-8"))
    assert len(rec["claims"]) == len(led.claims)


def test_noise_free_mse_matches_the_derived_remainder() -> None:
    # two-point: mean of the squared interpolation remainder; three-point is exact on the quadratic
    assert sc.noise_free_mse("two-point") == pytest.approx(np.mean(sc.two_point_remainder(T1, T2) ** 2))
    assert sc.noise_free_mse("three-point") == pytest.approx(0.0, abs=1e-18)
    with pytest.raises(ValueError, match="name"):
        sc.noise_free_mse("spline")


def test_noise_gain_and_crossing_follow_the_exact_mse() -> None:
    for n in ("two-point", "three-point", "least squares"):
        b, g = sc.noise_free_mse(n), sc.noise_gain(n)
        assert g > 0
        assert sc.expected(n, 3.0) == pytest.approx(b + 9.0 * g)   # E[MSE] = b + g sigma^2
    s = sc.crossing_sigma("three-point", "two-point")
    assert 1.0 < s < 3.0
    assert sc.expected("three-point", s) == pytest.approx(sc.expected("two-point", s))
    assert np.isnan(sc.crossing_sigma("two-point", "two-point"))
    with pytest.raises(ValueError, match="Kalman"):
        sc.noise_gain("Kalman, predict (§3)")


def test_reworded_records() -> None:
    mc = sc.monte_carlo(list(sc.METHODS), 1.0, 100, seed=1)
    sweep = {10.0: sc.monte_carlo(list(sc.METHODS), 10.0, 100, seed=2)}
    rt = sc.monte_carlo([ch.CAUSAL_IMPROVED, "two-point extrapolation"], 1.0, 100, seed=3, t_dst=T2[1:])
    tun = sc.monte_carlo(list(ch.FIG4), 1.0, 100, seed=4, q_v=1.0, q_a=0.1)
    exact = {n: sc.expected(n, 1.0) for n in sc.METHODS}
    byid = {c.id: c for c in ch.claims(T1, T2, mc, sweep, rt, tun, exact).claims}
    assert byid["shi-figs23"].status == "not reproduced"      # published axis values, not a proposition
    readings = [a.reading for a in byid["shi-interp-vs-ls"].alternatives]
    assert any("causal against causal" in r for r in readings) and any("σ_x = 0" in r for r in readings)
    assert any("Kalman filter's model" in a for a in byid["shi-improved"].assumptions)
    three = byid["shi-three-noise"]
    assert three.evidence.kind == "comparison" and "noise-free" in three.evidence.metric
