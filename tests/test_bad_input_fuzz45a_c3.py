"""Fuzz 45a C3: a large but valid shared initial velocity variance (``P0d = diag(0, 1e10)`` against a position noise
of 4e-4) made the covariance recursion cancel (the prior far above the posterior), and ``local_track`` returned a
shared part ``Pd`` with a plausible wrong variance (8.11e-6 for 9.45e-6) or a negative one (-3.05e-5 at 1e12); the
readers then refused it by internal names. The split's own invariant ``Pd + Pi = gains.P``, each entry relative to
``sqrt(P_ii P_jj)``, now estimates the round-off, and ``local_track`` refuses above 1e-6 naming ``P0d and P0i``
(its callers: their own arguments)."""

from __future__ import annotations

import dataclasses
import time
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion.filtering.tracks import local_track

F, H = [[1, 0.1], [0, 1]], [[1.0, 0.0]]
Q = [[9.44409928e-08, 1.88881986e-06], [1.88881986e-06, 3.77763971e-05]]   # the infrared/radar model at T = 0.1 s
R = 4e-4


def _track(big: float, K: int = 5):
    return local_track(np.zeros((1, K, 1)), F, H, Q, [[R]], np.zeros((1, 2)), np.diag([0.0, big]), np.diag([R, 0.0]))


def _exact(big: float, K: int):
    """P, Pd and Pi of the recursion in exact rational arithmetic (the float64 inputs read exactly)."""
    f = [[Fraction(x) for x in row] for row in F]
    q = [[Fraction(x) for x in row] for row in Q]
    r = Fraction(R)
    def mul(a, b):
        return [[sum(a[i][k] * b[k][j] for k in range(len(b))) for j in range(len(b[0]))] for i in range(len(a))]
    def tr(a):
        return [list(c) for c in zip(*a)]
    def add(a, b):
        return [[x + y for x, y in zip(u, v)] for u, v in zip(a, b)]
    Pd = [[Fraction(0), Fraction(0)], [Fraction(0), Fraction(big)]]
    Pi = [[r, Fraction(0)], [Fraction(0), Fraction(0)]]
    P = add(Pd, Pi)
    out = [(P, Pd, Pi)]
    for _ in range(1, K):
        Pm = add(mul(mul(f, P), tr(f)), q)
        g = [[Pm[0][0] / (Pm[0][0] + r)], [Pm[1][0] / (Pm[0][0] + r)]]   # H = [1, 0]
        A = [[1 - g[0][0], Fraction(0)], [-g[1][0], Fraction(1)]]
        gRg = [[g[i][0] * r * g[j][0] for j in range(2)] for i in range(2)]
        P = add(mul(mul(A, Pm), tr(A)), gRg)
        Pd = mul(mul(A, add(mul(mul(f, Pd), tr(f)), q)), tr(A))
        Pi = add(mul(mul(A, mul(mul(f, Pi), tr(f))), tr(A)), gRg)
        out.append((P, Pd, Pi))
    return [[np.array([[float(x) for x in row] for row in M]) for M in step] for step in out]


@pytest.mark.parametrize("big", [1e10, 1e12])
def test_diffuse_shared_prior_refused_naming_p0d_and_p0i(big):
    # before: returned, Pd[1][1, 1] = 8.11e-6 (exact 9.45e-6) at 1e10 and -3.05e-5 at 1e12
    t = time.process_time()
    with pytest.raises(ValueError, match=r"^P0d and P0i too large for the model's noise .*round-off.* above 1e-06"):
        _track(big)
    assert time.process_time() - t < 3.0


def test_edge_inside_accepted_and_accurate():
    # 1e8: the estimate 1.5e-7 (true error 8.7e-8); every part within 1e-6 of its scale sqrt(P_ii P_jj) of the exact P
    K = 8
    tr, ex = _track(1e8, K), _exact(1e8, K)
    for k in range(1, K):
        d = np.sqrt(np.diagonal(ex[k][0]))
        for X, ref in zip((tr.gains.P[k], tr.Pd[k], tr.Pi[k]), ex[k]):
            assert (np.abs(X - ref) / np.outer(d, d)).max() <= 1e-6


def test_local_track_invariant_is_unit_invariant():
    # a track re-validated (dataclasses.replace) with a part off by 1e-4 of a small component's own variance: before,
    # accepted (measured against the step's largest entry, 1e8 times larger); now refused
    tr = local_track(np.zeros((1, 4, 2)), np.eye(2), np.eye(2), np.zeros((2, 2)), np.diag([1e8, 1.0]), np.zeros((1, 2)),
                     np.zeros((2, 2)), np.diag([1e8, 1.0]))
    Pd = np.array(tr.Pd)
    Pd[2, 1, 1] += 1e-4 * tr.gains.P[2, 1, 1]
    with pytest.raises(ValueError, match=r"LocalTrack\.Pd and LocalTrack\.Pi must sum to LocalTrack\.gains\.P"):
        dataclasses.replace(tr, Pd=Pd)
    dataclasses.replace(tr, Pd=np.array(tr.Pd))   # as computed: accepted


def test_simulate_names_its_rate_sigma():
    # before: simulate returned; rule_errors then raised "P1 must be positive definite" (an internal name)
    from fusion.scenarios import infrared_radar as ir
    with pytest.raises(ValueError, match=r"^rate_sigma too large for the model's noise"):
        ir.simulate(np.random.default_rng(0), runs=1, rate_sigma=1e6)
    with pytest.raises(ValueError, match=r"^range_rate_sigma too large for the model's noise"):
        ir.simulate(np.random.default_rng(0), runs=1, range_rate_sigma=1e9)


def test_two_sensor_scenario_names_its_velocity_sigma():
    from fusion.scenarios.two_sensor import two_sensor_scenario
    with pytest.raises(ValueError, match=r"^velocity_sigma too large for the model's noise"):
        two_sensor_scenario(np.eye(2), np.eye(2), 1e-4 * np.eye(4), np.random.default_rng(0), runs=1, velocity_sigma=1e8)
    two_sensor_scenario(np.eye(2), np.eye(2), 1e-4 * np.eye(4), np.random.default_rng(0), runs=1, velocity_sigma=1e2)


@settings(max_examples=60, deadline=None)
@given(T=st.floats(0.01, 10.0), q=st.floats(1e-6, 1e2), r=st.floats(1e-4, 1e4), c=st.floats(1e-3, 1e3),
       seed=st.integers(0, 2**32 - 1))
def test_moderate_priors_accepted(T, q, r, c, seed):
    # a constant-velocity model with a shared velocity prior within 1e3 of what one measurement pair gives (r / T**2)
    Fm = [[1.0, T], [0.0, 1.0]]
    Qm = q * np.array([[T**3 / 3, T**2 / 2], [T**2 / 2, T]])
    z = np.random.default_rng(seed).standard_normal((2, 30, 1)) * np.sqrt(r)
    tr = local_track(z, Fm, H, Qm, [[r]], np.zeros((2, 2)), np.diag([0.0, c * r / T**2]), np.diag([r, 0.0]))
    assert np.isfinite(tr.Pd).all()
