r"""Chapter 06 (patent CN107330468B, distributed Chernoff fusion): checks, studies, tables, figures, claims.

Everything the chapter's notebook computes beyond calling the package: the exact checks K1-K5 on
random Gaussians, the static two-mixture example, the tables and figures of the tracking study
(:mod:`fusion.scenarios.range_bearing`) and the claims ledger (:func:`claims`). The notebook only
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
import inspect
import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from fusion._validation import FloatArray
from fusion.book.ledger import Alternative, Claim, Comparison, Ledger, Proposition, Unverifiable, fmt
from fusion.book.style import new_figure
from fusion.book.tables import rounded
from fusion.estimates import chernoff as ch
from fusion.estimates import covariance_intersection
from fusion.estimates import mixtures as mx
from fusion.optimise.swarm import particle_swarm
from fusion.scenarios import two_mixtures
from fusion.scenarios.fusion_networks import NETWORK_METHODS, NetworkStudy, premise_scenarios, run_network_study
from fusion.scenarios.range_bearing import (GUARD_STAGES, METHODS, RangeBearingScenario, TrackingRun, min_local_ess,
                                            nees_per_frame, position_sq_errors, posterior_crb, run_tracking,
                                            run_tracking_batch)

__all__ = [
    "BIBKEY",
    "LATE",
    "COLLAPSE_FRACTION",
    "pso_defaults",
    "random_spd",
    "GaussianChecks",
    "gaussian_checks",
    "ToyStudy",
    "toy_study",
    "objective_figure",
    "contour_figure",
    "criteria_example",
    "STUDY_RUNS",
    "STUDY_REASON",
    "study_scenario",
    "IsVarianceStudy",
    "StoppingStudy",
    "stopping_study",
    "is_variance_study",
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
    "premise_claims",
    "common_information_check",
    "readings_values",
    "claims",
]

#: BibTeX key of the source.
BIBKEY = "cn107330468b"
#: Frames 5 to the last (0-based slice; frames 5-10 in the study scenario): the frames over which errors are averaged.
LATE = slice(4, None)
#: A run is *collapsed* when some node's filter keeps fewer effective particles than this fraction of its
#: particles (5 of the study's 1,000; 10 of the default 2,000).
COLLAPSE_FRACTION = 0.005

_MSE = "per-run mean squared position error from frame 5 on (m²)"

#: Monte-Carlo runs of the chapter's study (the house minimum for a comparison).
STUDY_RUNS = 100
#: Why the study runs a smaller scenario than :class:`RangeBearingScenario`'s defaults (see :func:`study_scenario`).
STUDY_REASON = ("the study runs a shortened scenario, not the default one: 10 frames instead of 30 (errors averaged "
                "over frames 5-10, the end of the transient), 1,000 particles per node, R = 1,000 importance samples "
                "and 5,000 centralised particles (half the defaults), prior SD 30 m in position as in the default; "
                "100 runs of the default scenario, even vectorised across runs and nodes, cost more than the whole "
                "chapter's budget of about 60 s (benchmarks/bench_chernoff.py measures them, on one and on two cores)")


def study_scenario() -> RangeBearingScenario:
    """The scenario of the chapter's 100-run study: the defaults with 10 frames and half the particles.

    :data:`STUDY_REASON` says why: the full scenario does not fit the chapter's time budget at
    :data:`STUDY_RUNS` runs. Errors are still averaged from frame 5 (:data:`LATE`).

    Returns
    -------
    RangeBearingScenario
        10 frames, 1,000 particles per node, R = 1,000 importance samples, 5,000 centralised particles,
        with the readings of steps D and F (``readings=True``).
    """
    return dataclasses.replace(RangeBearingScenario(), frames=10, n_particles=1000, n_samples=1000, n_central=5000,
                               readings=True)


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
                "chf_foa_gap": rounded(np.max(self.foa - self.exact)),
                "chf_foa_min_gap": rounded(np.min(self.foa - self.exact)),
                "chf_foa_vertex": rounded(self.foa[0]), "chf_s_a": int(self.gms[0].weights.size),
                "chf_is_err_central": rounded(np.max(err[central])), "chf_is_err_end": rounded(np.max(err))}


def _grid_log_z(gms: tuple[mx.GaussianMixture, ...], e: FloatArray) -> float:
    return float(two_mixtures.grid_log_normaliser(list(gms), e).log_z[0])


def _foa_log_z(gms: tuple[mx.GaussianMixture, ...], e: FloatArray) -> float:
    return float(ch.foa_fusion(list(gms), e).log_z_foa)


def toy_study(rng: np.random.Generator, r: int = 20_000) -> ToyStudy:
    """Exact, first-order and importance-sampled log normaliser of the two toy mixtures.

    Parameters
    ----------
    rng : numpy.random.Generator
        Draws the ``r`` importance samples from the first-order mixture at ω = 0.5 (eq. ``eq-chf-is``).
    r : int

    Returns
    -------
    ToyStudy
    """
    toy = two_mixtures.toy_mixtures()
    gms = (toy.a, toy.b)
    omegas = np.linspace(0.0, 1.0, 101)
    E = np.column_stack([omegas, 1 - omegas])
    exact = two_mixtures.grid_log_normaliser(list(gms), E).log_z
    foa = np.array([ch.foa_fusion(list(gms), e).log_z_foa for e in E])
    g05 = ch.foa_fusion(list(gms), [0.5, 0.5]).mixture
    xs = mx.gm_sample(g05, rng, r)
    L, lg = ch.log_densities(list(gms), xs), mx.gm_logpdf(g05, xs)
    J = ch.is_objective(L, lg, E)
    w_exact = ch.minimise_on_simplex(lambda e: _grid_log_z(gms, e), 2).x[0]
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
@dataclass(frozen=True)
class IsVarianceStudy:
    """Bias of the importance-sampled objective and the finite-variance region, on the Gaussian pair of
    :func:`criteria_example` with the proposal at ω⁽⁰⁾ = 1/2.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per ω: ``rho`` (closed form :func:`fusion.estimates.chernoff.is_second_moment`,
        inf outside the region), ``rho (sampled)``, ``bias predicted`` (-(ρ-1)/(2R), nats; NaN outside),
        ``bias sampled`` and ``bias se`` (mean and standard error of Ĵ - log Z over the replicates).
    lo, hi : float
        The finite-variance interval of ω (bisection on the smallest eigenvalue of Λ(ω)).
    R, replicates : int
        Samples per estimate and replicates per ω.
    ok : bool
        In the region with ρ <= 2: sampled bias within 3 standard errors (+ 0.002 nats) of the
        prediction and sampled ρ within 5 % of the closed form.
    """

    table: pd.DataFrame
    lo: float
    hi: float
    R: int
    replicates: int
    ok: bool

    def glue(self) -> dict[str, Any]:
        """Glue values ``chf_isv_*``: the interval, R, replicates and the bias at ω = 0.2 and 0.8."""
        t = self.table
        return {"chf_isv_lo": rounded(self.lo), "chf_isv_hi": rounded(self.hi), "chf_isv_r": self.R,
                "chf_isv_reps": self.replicates,
                "chf_isv_bias_02": rounded(float(t.loc[0.2, "bias sampled"])),
                "chf_isv_pred_02": rounded(float(t.loc[0.2, "bias predicted"])),
                "chf_isv_rho_08": rounded(float(t.loc[0.8, "rho"]))}


def is_variance_study(rng: np.random.Generator, R: int = 100, replicates: int = 2000) -> IsVarianceStudy:
    """Check the bias of Ĵ and the finite-variance region of the IS weights numerically (Gaussian pair).

    Parameters
    ----------
    rng : numpy.random.Generator
        Draws the samples from the proposal.
    R : int
        Samples per estimate of Ĵ.
    replicates : int
        Estimates per ω.

    Returns
    -------
    IsVarianceStudy
    """
    a, A = np.array([0.0, 0.0]), np.diag([4.0, 1.0])
    b, B = np.array([2.0, 1.0]), np.array([[1.0, 0.5], [0.5, 3.0]])
    means, covs, e0 = [a, b], [A, B], np.array([0.5, 0.5])
    g = ch.chernoff_fuse_gaussians(means, covs, e0)
    Ai, Bi = np.linalg.inv(A), np.linalg.inv(B)

    def min_eig(w: float) -> float:
        return float(np.min(np.linalg.eigvalsh((2 * w - e0[0]) * Ai + (2 * (1 - w) - e0[1]) * Bi)))

    def edge(inside: float, outside: float) -> float:
        for _ in range(60):
            mid = 0.5 * (inside + outside)
            inside, outside = (mid, outside) if min_eig(mid) > 0 else (inside, mid)
        return inside
    lo = edge(0.5, 0.0) if min_eig(0.0) <= 0 else 0.0
    hi = edge(0.5, 1.0) if min_eig(1.0) <= 0 else 1.0
    x = g.x + rng.standard_normal((replicates, R, 2)) @ np.linalg.cholesky(g.P).T
    log_g = mx.gaussian_logpdf(x.reshape(-1, 2), g.x, g.P).reshape(replicates, R)
    rows = {}
    for w in (0.0, 0.1, 0.2, 0.3, 0.5, 0.7, 0.8, 0.9, 1.0):
        t = ch.chernoff_fuse_gaussians(means, covs, [w, 1 - w])
        lw = mx.gaussian_logpdf(x.reshape(-1, 2), t.x, t.P).reshape(replicates, R) - log_g
        j = mx.logsumexp(lw, axis=1) - np.log(R)  # Ĵ - log Z: the target is normalised
        rho = ch.is_second_moment(means, covs, [w, 1 - w], e0)
        rows[w] = {"rho": rho, "rho (sampled)": float(np.mean(np.exp(2 * lw))),
                   "bias predicted": -(rho - 1) / (2 * R) if np.isfinite(rho) else np.nan, "bias sampled": float(j.mean()),
                   "bias se": float(j.std(ddof=1) / np.sqrt(replicates))}
    table = pd.DataFrame.from_dict(rows, orient="index")
    table.index.name = "ω"
    good = table[(table["rho"] <= 2.0)]
    ok = bool(np.all(np.abs(good["bias sampled"] - good["bias predicted"]) <= 3 * good["bias se"] + 0.002)
              and np.all(np.abs(good["rho (sampled)"] / good["rho"] - 1) <= 0.05)
              and np.all(np.isinf(table.loc[[w for w in table.index if w < lo or w > hi], "rho"])))
    return IsVarianceStudy(table=table.round(4), lo=lo, hi=hi, R=R, replicates=replicates, ok=ok)


# --------------------------------------------------------------------------- the swarm's stopping rule
@dataclass(frozen=True)
class StoppingStudy:
    """The swarm under the two readings of G6 on the same importance-sampling problems.

    Attributes
    ----------
    gap : dict {"stagnation", "positions"} -> ndarray
        Objective found minus SLSQP's minimum on the same samples (nats), per problem.
    evaluations : dict {"stagnation", "positions"} -> ndarray
        Objective evaluations per problem.
    se : ndarray
        Sampling standard error of Ĵ at the optimum per problem (delta method, sqrt(1/ESS - 1/R)).
    limit : int
        Evaluations when the swarm runs to its iteration limit.
    R : int
        Samples per problem.
    xtol : float
        Position tolerance of the patent's rule.
    """

    gap: dict[str, FloatArray]
    evaluations: dict[str, FloatArray]
    se: FloatArray
    limit: int
    R: int = 0
    xtol: float = 0.0

    def within(self, rule: str) -> FloatArray:
        """Problems in which ``rule`` lands closer to SLSQP's minimum than Ĵ's sampling error."""
        return self.gap[rule] < self.se

    def glue(self) -> dict[str, Any]:
        """Glue values ``chf_stop_*``: mean evaluations, largest gap and share run to the limit, per rule."""
        v: dict[str, Any] = {"chf_stop_problems": int(self.se.size), "chf_stop_limit": self.limit,
                             "chf_stop_r": self.R, "chf_stop_xtol": self.xtol}
        for rule, key in (("stagnation", "stag"), ("positions", "pos")):
            v[f"chf_stop_evals_{key}"] = rounded(float(self.evaluations[rule].mean()), 0)
            v[f"chf_stop_gap_{key}"] = float(f"{np.max(self.gap[rule]):.2g}")
            v[f"chf_stop_atlimit_{key}"] = rounded(float(np.mean(self.evaluations[rule] >= self.limit)), 2)
            v[f"chf_stop_within_{key}"] = int(self.within(rule).sum())
        return v


def stopping_study(rng: np.random.Generator, problems: int = 100, R: int = 200, xtol: float = 1e-3) -> StoppingStudy:
    """Run the swarm with both G6 rules (same initial swarm) and SLSQP on the toy's importance-sampling problems.

    Each problem draws R samples from the first-order mixture of the three toy mixtures (A, B, A)
    at uniform exponents, as step E does; the swarm's random stream of problem ``j`` is the same for
    both rules.

    Parameters
    ----------
    rng : numpy.random.Generator
        Draws the samples and seeds the swarms.
    problems : int
        Number of problems.
    R : int
        Samples per problem.
    xtol : float
        Position tolerance of the patent's rule.

    Returns
    -------
    StoppingStudy
    """
    toy = two_mixtures.toy_mixtures()
    gms = [toy.a, toy.b, toy.a]
    g = ch.foa_fusion(gms, np.full(3, 1 / 3)).mixture
    p = inspect.signature(particle_swarm).parameters
    limit = int(p["n_particles"].default * (p["iterations"].default + 1))
    gap: dict[str, list[float]] = {"stagnation": [], "positions": []}
    evals: dict[str, list[float]] = {"stagnation": [], "positions": []}
    se = []
    for seed in rng.integers(2**32, size=problems):
        xs = mx.gm_sample(g, rng, R)
        L, lg = ch.log_densities(gms, xs), mx.gm_logpdf(g, xs)
        ref = ch.simplex_minimum(L, lg)
        w = ch.fused_weights(L, lg, ref.x)
        se.append(float(np.sqrt(max(np.sum(w**2) - 1.0 / R, 0.0))))
        for rule in gap:
            o = particle_swarm(lambda E: -ch.is_objective(L, lg, E), 3, np.random.default_rng(int(seed)), stop=rule,
                               xtol=xtol)
            gap[rule].append(-o.fun - ref.fun)
            evals[rule].append(o.n_evaluations)
    return StoppingStudy(gap={k: np.array(v) for k, v in gap.items()},
                         evaluations={k: np.array(v, dtype=float) for k, v in evals.items()}, se=np.array(se), limit=limit,
                         R=R, xtol=xtol)


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
            ("local filters", f"bootstrap PF, {sc.n_particles} particles, systematic resampling + regularisation"),
            ("mixtures (C)", f"weighted EM, {sc.n_components} full-covariance components, warm start, "
                             f"≤ {sc.em_iterations} iterations"),
            ("fusion (D-I)", f"ε⁽⁰⁾ uniform, R = {sc.n_samples} samples, PSO 20 × 50"),
            ("centralised PF", f"{sc.n_central} particles, all measurements"),
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


def method_table(runs: list[TrackingRun], crb_pos: FloatArray) -> pd.DataFrame:
    """Table of every method: RMSE over frames 5-K (m) and mean NEES (4-D), with the CRB as floor (2 decimals).

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs (every method of :data:`~fusion.scenarios.range_bearing.METHODS` recorded).
    crb_pos : ndarray, shape (K,)
        Root of the posterior CRB of the position per frame (m), from :func:`crb_position`.

    Returns
    -------
    DataFrame
        One row per method (indexed by its label in ``METHODS``) plus ``"posterior CRB (floor)"``;
        columns ``"RMSE from frame 5 (m)"`` (root of the squared position error averaged over runs
        and frames 5-K; for the CRB the root mean square of ``crb_pos`` over the same frames) and
        ``"mean NEES (4-D)"`` (NaN for the mean of local means, which has no covariance, and for the
        CRB row); rounded to 2 decimals.

    Raises
    ------
    ValueError
        ``runs`` is empty (nothing to stack).
    """
    rows = {}
    for key, label in METHODS.items():
        if key not in runs[0].estimates:  # a reading not computed (RangeBearingScenario.readings)
            continue
        rows[label] = {
            "RMSE from frame 5 (m)": np.sqrt(position_sq_errors(runs, key)[:, LATE].mean()),
            "mean NEES (4-D)": nees_per_frame(runs, key)[:, LATE].mean() if key != "mean_of_means" else np.nan,
        }
    rows["posterior CRB (floor)"] = {"RMSE from frame 5 (m)": np.sqrt(np.mean(crb_pos[LATE] ** 2)),
                                     "mean NEES (4-D)": np.nan}
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
        ``chf_ratio_local`` (RMSE of local PF 1 / RMSE of Chernoff-PSO); ``chf_pct_central`` (how
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
    v["chf_pct_central"] = rounded(100 * (t("chernoff_pso") / t("centralised") - 1))
    for k in ("naive_product", "chernoff_pso", "ci_gaussian", "centralised", "local1", "foa_uniform"):
        v[f"chf_nees_{k}"] = rounded(t(k, "mean NEES (4-D)"))
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


def per_run_nees(runs: list[TrackingRun], key: str) -> FloatArray:
    """Mean NEES (4-D) of one method over frames 5-K, per run.

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs.
    key : str
        A key of :data:`~fusion.scenarios.range_bearing.METHODS` other than ``"mean_of_means"``
        (which has no covariance).

    Returns
    -------
    ndarray, shape (runs,)
        Normalised estimation error squared of the 4-D state averaged over frames 5-K
        (:data:`LATE`), dimensionless; 4 on average for a consistent estimator.

    Raises
    ------
    ValueError
        ``key`` is not a method with a covariance, or ``runs`` is empty.
    """
    return np.round(nees_per_frame(runs, key)[:, LATE].mean(axis=1), 4)  # see per_run_mse


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


def typical_run(runs: list[TrackingRun], n_particles: int) -> int:
    """Index of the first run in which no node's filter collapses (the run the chapter's figures show).

    Parameters
    ----------
    runs : list of TrackingRun
    n_particles : int
        Particles per node (sets the collapse threshold of :func:`collapsed`).

    Returns
    -------
    int
        0-based index; 0 when every run collapses.
    """
    bad = collapsed(runs, n_particles)
    return int(np.argmin(bad)) if not np.all(bad) else 0


def collapse_values(runs: list[TrackingRun], sc: RangeBearingScenario) -> dict[str, Any]:
    """What the collapsed runs do to the study: RMSE gap to the centralised filter and NEES, with and without them.

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs.
    sc : RangeBearingScenario
        The scenario; its ``n_particles`` sets the collapse threshold (:func:`collapsed`).

    Returns
    -------
    dict
        Glue values: ``chf_n_collapsed`` and ``chf_runs_kept`` (int counts of runs);
        ``chf_collapse_run`` (1-based, first collapsed run, or 0 when none collapses);
        ``chf_collapse_ess`` (its smallest ESS, effective particles, 1 decimal; 0.0 when none);
        ``chf_collapse_frame`` and ``chf_collapse_node`` (1-based, where that ESS occurs; 0 when
        none); ``chf_rmse_chernoff_pso_kept`` and ``chf_rmse_centralised_kept`` (position RMSE,
        frames 5-K, runs kept, m); ``chf_pct_central_kept`` (how much larger, in %, Chernoff-PSO's
        RMSE is than the centralised filter's, runs kept); ``chf_nees_naive_kept`` and
        ``chf_nees_pso_kept`` (mean 4-D NEES, frames 5-K, runs kept); ``chf_ess_next`` (smallest
        ESS of any node in the runs kept, effective particles, 0 decimals). Other values 4 decimals.

    Raises
    ------
    ValueError
        No run is kept (``runs`` empty, or every run collapsed).
    """
    bad = collapsed(runs, sc.n_particles)
    keep = [r for r, b in zip(runs, bad) if not b]
    v: dict[str, Any] = {"chf_n_collapsed": int(bad.sum()), "chf_runs_kept": len(keep),
                         "chf_ess_next": rounded(float(np.min(min_local_ess(keep))), 0)}
    if bad.any():
        j = int(np.flatnonzero(bad)[0])
        ess = runs[j].ess["local"]
        k, i = np.unravel_index(int(np.argmin(ess)), ess.shape)
        v.update(chf_collapse_run=j + 1, chf_collapse_ess=rounded(float(ess[k, i]), 1),
                 chf_collapse_frame=int(k) + 1, chf_collapse_node=int(i) + 1)
    else:
        v.update(chf_collapse_run=0, chf_collapse_ess=0.0, chf_collapse_frame=0, chf_collapse_node=0)

    def rmse(rs: list[TrackingRun], key: str) -> float:
        return float(np.sqrt(position_sq_errors(rs, key)[:, LATE].mean()))
    v["chf_rmse_chernoff_pso_kept"] = rounded(rmse(keep, "chernoff_pso"))
    v["chf_rmse_centralised_kept"] = rounded(rmse(keep, "centralised"))
    v["chf_pct_central_kept"] = rounded(100 * (rmse(keep, "chernoff_pso") / rmse(keep, "centralised") - 1))
    v["chf_nees_naive_kept"] = rounded(float(nees_per_frame(keep, "naive_product")[:, LATE].mean()))
    v["chf_nees_pso_kept"] = rounded(float(nees_per_frame(keep, "chernoff_pso")[:, LATE].mean()))
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
    values : dict
        ``chf_gap_obj`` and ``chf_gap_eps`` (largest absolute difference PSO - SLSQP in objective and exponents over all
        frames and runs), ``chf_evals_pso``/``chf_evals_slsqp`` (mean evaluations per frame),
        ``chf_better_pso`` (fraction of frames where the swarm's value is below SLSQP's by > 1e-9).
    """
    r0, k = runs[show], frame - 1
    hist = -r0.swarm_history[k]
    fig, ax = new_figure(figsize=(7.0, 3.2))
    ax.plot(np.arange(hist.size), hist, color="#0072B2", marker=".", label="PSO: best Ĵ so far")
    ax.axhline(r0.objective["slsqp"][k], color="black", ls="--", label="SLSQP on the same samples")
    ax.set(xlabel="swarm iteration", ylabel="Ĵ(ε)")
    ax.legend()
    plt.close(fig)
    obj = {m: np.stack([r.objective[m] for r in runs]) for m in ("pso", "slsqp")}
    eps = {m: np.stack([r.eps[m] for r in runs]) for m in ("pso", "slsqp")}
    values = {
        "chf_k_show": frame,
        "chf_gap_obj": rounded(float(np.max(np.abs(obj["pso"] - obj["slsqp"])))),
        "chf_gap_eps": rounded(float(np.max(np.abs(eps["pso"] - eps["slsqp"])))),
        "chf_evals_pso": rounded(float(np.mean([r.evaluations["pso"] for r in runs]))),
        "chf_evals_slsqp": rounded(float(np.mean([r.evaluations["slsqp"] for r in runs]))),
        "chf_better_pso": rounded(float(np.mean(obj["pso"] < obj["slsqp"] - 1e-9))),
    }
    return fig, values


def benchmark_cost(path: Path) -> tuple[pd.DataFrame, dict[str, Any]]:
    """Cost per frame by stage from ``benchmarks/results/chernoff.json``, and the study's measured cost.

    Parameters
    ----------
    path : Path
        The benchmark result file.

    Returns
    -------
    table : DataFrame
        ms per frame, indexed by stage.
    values : dict
        ``chf_pso_ratio`` (time of the swarm / time of SLSQP on the same samples), ``chf_bench_runs``,
        ``chf_em_share`` (EM's share of the patent's own stages B-I), ``chf_bench_date``,
        and ``chf_bench_text``: the seconds for the batched runs of the default scenario (one process and
        two worker processes) and the batched runner's time relative to the per-run loop, in words for the
        prose ("not measured yet" when the file predates the batched runner).
    """
    bench = json.loads(Path(path).read_text(encoding="utf-8"))
    stages = [m for m in bench["measurements"] if "stage" in m]
    cost = pd.DataFrame({"stage": [m["what"].split(", ", 1)[1].rsplit(":", 1)[0] for m in stages],
                         "ms per frame": [round(1000 * m["value"], 1) for m in stages]}).set_index("stage")
    ratio = next(m["value"] for m in bench["measurements"] if m["what"].endswith("time(PSO) / time(SLSQP)"))
    patent = [i for i in cost.index if i.split(":")[0] in ("B", "C", "D", "E", "F", "G", "H-I")]
    share = cost.loc["C: weighted EM (3 nodes)", "ms per frame"] / cost.loc[patent, "ms per frame"].sum()
    date = str(bench.get("date", bench.get("timestamp", "undated")))[:10]

    def value(end: str) -> float:
        return float(next((m["value"] for m in bench["measurements"] if m["what"].endswith(end)), float("nan")))
    study = value("runs, run_tracking_batch (measured)")
    study2 = value("runs, run_tracking_batch, 2 worker processes (measured)")
    batch_loop = 1.0 / value("default scenario: time(loop) / time(batch)")
    if np.isfinite(study) and np.isfinite(batch_loop) and np.isfinite(study2):
        text = (f"{study:.0f} s for {int(bench['runs'])} runs on one core, {study2:.0f} s on two, the batched "
                f"runner taking {batch_loop:.2f} times the per-run loop's time (benchmark of {date}, load average "
                f"{bench.get('load_average', ['?'])[0]})")
    else:
        text = "not measured yet (run benchmarks/bench_chernoff.py on an idle machine)"
    return cost, {"chf_pso_ratio": rounded(ratio), "chf_bench_runs": int(bench["runs"]),
                  "chf_em_share": rounded(float(share)), "chf_bench_date": date, "chf_bench_text": text}


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
        ``chf_node_spread`` / ``_mean`` (m, frames 5-K, run 1), ``chf_ess1_note`` (mean ESS after
        frame 1 with P0^½ = diag(100, 10, 100, 10)), ``chf_ess1_ours``, ``chf_gm_gain`` (nats per
        particle of 3 components over one Gaussian), ``chf_mf_used``, ``chf_prev_eps_diff``.
    """
    node = runs[0].node_estimates
    if node is None:
        raise ValueError("runs[0] must have node_estimates (run_tracking(..., all_nodes=True))")
    spread = np.max(np.linalg.norm(node[:, :, [0, 2]] - node[:, :1, [0, 2]], axis=2), axis=1)
    wide = dataclasses.replace(sc, p0_std=(100.0, 10.0, 100.0, 10.0), frames=1)
    wide = dataclasses.replace(wide, variants=False, readings=False)  # only the local filters' first update is read
    ess_note = np.mean([r.ess["local"][0] for r in run_tracking_batch(wide, np.random.SeedSequence(seed).spawn(len(runs)))])
    values = {
        "chf_node_spread": spread[LATE].max(),
        "chf_node_spread_mean": spread[LATE].mean(),
        "chf_ess1_note": ess_note,
        "chf_ess1_ours": np.mean([r.ess["local"][0] for r in runs]),
        "chf_gm_gain": np.mean([r.gm_loglik - r.gm1_loglik for r in runs]),
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
        value over the same frames, m²), ``chf_crb_inside`` ("inside" or "outside" the interval);
        ``chf_naive_pso_d``/``_lo``/``_hi``/``_word`` (naive product minus the patent's method, per-run
        MSE, m²); ``chf_cf_eps_band`` (mean 10-90 % band over runs of the closed-form Chernoff exponents,
        per node and frame) and ``chf_cf_eps_max`` (their largest value); ``chf_is_out`` / ``chf_is_frames``
        (tracking frames whose optimised exponents leave the region min ε_i ≥ ε⁽⁰⁾_i / 2 = 1/(2N), where
        the importance weights' variance is guaranteed finite, and all frames). 4 decimals.

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
    return {
        "chf_central_mse": rounded(float(central.mean())), "chf_central_mse_lo": rounded(float(ci.low)),
        "chf_central_mse_hi": rounded(float(ci.high)), "chf_crb_mse": rounded(crb),
        "chf_crb_inside": "inside" if ci.low <= crb <= ci.high else ("above" if crb > ci.high else "below"),
        "chf_naive_pso_d": rounded(d), "chf_naive_pso_lo": rounded(lo), "chf_naive_pso_hi": rounded(hi),
        "chf_naive_pso_word": "better" if hi < 0 else "worse" if lo > 0 else "not distinguishable",
        "chf_cf_eps_band": rounded(float(np.mean(np.percentile(cf, 90, axis=0) - np.percentile(cf, 10, axis=0)))),
        "chf_cf_eps_max": rounded(float(cf.max())),
        "chf_is_out": int(out.sum()), "chf_is_frames": int(out.size),
    }


# --------------------------------------------------------------------------- where the premise can show
#: The networks' labels in the chapter's table and figure, in order.
PREMISE_LABELS: dict[str, str] = {"unequal": "unequal sensors", "non_gaussian": "range-only and bearings-only",
                                  "feedback": "feedback, 3 frames", "chain": "chain, 2 rounds"}
_PMSE = "per-run squared position error averaged over the nodes (m²)"
_POVER = "per-run share of nodes whose NEES (2-D) exceeds χ²₂'s 95 % point, 5.99"


def premise_studies(seed: int, runs: int = STUDY_RUNS, scenarios: dict[str, Any] | None = None
                    ) -> dict[str, NetworkStudy]:
    """The four designed networks (:func:`fusion.scenarios.fusion_networks.premise_scenarios`), ``runs`` runs each.

    Parameters
    ----------
    seed : int
        Root seed; network ``j`` (in the order of :data:`PREMISE_LABELS`) uses ``seed + j``.
    runs : int
        Monte-Carlo runs per network.
    scenarios : dict, optional
        The networks by key of :data:`PREMISE_LABELS` (default: the designed ones; tests pass smaller ones).

    Returns
    -------
    dict
        Network key -> :class:`~fusion.scenarios.fusion_networks.NetworkStudy`.
    """
    scs = premise_scenarios() if scenarios is None else scenarios
    return {k: run_network_study(scs[k], seed + j, runs) for j, k in enumerate(PREMISE_LABELS)}


def _pcmp(st: NetworkStudy, a: str, b: str) -> Comparison:
    return Comparison(st.mse(a), st.mse(b), NETWORK_METHODS[a], NETWORK_METHODS[b], "less", _PMSE, seed=st.seed)


def _over(st: NetworkStudy, key: str, claim: str) -> Comparison:
    v = st.overconfident(key)
    return Comparison(v, np.full(v.size, 0.05), NETWORK_METHODS[key], "a consistent estimator (5 %)", claim,  # type: ignore[arg-type]
                      _POVER, seed=st.seed)


def _word(c: Comparison) -> str:
    _, lo, hi = c.interval()
    return "better" if hi < 0 else "worse" if lo > 0 else "not distinguishable"


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
        cols[PREMISE_LABELS[key]] = col
    return pd.DataFrame(cols)


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
        exponents, m²) and ``chf_pr_<k>_mix_d``/``_lo``/``_hi``/``_word`` (mixture fusion − CI of Gaussians),
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
        for tag, (a, b) in (("eps", ("chernoff_pso", "chernoff_uniform")), ("mix", ("chernoff_pso", "ci_gaussian"))):
            c = _pcmp(st, a, b)
            d, lo, hi = c.interval()
            v.update({f"chf_pr_{key}_{tag}_d": rounded(d), f"chf_pr_{key}_{tag}_lo": rounded(lo),
                      f"chf_pr_{key}_{tag}_hi": rounded(hi), f"chf_pr_{key}_{tag}_word": _word(c)})
        v[f"chf_pr_{key}_over_naive"] = rounded(float(st.overconfident("naive_product").mean()))
        v[f"chf_pr_{key}_over_pso"] = rounded(float(st.overconfident("chernoff_pso").mean()))
        v[f"chf_pr_{key}_degenerate"] = int(st.degenerate("chernoff_pso").sum())
    any_st = next(iter(studies.values()))
    v.update(chf_pr_runs=any_st.runs, chf_pr_particles=any_st.scenario.n_particles,
             chf_pr_samples=any_st.scenario.n_samples)
    return v


def premise_claims(studies: dict[str, NetworkStudy]) -> list[Claim]:
    """Records ``chf-premise-eps``, ``chf-premise-mixture`` and ``chf-premise-double-count`` of the networks.

    Parameters
    ----------
    studies : dict
        :func:`premise_studies` (every network).

    Returns
    -------
    list of Claim
        Each with one network as its primary evidence and the others as alternatives ("network").
    """
    net = "designed static networks (fusion.scenarios.fusion_networks), 100 runs each, exact posterior on a grid"

    def alts(keys: tuple[str, ...], make: Any) -> tuple[Alternative, ...]:
        return tuple(Alternative("network", PREMISE_LABELS[k], make(studies[k])) for k in keys)
    return [
        Claim("chf-premise-eps", BIBKEY, "steps F-G (implied by the design; no accuracy claim is printed)",
              "Where the nodes differ, optimising the exponents by the Chernoff criterion gives a more accurate "
              "fused estimate than uniform exponents.",
              "qualitative", _pcmp(studies["unequal"], "chernoff_pso", "chernoff_uniform"), link="chf-premise",
              assumptions=(net, "unequal range-bearing sensors (8, 20, 50 m; 1, 2, 5°), one frame, full connectivity"),
              alternatives=alts(("non_gaussian", "feedback", "chain"),
                                lambda st: _pcmp(st, "chernoff_pso", "chernoff_uniform")),
              critiques=("chf-crit-gain",)),
        Claim("chf-premise-mixture", BIBKEY, "steps B-I (implied by the design; no accuracy claim is printed)",
              "Where the local posteriors are non-Gaussian, fusing Gaussian-mixture summaries is more accurate "
              "than covariance intersection of moment-matched Gaussians.",
              "qualitative", _pcmp(studies["non_gaussian"], "chernoff_pso", "ci_gaussian"), link="chf-premise",
              assumptions=(net, "two bearings-only nodes (1°) and a range-only node (4 m) 200-300 m from the target: "
                           "arcs and wedges", "3 components per node, weighted EM"),
              alternatives=alts(("chain", "unequal", "feedback"), lambda st: _pcmp(st, "chernoff_pso", "ci_gaussian")),
              critiques=("chf-crit-gmfit",)),
        Claim("chf-premise-double-count", BIBKEY, "steps D-H (Chernoff fusion vs product; the chapter's reading)",
              "With feedback, the naive product of the posteriors becomes overconfident (the fed-back information "
              "counted once per node and frame); Chernoff fusion does not.",
              "qualitative", _over(studies["feedback"], "naive_product", "greater"), link="chf-premise",
              bound="5 % of node estimates beyond χ²₂'s 95 % point for a consistent estimator",
              assumptions=(net, "three range-bearing nodes, three frames, the fused density fed back as every node's prior"),
              alternatives=(Alternative("network", PREMISE_LABELS["chain"], _over(studies["chain"], "naive_product",
                                                                                  "greater")),
                            Alternative("which half of the claim", "the patent's method is not overconfident "
                                        "(feedback network)", _over(studies["feedback"], "chernoff_pso", "less")),
                            Alternative("which half of the claim", "CI of moment-matched Gaussians is not "
                                        "overconfident (feedback network)", _over(studies["feedback"], "ci_gaussian",
                                                                                  "less"))),
              critiques=("chf-crit-gain",)),
    ]


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


# --------------------------------------------------------------------------- claims ledger
def _reason(runs: int) -> str:
    if runs >= STUDY_RUNS:
        return STUDY_REASON
    return f"{runs} runs (the runs kept of {STUDY_RUNS}); " + STUDY_REASON


def _mse_comparison(runs: list[TrackingRun], a: str, b: str, claim: str, seed: int) -> Comparison:
    return Comparison(per_run_mse(runs, a), per_run_mse(runs, b), METHODS[a], METHODS[b], claim,  # type: ignore[arg-type]
                      _MSE, seed=seed, reason=_reason(len(runs)))


_NEES = "per-run mean NEES (4-D) from frame 5 on"
#: NEES of a consistent estimator of a 4-D state (its expected value).
NEES_CONSISTENT = 4.0


def _nees_vs_consistent(runs: list[TrackingRun], key: str, claim: str, seed: int) -> Comparison:
    """A method's per-run mean NEES against the value 4 of a consistent estimator (one-sample t interval)."""
    nees = per_run_nees(runs, key)
    return Comparison(nees, np.full(nees.size, NEES_CONSISTENT), METHODS[key], "a consistent estimator (NEES 4)",
                      claim, _NEES, seed=seed, reason=_reason(len(runs)))  # type: ignore[arg-type]


def _without_collapse(runs: list[TrackingRun], bad: np.ndarray, a: str, b: str, claim: str, seed: int,
                      metric: str = "mse") -> Alternative:
    keep = [r for r, x in zip(runs, bad) if not x]
    if metric == "mse":
        ev = _mse_comparison(keep, a, b, claim, seed)
    else:
        ev = Comparison(per_run_nees(keep, a), per_run_nees(keep, b), METHODS[a], METHODS[b], claim,  # type: ignore[arg-type]
                        "per-run mean NEES (4-D) from frame 5 on", seed=seed, reason=_reason(len(keep)))
    return Alternative("runs with a collapsed node filter",
                       f"excluded ({int(bad.sum())} of {len(runs)} runs: a node keeps < "
                       f"{COLLAPSE_FRACTION * 100:g} % effective particles)", ev)


def guarded_runs(runs: list[TrackingRun], sc: RangeBearingScenario, seed: int) -> list[TrackingRun]:
    """The study's runs with the collapse guard of the local filters: collapsed runs redone, others reused.

    The guard (``RangeBearingScenario.guard`` = :data:`COLLAPSE_FRACTION`, progressive correction
    of an update whose effective sample size falls below it) draws nothing in a run where no node
    falls below the threshold, so such a run is identical with and without it (tested); only the
    collapsed runs (:func:`collapsed`) are run again, from their own seeds.

    Parameters
    ----------
    runs : list of TrackingRun
        The study, ``monte_carlo(sc, seed, len(runs))``.
    sc : RangeBearingScenario
        Its scenario (without guard).
    seed : int
        Its root seed.

    Returns
    -------
    list of TrackingRun
        What ``monte_carlo(replace(sc, guard=COLLAPSE_FRACTION), seed, len(runs))`` gives, except that
        the redone runs carry no ``node_estimates``.
    """
    _check_study(runs)
    bad = collapsed(runs, sc.n_particles)
    gsc = dataclasses.replace(sc, guard=COLLAPSE_FRACTION)
    seeds = np.random.SeedSequence(seed).spawn(len(runs))
    redo = run_tracking_batch(gsc, [seeds[j] for j in np.flatnonzero(bad)]) if bad.any() else []
    out, it = [], iter(redo)
    for r, b in zip(runs, bad):
        out.append(next(it) if b else r)
    return out


def _guarded_alt(guarded: list[TrackingRun] | None, a: str, b: str, claim: str, seed: int,
                 metric: str = "mse") -> tuple[Alternative, ...]:
    if guarded is None:
        return ()
    n = sum(1 for r in guarded if r.guarded)
    if metric == "mse":
        ev = _mse_comparison(guarded, a, b, claim, seed)
    else:
        ev = Comparison(per_run_nees(guarded, a), per_run_nees(guarded, b), METHODS[a], METHODS[b], claim,  # type: ignore[arg-type]
                        "per-run mean NEES (4-D) from frame 5 on", seed=seed, reason=_reason(len(guarded)))
    return (Alternative("local filter design", f"collapse guard: progressive correction in {GUARD_STAGES} steps when a "
                        f"node keeps < {COLLAPSE_FRACTION * 100:g} % effective particles ({n} of {len(guarded)} runs "
                        "redone)", ev),)


def guard_values(guarded: list[TrackingRun], sc: RangeBearingScenario) -> dict[str, Any]:
    """Glue values of the guarded study (:func:`guarded_runs`).

    Parameters
    ----------
    guarded : list of TrackingRun
        The runs with the collapse guard.
    sc : RangeBearingScenario
        The scenario (its ``n_particles`` sets the collapse threshold).

    Returns
    -------
    dict
        ``chf_guard_stages`` (int, tempering steps), ``chf_n_guarded`` (int, runs in which the guard acted), ``chf_guard_updates`` (int,
        guarded node updates), ``chf_guard_ess_min`` (smallest ESS of any node and frame in those
        runs, after the last tempering step, 1 decimal), ``chf_n_collapsed_guard`` (int, runs
        still collapsed), ``chf_pct_central_guard`` (how much larger, in %, Chernoff-PSO's RMSE is
        than the centralised filter's) and ``chf_nees_naive_guard`` (naive product's mean NEES
        from frame 5 on); 4 decimals unless stated.
    """
    _check_study(guarded)
    hit = [r for r in guarded if r.guarded]
    def rmse(key: str) -> float:
        return float(np.sqrt(position_sq_errors(guarded, key)[:, LATE].mean()))
    return {"chf_guard_stages": GUARD_STAGES, "chf_n_guarded": len(hit), "chf_guard_updates": sum(len(r.guarded) for r in hit),
            "chf_guard_ess_min": rounded(float(min_local_ess(hit).min()), 1) if hit else 0.0,
            "chf_n_collapsed_guard": int(collapsed(guarded, sc.n_particles).sum()),
            "chf_pct_central_guard": rounded(100 * (rmse("chernoff_pso") / rmse("centralised") - 1)),
            "chf_nees_naive_guard": rounded(float(nees_per_frame(guarded, "naive_product")[:, LATE].mean()))}


def _check_study(runs: object) -> None:
    if not isinstance(runs, list) or not runs or not all(isinstance(r, TrackingRun) for r in runs):
        raise ValueError("runs must be a non-empty list of TrackingRun")


def claims(checks: GaussianChecks, toy: ToyStudy, runs: list[TrackingRun], sc: RangeBearingScenario,
           seed: int, guarded: list[TrackingRun] | None = None, isv: IsVarianceStudy | None = None,
           stopping: StoppingStudy | None = None, premise: dict[str, NetworkStudy] | None = None,
           common: tuple[bool, float, float] | None = None) -> Ledger:
    """The claims ledger of the patent, built from the chapter's computed results.

    Parameters
    ----------
    checks : GaussianChecks
        K1-K5 (:func:`gaussian_checks`).
    toy : ToyStudy
        The static two-mixture example (:func:`toy_study`).
    runs : list of TrackingRun
        The Monte-Carlo runs of the tracking scenario (same seeds for every method).
    sc : RangeBearingScenario
    seed : int
        Root seed of the runs.
    guarded : list of TrackingRun, optional
        The same runs with the collapse guard (:func:`guarded_runs`); when given, the MSE and NEES
        comparisons get it as an alternative reading ("local filter design").
    isv : IsVarianceStudy, optional
        The importance-sampling variance study (:func:`is_variance_study`); when given, claim
        ``chf-is-variance`` records it.
    stopping : StoppingStudy, optional
        The two stopping rules of the swarm (:func:`stopping_study`); when given, claim ``chf-pso``
        gets the patent's rule as an alternative reading.
    premise : dict, optional
        The designed networks (:func:`premise_studies`); when given, records ``chf-premise-*``.
    common : (bool, float, float), optional
        :func:`common_information_check`; when given, record ``chf-common-once``. With ``sc.readings``,
        ``chf-gain-uniform`` gets the readings of steps D and F (initial exponents by minimising
        :math:`Z_{\\rm FOA}`; exponents by minimising :math:`Z_{\\rm FOA}`) as alternatives and the
        equal-KL rule is record ``chf-equal-kl``.

    Returns
    -------
    Ledger
        Claims of ``cn107330468b``; the headline is the implied gain of optimised exponents.
    """
    led = Ledger(BIBKEY)
    bad = collapsed(runs, sc.n_particles)
    recon = "formulas of claims 1-3 reconstructed from the literature (the patent prints none)"
    led.add(Claim(
        "chf-formulas", BIBKEY, "claims 1-3, steps A-J",
        "The distributed fusion method is specified by the formulas of claims 1-3.",
        "no formula, scenario or number printed",
        Unverifiable("every formula of the claims is missing from the text (the symbols were images); no "
                     "scenario, parameter or result is given, so nothing published can be recomputed"),
        link="chf-crit-formulas", critiques=("chf-crit-formulas", "chf-crit-unspecified")))
    if common is not None:
        led.add(Claim(
            "chf-common-once", BIBKEY, "steps D-I (Chernoff fusion)",
            "Chernoff fusion of the nodes' densities counts the information they share once, whatever the exponents.",
            "qualitative",
            Proposition(common[0], f"exact: a common factor c of every density enters the fusion as c^(Σε_i) = c; "
                        f"checked on 100 random 4-D Gaussian cases (fused information = common prior information "
                        f"J0 + Σ ε_i J_i, relative error {common[1]:.1e}; the naive product has N J0) and on 100 "
                        f"non-Gaussian 1-D cases on a grid (largest density difference {common[2]:.1e})"),
            link="chf-crit-formulas", bound="exact (algebra of the exponents on the simplex)",
            assumptions=(recon, "common information = a factor shared by every node's density (the common prior)"),
            critiques=("chf-crit-gain",)))
    led.add(Claim(
        "chf-gaussian-ci", BIBKEY, "steps D-I (Chernoff fusion)",
        "For Gaussians, Chernoff fusion is covariance intersection, with a normaliser Z <= 1.",
        "qualitative",
        Proposition(checks.ok, f"equal to covariance intersection to < {fmt(checks.tolerances[0])} (relative) on "
                    f"100 random 4-D pairs; closed-form normaliser to < {fmt(checks.tolerances[1])}; log Z <= 0; "
                    f"equal divergences at the optimum to < {fmt(checks.tolerances[2])} nats"),
        link="chf-crit-formulas", bound="exact: covariance intersection (Julier & Uhlmann 1997); eq. eq-chf-k2",
        assumptions=(recon,)))
    gap = toy.foa - toy.exact
    led.add(Claim(
        "chf-foa", BIBKEY, "step D (first-order approximation)",
        "The first-order approximation gives a fused Gaussian mixture g with M_f components from the local mixtures.",
        "qualitative",
        Proposition(bool(np.min(gap) >= -1e-9),
                    f"log Z_FOA - log Z from {np.min(gap):.3f} to {np.max(gap):.3f} nats on the two-mixture example: "
                    f"an upper bound, not the Chernoff normaliser; {sc.n_components ** len(sc.sensors)} components "
                    "for 3 nodes x 3, 3^N in general"),
        link="fig-chf-objective", bound="log Z_FOA >= log Z (subadditivity of t^ε), equality for single Gaussians",
        assumptions=(recon, "approximation (Σπ N)^ε ≈ Σ π^ε N^ε (Julier 2006), full overlap weights"),
        critiques=("chf-crit-components",)))
    d_is, d_foa = abs(toy.w_is - toy.w_exact), abs(toy.w_foa - toy.w_exact)
    central = (toy.omegas >= 0.2) & (toy.omegas <= 0.8)
    err = np.abs(toy.is_estimate - toy.exact)
    led.add(Claim(
        "chf-is", BIBKEY, "steps E-F (importance sampling)",
        "Importance sampling with g as proposal gives the objective whose minimiser is the optimal exponent.",
        "qualitative",
        Proposition(bool(d_is < d_foa),
                    f"IS minimiser {toy.w_is:.3f} vs exact {toy.w_exact:.3f} (first-order {toy.w_foa:.3f}); "
                    f"IS error <= {np.max(err[central]):.3f} nats for ω in [0.2, 0.8], up to {np.max(err):.2f} "
                    "at the ends (proposal at ω = 0.5)"),
        link="chf-crit-reuse",
        assumptions=(recon, "objective: min log Z (the Chernoff information; the patent names no objective)",
                     "densities of the samples from the fitted mixtures of step C"),
        alternatives=(() if isv is None else (
            Alternative("range of ω", "the whole [0, 1] from one proposal (as step G searches the whole simplex)",
                        Proposition(bool(isv.lo <= 0.0 and isv.hi >= 1.0),
                                    f"the weights have finite variance only for ω in [{isv.lo:.3f}, {isv.hi:.3f}] "
                                    "(see chf-is-variance); outside, the estimate has no finite variance")),)),
        critiques=("chf-crit-reuse", "chf-crit-gmfit")))
    is_out = np.min(np.stack([r.eps["pso"] for r in runs]), axis=2) < 1.0 / (2 * len(sc.sensors)) - 1e-12
    if isv is not None:
        led.add(Claim(
            "chf-is-variance", BIBKEY, "steps E-G (one proposal for the whole search)",
            "The importance-sampled objective of step F, from samples of g at ε⁽⁰⁾, can be minimised over the "
            "whole simplex.",
            "qualitative",
            Proposition(bool(isv.lo <= 0.0 and isv.hi >= 1.0),
                        f"Gaussian pair, proposal at ω⁽⁰⁾ = 0.5: the weights have finite variance only for ω in "
                        f"[{isv.lo:.3f}, {isv.hi:.3f}] (Λ = Σ(2ε_i - ε⁽⁰⁾_i)P_i⁻¹ positive definite); inside, Ĵ is "
                        f"biased low by (ρ - 1)/(2R), confirmed by {isv.replicates} estimates of R = {isv.R} per ω "
                        f"(check {'passed' if isv.ok else 'failed'}); in the tracking study the optimised exponents "
                        f"leave the region where finite variance is guaranteed (every ε_i ≥ ε⁽⁰⁾_i / 2 = 1/(2N)) in "
                        f"{int(is_out.sum())} of {is_out.size} frames"),
            link="chf-crit-reuse", bound="Λ(ε) ≻ 0 (finite weight variance); bias ≈ -(ρ - 1)/(2R)",
            assumptions=(recon, "single Gaussians per node (the mixture case inherits the tails of its components)"),
            critiques=("chf-crit-reuse",)))
    obj = {m: np.stack([r.objective[m] for r in runs]) for m in ("pso", "slsqp")}
    gap_obj = float(np.max(np.abs(obj["pso"] - obj["slsqp"])))
    gaps = np.round(np.maximum(obj["pso"] - obj["slsqp"], 0.0).ravel(), 12)   # the swarm's excess (nats), per frame
    # sampling error of Ĵ itself (delta method: Var log mean(w) ≈ 1/ESS - 1/R); the swarm "finds the optimum"
    # when it misses SLSQP's value by less than the estimate's own standard error, in every frame
    ess = np.stack([r.ess["pso"] for r in runs])
    se_j = np.sqrt(np.maximum(1.0 / ess - 1.0 / sc.n_samples, 0.0))
    within = np.abs(obj["pso"] - obj["slsqp"]) < se_j
    led.add(Claim(
        "chf-pso", BIBKEY, "step G (particle swarm)",
        "The particle swarm (G1-G6) finds the optimal exponents of step F.",
        "qualitative",
        Proposition(bool(np.all(within)),
                    f"objective within {gap_obj:.1e} of SLSQP on the same samples (below Ĵ's own sampling error, "
                    f"smallest {np.min(se_j):.1e}, in {int(within.sum())} of {within.size} frames of {len(runs)} runs); "
                    f"{np.mean([r.evaluations['pso'] for r in runs]):.0f} vs "
                    f"{np.mean([r.evaluations['slsqp'] for r in runs]):.0f} evaluations per frame"),
        link="chf-crit-pso", bound="global minimum of a convex objective (SLSQP with the exact gradient)",
        assumptions=("fitness -Ĵ (G3-G4 keep the higher fitness)",
                     "stopping rule: best fitness stagnates (the patent: positions converge)",
                     "swarm constants of Clerc & Kennedy (2002)"),
        alternatives=(
            Alternative("judged on its own", "the swarm's objective against SLSQP's on the same samples, without "
                        "reference to Ĵ's sampling error: within 10⁻³ nats in at least 95 % of the frames",
                        Proposition(bool(np.quantile(gaps, 0.95) <= 1e-3),
                                    f"gap PSO − SLSQP over {gaps.size} frames: median {np.median(gaps):.1e}, 95th "
                                    f"percentile {np.quantile(gaps, 0.95):.1e}, largest {np.max(gaps):.1e} nats")),
            Alternative("what the gap costs", "per-run MSE with the swarm's exponents against SLSQP's (same samples)",
                        _mse_comparison(runs, "chernoff_pso", "chernoff_slsqp", "less", seed)),
        ) + (() if stopping is None else (
            Alternative("stopping rule (G6)", f"positions converge (the patent's wording; every particle within "
                        f"{stopping.xtol:g} of the best), on {stopping.se.size} static problems",
                        Proposition(bool(np.all(stopping.within("positions"))),
                                    f"objective within {np.max(stopping.gap['positions']):.1e} of SLSQP (below Ĵ's "
                                    f"sampling error in {int(stopping.within('positions').sum())} of "
                                    f"{stopping.se.size} problems); {stopping.evaluations['positions'].mean():.0f} "
                                    f"evaluations vs {stopping.evaluations['stagnation'].mean():.0f} with the "
                                    f"stagnation rule; the iteration limit reached in "
                                    f"{int(np.sum(stopping.evaluations['positions'] >= stopping.limit))} problems")),)),
        critiques=("chf-crit-pso", "chf-crit-fitness", "chf-crit-criterion")))
    led.add(Claim(
        "chf-gain-uniform", BIBKEY, "steps F-G (implied by the design; no accuracy claim is printed)",
        "Optimising the exponents by the Chernoff criterion gives a more accurate fused estimate than "
        "uniform exponents.",
        "qualitative",
        _mse_comparison(runs, "chernoff_pso", "chernoff_uniform", "less", seed),
        link="chf-crit-gain",
        assumptions=("our scenario: 3 symmetric range-bearing nodes, no feedback, full connectivity",
                     "prior SD 30 m in position (the design note's 100 m leaves few effective particles at frame 1)",
                     "initial exponents ε⁽⁰⁾ uniform", "samples of step E reused at ε*"),
        alternatives=(
            _without_collapse(runs, bad, "chernoff_pso", "chernoff_uniform", "less", seed),
            Alternative("initial exponents ε⁽⁰⁾", "previous frame's ε*",
                        _mse_comparison(runs, "chernoff_prev", "chernoff_uniform", "less", seed)),
            Alternative("samples at ε*", "redrawn from g(ε*)",
                        _mse_comparison(runs, "chernoff_redraw", "chernoff_uniform", "less", seed)),
            Alternative("optimiser", "SLSQP on the same samples",
                        _mse_comparison(runs, "chernoff_slsqp", "chernoff_uniform", "less", seed)),
        ) + _guarded_alt(guarded, "chernoff_pso", "chernoff_uniform", "less", seed) + (() if not sc.readings else (
            Alternative("initial exponents ε⁽⁰⁾", "argmin of the first-order normaliser Z_FOA (step D needs no "
                        "exponents: no circularity), then steps E-I (step G: the exact minimum of Ĵ)",
                        _mse_comparison(runs, "chernoff_foa0", "chernoff_uniform", "less", seed)),
            Alternative("step F", "exponents argmin Z_FOA (the first-order criterion, no swarm), estimate by "
                        "importance sampling at them",
                        _mse_comparison(runs, "chernoff_foa", "chernoff_uniform", "less", seed)),
        )),
        headline=True, critiques=("chf-crit-gain", "chf-crit-circular")))
    if sc.readings:
        kl = np.stack([r.eps["equal_kl"] for r in runs])
        sl = np.stack([r.eps["slsqp"] for r in runs])
        ok = np.all(np.isfinite(kl), axis=2)
        gap = float(np.max(np.abs(kl[ok] - sl[ok]))) if ok.any() else float("nan")
        boundary = np.min(sl, axis=2) < 1e-6
        led.add(Claim(
            "chf-equal-kl", BIBKEY, "step F (a reading: the optimum as an equal-divergence rule)",
            "Step F's optimum is the exponent vector for which the fused density is equally far, in "
            "Kullback-Leibler divergence, from every node's density.",
            "qualitative",
            Proposition(bool(ok.all()), f"on the importance samples of step E the rule (equal estimated "
                        f"KL(p_ε‖p̂_i), Newton's method on Σε = 1) has a solution in the simplex in {int(ok.sum())} of "
                        f"{ok.size} frames, equal to SLSQP's minimum of Ĵ there to {gap:.1e}; in the other "
                        f"{int((~ok).sum())} it leaves the simplex: the minimum is on its boundary (an exponent "
                        f"below 10⁻⁶ in {int(boundary.sum())} frames), where the divergences are not equal"),
            link="chf-crit-circular", bound="exact at an interior optimum (eq. eq-chf-equal-kl, K5)",
            assumptions=(recon, "KL(p_ε‖p̂_i) estimated on the samples of step E with the fused weights"),
            critiques=("chf-crit-circular",)))
    led.add(Claim(
        "chf-gain-ci", BIBKEY, "steps B-I (implied by the design; no accuracy claim is printed)",
        "Fusing Gaussian-mixture summaries of the particle posteriors is more accurate than covariance "
        "intersection of moment-matched Gaussians.",
        "qualitative",
        _mse_comparison(runs, "chernoff_pso", "ci_gaussian", "less", seed),
        link="chf-crit-gmfit",
        assumptions=("our scenario (nearly Gaussian local posteriors)", "3 components per node, weighted EM"),
        alternatives=(_without_collapse(runs, bad, "chernoff_pso", "ci_gaussian", "less", seed),)
        + _guarded_alt(guarded, "chernoff_pso", "ci_gaussian", "less", seed),
        critiques=("chf-crit-gmfit",)))
    led.add(Claim(
        "chf-gain-local", BIBKEY, "claim 1 (purpose of fusing; no accuracy claim is printed)",
        "The distributed fusion is more accurate than a node's own particle filter.",
        "qualitative",
        _mse_comparison(runs, "chernoff_pso", "local1", "less", seed),
        link="fig-chf-rmse",
        assumptions=("our scenario",),
        alternatives=(_without_collapse(runs, bad, "chernoff_pso", "local1", "less", seed),
                      Alternative("which node", "sensor 2", _mse_comparison(runs, "chernoff_pso", "local2", "less", seed)),
                      Alternative("which node", "sensor 3", _mse_comparison(runs, "chernoff_pso", "local3", "less", seed))),
        critiques=("chf-crit-unspecified",)))
    keep = [r for r, x in zip(runs, bad) if not x]
    n_guard = None if guarded is None else sum(1 for r in guarded if r.guarded)
    double_alts: list[Alternative] = [
        Alternative("runs with a collapsed node filter", f"excluded ({int(bad.sum())} of {len(runs)} runs)",
                    _nees_vs_consistent(keep, "naive_product", "greater", seed)),
    ]
    if guarded is not None:
        double_alts.append(Alternative("local filter design", f"collapse guard ({n_guard} of {len(guarded)} runs redone)",
                                       _nees_vs_consistent(guarded, "naive_product", "greater", seed)))
    double_alts += [
        Alternative("yardstick", "the naive product's NEES above the Chernoff fusion's (a cautious fuser, not the "
                    "consistent value 4)",
                    Comparison(per_run_nees(runs, "naive_product"), per_run_nees(runs, "chernoff_pso"),
                               METHODS["naive_product"], METHODS["chernoff_pso"], "greater", _NEES, seed=seed,
                               reason=_reason(len(runs)))),
        Alternative("which half of the claim", "the Chernoff fusion is not overconfident: its NEES below 4",
                    _nees_vs_consistent(runs, "chernoff_pso", "less", seed)),
    ]
    led.add(Claim(
        "chf-double-count", BIBKEY, "steps D-H (Chernoff fusion vs product; the chapter's reading of the design)",
        "Multiplying the local posteriors (the naive product, exponents 1) is overconfident, because it counts "
        "the shared prior N times; Chernoff fusion avoids this.",
        "qualitative",
        _nees_vs_consistent(runs, "naive_product", "greater", seed),
        link="chf-crit-gain", bound="NEES 4 for a consistent estimator of the 4-D state",
        assumptions=("our scenario: no feedback, so double counting does not build up over frames",
                     "the effect is on the reported covariance only: for moment-matched Gaussians the product's mean "
                     "equals covariance intersection's at uniform exponents (its covariance is N times smaller)"),
        alternatives=tuple(double_alts), critiques=("chf-crit-gain",)))
    led.add(Claim(
        "chf-gain-closed-form", BIBKEY, "steps F-G (implied by the design; no accuracy claim is printed)",
        "Exponents chosen by the Chernoff criterion give a more accurate fused estimate than uniform exponents, "
        "without sampling noise: covariance intersection of moment-matched Gaussians with the closed-form Chernoff "
        "exponents against uniform exponents (whose mean is the naive product's).",
        "qualitative",
        _mse_comparison(runs, "ci_gaussian", "naive_product", "less", seed),
        link="chf-crit-gain",
        assumptions=("our scenario: 3 symmetric range-bearing nodes, no feedback, full connectivity",
                     "Gaussian summaries of the local posteriors (no mixtures, no importance sampling)"),
        alternatives=(_without_collapse(runs, bad, "ci_gaussian", "naive_product", "less", seed),)
        + _guarded_alt(guarded, "ci_gaussian", "naive_product", "less", seed),
        critiques=("chf-crit-gain",)))
    for claim in (premise_claims(premise) if premise is not None else []):
        led.add(claim)
    return led


def ledger_values(led: Ledger) -> dict[str, Any]:
    """Glue values of the ledger's comparisons: mean paired difference and its 95 % interval.

    Parameters
    ----------
    led : Ledger
        The claims ledger (:func:`claims`); only evidence of type ``Comparison`` contributes.

    Returns
    -------
    dict
        For each claim ``<id>`` (dashes as underscores) whose evidence is a comparison:
        ``<id>_d`` (mean paired difference A - B, in the comparison's units), ``<id>_lo`` and
        ``<id>_hi`` (its 95 % paired t interval; 4 decimals), ``<id>_status`` (``"reproduced"``,
        ``"contradicted"`` or ``"not distinguishable"``, as the interval shows) and ``<id>_runs``
        (int, paired runs); for squared-error comparisons ``<id>_word``: ``"better"`` (the interval
        of A - B below 0), ``"worse"`` (above 0) or ``"not distinguishable"``, A against B; the same
        keys ``<id>_alt<j>_*`` for its ``j``-th alternative (0-based) when that alternative's
        evidence is a comparison.
    """
    v: dict[str, Any] = {}

    def put(prefix: str, ev: Any) -> None:
        if isinstance(ev, Comparison):
            d, lo, hi = ev.interval()
            v.update({f"{prefix}_d": rounded(d), f"{prefix}_lo": rounded(lo), f"{prefix}_hi": rounded(hi),
                      f"{prefix}_status": ev.status(), f"{prefix}_runs": ev.runs})
            if ev.metric == _MSE:  # lower is better: the first method is better, worse or neither
                v[f"{prefix}_word"] = "better" if hi < 0 else "worse" if lo > 0 else "not distinguishable"
    for c in led.claims:
        p = c.id.replace("-", "_")
        put(p, c.evidence)
        for j, a in enumerate(c.alternatives):
            put(f"{p}_alt{j}", a.evidence)
    return v


__all__ += ["ledger_values"]


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
        ``chf_ss_v_08`` (difference from V at ω = 0.8), ``chf_ss_post`` (largest posterior difference), and
        ``chf_ss_max_swap_text`` / ``chf_ss_post_text`` (the two in words for the prose).

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
              "chf_ss_post": float(table[["posterior mean vs our fusion", "posterior covariance vs our fusion"]].max().max())}
    for key in ("chf_ss_max_swap", "chf_ss_post"):     # prose: "to round-off" for differences below 1e-6
        values[key + "_text"] = ("to round-off (relative difference below 10⁻⁶)" if values[key] == 0.0
                                 else f"up to a relative difference of {values[key]:.3g}")
    return table, values
