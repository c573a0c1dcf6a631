"""Fuzz 24a, classes P and G and debatables D2, D6: covariances singular or ill-conditioned to working precision.

P: LAPACK's Cholesky factorisation succeeds by rounding on some exactly singular matrices (``0.41 * ones((2, 2))``),
so the positive-definite check let them through and the fusions returned plausible wrong numbers. The shared rule
(``fusion._covariances.SINGULAR_MARGIN``) refuses a matrix whose correlation matrix has an eigenvalue within
``2 n eps`` of zero (relative to its largest), naming the argument; ill-conditioned valid covariances (correlation
condition numbers up to about 1e14) and semidefinite parts stay accepted. G: split CI inverts ``Pjd / omega + Pji``,
computed from valid parts: the same rule guards it (``check_invertible``), so it refuses instead of raising
LinAlgError or returning a wrong trace. D2 (decided: documented) the accuracy of the information-form fusions is
about ``cond * eps``. D6 (decided: fixed) a fusion-degree matrix has entries in [0, 1] and a unit diagonal.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.linalg.lapack import dpotrf

from fusion._validation import as_covariance, as_covariances, covariance_pair
from fusion.estimates import ci
from fusion.estimates import chernoff as CH
from fusion.estimates import mixtures
from fusion.readings import fusion_set as fs
from test_bad_input import REG, _fresh, CALLABLES

_EPS = float(np.finfo(float).eps)
S041 = np.full((2, 2), 0.41)  # eigenvalues 0 and 0.82; dpotrf succeeds with a last pivot of 7.45e-09
X1, X2 = np.array([1.0, 2.0]), np.array([1.5, 1.0])
P2 = np.array([[1.0, -0.2], [-0.2, 3.0]])
P1I = np.array([[1.0, 0.15], [0.15, 0.5]])
P2I = np.array([[0.5, -0.1], [-0.1, 1.5]])


def test_p_the_reproducer_passes_lapack_cholesky() -> None:
    """The premise of class P: the matrix is exactly singular yet LAPACK factorises it."""
    assert dpotrf(S041, lower=1, clean=0)[1] == 0
    assert np.linalg.eigvalsh(S041)[0] == 0.0 or abs(np.linalg.eigvalsh(S041)[0]) < 1e-16


@settings(max_examples=300, deadline=None)
@given(logc=st.floats(-3.0, 40.0))
def test_p_exactly_singular_constant_matrices_are_refused_naming_the_argument(logc: float) -> None:
    S = np.full((2, 2), 10.0**logc)
    with pytest.raises(ValueError, match="Pbad"):
        as_covariance(S, name="Pbad")
    with pytest.raises(ValueError, match=r"covs\[1\]"):
        as_covariances(np.stack((np.eye(2), S)), name="covs")
    with pytest.raises(ValueError, match="Pb"):
        covariance_pair(np.eye(2), S, ("Pa", "Pb"))


@settings(max_examples=300, deadline=None)
@given(n=st.integers(2, 6), seed=st.integers(0, 2**32 - 1))
def test_p_rounded_low_rank_products_are_refused(n: int, seed: int) -> None:
    """``B @ B.T`` with fewer columns than rows, rows of scales 1e-5 .. 1e5: singular up to its rounding."""
    rng = np.random.default_rng(seed)
    B = rng.normal(size=(n, int(rng.integers(1, n)))) * np.exp(rng.uniform(-11.5, 11.5, size=(n, 1)))
    S = B @ B.T
    S = 0.5 * (S + S.T)
    with pytest.raises(ValueError, match="Pbad"):
        as_covariance(S, name="Pbad")


@settings(max_examples=300, deadline=None)
@given(n=st.integers(2, 6), logk=st.floats(0.0, 13.0), seed=st.integers(0, 2**32 - 1))
def test_p_ill_conditioned_valid_covariances_stay_accepted_in_any_units(n: int, logk: float, seed: int) -> None:
    """Condition numbers up to 1e13 and per-component units from 1e-60 to 1e60: accepted, unchanged."""
    rng = np.random.default_rng(seed)
    Q, _ = np.linalg.qr(rng.normal(size=(n, n)))
    A = (Q * np.logspace(0.0, -logk, n)) @ Q.T
    A = 0.5 * (A + A.T)
    d = 10.0 ** rng.uniform(-60, 60, size=n)
    P = A * d[:, None] * d[None, :]
    P = 0.5 * (P + P.T)
    assume(dpotrf(P, lower=1, clean=0)[1] == 0)  # LAPACK itself accepts it (always, at these condition numbers)
    np.testing.assert_array_equal(as_covariance(P), P)
    np.testing.assert_array_equal(as_covariances(np.stack((P, P))), np.stack((P, P)))
    covariance_pair(P, P)


def test_p_semidefinite_parts_stay_accepted() -> None:
    """The correlated parts of split CI are documented semidefinite: an exactly singular one is fine."""
    r = ci.split_covariance_intersection(X1, S041, P1I, X2, P2, P2I, omega=0.4)
    assert np.all(np.isfinite(r.P))
    assert np.isfinite(ci.split_ci_objective(0.4, S041, P1I, P2, P2I))


_P_CALLS = {
    "P1 covariance_intersection": lambda: ci.covariance_intersection(X1, S041, X2, P2, omega=1.0),
    "P1 covariance_intersection, omega chosen": lambda: ci.covariance_intersection(X1, S041, X2, P2),
    "P2 convex_combination": lambda: ci.convex_combination(X1, S041, X2, P2),
    "P3 gaussian_logpdf": lambda: mixtures.gaussian_logpdf([[1.0, 2.0]], [1.0, 2.0], S041),
    "P4 chernoff_fuse_gaussians": lambda: CH.chernoff_fuse_gaussians(np.array([X1, X2]), np.array([S041, P2]),
                                                                      np.array([0.5, 0.5])),
    "P5 gaussian_kl": lambda: CH.gaussian_kl(X1, S041, X2, P2),
}
_P_NAMES = {"P1 covariance_intersection": "P1", "P1 covariance_intersection, omega chosen": "P1",
            "P2 convex_combination": "P1", "P3 gaussian_logpdf": "cov", "P4 chernoff_fuse_gaussians": "covs",
            "P5 gaussian_kl": "P0"}


@pytest.mark.parametrize("case", sorted(_P_CALLS))
def test_p1_p5_the_reproducers_are_refused_naming_the_covariance(case: str) -> None:
    with pytest.raises(ValueError, match=_P_NAMES[case]):
        _P_CALLS[case]()


# P6: every argument documented positive definite that accepted 0.41 * ones (the fuzz's sweep, sing041.jsonl)
_P6 = [
    ("fusion.estimates.ci.covariance_intersection", "P1"), ("fusion.estimates.ci.covariance_intersection", "P2"),
    ("fusion.estimates.ci.ci_weight", "P1"), ("fusion.estimates.ci.ci_weight", "P2"),
    ("fusion.estimates.ci.ci_objective", "P1"), ("fusion.estimates.ci.ci_objective", "P2"),
    ("fusion.estimates.ci.convex_combination", "P1"), ("fusion.estimates.ci.convex_combination", "P2"),
    ("fusion.estimates.fuzzy_cluster.fuzzy_cluster_fusion", "Ps"),
    ("fusion.estimates.mixtures.GaussianMixture", "covs"), ("fusion.estimates.mixtures.gaussian_logpdf", "cov"),
    ("fusion.estimates.chernoff.chernoff_fuse_gaussians", "covs"),
    ("fusion.estimates.chernoff.gaussian_log_normaliser", "covs"),
    ("fusion.estimates.chernoff.is_second_moment", "covs"),
    ("fusion.estimates.chernoff.gaussian_chernoff_weights", "covs"),
    ("fusion.estimates.chernoff.covariance_intersection_weights", "covs"),
    ("fusion.estimates.chernoff.gaussian_kl", "P0"), ("fusion.estimates.chernoff.gaussian_kl", "P1"),
    ("fusion.estimates.chernoff.log_normaliser_two_gaussians", "A"),
    ("fusion.estimates.chernoff.log_normaliser_two_gaussians", "B"),
    ("fusion.estimates.chernoff.fuse_mixtures_batch", "covs"),
    ("fusion.filtering.kalman.gain_sequence", "R"), ("fusion.filtering.kalman.split_covariances", "R"),
    ("fusion.filtering.kalman.error_moments", "R"),
]


@pytest.mark.parametrize(("name", "arg"), _P6)
def test_p6_every_positive_definite_argument_refuses_an_exactly_singular_matrix(name: str, arg: str) -> None:
    spec = REG[name]
    value = spec[arg].value
    base = value[0] if isinstance(value, list) else value
    bad = np.full(np.shape(base), 0.41)
    kwargs = _fresh({k: a.value for k, a in spec.items()})
    kwargs[arg] = [bad] + list(value[1:]) if isinstance(value, list) else bad
    with pytest.raises(ValueError, match=arg):
        CALLABLES[name](**kwargs)


def _inv2(m: list[list[Fraction]]) -> list[list[Fraction]]:
    (a, b), (c, d) = m
    det = a * d - b * c
    return [[d / det, -b / det], [-c / det, a / det]]


def _add2(x: list[list[Fraction]], y: list[list[Fraction]]) -> list[list[Fraction]]:
    return [[x[i][j] + y[i][j] for j in range(2)] for i in range(2)]


def _exact(M: np.ndarray) -> list[list[Fraction]]:
    return [[Fraction(float(v)) for v in row] for row in M]


def _split_trace_exact(w: float, P1d: np.ndarray) -> float:
    """The split-CI trace of split_ci_objective in exact rational arithmetic (the parts as stored)."""
    W = Fraction(w)
    T1 = _add2([[v / W for v in row] for row in _exact(P1d)], _exact(P1I))
    T2 = _add2([[v / (1 - W) for v in row] for row in _exact(P2)], _exact(P2I))
    P = _inv2(_add2(_inv2(T1), _inv2(T2)))
    return float(P[0][0] + P[1][1])


@pytest.mark.parametrize("P1d", [np.full((2, 2), 1e17), np.full((2, 2), 3e19), np.full((2, 2), 7e16),
                                 np.full((2, 2), 2**63 - 1, dtype=np.int64)], ids=["1e17", "3e19", "7e16", "int64max"])
def test_g1_g2_split_ci_objective_refuses_a_numerically_singular_system(P1d: np.ndarray) -> None:
    with pytest.raises(ValueError, match="P1d"):
        ci.split_ci_objective(0.4, P1d, P1I, P2, P2I)


def test_g3_split_covariance_intersection_refuses_instead_of_a_wrong_matrix() -> None:
    with pytest.raises(ValueError, match="P1d"):
        ci.split_covariance_intersection(X1, np.full((2, 2), 7e16), P1I, X2, P2, 0.5 * np.eye(2), omega=0.4)


def test_g_an_ill_conditioned_intermediate_matrix_is_refused_not_a_linalg_error() -> None:
    """Parts accepted (``P1d + P1i`` of condition 1e13) but ``P1d / omega + P1i`` singular to working precision."""
    P1d = np.full((2, 2), 1e13)
    with pytest.raises(ValueError, match="P1d, P1i, P2d and P2i"):
        ci.split_ci_objective(1e-3, P1d, P1I, P2, P2I)
    with pytest.raises(ValueError, match="P1d, P1i, P2d and P2i"):
        ci.split_covariance_intersection(X1, P1d, P1I, X2, P2, P2I, omega=1e-3)


@settings(max_examples=200, deadline=None)
@given(logc=st.floats(-2.0, 20.0), w=st.floats(1e-4, 1.0 - 1e-4))
def test_g_split_ci_objective_refuses_or_is_accurate(logc: float, w: float) -> None:
    """Against the exact rational value: an accepted call is accurate to its conditioning (kappa eps with kappa
    below the refusal margin, about 1e15), never off by the factor 2 of the fuzz's G2."""
    P1d = np.full((2, 2), 10.0**logc)
    try:
        got = ci.split_ci_objective(w, P1d, P1I, P2, P2I)
    except ValueError as exc:
        assert "P1d" in str(exc)
        return
    ref = _split_trace_exact(w, P1d)
    assert abs(got - ref) <= 0.25 * abs(ref)
    T1 = P1d / w + P1I
    if np.linalg.cond(T1) < 1e10:
        assert abs(got - ref) <= 1e-5 * abs(ref)


@settings(max_examples=200, deadline=None)
@given(logc=st.floats(0.0, 14.0), w=st.one_of(st.just(0.0), st.just(1.0), st.floats(1e-6, 1.0 - 1e-6)))
def test_d2_information_form_error_is_within_cond_eps(logc: float, w: float) -> None:
    """D2, decided: documented. The error of covariance_intersection / convex_combination grows like cond * eps
    (explicit inverses); tested against exact rational arithmetic on ``P1 = c 11^T + P1i``."""
    c = 10.0**logc
    P1 = np.full((2, 2), c) + P1I
    kappa = float(np.linalg.cond(P1))
    W = Fraction(w)
    A, B = _inv2(_exact(P1)), _inv2(_exact(P2))
    for omega, (a, b) in ((w, (W, 1 - W)), (None, (Fraction(1), Fraction(1)))):
        ref = _inv2(_add2([[a * v for v in r] for r in A], [[b * v for v in r] for r in B]))
        ref_P = np.array([[float(v) for v in r] for r in ref])
        got = ci.covariance_intersection(X1, P1, X2, P2, omega=w).P if omega is not None \
            else ci.convex_combination(X1, P1, X2, P2).P
        assert np.max(np.abs(got - ref_P)) <= 4.0 * kappa * _EPS * np.max(np.abs(ref_P)) + 1e-300


@pytest.mark.parametrize("C", [np.full((3, 3), 9.2e18), np.full((3, 3), 2.0), np.array([[1.0, -0.2], [-0.2, 1.0]]),
                               np.array([[0.5, 0.2], [0.2, 0.5]]), 1e-9 * np.array([[1.0, 0.0], [1.0, 1.0]]),
                               np.array([[1.0, 0.2], [0.2 + 1e-8, 1.0]])],
                         ids=["9.2e18", "2", "negative", "diagonal 0.5", "tiny asymmetric", "asymmetric 1e-8"])
@pytest.mark.parametrize("fn", [fs.distribution_balance, fs.consistency_degree], ids=["balance", "consistency"])
def test_d6_a_matrix_that_is_no_fusion_degree_matrix_is_refused(C: np.ndarray, fn) -> None:
    with pytest.raises(ValueError, match="C must"):
        fn(C)


@settings(max_examples=100, deadline=None)
@given(x=st.lists(st.integers(-10**6, 10**6).map(lambda k: k / 64.0), min_size=1, max_size=8),
       scale=st.floats(1e-3, 1e3))
def test_d6_fusion_degree_matrices_stay_accepted(x: list[float], scale: float) -> None:
    C = fs.fusion_degree_matrix(np.array(x), scale=scale)
    np.testing.assert_array_equal(fs.consistency_degree(C), C.mean(axis=1))
    fs.distribution_balance(C)


@pytest.mark.parametrize("lead", [(), (1,), (3,), (1, 2), (2, 3)])
def test_p_singular_mask_over_any_stack_shape(lead: tuple[int, ...]) -> None:
    """The rule over a stack of any leading shape (fuzz 24b P6c: a (1, 2) stack of 3 x 3 matrices raised an
    IndexError): each matrix judged alone, the exactly singular one found where it sits."""
    from fusion._covariances import singular_mask

    rng = np.random.default_rng(6)
    B = rng.normal(size=(3, 2))
    stack = np.broadcast_to(np.eye(3), lead + (3, 3)).copy()
    where = tuple(k - 1 for k in lead)
    stack[where] = B @ B.T  # rank 2, its correlation matrix's smallest eigenvalue rounds near 0
    expect = np.zeros(lead, dtype=bool)
    expect[where] = True
    np.testing.assert_array_equal(singular_mask(stack), expect)
