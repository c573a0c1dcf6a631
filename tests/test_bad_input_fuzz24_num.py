"""Fuzz 24a, numerical classes V and E (issue 35): results that must not depend on an offset or on a huge callable
output.

V (V1-V3): the centred and sample variance estimates of ``fusion.readings.weighting`` (and the centred one of
``fusion.readings.consistency.consistency_awf``) are covariances, unchanged by a common offset of the readings; from
raw moments :math:`E[X^2] - E[X]^2` an offset of 1e8 on a spread of 1 gave negative sample variances. They are
checked against an exact reference in fractions on readings of a 1/64 grid (the offset readings are exact in
float64). The ``"lecture"`` estimator uses raw moments by the source's definition and is not shift invariant.
E (E1): ``expected_mse`` squares what ``register`` returns: a value
beyond the magnitude rule (1e150) is refused naming ``register``, and an expected MSE beyond the float range from
in-range inputs is refused naming them.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion.readings import consistency as cs
from fusion.readings import weighting as wt
from fusion import registration as rm

_X0 = np.round(np.random.default_rng(0).normal(0, 1, (40, 3)) * np.array([1.0, 2.0, 3.0]) * 64) / 64
_OFFSETS = st.builds(lambda m, e: m * 10.0**e, st.sampled_from([1.0, -1.0, 3.0, -7.0]), st.integers(0, 9))


def _exact(X: np.ndarray, weights: list[Fraction], estimator: str) -> np.ndarray:
    """The estimate from the weighted averages of the readings (rows) ``X``, in fractions: centred (Grubbs-type
    cross-covariance estimate) or sample (each sensor's own covariance)."""
    rows = [[Fraction(float(v)) for v in row] for row in X]
    tot = sum(weights)
    n = len(rows[0])
    m = [sum(w * r[p] for w, r in zip(weights, rows)) / tot for p in range(n)]
    C = [[sum(w * (r[p] - m[p]) * (r[q] - m[q]) for w, r in zip(weights, rows)) / tot for q in range(n)]
         for p in range(n)]
    if estimator == "sample":
        return np.array([float(C[p][p]) for p in range(n)])
    return np.array([float(C[p][p] - sum(C[p][q] for q in range(n) if q != p) / (n - 1)) for p in range(n)])


def _close(got: np.ndarray, exact: np.ndarray) -> None:
    """Within 1e-9 of the largest exact variance (the round-off of the spread's scale, not of the offset's)."""
    np.testing.assert_allclose(got, exact, rtol=0, atol=1e-9 * float(np.abs(exact).max()))


@settings(max_examples=25, deadline=None)
@given(c=_OFFSETS)
def test_v1_centred_estimates_do_not_depend_on_an_offset(c: float) -> None:
    X = _X0 + c  # exact: a 1/64 grid within 2^53 / 64
    exact = _exact(_X0, [Fraction(1)] * len(_X0), "centred")
    _close(wt.variance_estimates(X, "centred"), exact)
    _close(wt.running_variances(X, "centred")[-1], exact)
    _close(wt.tracking_variances(X, "centred")[-1], exact)
    _close(wt.awf(X, "centred").variances[-1], exact)
    _close(cs.consistency_awf(X, 1e3, "centred").awf.variances[-1], exact)  # nothing rejected at eps = 1e3


@settings(max_examples=25, deadline=None)
@given(c=_OFFSETS, estimator=st.sampled_from(["centred", "sample"]), window=st.integers(2, 40))
def test_v2_v3_windowed_estimates_do_not_depend_on_an_offset(c: float, estimator: str, window: int) -> None:
    got = wt.tracking_variances(_X0 + c, estimator=estimator, memory="window", window=window)[-1]
    _close(got, _exact(_X0[-window:], [Fraction(1)] * window, estimator))


@settings(max_examples=15, deadline=None)
@given(c=_OFFSETS, estimator=st.sampled_from(["centred", "sample"]))
def test_v_forgetting_estimates_do_not_depend_on_an_offset(c: float, estimator: str) -> None:
    lam = Fraction(3, 4)
    K = len(_X0)
    got = wt.tracking_variances(_X0 + c, estimator=estimator, memory="forgetting", forgetting=0.75)[-1]
    _close(got, _exact(_X0, [lam ** (K - 1 - i) for i in range(K)], estimator))


def test_v_one_pass_helpers_keep_the_public_arrays_bit_for_bit() -> None:
    X = _X0 + 1e8
    lec, cen, means = wt._running_estimates(X)
    _close(cen[-1], _exact(_X0, [Fraction(1)] * len(_X0), "centred"))
    np.testing.assert_array_equal(lec, wt.running_variances(X, "lecture"))
    np.testing.assert_array_equal(cen, wt.running_variances(X, "centred"))
    np.testing.assert_array_equal(means, wt.running_means(X))
    for memory in ("growing", "window", "forgetting"):
        got = wt._tracking_estimates(X, ("sample", "lecture", "centred"), memory, window=7)
        for e, g in zip(("sample", "lecture", "centred"), got):
            np.testing.assert_array_equal(g, wt.tracking_variances(X, e, memory, window=7))


def test_v_lecture_estimator_uses_raw_moments_by_definition() -> None:
    # R_pp - mean_q R_pq with raw moments: an offset changes it (documented), unlike the centred estimate
    assert "not shift invariant" in " ".join(wt.running_variances.__doc__.split())
    a, b = wt.variance_estimates(_X0, "lecture"), wt.variance_estimates(_X0 + 10.0, "lecture")
    assert not np.allclose(a, b)


@settings(max_examples=20, deadline=None)
@given(e=st.integers(151, 300), ok=st.integers(0, 149))
def test_e1_register_output_beyond_the_magnitude_rule_is_refused(e: int, ok: int) -> None:
    with pytest.raises(ValueError, match="register returned a value of magnitude"):
        rm.expected_mse(lambda z: z[:3] * 10.0**e, np.linspace(0, 1, 6), np.zeros(3), 1.0)
    with pytest.raises(ValueError, match="register returned a value of magnitude"):
        rm.affine_decomposition(lambda z: z[:3] * 10.0**e, np.linspace(0, 1, 6))
    # within the rule: accepted, the exact expected MSE (mean b^2 + sigma^2 |a_k|^2, a_k = 10^ok e_k)
    v = rm.expected_mse(lambda z: z[:3] * 10.0**ok, np.linspace(0, 1, 6), np.zeros(3), 1.0)
    z = np.linspace(0, 1, 6)[:3] * 10.0**ok
    assert v == pytest.approx(float(np.mean(z**2)) + 10.0 ** (2 * ok), rel=1e-12)


def test_e1_register_that_writes_huge_values_into_its_samples_is_refused() -> None:
    def mutator(z: np.ndarray) -> np.ndarray:
        z[:] = 1e300
        return z[:3]

    with pytest.raises(ValueError, match="register"):
        rm.expected_mse(mutator, np.linspace(0, 1, 6), np.zeros(3), 1.0)


def test_e1_expected_mse_beyond_the_float_range_is_refused_naming_the_inputs() -> None:
    # each input in range (sigma 1e150, responses 1e10), sigma^2 |a|^2 = 1e320 is not
    with pytest.raises(ValueError, match="register, z0, truth_at_query and sigma"):
        rm.expected_mse(lambda z: 1e10 * z[:3], np.linspace(0, 1, 6), np.zeros(3), 1e150)


def test_s1_weighted_em_adds_the_documented_absolute_floor() -> None:
    """Fuzz 24a S1, decided (documented): the M-step adds ``floor`` times each coordinate's weighted variance and
    an absolute 1e-12 I; one component on samples of variance 1e-12 gets about twice their covariance."""
    from fusion.estimates.mixtures import weighted_em

    x = np.random.default_rng(3).normal(size=(400, 2)) * 1e-6
    w = np.full(400, 1 / 400)
    fit = weighted_em(x, w, 1, np.random.default_rng(0), max_iter=5, floor=0.0)
    m = w @ x
    sample = ((x - m).T * w) @ (x - m)
    np.testing.assert_allclose(fit.mixture.covs[0], sample + 1e-12 * np.eye(2), rtol=1e-9, atol=0)
