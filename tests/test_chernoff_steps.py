"""Appendix studies of chapter 06's single steps (fusion.book.chapters.chernoff_steps): closed forms and properties."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from fusion.book.chapters import chernoff_scaling as csc
from fusion.book.chapters import chernoff_steps as cs
from fusion.estimates import chernoff as ch
from fusion.estimates import mixtures as mx
from fusion.scenarios.range_bearing import RangeBearingScenario, monte_carlo


def _gaussian_case(m: float, s2: float) -> tuple[np.ndarray, float, float, float]:
    """Target N(m, 1), proposal N(0, s2) in 1-D: grid and the closed forms of c, V and E_g[w^2]."""
    x = np.linspace(-25.0, 25.0, 200_001)
    a = 1.0 - 1.0 / (2.0 * s2)  # p^2/g ∝ exp(-a x^2 + 2 m x - m^2): a Gaussian of mean m/a, variance 1/(2a)
    second = np.sqrt(s2) / np.sqrt(2 * a) * np.exp(m**2 * (1 / a - 1))
    c = -second * (m / a - m)
    V = second * (1 / (2 * a) + (m / a - m) ** 2)
    return x, c, V, second


@pytest.mark.parametrize("m, s2", [(0.7, 1.5), (-1.2, 2.0), (0.0, 0.8)])
def test_delta_terms_match_the_gaussian_closed_form(m: float, s2: float) -> None:
    x, c, V, second = _gaussian_case(m, s2)
    log_p = -0.5 * (x - m) ** 2 + 3.0  # unnormalised on purpose: the function normalises
    log_g = -0.5 * x**2 / s2 - 0.5 * np.log(2 * np.pi * s2)
    d = cs.snis_delta_terms(x[:, None], log_p, log_g, float(x[1] - x[0]))
    assert d.mu[0] == pytest.approx(m, abs=1e-9)
    assert d.c[0] == pytest.approx(c, rel=1e-7, abs=1e-12)
    assert d.V[0, 0] == pytest.approx(V, rel=1e-7)
    assert d.second_moment == pytest.approx(second, rel=1e-7)


def test_bias_formula_against_a_large_simulation() -> None:
    """Mean error of the self-normalised mean over many blocks of R samples, times R, is c (to O(1/R))."""
    m, s2, R, K = 0.8, 1.5, 40, 50_000
    x, c, _, _ = _gaussian_case(m, s2)
    rng = np.random.default_rng(7)
    xs = rng.standard_normal((K, R)) * np.sqrt(s2)
    lw = -0.5 * (xs - m) ** 2 + 0.5 * xs**2 / s2
    w = np.exp(lw - lw.max(axis=1, keepdims=True))
    err = np.sum(w * xs, axis=1) / np.sum(w, axis=1) - m
    se = err.std(ddof=1) / np.sqrt(K)
    assert abs(err.mean() - c / R) < 4 * se + 0.1 * abs(c) / R  # the O(1/R^2) remainder is far below c/R at R = 40
    assert abs(c / R) > 4 * se  # the test can tell c/R from zero


def test_bias_vanishes_when_the_proposal_is_the_target() -> None:
    x = np.linspace(-12.0, 12.0, 4001)
    log_p = -0.5 * (x - 1.0) ** 2 / 2.0 - 0.5 * np.log(4 * np.pi)
    d = cs.snis_delta_terms(x[:, None], log_p, log_p, float(x[1] - x[0]))
    assert abs(d.c[0]) < 1e-10 and d.second_moment == pytest.approx(1.0, abs=1e-10)
    assert d.V[0, 0] == pytest.approx(2.0, rel=1e-8)  # the plain Monte-Carlo variance


def test_delta_terms_refuse_bad_input() -> None:
    x = np.linspace(-1, 1, 5)[:, None]
    with pytest.raises(ValueError, match="cell"):
        cs.snis_delta_terms(x, np.zeros(5), np.zeros(5), 0.0)
    with pytest.raises(ValueError, match="log_target"):
        cs.snis_delta_terms(x, np.zeros(4), np.zeros(5), 0.1)
    with pytest.raises(ValueError, match="log_proposal"):
        cs.snis_delta_terms(x, np.zeros(5), np.full(5, np.nan), 0.1)


def test_logpdf_matches_the_package() -> None:
    ref = cs.toy_reference()
    x = mx.gm_sample(ref.proposal, np.random.default_rng(3), 500)
    for g in (ref.proposal, *ref.gms):
        np.testing.assert_allclose(cs._logpdf(g, x), mx.gm_logpdf(g, x), rtol=0, atol=1e-12)


def test_defensive_weights_are_bounded_everywhere() -> None:
    """prod p_i^eps / g_alpha <= N / alpha for every eps on the simplex (weighted AM-GM)."""
    ref = cs.toy_reference()
    gms = list(ref.gms)
    rng = np.random.default_rng(11)
    for alpha in (0.05, 0.2, 1.0):
        gd = cs.defensive_mixture(ref.proposal, gms, alpha)
        x = rng.uniform(-15, 15, size=(20_000, 2))
        L, lg = ch.log_densities(gms, x), mx.gm_logpdf(gd, x)
        E = rng.dirichlet([0.3, 0.3], size=50)
        lw = L @ E.T - lg[:, None]
        assert lw.max() <= np.log(len(gms) / alpha) + 1e-9
    # the first-order mixture alone has no such bound: at a vertex its weights exceed N / alpha somewhere
    lw0 = ch.log_densities(gms, x)[:, 0] - mx.gm_logpdf(ref.proposal, x)
    assert lw0.max() > np.log(len(gms) / 0.05)


def test_defensive_mixture_refuses_bad_input() -> None:
    ref = cs.toy_reference()
    for alpha in (0.0, -0.1, 1.5, float("nan")):
        with pytest.raises(ValueError, match="alpha"):
            cs.defensive_mixture(ref.proposal, list(ref.gms), alpha)
    with pytest.raises(ValueError, match="local"):
        cs.defensive_mixture(ref.proposal, [], 0.2)


def test_toy_reference_vertex_means_are_the_inputs_means() -> None:
    ref = cs.toy_reference()
    means = ref.fused_mean([1.0, 0.0])
    np.testing.assert_allclose(means[0], mx.gm_moments(ref.gms[0]).mean, atol=1e-6)
    np.testing.assert_allclose(means[1], mx.gm_moments(ref.gms[1]).mean, atol=1e-6)
    assert 0.0 < ref.omega_star < 1.0


def test_snis_study_is_reproducible_and_checks_rs() -> None:
    a = cs.snis_bias_study(np.random.default_rng(5), rs=(10, 20), total=40_000)
    b = cs.snis_bias_study(np.random.default_rng(5), rs=(10, 20), total=40_000)
    assert a.table.equals(b.table)
    with pytest.raises(ValueError, match="rs"):
        cs.snis_bias_study(np.random.default_rng(5), rs=(7,), total=40_000)


def test_defensive_study_shapes_and_pairing() -> None:
    st = cs.defensive_study(np.random.default_rng(2), runs=5, r=200)
    assert set(st.sq_err) == {"patent", "redraw", "defensive"}
    assert all(v.shape == (5,) for v in st.sq_err.values())
    np.testing.assert_array_equal(st.omega_err["redraw"], st.omega_err["patent"])  # the redraw reuses the patent's ω̂*
    assert all(np.all((v > 0) & (v <= 1)) for v in st.ess.values())


def test_paired_numbers_share_and_median() -> None:
    a, b = np.arange(100.0), np.arange(100.0) + np.where(np.arange(100) < 70, 1.0, -1.0)
    v = cs.paired_numbers(a, b, "x")
    assert v["x_won"] == 0.7 and v["x_med"] == -1.0 and v["x_runs"] == 100
    assert v["x_lo"] <= v["x_d"] <= v["x_hi"]


def _tiny() -> RangeBearingScenario:
    return dataclasses.replace(RangeBearingScenario(), frames=3, n_particles=40, n_samples=40, n_central=60,
                               n_components=1, em_iterations=2)


def test_study_truths_are_the_runs_truths() -> None:
    sc = _tiny()
    runs = monte_carlo(sc, 123, 2, all_nodes_first=False)
    np.testing.assert_array_equal(cs.study_truths(sc, 123, 2), np.stack([r.truth for r in runs]))


def test_single_sensor_bounds_exceed_the_centralised_bound() -> None:
    sc = RangeBearingScenario()
    tr = cs.study_truths(sc, 9, 20)
    b = cs.single_sensor_crb(sc, tr)
    assert all(b[f"sensor{i + 1}"] > b["all"] for i in range(len(sc.sensors)))
    one = dataclasses.replace(sc, sensors=(sc.sensors[1],))
    b1 = cs.single_sensor_crb(one, tr)
    assert b1["sensor1"] == b1["all"] == pytest.approx(b["sensor2"], rel=0, abs=0)


def test_box_corner_detects_ties_of_positive_exponents() -> None:
    e = np.array([[0.5, 0.5, 0.0], [0.4, 0.35, 0.25], [1 / 3, 1 / 3, 1 / 3], [1.0, 0.0, 0.0], [0.6, 0.2, 0.2]])
    np.testing.assert_array_equal(csc.box_corner(e), [True, False, True, False, True])
    # the image of a corner of the swarm's box [lo, 1]^N under u -> u / sum(u)
    u = np.array([1.0, 1e-6, 1.0, 1.0, 1e-6])
    assert csc.box_corner((u / u.sum())[None])[0]


def test_gaussian_problems_are_valid_fusion_inputs() -> None:
    w, m, c = csc.gaussian_problems(np.random.default_rng(0), 4, 3)
    assert w.shape == (4, 3, 1) and m.shape == (4, 3, 1, 2) and c.shape == (4, 3, 1, 2, 2)
    assert np.all(np.linalg.eigvalsh(c) > 0)
    with pytest.raises(ValueError, match="runs"):
        csc.gaussian_problems(np.random.default_rng(0), 0, 3)


def test_swarm_study_gap_is_against_the_convex_minimum() -> None:
    st = csc.swarm_study(3, ns=(2, 3), runs=4, r=200)
    for g in st.gap.values():
        assert np.all(g >= -1e-7)  # SLSQP minimises the same convex function on the same samples
    assert set(st.gap) == {(2, next(iter(csc.SWARM_VARIANTS))), *((3, k) for k in csc.SWARM_VARIANTS)}


def test_density_evaluations_closed_form() -> None:
    assert csc.density_evaluations(2, 2) == 4 + 4 and csc.density_evaluations(10, 1) == 11
    assert csc.density_evaluations(3, 3) == 27 + 9
    t = csc.cost_table(ns=(2, 3), ss=(1, 2))
    assert t.loc[3, "S = 2"] == 8 + 6
    with pytest.raises(ValueError, match="s"):
        csc.density_evaluations(3, 0)


def test_scaling_slope_of_a_monte_carlo_rate() -> None:
    rs = (100, 400, 1600)
    st = csc.ScalingStudy(rs, np.array([[1 / np.sqrt(r)] * 3 for r in rs]), 3, 3)
    assert st.slope() == pytest.approx(-0.5, abs=1e-12)


def test_scaling_study_errors_shrink_with_r() -> None:
    st = csc.scaling_study(4, rs=(200, 20_000), runs=20)
    assert st.eps_err.shape == (2, 20) and np.all(st.eps_err >= 0)
    assert np.median(st.eps_err[1]) < np.median(st.eps_err[0])  # 100 times the samples: about a tenth of the error


def test_frame_clouds_are_the_runs_own_estimates_and_the_figure_follows_the_rules() -> None:
    import matplotlib
    matplotlib.use("Agg")
    from fusion.book.figures import audit_figure

    sc = _tiny()
    fc = csc.frame_clouds(sc, 123, 2, run=1, frame=2)
    run = monte_carlo(sc, 123, 2, all_nodes_first=False)[1]
    np.testing.assert_allclose(fc.chernoff, run.estimates["chernoff_pso"][2], rtol=0, atol=1e-9)
    np.testing.assert_array_equal(fc.truth, run.truth)
    assert fc.particles.shape == (len(sc.sensors), sc.n_particles, 4)
    fig, alt = csc.clouds_figure(fc)
    assert audit_figure(fig) == [] and "sensor" in alt
    with pytest.raises(ValueError, match="frame"):
        csc.frame_clouds(sc, 123, 2, frame=3)


def test_paired_numbers_region_applies_the_chapter_margin() -> None:
    """With the margin, the region is rule R2's: a difference inside ±5 % of b's mean is equivalent, beyond it lower."""
    rng = np.random.default_rng(5)
    b = 10.0 + rng.standard_normal(200)
    tiny = cs.paired_numbers(b - 0.01, b, "x", relative_margin=cs.MARGIN)
    big = cs.paired_numbers(b - 2.0, b, "x", relative_margin=cs.MARGIN)
    assert tiny["x_region"] == "equivalent" and big["x_region"] == "lower"
    assert "x_region" not in cs.paired_numbers(b - 2.0, b, "x")
    with pytest.raises(ValueError, match="relative_margin"):
        cs.paired_numbers(b, b, "x", relative_margin=-0.05)


def test_swarm_within_se_is_the_swarm_studys_gap() -> None:
    """The reading ten-nodes of chf-pso-rebuild runs the swarm study's problems: the same gaps, and a finite SE."""
    gap, se = csc.swarm_within_se(11, 3, runs=4, r=200)
    st = csc.swarm_study(11, ns=(3,), runs=4, r=200)
    np.testing.assert_array_equal(gap, st.gap[(3, next(iter(csc.SWARM_VARIANTS)))])
    assert se.shape == (4,) and np.all(np.isfinite(se)) and np.all(se >= 0)
