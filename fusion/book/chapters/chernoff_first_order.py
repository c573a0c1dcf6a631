"""Chapter 06 appendix: a sigma-point first-order fusion in place of step D's mixture of powers.

Günay et al. (2014) approximate the Chernoff fusion of Gaussian mixtures with sigma points; this is the book's
reconstruction from the paper's abstract, run on the two-mixture example and on random pairs of mixtures.

References
----------
* Günay, M., Orguner, U. & Demirekler, M. (2014). Approximate Chernoff fusion of Gaussian mixtures using
   sigma-points. *Proceedings of the 17th International Conference on Information Fusion*, Salamanca (book bib key
   ``gunay2014sigma``).
"""

from __future__ import annotations
import dataclasses
from collections.abc import Callable, Sequence
from dataclasses import dataclass
import numpy as np
import pandas as pd
from numpy.typing import ArrayLike
from fusion._guards import own_underflow
from fusion._results import ResultSpec, instance, number, table, validated_post_init
from fusion._limits import SIGMA_FIRST_ORDER_STUDY, STUDY_WORK
from fusion._validation import FloatArray, as_rng, allocation, count, instance_of, work
from fusion.estimates.chernoff._product import product_size
from fusion.book.tables import rounded
from fusion.estimates import chernoff as ch
from fusion.estimates.chernoff import mixture as chm
from fusion.estimates import mixtures as mx
from fusion.scenarios import two_mixtures
from fusion.book.chapters.chernoff_steps import MARGIN, _gaussian_rows, _log_densities, _logpdf, paired_numbers
from fusion.book.glue import GlueValues

__all__ = ['sigma_point_first_order', 'random_two_mixtures', 'SIGMA_RANDOM_NODES', 'SAME_DENSITY_NATS', 'SigmaProblem', 'sigma_first_order_problem', 'SigmaFirstOrderStudy', 'sigma_first_order_study']


# ---------------------------------------------------------------------------------------------- step D: sigma points


def sigma_point_first_order(gms: list[mx.GaussianMixture] | tuple[mx.GaussianMixture, ...], eps: ArrayLike
                    ) -> ch.FirstOrderMixture:
    r"""A sigma-point first-order fusion in place of step D's mixture of powers (after Günay et al. 2014).

    With the responsibilities :math:`\gamma_{is}(x) = \pi_{is}\mathcal N_{is}(x)/\hat p_i(x)` the fused density is
    exactly

    .. math:: \prod_i\hat p_i^{\varepsilon_i} = \sum_m \prod_i(\pi_{i,s_i}\mathcal N_{i,s_i})^{\varepsilon_i}
              \,R_m(x), \qquad R_m(x) = \prod_i\gamma_{i,s_i}(x)^{1-\varepsilon_i} \in [0, 1],

    a sum over the component tuples :math:`m` of step D. Step D's first-order approximation sets :math:`R_m = 1`
    (whence :math:`Z_{\rm FO} \ge Z`); here :math:`R_m` is replaced by its average over the :math:`2d` symmetric
    sigma points :math:`\mu_m \pm \sqrt d\,L_m e_j` of the tuple's fused Gaussian :math:`\mathcal N(\mu_m, P_m)`.
    The result is again a mixture of the same Gaussians, with weights
    :math:`\propto\tilde\alpha_m\bar R_m`, and the closed-form normaliser :math:`\sum_m\tilde\alpha_m\bar R_m \le
    Z_{\rm FO}`. Our reconstruction from the paper's abstract (a sigma-point approximation of the densities giving a
    closed-form cost and an analytical fused mixture); the paper's own formulas may differ.

    Parameters
    ----------
    gms : sequence of GaussianMixture
        The N node mixtures.
    eps : array_like, shape (N,)
        Exponents on the simplex.

    Returns
    -------
    FirstOrderMixture
        The fused mixture (components of weight below 1e-12 pruned) and its log normaliser (field ``log_z_first_order``).

    Raises
    ------
    ValueError
        As :func:`fusion.estimates.chernoff.first_order_fusion`: ``eps`` off the simplex, or ``gms`` whose product
        mixture (``S ** N`` component tuples, S the largest mixture's components) is beyond the memory or work budget,
        or whose sigma points' component densities (``2d S ** N`` points x ``S`` components, each mixture's) are,
        naming ``gms`` before any array is built (fuzz 69b C3).
    """
    chm._check_mixtures(gms)
    e = ch.check_simplex(eps, len(gms))
    # the product mixture's tuples by the estimates' rule (fuzz 35a C7): ~0.3 us a tuple-mixture measured at d = 2,
    # the first-order fusion's weight
    tuples, per = product_size(1, len(gms), max(g.weights.size for g in gms), gms[0].dim, "gms", first_order=True)
    work((tuples,), "gms (the product mixture's component tuples)", weight=per)
    _sigma_point_budget(len(gms), max(g.weights.size for g in gms), gms[0].dim, "gms")
    return _sigma_point_fusion(gms, e, _weighted_component_rows)


#: Units (``fusion._limits.MAX_WORK``'s 10 ns) of one sigma point x component x mixture of
#: :func:`_sigma_point_fusion` (each mixture padded to the largest S, so S**N tuples of 2d points each) are
#: ``_SP_POINT_BASE + d``: twice the measured 23-26 ns at d = 2 (one mixture of 1 and one of 100 or 150 components:
#: 0.19 s for 8.0e6, 0.63 s for 2.7e7; 100 x 100: 0.21 s for 8.0e6), 32.5 ns at d = 4 (1 x 60) and 56 ns at d = 8
#: (1 x 40); process_time, minimum of 2, OPENBLAS_NUM_THREADS=1, the machine shared. Fuzz 69b C2/C3: only the
#: tuples' first-order weight was counted, so 250 x 250 was refused by an inner ``a`` and 1 x 1500 in chapter 06's
#: problem ran to a raw MemoryError.
_SP_POINT_BASE = 3
#: Arrays of the sigma points' (2d S**N, S) component rows at :func:`_sigma_point_fusion`'s peak: tracemalloc's peak
#: 4.1 of one (1 x 100 components, d = 2; fuzz 69b C3).
_SP_ARRAYS = 5


def _sigma_point_budget(n: int, s: int, d: int, names: str) -> None:
    """Refuse :func:`_sigma_point_fusion` of ``n`` mixtures padded to ``s`` components in dimension ``d`` whose
    (2d s**n, s) component rows are beyond the memory budget or whose density evaluations (those rows for each
    mixture) are beyond the work budget, naming ``names`` (fuzz 69b C2/C3), before any array is built."""
    points = 2 * d * s**n
    allocation((points, s), f"{names} (the sigma points' component densities, {s}**{n} tuples padded to the "
                            "largest mixture)", arrays=_SP_ARRAYS)
    work((points, s, n), f"{names} (the sigma points' component densities, {s}**{n} tuples padded to the largest "
                         "mixture)", weight=_SP_POINT_BASE + d)


def _weighted_component_rows(g: mx.GaussianMixture, x: FloatArray, S: int) -> FloatArray:
    r""":math:`\log\pi_s + \log\mathcal N_s(x)` of ``g``'s components at the points ``x`` (n, d), as (n, S)
    columns (``-inf`` for a component of weight zero and for the padding up to ``S``): each kept component's log
    density is the one-component mixture's ``_logpdf`` (the same numbers), all at once."""
    comp = np.full((x.shape[0], S), -np.inf)
    kept = np.flatnonzero(g.weights > 0)
    rows = _gaussian_rows(np.zeros(kept.size), g.means[kept], g.covs[kept], x)
    for j, s in enumerate(kept):
        comp[:, s] = np.log(g.weights[s]) + rows[j]
    return comp


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _sigma_point_fusion(gms: Sequence[mx.GaussianMixture], e: FloatArray,
                        component_rows: Callable[[mx.GaussianMixture, FloatArray, int], FloatArray]
                        ) -> ch.FirstOrderMixture:
    """:func:`sigma_point_first_order` on validated mixtures and exponents ``e``, the components' weighted log
    densities at the sigma points from ``component_rows`` (:func:`_weighted_component_rows`; the parity reference
    in ``benchmarks/_reference_kernels.py`` passes its einsum form)."""
    logw, means, covs = chm._mixture_arrays(list(gms))
    N, S, d = means.shape
    wg, mug, Pg, log_z = chm._first_order_arrays(logw[None], means[None], covs[None], e[None])
    wg, mug, Pg = wg[0], mug[0], Pg[0]
    L = np.linalg.cholesky(Pg) * np.sqrt(d)
    pts = mug[:, None, :] + np.concatenate([np.swapaxes(L, -1, -2), -np.swapaxes(L, -1, -2)], axis=1)  # (M, 2d, d)
    flat = pts.reshape(-1, d)
    idx = np.array(np.meshgrid(*[np.arange(S)] * N, indexing="ij")).reshape(N, -1).T  # tuples, lexicographic
    logR = np.zeros(flat.shape[0])
    M = idx.shape[0]
    owner = np.repeat(np.arange(M), 2 * d)
    for i, g in enumerate(gms):
        comp = component_rows(g, flat, S)
        lse = mx.logsumexp(comp.T, axis=0)
        with np.errstate(invalid="ignore"):
            lg = comp[np.arange(flat.shape[0]), idx[owner, i]] - lse
        logR += (1.0 - e[i]) * np.where(np.isfinite(lg), lg, -np.inf)
    rbar = np.exp(logR).reshape(M, 2 * d).mean(axis=1)
    with np.errstate(divide="ignore"):
        lw = np.where((wg > 0) & (rbar > 0), np.log(np.where(wg > 0, wg, 1.0)) + np.log(np.where(rbar > 0, rbar, 1.0)),
                      -np.inf)
    top = mx.logsumexp(lw)
    w = np.exp(lw - top)
    keep = w > 1e-12
    return ch.FirstOrderMixture(mixture=mx.GaussianMixture(w[keep] / w[keep].sum(), mug[keep], Pg[keep]),
                         log_z_first_order=float(log_z[0] + top))


def random_two_mixtures(rng: np.random.Generator) -> tuple[mx.GaussianMixture, mx.GaussianMixture]:
    r"""Two random 2-D mixtures of 2-3 components, inside the quadrature grid of the two-mixture example.

    Means uniform on :math:`[-3, 3]^2`, covariances :math:`s^2(AA^\top/2 + I/4)` with :math:`A` standard normal and
    :math:`\log_2 s` uniform on [-1, 0.5], weights Dirichlet(2, ..., 2).

    Parameters
    ----------
    rng : numpy.random.Generator

    Returns
    -------
    tuple of GaussianMixture
        The two mixtures (a, b), each of 2 or 3 components, drawn one after the other from ``rng``.
    """
    as_rng(rng)  # a Generator itself, over a numpy bit generator (fuzz 57b C1)
    out = []
    for _ in range(2):
        S = int(rng.integers(2, 4))
        A = rng.standard_normal((S, 2, 2))
        s2 = 4.0 ** rng.uniform(-1, 0.5, (S, 1, 1))
        covs = s2 * (np.einsum("sij,skj->sik", A, A) / 2 + 0.25 * np.eye(2))
        out.append(mx.GaussianMixture(rng.dirichlet(np.full(S, 2.0)), rng.uniform(-3, 3, (S, 2)),
                                      0.5 * (covs + np.swapaxes(covs, 1, 2))))
    return out[0], out[1]


#: Quadrature grid of :func:`sigma_first_order_problem`: half-width and nodes per axis (those of
#: :func:`fusion.scenarios.two_mixtures.grid_log_normaliser`).
_SIGMA_GRID = (9.0, 601)
#: Nodes per axis for the random problems of :func:`sigma_first_order_study` (the same square; spacing 0.045).
SIGMA_RANDOM_NODES = 401


@dataclass(frozen=True)
class SigmaProblem:
    r"""Step D's first-order mixture and the sigma-point mixture against the exact answer on one problem.

    Attributes
    ----------
    omega_exact : float
        :math:`\omega^*`, the minimiser of the exact :math:`\log Z(\omega)` (quadrature).
    omega_first_order, tv_first_order, logz_first_order : float
        Step D (the mixture of powers): the minimiser of its own normaliser; the total-variation distance of its
        fused mixture from the exact fused density at :math:`\omega^*` (on the grid); its normaliser's error at
        :math:`\omega^*` (nats).
    omega_sp, tv_sp, logz_sp : float
        The same for the sigma-point mixture (:func:`sigma_point_first_order`).
    """

    omega_exact: float
    omega_first_order: float
    tv_first_order: float
    logz_first_order: float
    omega_sp: float
    tv_sp: float
    logz_sp: float

    __result_spec__ = ResultSpec({**{f"omega_{k}": number(bounds=(0.0, 1.0)) for k in ("exact", "first_order", "sp")},
                                  **{f"tv_{k}": number(bounds=(0.0, 1.0)) for k in ("first_order", "sp")},
                                  **{f"logz_{k}": number(nonnegative=False) for k in ("first_order", "sp")}})
    __post_init__ = validated_post_init



#: Units (``fusion._limits.MAX_WORK``'s 10 ns) of one node of :func:`sigma_first_order_problem`'s n x n grid (both
#: mixtures' log-densities, the exact and both approximate normalisers and their searches): about 0.8-0.9 us (the
#: two-mixture example, n 401 -> 1,201: 0.125 -> 1.321 CPU-s; a random problem 0.138 -> 1.115; process_time, minimum of
#: 2, OPENBLAS_NUM_THREADS=1, the shared machine loaded), weighed twice (book audit 76: only the memory budget, so
#: n = 11,000, about 1.2e8 nodes and some 100 CPU-s, was accepted).
_SIGMA_NODE = 200
#: Units of one random problem of :func:`sigma_first_order_study` (:data:`SIGMA_RANDOM_NODES` per axis, the mixtures
#: drawn): about 120 ms (runs 5 -> 25: 0.979 -> 3.371 CPU-s, as above), weighed twice (book audit 76: no budget, so
#: 10**7 problems were accepted).
_SIGMA_PROBLEM = 24_000_000
#: Units of one node x component of a density :func:`sigma_first_order_problem` evaluates on its grid (``a`` and
#: ``b``, then each method's fused mixture of up to S_a x S_b components): twice the 40-46 ns measured where the
#: arrays are large (S_a = S_b = 60 at n = 201, 13.5 CPU-s for 2 x 1.45e8 node-components, 46 ns; 30 at n = 201,
#: 3.4 CPU-s for 7.5e7, 45 ns; ``_logpdf`` alone 14-16 ns at 8 MB, 26-28 ns at 1.2 GB; process_time, minimum of 2,
#: OPENBLAS_NUM_THREADS=1, the machine shared). Fuzz 68b C9/C9b: only the n x n nodes were counted, so
#: 100-component mixtures ran to a raw MemoryError (a 3 GiB array) and 60 components ran 14.9 CPU-s.
_GRID_COMPONENT = 9
#: Calls of each method's fusion in :func:`sigma_first_order_problem` (its bounded search, then its fused mixture at
#: ω* and its normaliser there): at most 16 measured (33 problems: the book's, random ones, 3-30 components), 20 here.
_SEARCH_CALLS = 20
#: Units of a component tuple of one first-order fusion call (the search's): twice the 1.5 us measured at 3,600-10,000
#: tuples (5.5 ms, 14.6 ms; 9 us a tuple at 100 tuples, whose call overhead :data:`_SIGMA_NODE` covers; fuzz 68b C9).
_FO_TUPLE = 300


#: :func:`sigma_first_order_problem` refuses two mixtures whose exact log Z at ω = 1/2 lies at most this far below
#: the mean of its end points (nats; the Bhattacharyya distance of a and b): one density, whose ω* is undetermined.
SAME_DENSITY_NATS = 1e-12


def _problem_budget(s_a: int, s_b: int, n: int) -> None:
    """The memory and work of :func:`sigma_first_order_problem` by its mixtures' components and grid, refused naming
    ``a, b and n`` before the grid (fuzz 68b C9, C9b): each fused mixture of up to ``s_a * s_b`` components on the
    n x n nodes (two arrays of that shape at once, tracemalloc's peak of ``_logpdf``: 2.00-2.01 of one), the two
    mixtures' own densities there, and each method's fusions in its search, both padded to ``max(s_a, s_b) ** 2``
    tuples (the sigma-point fusion's 4 points x ``max(s_a, s_b)`` components each; fuzz 69b C2/C3)."""
    tuples, nodes, s = s_a * s_b, n * n, max(s_a, s_b)
    allocation((tuples, nodes), "a, b and n (the fused mixture's components on the n x n grid)", arrays=2)
    # both fusions pad a and b to the larger s, so s**2 tuples, of 4 sigma points and s components each in the
    # sigma-point fusion (fuzz 69b C2/C3: s_a * s_b tuples were counted, so 1 x 200 ran 45 CPU-s and 1 x 1500 to a
    # raw MemoryError); the weights are those of sigma_point_first_order's own budget
    allocation((4 * s * s, s), "a, b and n (the sigma points' component densities, both mixtures padded to the "
               "larger)", arrays=_SP_ARRAYS)
    grid = nodes * (s_a + s_b + 2 * tuples) * _GRID_COMPONENT
    search = _SEARCH_CALLS * s * s * (_FO_TUPLE + 4 * s * 2 * (_SP_POINT_BASE + 2))
    work((1,), "a, b and n (the mixtures' components on the n x n grid and in each method's search)",
         weight=grid + search)


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def sigma_first_order_problem(a: mx.GaussianMixture, b: mx.GaussianMixture, n: int = _SIGMA_GRID[1]) -> SigmaProblem:
    r"""Step D's first-order mixture and the sigma-point mixture against the exact answer, for two 2-D mixtures.

    The exact :math:`\log Z(\omega)` and :math:`p_{(\omega, 1-\omega)}` come from quadrature on the grid of
    :func:`fusion.scenarios.two_mixtures.grid_log_normaliser`; each method's exponent minimises its own
    normaliser (bounded scalar search on [0, 1]).

    Parameters
    ----------
    a, b : GaussianMixture
        Two 2-D mixtures.
    n : int
        Quadrature nodes per axis on :math:`[-9, 9]^2` (>= 2; its n x n grid within the memory budget, 2 GiB). A
        resolution, not checked against the mixtures: the "exact" values are those of the quadrature, as exact as
        its spacing ``18 / (n - 1)`` resolves the components (the default's 0.03 does the book's mixtures; a grid
        of a few nodes, ``n = 2`` its four corners, returns a valid result whose ω* says nothing about the
        mixtures: fuzz 24b D2, kept valid as documented since the function cannot tell a fine enough grid).

    Returns
    -------
    SigmaProblem
        The exact minimiser ω* (of the quadrature); per method its own minimiser, the total variation to the exact fusion at ω* and its
        log-normaliser error there (nats).

    Raises
    ------
    TypeError
        ``a`` or ``b`` not a mixture, ``n`` not an integer.
    ValueError
        ``a`` or ``b`` not 2-D, ``n`` below 2, an n x n grid beyond the memory budget
        (``fusion._validation.allocation``) or the work budget (``fusion._limits.MAX_WORK``: n about 2,200), ``a`` and
        ``b`` whose components (their fused mixture's ``S_a * S_b`` on the grid, and in each method's search the
        ``max(S_a, S_b) ** 2`` padded tuples with the sigma points' densities) with ``n`` are beyond those budgets
        (fuzz 68b C9, fuzz 69b C2/C3), before the grid; or ``b`` the same density as ``a`` on the grid
        (their Bhattacharyya distance at most :data:`SAME_DENSITY_NATS`; ``a`` itself, or its components reordered or split): every
        exponent then gives the same fusion and ω* is undetermined (fuzz 26b D5: the bounded search returned its
        end point as "exact").
    """
    for name, gm in (("a", a), ("b", b)):
        instance_of(gm, mx.GaussianMixture, name)
        if gm.means.shape[1] != 2:  # the quadrature grid is 2-D (issue 35: refused naming the inner gms)
            raise ValueError(f"{name} must be a 2-D mixture (the grid is on [-9, 9]^2), got dimension "
                             f"{gm.means.shape[1]}")
    from scipy.optimize import minimize_scalar

    n = count(n, "n", minimum=2)
    allocation((n, n, 2), "n")  # the n x n grid's log-densities of the two mixtures, before they are computed
    work((n, n), "n", weight=_SIGMA_NODE)  # the grid's nodes, before any is computed (book audit 76)
    _problem_budget(a.weights.size, b.weights.size, n)
    axis = np.linspace(-_SIGMA_GRID[0], _SIGMA_GRID[0], n)
    X, Y = np.meshgrid(axis, axis)
    pts = np.column_stack([X.ravel(), Y.ravel()])
    L = _log_densities([a, b], pts)
    log_cell = float(2 * np.log(axis[1] - axis[0]))

    L0, L1 = np.ascontiguousarray(L[:, 0]), np.ascontiguousarray(L[:, 1])
    lse = mx._logsumexp if np.isfinite(L).all() else mx.logsumexp  # finite L: every w in [0, 1] passes its checks

    def exact(w: float) -> float:
        return float(lse(L0 * w + L1 * (1 - w), 0)) + log_cell

    def first_order(w: float) -> float:
        return ch.first_order_fusion([a, b], [w, 1 - w]).log_z_first_order

    def sp(w: float) -> float:
        return sigma_point_first_order([a, b], [w, 1 - w]).log_z_first_order

    # fuzz 26b D5: log Z is convex in ω with log Z(0) = log Z(1) (both normalised), below them in between unless a
    # and b are one density (Hölder's equality): then every ω gives the same fusion and ω* is no number at all
    dip = 0.5 * (exact(0.0) + exact(1.0)) - exact(0.5)
    if dip <= SAME_DENSITY_NATS:
        raise ValueError(f"b is the same density as a on the grid (log Z(1/2) is {dip:.2g} nats below the mean of its "
                         f"end points, at most {SAME_DENSITY_NATS:g}): every exponent gives the same fusion, so the "
                         "exact ω* is undetermined")
    opts = {"bounds": (0.0, 1.0), "method": "bounded", "options": {"xatol": 1e-6}}
    w_star = float(minimize_scalar(exact, **opts).x)  # type: ignore[call-overload]
    out = {"omega_exact": w_star}
    a_ = L[:, 0] * w_star + L[:, 1] * (1 - w_star)
    p = np.exp(a_ - mx.logsumexp(a_))
    for key, f, fuse in (("first_order", first_order, ch.first_order_fusion), ("sp", sp, sigma_point_first_order)):
        out[f"omega_{key}"] = float(minimize_scalar(f, **opts).x)  # type: ignore[call-overload]
        q = np.exp(_logpdf(fuse([a, b], [w_star, 1 - w_star]).mixture, pts) + log_cell)
        out[f"tv_{key}"] = float(0.5 * np.sum(np.abs(p - q)))
        out[f"logz_{key}"] = f(w_star) - exact(w_star)
    return SigmaProblem(**out)


#: The cells of :attr:`SigmaFirstOrderStudy.runs`: the fields of :class:`SigmaProblem` by its own rules (exponents and
#: total variations in [0, 1], normaliser errors finite), which the table's medians read (decision 33b).
_SIGMA_CELLS = {**{f"omega_{k}": (0.0, 1.0, False) for k in ("exact", "first_order", "sp")},
                **{f"tv_{k}": (0.0, 1.0, False) for k in ("first_order", "sp")},
                **{f"logz_{k}": (-np.inf, np.inf, False) for k in ("first_order", "sp")}}


@dataclass(frozen=True)
class SigmaFirstOrderStudy:
    """Step D's first-order mixture against the sigma-point mixture: the two-mixture example and random problems.

    Attributes
    ----------
    toy : SigmaProblem
        :func:`sigma_first_order_problem` on the chapter's two-mixture example.
    runs : DataFrame
        One row per random problem (:func:`random_two_mixtures`), the fields of :class:`SigmaProblem` as columns;
        no row twice (a repeated problem would count as two).
    """

    toy: SigmaProblem
    runs: pd.DataFrame

    __result_spec__ = ResultSpec({"toy": instance(SigmaProblem),
                                  "runs": table(*(f.name for f in dataclasses.fields(SigmaProblem)),
                                                key=tuple(f.name for f in dataclasses.fields(SigmaProblem)),
                                                cells=_SIGMA_CELLS)})
    __post_init__ = validated_post_init


    def table(self) -> pd.DataFrame:
        """The example and the random problems' medians: exponent error, normaliser error, total variation."""
        rows = []
        for label, v in (("two-mixture example", dataclasses.asdict(self.toy)),
                         (f"{len(self.runs)} random problems (median)", self.runs.median().to_dict())):
            for key, name in (("first_order", "step D (mixture of powers)"), ("sp", "sigma points")):
                err = (abs(v[f"omega_{key}"] - v["omega_exact"]) if label.startswith("two")
                       else float(np.median(np.abs(self.runs[f"omega_{key}"] - self.runs["omega_exact"]))))
                rows.append({"problems": label, "fusion": name, "|ω − ω*|": rounded(err),
                             "log Z error at ω* (nats)": rounded(v[f"logz_{key}"]),
                             "total variation from p at ω*": rounded(v[f"tv_{key}"])})
        return pd.DataFrame(rows).set_index(["problems", "fusion"])

    def glue(self) -> GlueValues:
        """Glue ``chf_sp_*``: the example's exponents and distances; on the random problems the paired differences
        (sigma points minus step D) of the exponent error and of the total variation, with 95 % intervals."""
        t, r = self.toy, self.runs
        v: GlueValues = {"chf_sp_omega_star": rounded(t.omega_exact), "chf_sp_omega_first_order": rounded(t.omega_first_order),
                         "chf_sp_omega_sp": rounded(t.omega_sp), "chf_sp_tv_first_order": rounded(t.tv_first_order),
                         "chf_sp_tv_sp": rounded(t.tv_sp), "chf_sp_logz_first_order": rounded(t.logz_first_order),
                         "chf_sp_logz_sp": rounded(t.logz_sp), "chf_sp_runs": int(len(r))}
        v.update(paired_numbers(np.abs(r["omega_sp"] - r["omega_exact"]), np.abs(r["omega_first_order"] - r["omega_exact"]),
                                "chf_sp_eps", relative_margin=MARGIN))
        v.update(paired_numbers(r["tv_sp"], r["tv_first_order"], "chf_sp_tvd", relative_margin=MARGIN))
        for k in ("runs",):
            v.pop(f"chf_sp_eps_{k}"), v.pop(f"chf_sp_tvd_{k}")
        return v


def sigma_first_order_study(rng: np.random.Generator, runs: int = 100) -> SigmaFirstOrderStudy:
    """:func:`sigma_first_order_problem` on the two-mixture example and on ``runs`` random problems (grid of
    :data:`SIGMA_RANDOM_NODES` nodes per axis for those).

    Parameters
    ----------
    rng : numpy.random.Generator
        Draws the random problems.
    runs : int
        Random problems, at least 2 (the glued paired differences need two runs).

    Returns
    -------
    SigmaFirstOrderStudy
        The two-mixture example's :class:`SigmaProblem` and a DataFrame of the random problems, one row each.

    Raises
    ------
    ValueError
        ``runs`` below 2 or beyond the work budget (``fusion._limits.STUDY_WORK``'s entry for the appendix's call:
        about 205 problems).
    """
    as_rng(rng)  # a Generator itself, over a numpy bit generator (fuzz 57b C1)
    runs = count(runs, "runs", minimum=2)
    # the example's grid and every problem, before the first (book audit 76: no budget); a STUDY_WORK entry, the
    # appendix's 100 problems counting 2.47e9 units
    work((_SIGMA_GRID[1] ** 2 * _SIGMA_NODE + runs * _SIGMA_PROBLEM,), "runs", limit=STUDY_WORK[SIGMA_FIRST_ORDER_STUDY],
         served=SIGMA_FIRST_ORDER_STUDY)
    toy = two_mixtures.toy_mixtures()
    rows = [sigma_first_order_problem(*random_two_mixtures(rng), n=SIGMA_RANDOM_NODES) for _ in range(runs)]
    return SigmaFirstOrderStudy(toy=sigma_first_order_problem(toy.a, toy.b),
                                runs=pd.DataFrame([dataclasses.asdict(row) for row in rows]))


