"""Track-level fusion (fusion.filtering.tracks.fuse_tracks) and the infrared + radar case of source 000."""

from __future__ import annotations

import numpy as np
import pytest

from fusion import data
from fusion import estimates as es
from fusion.scenarios import infrared_radar as ir
from fusion import filtering as tr
from fusion.scenarios import two_sensor


@pytest.fixture(scope="module")
def sim() -> ir.IrRadarRuns:
    p = data.WANG2024_IR_RADAR
    return ir.simulate(np.random.default_rng(3), runs=20, sigma_ir=p["sigma_ir"], sigma_angle=p["sigma_angle"],
                       sigma_range=p["sigma_range"], r0=p["range"], az0=p["azimuth"], el0=p["elevation"],
                       velocity=p["velocity"])


def test_spherical_round_trip() -> None:
    rng = np.random.default_rng(0)
    p = rng.normal(scale=1000.0, size=(50, 3))
    np.testing.assert_allclose(ir.spherical_to_cartesian(*ir.cartesian_to_spherical(p).T), p, rtol=1e-12, atol=1e-9)
    with pytest.raises(ValueError, match="range 0"):
        ir.cartesian_to_spherical(np.zeros(3))


def test_truth_matches_the_published_geometry() -> None:
    p = data.WANG2024_IR_RADAR
    true_path = ir.truth(0.1, 10.0, p["range"], p["azimuth"], p["elevation"], p["velocity"])
    t, pos, sph = true_path.t, true_path.pos, true_path.sph
    np.testing.assert_allclose(sph[0], [p["range"], p["azimuth"], p["elevation"]], rtol=1e-12)
    np.testing.assert_allclose(np.diff(pos, axis=0) / 0.1, np.broadcast_to(p["velocity"], (t.size - 1, 3)), rtol=1e-9)


def test_local_filters_are_consistent_or_conservative(sim: ir.IrRadarRuns) -> None:
    """Mean NEES of each angle filter at most the state dimension (4) after the transient."""
    rates = np.gradient(sim.sph[:, 1:], sim.t, axis=0)
    truth = np.column_stack([sim.sph[:, 1], rates[:, 0], sim.sph[:, 2], rates[:, 1]])
    for track in (sim.ir, sim.radar):
        assert tr.nees(track.est - truth, track.gains.P)[:, 20:].mean() < 4.0


def test_covariance_aware_rules_follow_the_precise_sensor(sim: ir.IrRadarRuns) -> None:
    """IR angles are 200x more precise: CI puts (almost) all the weight on them, the convex
    combination and split CI are within 1 % of the IR track's error; fuzzy clustering, which
    averages without weights, is far worse."""
    err = lambda est: np.sqrt(np.mean((est[:, 20:, 0] - sim.sph[20:, 1]) ** 2))  # noqa: E731
    ci = tr.fuse_tracks(sim.ir, sim.radar, "ci")
    assert np.all(ci.omega > 0.99)
    base = err(sim.ir.est)
    for rule in ("ci", "convex", "split"):
        assert err(tr.fuse_tracks(sim.ir, sim.radar, rule).est) <= 1.01 * base
    assert err(tr.fuse_tracks(sim.ir, sim.radar, "fuzzy").est) > 10 * base


def test_fuse_tracks_special_cases(sim: ir.IrRadarRuns) -> None:
    a, b = sim.ir, sim.radar
    np.testing.assert_allclose(tr.fuse_tracks(a, b, "ci", omega=1.0).est, a.est, atol=1e-12)
    np.testing.assert_allclose(tr.fuse_tracks(a, b, "ci", omega=0.0).est, b.est, atol=1e-9)
    # per-step weights are used as given, and equal the scalar call step by step
    w = np.linspace(0.1, 0.9, a.est.shape[1])
    f = tr.fuse_tracks(a, b, "ci", omega=w)
    np.testing.assert_allclose(f.omega, w)
    k = 37
    one = es.covariance_intersection(a.est[0, k], a.gains.P[k], b.est[0, k], b.gains.P[k], omega=w[k])
    np.testing.assert_allclose(f.est[0, k], one.x, rtol=1e-10)
    np.testing.assert_allclose(f.P[k], one.P, rtol=1e-10)
    assert tr.fuse_tracks(a, b, "fuzzy").P is None
    with pytest.raises(ValueError, match="rule"):
        tr.fuse_tracks(a, b, "average")
    with pytest.raises(ValueError, match="same shape"):
        tr.fuse_tracks(a, sim.radar_range, "ci")


def test_position_and_bad_input(sim: ir.IrRadarRuns) -> None:
    p = ir.position(sim.radar_range.est, sim.ir.est)
    assert p.shape == (20, sim.t.size, 3)
    with pytest.raises(ValueError, match="range tracks"):
        ir.position(sim.radar_range.est, sim.ir.est[..., :2])
    with pytest.raises(ValueError, match="runs"):
        ir.simulate(np.random.default_rng(0), runs=0)
    with pytest.raises(ValueError, match="sigma_ir"):
        ir.simulate(np.random.default_rng(0), sigma_ir=-1.0)
    with pytest.raises(ValueError, match="positive semidefinite"):
        tr.gain_sequence(np.eye(2), np.eye(1, 2), -np.eye(2), np.eye(1), np.eye(2), 3)


def test_two_sensor_scenario_is_deterministic_and_central_is_best() -> None:
    Q, R = np.diag([100.0] * 4), np.diag([150.0**2] * 2)
    s1 = two_sensor.two_sensor_scenario(R, R, Q, np.random.default_rng(9), runs=10)
    s2 = two_sensor.two_sensor_scenario(R, R, Q, np.random.default_rng(9), runs=10)
    np.testing.assert_array_equal(s1.tracks[0].est, s2.tracks[0].est)
    # the centralised covariance is below each local one and below the CI one (Loewner order)
    ci = tr.fuse_tracks(*s1.tracks, "ci")
    for k in (10, 100, 200):
        assert np.linalg.eigvalsh(s1.tracks[0].gains.P[k] - s1.central.gains.P[k]).min() > 0
        assert np.linalg.eigvalsh(ci.P[k] - s1.central.gains.P[k]).min() > 0


def test_rule_errors_cover_every_rule_and_the_unfiltered_reference(sim: ir.IrRadarRuns) -> None:
    errs = ir.rule_errors(sim)
    assert set(errs) == {ir.IrMethod.IR_ALONE, ir.IrMethod.RADAR_ALONE, ir.PER_SCAN, *ir.RULES}
    for e in errs.values():
        assert e.shape == (20, sim.t.size, 4) and np.all(np.isfinite(e))
    # the reference is the raw infrared angle noise: its RMSE is the infrared sigma
    sigma = data.WANG2024_IR_RADAR["sigma_ir"]
    assert np.sqrt(np.mean(errs[ir.PER_SCAN][..., :2] ** 2)) == pytest.approx(sigma, rel=0.05)
    np.testing.assert_allclose(errs[ir.IrMethod.IR_ALONE][..., 0], sim.ir.est[..., 0] - sim.sph[:, 1])


def test_nan_and_wrong_shapes_are_rejected() -> None:
    from fusion.optimise import scalar as opt

    with pytest.raises(ValueError, match="finite"):
        ir.spherical_to_cartesian(1000.0, np.nan, 0.1)
    with pytest.raises(ValueError, match="finite"):
        ir.cartesian_to_spherical([1.0, np.nan, 0.0])
    with pytest.raises(ValueError, match="velocity"):
        ir.truth(velocity=(300.0, np.nan, 0.0))
    with pytest.raises(ValueError, match="velocity"):
        ir.truth(velocity=(300.0, 100.0))
    with pytest.raises(ValueError, match="finite"):
        ir.position(np.full((3, 2), np.nan), np.zeros((3, 4)))
    model = tr.cv_model(1.0)
    F, H = model.F, model.H
    z = np.zeros((2, 5, 2))
    with pytest.raises(ValueError, match="x0"):
        tr.local_track(z, F, H, np.eye(4), np.eye(2), np.full((2, 4), np.nan), np.eye(4), np.eye(4))
    with pytest.raises(ValueError, match="x0"):
        tr.local_track(z, F, H, np.eye(4), np.eye(2), np.zeros((3, 4)), np.eye(4), np.eye(4))
    with pytest.raises(ValueError, match="P0d"):
        tr.local_track(z, F, H, np.eye(4), np.eye(2), np.zeros((2, 4)), -np.eye(4), np.eye(4))
    # an objective that ignores vectorisation, or returns NaN, is caught
    with pytest.raises(ValueError, match="shape"):
        opt.fruit_fly(lambda w: 1.0, np.random.default_rng(0), vectorized=True)
    with pytest.raises(ValueError, match="NaN"):
        opt.grid_search(lambda w: np.nan, 11)


# ------------------------------------------------------------------ many-scan bound, Cartesian readings
def _path(velocity=(300.0, 100.0, 0.0), T=0.1, duration=2.0) -> ir.Truth:
    p = data.WANG2024_IR_RADAR
    return ir.truth(T, duration, p["range"], p["azimuth"], p["elevation"], velocity)


def test_conversion_jacobian_matches_finite_differences() -> None:
    sph = np.array([[1000.0, 0.6, 0.4], [2500.0, -1.2, 0.1]])
    J = ir.conversion_jacobian(sph)
    h = np.array([1e-3, 1e-7, 1e-7])
    for i in range(3):
        d = np.zeros(3)
        d[i] = h[i]
        fd = (ir.spherical_to_cartesian(*(sph + d).T) - ir.spherical_to_cartesian(*(sph - d).T)) / (2 * h[i])
        np.testing.assert_allclose(J[..., i], fd, rtol=1e-6, atol=1e-6)


def test_bound_of_a_stationary_target_is_the_regression_formula() -> None:
    """v = 0: the scans all see one geometry, so the bound on p(t_k) from scans 0..k is the straight-line
    regression variance (1/N + (t_k - mean t)^2 / S_tt) times the single-scan converted covariance."""
    path = _path(velocity=(0.0, 0.0, 0.0))
    sr, sa = 5.0, 0.02
    b = ir.many_scan_bound(path, 1e-4, sa, sr, "radar")
    J = ir.conversion_jacobian(path.sph[0])
    C = J @ np.diag([sr**2, sa**2, sa**2]) @ J.T
    for k in (1, 5, path.t.size - 1):
        tt = path.t[: k + 1]
        g = 1 / tt.size + (tt[-1] - tt.mean()) ** 2 / np.sum((tt - tt.mean()) ** 2)
        np.testing.assert_allclose(b[k, 2:], np.sqrt(g * np.diag(C)[:2]), rtol=1e-8)
    assert np.all(np.isnan(b[0]))   # one scan: 3 measurements for 6 parameters


def test_bound_orders() -> None:
    """More information never raises the bound: both sensors <= each alone; every scan <= the scans so far;
    the infrared alone cannot range (x, y infinite) but bounds its angles."""
    path = _path()
    args = (1e-4, 0.02, 5.0)
    both, radar, infra = (ir.many_scan_bound(path, *args, s) for s in ir.BOUND_SENSORS[::-1])
    smooth = ir.many_scan_bound(path, *args, "both", smoother=True)
    ok = ~np.isnan(both[:, 0]) & ~np.isnan(infra[:, 0])
    assert np.all(both[ok] <= radar[ok] * (1 + 1e-9))
    assert np.all(both[ok, :2] <= infra[ok, :2] * (1 + 1e-9))
    assert np.all(np.isinf(infra[:, 2:]))
    assert np.all(np.isfinite(infra[2:, :2])) and np.all(np.isnan(infra[:2, :2]))
    assert np.all(smooth[1:] <= both[1:] * (1 + 1e-9))
    np.testing.assert_allclose(smooth[-1], both[-1], rtol=1e-9)
    # the infrared alone at its own noise is the angle bound of a single scan when nothing else constrains it
    assert infra[2, 0] < 1e-4


def test_bound_binds_the_simulated_filters(sim: ir.IrRadarRuns) -> None:
    """Every method's RMSE over 20 runs stays above the bound of the flight it tracks (t >= 2 s)."""
    p = data.WANG2024_IR_RADAR
    b = ir.many_scan_bound(sim.path, p["sigma_ir"], p["sigma_angle"], p["sigma_range"])
    late = sim.t >= 2.0
    for name, r in ir.rmse_by_rule(sim).items():
        assert np.all(r[late] > b[late]), name


def test_bound_refuses_a_curved_path_and_bad_sensors() -> None:
    path = _path()
    bent_pos = path.pos + np.c_[path.t**2, 0 * path.t, 0 * path.t]
    bent = ir.Truth(t=path.t, pos=bent_pos, sph=ir.cartesian_to_spherical(bent_pos))
    with pytest.raises(ValueError, match="straight"):
        ir.many_scan_bound(bent, 1e-4, 0.02, 5.0)
    with pytest.raises(ValueError, match="sensors"):
        ir.many_scan_bound(path, 1e-4, 0.02, 5.0, "sonar")


def test_cartesian_tracks_split_and_near_efficiency(sim: ir.IrRadarRuns) -> None:
    """The split sums to each filter's covariance; the infrared + range track with a small process noise comes
    within 20 % of the many-scan bound in x and y (20 runs), the radar's own track within 30 % of its bound."""
    ct = ir.cartesian_tracks(sim, sigma_acc=0.1)
    for track in (ct.radar, ct.ir):
        np.testing.assert_allclose(track.Pd + track.Pi, track.gains.P, rtol=1e-9, atol=1e-9)
    assert 0.0 < ct.r_change < 0.2
    p = data.WANG2024_IR_RADAR
    late = sim.t >= 2.0
    err = ir.cartesian_errors(sim, ct, (ir.IrMethod.SPLIT_CI,))
    assert set(err) == {*ir.CARTESIAN_LOCAL.values(), ir.IrMethod.SPLIT_CI}
    for name, sensors, tol in ((ir.CARTESIAN_LOCAL["ir"], "both", 1.2), (ir.CARTESIAN_LOCAL["radar"], "radar", 1.3)):
        b = ir.many_scan_bound(sim.path, p["sigma_ir"], p["sigma_angle"], p["sigma_range"], sensors)[late, 2:].mean(axis=0)
        r = np.sqrt(np.mean(err[name][:, late, 2:] ** 2, axis=(0, 1)))
        assert np.all(r < tol * b) and np.all(r > 0.8 * b), (name, r, b)


def test_rule_subset_and_q_scale(sim: ir.IrRadarRuns) -> None:
    full = ir.rule_errors(sim)
    sub = ir.rule_errors(sim, ("ci_closed_form",))   # a plain string key works as its IrMethod
    assert set(sub) == {ir.IrMethod.IR_ALONE, ir.IrMethod.RADAR_ALONE, ir.IrMethod.CI, ir.PER_SCAN}
    np.testing.assert_array_equal(sub[ir.IrMethod.CI], full[ir.IrMethod.CI])
    with pytest.raises(ValueError, match="rules"):
        ir.rule_errors(sim, ("average",))
    p = data.WANG2024_IR_RADAR
    kw = dict(runs=2, sigma_ir=p["sigma_ir"], sigma_angle=p["sigma_angle"], sigma_range=p["sigma_range"])
    s1 = ir.simulate(np.random.default_rng(0), **kw)
    s4 = ir.simulate(np.random.default_rng(0), q_scale=4.0, **kw)
    for k, v in s1.sigma_acc.items():
        assert s4.sigma_acc[k] == pytest.approx(2.0 * v)
    np.testing.assert_array_equal(s1.ir.z, s4.ir.z)   # same draws: readings are paired
