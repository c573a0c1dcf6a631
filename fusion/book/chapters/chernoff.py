r"""Chapter 06 (patent CN107330468B, distributed Chernoff fusion): checks, studies, tables, figures, claims.

Everything the chapter's notebook computes beyond calling the package: the exact checks K1-K5 on
random Gaussians, the static two-mixture example, the tables and figures of the tracking study
(:mod:`fusion.scenarios.range_bearing`) and the evidence of the claim file ``book/claims/cn107330468b.yaml``
(functions ``ev_*``, one per record, called by :func:`chapter_evidence` with each reading's settings; the studies
behind them cached, so that the notebook computes each once). The notebook only
calls these functions and glues their values.

References
----------
.. [1] Julier, S. J., Uhlmann, J. K. (1997). A non-divergent estimation algorithm in the presence of
   unknown correlations. *Proc. American Control Conference*, 2369-2373.
.. [2] Hurley, M. B. (2002). An information theoretic justification for covariance intersection and
   its generalization. *Proc. FUSION 2002*, 505-511.
.. [3] Julier, S. J. (2006). An empirical study into the use of Chernoff information for robust,
   distributed fusion of Gaussian mixture models. *Proc. FUSION 2006*.
.. [4] Tichavský, P., Muravchik, C. H., Nehorai, A. (1998). Posterior Cramér-Rao bounds for
   discrete-time nonlinear filtering. *IEEE Trans. Signal Processing* 46(5), 1386-1396.
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import json
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from fusion._validation import FloatArray
from fusion.book.ledger import Comparison, Conjunction, Ledger, Proposition, Unverifiable, fmt
from fusion.book.style import new_figure
from fusion.book.tables import rounded
from fusion.estimates import chernoff as ch
from fusion.estimates import covariance_intersection
from fusion.estimates import mixtures as mx
from fusion.optimise.swarm import particle_swarm
from fusion.scenarios import two_mixtures
from fusion.scenarios.fusion_networks import (NETWORK_METHODS, NetworkStudy, premise_scenarios, redundancy_scenarios,
                                              run_network_study)
from fusion.scenarios.range_bearing import (GUARD_STAGES, METHODS, RangeBearingScenario, TrackingRun, min_local_ess,
                                            linearised_errors, nees_per_frame, position_sq_errors, posterior_crb,
                                            monte_carlo, run_tracking, run_tracking_batch)

__all__ = [
    "BIBKEY",
    "LATE",
    "COLLAPSE_FRACTION",
    "pso_defaults",
    "double_count_values",
    "BENCH_SCHEMA",
    "premise_robust_values",
    "PREMISE_MORE_RUNS",
    "guard_usability",
    "random_spd",
    "GaussianChecks",
    "gaussian_checks",
    "ToyStudy",
    "toy_study",
    "objective_figure",
    "contour_figure",
    "criteria_example",
    "STUDY_RUNS",
    "STUDY_WORKERS",
    "STUDY_REASON",
    "EARLY",
    "ALL_FRAMES",
    "study_scenario",
    "guarded_scenario",
    "IsVarianceStudy",
    "is_variance_study",
    "stopping_values",
    "DesignStudy",
    "design_study",
    "gm_yardstick",
    "consistency_figure",
    "central_collapsed",
    "scenario_values",
    "scenario_table",
    "crb_position",
    "method_table",
    "rmse_figure",
    "per_run_mse",
    "per_run_nees",
    "typical_run",
    "stonesoup_check",
    "STONESOUP_RECORD",
    "review_values",
    "NEES_CONSISTENT",
    "gain_values",
    "collapsed",
    "any_collapsed",
    "collapse_values",
    "guarded_runs",
    "guard_values",
    "eps_figure",
    "pso_figure",
    "benchmark_cost",
    "diagnostics",
    "PREMISE_LABELS",
    "premise_studies",
    "premise_table",
    "premise_figure",
    "premise_values",
    "common_information_check",
    "readings_values",
]

#: BibTeX key of the source.
BIBKEY = "cn107330468b"
#: Frames 5 to the last (0-based slice; frames 5-30 in the study scenario): the frames over which errors are averaged.
LATE = slice(4, None)
#: Frames 1-4 (0-based slice), where the shared prior still weighs most.
EARLY = slice(0, 4)
#: Every frame.
ALL_FRAMES = slice(None)
#: A run is *collapsed* when some node's filter keeps fewer effective particles than this fraction of its
#: particles (10 of the default 2,000), or the centralised filter fewer than this fraction of its own (50 of 10,000).
COLLAPSE_FRACTION = 0.005

_MSE = "per-run mean squared position error from frame 5 on (m²)"

#: Monte-Carlo runs of the chapter's study (the house minimum for a comparison).
STUDY_RUNS = 100
#: Worker processes of the study (:func:`fusion.scenarios.range_bearing.run_tracking_batch`; results do not depend on it).
STUDY_WORKERS = 2
#: Why a comparison has fewer than :data:`STUDY_RUNS` runs (the runs kept when the collapsed ones are excluded).
STUDY_REASON = "the runs kept of the study's 100 when the runs with a collapsed filter are excluded"


def study_scenario() -> RangeBearingScenario:
    """The scenario of the chapter's 100-run study: the defaults of :class:`RangeBearingScenario`, with the readings.

    30 frames, 2,000 particles per node, R = 2,000 importance samples, 10,000 centralised particles; the
    readings of steps D, F and G6 (``readings=True``) and the variant with ε⁽⁰⁾ = the previous ε*
    optimised by the projected Newton method (``prev_optimiser="newton"``, the swarm's optimum within its
    sampling error, record ``chf-pso``). Without collapse guard: :func:`guarded_runs` adds it.

    Returns
    -------
    RangeBearingScenario
    """
    return dataclasses.replace(RangeBearingScenario(), readings=True, prev_optimiser="newton")


def guarded_scenario(sc: RangeBearingScenario) -> RangeBearingScenario:
    """``sc`` with the collapse guard of every filter (nodes and centralised) at :data:`COLLAPSE_FRACTION`.

    Parameters
    ----------
    sc : RangeBearingScenario

    Returns
    -------
    RangeBearingScenario
        ``guard`` and ``central_guard`` set to :data:`COLLAPSE_FRACTION`.
    """
    return dataclasses.replace(sc, guard=COLLAPSE_FRACTION, central_guard=COLLAPSE_FRACTION)


def pso_defaults() -> dict[str, Any]:
    """Default settings of :func:`fusion.optimise.swarm.particle_swarm`, as glue values ``chf_pso_*``.

    Read from the function's signature, so the prose quotes the defaults the study actually used.

    Returns
    -------
    dict
        ``chf_pso_inertia`` (inertia weight), ``chf_pso_c1`` (cognitive coefficient),
        ``chf_pso_n`` (particles), ``chf_pso_iter`` (largest number of iterations),
        ``chf_pso_tol`` (stagnation tolerance on the best fitness) and ``chf_pso_patience``
        (iterations of stagnation before stopping); values unrounded, as in the signature.
    """
    p = inspect.signature(particle_swarm).parameters
    names = {"inertia": "inertia", "c1": "c1", "n": "n_particles", "iter": "iterations", "tol": "tol",
             "patience": "patience"}
    return {f"chf_pso_{k}": p[v].default for k, v in names.items()}


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
    """
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

    @property
    def ok(self) -> bool:
        """Whether every check meets its tolerance (and log Z <= 0)."""
        t1, t2, t5 = self.tolerances
        return bool(self.k1 < t1 and self.k2 < t2 and self.k5 < t5 and self.kis < 1e-9 and self.k3 <= 1e-12)

    def glue(self) -> dict[str, Any]:
        """Glue values: the tolerances met (not the round-off errors themselves, which flicker)."""
        t1, t2, t5 = self.tolerances
        return {"chf_k1": t1, "chf_k2": t2, "chf_k5": t5, "chf_k5_interior": self.n_interior}


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
    """
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
    g = ch.foa_fusion(gs, e).mixture
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


# --------------------------------------------------------------------------- static example
@dataclass(frozen=True)
class ToyStudy:
    r"""The static two-mixture example: :math:`\log Z(\omega)` exact, first-order and by IS.

    Attributes
    ----------
    gms : tuple of GaussianMixture
        The mixtures A (3 components) and B (2 components), :func:`fusion.scenarios.two_mixtures.toy_mixtures`.
    omegas : ndarray, shape (101,)
        Exponent of A; B has :math:`1-\omega`.
    exact, foa, is_estimate : ndarray, shape (101,)
        :math:`\log Z` by quadrature, :math:`\log Z_{\rm FOA}` and :math:`\hat J` (proposal at ω = 0.5), nats.
    w_exact, w_foa, w_is : float
        The minimiser of each.
    r : int
        Importance samples.
    """

    gms: tuple[mx.GaussianMixture, mx.GaussianMixture]
    omegas: FloatArray
    exact: FloatArray
    foa: FloatArray
    is_estimate: FloatArray
    w_exact: float
    w_foa: float
    w_is: float
    r: int

    def glue(self) -> dict[str, Any]:
        """Glue values ``chf_w_*``, ``chf_foa_*``, ``chf_is_err_*`` and the sizes (4 decimals)."""
        central = (self.omegas >= 0.2) & (self.omegas <= 0.8)
        err = np.abs(self.is_estimate - self.exact)
        grid_n = inspect.signature(two_mixtures.grid_log_normaliser).parameters["n"].default
        return {"chf_r_toy": self.r, "chf_grid_n": grid_n,
                "chf_w_exact": rounded(self.w_exact), "chf_w_foa": rounded(self.w_foa), "chf_w_is": rounded(self.w_is),
                "chf_foa_gap": round(float(np.max(self.foa - self.exact)), 3),  # as the ledger's chf-foa writes them
                "chf_foa_min_gap": round(float(np.min(self.foa - self.exact)), 3),
                "chf_foa_vertex": rounded(self.foa[0]), "chf_s_a": int(self.gms[0].weights.size),
                "chf_is_err_central": rounded(np.max(err[central])), "chf_is_err_end": rounded(np.max(err))}


def _foa_log_z(gms: tuple[mx.GaussianMixture, ...], e: FloatArray) -> float:
    return float(ch.foa_fusion(list(gms), e).log_z_foa)


def toy_study(rng: np.random.Generator, r: int = 20_000, base: ToyStudy | None = None) -> ToyStudy:
    """Exact, first-order and importance-sampled log normaliser of the two toy mixtures.

    Parameters
    ----------
    rng : numpy.random.Generator
        Draws the ``r`` importance samples from the first-order mixture at ω = 0.5 (eq. ``eq-chf-is``).
    r : int
    base : ToyStudy, optional
        A study of the same mixtures whose exact and first-order curves and minimisers are reused (they do not
        depend on the samples): only the importance sampling is redone.

    Returns
    -------
    ToyStudy
    """
    toy = two_mixtures.toy_mixtures()
    gms = (toy.a, toy.b)
    omegas = np.linspace(0.0, 1.0, 101)
    E = np.column_stack([omegas, 1 - omegas])
    g05 = ch.foa_fusion(list(gms), [0.5, 0.5]).mixture
    if base is not None:
        xs = mx.gm_sample(g05, rng, r)
        L, lg = ch.log_densities(list(gms), xs), mx.gm_logpdf(g05, xs)
        return dataclasses.replace(base, is_estimate=ch.is_objective(L, lg, E),
                                   w_is=float(ch.simplex_minimum(L, lg).x[0]), r=r)
    exact = two_mixtures.grid_log_normaliser(list(gms), E).log_z
    # the exact minimiser: the same quadrature with the log densities on the grid computed once, and its gradient
    # (the fused density's expectation of log p_i) exact, so that the search costs a few grid sums
    n_grid = inspect.signature(two_mixtures.grid_log_normaliser).parameters["n"].default
    axis = np.linspace(-9.0, 9.0, n_grid)
    X, Y = np.meshgrid(axis, axis)
    Lg = ch.log_densities(list(gms), np.column_stack([X.ravel(), Y.ravel()]))
    log_cell = 2 * np.log(axis[1] - axis[0])

    def grid_f(e: FloatArray) -> float:
        return float(mx.logsumexp(Lg @ e)) + log_cell

    def grid_g(e: FloatArray) -> FloatArray:
        a = Lg @ e
        w = np.exp(a - mx.logsumexp(a))
        return w @ Lg
    foa = np.array([ch.foa_fusion(list(gms), e).log_z_foa for e in E])
    xs = mx.gm_sample(g05, rng, r)
    L, lg = ch.log_densities(list(gms), xs), mx.gm_logpdf(g05, xs)
    J = ch.is_objective(L, lg, E)
    w_exact = ch.minimise_on_simplex(grid_f, 2, jac=grid_g, ftol=1e-12).x[0]
    w_foa = ch.minimise_on_simplex(lambda e: _foa_log_z(gms, e), 2).x[0]
    w_is = ch.simplex_minimum(L, lg).x[0]
    return ToyStudy(gms, omegas, exact, foa, J, float(w_exact), float(w_foa), float(w_is), r)


def objective_figure(toy: ToyStudy) -> Figure:
    r"""Figure ``fig-chf-objective``: the three log normalisers against ω, each minimiser marked.

    Parameters
    ----------
    toy : ToyStudy
        The static two-mixture example (:func:`toy_study`): exact, first-order and importance-sampled
        :math:`\log Z(\omega)` (nats) on its grid of ω and their minimisers.

    Returns
    -------
    Figure
        One panel, ω (exponent of mixture A) on the x axis, :math:`\log Z` (nats) on the y axis; a
        vertical line marks each minimiser. The figure is closed (not shown by pyplot).
    """
    fig, ax = new_figure(figsize=(7.0, 4.4))
    ax.plot(toy.omegas, toy.exact, color="black", label="exact (grid)")
    ax.plot(toy.omegas, toy.foa, color="#D55E00", ls="--", label=r"first-order $\log Z_{\rm FOA}$")
    ax.plot(toy.omegas, toy.is_estimate, color="#0072B2", ls=":", lw=2,
            label=r"importance sampling $\hat J$ (proposal at ω = 0.5)")
    for w_, c in ((toy.w_exact, "black"), (toy.w_foa, "#D55E00"), (toy.w_is, "#0072B2")):
        ax.axvline(w_, color=c, lw=0.8, alpha=0.7)
    ax.set(xlabel="ω (exponent of A)", ylabel="log Z(ω)")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), ncols=2)
    plt.close(fig)
    return fig


def contour_figure(toy: ToyStudy, rng: np.random.Generator, n_particles: int = 2000) -> tuple[Figure, dict[str, float]]:
    r"""Figure ``fig-chf-contours`` and the :math:`L^1` distances of the first-order mixture to the exact fusion.

    Parameters
    ----------
    toy : ToyStudy
        Supplies the mixtures and :math:`\omega^*` (the exact minimiser).
    rng : numpy.random.Generator
        Draws the importance-sampled particles shown in the fifth panel.
    n_particles : int

    Returns
    -------
    fig : Figure
    values : dict
        ``chf_l1_full`` and ``chf_l1_simple``: :math:`\int|g(\omega^*) - p_{\omega^*}|` with the full
        weights (eq. ``eq-chf-foa``) and with the simplified weights :math:`\prod_i\pi_{i,s_i}^{\varepsilon_i}`.
    """
    gA, gB = toy.gms
    ws = toy.w_exact
    logf = two_mixtures.grid_log_normaliser([gA, gB], [ws, 1 - ws], return_density=True).log_fused
    assert logf is not None
    axis = np.linspace(-9, 9, 601)
    X, Y = np.meshgrid(axis, axis)
    pts = np.column_stack([X.ravel(), Y.ravel()])
    g_star = ch.foa_fusion([gA, gB], [ws, 1 - ws]).mixture
    g_simple = ch.foa_fusion([gA, gB], [ws, 1 - ws], simplified=True).mixture
    dens = {
        "$p_A$": np.exp(mx.gm_logpdf(gA, pts)).reshape(X.shape),
        "$p_B$": np.exp(mx.gm_logpdf(gB, pts)).reshape(X.shape),
        r"exact $p_{\omega^*}$": np.exp(logf[0]),
        r"first-order $g(\omega^*)$": np.exp(mx.gm_logpdf(g_star, pts)).reshape(X.shape),
    }
    cell = (axis[1] - axis[0]) ** 2
    exact = dens[r"exact $p_{\omega^*}$"]
    l1_full = float(np.sum(np.abs(dens[r"first-order $g(\omega^*)$"] - exact)) * cell)
    l1_simple = float(np.sum(np.abs(np.exp(mx.gm_logpdf(g_simple, pts)).reshape(X.shape) - exact)) * cell)
    xs = mx.gm_sample(g_star, rng, n_particles)
    w = ch.fused_weights(ch.log_densities([gA, gB], xs), mx.gm_logpdf(g_star, xs), [ws, 1 - ws])
    fig, axes = new_figure(2, 3, figsize=(7.5, 5.2), sharex=True, sharey=True)
    axes = axes.ravel()
    axes[5].axis("off")
    for axk, (title, d) in zip(axes, dens.items()):
        axk.contour(X, Y, d, levels=8, linewidths=0.8, cmap="viridis")
        axk.set_title(title)
    axes[4].scatter(xs[:, 0], xs[:, 1], s=n_particles * w, color="#0072B2", alpha=0.5, lw=0)
    axes[4].set_title("IS particles, size ∝ weight")
    for axk in axes[:5]:
        axk.set(xlim=(-6, 6), ylim=(-5, 4), aspect="equal")
    plt.close(fig)
    return fig, {"chf_l1_full": rounded(l1_full), "chf_l1_simple": rounded(l1_simple)}


def criteria_example() -> dict[str, float]:
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


# --------------------------------------------------------------------------- importance-sampling variance
def _moment_region(covs: list[FloatArray], e0: FloatArray, k: int) -> Any:
    r"""ω ↦ smallest eigenvalue of :math:`\sum_i(k\varepsilon_i - (k-1)\varepsilon^{(0)}_i)P_i^{-1}` (two Gaussians).

    The k-th moment of the weights :math:`p_\varepsilon/g` under :math:`g = p_{\varepsilon^{(0)}}` is finite iff
    this matrix is positive definite: the integrand :math:`p_\varepsilon^k/g^{k-1}` is a Gaussian kernel with
    precision :math:`kP^{-1} - (k-1)G^{-1}`.
    """
    infos = [np.linalg.inv(c) for c in covs]

    def min_eig(w: float) -> float:
        e = np.array([w, 1.0 - w])
        return float(np.min(np.linalg.eigvalsh(sum((k * e[i] - (k - 1) * e0[i]) * infos[i] for i in range(2)))))
    return min_eig


@dataclass(frozen=True)
class IsVarianceStudy:
    """Bias of the importance-sampled objective and the finite-moment regions, on the Gaussian pair of
    :func:`criteria_example` with the proposal at ω⁽⁰⁾ = 1/2.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per ω: ``rho`` (closed form :func:`fusion.estimates.chernoff.is_second_moment`, inf outside
        the region), ``rho (sampled)``, ``3rd moment finite`` (bool), ``bias predicted`` (-(ρ-1)/(2R), nats;
        NaN outside), ``bias sampled`` and ``bias se`` (mean of Ĵ - log Z over the replicates and its standard
        error), ``median`` (median of Ĵ - log Z, a typical estimate's error).
    lo, hi : float
        The finite-variance interval of ω (bisection on the smallest eigenvalue of Λ(ω), eq. ``eq-chf-is-region``).
    lo3, hi3 : float
        The interval where the weights' third moment is finite (:math:`3P^{-1} - 2G^{-1} \\succ 0`), where the
        first-order bias formula applies.
    R, replicates : int
        Samples per estimate and replicates per ω.
    ok : bool
        Where the third moment is finite (and ω ≠ ω⁽⁰⁾, where the bias is 0): sampled bias within 3 standard
        errors of the prediction; where the fourth moment is finite, sampled ρ within 5 % of the closed form;
        outside the finite-variance interval, ρ infinite.
    power : float
        The largest ``|bias predicted| / bias se`` over the rows tested: above 3, an estimator without bias
        would fail the test (the test can fail).
    """

    table: pd.DataFrame
    lo: float
    hi: float
    lo3: float
    hi3: float
    R: int
    replicates: int
    ok: bool
    power: float

    def glue(self) -> dict[str, Any]:
        """Glue values ``chf_isv_*``: the intervals, R, replicates, rows of the table and the test's power."""
        t = self.table
        v: dict[str, Any] = {"chf_isv_lo": rounded(self.lo), "chf_isv_hi": rounded(self.hi),
                             "chf_isv_lo3": rounded(self.lo3), "chf_isv_hi3": rounded(self.hi3), "chf_isv_r": self.R,
                             "chf_isv_reps": self.replicates, "chf_isv_power": rounded(self.power, 1)}
        for w, key in ((0.2, "02"), (0.7, "07"), (0.8, "08"), (0.1, "01")):
            v[f"chf_isv_bias_{key}"] = rounded(float(t.loc[w, "bias sampled"]), 5)
            v[f"chf_isv_se_{key}"] = rounded(float(t.loc[w, "bias se"]), 5)
            v[f"chf_isv_pred_{key}"] = rounded(float(t.loc[w, "bias predicted"]), 5)
            v[f"chf_isv_median_{key}"] = rounded(float(t.loc[w, "median"]), 5)
        v["chf_isv_rho_08"] = rounded(float(t.loc[0.8, "rho"]))
        v["chf_isv_over_08"] = rounded(100 * float(t.loc[0.8, "bias predicted"] / t.loc[0.8, "bias sampled"] - 1), 0)
        v["chf_isv_median_ratio_08"] = rounded(float(t.loc[0.8, "median"] / t.loc[0.8, "bias sampled"]), 1)
        return v


def is_variance_study(rng: np.random.Generator, R: int = 100, replicates: int = 20_000) -> IsVarianceStudy:
    """Check the bias of Ĵ and the finite-moment regions of the IS weights numerically (Gaussian pair).

    Parameters
    ----------
    rng : numpy.random.Generator
        Draws the samples from the proposal.
    R : int
        Samples per estimate of Ĵ.
    replicates : int
        Estimates per ω (the standard error of the sampled bias falls as 1/sqrt(replicates): 20,000 make the
        predicted bias several standard errors from zero, so the test can fail).

    Returns
    -------
    IsVarianceStudy
    """
    a, A = np.array([0.0, 0.0]), np.diag([4.0, 1.0])
    b, B = np.array([2.0, 1.0]), np.array([[1.0, 0.5], [0.5, 3.0]])
    means, covs, e0 = [a, b], [A, B], np.array([0.5, 0.5])
    g = ch.chernoff_fuse_gaussians(means, covs, e0)

    def edge(f: Any, inside: float, outside: float) -> float:
        if f(outside) > 0:
            return outside
        for _ in range(60):
            mid = 0.5 * (inside + outside)
            inside, outside = (mid, outside) if f(mid) > 0 else (inside, mid)
        return inside
    m2, m3, m4 = (_moment_region(covs, e0, k) for k in (2, 3, 4))
    lo, hi = edge(m2, 0.5, 0.0), edge(m2, 0.5, 1.0)
    lo3, hi3 = edge(m3, 0.5, 0.0), edge(m3, 0.5, 1.0)
    x = g.x + rng.standard_normal((replicates, R, 2)) @ np.linalg.cholesky(g.P).T
    log_g = mx.gaussian_logpdf(x.reshape(-1, 2), g.x, g.P).reshape(replicates, R)
    rows = {}
    for w in (0.0, 0.1, 0.2, 0.3, 0.5, 0.7, 0.8, 0.9, 1.0):
        t = ch.chernoff_fuse_gaussians(means, covs, [w, 1 - w])
        lw = mx.gaussian_logpdf(x.reshape(-1, 2), t.x, t.P).reshape(replicates, R) - log_g
        j = mx.logsumexp(lw, axis=1) - np.log(R)  # Ĵ - log Z: the target is normalised
        rho = ch.is_second_moment(means, covs, [w, 1 - w], e0)
        rows[w] = {"rho": rho, "rho (sampled)": float(np.mean(np.exp(2 * lw))), "3rd moment finite": m3(w) > 0,
                   "bias predicted": -(rho - 1) / (2 * R) if np.isfinite(rho) else np.nan, "bias sampled": float(j.mean()),
                   "bias se": float(j.std(ddof=1) / np.sqrt(replicates)), "median": float(np.median(j))}
    table = pd.DataFrame.from_dict(rows, orient="index")
    table.index.name = "ω"
    test = table[table["3rd moment finite"] & (table.index != e0[0])]
    fourth = [w for w in table.index if m4(w) > 0]
    outside = [w for w in table.index if w < lo or w > hi]
    ok = bool(np.all(np.abs(test["bias sampled"] - test["bias predicted"]) <= 3 * test["bias se"])
              and np.all(np.abs(table.loc[fourth, "rho (sampled)"] / table.loc[fourth, "rho"] - 1) <= 0.05)
              and np.all(np.isinf(table.loc[outside, "rho"])))
    power = float(np.max(np.abs(test["bias predicted"]) / test["bias se"]))
    num = table.columns.drop("3rd moment finite")
    table[num] = table[num].round(5) + 0.0  # no "-0.0" in the displayed table
    return IsVarianceStudy(table=table, lo=lo, hi=hi, lo3=lo3, hi3=hi3, R=R, replicates=replicates, ok=ok,
                           power=power)


# --------------------------------------------------------------------------- tracking study
def scenario_values(sc: RangeBearingScenario, runs: int) -> dict[str, int]:
    """Glue values of the scenario's sizes (``chf_runs``, ``chf_frames``, ``chf_n``, ...).

    Parameters
    ----------
    sc : RangeBearingScenario
        The tracking scenario.
    runs : int
        Number of Monte-Carlo runs of the study (stored as given, not checked).

    Returns
    -------
    dict of str to int
        ``chf_runs`` (runs), ``chf_frames`` (frames K), ``chf_n`` (nodes N), ``chf_q_particles``
        (particles per node filter), ``chf_s`` (mixture components per node), ``chf_r``
        (importance samples R), ``chf_central`` (particles of the centralised filter), ``chf_mf``
        (components of the first-order fused mixture, :math:`S^N`) and ``chf_mf_10``
        (:math:`3^{10}`, the count for ten nodes).
    """
    n = len(sc.sensors)
    return {"chf_runs": runs, "chf_frames": sc.frames, "chf_n": n, "chf_q_particles": sc.n_particles,
            "chf_s": sc.n_components, "chf_r": sc.n_samples, "chf_central": sc.n_central,
            "chf_mf": sc.n_components**n, "chf_mf_10": 3**10}


def message_sizes(sc: RangeBearingScenario, d: int = 4) -> dict[str, int]:
    """What a node sends per frame: its mixture's parameters (step C) against its particles. Glue ``chf_msg_*``.

    Parameters
    ----------
    sc : RangeBearingScenario
        Its ``n_components`` and ``n_particles``.
    d : int
        State dimension.

    Returns
    -------
    dict
        ``chf_msg_gm`` (numbers of a mixture: S × (1 weight + d mean + d(d+1)/2 covariance)), ``chf_msg_pf`` (numbers
        of the weighted particles: Q × (d + 1)), ``chf_msg_d`` and ``chf_msg_s`` (int).
    """
    return {"chf_msg_gm": sc.n_components * (1 + d + d * (d + 1) // 2), "chf_msg_pf": sc.n_particles * (d + 1),
            "chf_msg_d": d, "chf_msg_s": sc.n_components}


def scenario_table(sc: RangeBearingScenario) -> pd.DataFrame:
    """The scenario's choices, one row per item (the patent states none of them).

    Parameters
    ----------
    sc : RangeBearingScenario
        The tracking scenario.

    Returns
    -------
    DataFrame
        Ten rows indexed by ``item`` (sensors, measurement, motion, truth, shared prior, local
        filters, mixtures, fusion, centralised PF, feedback and topology) with one text column
        ``choice``; units in the text (m, m/s, °, s, m²/s³).
    """
    return pd.DataFrame(
        [
            ("sensors (m)", "; ".join(f"({x:.0f}, {y:.0f})" for x, y in sc.sensors)),
            ("measurement", f"range σ = {sc.sigma_r:.0f} m, bearing σ = {np.rad2deg(sc.sigma_theta):.0f}°, every frame"),
            ("motion", f"nearly constant velocity, T = {sc.T:.0f} s, q = {sc.q} m²/s³"),
            ("truth", f"x0 = {sc.x0} (m, m/s), {sc.frames} frames, process noise"),
            ("shared prior", f"N(x0 + P0^½ξ, P0), P0^½ = diag{sc.p0_std}"),
            ("local filters", f"bootstrap PF, {sc.n_particles} particles, systematic resampling + regularisation"
                              + (f"; collapse guard: progressive correction in {GUARD_STAGES} steps below "
                                 f"{sc.guard * 100:g} % effective particles" if sc.guard > 0 else "")),
            ("mixtures (C)", f"weighted EM, {sc.n_components} full-covariance components, warm start, "
                             f"≤ {sc.em_iterations} iterations"),
            ("fusion (D-I)", f"ε⁽⁰⁾ uniform, R = {sc.n_samples} samples, PSO 20 × 50"),
            ("centralised PF", f"{sc.n_central} particles, all measurements"
                               + ("; the same collapse guard" if sc.central_guard > 0 else "")),
            ("feedback, topology", "none; fully connected"),
        ],
        columns=["item", "choice"],
    ).set_index("item")


def crb_position(sc: RangeBearingScenario, runs: list[TrackingRun]) -> FloatArray:
    r"""Root of the posterior CRB of the position, :math:`\sqrt{J^{-1}_{xx} + J^{-1}_{yy}}`, per frame.

    The expectation of the bound's recursion is averaged over the true trajectories of ``runs``
    (:func:`fusion.scenarios.range_bearing.posterior_crb`).

    Parameters
    ----------
    sc : RangeBearingScenario
        Model, sensors and noise levels.
    runs : list of TrackingRun
        Monte-Carlo runs; only their ``truth`` (shape (K, 4)) is used.

    Returns
    -------
    ndarray, shape (K,)
        Lower bound on the position RMSE at frames 1..K (m).

    Raises
    ------
    ValueError
        ``runs`` is empty (nothing to stack), or the truths are not of shape (K, 4).
    """
    crb = posterior_crb(sc, np.stack([r.truth for r in runs]))
    return np.sqrt(crb[:, 0, 0] + crb[:, 2, 2])


def method_table(runs: list[TrackingRun], crb_pos: FloatArray, plain: list[TrackingRun] | None = None) -> pd.DataFrame:
    """Table of every method: RMSE over frames 5-K (m) and mean NEES (4-D), with the CRB as floor (2 decimals).

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs (every method of :data:`~fusion.scenarios.range_bearing.METHODS` recorded).
    crb_pos : ndarray, shape (K,)
        Root of the posterior CRB of the position per frame (m), from :func:`crb_position`.
    plain : list of TrackingRun, optional
        The same runs without the collapse guard: adds the column ``"RMSE, no guard (m)"``.

    Returns
    -------
    DataFrame
        One row per method (indexed by its label in ``METHODS``) plus ``"posterior CRB (floor)"``;
        columns ``"RMSE from frame 5 (m)"`` (root of the squared position error averaged over runs
        and frames 5-K; for the CRB the root mean square of ``crb_pos`` over the same frames),
        ``"RMSE, no guard (m)"`` (with ``plain``), ``"NEES, frames 1-4"`` and ``"mean NEES (4-D), frames 5-30"`` (frames
        5-K; NaN for the mean of local means, which has no covariance, and for the CRB row); 2 decimals.

    Raises
    ------
    ValueError
        ``runs`` is empty (nothing to stack).
    """
    rows = {}
    for key, label in METHODS.items():
        if key not in runs[0].estimates:  # a reading not computed (RangeBearingScenario.readings)
            continue
        has_cov = key != "mean_of_means"
        rows[label] = {"RMSE from frame 5 (m)": np.sqrt(position_sq_errors(runs, key)[:, LATE].mean())}
        if plain is not None:
            rows[label]["RMSE, no guard (m)"] = np.sqrt(position_sq_errors(plain, key)[:, LATE].mean())
        rows[label]["NEES, frames 1-4"] = nees_per_frame(runs, key)[:, EARLY].mean() if has_cov else np.nan
        rows[label]["mean NEES (4-D), frames 5-30"] = nees_per_frame(runs, key)[:, LATE].mean() if has_cov else np.nan
    rows["posterior CRB (floor)"] = {k: np.nan for k in next(iter(rows.values()))}
    rows["posterior CRB (floor)"]["RMSE from frame 5 (m)"] = np.sqrt(np.mean(crb_pos[LATE] ** 2))
    return pd.DataFrame(rows).T.round(2)


def table_values(table: pd.DataFrame) -> dict[str, float]:
    """Glue values read from :func:`method_table`: ``chf_rmse_<key>``, ``chf_nees_<key>``, ratios.

    Parameters
    ----------
    table : DataFrame
        The table of :func:`method_table` (rows labelled as in ``METHODS`` plus the CRB row).

    Returns
    -------
    dict of str to float
        ``chf_rmse_<key>`` for every key of ``METHODS`` and ``chf_rmse_crb`` (m);
        ``chf_ratio_local`` (RMSE of local PF 1 / RMSE of Chernoff-PSO; ``chf_ratio_local_min`` the smallest such
        ratio over the local filters); ``chf_pct_central`` (how
        much larger, in %, Chernoff-PSO's RMSE is than the centralised filter's);
        ``chf_nees_<key>`` for the naive product, Chernoff-PSO, CI of Gaussians, the centralised
        filter and local PF 1, and ``chf_nees_foa`` (first-order mixture at uniform ε); 4 decimals.

    Raises
    ------
    KeyError
        ``table`` lacks a row or column of :func:`method_table`.
    """
    def t(key: str, col: str = "RMSE from frame 5 (m)") -> float:
        return float(table.loc[METHODS[key], col])
    v: dict[str, float] = {f"chf_rmse_{k}": rounded(t(k)) for k in METHODS if METHODS[k] in table.index}
    v["chf_rmse_crb"] = rounded(table.loc["posterior CRB (floor)", "RMSE from frame 5 (m)"])
    v["chf_ratio_local"] = rounded(t("local1") / t("chernoff_pso"))
    v["chf_ratio_local_min"] = rounded(min(t(k) for k in METHODS if k.startswith("local") and METHODS[k] in table.index)
                                       / t("chernoff_pso"))
    v["chf_pct_central"] = rounded(100 * (t("chernoff_pso") / t("centralised") - 1))
    for k in ("naive_product", "chernoff_pso", "ci_gaussian", "centralised", "local1", "foa_uniform"):
        v[f"chf_nees_{k}"] = rounded(t(k, "mean NEES (4-D), frames 5-30"))
    v["chf_nees_foa"] = v.pop("chf_nees_foa_uniform")
    return v


__all__.append("table_values")

_STYLE = {
    "local1": ("#999999", "-"), "local2": ("#999999", "--"), "local3": ("#999999", ":"),
    "mean_of_means": ("#E69F00", "-"), "naive_product": ("#CC79A7", "--"), "ci_gaussian": ("#009E73", "-"),
    "chernoff_uniform": ("#56B4E9", "-"), "chernoff_pso": ("#0072B2", "-"), "centralised": ("#000000", "-"),
}


def rmse_figure(runs: list[TrackingRun], crb_pos: FloatArray) -> Figure:
    """Figure ``fig-chf-rmse``: position RMSE over runs against frame, log scale (the bound is compared in the text).

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs.
    crb_pos : ndarray, shape (K,)
        Root of the posterior CRB of the position per frame (m), from :func:`crb_position`; its
        length sets the frames shown (1..K).

    Returns
    -------
    Figure
        One panel: RMSE over runs (m, log scale) against frame for the local filters, the mean of
        local means, the naive product, CI, Chernoff with uniform and optimised exponents, the
        centralised filter (the CRB is not drawn: Monte-Carlo error lets the centralised RMSE dip below it at
        some frames; see :func:`review_values`). The figure is closed (not shown by pyplot).

    Raises
    ------
    ValueError
        ``runs`` is empty (nothing to stack).
    """
    frames = np.arange(1, crb_pos.size + 1)
    fig, ax = new_figure(figsize=(7.5, 4.8))
    for key, (c, ls) in _STYLE.items():
        rmse = np.sqrt(position_sq_errors(runs, key).mean(axis=0))
        ax.plot(frames, rmse, color=c, ls=ls, lw=2.0 if key == "chernoff_pso" else 1.2, label=METHODS[key])
    # the posterior CRB is not drawn: with 100 runs the centralised filter's RMSE falls below it at some
    # frames (Monte-Carlo error); the chapter compares the two with an interval instead (review_values)
    ax.set(xlabel="frame", ylabel="position RMSE (m)", yscale="log")
    ax.legend(ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.18))
    plt.close(fig)
    return fig


def per_run_mse(runs: list[TrackingRun], key: str) -> FloatArray:
    r"""Mean squared position error of one method over frames 5-K, per run.

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs.
    key : str
        A key of :data:`~fusion.scenarios.range_bearing.METHODS`.

    Returns
    -------
    ndarray, shape (runs,)
        :math:`(\hat x - x)^2 + (\hat y - y)^2` averaged over frames 5-K (:data:`LATE`), m²,
        rounded to :math:`10^{-4}` m²: some estimates (those reached through BLAS products, such as the
        quadratic-feature densities of the mixtures) move in their last digits with the BLAS kernel, and
        the paired differences of the claims ledger must not.

    Raises
    ------
    ValueError
        ``key`` is not a key of ``METHODS``, or ``runs`` is empty.
    """
    return np.round(position_sq_errors(runs, key)[:, LATE].mean(axis=1), 4)


def per_run_nees(runs: list[TrackingRun], key: str, frames: slice = LATE) -> FloatArray:
    """Mean NEES (4-D) of one method over a window of frames, per run.

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs.
    key : str
        A key of :data:`~fusion.scenarios.range_bearing.METHODS` other than ``"mean_of_means"``
        (which has no covariance).
    frames : slice
        The window (0-based): :data:`LATE` (frames 5-K, default), :data:`EARLY` (1-4) or :data:`ALL_FRAMES`.

    Returns
    -------
    ndarray, shape (runs,)
        Normalised estimation error squared of the 4-D state averaged over the window, dimensionless; 4 on
        average for a consistent estimator; rounded to 10⁻⁴ (see :func:`per_run_mse`).

    Raises
    ------
    ValueError
        ``key`` is not a method with a covariance, or ``runs`` is empty.
    """
    return np.round(nees_per_frame(runs, key)[:, frames].mean(axis=1), 4)  # see per_run_mse


def gain_values(runs: list[TrackingRun]) -> dict[str, Any]:
    """Paired per-run MSE differences (m²): mean and standard error, as glue values.

    The ledger's 95 % intervals are in :func:`ledger_values`.

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs (same seeds for every method, so the differences are paired).

    Returns
    -------
    dict
        ``chf_gain_uni`` (patent minus uniform exponents), ``chf_gain_ci`` (patent minus CI of
        Gaussians), ``chf_gain_prev`` (ε⁽⁰⁾ = previous ε* minus patent): means over runs of the
        per-run MSE difference (frames 5-K, m², 4 decimals; negative means the first is more
        accurate), each with ``_se`` (standard error, ``ddof=1``; NaN, with a numpy warning, for a
        single run); ``chf_n_worse_uni`` (int: runs in which the patent's method has the larger MSE
        than uniform exponents).

    Raises
    ------
    ValueError
        ``runs`` is empty (nothing to stack).
    """
    mse = {k: per_run_mse(runs, k) for k in ("chernoff_pso", "chernoff_uniform", "ci_gaussian", "chernoff_prev")}
    diffs = {"uni": mse["chernoff_pso"] - mse["chernoff_uniform"], "ci": mse["chernoff_pso"] - mse["ci_gaussian"],
             "prev": mse["chernoff_prev"] - mse["chernoff_pso"]}
    v: dict[str, Any] = {}
    for name, d in diffs.items():
        v[f"chf_gain_{name}"] = rounded(float(d.mean()))
        v[f"chf_gain_{name}_se"] = rounded(float(d.std(ddof=1) / np.sqrt(d.size)))
    v["chf_n_worse_uni"] = int(np.sum(diffs["uni"] > 0))
    return v


def collapsed(runs: list[TrackingRun], n_particles: int) -> np.ndarray:
    """Runs in which some node's particle filter collapses.

    A run is collapsed when, at some frame, some node keeps fewer than
    :data:`COLLAPSE_FRACTION` × ``n_particles`` effective particles.

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs (their ``ess["local"]``, shape (K, N), is used).
    n_particles : int
        Particles of each node's filter (``RangeBearingScenario.n_particles``).

    Returns
    -------
    ndarray of bool, shape (runs,)
        True for a collapsed run; empty for no runs.
    """
    return min_local_ess(runs) < COLLAPSE_FRACTION * n_particles


def central_collapsed(runs: list[TrackingRun], n_central: int) -> np.ndarray:
    """Runs in which the centralised filter collapses (fewer than :data:`COLLAPSE_FRACTION` × ``n_central``
    effective particles at some frame).

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs (their ``ess["centralised"]``, shape (K,)).
    n_central : int
        Particles of the centralised filter (``RangeBearingScenario.n_central``).

    Returns
    -------
    ndarray of bool, shape (runs,)
    """
    return np.array([float(np.min(r.ess["centralised"])) < COLLAPSE_FRACTION * n_central for r in runs], dtype=bool)


def any_collapsed(runs: list[TrackingRun], sc: RangeBearingScenario) -> np.ndarray:
    """Runs in which some node's filter (:func:`collapsed`) or the centralised filter (:func:`central_collapsed`) collapses.

    Parameters
    ----------
    runs : list of TrackingRun
    sc : RangeBearingScenario
        Its ``n_particles`` and ``n_central`` set the thresholds.

    Returns
    -------
    ndarray of bool, shape (runs,)
    """
    return collapsed(runs, sc.n_particles) | central_collapsed(runs, sc.n_central)


def typical_run(runs: list[TrackingRun], n_particles: int, n_central: int | None = None) -> int:
    """Index of the first run in which no filter collapses (the run the chapter's figures show).

    Parameters
    ----------
    runs : list of TrackingRun
    n_particles : int
        Particles per node (sets the collapse threshold of :func:`collapsed`).
    n_central : int, optional
        Particles of the centralised filter; when given, its collapse (:func:`central_collapsed`) counts too.

    Returns
    -------
    int
        0-based index; 0 when every run collapses.
    """
    bad = collapsed(runs, n_particles)
    if n_central is not None:
        bad = bad | central_collapsed(runs, n_central)
    return int(np.argmin(bad)) if not np.all(bad) else 0


def collapse_values(plain: list[TrackingRun], sc: RangeBearingScenario) -> dict[str, Any]:
    """Where the filters collapse without the guard, and what the collapsed runs do to the study.

    Parameters
    ----------
    plain : list of TrackingRun
        The runs without collapse guard (``monte_carlo(sc, ...)``).
    sc : RangeBearingScenario
        The scenario; its ``n_particles`` and ``n_central`` set the collapse thresholds.

    Returns
    -------
    dict
        Glue values: ``chf_n_collapsed`` (runs in which some node collapses), ``chf_n_central_collapsed`` (runs in
        which the centralised filter collapses), ``chf_n_both_collapsed`` (both in the same run),
        ``chf_n_any_collapsed`` and ``chf_runs_kept`` (int counts); ``chf_collapse_text`` (every node collapse:
        run, node, frame and effective particles, in words) and ``chf_collapse_late`` (int, those after frame 1;
        ``chf_collapse_late_text`` in words, with run and frame); ``chf_ess_next`` (smallest ESS of any node in the
        runs kept, effective particles, 0 decimals); ``chf_central_ess_min`` (smallest ESS of the centralised
        filter, 1 decimal) and ``chf_central_ess_next`` (its smallest in the runs kept, 0 decimals);
        ``chf_rmse_chernoff_pso_plain``, ``chf_rmse_centralised_plain`` and their ``_kept`` versions (position
        RMSE, frames 5-K, m), ``chf_pct_central_plain`` / ``_kept`` (how much larger, in %, the patent's RMSE is
        than the centralised filter's), ``chf_nees_naive_plain`` / ``_kept`` (naive product's mean NEES over
        every frame) and ``chf_nees_naive_plain_max`` (its largest per-run mean, 0 decimals). 4 decimals unless
        stated.

    Raises
    ------
    ValueError
        No run is kept.
    """
    bad, cbad = collapsed(plain, sc.n_particles), central_collapsed(plain, sc.n_central)
    anyb = bad | cbad
    keep = [r for r, b in zip(plain, anyb) if not b]
    if not keep:
        raise ValueError("every run collapses: nothing is kept")
    events, late, late_at = [], 0, []
    for j in np.flatnonzero(bad):
        ess = plain[j].ess["local"]
        for k, i in zip(*np.nonzero(ess < COLLAPSE_FRACTION * sc.n_particles)):
            events.append(f"run {j + 1}, node {i + 1}, frame {k + 1}: {ess[k, i]:.1f}")
            late += int(k > 0)
            if k > 0:
                late_at.append(f"run {j + 1}, frame {k + 1}")
    words = {0: "no node collapse comes", 1: "one node collapse comes"}
    late_text = (words.get(late, f"{late} node collapses come") + " later"
                 + (f" ({'; '.join(late_at)})" if late_at else ""))
    v: dict[str, Any] = {"chf_n_collapsed": int(bad.sum()), "chf_n_central_collapsed": int(cbad.sum()),
                         "chf_n_both_collapsed": int((bad & cbad).sum()), "chf_n_any_collapsed": int(anyb.sum()),
                         "chf_runs_kept": len(keep), "chf_collapse_text": "; ".join(events) if events else "none",
                         "chf_collapse_late": late, "chf_collapse_late_text": late_text,
                         "chf_ess_next": rounded(float(np.min(min_local_ess(keep))), 0),
                         "chf_central_ess_min": rounded(float(min(np.min(r.ess["centralised"]) for r in plain)), 1),
                         "chf_central_ess_next": rounded(float(min(np.min(r.ess["centralised"]) for r in keep)), 0)}

    def rmse(rs: list[TrackingRun], key: str) -> float:
        return float(np.sqrt(position_sq_errors(rs, key)[:, LATE].mean()))
    for tag, rs in (("plain", plain), ("kept", keep)):
        v[f"chf_rmse_chernoff_pso_{tag}"] = rounded(rmse(rs, "chernoff_pso"))
        v[f"chf_rmse_centralised_{tag}"] = rounded(rmse(rs, "centralised"))
        v[f"chf_pct_central_{tag}"] = rounded(100 * (rmse(rs, "chernoff_pso") / rmse(rs, "centralised") - 1))
        v[f"chf_nees_naive_{tag}"] = rounded(float(nees_per_frame(rs, "naive_product").mean()))
    v["chf_nees_naive_plain_max"] = rounded(float(np.max(nees_per_frame(plain, "naive_product").mean(axis=1))), 0)
    return v


def eps_figure(runs: list[TrackingRun], sc: RangeBearingScenario, show: int = 0) -> tuple[Figure, dict[str, float]]:
    """Figure ``fig-chf-eps`` (optimal exponents and ESS/R against frame) and its glue values.

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs (their ``eps["pso"]``, shape (K, N), and ``ess``).
    sc : RangeBearingScenario
        The scenario: number of nodes N, frames K, importance samples R (``n_samples``) and
        particles of the centralised filter (``n_central``).
    show : int
        0-based index of the run drawn on the left (e.g. :func:`typical_run`).

    Returns
    -------
    fig : Figure
        Left: ε* of each node against frame (run ``show + 1``, with the 10-90 % band over runs) and the
        uniform 1/N; right: mean ESS / R against frame at ε⁽⁰⁾, at ε* and redrawn, and the
        centralised filter's ESS / particles. The figure is closed (not shown by pyplot).
    values : dict of str to float
        ``chf_eps_spread`` (mean over frames and nodes of the 10-90 % band width of ε*),
        ``chf_ess_uniform``, ``chf_ess_pso``, ``chf_ess_redraw`` (mean ESS / R at ε⁽⁰⁾, at ε* with
        the samples reused, and redrawn), ``chf_ess_pso_min`` (smallest ESS at ε*, samples),
        ``chf_ess_central_1`` (mean ESS of the centralised filter at frame 1, particles),
        ``chf_ess_central_late`` (its mean ESS / particles over frames 5-K), ``chf_eps_max_mean``
        (mean over runs and frames of the largest exponent) and ``chf_eps_max_max`` (largest
        exponent); 4 decimals.

    Raises
    ------
    ValueError
        ``runs`` is empty (nothing to stack).
    """
    n = len(sc.sensors)
    frames = np.arange(1, sc.frames + 1)
    eps_all = np.stack([r.eps["pso"] for r in runs])  # (runs, K, N)
    fig, (ax1, ax2) = new_figure(2, 1, figsize=(7.5, 6.4))
    colors = ["#0072B2", "#D55E00", "#009E73"]
    for i in range(n):
        c = colors[i % len(colors)]
        ax1.fill_between(frames, np.percentile(eps_all[:, :, i], 10, axis=0),
                         np.percentile(eps_all[:, :, i], 90, axis=0), color=c, alpha=0.15, lw=0)
        ax1.plot(frames, eps_all[show, :, i], color=c, label=f"ε{i + 1} (sensor {i + 1}), run {show + 1}")
    ax1.axhline(1 / n, color="grey", lw=0.8, ls="--")
    ax1.set(xlabel="frame", ylabel="ε*", ylim=(0, 1))
    ax1.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    for key, c, label in (("uniform", "#56B4E9", "at ε⁽⁰⁾ (uniform)"),
                          ("pso", "#0072B2", "at ε* (patent: samples reused)"),
                          ("redraw", "#009E73", "at ε*, samples redrawn")):
        ax2.plot(frames, np.mean([r.ess[key] for r in runs], axis=0) / sc.n_samples, color=c, label=label)
    ax2.plot(frames, np.mean([r.ess["centralised"] for r in runs], axis=0) / sc.n_central, color="black", ls=":",
             label="centralised PF (ESS / particles)")
    ax2.set(xlabel="frame", ylabel="ESS / R (centralised:\nESS / particles)", ylim=(0, 1.05))
    ax2.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    plt.close(fig)
    ess = {k: np.stack([r.ess[k] for r in runs]) for k in ("uniform", "pso", "redraw", "centralised")}
    values = {
        "chf_eps_spread": np.mean(np.percentile(eps_all, 90, axis=0) - np.percentile(eps_all, 10, axis=0)),
        "chf_ess_uniform": np.mean(ess["uniform"]) / sc.n_samples,
        "chf_ess_pso": np.mean(ess["pso"]) / sc.n_samples,
        "chf_ess_pso_min": np.min(ess["pso"]),
        "chf_ess_redraw": np.mean(ess["redraw"]) / sc.n_samples,
        "chf_ess_central_1": np.mean(ess["centralised"][:, 0]),
        "chf_ess_central_late": np.mean(ess["centralised"][:, LATE]) / sc.n_central,
        "chf_eps_max_mean": np.mean(eps_all.max(axis=2)),
        "chf_eps_max_max": np.max(eps_all),
    }
    return fig, {k: rounded(float(x)) for k, x in values.items()}


def pso_figure(runs: list[TrackingRun], frame: int = 10, show: int = 0) -> tuple[Figure, dict[str, float]]:
    """Figure ``fig-chf-pso`` (the swarm's best Ĵ against iteration in one run) and swarm-vs-SLSQP glue values.

    Parameters
    ----------
    runs : list of TrackingRun
    frame : int
        1-based frame to show.
    show : int
        0-based index of the run shown (e.g. :func:`typical_run`).

    Returns
    -------
    fig : Figure
        The swarm's best Ĵ against iteration until the stagnation rule stops (circled), the same swarm followed
        to its iteration limit with the iteration where the patent's rule (positions converge) stops
        (square; with ``readings``), and SLSQP's minimum on the same samples.
    values : dict
        ``chf_gap_obj`` and ``chf_gap_eps`` (largest absolute difference PSO - SLSQP in objective and exponents over all
        frames and runs), ``chf_evals_pso``/``chf_evals_slsqp`` (mean evaluations per frame),
        ``chf_better_pso`` (fraction of frames where the swarm's value is below SLSQP's by > 1e-9).
    """
    r0, k = runs[show], frame - 1
    n_part = inspect.signature(particle_swarm).parameters["n_particles"].default
    stop = int(r0.evaluations["pso"][k]) // n_part - 1  # the stagnation rule stopped after this iteration
    hist = -r0.swarm_history[k][:stop + 1]  # (the stored history is padded after the stop)
    fig, ax = new_figure(figsize=(7.0, 3.4))
    if r0.swarm_trace:  # the same swarm followed to its iteration limit (readings)
        full = -r0.swarm_trace["fitness"][k]
        ax.plot(np.arange(full.size), full, color="#999999", lw=1.0, label="PSO followed to its limit")
        lit = int(r0.evaluations["literal"][k]) // n_part - 1
        ax.plot([lit], [full[lit]], "s", color="#D55E00", label="positions converge (G6 as worded)")
    ax.plot(np.arange(hist.size), hist, color="#0072B2", marker=".", label="PSO: best Ĵ so far")
    ax.plot([stop], [hist[-1]], "o", color="#0072B2", ms=9, mfc="none", label="stagnation rule stops")
    ax.axhline(r0.objective["slsqp"][k], color="black", ls="--", label="SLSQP on the same samples")
    ax.set(xlabel="swarm iteration", ylabel="Ĵ(ε)")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    plt.close(fig)
    obj = {m: np.stack([r.objective[m] for r in runs]) for m in ("pso", "slsqp")}
    eps = {m: np.stack([r.eps[m] for r in runs]) for m in ("pso", "slsqp")}
    values = {
        "chf_k_show": frame,
        "chf_gap_obj": float(f"{np.max(np.abs(obj['pso'] - obj['slsqp'])):.1e}"),  # two significant digits, as shown
        "chf_gap_eps": rounded(float(np.max(np.abs(eps["pso"] - eps["slsqp"])))),
        "chf_evals_pso": rounded(float(np.mean([r.evaluations["pso"] for r in runs]))),
        "chf_evals_slsqp": rounded(float(np.mean([r.evaluations["slsqp"] for r in runs]))),
        "chf_better_pso": rounded(float(np.mean(obj["pso"] < obj["slsqp"] - 1e-9))),
    }
    return fig, values


#: Schema of ``benchmarks/results/chernoff.json`` written by ``benchmarks/bench_chernoff.py`` for the current pipeline
#: (the study configuration, loop against batch, stage costs); a file without it predates that pipeline.
BENCH_SCHEMA = 2


def benchmark_cost(path: Path) -> tuple[pd.DataFrame, dict[str, Any]]:
    """Cost per frame by stage from ``benchmarks/results/chernoff.json``, and the study's measured cost.

    Parameters
    ----------
    path : Path
        The benchmark result file.

    Returns
    -------
    table : DataFrame
        ms per frame, indexed by stage; empty (no rows) when the file predates :data:`BENCH_SCHEMA`.
    values : dict
        ``chf_bench_date`` (str), ``chf_bench_current`` (bool: the file has :data:`BENCH_SCHEMA`), and, in words for
        the prose (``"not measured yet ..."`` when the file is not current): ``chf_bench_text`` (the seconds of the
        study's runs by the per-run loop, batched in one process and with the chapter's worker processes, whether
        their results are identical, and the verdict against 60 s for 100 runs on 2 cores), ``chf_bench_stage_text``
        (EM's share of the patent's own stages B-I and the runs measured) and ``chf_pso_ratio_text`` (time of the
        swarm / time of SLSQP on the same samples).
    """
    bench = json.loads(Path(path).read_text(encoding="utf-8"))
    date = str(bench.get("date", bench.get("timestamp", "undated")))[:10]
    current = bench.get("schema") == BENCH_SCHEMA
    pending = "not measured yet for the current pipeline (run benchmarks/bench_chernoff.py on an idle machine)"
    if not current:
        empty = pd.DataFrame({"stage": [], "ms per frame": []}).set_index("stage")
        return empty, {"chf_bench_date": date, "chf_bench_current": False, "chf_bench_text": pending,
                       "chf_bench_stage_text": pending, "chf_pso_ratio_text": pending}
    ms = bench["measurements"]
    stages = [m for m in ms if "stage" in m]
    cost = pd.DataFrame({"stage": [m["what"].split(", ", 1)[1].rsplit(":", 1)[0] for m in stages],
                         "ms per frame": [round(1000 * m["value"], 1) for m in stages]}).set_index("stage")
    key = {m["key"]: float(m["value"]) for m in ms if "key" in m}
    patent = [i for i in cost.index if i.split(":")[0] in ("B", "C", "D", "E", "F", "G", "H-I")]
    share = cost.loc["C: weighted EM (3 nodes)", "ms per frame"] / cost.loc[patent, "ms per frame"].sum()
    runs, workers = int(bench["runs"]), int(bench.get("workers", STUDY_WORKERS))
    slsqp = next(i for i in cost.index if i.startswith("SLSQP"))
    stage_ratio = cost.loc["G: particle swarm", "ms per frame"] / cost.loc[slsqp, "ms per frame"]
    t2 = key["study_seconds_workers"]
    target = 60.0 * runs / 100
    text = (f"{runs} runs take {key['loop_seconds']:.0f} s by the per-run loop, {key['study_seconds']:.0f} s batched "
            f"in one process and {t2:.0f} s batched with {workers} worker processes, "
            f"{'within' if t2 <= target else 'over'} the target of {target:.0f} s on 2 cores; the three give "
            f"{'identical' if key['identical'] == 1.0 else 'different'} results (benchmark of {date}, load average "
            f"{bench.get('load_average', ['?'])[0]})")
    stage_text = (f"weighted EM takes a share {share:.2f} of the patent's own stages (B-I), measured over {runs} runs "
                  f"of the study on {date}")
    return cost, {"chf_bench_date": date, "chf_bench_current": True, "chf_bench_text": text,
                  "chf_bench_stage_text": stage_text,
                  "chf_pso_ratio_text": f"{key['pso_over_slsqp']:.0f} times slower (benchmark of {date}) on the "
                                        "static example with a duplicated input [A, B, A], whose objective has a flat "
                                        f"direction; in the study's own stage costs {stage_ratio:.1f} times "
                                        f"({cost.loc['G: particle swarm', 'ms per frame']:.1f} against "
                                        f"{cost.loc[slsqp, 'ms per frame']:.1f} ms per frame)"}


def gm_yardstick(rng: np.random.Generator, runs: list[TrackingRun], sc: RangeBearingScenario,
                 sets: int = 100) -> dict[str, Any]:
    r"""How much a mixture gains over one Gaussian on *truly Gaussian* weighted particles: the yardstick of "nearly Gaussian".

    The same weighted EM as the nodes (:data:`~fusion.scenarios.range_bearing.RangeBearingScenario`'s
    components, iterations; k-means++ start) always gains a little on a finite sample (it has more
    parameters). On weighted particles with the tracking's effective sample size, drawn so that their
    weighted distribution is exactly Gaussian (prior :math:`\mathcal N(0, cI)`, weights
    :math:`\propto\mathcal N(x; 0, I)/\mathcal N(x; 0, cI)`, :math:`c` chosen so that
    :math:`\mathrm{ESS}/Q = ((2c-1)^{1/2}/c)^d`), that gain is the part of the tracking's gain that says
    nothing about non-Gaussianity. The log-likelihood ratio is affine invariant, so the Gaussian's mean and
    covariance do not matter.

    Parameters
    ----------
    rng : numpy.random.Generator
    runs : list of TrackingRun
        The study's runs: their per-frame gains (``gm_loglik - gm1_loglik``) and local ESS.
    sc : RangeBearingScenario
    sets : int
        Gaussian sets per yardstick.

    Returns
    -------
    dict
        ``chf_gm_gain`` (tracking, mean over runs, nodes and frames, nats per particle), ``chf_gm_gain_1``,
        ``chf_gm_gain_2`` and ``chf_gm_gain_late`` (frame 1, frame 2, frames 5-K), ``chf_gm_ess_1`` and
        ``chf_gm_ess_late`` (mean ESS / Q of the nodes at frame 1 and over frames 5-K), ``chf_gm_yard_1`` and
        ``chf_gm_yard_late`` (the yardstick's mean gain at those ESS) with ``_hi`` (its 95th percentile over
        the sets); 4 decimals.
    """
    from scipy.optimize import brentq

    gain = np.stack([r.gm_loglik - r.gm1_loglik for r in runs])  # (runs, K, N)
    ess = np.stack([r.ess["local"] for r in runs]) / sc.n_particles
    d, Q = 4, sc.n_particles
    out: dict[str, Any] = {"chf_gm_gain": gain.mean(), "chf_gm_gain_1": gain[:, 0].mean(),
                           "chf_gm_gain_2": gain[:, 1].mean() if gain.shape[1] > 1 else np.nan,
                           "chf_gm_gain_late": gain[:, LATE].mean(), "chf_gm_ess_1": ess[:, 0].mean(),
                           "chf_gm_ess_late": ess[:, LATE].mean()}
    for tag in ("1", "late"):
        f = float(out[f"chf_gm_ess_{tag}"])
        c = brentq(lambda c: d * np.log(np.sqrt(2 * c - 1) / c) - np.log(f), 1.0 + 1e-9, 1e6) if f < 1 else 1.0
        x = np.sqrt(c) * rng.standard_normal((sets, Q, d))
        lw = -0.5 * np.sum(x**2, axis=-1) * (1.0 - 1.0 / c)
        w = np.exp(lw - lw.max(axis=1, keepdims=True))
        w /= w.sum(axis=1, keepdims=True)
        fits = mx.weighted_em_batch(x, w, sc.n_components, [np.random.default_rng(s) for s in rng.integers(2**32, size=sets)],
                                    max_iter=sc.em_iterations, tol=1e-6, floor=1e-6)
        g = np.empty(sets)
        for b, fit in enumerate(fits):
            m = w[b] @ x[b]
            P = (x[b] - m).T @ ((x[b] - m) * w[b][:, None])
            g[b] = float(w[b] @ mx.gm_logpdf(fit.mixture, x[b])) + 0.5 * (d * np.log(2 * np.pi) + np.linalg.slogdet(P)[1] + d)
        out[f"chf_gm_yard_{tag}"], out[f"chf_gm_yard_{tag}_hi"] = g.mean(), np.quantile(g, 0.95)
    return {k: rounded(float(v)) for k, v in out.items()}


def consistency_figure(runs: list[TrackingRun], plain: list[TrackingRun], sc: RangeBearingScenario) -> Figure:
    """Figure ``fig-chf-consistency``: mean NEES per frame, and every node's effective sample size per frame.

    Parameters
    ----------
    runs : list of TrackingRun
        The study (with the collapse guard).
    plain : list of TrackingRun
        The same runs without guard.
    sc : RangeBearingScenario
        Frames, nodes, particles.

    Returns
    -------
    Figure
        Top: mean NEES (4-D, log scale) over the runs against frame for the naive product, the patent's method,
        CI of moment-matched Gaussians (Chernoff ε), the local filters (their mean) and the centralised filter,
        the naive product's expected NEES for linearised filters with exact cross-covariances
        (:func:`~fusion.scenarios.range_bearing.linearised_errors`, dotted), with 4 and the 95 % band of a mean of as many χ²₄ values as runs. Bottom: effective particles of each
        node after weighting (log scale), the smallest over the runs without the guard (dotted) and with it
        (solid), and the median with it (thick, faded, unlabelled); the collapse threshold dashed. Closed.
    """
    from scipy import stats as _stats

    frames = np.arange(1, sc.frames + 1)
    from matplotlib.ticker import NullFormatter, ScalarFormatter

    fig, (ax1, ax2) = new_figure(2, 1, figsize=(7.5, 8.6))
    n = len(runs)
    lo, hi = _stats.chi2.ppf([0.025, 0.975], 4 * n) / n
    ax1.axhspan(lo, hi, color="#DDDDDD", lw=0)
    ax1.axhline(4.0, color="grey", lw=0.8, ls="--")
    local = np.mean([nees_per_frame(runs, f"local{i + 1}").mean(axis=0) for i in range(len(sc.sensors))], axis=0)
    ax1.plot(frames, local, color="#999999", label="local PFs (mean of the nodes)")
    for key in ("naive_product", "ci_gaussian", "chernoff_pso", "centralised"):
        c, ls = _STYLE[key]
        ax1.plot(frames, nees_per_frame(runs, key).mean(axis=0), color=c, ls=ls, lw=2.0 if key == "naive_product" else 1.2,
                 label=METHODS[key])
    ax1.plot(frames, linearised_errors(sc).nees_naive, color=_STYLE["naive_product"][0], ls=":", lw=1.5,
             label="naive product, linearised (exact cross-covariances)")
    ax1.set(xlabel="frame", ylabel="mean NEES (4-D)", yscale="log", yticks=[1.5, 2, 3, 4, 6, 8])
    ax1.yaxis.set_major_formatter(ScalarFormatter())
    ax1.yaxis.set_minor_formatter(NullFormatter())
    ax1.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncols=2)
    colors = ["#0072B2", "#D55E00", "#009E73"]
    for rs, ls, tag in ((plain, ":", "no guard"), (runs, "-", "guard")):
        ess = np.stack([r.ess["local"] for r in rs])  # (runs, K, N)
        for i in range(len(sc.sensors)):
            c = colors[i % len(colors)]
            ax2.plot(frames, np.min(ess[:, :, i], axis=0), color=c, ls=ls, label=f"node {i + 1}, smallest ({tag})")
            if tag == "guard":
                ax2.plot(frames, np.median(ess[:, :, i], axis=0), color=c, lw=2.0, alpha=0.5)  # median (caption)
    ax2.axhline(COLLAPSE_FRACTION * sc.n_particles, color="black", lw=0.8, ls="--")
    ax2.set(xlabel="frame", ylabel="effective particles", yscale="log")
    ax2.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncols=2)
    plt.close(fig)
    return fig


def double_count_values(runs: list[TrackingRun], sc: RangeBearingScenario) -> dict[str, Any]:
    """Why the naive product is overconfident, and why uniform exponents are hard to beat: glue ``chf_lin_*``.

    The linearised analysis (:func:`~fusion.scenarios.range_bearing.linearised_errors`, no sampling) of the
    scenario with the nodes sharing the prior and the process noise, and with one of the two shared sources
    removed from the cross terms, beside the particle study's per-frame NEES.

    Parameters
    ----------
    runs : list of TrackingRun
        The study.
    sc : RangeBearingScenario
        Its scenario (frames 1-4 are the early window, 5 on the late one).

    Returns
    -------
    dict
        ``chf_lin_nees_1``, ``_min``, ``_end`` (expected NEES of the naive product at frame 1, its minimum over
        frames, at the last frame), ``chf_lin_min_frame`` (int), ``chf_lin_nees_early``/``_late`` (means over
        frames 1-4 and 5 on), ``chf_lin_noq_early``/``_late`` (process noise independent across nodes),
        ``chf_lin_noprior_early``/``_late`` (prior errors independent), ``chf_lin_cv_10``/``_end`` and
        ``chf_lin_cp_end`` (correlation of two nodes' velocity / position errors at frame 10, or the last if earlier,
        and at the last frame),
        ``chf_lin_rmse_uniform``/``_best`` (m, last frame: the naive product's mean against the best linear
        combination that knows the cross-covariances) and ``chf_lin_best_pct`` (how much lower the latter is, %);
        from the particle study, ``chf_pf_naive_mid``/``_end`` (the naive product's mean NEES over the runs at
        the middle and the last frame) and ``chf_pf_ratio_early``/``_late`` (its mean NEES over the local
        filters', frames 1-4 and 5 on). 2 decimals (correlations 2, percentages 1).
    """
    lin = linearised_errors(sc)
    noq = linearised_errors(sc, common_process=False)
    nop = linearised_errors(sc, common_prior=False)
    naive = nees_per_frame(runs, "naive_product").mean(axis=0)
    local = np.mean([nees_per_frame(runs, f"local{i + 1}").mean(axis=0) for i in range(len(sc.sensors))], axis=0)
    mid = sc.frames // 2 - 1
    v = {"chf_lin_nees_1": lin.nees_naive[0], "chf_lin_nees_min": lin.nees_naive.min(),
         "chf_lin_nees_end": lin.nees_naive[-1], "chf_lin_nees_early": lin.nees_naive[EARLY].mean(),
         "chf_lin_nees_late": lin.nees_naive[LATE].mean(), "chf_lin_noq_early": noq.nees_naive[EARLY].mean(),
         "chf_lin_noq_late": noq.nees_naive[LATE].mean(), "chf_lin_noprior_early": nop.nees_naive[EARLY].mean(),
         "chf_lin_noprior_late": nop.nees_naive[LATE].mean(), "chf_lin_cv_10": lin.corr_velocity[min(9, sc.frames - 1)],
         "chf_lin_cv_end": lin.corr_velocity[-1], "chf_lin_cp_end": lin.corr_position[-1],
         "chf_lin_rmse_uniform": lin.rmse_uniform[-1], "chf_lin_rmse_best": lin.rmse_best[-1],
         "chf_pf_naive_mid": naive[mid], "chf_pf_naive_end": naive[-1],
         "chf_pf_ratio_early": naive[EARLY].mean() / local[EARLY].mean(),
         "chf_pf_ratio_late": naive[LATE].mean() / local[LATE].mean()}
    out: dict[str, Any] = {k: rounded(float(x), 2) for k, x in v.items()}
    out["chf_lin_min_frame"] = int(np.argmin(lin.nees_naive)) + 1
    out["chf_pf_mid_frame"] = mid + 1
    out["chf_lin_best_pct"] = rounded(float(100 * (1 - lin.rmse_best[-1] / lin.rmse_uniform[-1])), 1)
    return out


def stopping_values(runs: list[TrackingRun], sc: RangeBearingScenario,
                    xtols: tuple[float, ...] = (1e-3, 3e-3, 1e-2, 3e-2)) -> dict[str, Any]:
    """The swarm's two readings of G6 on every tracking frame, from the swarm followed to its limit (``readings``).

    The swarm's moves do not depend on its stopping rule until it stops, so the traced swarm gives what the
    patent's rule (every particle within ``xtol`` of the best) returns at any tolerance, on the same samples
    as the stagnation rule.

    Parameters
    ----------
    runs : list of TrackingRun
        The study's runs (with ``swarm_trace``, ``objective["slsqp"]`` and ``ess["pso"]``).
    sc : RangeBearingScenario
    xtols : tuple of float
        Position tolerances (the first is the one of ``sc.literal_xtol``, recorded as ``chernoff_literal``).

    Returns
    -------
    dict
        ``chf_stop_frames`` (int), ``chf_stop_limit`` (evaluations at the iteration limit), ``chf_stop_xtol``;
        ``chf_stop_evals_stag`` (mean evaluations, stagnation rule); per tolerance ``j`` (0-based, in the order
        given): ``chf_stop_x{j}`` (the tolerance), ``chf_stop_atlimit_{j}`` (share of frames run to the limit),
        ``chf_stop_evals_{j}`` (mean evaluations), ``chf_stop_gap_{j}`` (largest objective above SLSQP's, nats,
        2 significant digits) and ``chf_stop_within_{j}`` (int, frames within Ĵ's sampling error of SLSQP);
        ``chf_stop_gap_stag`` and ``chf_stop_within_stag`` likewise for the stagnation rule; ``chf_stop_ratio_0``
        (evaluations of the first tolerance over the stagnation rule's, 1 decimal), ``chf_stop_within_all`` (int, the
        fewest frames within the sampling error over every rule and tolerance; ``chf_stop_within_text`` in words);
        with ``sc.readings``
        ``chf_stop_mse_d``/``_lo``/``_hi``/``_word``: the patent's method with the literal rule minus with the
        stagnation rule, per-run MSE from frame 5 on (m², paired 95 % interval; the same samples).
    """
    fit = np.stack([r.swarm_trace["fitness"] for r in runs])  # (runs, K, T + 1)
    spread = np.stack([r.swarm_trace["spread"] for r in runs])
    ref = np.stack([r.objective["slsqp"] for r in runs])
    ess = np.stack([r.ess["pso"] for r in runs])
    se = np.sqrt(np.maximum(1.0 / ess - 1.0 / sc.n_samples, 0.0))
    n_part = inspect.signature(particle_swarm).parameters["n_particles"].default
    T = fit.shape[-1] - 1
    v: dict[str, Any] = {"chf_stop_frames": int(ref.size), "chf_stop_limit": int(n_part * (T + 1)),
                         "chf_stop_xtol": sc.literal_xtol}
    stag = np.stack([r.objective["pso"] for r in runs])
    v["chf_stop_evals_stag"] = rounded(float(np.mean([r.evaluations["pso"] for r in runs])), 0)
    v["chf_stop_gap_stag"] = float(f"{np.max(stag - ref):.2g}")
    v["chf_stop_within_stag"] = int(np.sum(stag - ref < se))
    for j, xtol in enumerate(xtols):
        hit = spread[..., 1:] < xtol
        t = np.where(hit.any(axis=-1), np.argmax(hit, axis=-1) + 1, T)
        obj = -np.take_along_axis(fit, t[..., None], axis=-1)[..., 0]
        v.update({f"chf_stop_x{j}": xtol, f"chf_stop_atlimit_{j}": rounded(float(np.mean(t >= T)), 3),
                  f"chf_stop_evals_{j}": rounded(float(np.mean(n_part * (t + 1))), 0),
                  f"chf_stop_gap_{j}": float(f"{np.max(obj - ref):.2g}"),
                  f"chf_stop_within_{j}": int(np.sum(obj - ref < se))})
    v["chf_stop_ratio_0"] = rounded(float(v["chf_stop_evals_0"] / v["chf_stop_evals_stag"]), 1)
    v["chf_stop_within_all"] = min(v["chf_stop_within_stag"], *(v[f"chf_stop_within_{j}"] for j in range(len(xtols))))
    v["chf_stop_within_text"] = ("in every one of the" if v["chf_stop_within_all"] == v["chf_stop_frames"]
                                 else f"in at least {v['chf_stop_within_all']} of the")
    if sc.readings:  # the literal rule's estimate against the stagnation rule's (same samples), per-run MSE
        c = Comparison(per_run_mse(runs, "chernoff_literal"), per_run_mse(runs, "chernoff_pso"),
                       METHODS["chernoff_literal"], METHODS["chernoff_pso"], "less", _MSE, reason=_reason(len(runs)))
        d, lo, hi = c.interval()
        v.update(chf_stop_mse_d=rounded(d), chf_stop_mse_lo=rounded(lo), chf_stop_mse_hi=rounded(hi),
                 chf_stop_mse_word=_word(c))
    return v


def diagnostics(runs: list[TrackingRun], sc: RangeBearingScenario, seed: int) -> dict[str, float]:
    """Glue values of the critique boxes: node spread, the wide-prior ESS note, mixture gain, components.

    Parameters
    ----------
    runs : list of TrackingRun
        Run 0 must hold ``node_estimates`` (``all_nodes=True``).
    sc : RangeBearingScenario
    seed : int
        Seed of the one-frame wide-prior runs (as many as ``runs``).

    Returns
    -------
    dict
        ``chf_node_spread`` / ``_mean`` (m, frames 5-K, run 1), ``chf_node_run_ess`` (smallest ESS of a node in
        run 1, effective particles), ``chf_ess1_note`` (mean ESS after frame 1 with P0^½ = diag(100, 10, 100,
        10)), ``chf_ess1_ours``, ``chf_mf_used``, ``chf_prev_eps_diff``.
    """
    node = runs[0].node_estimates
    if node is None:
        raise ValueError("runs[0] must have node_estimates (run_tracking(..., all_nodes=True))")
    spread = np.max(np.linalg.norm(node[:, :, [0, 2]] - node[:, :1, [0, 2]], axis=2), axis=1)
    wide = dataclasses.replace(sc, p0_std=(100.0, 10.0, 100.0, 10.0), frames=1)
    # only the local filters' first update is read: the fusion and the centralised filter run small (they draw
    # from their own streams, after the nodes' weights, so the nodes' effective sample sizes do not change)
    wide = dataclasses.replace(wide, variants=False, readings=False, n_samples=50, n_central=50, em_iterations=1)
    ess_note = np.mean([r.ess["local"][0] for r in run_tracking_batch(wide, np.random.SeedSequence(seed).spawn(len(runs)),
                                                                      workers=STUDY_WORKERS)])
    values = {
        "chf_node_spread": spread[LATE].max(),
        "chf_node_spread_mean": spread[LATE].mean(),
        "chf_node_run_ess": np.min(runs[0].ess["local"]),
        "chf_ess1_note": ess_note,
        "chf_ess1_ours": np.mean([r.ess["local"][0] for r in runs]),
        "chf_mf_used": np.mean([r.n_fused_components for r in runs]),
        "chf_prev_eps_diff": np.mean(np.abs(np.stack([r.eps["prev"] - r.eps["pso"] for r in runs]))),
    }
    return {k: rounded(float(x)) for k, x in values.items()}


def review_values(runs: list[TrackingRun], crb_pos: FloatArray, sc: RangeBearingScenario, seed: int) -> dict[str, Any]:
    """Glue values answering the chapter's independent review: the bound, the yardsticks, the exponents' spread.

    Parameters
    ----------
    runs : list of TrackingRun
        The study's runs.
    crb_pos : ndarray, shape (K,)
        Root of the posterior CRB of the position per frame (m), :func:`crb_position`.
    sc : RangeBearingScenario
        The scenario (N nodes).
    seed : int
        Root seed of the study (recorded in the comparisons).

    Returns
    -------
    dict
        ``chf_central_mse`` with ``_lo``/``_hi`` (the centralised filter's mean squared position error over
        frames 5-K and its 95 % t interval over runs, m²) and ``chf_crb_mse`` (the bound's mean squared
        value over the same frames, m²), ``chf_crb_inside`` ("inside", "above" or "below" the interval) and
        ``chf_crb_text`` (what that means, in words);
        ``chf_naive_pso_d``/``_lo``/``_hi``/``_word`` (naive product minus the patent's method, per-run
        MSE, m²); ``chf_cf_eps_band`` (mean 10-90 % band over runs of the closed-form Chernoff exponents,
        per node and frame) and ``chf_cf_eps_max`` (their largest value); ``chf_is_out`` / ``chf_is_frames``
        (tracking frames whose optimised exponents leave the region min ε_i ≥ ε⁽⁰⁾_i / 2 = 1/(2N), a
        *sufficient* condition of finite weight variance, and all frames); ``chf_is_out_exact`` (frames where
        the exact condition fails for the nodes' moment-matched Gaussians: Λ = Σ(2ε*_i − ε⁽⁰⁾_i)P_i⁻¹ not positive
        definite); ``chf_prev_d``/``_lo``/``_hi`` (ε⁽⁰⁾ = previous ε* minus the patent's method, per-run MSE,
        m²); ``chf_top_run`` (1-based) and ``chf_top_share`` (%) (the run with the largest paired difference of
        the patent's method and uniform exponents, and its share of the summed differences). 4 decimals.

    References
    ----------
    * Tichavský, P., Muravchik, C. H., & Nehorai, A. (1998). Posterior Cramér-Rao bounds for discrete-time
      nonlinear filtering. IEEE Trans. Signal Processing, 46(5), 1386-1396.
    """
    from scipy import stats as _stats

    central = per_run_mse(runs, "centralised")
    ci = _stats.ttest_1samp(central, 0.0).confidence_interval(0.95)
    crb = float(np.mean(np.asarray(crb_pos, dtype=float)[LATE] ** 2))
    cmp_ = _mse_comparison(runs, "naive_product", "chernoff_pso", "less", seed)
    d, lo, hi = cmp_.interval()
    cf = np.stack([r.eps["ci_gaussian"] for r in runs])           # (runs, K, N)
    pso = np.stack([r.eps["pso"] for r in runs])
    n = len(sc.sensors)
    out = np.min(pso, axis=2) < 1.0 / (2 * n) - 1e-12
    infos = np.linalg.inv(np.stack([np.stack([r.covariances[f"local{i + 1}"] for i in range(n)], axis=1) for r in runs]))
    lam = np.sum((2 * pso - 1.0 / n)[..., None, None] * infos, axis=2)  # (runs, K, d, d)
    exact_out = np.linalg.eigvalsh(0.5 * (lam + np.swapaxes(lam, -1, -2)))[..., 0] <= 0
    prev = _mse_comparison(runs, "chernoff_prev", "chernoff_pso", "less", seed).interval()
    dd = per_run_mse(runs, "chernoff_pso") - per_run_mse(runs, "chernoff_uniform")
    top = int(np.argmax(dd))
    return {
        "chf_is_out_exact": int(exact_out.sum()),
        "chf_prev_d": rounded(prev[0]), "chf_prev_lo": rounded(prev[1]), "chf_prev_hi": rounded(prev[2]),
        "chf_top_run": top + 1, "chf_top_share": rounded(float(100 * dd[top] / dd.sum()), 0),
        "chf_central_mse": rounded(float(central.mean())), "chf_central_mse_lo": rounded(float(ci.low)),
        "chf_central_mse_hi": rounded(float(ci.high)), "chf_crb_mse": rounded(crb),
        "chf_crb_inside": "inside" if ci.low <= crb <= ci.high else ("above" if crb > ci.high else "below"),
        "chf_crb_text": ("so the centralised filter meets the bound within Monte-Carlo error" if ci.low <= crb <= ci.high
                         else f"so the centralised filter stays above the bound, by "
                              f"{100 * (np.sqrt(central.mean() / crb) - 1):.0f} % in RMSE" if crb < ci.low
                         else "above the filter's interval: a bound the filter beats, by Monte-Carlo error or because "
                              "it does not bind"),
        "chf_naive_pso_d": rounded(d), "chf_naive_pso_lo": rounded(lo), "chf_naive_pso_hi": rounded(hi),
        "chf_naive_pso_word": "better" if hi < 0 else "worse" if lo > 0 else "not distinguishable",
        "chf_cf_eps_band": rounded(float(np.mean(np.percentile(cf, 90, axis=0) - np.percentile(cf, 10, axis=0)))),
        "chf_cf_eps_max": rounded(float(cf.max())),
        "chf_is_out": int(out.sum()), "chf_is_frames": int(out.size),
    }


# --------------------------------------------------------------------------- where the premise can show
#: The networks' labels in the chapter's table and figure, in order.
PREMISE_LABELS: dict[str, str] = {"unequal": "unequal sensors", "non_gaussian": "range-only and bearings-only",
                                  "feedback": "feedback, 3 frames", "chain": "chain, 2 rounds",
                                  "relay": "node 3 relays node 1", "overconfident": "node 3 overconfident"}
_PMSE = "per-run squared position error averaged over the nodes (m²)"
_MINERR = "error |ω̂ − ω*| of the minimiser of log Z, two-mixture example (per independent sample set)"
_POVER = "per-run share of nodes whose NEES (2-D) exceeds χ²₂'s 95 % point, 5.99"


#: Networks run with more than :data:`STUDY_RUNS` runs: none. The range-only network ran 400 times until the fourth
#: review showed that count was chosen after its 100-run result was seen; the relay network ran 400 times from the
#: commit that added it, with no record that the count was fixed before its outcome was read (review 5, m3). Every
#: network now runs the count every network had before any outcome was read; the reseeding sweep reruns every
#: primary at more runs.
PREMISE_MORE_RUNS: dict[str, int] = {}


def nested_gaussian_weight(k: ArrayLike) -> FloatArray:
    r"""Chernoff weight of the sharper of two nested Gaussians :math:`\mathcal N(0, I)` and :math:`\mathcal N(0, kI)`.

    :math:`\log Z(\omega) = \tfrac d2\,[-\ln(\omega + (1-\omega)/k) - (1-\omega)\ln k]` is minimised at
    :math:`\omega^* = 1/\ln k - 1/(k-1)`, whatever the dimension :math:`d`: it tends to 0 as :math:`k` grows, so the
    criterion leans towards the *less* informative density.

    Parameters
    ----------
    k : array_like
        Variance ratios, > 1.

    Returns
    -------
    ndarray
        :math:`\omega^*` for each ``k``.

    Raises
    ------
    ValueError
        A ratio not above 1.
    """
    k = np.asarray(k, dtype=float)
    if not np.all(np.isfinite(k)) or np.any(k <= 1.0):
        raise ValueError(f"k must hold finite ratios > 1, got {k!r}")
    return 1.0 / np.log(k) - 1.0 / (k - 1.0)


def nested_values(ks: tuple[float, ...] = (2.0, 10.0, 100.0, 1e4)) -> dict[str, Any]:
    """Glue ``chf_nest_*``: the closed form :func:`nested_gaussian_weight` against the numerical Chernoff weights.

    Parameters
    ----------
    ks : tuple of float
        Variance ratios.

    Returns
    -------
    dict
        ``chf_nest_k<j>`` (the ratio), ``chf_nest_w<j>`` (the closed form, 4 decimals) and ``chf_nest_err`` (largest
        difference from :func:`fusion.estimates.chernoff.gaussian_chernoff_weights` in 2-D, 1 significant digit).
    """
    v: dict[str, Any] = {}
    err = 0.0
    for j, k in enumerate(ks):
        w = float(nested_gaussian_weight(k))
        num = ch.gaussian_chernoff_weights(np.zeros((2, 2)), np.stack([np.eye(2), k * np.eye(2)])).eps[0]
        err = max(err, abs(num - w))
        v.update({f"chf_nest_k{j}": k, f"chf_nest_w{j}": rounded(w)})
    v["chf_nest_err"] = float(f"{err:.0e}")
    return v


#: Networks with one exchange of fully connected nodes: their MSE oracle is a fixed exponent vector.
ORACLE_NETWORKS = ("unequal", "non_gaussian", "relay", "overconfident")


_ORACLE_CACHE: dict[tuple[int, float], tuple[NetworkStudy, tuple[FloatArray, FloatArray]]] = {}


def oracle_exponents(st: NetworkStudy, step: float = 0.02) -> tuple[FloatArray, FloatArray]:
    r"""The MSE-optimal fixed exponents of covariance intersection of the nodes' Gaussian summaries (an oracle).

    For a network with one exchange and full connectivity, the fused mean at exponents :math:`\varepsilon` is
    :math:`(\sum_i\varepsilon_i J_i)^{-1}\sum_i\varepsilon_i J_i m_i` (:math:`m_i, J_i^{-1}`: the moments of node
    :math:`i`'s local posterior). The oracle picks, on a grid of the simplex, the exponents with the smallest mean squared
    error over the runs (it knows the truth); its per-run error is cross-validated (exponents chosen on the odd
    runs are scored on the even ones and vice versa), so it is not flattered by the choice.

    Parameters
    ----------
    st : NetworkStudy
        A network of :data:`ORACLE_NETWORKS` (one frame, one round, full connectivity).
    step : float
        Grid step on the simplex.

    Returns
    -------
    eps : ndarray, shape (N,)
        The oracle's exponents (chosen on every run).
    mse : ndarray, shape (runs,)
        Cross-validated per-run squared position error (m²).

    Raises
    ------
    ValueError
        A network with several exchanges or partial connectivity.
    """
    hit = _ORACLE_CACHE.get((id(st), step))
    if hit is not None and hit[0] is st:  # the studies are read-only: computed once per study
        return hit[1]
    sc = st.scenario
    if sc.frames != 1 or sc.rounds != 1 or sc.edges is not None:
        raise ValueError("st must be a network with one exchange and full connectivity")
    N = len(sc.nodes)
    n = int(round(1.0 / step))
    grid = np.array([c for c in np.ndindex(*(n + 1,) * (N - 1)) if sum(c) <= n], dtype=float)
    E = np.column_stack([grid, n - grid.sum(axis=1)]) / n  # (G, N)
    J = np.linalg.inv(st.local_cov + 1e-9 * sc.prior_std**2 * np.eye(2))  # (B, N, 2, 2); the study's floor
    Jm = np.einsum("bnij,bnj->bni", J, st.local_mean)
    A = np.einsum("gn,bnij->bgij", E, J)
    x = np.linalg.solve(A, np.einsum("gn,bni->bgi", E, Jm)[..., None])[..., 0]  # (B, G, 2)
    se = np.sum((x - st.truth) ** 2, axis=-1)  # (B, G)
    odd = np.arange(st.runs) % 2 == 1
    mse = np.empty(st.runs)
    for fit in (odd, ~odd):
        mse[~fit] = se[~fit, int(np.argmin(se[fit].mean(axis=0)))]
    out = (E[int(np.argmin(se.mean(axis=0)))], np.round(mse, 6))
    for a in out:
        a.setflags(write=False)
    _ORACLE_CACHE[(id(st), step)] = (st, out)
    return out


def premise_studies(seed: int, runs: int = STUDY_RUNS, scenarios: dict[str, Any] | None = None,
                    more: dict[str, int] | None = None) -> dict[str, NetworkStudy]:
    """The six designed networks (:func:`~fusion.scenarios.fusion_networks.premise_scenarios` and
    :func:`~fusion.scenarios.fusion_networks.redundancy_scenarios`), ``runs`` runs each.

    Parameters
    ----------
    seed : int
        Root seed; network ``j`` (in the order of :data:`PREMISE_LABELS`) uses ``seed + j``.
    runs : int
        Monte-Carlo runs per network.
    scenarios : dict, optional
        The networks by key of :data:`PREMISE_LABELS` (default: the designed ones; tests pass smaller ones).
    more : dict, optional
        Network key -> runs, for networks run more often than ``runs`` (the chapter passes
        :data:`PREMISE_MORE_RUNS`).

    Returns
    -------
    dict
        Network key -> :class:`~fusion.scenarios.fusion_networks.NetworkStudy`.
    """
    scs = premise_scenarios() | redundancy_scenarios() if scenarios is None else scenarios
    more = {} if more is None else more
    return {k: run_network_study(scs[k], seed + j, more.get(k, runs)) for j, k in enumerate(PREMISE_LABELS)}


def _wins(st: NetworkStudy, a: str, b: str) -> Comparison:
    """Share of runs in which ``a`` has the lower MSE, against one half (a sign test read as a paired interval)."""
    win = (st.mse(a) < st.mse(b)).astype(float)
    return Comparison(win, np.full(win.size, 0.5), NETWORK_METHODS[a], "a coin (half of the runs)", "greater",
                      f"share of runs in which {NETWORK_METHODS[a]} has the lower {_PMSE}", seed=st.seed)


def premise_robust_values(studies: dict[str, NetworkStudy]) -> dict[str, Any]:
    """The heavy tail of the mixture question, network by network: glue ``chf_pr_<k>_mix_*`` beyond the mean.

    Parameters
    ----------
    studies : dict
        :func:`premise_studies`.

    Returns
    -------
    dict
        Per network ``<k>``: ``chf_pr_<k>_runs`` (int), ``chf_pr_<k>_mix_median`` (median paired difference, m²),
        ``chf_pr_<k>_mix_win`` (share of runs in which the mixtures are more accurate), ``chf_pr_<k>_mix_win_lo``/
        ``_hi`` (its 95 % interval), ``chf_pr_<k>_mix_sign_p`` (two-sided sign-test p-value, 2 significant digits),
        ``chf_pr_<k>_mix_top3`` (share of the total absolute difference carried by the three largest runs), and
        ``chf_pr_<k>_mix_wo2`` (mean difference without the two largest absolute differences, m²), ``chf_pr_<k>_mix_mean``
        (the mean difference, m²).
    """
    from scipy import stats as _stats

    v: dict[str, Any] = {}
    for key, st in studies.items():
        d = st.mse("chernoff_pso") - st.mse("ci_gaussian")
        a = np.abs(d)
        order = np.argsort(-a)
        wins = int(np.sum(d < 0))
        ties = int(np.sum(d == 0))
        _, lo, hi = _wins(st, "chernoff_pso", "ci_gaussian").interval()
        p = float(_stats.binomtest(wins, d.size - ties, 0.5).pvalue) if d.size > ties else 1.0
        v.update({f"chf_pr_{key}_runs": st.runs, f"chf_pr_{key}_mix_median": rounded(float(np.median(d)), 2),
                  f"chf_pr_{key}_mix_win": rounded(wins / d.size, 3), f"chf_pr_{key}_mix_win_lo": rounded(0.5 + lo, 3),
                  f"chf_pr_{key}_mix_win_hi": rounded(0.5 + hi, 3), f"chf_pr_{key}_mix_sign_p": float(f"{p:.2g}"),
                  f"chf_pr_{key}_mix_top3": rounded(float(a[order[:3]].sum() / a.sum()), 2) if a.sum() > 0 else 0.0,
                  f"chf_pr_{key}_mix_wo2": rounded(float(d[order[2:]].mean()), 2),
                  f"chf_pr_{key}_mix_mean": rounded(float(d.mean()), 2)})
    return v


def _pcmp(st: NetworkStudy, a: str, b: str) -> Comparison:
    return Comparison(st.mse(a), st.mse(b), NETWORK_METHODS[a], NETWORK_METHODS[b], "less", _PMSE, seed=st.seed)


def _over(st: NetworkStudy, key: str, claim: str) -> Comparison:
    v = st.overconfident(key)
    return Comparison(v, np.full(v.size, 0.05), NETWORK_METHODS[key], "the nominal 5 % of a consistent estimator (a constant: a one-sample test)", claim,  # type: ignore[arg-type]
                      _POVER, seed=st.seed)


def premise_table(studies: dict[str, NetworkStudy]) -> pd.DataFrame:
    """The networks side by side: how non-Gaussian, each method's RMSE, the two paired questions, overconfidence.

    Parameters
    ----------
    studies : dict
        :func:`premise_studies`.

    Returns
    -------
    DataFrame
        One column per network (labels of :data:`PREMISE_LABELS`); rows: the largest mean KL divergence of
        a node's exact local posterior from its moment-matched Gaussian (nats) and that node's mixture gain
        (nats per particle), the RMSE of every method (m), the paired MSE differences optimised − uniform
        exponents and mixture fusion − CI of Gaussians with their 95 % intervals (m², as text), and the
        share of node estimates whose NEES exceeds 5.99 for the naive product and the patent's method;
        2 decimals.
    """
    cols = {}
    for key, st in studies.items():
        kl = st.kl_local.mean(axis=0)
        j = int(np.argmax(kl))
        col: dict[str, Any] = {"most non-Gaussian node: KL from one Gaussian (nats)": f"{kl[j]:.2f}",
                               "that node: mixture gain over one Gaussian (nats/particle)":
                                   f"{st.gm_gain[:, 0, j].mean():.2f}"}
        for m, label in NETWORK_METHODS.items():
            col[f"RMSE (m): {label}"] = f"{np.sqrt(st.mse(m).mean()):.2f}"
        for name, (a, b) in (("optimised − uniform exponents", ("chernoff_pso", "chernoff_uniform")),
                             ("mixture fusion − CI of Gaussians", ("chernoff_pso", "ci_gaussian"))):
            d, lo, hi = _pcmp(st, a, b).interval()
            col[f"{name} (m², 95 % interval)"] = f"{d:.1f} [{lo:.1f}, {hi:.1f}]"
        for m in ("naive_product", "chernoff_pso", "ci_gaussian"):
            col[f"NEES > 5.99 (share of nodes): {NETWORK_METHODS[m]}"] = f"{st.overconfident(m).mean():.2f}"
        col.update(_exponent_rows(key, st))
        cols[PREMISE_LABELS[key]] = col
    return pd.DataFrame(cols)


def _eps_star(st: NetworkStudy) -> str:
    """The swarm's mean exponents of the first exchange (node 1's fusion), as text; "—" without full connectivity."""
    return "—" if st.scenario.edges is not None else ", ".join(f"{x:.2f}" for x in np.nanmean(st.eps[:, 0, 0], axis=0))


def _exponent_rows(key: str, st: NetworkStudy) -> dict[str, str]:
    """Rows of :func:`premise_table` on the exponents: the swarm's, the closed-form Chernoff, the MSE oracle's."""
    rows = {"mean ε* of the swarm (nodes 1, 2, 3; first exchange)": _eps_star(st),
            "MSE oracle ε (fixed, Gaussian summaries)": "—", "RMSE (m): MSE oracle (cross-validated)": "—",
            "oracle − uniform exponents (m², 95 % interval)": "—"}
    if key in ORACLE_NETWORKS:
        e, mse = oracle_exponents(st)
        d, lo, hi = Comparison(mse, st.mse("naive_product"), "oracle", "uniform", "less", _PMSE).interval()
        rows.update({"MSE oracle ε (fixed, Gaussian summaries)": ", ".join(f"{x:.2f}" for x in e),
                     "RMSE (m): MSE oracle (cross-validated)": f"{np.sqrt(mse.mean()):.2f}",
                     "oracle − uniform exponents (m², 95 % interval)": f"{d:.1f} [{lo:.1f}, {hi:.1f}]"})
    return rows


def premise_figure(studies: dict[str, NetworkStudy]) -> Figure:
    """Figure ``fig-chf-premise``: the two paired questions per network, with their 95 % intervals.

    Parameters
    ----------
    studies : dict
        :func:`premise_studies`.

    Returns
    -------
    Figure
        Left: per-run MSE difference (m², symmetric-log axis, linear within ±10 m²) of optimised − uniform
        exponents and of mixture fusion − CI of moment-matched Gaussians, mean and paired 95 % interval, one
        row per network (left of zero: the first is more accurate). Right: share of node estimates whose NEES exceeds χ²₂'s 95 % point for
        the naive product, CI and the patent's method (5 % when consistent). Closed.
    """
    fig, (ax1, ax2) = new_figure(1, 2, figsize=(7.5, 4.4), sharey=True)
    keys = list(studies)
    y = np.arange(len(keys))
    for off, (label, a, b, c) in zip((-0.15, 0.15), (("optimised − uniform exponents", "chernoff_pso", "chernoff_uniform",
                                                       "#0072B2"),
                                                      ("mixture fusion − CI of Gaussians", "chernoff_pso", "ci_gaussian",
                                                       "#009E73"))):
        iv = np.array([_pcmp(studies[k], a, b).interval() for k in keys])
        ax1.errorbar(iv[:, 0], y + off, xerr=[iv[:, 0] - iv[:, 1], iv[:, 2] - iv[:, 0]], fmt="o", color=c, capsize=3,
                     label=label)
    ax1.axvline(0.0, color="grey", lw=0.8)
    ax1.set_xscale("symlog", linthresh=10.0)  # linear within ±10 m², logarithmic beyond: the chain's outliers
    ax1.set(yticks=y, yticklabels=[PREMISE_LABELS[k] for k in keys], xlabel="paired MSE difference (m², symlog)")
    ax1.invert_yaxis()
    for off, m in zip((-0.2, 0.0, 0.2), ("naive_product", "ci_gaussian", "chernoff_pso")):
        ax2.plot([studies[k].overconfident(m).mean() for k in keys], y + off, "s", color=_COLOR[m],
                 label=NETWORK_METHODS[m])
    ax2.axvline(0.05, color="grey", lw=0.8, ls="--")
    ax2.set(xlabel="share of nodes with NEES > 5.99", xlim=(0, 1))
    ax1.legend(loc="upper center", bbox_to_anchor=(0.5, -0.22))
    ax2.legend(loc="upper center", bbox_to_anchor=(0.5, -0.22))
    plt.close(fig)
    return fig


_COLOR = {"naive_product": "#CC79A7", "ci_gaussian": "#009E73", "chernoff_pso": "#0072B2"}


def premise_values(studies: dict[str, NetworkStudy]) -> dict[str, Any]:
    """Glue values ``chf_pr_*`` of the networks (4 decimals unless stated).

    Parameters
    ----------
    studies : dict
        :func:`premise_studies`.

    Returns
    -------
    dict
        Per network ``<k>`` (``unequal``, ``non_gaussian``, ``feedback``, ``chain``): ``chf_pr_<k>_kl`` (largest
        mean KL of a node's local posterior from one Gaussian, nats), ``chf_pr_<k>_gain`` (that node's mixture
        gain, nats per particle), ``chf_pr_<k>_eps_d``/``_lo``/``_hi``/``_word`` (optimised − uniform
        exponents, m²), ``chf_pr_<k>_mix_d``/``_lo``/``_hi``/``_word`` (mixture fusion − CI of Gaussians) and
        ``chf_pr_<k>_cf_*`` (CI with closed-form Chernoff exponents − uniform exponents, i.e. the naive product's mean),
        ``chf_pr_<k>_eps_star`` (the swarm's mean exponents, text), ``chf_pr_<k>_runs`` (int); for a network with a
        relay, ``chf_pr_<k>_copies_star`` and ``chf_pr_<k>_copies_oracle`` (the swarm's mean and the oracle's sum of the
        exponents of the relayed node and its relay, 2 decimals); for the networks of
        :data:`ORACLE_NETWORKS` ``chf_pr_<k>_oracle_eps`` (text), ``_d``/``_lo``/``_hi``/``_word`` (the MSE oracle
        − uniform exponents on the Gaussian summaries, m²) and ``_pct`` (% of the uniform MSE);
        ``chf_pr_<k>_over_naive``/``_pso`` (share of nodes with NEES > 5.99), ``chf_pr_<k>_degenerate`` (int,
        runs in which the patent's fused covariance of some node is singular); ``chf_pr_runs`` (int),
        ``chf_pr_particles``, ``chf_pr_samples`` (int), ``chf_pr_tracking_kl`` is not here (see
        :func:`diagnostics`).
    """
    v: dict[str, Any] = {}
    for key, st in studies.items():
        kl = st.kl_local.mean(axis=0)
        j = int(np.argmax(kl))
        v[f"chf_pr_{key}_kl"] = rounded(float(kl[j]))
        v[f"chf_pr_{key}_gain"] = rounded(float(st.gm_gain[:, 0, j].mean()))
        for tag, (a, b) in (("eps", ("chernoff_pso", "chernoff_uniform")), ("mix", ("chernoff_pso", "ci_gaussian")),
                            ("cf", ("ci_gaussian", "naive_product"))):
            c = _pcmp(st, a, b)
            d, lo, hi = c.interval()
            v.update({f"chf_pr_{key}_{tag}_d": rounded(d), f"chf_pr_{key}_{tag}_lo": rounded(lo),
                      f"chf_pr_{key}_{tag}_hi": rounded(hi), f"chf_pr_{key}_{tag}_word": _word(c)})
        v[f"chf_pr_{key}_over_naive"] = rounded(float(st.overconfident("naive_product").mean()))
        v[f"chf_pr_{key}_over_pso"] = rounded(float(st.overconfident("chernoff_pso").mean()))
        v[f"chf_pr_{key}_degenerate"] = int(st.degenerate("chernoff_pso").sum())
        v[f"chf_pr_{key}_eps_star"] = _eps_star(st)
        copies = [(j, n.relay_of) for j, n in enumerate(st.scenario.nodes) if n.relay_of is not None]
        if copies and st.scenario.edges is None:  # identical inputs: only the sum of their exponents matters
            j, i = copies[0]
            v[f"chf_pr_{key}_copies_star"] = rounded(float(np.nanmean(st.eps[:, 0, 0, i] + st.eps[:, 0, 0, j])), 2)
            if key in ORACLE_NETWORKS:
                e = oracle_exponents(st)[0]
                v[f"chf_pr_{key}_copies_oracle"] = rounded(float(e[i] + e[j]), 2)
        v[f"chf_pr_{key}_runs"] = st.runs
        if key in ORACLE_NETWORKS:
            e, mse = oracle_exponents(st)
            c = Comparison(mse, st.mse("naive_product"), "oracle", "uniform", "less", _PMSE)
            d, lo, hi = c.interval()
            v.update({f"chf_pr_{key}_oracle_eps": ", ".join(f"{x:.2f}" for x in e),
                      f"chf_pr_{key}_oracle_d": rounded(d), f"chf_pr_{key}_oracle_lo": rounded(lo),
                      f"chf_pr_{key}_oracle_hi": rounded(hi), f"chf_pr_{key}_oracle_word": _word(c),
                      f"chf_pr_{key}_oracle_pct": rounded(100 * d / float(st.mse("naive_product").mean()), 1)})
    any_st = next(iter(studies.values()))
    v.update(chf_pr_runs=any_st.runs, chf_pr_particles=any_st.scenario.n_particles,
             chf_pr_samples=any_st.scenario.n_samples)
    return v


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
    """
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


def readings_values(runs: list[TrackingRun]) -> dict[str, Any]:
    """Glue values of the readings of steps D and F (``readings=True``): ``chf_rd_*`` (4 decimals unless stated).

    Parameters
    ----------
    runs : list of TrackingRun
        The study's runs.

    Returns
    -------
    dict
        ``chf_rd_foa_eps_diff`` (mean absolute difference of the exponents argmin Z_FOA from uniform),
        ``chf_rd_kl_frames`` (int, frames where the equal-KL rule has a solution in the simplex),
        ``chf_rd_frames`` (int, all frames), ``chf_rd_kl_gap`` (largest absolute difference of its exponents
        from SLSQP's minimum of Ĵ on the same samples, where it has one), ``chf_rd_boundary`` (int, frames where
        SLSQP's minimum has an exponent below 1e-6).
    """
    foa = np.stack([r.eps["foa"] for r in runs])
    kl = np.stack([r.eps["equal_kl"] for r in runs])
    sl = np.stack([r.eps["slsqp"] for r in runs])
    ok = np.all(np.isfinite(kl), axis=2)
    return {"chf_rd_foa_eps_diff": rounded(float(np.mean(np.abs(foa - 1.0 / foa.shape[2])))),
            "chf_rd_kl_frames": int(ok.sum()), "chf_rd_frames": int(ok.size),
            "chf_rd_kl_gap": float(f"{np.max(np.abs(kl[ok] - sl[ok])) if ok.any() else float('nan'):.1e}"),
            "chf_rd_boundary": int(np.sum(np.min(sl, axis=2) < 1e-6))}


def equal_kl_g_values(runs: list[TrackingRun]) -> dict[str, Any]:
    """Glue values of the equal-KL rule applied to the first-order mixture g (``eps["equal_kl_g"]``): ``chf_klg_*``.

    Parameters
    ----------
    runs : list of TrackingRun
        The study's runs (``readings=True``).

    Returns
    -------
    dict
        ``chf_klg_frames`` (int, frames where the rule on g has a solution in the simplex), ``chf_klg_all`` (int,
        all frames), ``chf_klg_equal`` (int, of those, frames within ``chf_klg_tol`` of SLSQP's minimum of Ĵ in
        every exponent; ``chf_klg_tol`` is the primary's agreement, ``chf_rd_kl_gap`` of :func:`readings_values`:
        how closely SLSQP reproduces an exact solution), ``chf_klg_gap_max``, ``chf_klg_gap_median`` (largest and median over those frames of
        the largest absolute exponent difference from SLSQP's minimum; 4 decimals).
    """
    klg = np.stack([r.eps["equal_kl_g"] for r in runs])
    sl = np.stack([r.eps["slsqp"] for r in runs])
    ok = np.all(np.isfinite(klg), axis=2)
    gap = np.max(np.abs(klg - sl), axis=2)[ok]
    tol = readings_values(runs)["chf_rd_kl_gap"]
    return {"chf_klg_frames": int(ok.sum()), "chf_klg_all": int(ok.size), "chf_klg_tol": tol,
            "chf_klg_equal": int(np.sum(gap <= tol)),
            "chf_klg_gap_max": rounded(float(np.max(gap))) if gap.size else float("nan"),
            "chf_klg_gap_median": rounded(float(np.median(gap))) if gap.size else float("nan")}


# --------------------------------------------------------------------------- claims ledger
def _reason(runs: int) -> str:
    return "" if runs >= STUDY_RUNS else f"{runs} runs: {STUDY_REASON}"


def _mse_comparison(runs: list[TrackingRun], a: str, b: str, claim: str, seed: int, frames: slice = LATE) -> Comparison:
    metric = _MSE if frames == LATE else _MSE.replace("from frame 5 on", _window_text(frames))
    if frames == LATE:
        va, vb = per_run_mse(runs, a), per_run_mse(runs, b)
    else:
        va = np.round(position_sq_errors(runs, a)[:, frames].mean(axis=1), 4)
        vb = np.round(position_sq_errors(runs, b)[:, frames].mean(axis=1), 4)
    return Comparison(va, vb, METHODS[a], METHODS[b], claim,  # type: ignore[arg-type]
                      metric, seed=seed, reason=_reason(len(runs)))


def _window_text(frames: slice) -> str:
    for window, text in ((LATE, "from frame 5 on"), (EARLY, "over frames 1-4"), (ALL_FRAMES, "over every frame")):
        if frames == window:
            return text
    raise ValueError(f"frames must be LATE, EARLY or ALL_FRAMES, got {frames!r}")


_NEES = "per-run mean NEES (4-D) from frame 5 on"
#: NEES of a consistent estimator of a 4-D state (its expected value).
NEES_CONSISTENT = 4.0


def _nees_vs_consistent(runs: list[TrackingRun], key: str, claim: str, seed: int, frames: slice = LATE) -> Comparison:
    """A method's per-run mean NEES over a window against the value 4 of a consistent estimator (one-sample t interval)."""
    nees = per_run_nees(runs, key, frames)
    return Comparison(nees, np.full(nees.size, NEES_CONSISTENT), METHODS[key], "a consistent estimator (NEES 4)",
                      claim, _NEES.replace("from frame 5 on", _window_text(frames)), seed=seed,  # type: ignore[arg-type]
                      reason=_reason(len(runs)))


def guarded_runs(runs: list[TrackingRun], sc: RangeBearingScenario, seed: int,
                 workers: int = STUDY_WORKERS) -> list[TrackingRun]:
    """The study's runs with the collapse guard of every filter: collapsed runs redone, others reused.

    The guard (:func:`guarded_scenario`: progressive correction of an update whose effective sample
    size falls below :data:`COLLAPSE_FRACTION` of the filter's particles, for the nodes and the
    centralised filter) draws nothing in a run where no filter falls below the threshold, so such a run is
    identical with and without it (tested); only the runs in which some filter collapses
    (:func:`any_collapsed`) are run again, from their own seeds (with ``all_nodes`` where the run had it).

    Parameters
    ----------
    runs : list of TrackingRun
        The study without guard, ``monte_carlo(sc, seed, len(runs))``.
    sc : RangeBearingScenario
        Its scenario (without guard).
    seed : int
        Its root seed.
    workers : int
        Processes for the redone runs (results do not depend on it).

    Returns
    -------
    list of TrackingRun
        What ``monte_carlo(guarded_scenario(sc), seed, len(runs))`` gives.
    """
    _check_study(runs)
    bad = any_collapsed(runs, sc)
    seeds = np.random.SeedSequence(seed).spawn(len(runs))
    idx = np.flatnonzero(bad)
    redo = (run_tracking_batch(guarded_scenario(sc), [seeds[j] for j in idx],
                               all_nodes=[runs[j].node_estimates is not None for j in idx], workers=workers)
            if bad.any() else [])
    out, it = [], iter(redo)
    for r, b in zip(runs, bad):
        out.append(next(it) if b else r)
    return out


def guard_values(guarded: list[TrackingRun], sc: RangeBearingScenario) -> dict[str, Any]:
    """Glue values of the guarded study (:func:`guarded_runs`), the study's primary design.

    Parameters
    ----------
    guarded : list of TrackingRun
        The runs with the collapse guard.
    sc : RangeBearingScenario
        The scenario (its ``n_particles`` and ``n_central`` set the collapse thresholds).

    Returns
    -------
    dict
        ``chf_guard_stages`` (int, tempering steps), ``chf_n_guarded`` (int, runs in which the guard acted),
        ``chf_guard_updates`` (int, guarded node updates), ``chf_guard_central`` (int, guarded updates of the
        centralised filter), ``chf_guard_ess_min`` (smallest ESS of any node and frame in those runs, after the
        last tempering step, 1 decimal), ``chf_guard_central_min`` (the centralised filter's, 0 decimals),
        ``chf_n_collapsed_guard`` (int, runs still collapsed, node or centralised).
    """
    _check_study(guarded)
    hit = [r for r in guarded if r.guarded]
    return {"chf_guard_stages": GUARD_STAGES, "chf_n_guarded": len(hit),
            "chf_guard_updates": sum(1 for r in hit for _, i in r.guarded if i >= 0),
            "chf_guard_central": sum(1 for r in hit for _, i in r.guarded if i < 0),
            "chf_guard_ess_min": rounded(float(min_local_ess(hit).min()), 1) if hit else 0.0,
            "chf_guard_central_min": rounded(float(min(np.min(r.ess["centralised"]) for r in hit)), 0) if hit else 0.0,
            "chf_n_collapsed_guard": int(any_collapsed(guarded, sc).sum())}


def guard_usability(guarded: list[TrackingRun], plain: list[TrackingRun], sc: RangeBearingScenario,
                    thresholds: tuple[float, ...] = (0.01, 0.05)) -> dict[str, Any]:
    """Are the guarded runs' posteriors usable, by measures the guard does not target? Glue ``chf_gu_*``.

    The guard acts on the effective sample size; usability is judged here by the local filters' consistency and
    the fused accuracy: each run in which the guard acted is placed among the runs it did not touch, by the mean
    NEES (4-D) of its local filters (over nodes and every frame) and by the patent's method's mean squared error
    (frames 5 on). The rule, fixed before reading the numbers: usable when every guarded run lies at or below the
    95th percentile of the untouched runs on both. The collapse threshold is an open choice: the updates that
    would trigger the guard at other thresholds are counted on the plain runs (not rerun).

    Parameters
    ----------
    guarded : list of TrackingRun
        The study (with the guard).
    plain : list of TrackingRun
        The same runs without the guard.
    sc : RangeBearingScenario
        Particles per node (thresholds are fractions of them).
    thresholds : tuple of float
        Other collapse thresholds (fractions of the particles) whose trigger counts are reported.

    Returns
    -------
    dict
        ``chf_gu_runs`` (int, runs in which the guard acted), ``chf_gu_nees_max``/``_p95`` (largest local NEES of
        those runs / 95th percentile of the others), ``chf_gu_nees_rank`` (largest percentile rank of a guarded
        run among the others, %), the same ``chf_gu_mse_*`` (m²), ``chf_gu_usable`` (bool, the rule above);
        ``chf_gu_chance_fail`` (the chance that the rule fails on one measure even if the repaired runs were exchangeable
        with the others, 1 − 0.95^k); ``chf_gu_own_n`` (int, repaired filters: run and node, or the centralised filter), ``chf_gu_own_ratio_max``
        (largest ratio of a repaired filter's own mean NEES to the 95th percentile of the same filter in the untouched
        runs) and ``chf_gu_own_usable`` (bool, every ratio at most 1); ``chf_gu_worst_run`` (int, the repaired run with
        the largest MSE), ``chf_gu_worst_node``/``_nees`` (its node with the largest mean NEES, and that NEES) and
        ``chf_gu_worst_repaired`` (str, the filters the guard repaired in it); and
        per threshold ``j`` ``chf_gu_thr<j>`` (%), ``chf_gu_thr<j>_runs`` and ``chf_gu_thr<j>_updates`` (int:
        runs and node updates of the plain runs below it). 2 decimals (ranks and percentiles 0).

    Raises
    ------
    ValueError
        Fewer than two runs in which the guard did not act.
    """
    _check_study(guarded)
    _check_study(plain)
    hit = np.array([bool(r.guarded) for r in guarded])
    if (~hit).sum() < 2:
        raise ValueError("guarded: fewer than two runs without the guard's action, nothing to compare with")
    nees = np.mean([per_run_nees(guarded, f"local{i + 1}", ALL_FRAMES) for i in range(len(sc.sensors))], axis=0)
    mse = per_run_mse(guarded, "chernoff_pso")
    v: dict[str, Any] = {"chf_gu_runs": int(hit.sum())}
    usable = True
    for tag, x in (("nees", nees), ("mse", mse)):
        others = x[~hit]
        p95 = float(np.percentile(others, 95))
        worst = float(x[hit].max()) if hit.any() else 0.0  # no repaired run: nothing to place
        rank = float(max(np.mean(others < y) for y in x[hit]) * 100) if hit.any() else 0.0
        usable = usable and (not hit.any() or worst <= p95)
        v.update({f"chf_gu_{tag}_max": rounded(worst, 2), f"chf_gu_{tag}_p95": rounded(p95, 2),
                  f"chf_gu_{tag}_rank": rounded(rank, 0)})
    v["chf_gu_usable"] = bool(usable)
    # the rule's own false alarm: k runs exchangeable with the others all at or below a 95th percentile, on one measure
    v["chf_gu_chance_fail"] = rounded(1.0 - 0.95 ** int(hit.sum()), 2)
    # the repaired filters themselves: each repaired node's (or the centralised filter's) own mean NEES against the
    # 95th percentile of the same filter in the untouched runs (a reading added after the rule above was read)
    own = {i: per_run_nees(guarded, f"local{i + 1}" if i >= 0 else "centralised", ALL_FRAMES)
           for i in range(-1, len(sc.sensors))}
    pairs = sorted({(j, i) for j, r in enumerate(guarded) for _, i in r.guarded})
    ratios = [own[i][j] / float(np.percentile(own[i][~hit], 95)) for j, i in pairs]
    v["chf_gu_own_ratio_max"] = rounded(float(max(ratios)), 2) if ratios else 0.0
    v["chf_gu_own_n"] = len(pairs)
    v["chf_gu_own_usable"] = bool(all(x <= 1.0 for x in ratios))
    worst = int(np.flatnonzero(hit)[np.argmax(mse[hit])]) if hit.any() else 0
    v["chf_gu_worst_run"] = worst + 1
    v["chf_gu_worst_nees"] = rounded(float(max(own[i][worst] for i in range(len(sc.sensors)))), 2)
    v["chf_gu_worst_node"] = int(np.argmax([own[i][worst] for i in range(len(sc.sensors))])) + 1
    v["chf_gu_worst_repaired"] = ", ".join("centralised" if i < 0 else f"node {i + 1}"
                                           for i in sorted({i for _, i in guarded[worst].guarded}))
    ess = np.stack([r.ess["local"] for r in plain])  # (runs, K, N)
    for j, t in enumerate(thresholds):
        below = ess < t * sc.n_particles
        v.update({f"chf_gu_thr{j}": rounded(100 * t, 1), f"chf_gu_thr{j}_runs": int(below.any(axis=(1, 2)).sum()),
                  f"chf_gu_thr{j}_updates": int(below.sum())})
    return v


@dataclass(frozen=True)
class DesignStudy:
    """The first update of the local filters under three designs, on the same runs (:func:`design_study`).

    Attributes
    ----------
    ess : dict {"plain", "more particles", "guard"} -> ndarray, shape (runs, N)
        Effective particles of every node after its first update (after the last tempering step for the guard).
    weighted : dict
        Particles weighted at the first update, per node (the design's cost: 2,000; ``n_initial``; 2,000 plus
        the tempering steps where the guard acts, counted as likelihood passes × particles).
    n_initial : int
        Particles drawn from the prior by the "more particles" design (then resampled to ``n_particles``).
    threshold : float
        Effective particles below which a node counts as collapsed (:data:`COLLAPSE_FRACTION` × ``n_particles``).
    """

    ess: dict[str, FloatArray]
    weighted: dict[str, float]
    n_initial: int
    threshold: float

    def glue(self) -> dict[str, Any]:
        """Glue values ``chf_design_*``: runs collapsed at the first update, smallest ESS and cost, per design."""
        v: dict[str, Any] = {"chf_design_n0": self.n_initial, "chf_design_runs": int(self.ess["plain"].shape[0])}
        for name, key in (("plain", "plain"), ("more particles", "more"), ("guard", "guard")):
            low = self.ess[name].min(axis=1)
            v[f"chf_design_{key}_collapsed"] = int(np.sum(low < self.threshold))
            v[f"chf_design_{key}_min"] = rounded(float(low.min()), 1)
            v[f"chf_design_{key}_cost"] = rounded(float(self.weighted[name]), 0)
        return v


def design_study(sc: RangeBearingScenario, seed: int, runs: int = STUDY_RUNS, n_initial: int = 10_000,
                 workers: int = STUDY_WORKERS) -> DesignStudy:
    """Three designs of the local filters on the first update of the same runs: which one avoids collapse, at what cost.

    Every observed collapse of a node is a first update whose likelihood is much narrower than the prior (or,
    rarely, a later one). The designs: the plain bootstrap filter; *more particles* for the first update
    (``n_initial`` drawn from the prior, resampled to ``n_particles`` after weighting); and the *guard*,
    progressive correction where a node falls below :data:`COLLAPSE_FRACTION` (:func:`guarded_scenario`).
    One-frame runs of the study's seeds: the same prior means, first true states and particle draws as the
    study's runs, but not the same first readings (a run draws its measurement noise after its whole trajectory).

    Parameters
    ----------
    sc : RangeBearingScenario
        The study's scenario.
    seed : int
        Root seed (every design uses the same runs).
    runs : int
    n_initial : int
        Particles of the "more particles" design's first update.
    workers : int
        Processes (results do not depend on it).

    Returns
    -------
    DesignStudy
    """
    # the nodes' first update is all that is read: the fusion and the centralised filter run small (they draw from
    # their own streams, after the nodes' weights are computed, so the effective sample sizes do not change)
    one = dataclasses.replace(sc, frames=1, variants=False, readings=False, n_samples=50, n_central=50, em_iterations=1)
    designs = {"plain": one, "more particles": dataclasses.replace(one, n_initial=n_initial),
               "guard": dataclasses.replace(one, guard=COLLAPSE_FRACTION)}
    ess, weighted = {}, {}
    plain: list[TrackingRun] = []
    for name, d in designs.items():
        seeds = np.random.SeedSequence(seed).spawn(runs)  # fresh: a SeedSequence spawns new children at every spawn
        if name == "guard":  # the guard draws nothing where no node collapses: redo only the runs that collapse
            idx = [j for j, r in enumerate(plain) if np.min(r.ess["local"][0]) < COLLAPSE_FRACTION * sc.n_particles]
            redo = run_tracking_batch(d, [seeds[j] for j in idx], workers=workers) if idx else []
            rs = list(plain)
            for j, r in zip(idx, redo):
                rs[j] = r
        else:
            rs = run_tracking_batch(d, seeds, workers=workers)
        if name == "plain":
            plain = rs
        ess[name] = np.stack([r.ess["local"][0] for r in rs])
        n_nodes = ess[name].size
        extra = sum(len(r.guarded) for r in rs) * (GUARD_STAGES - 1) * sc.n_particles
        weighted[name] = (max(d.n_initial, d.n_particles) * n_nodes + extra) / n_nodes
    return DesignStudy(ess=ess, weighted=weighted, n_initial=n_initial, threshold=COLLAPSE_FRACTION * sc.n_particles)


def _check_study(runs: object) -> None:
    if not isinstance(runs, list) or not runs or not all(isinstance(r, TrackingRun) for r in runs):
        raise ValueError("runs must be a non-empty list of TrackingRun")


# --------------------------------------------------------------------------- evidence of the claim file
# Every record of book/claims/cn107330468b.yaml names one of the functions below as its evidence. Each takes the
# reading's settings (from the claim file), the chapter's root seed and its run count, and returns the evidence;
# the studies behind them are cached on (seed, runs, scenario), so the notebook, which calls the same study
# functions, computes each study once.

@lru_cache(maxsize=2)
def _tracking(seed: int, runs: int, sc: RangeBearingScenario) -> tuple[list[TrackingRun], list[TrackingRun]]:
    plain = monte_carlo(sc, seed, runs, workers=STUDY_WORKERS)
    return plain, guarded_runs(plain, sc, seed)


def tracking_study(seed: int, runs: int = STUDY_RUNS, sc: RangeBearingScenario | None = None,
                   ) -> tuple[list[TrackingRun], list[TrackingRun]]:
    """The tracking study, without and with the collapse guard (cached: computed once per seed, runs, scenario).

    Parameters
    ----------
    seed : int
        Root seed of the runs (the same seeds for every method).
    runs : int
    sc : RangeBearingScenario, optional
        Default :func:`study_scenario`.

    Returns
    -------
    plain, guarded : list of TrackingRun
        ``monte_carlo(sc, seed, runs)`` and :func:`guarded_runs` of it (do not modify them: they are cached).
    """
    return _tracking(int(seed), int(runs), study_scenario() if sc is None else sc)


@lru_cache(maxsize=2)
def _design(seed: int, runs: int, sc: RangeBearingScenario) -> DesignStudy:
    return design_study(sc, seed, runs)


def design(seed: int, runs: int = STUDY_RUNS, sc: RangeBearingScenario | None = None) -> DesignStudy:
    """:func:`design_study` of the study's scenario (or ``sc``), cached.

    Parameters
    ----------
    seed, runs : int
        Seed and runs of the study.
    sc : RangeBearingScenario, optional
        Default: the study's scenario.

    Returns
    -------
    DesignStudy
    """
    return _design(int(seed), int(runs), study_scenario() if sc is None else sc)


@lru_cache(maxsize=2)
def checks_study(seed: int) -> GaussianChecks:
    """:func:`gaussian_checks` with ``default_rng(seed)``, cached."""
    return gaussian_checks(np.random.default_rng(seed))


@lru_cache(maxsize=2)
def common_study(seed: int) -> tuple[bool, float, float]:
    """:func:`common_information_check` with ``default_rng(seed + 5)``, cached."""
    return common_information_check(np.random.default_rng(seed + 5))


@lru_cache(maxsize=4)
def _toy(seed: int, r: int) -> ToyStudy:
    base = None if r == 20_000 else _toy(seed, 20_000)  # the exact and first-order curves do not depend on r
    return toy_study(np.random.default_rng(seed + 1), r, base)


def toy(seed: int, r: int = 20_000) -> ToyStudy:
    """:func:`toy_study` with ``default_rng(seed + 1)`` and ``r`` importance samples, cached.

    Parameters
    ----------
    seed : int
        Seed (the study uses ``default_rng(seed + 1)``).
    r : int
        Importance samples.

    Returns
    -------
    ToyStudy
    """
    return _toy(int(seed), int(r))


@lru_cache(maxsize=2)
def isv_study(seed: int) -> IsVarianceStudy:
    """:func:`is_variance_study` with ``default_rng(seed + 3)``, cached."""
    return is_variance_study(np.random.default_rng(seed + 3))


@lru_cache(maxsize=2)
def _premise(seed: int, runs: int, scenarios: tuple[tuple[str, Any], ...] | None) -> dict[str, NetworkStudy]:
    more = {k: n * runs // STUDY_RUNS for k, n in PREMISE_MORE_RUNS.items()}
    return premise_studies(seed + 10, runs, None if scenarios is None else dict(scenarios), more=more)


def premise_study(seed: int, runs: int = STUDY_RUNS, scenarios: dict[str, Any] | None = None) -> dict[str, NetworkStudy]:
    """The designed networks (:func:`premise_studies` with seed ``seed + 10``), cached.

    Parameters
    ----------
    seed : int
        The chapter's root seed.
    runs : int
        Runs per network; the networks of :data:`PREMISE_MORE_RUNS` run ``runs / 100`` times theirs.
    scenarios : dict, optional
        Other networks (tests).

    Returns
    -------
    dict
        Network key -> NetworkStudy (do not modify: cached).
    """
    return _premise(int(seed), int(runs), None if scenarios is None else tuple(scenarios.items()))


@lru_cache(maxsize=2)
def premise_mixture_scaled(seed: int, runs: int = STUDY_RUNS, factor: int = 10) -> dict[str, Any]:
    """Record chf-premise-mixture's primary comparison at ``factor`` times the runs, on the chapter's own seed.

    The range-only network with the seed :func:`premise_study` gives it (``seed + 10`` plus its index in
    :data:`PREMISE_LABELS`), ``factor * runs`` runs (run ``r`` is the ``r``-th child of the seed's ``SeedSequence``, so the
    first ``runs`` are the chapter's own runs, extended). The reseeding sweep's run at more runs uses a seed of its own; this one answers
    whether the chapter's borderline mean gain holds on its own seed.

    Parameters
    ----------
    seed, runs : int
        The chapter's root seed and runs per network.
    factor : int
        Multiple of the runs.

    Returns
    -------
    dict
        Glue values ``chf_pr_ngx_*``: ``runs``, ``seed`` (int), ``d``/``lo``/``hi`` (mixture fusion − CI of Gaussians,
        mean and paired 95 % interval, m²), ``margin`` (R2's, m²), ``status`` (the rulebook's), ``median`` (m²),
        ``win`` (share of runs in which the mixtures are more accurate) and ``hill`` (the differences' Hill index).
    """
    j = list(PREMISE_LABELS).index("non_gaussian")
    st = run_network_study(premise_scenarios()["non_gaussian"], int(seed) + 10 + j, int(factor) * int(runs))
    c = _pcmp(st, "chernoff_pso", "ci_gaussian")
    jd = c.judgement()
    d = st.mse("chernoff_pso") - st.mse("ci_gaussian")
    return {"chf_pr_ngx_runs": int(st.runs), "chf_pr_ngx_seed": int(st.seed), "chf_pr_ngx_d": rounded(jd.estimate),
            "chf_pr_ngx_lo": rounded(jd.low), "chf_pr_ngx_hi": rounded(jd.high), "chf_pr_ngx_margin": rounded(jd.margin),
            "chf_pr_ngx_status": jd.status, "chf_pr_ngx_median": rounded(float(np.median(d))),
            "chf_pr_ngx_win": rounded(float(jd.share)), "chf_pr_ngx_hill": rounded(float(jd.tail_index), 2)}


def _settings(settings: Any, allowed: dict[str, tuple[Any, ...]], defaults: dict[str, Any]) -> dict[str, Any]:
    """Settings of a reading, checked against the allowed values (ValueError naming the setting)."""
    if not isinstance(settings, dict):
        raise ValueError(f"settings must be a dict, got {type(settings).__name__}")
    extra = set(settings) - set(allowed)
    if extra:
        raise ValueError(f"settings: unknown {sorted(extra)} (allowed {sorted(allowed)})")
    out = {**defaults, **settings}
    for k, ok in allowed.items():
        if k not in out:
            raise ValueError(f"settings: {k!r} is required")
        if ok and out[k] not in ok:
            raise ValueError(f"settings[{k!r}] must be one of {list(ok)}, got {out[k]!r}")
    return out


_WINDOWS = {"late": LATE, "early": EARLY, "all": ALL_FRAMES}
_TRACK_METHODS = (*METHODS, "consistent")


def ev_tracking(settings: dict[str, Any], *, seed: int, runs: int,
                sc: RangeBearingScenario | None = None) -> Comparison:
    """A paired comparison of two methods of the tracking study (records ``chf-gain-*``, ``chf-double-count``).

    Parameters
    ----------
    settings : dict
        ``a``, ``b`` (keys of :data:`~fusion.scenarios.range_bearing.METHODS`; ``"consistent"``: NEES 4 in every
        run), ``design`` (``"guard"``, default; ``"plain"``: no collapse guard; ``"plain-kept"``: no guard, the runs
        with a collapsed filter left out), ``window`` (``"late"``, default: frames 5 on; ``"early"``: 1-4;
        ``"all"``), ``metric`` (``"mse"``, default, or ``"nees"``) and ``claim`` (``"less"``, default, or
        ``"greater"``).
    seed, runs : int
        The study's root seed and run count (:func:`tracking_study`).
    sc : RangeBearingScenario, optional
        Default :func:`study_scenario`.

    Returns
    -------
    Comparison
    """
    s = _settings(settings, {"a": _TRACK_METHODS, "b": _TRACK_METHODS, "design": ("guard", "plain", "plain-kept"),
                             "window": tuple(_WINDOWS), "metric": ("mse", "nees"), "claim": ("less", "greater")},
                  {"design": "guard", "window": "late", "metric": "mse", "claim": "less"})
    plain, guarded = tracking_study(seed, runs, sc)
    rs = guarded if s["design"] == "guard" else plain
    if s["design"] == "plain-kept":
        bad = any_collapsed(plain, study_scenario() if sc is None else sc)
        rs = [r for r, x in zip(plain, bad) if not x]
    frames = _WINDOWS[s["window"]]
    if s["metric"] == "mse":
        if "consistent" in (s["a"], s["b"]):
            raise ValueError("settings: 'consistent' is a NEES yardstick, not a method with a squared error")
        return _mse_comparison(rs, s["a"], s["b"], s["claim"], seed, frames)
    vals = {k: (np.full(len(rs), NEES_CONSISTENT) if k == "consistent" else per_run_nees(rs, k, frames))
            for k in (s["a"], s["b"])}
    name = {k: "a consistent estimator (NEES 4)" if k == "consistent" else METHODS[k] for k in vals}
    return Comparison(vals[s["a"]], vals[s["b"]], name[s["a"]], name[s["b"]], s["claim"],
                      _NEES.replace("from frame 5 on", _window_text(frames)), seed=seed, reason=_reason(len(rs)))


def _equivalent(cmp: Comparison) -> Proposition:
    """"No difference that matters": the paired interval inside ±5 % of the baseline's mean (R2's margin)."""
    eq = Comparison(cmp.a, cmp.b, cmp.a_name, cmp.b_name, "equal", cmp.metric, cmp.seed, cmp.reason)
    return Proposition(eq.status() == "reproduced", eq.summary())


def ev_pso(settings: dict[str, Any], *, seed: int, runs: int,
           sc: RangeBearingScenario | None = None) -> Proposition | Conjunction:
    """Record chf-pso-rebuild: does the swarm of step G find the minimum of Ĵ (SLSQP's, on the same samples)?

    Parameters
    ----------
    settings : dict
        ``check``: ``"within-se"`` (every frame within Ĵ's delta-method standard error, √(1/ESS − 1/R), of SLSQP),
        ``"within-se-and-cost"`` (that, and the per-run MSE against SLSQP's within ±5 %: a conjunction whose
        comparison gives the record a run count, so the reseeding sweep covers it),
        ``"fixed-tolerance"`` (the gap below 10⁻³ nats in 95 % of the frames), ``"literal"`` (the literal stopping
        rule of G6 within the standard error in every frame), ``"gap-mse"`` / ``"literal-mse"`` (the estimate's
        per-run MSE against SLSQP's / the stagnation rule's within ±5 %).
    seed, runs : int
    sc : RangeBearingScenario, optional

    Returns
    -------
    Proposition
    """
    s = _settings(settings, {"check": ("within-se", "within-se-and-cost", "fixed-tolerance", "literal", "gap-mse",
                                       "literal-mse")}, {})
    _, rs = tracking_study(seed, runs, sc)
    obj = {m: np.stack([r.objective[m] for r in rs]) for m in ("pso", "slsqp")}
    # Ĵ's own sampling error (delta method: Var log mean(w) ≈ 1/ESS − 1/R)
    se = np.sqrt(np.maximum(1.0 / np.stack([r.ess["pso"] for r in rs])
                            - 1.0 / (study_scenario() if sc is None else sc).n_samples, 0.0))
    evals = np.mean([r.evaluations["pso"] for r in rs])
    if s["check"] in ("within-se", "within-se-and-cost"):
        within = np.abs(obj["pso"] - obj["slsqp"]) < se
        prop = Proposition(bool(within.all()), f"objective within {np.max(np.abs(obj['pso'] - obj['slsqp'])):.1e} "
                           f"nats of SLSQP's, below Ĵ's standard error in {int(within.sum())} of {within.size} frames; "
                           f"{evals:.0f} vs {np.mean([r.evaluations['slsqp'] for r in rs]):.0f} evaluations per frame", runs=len(rs))
        if s["check"] == "within-se":
            return prop
        cmp = _mse_comparison(rs, "chernoff_pso", "chernoff_slsqp", "less", seed)
        eq = Comparison(cmp.a, cmp.b, cmp.a_name, cmp.b_name, "equal", cmp.metric, cmp.seed, cmp.reason)
        return Conjunction([("every frame within Ĵ's standard error of SLSQP", prop),
                            ("no accuracy cost against SLSQP's exponents (per-run MSE, ±5 %)", eq)])
    if s["check"] == "fixed-tolerance":
        gaps = np.round(np.maximum(obj["pso"] - obj["slsqp"], 0.0).ravel(), 12)
        return Proposition(bool(np.quantile(gaps, 0.95) <= 1e-3),
                           f"gap over {gaps.size} frames: median {np.median(gaps):.1e}, 95th percentile "
                           f"{np.quantile(gaps, 0.95):.1e}, largest {np.max(gaps):.1e} nats", runs=len(rs))
    if s["check"] == "literal":
        lit = np.stack([r.objective["literal"] for r in rs])
        ev = np.stack([r.evaluations["literal"] for r in rs])
        p = inspect.signature(particle_swarm).parameters
        limit = int(p["n_particles"].default * (p["iterations"].default + 1))
        within = lit - obj["slsqp"] < se
        return Proposition(bool(within.all()), f"objective within {np.max(lit - obj['slsqp']):.1e} nats of SLSQP's, "
                           f"below Ĵ's standard error in {int(within.sum())} of {within.size} frames; {ev.mean():.0f} "
                           f"evaluations per frame against {evals:.0f}; the iteration limit reached in "
                           f"{int(np.sum(ev >= limit))} frames", runs=len(rs))
    a, b = ("chernoff_pso", "chernoff_slsqp") if s["check"] == "gap-mse" else ("chernoff_literal", "chernoff_pso")
    return _equivalent(_mse_comparison(rs, a, b, "less", seed))


def ev_formulas(settings: dict[str, Any], *, seed: int, runs: int) -> Unverifiable:
    """Record chf-formulas: nothing to compute (the reason is the claim file's).

    Parameters
    ----------
    settings : dict
        The reading's settings (from the claim file).
    seed, runs : int
        Seed and Monte-Carlo runs of the reading.

    Returns
    -------
    Unverifiable
    """
    _settings(settings, {}, {})
    return Unverifiable("the patent prints no formula")


def ev_common_once(settings: dict[str, Any], *, seed: int, runs: int) -> Proposition:
    """Record chf-common-once: :func:`common_information_check` (a common factor c enters as c^(Σε) = c).

    Parameters
    ----------
    settings : dict
        The reading's settings (from the claim file).
    seed, runs : int
        Seed and Monte-Carlo runs of the reading.

    Returns
    -------
    Proposition
    """
    _settings(settings, {}, {})
    ok, err_g, err_d = common_study(seed)
    return Proposition(ok, f"fused information = J0 + Σ ε_i J_i on 100 random 4-D Gaussian cases (relative error "
                       f"{err_g:.0e}; the naive product has N J0); 100 non-Gaussian 1-D cases on a grid (largest "
                       f"density difference {err_d:.0e})")


def ev_gaussian_ci(settings: dict[str, Any], *, seed: int, runs: int) -> Proposition:
    """Records chf-gaussian-ci (K1), chf-gaussian-normaliser (K2) and chf-gaussian-z-bound (K3): one statement each.

    Parameters
    ----------
    settings : dict
        ``statement``: ``"ci"`` (default: Chernoff fusion of Gaussians is covariance intersection, K1),
        ``"normaliser"`` (the closed form eq. ``eq-chf-k2``, K2) or ``"z-bound"`` (Z <= 1, K3).
    seed, runs : int
        Seed and Monte-Carlo runs of the reading.

    Returns
    -------
    Proposition
    """
    s = _settings(settings, {"statement": ("ci", "normaliser", "z-bound")}, {"statement": "ci"})
    k = checks_study(seed)
    t1, t2, _ = k.tolerances
    if s["statement"] == "ci":
        return Proposition(k.k1 < t1, f"Chernoff fusion and covariance intersection equal to < {fmt(t1)} (relative) "
                           "on 100 random 4-D pairs")
    if s["statement"] == "normaliser":
        return Proposition(k.k2 < t2, f"general and closed-form normaliser equal to < {fmt(t2)} nats on 100 random "
                           "4-D pairs")
    return Proposition(k.k3 <= 1e-12, "log Z <= 0 on 100 random 4-D pairs")


def ev_foa(settings: dict[str, Any], *, seed: int, runs: int) -> Proposition:
    """Record chf-foa-rebuild: log Z_FOA >= log Z on the two-mixture example (g approximates, and bounds, the fusion).

    Parameters
    ----------
    settings : dict
        The reading's settings (from the claim file).
    seed, runs : int
        Seed and Monte-Carlo runs of the reading.

    Returns
    -------
    Proposition
    """
    _settings(settings, {}, {})
    t = toy(seed)
    gap = t.foa - t.exact
    return Proposition(bool(np.min(gap) >= -1e-9), f"log Z_FOA − log Z from {np.min(gap):.3f} to {np.max(gap):.3f} "
                       "nats on the two-mixture example: an upper bound, not the Chernoff normaliser")


@lru_cache(maxsize=4)
def is_replicates(seed: int, r: int, runs: int = STUDY_RUNS) -> FloatArray:
    r"""Minimiser errors of importance sampling on the two-mixture example over independent sample sets.

    One stream (``default_rng(seed + 100)``) draws ``runs`` independent sets of ``r`` samples from the first-order
    mixture at ω = 0.5 (their densities evaluated in one call); each set's :math:`\hat J` (eq. ``eq-chf-is``) is
    minimised on the simplex.

    Parameters
    ----------
    seed : int
        The chapter's root seed.
    r : int
        Importance samples per replicate.
    runs : int
        Replicates (independent sample sets).

    Returns
    -------
    ndarray, shape (runs,)
        The absolute error of the importance-sampled minimiser of ω per replicate (do not modify: cached).
    """
    t = toy(seed)
    gms = list(t.gms)
    g05 = ch.foa_fusion(gms, [0.5, 0.5]).mixture
    xs = mx.gm_sample(g05, np.random.default_rng(seed + 100), int(runs) * int(r))
    L, lg = ch.log_densities(gms, xs), mx.gm_logpdf(g05, xs)
    sets = [slice(j * int(r), (j + 1) * int(r)) for j in range(int(runs))]
    return np.array([abs(float(ch.simplex_minimum(L[k], lg[k]).x[0]) - t.w_exact) for k in sets])


def is_replicate_values(seed: int, runs: int = STUDY_RUNS) -> dict[str, Any]:
    """Glue ``chf_isr_*``: the importance-sampled minimiser's error over independent sample sets (record chf-is).

    Parameters
    ----------
    seed : int
        The chapter's root seed.
    runs : int
        Sample sets per R (:func:`is_replicates`).

    Returns
    -------
    dict
        ``chf_isr_runs`` (int), ``chf_isr_foa`` (the first-order minimiser's error), ``chf_isr_err_hi`` and
        ``chf_isr_err_lo`` (mean error at R = 20 000 and 2 000), ``chf_isr_worse_lo`` (share of the sets at R = 2 000
        whose error exceeds the first-order one); 4 decimals (shares 2).
    """
    t = toy(seed)
    foa = abs(t.w_foa - t.w_exact)
    hi, lo = is_replicates(int(seed), 20_000, int(runs)), is_replicates(int(seed), 2_000, int(runs))
    return {"chf_isr_runs": int(runs), "chf_isr_foa": rounded(foa), "chf_isr_err_hi": rounded(float(hi.mean())),
            "chf_isr_err_lo": rounded(float(lo.mean())), "chf_isr_worse_lo": rounded(float(np.mean(lo > foa)), 2)}


def ev_is(settings: dict[str, Any], *, seed: int, runs: int) -> Comparison:
    """Record chf-is-rebuild: the IS minimiser's error against the first-order minimiser's, over independent sample sets.

    Parameters
    ----------
    settings : dict
        ``r``: importance samples per set (default 2 000, the tracking study's).
    seed, runs : int
        Seed and replicates (independent sample sets, :func:`is_replicates`).

    Returns
    -------
    Comparison
        Per replicate the absolute error of the importance-sampled minimiser against the first-order minimiser's
        error (the same in every replicate: it draws nothing), direction "less".
    """
    s = _settings(settings, {"r": ()}, {"r": 2_000})
    t = toy(seed)
    err = is_replicates(int(seed), int(s["r"]), int(runs))
    return Comparison(err, np.full(err.size, abs(t.w_foa - t.w_exact)), f"importance sampling, R = {int(s['r'])}",
                      "the first-order approximation", "less", _MINERR, seed=seed, reason=_reason(err.size))


def ev_is_variance(settings: dict[str, Any], *, seed: int, runs: int,
                   sc: RangeBearingScenario | None = None) -> Proposition:
    """Record chf-is-variance: the finite-variance region of the weights (Gaussian pair) and the study's frames.

    Parameters
    ----------
    settings : dict
        The reading's settings (from the claim file).
    seed, runs : int
        Seed and Monte-Carlo runs of the reading.
    sc : RangeBearingScenario, optional
        Another scenario (tests); default the study's.

    Returns
    -------
    Proposition
    """
    _settings(settings, {}, {})
    isv = isv_study(seed)
    _, rs = tracking_study(seed, runs, sc)
    v = _is_region_counts(rs)
    return Proposition(bool(isv.lo <= 0.0 and isv.hi >= 1.0),
                       f"Gaussian pair, proposal at ω⁽⁰⁾ = 0.5: finite variance only for ω in [{isv.lo:.3f}, "
                       f"{isv.hi:.3f}]; the bias (ρ − 1)/(2R) confirmed where the third moment is finite ([{isv.lo3:.3f}, "
                       f"{isv.hi3:.3f}]); in the tracking study the exact condition fails in {v['chf_is_out_exact']} of "
                       f"{v['chf_is_frames']} frames")


def _is_region_counts(rs: list[TrackingRun]) -> dict[str, int]:
    """Frames whose swarm exponents leave the finite-variance region: exact (Λ not ≻ 0) and sufficient condition."""
    pso = np.stack([r.eps["pso"] for r in rs])
    n = pso.shape[2]
    infos = np.linalg.inv(np.stack([np.stack([r.covariances[f"local{i + 1}"] for i in range(n)], axis=1) for r in rs]))
    lam = np.sum((2 * pso - 1.0 / n)[..., None, None] * infos, axis=2)
    exact_out = np.linalg.eigvalsh(0.5 * (lam + np.swapaxes(lam, -1, -2)))[..., 0] <= 0
    return {"chf_is_out_exact": int(exact_out.sum()), "chf_is_frames": int(exact_out.size),
            "chf_is_out": int(np.sum(np.min(pso, axis=2) < 1.0 / (2 * n) - 1e-12))}


def ev_equal_kl(settings: dict[str, Any], *, seed: int, runs: int,
                sc: RangeBearingScenario | None = None) -> Proposition:
    """Record chf-equal-kl: frames where the equal-divergence rule has a solution in the simplex (``readings``).

    Parameters
    ----------
    settings : dict
        ``fused``: ``"samples"`` (default: the rule on the importance-sampled estimate of p_ε, where a solution is
        the minimum of Ĵ) or ``"g"`` (the rule on the first-order mixture g, as public codes apply it: a solution
        in every frame, equal to SLSQP's minimum of Ĵ as closely as the primary's solutions are,
        :func:`equal_kl_g_values`).
    seed, runs : int
        Seed and Monte-Carlo runs of the reading.
    sc : RangeBearingScenario, optional
        Another scenario (tests); default the study's.

    Returns
    -------
    Proposition
    """
    s = _settings(settings, {"fused": ("samples", "g")}, {"fused": "samples"})
    _, rs = tracking_study(seed, runs, sc)
    if s["fused"] == "g":
        u = equal_kl_g_values(rs)
        return Proposition(u["chf_klg_frames"] == u["chf_klg_all"] and u["chf_klg_equal"] == u["chf_klg_frames"],
                           f"on the first-order mixture g: a solution in the simplex in {u['chf_klg_frames']} of "
                           f"{u['chf_klg_all']} frames, equal to SLSQP's minimum of Ĵ (to {u['chf_klg_tol']:.1e}, the primary's agreement) in "
                           f"{u['chf_klg_equal']} of them (largest gap {u['chf_klg_gap_max']:.3f}, median "
                           f"{u['chf_klg_gap_median']:.3f})", runs=len(rs))
    v = readings_values(rs)
    return Proposition(v["chf_rd_kl_frames"] == v["chf_rd_frames"],
                       f"a solution in the simplex in {v['chf_rd_kl_frames']} of {v['chf_rd_frames']} frames, equal to "
                       f"SLSQP's minimum there to {v['chf_rd_kl_gap']:.1e}; elsewhere the minimum is on the boundary "
                       f"(an exponent below 10⁻⁶ in {v['chf_rd_boundary']} frames)", runs=len(rs))


def ev_filter_design(settings: dict[str, Any], *, seed: int, runs: int,
                     sc: RangeBearingScenario | None = None) -> Proposition | Conjunction:
    """Record chf-filter-design: collapses of the local filters under each design, and the repaired runs' use.

    Parameters
    ----------
    settings : dict
        ``reading``: ``"guard"`` (no collapse at any frame of the study with the guard, and each repaired filter as
        consistent as the same filter in the untouched runs: a conjunction), ``"plain"``, ``"more"`` (first update
        only), ``"study-plain"`` (every frame of the study, plain filters), ``"runs"`` (the rule first fixed: the
        repaired runs' local NEES and fused MSE against the untouched runs').
    seed, runs : int
    sc : RangeBearingScenario, optional

    Returns
    -------
    Proposition or Conjunction
    """
    s = _settings(settings, {"reading": ("guard", "plain", "more", "study-plain", "runs")}, {})
    sc_ = study_scenario() if sc is None else sc
    g = design(seed, runs, sc).glue()
    plain, rs = tracking_study(seed, runs, sc)
    first = {k: Proposition(g[f"chf_design_{k}_collapsed"] == 0,
                            f"{g[f'chf_design_{k}_collapsed']} of {g['chf_design_runs']} runs below "
                            f"{COLLAPSE_FRACTION * sc_.n_particles:g} effective particles at the first update (worst "
                            f"node {g[f'chf_design_{k}_min']:.1f}; {g[f'chf_design_{k}_cost']:.0f} particle-likelihoods "
                            "per node)", runs=int(g["chf_design_runs"])) for k in ("plain", "more", "guard")}
    if s["reading"] in ("plain", "more"):
        return first[s["reading"]]
    if s["reading"] == "study-plain":
        return Proposition(not bool(any_collapsed(plain, sc_).any()),
                           f"a node collapses in {int(collapsed(plain, sc_.n_particles).sum())} runs, the centralised "
                           f"filter in {int(central_collapsed(plain, sc_.n_central).sum())}; with the guard in "
                           f"{int(any_collapsed(rs, sc_).sum())}", runs=len(plain))
    u = guard_usability(rs, plain, sc_)
    if s["reading"] == "runs":
        return Proposition(
            u["chf_gu_usable"], f"{u['chf_gu_runs']} repaired runs: local NEES at most {u['chf_gu_nees_max']:.2f} "
            f"(95th percentile of the others {u['chf_gu_nees_p95']:.2f}, rank {u['chf_gu_nees_rank']:.0f} %); MSE at most "
            f"{u['chf_gu_mse_max']:.2f} m² ({u['chf_gu_mse_p95']:.2f}, rank {u['chf_gu_mse_rank']:.0f} %); run "
            f"{u['chf_gu_worst_run']} has node {u['chf_gu_worst_node']} at NEES {u['chf_gu_worst_nees']:.2f}, the guard "
            f"repaired {u['chf_gu_worst_repaired']}", runs=len(rs))
    n_col = int(any_collapsed(rs, sc_).sum())
    return Conjunction([
        ("no collapse in the study", Proposition(
            n_col == 0, f"{n_col} of {len(rs)} runs with a filter below its collapse threshold, {COLLAPSE_FRACTION * 100:g} % of "
            f"its particles ({COLLAPSE_FRACTION * sc_.n_particles:g} effective particles for a node, "
            f"{COLLAPSE_FRACTION * sc_.n_central:g} for the centralised filter), at any frame with the guard (first "
            f"update alone: {first['guard'].ours})", runs=len(rs))),
        ("the repaired filters usable", Proposition(
            u["chf_gu_own_usable"], f"{u['chf_gu_own_n']} repaired filters: own mean NEES at most "
            f"{u['chf_gu_own_ratio_max']:.2f} times the same filter's 95th percentile in the untouched runs (a post-hoc "
            "criterion: it replaced, after the fourth review, the rule first fixed, which fails)", runs=len(rs)))])


def ev_peer(settings: dict[str, Any], *, seed: int, runs: int) -> Proposition:
    """Record chf-peer-stonesoup: Stone Soup's fused estimate and innovation covariance (:func:`stonesoup_check`).

    Parameters
    ----------
    settings : dict
        The reading's settings (from the claim file).
    seed, runs : int
        Seed and Monte-Carlo runs of the reading.

    Returns
    -------
    Proposition
    """
    s = _settings(settings, {"half": ("both", "estimate")}, {"half": "both"})
    _, p = stonesoup_check()
    if s["half"] == "estimate":
        return Proposition(bool(p["chf_ss_post"] == 0.0), f"equal to our Chernoff fusion {p['chf_ss_post_text']}")
    return Proposition(bool(p["chf_ss_post"] == 0.0 and p["chf_ss_v_max"] == 0.0),
                       f"Stone Soup {p['chf_ss_version']} at ω = 0.2, 0.5, 0.8: estimate equal {p['chf_ss_post_text']}; "
                       f"innovation covariance = the swapped A/(1−ω) + B/ω {p['chf_ss_max_swap_text']}, "
                       f"{p['chf_ss_v_08']:.2f} (relative) from V at ω = 0.8")


_NET_METHODS = (*NETWORK_METHODS, "nominal", "oracle")


def ev_premise(settings: dict[str, Any], *, seed: int, runs: int,
               scenarios: dict[str, Any] | None = None) -> Comparison:
    """A paired comparison in one designed network (records ``chf-premise-*``).

    Parameters
    ----------
    settings : dict
        ``network`` (a key of :data:`PREMISE_LABELS`), ``a``, ``b`` (keys of
        :data:`~fusion.scenarios.fusion_networks.NETWORK_METHODS`; ``"nominal"``: the share 5 % in every run) and
        ``test``: ``"mse"`` (default; per-run MSE, "a less than b"), ``"losses"`` (the indicator that a is *not*
        more accurate than b, against one half: a sign test) or ``"over"`` (share of overconfident nodes, "a
        greater than b").
    seed, runs : int
        The chapter's root seed and runs per network (:func:`premise_study`).
    scenarios : dict, optional
        Other networks (tests).

    Returns
    -------
    Comparison
    """
    s = _settings(settings, {"network": tuple(PREMISE_LABELS), "a": _NET_METHODS, "b": _NET_METHODS,
                             "test": ("mse", "losses", "over")}, {"test": "mse"})
    st = premise_study(seed, runs, scenarios)[s["network"]]
    a, b = s["a"], s["b"]
    if s["test"] == "over":
        v = {k: np.full(st.runs, 0.05) if k == "nominal" else st.overconfident(k) for k in (a, b)}
        name = {k: "the nominal 5 % of a consistent estimator (a constant: a one-sample test)" if k == "nominal" else NETWORK_METHODS[k] for k in (a, b)}
        return Comparison(v[a], v[b], name[a], name[b], "greater", _POVER, seed=st.seed)
    if "nominal" in (a, b) or "oracle" in (a, b) and s["test"] != "mse":
        raise ValueError("settings: 'nominal' is the yardstick of the 'over' test, 'oracle' a method of the 'mse' test")
    if "oracle" in (a, b):  # the MSE oracle's fixed exponents on the Gaussian summaries (cross-validated)
        mse = {k: oracle_exponents(st)[1] if k == "oracle" else st.mse(k) for k in (a, b)}
        name = {k: "MSE-oracle exponents (cross-validated)" if k == "oracle" else NETWORK_METHODS[k] for k in (a, b)}
        return Comparison(mse[a], mse[b], name[a], name[b], "less", _PMSE, seed=st.seed)
    if s["test"] == "losses":
        lose = (st.mse(a) >= st.mse(b)).astype(float)
        return Comparison(lose, np.full(lose.size, 0.5), f"{NETWORK_METHODS[a]} not more accurate",
                          "a coin (half of the runs)", "less",
                          f"share of runs in which {NETWORK_METHODS[a]} does not have the lower {_PMSE}", seed=st.seed)
    return _pcmp(st, a, b)


def chapter_evidence(seed: int, runs: int = STUDY_RUNS, *, sc: RangeBearingScenario | None = None,
                     scenarios: dict[str, Any] | None = None, network_runs: int | None = None,
                     claims: Any = None) -> dict[str, dict[str, Any]]:
    """The evidence of every record of the chapter, reading by reading, from the claim file's settings.

    Parameters
    ----------
    seed, runs : int
        The chapter's root seed and run count.
    sc : RangeBearingScenario, optional
        The tracking scenario (default :func:`study_scenario`; tests pass small ones).
    scenarios : dict, optional
        The designed networks (tests).
    network_runs : int, optional
        Runs per network, when not ``runs`` (tests run small tracking studies and 100-run networks).
    claims : fusion.book.claims.ClaimsFile, optional
        Default ``book/claims/cn107330468b.yaml``.

    Returns
    -------
    dict
        Record id -> {reading key -> evidence}, for :func:`fusion.book.claims.build_ledger`.
    """
    from fusion.book import claims as cl

    cf = claims if claims is not None else cl.load(Path(__file__).resolve().parents[3] / "book" / "claims"
                                                   / f"{BIBKEY}.yaml")
    out: dict[str, dict[str, Any]] = {}
    for spec in cf.records:
        if spec.chapter != SOURCE_CHAPTER:
            continue
        mod, name = spec.evidence.split(":")
        fn = getattr(importlib.import_module(mod), name)
        params = inspect.signature(fn).parameters
        extra = {k: v for k, v in (("sc", sc), ("scenarios", scenarios)) if k in params}
        n = runs if "scenarios" not in params or network_runs is None else network_runs
        keyed = {r.key: r.settings for r in spec.readings}
        keyed.setdefault("primary", {})
        out[spec.id] = {k: fn(dict(v), seed=seed, runs=n, **extra) for k, v in keyed.items()}
    return out


def claim_values(seed: int, runs: int = STUDY_RUNS, *, sc: RangeBearingScenario | None = None,
                 scenarios: dict[str, Any] | None = None, network_runs: int | None = None) -> dict[str, Any]:
    """The computed values the claim file's texts name (``{name}`` fields), the same as the chapter's glue.

    Parameters
    ----------
    seed, runs : int
    sc : RangeBearingScenario, optional
    scenarios : dict, optional
    network_runs : int, optional
        As in :func:`chapter_evidence`.

    Returns
    -------
    dict
        ``chf_runs``, ``chf_n_any_collapsed``, ``chf_r_toy``, ``chf_design_n0``, the linearised analysis
        (:func:`double_count_values`), the collapse thresholds (:func:`guard_usability`) and the networks' run counts
        (``chf_pr_runs``, ``chf_pr_non_gaussian_runs``).
    """
    sc_ = study_scenario() if sc is None else sc
    plain, rs = tracking_study(seed, runs, sc)
    nets = premise_study(seed, runs if network_runs is None else network_runs, scenarios)
    u = guard_usability(rs, plain, sc_)
    t = toy(seed)
    return ({"chf_runs": len(rs), "chf_r": sc_.n_samples, "chf_w_exact": t.w_exact,
             "chf_w_exact_off": abs(t.w_exact - 0.5), "chf_n_any_collapsed": int(any_collapsed(plain, sc_).sum()),
             "chf_r_toy": t.r, "chf_design_n0": design(seed, runs, sc).n_initial,
             "chf_pr_runs": nets["unequal"].runs, "chf_pr_non_gaussian_runs": nets["non_gaussian"].runs,
             "chf_pr_relay_runs": nets["relay"].runs}
            | {f"chf_pr_{k}_oracle_eps": ", ".join(f"{x:.2f}" for x in oracle_exponents(nets[k])[0])
               for k in ("unequal", "overconfident")}
            | _is_region_counts(rs) | double_count_values(rs, sc_)
            | {k: v for k, v in u.items() if k.startswith("chf_gu_thr")})


#: Docname of the chapter.
SOURCE_CHAPTER = "notebooks/06_chernoff_fusion"


@lru_cache(maxsize=1)
def _referenced_keys() -> frozenset[str]:
    """Glue keys of the chapter that something reads: its markdown, the book's pages, the claim file's texts."""
    import re

    root = Path(__file__).resolve().parents[3]
    nb = json.loads((root / f"{SOURCE_CHAPTER}.ipynb").read_text(encoding="utf-8"))
    text = "".join("".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "markdown")
    keys = set(re.findall(r"\{glue(?::\w+)?\}`([A-Za-z0-9_-]+)", text))
    pages = "".join(p.read_text(encoding="utf-8") for p in sorted((root / "book").glob("*.md")))
    appendix = root / f"{SOURCE_CHAPTER}_appendix.ipynb"  # the chapter's appendix reads its values across documents
    if appendix.is_file():
        pages += "".join("".join(c["source"]) for c in json.loads(appendix.read_text(encoding="utf-8"))["cells"]
                         if c["cell_type"] == "markdown")
    keys |= set(re.findall(r"06_chernoff_fusion\.ipynb::([A-Za-z0-9_-]+)", pages))
    keys |= set(re.findall(r"\{(chf_[A-Za-z0-9_]+)", (root / "book" / "claims" / f"{BIBKEY}.yaml").read_text(encoding="utf-8")))
    return frozenset(keys)


def referenced(values: dict[str, Any]) -> dict[str, Any]:
    """The glue values that something reads (``_referenced_keys``): the chapter glues no value nobody uses.

    Parameters
    ----------
    values : dict
        Glue key -> value.

    Returns
    -------
    dict
        The subset whose keys appear in a ``{glue}`` role of the chapter's markdown, in a ``{glue}`` role of a page of
        ``book/`` or of the chapter's appendix naming this notebook, or as a ``{name}`` field of the claim file.
    """
    keys = _referenced_keys()
    return {k: v for k, v in values.items() if k in keys}


def _word(c: Comparison) -> str:
    """A squared-error comparison in one word, A against B, by the rulebook's region (margin included, R2-R3)."""
    return {"lower": "better", "higher": "worse", "equivalent": "no different beyond the margin",
            "undecided": "not distinguishable"}[c.judgement().region]


def ledger_values(led: Ledger) -> dict[str, Any]:
    """Glue values of the ledger's records, as the rulebook judged them.

    Parameters
    ----------
    led : Ledger
        The chapter's ledger (:func:`fusion.book.claims.build_ledger` on :func:`chapter_evidence`).

    Returns
    -------
    dict
        For every record ``<id>`` (dashes as underscores) ``<id>_record_status`` (its status by the rulebook); for
        each whose evidence is a comparison: ``<id>_d`` (the deciding
        statistic of A − B: the mean paired difference, or the median for heavy-tailed differences), ``<id>_lo`` and
        ``<id>_hi`` (its 95 % interval; 4 decimals), ``<id>_status`` (the rulebook's status of that reading),
        ``<id>_runs`` (int) and ``<id>_margin`` (the practical margin, 4 decimals); for squared-error comparisons
        ``<id>_word`` (``_word``); the same keys ``<id>_alt<j>_*`` for its ``j``-th other reading (0-based, the
        claim file's order); ``<id>_alt_n`` and ``<id>_alt_holds`` (int) for a record with readings: the readings that
        count towards robustness (open choices with enough runs, R4-R5) and those of them under which the claim is
        reproduced; ``chf_source_n``, ``chf_implied_n``, ``chf_book_n`` (int: records by claimant, R8),
        ``chf_contradicted_n`` (int, records contradicted), ``chf_implied_contradicted`` (int, the book's readings
        of the patent's purpose that are contradicted), ``chf_source_contradicted`` (int, claims the patent prints
        that are contradicted), ``chf_source_unchecked`` (int, claims the patent prints that cannot be checked) and
        ``<id>_alt_nd`` (int, counted readings that are not distinguishable).
    """
    v: dict[str, Any] = {}

    def put(prefix: str, ev: Any) -> None:
        if isinstance(ev, Comparison):
            d, lo, hi = ev.interval()
            v.update({f"{prefix}_d": rounded(d), f"{prefix}_lo": rounded(lo), f"{prefix}_hi": rounded(hi),
                      f"{prefix}_status": ev.status(), f"{prefix}_runs": ev.runs, f"{prefix}_margin": rounded(ev.margin)})
            if ev.metric.startswith(_MSE.split(" from ")[0]) or ev.metric == _PMSE:  # squared error: lower is better
                v[f"{prefix}_word"] = _word(ev)
    good = ("reproduced", "reproduced under stated assumptions")
    for c in led.claims:
        p = c.id.replace("-", "_")
        v[f"{p}_record_status"] = c.status
        put(p, c.evidence)
        for j, a in enumerate(c.alternatives):
            put(f"{p}_alt{j}", a.evidence)
        if c.alternatives:
            counted = [a for a in c.alternatives if a.counted(c.runs)[0]]
            v[f"{p}_alt_n"] = len(counted)
            v[f"{p}_alt_holds"] = sum(a.evidence.status() in good for a in counted)
            v[f"{p}_alt_nd"] = sum(a.evidence.status() == "not distinguishable" for a in counted)
    for who in ("source", "implied", "book"):
        v[f"chf_{who}_n"] = sum(c.claimant == who for c in led.claims)
    v["chf_contradicted_n"] = sum(c.status == "contradicted" for c in led.claims)
    v["chf_implied_contradicted"] = sum(c.status == "contradicted" and c.claimant == "implied" for c in led.claims)
    v["chf_source_contradicted"] = sum(c.status == "contradicted" and c.claimant == "source" for c in led.claims)
    v["chf_source_unchecked"] = sum(c.status == "cannot be checked" and c.claimant == "source" for c in led.claims)
    return v


__all__ += ["ledger_values", "tracking_study", "design", "checks_study", "common_study", "toy", "isv_study", "is_replicates", "is_replicate_values",
            "premise_study", "ev_tracking", "ev_pso", "ev_formulas", "ev_common_once", "ev_gaussian_ci", "ev_foa",
            "ev_is", "ev_is_variance", "ev_equal_kl", "ev_filter_design", "ev_peer", "ev_premise", "chapter_evidence",
            "claim_values", "SOURCE_CHAPTER", "referenced", "nested_gaussian_weight", "nested_values", "premise_mixture_scaled",
            "oracle_exponents", "ORACLE_NETWORKS", "message_sizes", "equal_kl_g_values"]


#: Stone Soup's ChernoffUpdater outputs, recorded by ``benchmarks/crosscheck_stonesoup.py`` in a side environment.
STONESOUP_RECORD = Path(__file__).resolve().parents[2] / "data" / "peers" / "stonesoup_chernoff.json"


def stonesoup_check(record: dict[str, Any] | None = None) -> tuple[pd.DataFrame, dict[str, Any]]:
    r"""Stone Soup's ``ChernoffUpdater`` at ω ≠ 0.5 against the Chernoff normaliser and our fusion.

    For a measurement :math:`\mathcal N(a, A)` weighted :math:`\omega` and a prediction :math:`\mathcal N(b, B)`
    weighted :math:`1-\omega`, the normaliser is :math:`Z \propto \exp(-\tfrac12 (a-b)^\top V^{-1}(a-b))` with
    :math:`V = A/\omega + B/(1-\omega)`: the covariance a gate on :math:`a - b` should use. Here :math:`V` is
    obtained independently, as the inverse Hessian in :math:`a` of :math:`-\log Z`
    (:func:`fusion.estimates.chernoff.log_normaliser_two_gaussians`, central differences).

    Parameters
    ----------
    record : dict, optional
        The recorded outputs (default: :data:`STONESOUP_RECORD`).

    Returns
    -------
    table : pandas.DataFrame
        One row per ω: relative difference of Stone Soup's innovation covariance from :math:`V` and from
        the swapped form :math:`A/(1-\omega) + B/\omega`, and of its posterior mean and covariance from
        our Chernoff fusion (:func:`fusion.estimates.chernoff.chernoff_fuse_gaussians`); 3 significant digits.
    values : dict
        ``chf_ss_version``, ``chf_ss_max_swap`` (largest difference from the swapped form),
        ``chf_ss_v_08`` (difference from V at ω = 0.8), ``chf_ss_v_max`` (largest difference from V),
        ``chf_ss_post`` (largest posterior difference), and ``chf_ss_max_swap_text`` / ``chf_ss_post_text``
        (the two in words for the prose); with a ``detection_case`` in the record (a detection whose own
        covariance A2 differs from the measurement model's A, ω = 0.8): ``chf_ss_det_model`` (its innovation
        covariance against the swapped form with the model's A), ``chf_ss_det_v`` (against the normaliser's
        curvature with the detection's own covariance, A2/ω + B/(1−ω)) and ``chf_ss_det_post`` (its posterior
        against our fusion with A2).

    References
    ----------
    * Hurley, M. B. (2002). An information theoretic justification for covariance intersection and its
      generalization. Proc. FUSION 2002, 505-511.
    * Stone Soup (dstl), ``stonesoup.updater.chernoff.ChernoffUpdater``.
    """
    from fusion.estimates.chernoff import chernoff_fuse_gaussians, log_normaliser_two_gaussians

    rec = record if record is not None else json.loads(STONESOUP_RECORD.read_text(encoding="utf-8"))
    a, A = np.array(rec["measurement"]["mean"], float), np.array(rec["measurement"]["covariance"], float)
    b, B = np.array(rec["prediction"]["mean"], float), np.array(rec["prediction"]["covariance"], float)
    rel = lambda x, y: float(np.linalg.norm(np.asarray(x) - np.asarray(y)) / np.linalg.norm(y))  # noqa: E731
    rows = {}
    h = 1e-3
    for r in rec["rows"]:
        w = float(r["omega"])
        d = a.size
        H = np.empty((d, d))
        f = lambda x: -log_normaliser_two_gaussians(x, A, b, B, w)  # noqa: E731
        for i in range(d):
            for j in range(d):
                ei, ej = np.eye(d)[i] * h, np.eye(d)[j] * h
                H[i, j] = (f(a + ei + ej) - f(a + ei - ej) - f(a - ei + ej) + f(a - ei - ej)) / (4 * h * h)
        V = np.linalg.inv((H + H.T) / 2)
        ours = chernoff_fuse_gaussians(np.stack([a, b]), np.stack([A, B]), [w, 1 - w])
        Vs = np.array(r["innovation_covariance"], float)
        rows[w] = {"innovation covariance vs V = A/ω + B/(1−ω)": rel(Vs, V),
                   "vs the swapped A/(1−ω) + B/ω": rel(Vs, A / (1 - w) + B / w),
                   "posterior mean vs our fusion": rel(r["posterior_mean"], ours.x),
                   "posterior covariance vs our fusion": rel(r["posterior_covariance"], ours.P)}
    table = pd.DataFrame.from_dict(rows, orient="index")
    table.index.name = "ω (weight of the measurement)"
    table = table.map(lambda x: float(f"{x:.3g}") if x > 1e-6 else 0.0)
    values = {"chf_ss_version": rec["stonesoup_version"],
              "chf_ss_max_swap": float(table["vs the swapped A/(1−ω) + B/ω"].max()),
              "chf_ss_v_08": float(table.loc[0.8, "innovation covariance vs V = A/ω + B/(1−ω)"]),
              "chf_ss_v_max": float(table["innovation covariance vs V = A/ω + B/(1−ω)"].max()),
              "chf_ss_post": float(table[["posterior mean vs our fusion", "posterior covariance vs our fusion"]].max().max())}
    for key in ("chf_ss_max_swap", "chf_ss_post"):     # prose: "to round-off" for differences below 1e-6
        values[key + "_text"] = ("to round-off (relative difference below 10⁻⁶)" if values[key] == 0.0
                                 else f"up to a relative difference of {values[key]:.3g}")
    case = rec.get("detection_case")
    if case is not None:
        w, A2 = float(case["omega"]), np.array(case["detection_covariance"], float)
        Vd = np.array(case["innovation_covariance"], float)
        ours = chernoff_fuse_gaussians(np.stack([a, b]), np.stack([A2, B]), [w, 1 - w])
        g3 = lambda x: float(f"{x:.3g}") if x > 1e-6 else 0.0  # noqa: E731
        values.update(chf_ss_det_model=g3(rel(Vd, A / (1 - w) + B / w)), chf_ss_det_v=g3(rel(Vd, A2 / w + B / (1 - w))),
                      chf_ss_det_post=g3(max(rel(case["posterior_mean"], ours.x), rel(case["posterior_covariance"], ours.P))))
        for key in ("chf_ss_det_model", "chf_ss_det_post"):  # the same words as above for a difference below 1e-6
            values[key + "_text"] = ("to round-off (relative difference below 10⁻⁶)" if values[key] == 0.0
                                     else f"up to a relative difference of {values[key]:.3g}")
    return table, values
