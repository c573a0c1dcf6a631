"""The exact checks K1-K5 on random Gaussians, the common-information check and the CI weight by three criteria.

Part of :mod:`fusion.book.chapters.chernoff` (chapter 06, patent CN107330468B), which re-exports its public names."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fusion._guards import own_underflow
from fusion._results import ResultSpec, integer, number, tuple_of, validated_post_init
from fusion._limits import work
from fusion._validation import FloatArray, allocation, as_rng, count
from fusion.book.tables import rounded
from fusion.estimates import chernoff as ch, covariance_intersection, mixtures as mx
from fusion.book.glue import GlueValues

__all__ = ["random_spd", "GaussianChecks", "gaussian_checks", "criteria_example", "common_information_check"]


def random_spd(rng: np.random.Generator, n: int) -> FloatArray:
    """Random symmetric positive definite matrix :math:`AA^\\top + I/2`, :math:`A` standard normal.

    Parameters
    ----------
    rng : numpy.random.Generator
    n : int
        Dimension.

    Returns
    -------
    ndarray, shape (n, n); smallest eigenvalue >= 0.5
        A Aᵀ + I/2 for one standard normal n × n draw A: symmetric, positive definite.

    Raises
    ------
    TypeError
        ``rng`` is not a Generator or ``n`` not an integer.
    ValueError
        ``n`` below 1, or an n x n matrix beyond the memory budget.
    """
    as_rng(rng, "rng")
    n = count(n, "n")
    allocation((n, n), "n")
    A = rng.standard_normal((n, n))
    return A @ A.T + 0.5 * np.eye(n)


# --------------------------------------------------------------------------- K1-K5
@dataclass(frozen=True)
class GaussianChecks:
    """Largest errors of the exact checks on random Gaussians (see :func:`gaussian_checks`).

    Attributes
    ----------
    k1 : float
        Largest relative difference between Chernoff fusion of two Gaussians and covariance
        intersection (eq. ``eq-chf-k1``), over mean and covariance.
    k2 : float
        Largest absolute difference between the general log normaliser and the two-Gaussian
        closed form (eq. ``eq-chf-k2``), nats.
    k3 : float
        Largest log normaliser found (Hölder: must be <= 0).
    kis : float
        ``|ESS/R - 1|`` of importance sampling from the first-order mixture at the same exponents
        (single Gaussians: the weights are constant).
    k5 : float
        Largest ``|KL(p_eps* || p_i) + log Z(eps*)|`` over inputs with positive weight (eq.
        ``eq-chf-equal-kl``), nats.
    n_interior : int
        Triples whose optimal exponents are all positive.
    tolerances : tuple of float
        Tolerances of k1, k2, k5 (kis uses 1e-9); round-off sized errors vary with the BLAS.
    """

    k1: float
    k2: float
    k3: float
    kis: float
    k5: float
    n_interior: int
    tolerances: tuple[float, float, float] = (1e-12, 1e-9, 1e-5)

    __result_spec__ = ResultSpec({**{name: number() for name in ("k1", "k2", "kis", "k5")},
                                  "k3": number(nonnegative=False), "n_interior": integer(0),
                                  "tolerances": tuple_of(number(positive=True), count=3)})
    __post_init__ = validated_post_init

    @property
    def ok(self) -> bool:
        """Whether every check meets its tolerance (and log Z <= 0)."""
        t1, t2, t5 = self.tolerances
        return bool(self.k1 < t1 and self.k2 < t2 and self.k5 < t5 and self.kis < 1e-9 and self.k3 <= 1e-12)

    def glue(self) -> GlueValues:
        """Glue values: the tolerances met (not the round-off errors themselves, which flicker)."""
        t1, t2, t5 = self.tolerances
        return {"chf_k1": t1, "chf_k2": t2, "chf_k5": t5, "chf_k5_interior": self.n_interior}


#: Units (``fusion._limits.MAX_WORK``'s 10 ns) of one case of :func:`gaussian_checks`: a pair of 4-D Gaussians fused
#: two ways, about 1.1 ms (``cases`` 20 -> 200 at one triple: 0.029 -> 0.224 CPU-s, process_time, minimum of 2,
#: OPENBLAS_NUM_THREADS=1, the shared machine loaded), weighed twice (book audit 76: no budget, so 10**7 cases, some
#: 3 CPU-hours, were accepted).
_CHECK_CASE = 220_000
#: Units of one triple of :func:`gaussian_checks` (a Chernoff optimisation of three 2-D Gaussians and three KLs):
#: about 4.2 ms (``triples`` 20 -> 200 at one case: 0.083 -> 0.850 CPU-s, as above), weighed twice (book audit 76).
_CHECK_TRIPLE = 840_000
#: Units of one case of :func:`common_information_check` (a Gaussian fusion and densities on a 2,001-point grid):
#: about 1.4 ms (``cases`` 10 -> 100: 0.013 -> 0.141 CPU-s, as above), weighed twice (book audit 76: no budget, so
#: 10**7 cases, about 4 CPU-hours, were accepted).
_COMMON_CASE = 280_000


def gaussian_checks(rng: np.random.Generator, cases: int = 100, triples: int = 20) -> GaussianChecks:
    """K1-K3 on random pairs of 4-D Gaussians, the Gaussian IS identity and K5 on random triples.

    Parameters
    ----------
    rng : numpy.random.Generator
    cases : int
        Random pairs of 4-D Gaussians (means of scale 100, weights in [0.05, 0.95]).
    triples : int
        Random triples of 2-D Gaussians for the equal-divergence property K5.

    Returns
    -------
    GaussianChecks
        Largest errors of K1-K3 over the pairs, of the IS identity, and of K5 over the triples, with the count of
        interior triples and the tolerances.

    Raises
    ------
    TypeError
        ``rng`` is not a Generator, or ``cases`` or ``triples`` not an integer.
    ValueError
        ``cases`` or ``triples`` below 1 (a check of no case would pass vacuously), or the cases and triples beyond
        the work budget (``fusion._limits.MAX_WORK``: about 4,500 cases, or 1,200 triples).
    """
    as_rng(rng, "rng")
    cases, triples = count(cases, "cases"), count(triples, "triples")
    work((cases * _CHECK_CASE + triples * _CHECK_TRIPLE,), "cases and triples")  # before the first case
    k1 = k2 = k3 = 0.0
    for _ in range(cases):
        a, b = 100 * rng.normal(size=4), 100 * rng.normal(size=4)
        A, B = random_spd(rng, 4), random_spd(rng, 4)
        w = rng.uniform(0.05, 0.95)
        f = ch.chernoff_fuse_gaussians([a, b], [A, B], [w, 1 - w])
        ci = covariance_intersection(a, A, b, B, omega=w)
        err_x = np.max(np.abs(f.x - ci.x)) / np.max(np.abs(ci.x))
        err_P = np.max(np.abs(f.P - ci.P)) / np.max(np.abs(ci.P))
        k1 = max(k1, err_x, err_P)
        k2 = max(k2, abs(f.log_normaliser - ch.log_normaliser_two_gaussians(a, A, b, B, w)))
        k3 = max(k3, f.log_normaliser)
    gs = [mx.GaussianMixture(np.ones(1), rng.normal(size=(1, 4)), random_spd(rng, 4)[None]) for _ in range(3)]
    e = np.array([0.2, 0.5, 0.3])
    g = ch.first_order_fusion(gs, e).mixture
    xs = mx.gm_sample(g, rng, 1000)
    w_is = ch.fused_weights(ch.log_densities(gs, xs), mx.gm_logpdf(g, xs), e)
    kis = abs(1.0 / np.sum(w_is**2) / 1000 - 1.0)
    k5, n_interior = 0.0, 0
    for _ in range(triples):
        means, covs = 2 * rng.normal(size=(3, 2)), np.stack([random_spd(rng, 2) for _ in range(3)])
        opt = ch.gaussian_chernoff_weights(means, covs)
        kl = np.array([ch.gaussian_kl(opt.x, opt.P, m, P) for m, P in zip(means, covs)])
        act = opt.eps > 1e-6
        n_interior += int(act.all())
        k5 = max(k5, float(np.max(np.abs(kl[act] + opt.log_normaliser))))
    return GaussianChecks(float(k1), float(k2), float(k3), float(kis), k5, n_interior)


def criteria_example() -> GlueValues:
    r"""The CI weight ω of A by three criteria on one 2-D Gaussian pair (critique box ``chf-crit-criterion``).

    A = N((0, 0), diag(4, 1)), B = N((2, 1), [[1, .5], [.5, 3]]).

    Returns
    -------
    dict
        ``chf_w_chernoff`` (min log Z), ``chf_w_det`` (min det P = min entropy), ``chf_w_trace``
        (min trace P), ``chf_w_chernoff_same`` (Chernoff with both means at A's).
    """
    a, A = np.array([0.0, 0.0]), np.diag([4.0, 1.0])
    b, B = np.array([2.0, 1.0]), np.array([[1.0, 0.5], [0.5, 3.0]])
    return {k: rounded(v) for k, v in {
        "chf_w_chernoff": ch.gaussian_chernoff_weights([a, b], [A, B]).eps[0],
        "chf_w_det": covariance_intersection(a, A, b, B, criterion="det").omega,
        "chf_w_trace": covariance_intersection(a, A, b, B, criterion="trace").omega,
        "chf_w_chernoff_same": ch.gaussian_chernoff_weights([a, a], [A, B]).eps[0],
    }.items()}


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def common_information_check(rng: np.random.Generator, cases: int = 100) -> tuple[bool, float, float]:
    r"""Chernoff fusion counts common information once: exact checks on random Gaussians and on a grid.

    Gaussian: node posteriors with information :math:`J_0 + J_i` (a common prior :math:`J_0` and independent
    information :math:`J_i`, random 4-D): the fused information is :math:`\sum_i\varepsilon_i(J_0 + J_i) = J_0 +
    \sum_i\varepsilon_iJ_i`, the prior once, whatever the exponents (the naive product has :math:`NJ_0`). Grid:
    densities :math:`p_i \propto c\,q_i` with a common factor :math:`c` and non-Gaussian :math:`q_i` (1-D mixtures):
    the normalised :math:`\prod_ip_i^{\varepsilon_i}` equals the normalised :math:`c\prod_iq_i^{\varepsilon_i}`.

    Parameters
    ----------
    rng : numpy.random.Generator
    cases : int
        Random cases of each kind.

    Returns
    -------
    (bool, float, float)
        Both errors below their tolerances (1e-10 relative; 1e-12 absolute on densities normalised on the
        grid), the largest relative error of the Gaussian information and the largest density difference.

    Raises
    ------
    TypeError
        ``rng`` is not a Generator or ``cases`` not an integer.
    ValueError
        ``cases`` below 1 (a check of no case would pass vacuously) or beyond the work budget
        (``fusion._limits.MAX_WORK``: about 3,500 cases).
    """
    as_rng(rng, "rng")
    cases = count(cases, "cases")
    work((cases,), "cases", weight=_COMMON_CASE)  # before the first case
    err_g = err_d = 0.0
    x = np.linspace(-10, 10, 2001)
    for _ in range(cases):
        N = int(rng.integers(2, 5))
        J0 = random_spd(rng, 4)
        J = np.stack([random_spd(rng, 4) for _ in range(N)])
        e = rng.dirichlet(np.ones(N))
        covs = np.linalg.inv(J0 + J)
        means = rng.normal(size=(N, 4))
        fused_info = np.linalg.inv(ch.chernoff_fuse_gaussians(means, covs, e).P)
        want = J0 + np.einsum("n,nij->ij", e, J)
        err_g = max(err_g, float(np.max(np.abs(fused_info - want)) / np.max(np.abs(want))))
        c = np.exp(-0.5 * (x - rng.normal()) ** 2 / rng.uniform(1, 4))
        q = [0.5 * np.exp(-0.5 * (x - rng.normal(-2, 1)) ** 2) + 0.5 * np.exp(-0.5 * (x - rng.normal(2, 1)) ** 2 / 0.3)
             for _ in range(N)]
        p = [c * qi / np.sum(c * qi) for qi in q]
        f1 = np.prod([pi ** ei for pi, ei in zip(p, e)], axis=0)
        f2 = c * np.prod([qi ** ei for qi, ei in zip(q, e)], axis=0)
        err_d = max(err_d, float(np.max(np.abs(f1 / f1.sum() - f2 / f2.sum()))))
    return bool(err_g < 1e-10 and err_d < 1e-12), err_g, err_d
