"""Two local filters and a fusion centre with and without feedback (fusion.filtering.feedback, chapter 05)."""

from __future__ import annotations

import numpy as np
import pytest

from fusion.filtering.feedback import FEEDBACK_RULES, fusion_loop
from fusion.filtering.kalman import cv_model, nees
from fusion.filtering.tracks import fuse_tracks, local_track
from fusion.scenarios import two_sensor

MODEL = cv_model(1.0)
F, H = MODEL.F, MODEL.H
Q = np.diag([4.0, 1.0, 4.0, 1.0])
P0D = np.diag([0.0, 25.0, 0.0, 25.0])


def _case(r2: float, runs: int = 40, K: int = 30, seed: int = 0):
    rng = np.random.default_rng(seed)
    R1, R2 = np.eye(2) * 100.0, np.eye(2) * r2
    truth = two_sensor.model_truth(rng, F, Q, np.array([0.0, 5.0, 0.0, 2.0]), K, runs)
    z1 = truth[:, :, [0, 2]] + rng.standard_normal((runs, K, 2)) * 10.0
    z2 = truth[:, :, [0, 2]] + rng.standard_normal((runs, K, 2)) * np.sqrt(r2)
    x0 = [np.column_stack([z[:, 0, 0], np.zeros(runs), z[:, 0, 1], np.zeros(runs)]) for z in (z1, z2)]
    P0i = [np.diag([R[0, 0], 0.0, R[1, 1], 0.0]) for R in (R1, R2)]
    return truth, z1, z2, x0, R1, R2, P0i


@pytest.mark.parametrize("rule", ["convex", "ci", "split", "printed"])
def test_without_feedback_equals_track_fusion(rule: str) -> None:
    _, z1, z2, x0, R1, R2, P0i = _case(25.0)
    loop = fusion_loop(z1, z2, x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1], rule)
    a = local_track(z1, F, H, Q, R1, x0[0], P0D, P0i[0])
    b = local_track(z2, F, H, Q, R2, x0[1], P0D, P0i[1])
    ref = fuse_tracks(a, b, rule)
    np.testing.assert_allclose(loop.est, ref.est, rtol=1e-7, atol=1e-6)
    np.testing.assert_allclose(loop.P, ref.P, rtol=1e-7, atol=1e-8)


def test_ci_on_identical_sensors_is_unchanged_by_feedback() -> None:
    # P1 = P2: CI reports P = P1, so each filter gets back its own covariance and the same average
    _, z1, z2, x0, R1, _, P0i = _case(100.0)
    none = fusion_loop(z1, z2, x0[0], x0[1], F, H, Q, R1, R1, P0D, P0i[0], P0i[1], "ci")
    fed = fusion_loop(z1, z2, x0[0], x0[1], F, H, Q, R1, R1, P0D, P0i[0], P0i[1], "ci", feedback="split")
    np.testing.assert_allclose(fed.est, none.est, rtol=1e-9, atol=1e-8)


@pytest.mark.parametrize("rule", ["convex", "ci", "bsc"])
def test_feedback_readings_coincide_for_rules_without_split(rule: str) -> None:
    _, z1, z2, x0, R1, R2, P0i = _case(9.0)
    args = (z1, z2, x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1], rule)
    a = fusion_loop(*args, feedback="split", process_noise="shared")
    b = fusion_loop(*args, feedback="common", process_noise="own")
    np.testing.assert_allclose(a.est, b.est, rtol=1e-9, atol=1e-8)


def test_bar_shalom_campo_is_consistent_with_and_without_feedback() -> None:
    # the exact cross-covariance makes the reported covariance the error covariance: NEES near 4
    truth, z1, z2, x0, R1, R2, P0i = _case(25.0, runs=400, K=40, seed=3)
    for fb in ("none", "split"):
        r = fusion_loop(z1, z2, x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1], "bsc", feedback=fb)
        m = float(nees(r.est - truth, r.P)[:, 10:].mean())
        assert 3.6 < m < 4.4, (fb, m)


def test_convex_fed_back_is_overconfident() -> None:
    # treating the fed-back fused error as independent counts it again at every step
    truth, z1, z2, x0, R1, _, P0i = _case(100.0, runs=200, K=40, seed=4)
    r = fusion_loop(z1, z2, x0[0], x0[1], F, H, Q, R1, R1, P0D, P0i[0], P0i[1], "convex", feedback="split")
    assert float(nees(r.est - truth, r.P)[:, 10:].mean()) > 8.0


def test_fused_split_sums_to_the_fused_covariance() -> None:
    # with feedback the split rules feed back parts that must add up to the reported P
    _, z1, z2, x0, R1, R2, P0i = _case(25.0)
    r = fusion_loop(z1, z2, x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1], "split", feedback="split")
    assert np.all(np.isfinite(r.est))
    assert np.all(np.linalg.eigvalsh(r.P) > 0)
    assert np.all((r.omega > 0) & (r.omega < 1))


def test_bad_input() -> None:
    _, z1, z2, x0, R1, R2, P0i = _case(25.0)
    with pytest.raises(ValueError, match="rule"):
        fusion_loop(z1, z2, x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1], "nope")
    with pytest.raises(ValueError, match="z2"):
        fusion_loop(z1, z2[:, :-1], x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1], "ci")
    with pytest.raises(ValueError, match="feedback"):
        fusion_loop(z1, z2, x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1], "ci", feedback="yes")
    assert set(FEEDBACK_RULES) == {"convex", "ci", "split", "printed", "bsc", "lossless"}
    with pytest.raises(ValueError, match="lossless"):
        fusion_loop(z1, z2, x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1], "lossless")
    with pytest.raises(ValueError, match="omega"):
        fusion_loop(z1, z2, x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1], "ci", omega=0.5)
    for bad in (0.0, 1.5, float("nan")):
        with pytest.raises(ValueError, match="omega"):
            fusion_loop(z1, z2, x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1], "split", omega=bad)
    with pytest.raises(ValueError, match="omega"):   # split divides the second part by 1 - ω
        fusion_loop(z1, z2, x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1], "split", omega=1.0)


def test_lossless_fusion_with_feedback_is_the_centralised_filter() -> None:
    """With feedback the common prior is known; removing it once gives the centralised Kalman filter on both
    sensors' measurements, started from the step-0 Bar-Shalom–Campo fusion (which shares only P0d)."""
    from fusion.filtering.kalman import filter_runs, gain_sequence
    _, z1, z2, x0, R1, R2, P0i = _case(9.0, runs=5, K=25, seed=6)
    r = fusion_loop(z1, z2, x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1], "lossless", feedback="split")
    b = fusion_loop(z1, z2, x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1], "bsc", feedback="split")
    Hc, Rc = np.vstack([H, H]), np.zeros((4, 4))
    Rc[:2, :2], Rc[2:, 2:] = R1, R2
    g = gain_sequence(F, Hc, Q, Rc, r.P[0], z1.shape[1])
    central = filter_runs(np.concatenate([z1, z2], axis=2), g, r.est[:, 0])
    np.testing.assert_allclose(r.P, g.P, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(r.est, central, rtol=1e-9, atol=1e-7)
    np.testing.assert_allclose(r.est[:, 0], b.est[:, 0])          # step 0: Bar-Shalom–Campo
    # Bar-Shalom–Campo sees only the two tracks: with feedback it reports more than the lossless P
    assert np.all(b.P[5:, 0, 0] > r.P[5:, 0, 0] * (1 + 1e-6))
    # the same with the fused covariance fed back as common
    c = fusion_loop(z1, z2, x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1], "lossless", feedback="common")
    np.testing.assert_allclose(c.est, r.est, rtol=1e-9, atol=1e-7)


def test_fixed_weight_of_the_printed_rule() -> None:
    """A fixed ω: eqs. 11-12 at ω = 1/2 are split CI at 1/2 (both divide each correlated part by 1/2), with and
    without feedback; a smaller ω inflates the correlated parts, so the reported covariance grows."""
    _, z1, z2, x0, R1, R2, P0i = _case(25.0)
    args = (z1, z2, x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1])
    for fb in ("none", "split"):
        p = fusion_loop(*args, "printed", feedback=fb, omega=0.5)
        s = fusion_loop(*args, "split", feedback=fb, omega=0.5)
        np.testing.assert_allclose(p.est, s.est, rtol=1e-9, atol=1e-8)
        np.testing.assert_array_equal(p.omega, np.full(z1.shape[1], 0.5))
    small = fusion_loop(*args, "printed", omega=0.0018)
    half = fusion_loop(*args, "printed", omega=0.5)
    assert np.all(np.trace(small.P[1:], axis1=1, axis2=2) > np.trace(half.P[1:], axis1=1, axis2=2))


def test_architecture_study_shapes() -> None:
    """The shapes (per run, per NEES run) and the keys of the study's results. Sampled at T = 5 s, not the default
    1 s: what is checked does not depend on the track's number of steps (the same 19 and 18 keys at both), and the
    study costs 0.55 CPU-s instead of 2.2 (speed66b)."""
    st = two_sensor.architecture_study(np.random.default_rng(1), np.eye(2) * 2500.0, np.eye(2) * 900.0,
                                       np.diag([1.0] * 4), runs=3, nees_runs=2, T=5.0)
    assert all(v.shape == (3,) for v in st.run_rmse.values())
    assert all(v.shape == (2,) for v in st.model_rmse.values())
    A, AR = two_sensor.Architecture, two_sensor.ArchRule
    assert (A.CENTRALISED, AR.CENTRALISED_KF) in st.run_rmse
    assert set(st.nees) == set(st.reported) == set(st.run_rmse) - {(A.INDEPENDENT, AR.FUZZY)}


def test_time_varying_and_shared_measurement_noise() -> None:
    """A per-step R equal at every step gives the constant-R filter; R_shared adds to the filter's noise and
    goes to the shared part of the split; bad R_shared is refused by name."""
    from fusion.filtering.kalman import cv_model, gain_sequence, split_covariances
    m = cv_model(1.0)
    Q, R, P0 = np.diag([0.0, 1.0, 0.0, 1.0]), np.diag([4.0, 9.0]), 100.0 * np.eye(4)
    g1 = gain_sequence(m.F, m.H, Q, R, P0, 6)
    g2 = gain_sequence(m.F, m.H, Q, np.broadcast_to(R, (6, 2, 2)), P0, 6)
    np.testing.assert_array_equal(g1.P, g2.P)
    with pytest.raises(ValueError, match="R"):
        gain_sequence(m.F, m.H, Q, np.broadcast_to(R, (5, 2, 2)), P0, 6)
    Rs = np.diag([1.0, 0.0])
    z = np.random.default_rng(0).normal(size=(3, 6, 2))
    t = local_track(z, m.F, m.H, Q, R, np.zeros((3, 4)), 0.5 * P0, 0.5 * P0, R_shared=Rs)
    np.testing.assert_allclose(t.gains.P, gain_sequence(m.F, m.H, Q, R + Rs, P0, 6).P, rtol=1e-12)
    np.testing.assert_allclose(t.Pd + t.Pi, t.gains.P, rtol=1e-9, atol=1e-9)
    no = split_covariances(t.gains, Q, R + Rs, 0.5 * P0, 0.5 * P0)
    assert np.all(np.trace(t.Pd, axis1=1, axis2=2)[1:] > np.trace(no.Pd, axis1=1, axis2=2)[1:])
    # with a shared part, the own part may be singular (only the sum must be definite)
    split_covariances(t.gains, Q, np.diag([3.0, 0.0]), 0.5 * P0, 0.5 * P0, R_shared=np.diag([1.0, 9.0]))
    for bad in (np.diag([1.0, -1.0]), np.full((2, 2), np.nan), np.eye(3)):
        with pytest.raises((ValueError, TypeError), match="R_shared"):
            local_track(z, m.F, m.H, Q, R, np.zeros((3, 4)), 0.5 * P0, 0.5 * P0, R_shared=bad)


@pytest.mark.parametrize("rule", ["split", "printed"])
@pytest.mark.parametrize("r2", [25.0, 400.0])
def test_weights_of_all_steps_at_once_are_the_per_step_search(rule: str, r2: float,
                                                                monkeypatch: pytest.MonkeyPatch) -> None:
    """Without feedback every step's weight is searched at once; parity with scipy's search step by step, bit for bit
    (weights, estimates and covariances: the batched path fuses from its validated parts), and with split CI's own search
    on the loop's local splits."""
    from fusion.estimates import ci as es
    from fusion.filtering import feedback

    _, z1, z2, x0, R1, R2, P0i = _case(r2, K=60)
    args = (z1, z2, x0[0], x0[1], F, H, Q, R1, R2, P0D, P0i[0], P0i[1], rule)
    batched = fusion_loop(*args)
    with monkeypatch.context() as m:
        m.setattr(feedback, "_split_weights", lambda *a, **k: (None, None))   # the per-step search inside the loop
        stepwise = fusion_loop(*args)
    for got, want in ((batched.omega, stepwise.omega), (batched.est, stepwise.est), (batched.P, stepwise.P)):
        np.testing.assert_array_equal(got, want)
    Pd, Pi, zero, ws = [P0D, P0D], list(P0i), np.zeros(4), []
    Qd, Qi = Q, np.zeros_like(Q)
    for k in range(z1.shape[1]):
        if k:
            for j, R in enumerate((R1, R2)):
                Pd[j], Pi[j] = feedback._local_update(F, H, Qd, Qi, R, Pd[j], Pi[j])[3:]
        ws.append(es.split_covariance_intersection(zero, Pd[0], Pi[0], zero, Pd[1], Pi[1],
                                                   same_omega=rule == "printed").omega)
    np.testing.assert_array_equal(batched.omega, ws)
    assert 0.0 < batched.omega.min() and batched.omega.max() <= 1.0
