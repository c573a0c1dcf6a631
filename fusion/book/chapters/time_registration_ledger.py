r"""Chapter 07 (time registration, Shi, Suo & Ma 2023): the claims ledger's evidence and the values its texts quote.

Every Monte-Carlo study the ledger needs (:func:`study`, computed once per seed and run count by
:func:`cached_study`), one evidence function per record of ``book/claims/shi2023time.yaml``, and the
stress, cost and gain values the chapter glues. Tables and figures are in
:mod:`fusion.book.chapters.time_registration`.
"""

from __future__ import annotations

import functools
import json
from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd
from numpy.typing import ArrayLike

from fusion import data
from fusion.book.chapters.time_registration import (CAUSAL_IMPROVED, FIG4, IMPROVED, S3_READINGS, TWO,
                                                    robustness_readings)
from fusion.registration import affine_decomposition
from fusion.book.exact import ExactComparison
from fusion.book.ledger import Comparison, Conjunction, Evidence, Proposition, Unverifiable, ledger_dir
from fusion.scenarios import time_registration as sc

__all__ = [
    "study",
    "cached_study",
    "PRIMARY_SIGMA",
    "ledger_evidence",
    "cost_count",
    "cost_values",
    "manoeuvre_values",
    "latency_values",
    "gain_values",
    "blue_whole_record",
    "stress_table",
    "keep",
    "STRESS",
    "UNREGISTERED",
    "FIG23_HYPOTHESES",
    "figs23_fits",
    "exact_check",
    "noise_gain_by_instant",
    "unregistered_runs",
]

# ---------------------------------------------------------------- the ledger's evidence (book/claims/shi2023time.yaml)
#
# Each ``_ev_*`` function computes one record's evidence from the chapter's study (:func:`study`), one
# Evidence per reading key of the claim file; every text of the record (claim, readings, assumptions,
# bound, reason) is in the claim file. The public ``ev_*`` named by the claim file take
# ``(settings, *, seed, runs)`` (:func:`fusion.book.claims.evaluate`): the reading is ``settings["reading"]``
# and the study is computed once per (seed, runs) (:func:`cached_study`).

S3 = "Kalman, predict (§3)"
EXTRAP = "two-point extrapolation"
FIXED_LAG = "fixed-lag smoother (next sample)"
QLS = "quadratic least squares (past + next sample)"
LOCAL_QLS = "local quadratic least squares (last 4 + next sample)"
MSE = "registration MSE (m²)"
#: The §3 filter as the text describes it: the filter period changed at every registration instant.
PC: dict[str, object] = {"period_change": True}

#: The unmodelled changes every compared method is run under (rule R6): key -> monte_carlo keywords.
STRESS: dict[str, dict[str, object]] = {
    "manoeuvre-stop": {"a_after": 0.0},
    "manoeuvre-reverse": {"a_after": -2.0},
    "latency-10ms": {"delay": 0.01},
    "latency-minus-10ms": {"delay": -0.01},
}

#: Noise levels of the readings (m), besides the primary σ.
SIGMAS_ALT: tuple[float, ...] = (0.1, 0.3, 3.0, 10.0)

#: Methods run in every noise-level and stress study.
STUDY_METHODS: tuple[str, ...] = (TWO, IMPROVED, "three-point", "least squares", EXTRAP, S3, CAUSAL_IMPROVED,
                                  "three-point extrapolation", "Kalman + two-point", FIXED_LAG, QLS, LOCAL_QLS,
                                  "quadratic least squares (causal)", "RTS smoother (whole record)",
                                  "cubic spline (whole record)")


#: Sensor 1's last sample taken as simultaneous with the instant (no registration).
UNREGISTERED = "no registration (sensor 1's last sample)"


def unregistered_runs(m: sc.MonteCarlo, t1: ArrayLike, t2: ArrayLike) -> np.ndarray:
    """Per-run MSE (m²) of taking sensor 1's last sample as simultaneous, on the very runs of ``m``.

    The noisy samples are drawn again exactly as :func:`fusion.scenarios.time_registration.monte_carlo` draws
    them (``default_rng(m.seed)``, the source's truth, no latency), so the runs are paired with ``m``'s.

    Parameters
    ----------
    m : MonteCarlo
        Runs on the source's truth at the default instants.
    t1, t2 : array_like
        Sample times and instants (s).

    Returns
    -------
    ndarray, shape (m.runs,)
    """
    t1, t2 = np.asarray(t1, dtype=float), np.asarray(t2, dtype=float)
    z = sc.truth(t1) + m.sigma * np.random.default_rng(m.seed).standard_normal((m.runs, t1.size))
    last = np.searchsorted(t1, t2, side="right") - 1
    return np.round(np.mean((z[:, last] - sc.truth(t2)) ** 2, axis=1), 10)


def _key(s: float) -> str:
    """Reading key of a noise level: ``sigma-0-1`` for 0.1 m."""
    return "sigma-" + f"{s:g}".replace(".", "-")


def _c(m: sc.MonteCarlo, a: str, b: str, claim: str = "less", metric: str = MSE, cond: str = "") -> Comparison:
    return Comparison(m.per_run[a], m.per_run[b], a, b, claim, metric, seed=m.seed,  # type: ignore[arg-type]
                      conditions=(cond, cond))


def study(t1: ArrayLike, t2: ArrayLike, sigma: float, runs: int, seed: int) -> dict[str, object]:
    """Every Monte-Carlo study the ledger needs, each reading at the primary's ``runs`` (rule R4).

    Parameters
    ----------
    t1, t2 : array_like
        Sensor-1 sample times and sensor-2 instants (s).
    sigma : float
        Primary noise level (m).
    runs : int
        Runs of the primary and of every reading.
    seed : int
        Seed of the primary runs (``seed``); the readings use ``seed + 100 + i``.

    Returns
    -------
    dict
        ``mc`` (every method of ``STUDY_METHODS``, the primary runs), ``sweep`` (σ -> runs),
        ``stress`` (key of :data:`STRESS` -> runs of every method), ``robust`` (key of :func:`~fusion.book.chapters.time_registration.robustness_readings`
        -> runs of the Fig. 4 methods), ``s3`` (key of :data:`~fusion.book.chapters.time_registration.S3_READINGS` -> runs of the §3 method and
        two-point extrapolation), ``s3_fair`` (σ -> §3, three-point extrapolation and least squares from the second instant),
        ``s3_period`` (the §3 method with the period changed, on the primary runs), ``s3_pc`` (the §3 method
        with the period changed and two-point extrapolation on the runs of each noise level and stress test),
        ``realtime`` (causal
        improved and two-point extrapolation from the second instant), ``stress_tuned`` (the stop of the
        acceleration with q_v = 1, q_a = 0.1), ``cv_integer`` (a constant-velocity target, sensor 2 every 6 s:
        where Blair's least squares is designed for), ``t1``, ``t2``, ``sigma``.
    """
    t1, t2 = np.asarray(t1, dtype=float), np.asarray(t2, dtype=float)
    names = list(STUDY_METHODS)
    out: dict[str, object] = {"t1": t1, "t2": t2, "sigma": float(sigma),
                              "mc": sc.monte_carlo(names, sigma, runs, seed)}
    out["sweep"] = {s: sc.monte_carlo(names, s, runs, seed + 100 + i) for i, s in enumerate(SIGMAS_ALT)}
    out["stress"] = {k: sc.monte_carlo(names, sigma, runs, seed + 110 + i, **kw)  # type: ignore[arg-type]
                     for i, (k, kw) in enumerate(STRESS.items())}
    fig4 = list(FIG4) + ["least squares"]
    out["robust"] = {k: sc.monte_carlo(fig4, sigma, runs, seed + 120 + i, **kw)  # type: ignore[arg-type]
                     for i, (k, _, _, kw) in enumerate(robustness_readings(sigma, t2))}
    out["s3"] = {k: sc.monte_carlo([S3, EXTRAP], sigma, runs, seed + 140 + i, kf={**kw, **PC})
                 for i, (k, _, _, kw) in enumerate(S3_READINGS) if k != "per-step-period-changed"}
    out["s3_fair"] = {s: sc.monte_carlo([S3, "three-point extrapolation", "least squares"], s, runs, seed + 150 + i,
                                        t_dst=t2[1:], kf=PC) for i, s in enumerate((0.1, float(sigma)))}
    out["s3_period"] = sc.monte_carlo([S3], sigma, runs, seed, kf=PC)
    # §3 as the text describes it (period changed), on the very runs of the sweep and of the stress tests
    out["s3_pc"] = {**{_key(s): sc.monte_carlo([S3, EXTRAP], s, runs, seed + 100 + i, kf=PC)
                       for i, s in enumerate(SIGMAS_ALT)},
                    **{k: sc.monte_carlo([S3, EXTRAP], sigma, runs, seed + 110 + i, kf=PC, **kw)  # type: ignore[arg-type]
                       for i, (k, kw) in enumerate(STRESS.items())},
                    "manoeuvre-stop-tuned": sc.monte_carlo([S3, EXTRAP], sigma, runs, seed + 170, kf=PC, a_after=0.0,
                                                           q_v=1.0, q_a=0.1)}
    out["realtime"] = sc.monte_carlo([CAUSAL_IMPROVED, EXTRAP], sigma, runs, seed + 160, t_dst=t2[1:])
    out["stress_tuned"] = sc.monte_carlo([IMPROVED, TWO, S3, EXTRAP, FIXED_LAG], sigma, runs, seed + 170,
                                         a_after=0.0, q_v=1.0, q_a=0.1)
    out["cv_integer"] = sc.monte_carlo([TWO, EXTRAP, "least squares"], sigma, runs, seed + 180,
                                       t_dst=sc.instants(6.0)[1], window=6.0, a_after=0.0, t_change=0.0)
    return out


def _noise_levels(st: Mapping[str, object], a: str, b: str, claim: str = "less") -> dict[str, Evidence]:
    return {_key(s): _c(m, a, b, claim) for s, m in st["sweep"].items()}  # type: ignore[attr-defined]


def _stress(st: Mapping[str, object], a: str, b: str, keys: Sequence[str] = ("manoeuvre-stop", "manoeuvre-reverse"),
            claim: str = "less") -> dict[str, Evidence]:
    return {k: _c(st["stress"][k], a, b, claim, cond=k) for k in keys}  # type: ignore[index]


def _ev_samples(st: Mapping[str, object]) -> Evidence:
    """``shi-samples``: how many samples a 5 s sensor can give in 40 s."""
    t1, t2 = st["t1"], st["t2"]
    dur, p2 = float(sc.SCENARIO["duration"]), float(sc.SCENARIO["period_2"])
    n2_max = int(np.floor(dur / p2)) + 1
    return Proposition(bool(n2_max >= data.SHI2023_CLAIMED_SAMPLES.values[1]),
                       f"at most {n2_max} samples from a {p2:g} s sensor in {dur:g} s whatever its start time "
                       f"({np.size(t2)} from 3 s); sensor 1 gives {np.size(t1)}")


#: Hypotheses on the authors' program for Figs. 2-3: (label, acceleration in x = t + a t²/2 (m/s²), end of record (s),
#: direction of simulation 2's least squares: "fast onto slow" as simulation 1, or "slow onto fast" as its text goes on).
FIG23_HYPOTHESES: tuple[tuple[str, float, float, str], ...] = (
    ("the stated scenario", 2.0, 40.0, "fast onto slow"),
    ("acceleration halved (x = t + t²/2)", 1.0, 40.0, "fast onto slow"),
    ("the ½ dropped (x = t + 2t²)", 4.0, 40.0, "fast onto slow"),
    ("20 samples per sensor", 2.0, 100.0, "fast onto slow"),
    ("20 samples per sensor, acceleration halved", 1.0, 100.0, "fast onto slow"),
    ("simulation 2 slow onto fast (sensor 2 fitted, at sensor 1's times)", 2.0, 40.0, "slow onto fast"),
    ("slow onto fast, acceleration halved", 1.0, 40.0, "slow onto fast"))


def figs23_fits(a: float, end: float, direction: str = "fast onto slow") -> dict[str, bool]:
    """Which of the four panels of the source's Figs. 2-3 a noise-free program with acceleration ``a`` and record
    length ``end`` would draw with the printed y-axis: the panel's largest value lies in (0.8 axis, axis], as an
    automatic axis puts its top tick within one of about five tick steps above the data.

    Parameters
    ----------
    a : float
        Acceleration (m/s²) of x(t) = t + a t²/2.
    end : float
        End of the record (s); sensor 1 from 1 s every 2 s, sensor 2 from 3 s every 5 s.
    direction : {"fast onto slow", "slow onto fast"}
        Simulation 2 (Fig. 3): sensor 1 fitted on (t_k − 5 s, t_k] at sensor 2's instants, or, as its text goes
        on, sensor 2's samples fitted by a line on (t − 10 s, t] (two sensor-2 samples at least) at sensor 1's
        times from sensor 2's second sample on.

    Returns
    -------
    dict
        Panel key of ``fusion.data.SHI2023_AXES`` -> whether it fits.
    """
    from fusion.registration import least_squares, two_point
    if direction not in ("fast onto slow", "slow onto fast"):
        raise ValueError(f"direction must be 'fast onto slow' or 'slow onto fast', got {direction!r}")
    t1, t2 = np.arange(1.0, end, 2.0), np.arange(3.0, end - 1.0, 5.0)
    x1, x2 = t1 + a * t1**2 / 2, t2 + a * t2**2 / 2
    after3 = (least_squares(t1, x1, t2, 5.0) if direction == "fast onto slow"
              else least_squares(t2, x2, t1[t1 >= t2[1]], 10.0))
    top = {"fig2_before_y": x1.max(), "fig2_after_y": two_point(t1, x1, t2).max(),
           "fig3_before_y": max(x1.max(), x2.max()), "fig3_after_y": after3.max()}
    ax = data.SHI2023_AXES.columns
    return {k: bool(0.8 * float(ax[k][0]) < v <= float(ax[k][0])) for k, v in top.items()}


def _ev_figs23(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-figs23``: do the registered positions fit under the 'after' axes? (and which program would draw them)"""
    ax = data.SHI2023_AXES.columns
    t1, t2 = st["t1"], st["t2"]
    top2 = float(sc.register(TWO, t1, sc.truth(t1), t2, 1.0).max())          # Fig. 2: two-point interpolation
    top3 = float(sc.register("least squares", t1, sc.truth(t1), t2, 1.0).max())  # Fig. 3: least squares
    a2, a3 = float(ax["fig2_after_y"][0]), float(ax["fig3_after_y"][0])
    fits = {label: figs23_fits(a, end, d) for label, a, end, d in FIG23_HYPOTHESES}
    said = "; ".join(f"{label}: {', '.join(k for k, v in f.items() if v) or 'no panel'}" for label, f in fits.items())
    return {"primary": Proposition(bool(top2 <= a2 and top3 <= a3),
                                   f"registered positions reach {top2:.0f} m (two-point, Fig. 2) and {top3:.0f} m "
                                   f"(least squares, Fig. 3; the truth at the last instant: "
                                   f"{float(sc.truth(t2).max()):.0f} m); the 'after' axes stop at {a2:g} and {a3:g} m"),
            "program-hypotheses": Proposition(bool(any(all(f.values()) for f in fits.values())),
                                              f"panels each program would draw with the printed axis: {said}")}


def _ev_eqs(st: Mapping[str, object]) -> Evidence:
    """``shi-eqs``: the equations are not in the text (the reason is in the claim file)."""
    return Unverifiable("see the record's reason")


def _ev_metric(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-metric``: the mean-square error (Fig. 4's axis) and, literally, the covariance of the two series."""
    t1, t2 = st["t1"], st["t2"]
    ls, x2 = sc.register("least squares", t1, sc.truth(t1), t2, 1.0), sc.truth(t2)
    cov, cov_shift = float(np.cov(ls, x2)[0, 1]), float(np.cov(ls + 100.0, x2)[0, 1])
    mse, mse_shift = float(np.mean((ls - x2) ** 2)), float(np.mean((ls + 100.0 - x2) ** 2))
    return {"primary": Proposition(bool(mse_shift > mse), f"a 100 m offset raises the MSE from {mse:.2f} to "
                                                          f"{mse_shift:.0f} m²: it measures accuracy"),
            "literal-covariance": Proposition(bool(not np.isclose(cov, cov_shift)),
                                              f"a 100 m offset leaves the covariance unchanged ({cov:.0f} m²)")}


def _ev_interp_vs_ls(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-interp-vs-ls``: two-point interpolation against least squares."""
    mc = st["mc"]
    t1, t2 = st["t1"], st["t2"]
    nf = {n: sc.noise_free_mse(n, t1, t2) for n in (TWO, EXTRAP, "least squares")}
    return {"primary": _c(mc, EXTRAP, "least squares"),
            "interpolation": _c(mc, TWO, "least squares"),
            "noise-free": Conjunction((("interpolation", Proposition(bool(nf[TWO] < nf["least squares"]),
                                                                     f"noise-free MSE {nf[TWO]:.4f} vs "
                                                                     f"{nf['least squares']:.4f} m²")),
                                       ("extrapolation", Proposition(bool(nf[EXTRAP] < nf["least squares"]),
                                                                     f"noise-free MSE {nf[EXTRAP]:.4f} vs "
                                                                     f"{nf['least squares']:.4f} m²")))),
            **_noise_levels(st, EXTRAP, "least squares"),
            **{"interpolation-" + k: v for k, v in _noise_levels(st, TWO, "least squares").items()},
            **_stress(st, EXTRAP, "least squares"),
            "quadratic-global": _c(mc, TWO, QLS),
            "quadratic-local": _c(mc, TWO, LOCAL_QLS),
            "quadratic-causal": _c(mc, EXTRAP, "quadratic least squares (causal)"),
            "integer-ratio": _c(st["robust"]["integer-ratio"], TWO, "least squares"),  # type: ignore[index]
            "cv-integer-ratio": _c(st["cv_integer"], TWO, "least squares")}


def _ev_curve_fitting(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-curve-fitting``: a quadratic fitted by least squares against the straight line (and locally, look-ahead)."""
    mc, qc = st["mc"], "quadratic least squares (causal)"
    return {"primary": _c(mc, qc, "least squares"), "local-look-ahead": _c(mc, LOCAL_QLS, TWO),
            "last-three": _c(st["s3_fair"][float(st["sigma"])], "three-point extrapolation",  # type: ignore[index]
                             "least squares"),
            "manoeuvre-stop": _c(st["stress"]["manoeuvre-stop"], qc, "least squares", cond="manoeuvre-stop"),  # type: ignore[index]
            "manoeuvre-stop-local": _c(st["stress"]["manoeuvre-stop"], LOCAL_QLS, TWO,  # type: ignore[index]
                                       cond="manoeuvre-stop")}


def _ev_kalman_s3(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-kalman-s3``: the §3 Kalman prediction against the raw samples (both causal)."""
    mc, pc = st["mc"], st["s3_pc"]
    out: dict[str, Evidence] = {
        "primary": Comparison(st["s3_period"].per_run[S3], mc.per_run[EXTRAP], S3, EXTRAP, "less", MSE,  # type: ignore[attr-defined]
                              seed=mc.seed),  # type: ignore[attr-defined]
        "period-unchanged": _c(mc, S3, EXTRAP),  # type: ignore[arg-type]
        **{_key(s): _c(pc[_key(s)], S3, EXTRAP) for s in SIGMAS_ALT}}  # type: ignore[index]
    for s, m in st["s3_fair"].items():  # type: ignore[attr-defined]
        out["three-point-baseline-" + _key(s)] = _c(m, S3, "three-point extrapolation")
    for k, m in st["s3"].items():  # type: ignore[attr-defined]
        out[k] = _c(m, S3, EXTRAP)
    for k in ("manoeuvre-stop", "manoeuvre-reverse", "manoeuvre-stop-tuned"):
        out[k] = _c(pc[k], S3, EXTRAP, cond=k)  # type: ignore[index]
    return out


def _ev_three_noise(st: Mapping[str, object]) -> dict[str, Evidence]:
    r"""``shi-three-noise``: is three-point interpolation comparatively (比较) more affected by noise? (exact, R9)

    The noise-added MSE of a fixed-weight method is exactly :math:`g\sigma^2` and its total expected MSE
    :math:`b + g\sigma^2` (eq. reg-mse), so every reading is judged on the closed form with a zero-width interval
    (:class:`~fusion.book.exact.ExactComparison`). A run's MSE minus :math:`b` still holds the zero-mean cross term
    :math:`2 b_k a_k^\top v`, whose spread grows with :math:`\sigma` while the signal grows with :math:`\sigma^2`:
    at 0.1 and 0.3 m a Monte-Carlo interval of 1000 runs cannot resolve the 15 % the closed form gives exactly.
    """
    t1, t2, s = st["t1"], st["t2"], float(st["sigma"])
    g = {n: sc.noise_gain(n) for n in ("three-point", TWO)}
    between = t2[~np.isin(t2, t1)]          # the instants where interpolation happens (the others are samples)
    gi = {n: sc.mse_coefficients(n, s, t_dst=between)[1] for n in ("three-point", TWO)}
    gx = {n: sc.mse_coefficients(n, s, t_dst=t2[1:])[1] for n in ("three-point extrapolation", EXTRAP)}
    nam = "noise-added MSE gσ² (m², exact)"
    three, two = "three-point interpolation", "two-point interpolation"

    def added(sig: float) -> ExactComparison:
        return ExactComparison(g["three-point"] * sig**2, g[TWO] * sig**2, three, two, "greater", nam)

    def total(sig: float) -> ExactComparison:
        return ExactComparison(sc.expected("three-point", sig), sc.expected(TWO, sig), three, two, "greater",
                               "E[MSE] = b + gσ² (m², exact)")

    return {"primary": added(s),
            "amplifies": ExactComparison(g["three-point"] * s**2, s**2, three, "a raw sample (σ²)", "greater", nam),
            "interpolating-instants": ExactComparison(gi["three-point"] * s**2, gi[TWO] * s**2, three, two, "greater",
                                                      nam + f", the {between.size} instants between samples"),
            "total-mse": total(s),
            "total-mse-sigma-3": total(3.0),
            "extrapolation": Conjunction((
                ("three-point", Proposition(bool(gx["three-point extrapolation"] > 1.0),
                                            f"g = {gx['three-point extrapolation']:.4f}")),
                ("against two-point", Proposition(bool(gx["three-point extrapolation"] > gx[EXTRAP]),
                                                  f"g = {gx['three-point extrapolation']:.4f} vs {gx[EXTRAP]:.4f}"))))}


def _ev_improved(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-improved`` (headline): the improved method against two-point interpolation."""
    out: dict[str, Evidence] = {"primary": _c(st["mc"], IMPROVED, TWO), **_noise_levels(st, IMPROVED, TWO),
                                "real-time": _c(st["realtime"], CAUSAL_IMPROVED, EXTRAP)}
    stress = {k for k, *_ in robustness_readings(float(st["sigma"]), st["t2"]) if k.startswith(("latency", "manoeuvre"))}
    for k, m in st["robust"].items():  # type: ignore[attr-defined]
        out[k] = _c(m, IMPROVED, TWO, cond=k if k in stress else "")
    return out


def _ev_improved_fair(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-improved-fair`` (the book's question): the improved method against the same information's best use."""
    mc = st["mc"]
    return {"primary": _c(mc, IMPROVED, FIXED_LAG),
            "quadratic-global": _c(mc, IMPROVED, QLS),
            "quadratic-local": _c(mc, IMPROVED, LOCAL_QLS),
            "rts": _c(mc, IMPROVED, "RTS smoother (whole record)"),
            "spline": _c(mc, IMPROVED, "cubic spline (whole record)"),
            "real-time-s3": _c(mc, CAUSAL_IMPROVED, S3),
            "real-time-quadratic": _c(mc, CAUSAL_IMPROVED, "quadratic least squares (causal)"),
            **_stress(st, IMPROVED, FIXED_LAG),
            **{f"{k}-global": _c(st["stress"][k], IMPROVED, QLS, cond=k)  # type: ignore[index]
               for k in ("manoeuvre-stop", "manoeuvre-reverse")},
            "manoeuvre-stop-tuned": _c(st["stress_tuned"], IMPROVED, FIXED_LAG, cond="manoeuvre-stop-tuned")}


#: Multiplications and divisions of one step of the constant-acceleration filter (3 states, dense 3 × 3 matrices, a
#: scalar position measurement): the prediction F x (9) and F P Fᵀ (2 × 27); the update K = P Hᵀ / S (3 divisions),
#: x + K ν (3) and P − K (H P) (9); the state alone predicted to an instant (F x, no covariance); one three-point
#: (Lagrange) evaluation: three weights of two products and one division each, and the three-term sum.
KF_PREDICT_OPS, KF_UPDATE_OPS, STATE_PREDICT_OPS, THREE_POINT_OPS = 63, 15, 9, 12

#: Multiplications and divisions of one three-point evaluation whose weights are precomputed (the three-term sum),
#: and of computing one set of weights (three weights of two products and one division each).
THREE_POINT_PRECOMPUTED_OPS, THREE_POINT_WEIGHTS_OPS = 3, 9

#: Building the transition matrix for one step length T (T² and its half).
TRANSITION_OPS = 2


def structured_ops() -> dict[str, int]:
    r"""Multiplications and divisions of one step of the constant-acceleration filter when the structure is used.

    Counted from the matrices' patterns, not by hand: :math:`F` is upper triangular with ones on the diagonal and
    two other distinct entries (:math:`T`, :math:`T^2/2`; a product by 0 or 1 is free), :math:`P` is symmetric (only
    its upper triangle is computed) and :math:`H = [1\;0\;0]`. The prediction :math:`F x` and
    :math:`F P F^\top` (:math:`A = F P`, only the entries of :math:`A` the upper triangle of :math:`A F^\top`
    needs); the update :math:`K = P H^\top / S` (3 divisions), :math:`x + K\nu` (3) and :math:`P - K (H P)`
    (upper triangle, 6); the state alone predicted (:math:`F x`).

    Returns
    -------
    dict
        ``predict``, ``update``, ``state`` (operations).
    """
    gen = np.array([[0, 1, 1], [0, 0, 1], [0, 0, 0]], dtype=bool)    # F's entries other than 0 and 1
    nz = np.triu(np.ones((3, 3), dtype=bool))                          # F's non-zero entries
    state = int(gen.sum())                                             # F x: one product per general entry
    upper = np.triu(np.ones((3, 3), dtype=bool))
    need_a = np.zeros((3, 3), dtype=bool)
    stage2 = 0
    for i, j in zip(*np.nonzero(upper)):                               # (A Fᵀ)_ij = Σ_k A_ik F_jk
        need_a[i, nz[j]] = True
        stage2 += int(gen[j].sum())
    stage1 = sum(int(gen[i].sum()) for i, _ in zip(*np.nonzero(need_a)))   # A_ik = Σ_l F_il P_lk
    update = 3 + 3 + int(upper.sum())
    return {"predict": state + stage1 + stage2, "update": update, "state": state}


def cost_count(t1: ArrayLike, t2: ArrayLike) -> dict[str, int]:
    """What each Kalman route computes over the record: filter steps and distinct filter periods.

    The §3 method changes the filter period at every registration instant (it steps to the instant, then on to
    the next sample); the improved method of §4 filters at the sampling period only and evaluates a three-point
    formula per instant. A step with a new period needs a new transition matrix and driving noise.

    Parameters
    ----------
    t1, t2 : array_like
        Sample times and registration instants (s).

    Returns
    -------
    dict
        ``s3_steps``, ``improved_steps`` (filter steps), ``s3_periods``, ``improved_periods`` (distinct step
        lengths, to 1e-9 s), ``three_point_evals`` (formula evaluations of the improved method), and the
        multiplications and divisions over the record (``KF_PREDICT_OPS`` and the other module constants):
        ``improved_ops``, ``s3_ops``
        (the period changed: a full prediction to each instant between samples, the filter going on from there)
        and ``s3_unchanged_ops`` (the period kept: the state alone predicted to those instants); the other
        counting conventions: ``improved_ops_weights`` (dense, each distinct set of three-point weights computed
        once, ``weight_sets``, and each evaluation a three-term sum), ``improved_ops_structured`` and
        ``s3_ops_structured`` (the filter's structure used, ``structured_ops``; the transition matrix built
        once per distinct period; the improved method evaluates the formula only at the
        ``three_point_evals_between`` instants between samples, as §3 predicts only there) and
        ``improved_ops_structured_weights`` (both), with ``ops_step_structured`` and ``ops_predict_structured``.
    """
    t1, t2 = np.asarray(t1, dtype=float), np.asarray(t2, dtype=float)
    grid = np.union1d(t1, t2[(t2 > t1[0]) & (t2 < t1[-1])])
    between = ~np.isin(t2, t1) & (t2 > t1[0]) & (t2 < t1[-1])
    off = int(np.sum(between))   # instants between samples
    n = int(t1.size - 1)
    s3_periods = int(np.unique(np.round(np.diff(grid), 9)).size)
    impr_periods = int(np.unique(np.round(np.diff(t1), 9)).size)

    def patterns(q: np.ndarray) -> int:
        """Distinct sets of three-point weights: the nodes' offsets from the instant (to 1e-9 s)."""
        j = np.clip(np.searchsorted(t1, q, side="right") - 1, 1, t1.size - 2)
        return int(np.unique(np.round(t1[np.stack([j - 1, j, j + 1], axis=1)] - q[:, None], 9), axis=0).shape[0])

    so = structured_ops()
    step, s_step = KF_PREDICT_OPS + KF_UPDATE_OPS, so["predict"] + so["update"]
    return {"s3_steps": int(grid.size - 1), "improved_steps": n,
            "s3_periods": s3_periods, "improved_periods": impr_periods,
            "three_point_evals": int(t2.size), "three_point_evals_between": off,
            "weight_sets": patterns(t2), "weight_sets_between": patterns(t2[between]),
            "improved_ops": n * step + int(t2.size) * THREE_POINT_OPS,
            "s3_ops": n * step + off * KF_PREDICT_OPS,
            "s3_unchanged_ops": n * step + off * STATE_PREDICT_OPS,
            "improved_ops_weights": n * step + int(t2.size) * THREE_POINT_PRECOMPUTED_OPS
                                    + patterns(t2) * THREE_POINT_WEIGHTS_OPS,
            "improved_ops_structured": n * s_step + off * THREE_POINT_OPS + impr_periods * TRANSITION_OPS,
            "improved_ops_structured_weights": n * s_step + off * THREE_POINT_PRECOMPUTED_OPS
                                               + patterns(t2[between]) * THREE_POINT_WEIGHTS_OPS
                                               + impr_periods * TRANSITION_OPS,
            "s3_ops_structured": n * s_step + off * so["predict"] + s3_periods * TRANSITION_OPS,
            "ops_step_structured": s_step, "ops_predict_structured": so["predict"]}


def _ev_simplifies(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-simplifies``: fewer filter steps and one period, and the §3 method's accuracy kept."""
    mc, cc = st["mc"], cost_count(st["t1"], st["t2"])
    s3_pc = st["s3_period"].per_run[S3]  # type: ignore[attr-defined]
    ops = (f"multiplications and divisions over the record ({cc['improved_steps']} filter steps at "
           f"{cc['improved_periods']} period and {cc['three_point_evals']} three-point evaluations")
    simpler = ExactComparison(cc["improved_ops"], cc["s3_ops"], "improved (§4)", "§3, period changed", "less",
                              ops + f"; §3: {cc['s3_steps']} steps at {cc['s3_periods']} periods)")
    same_grid = ExactComparison(cc["improved_ops"], cc["s3_unchanged_ops"], "improved (§4)", "§3, period kept", "less",
                                ops + f"; §3: {cc['improved_steps']} steps and {cc['s3_steps'] - cc['improved_steps']}"
                                      " state predictions)")

    def kept(a: str) -> Comparison:
        return Comparison(mc.per_run[a], s3_pc, a, S3 + ", period changed", "less", MSE, seed=mc.seed)  # type: ignore[attr-defined]

    def counted(a: str, b: str, how: str) -> ExactComparison:
        return ExactComparison(cc[a], cc[b], "improved (§4)", "§3, period changed", "less",
                               f"multiplications and divisions over the record, {how}")

    acc = ("keeps the accuracy", kept(IMPROVED))
    return {"primary": Conjunction((("simpler", simpler), acc)),
            "ops-dense-weights": Conjunction((("simpler", counted(
                "improved_ops_weights", "s3_ops", f"dense, {cc['weight_sets']} sets of three-point weights "
                                                  "computed once")), acc)),
            "ops-structured": Conjunction((("simpler", counted(
                "improved_ops_structured", "s3_ops_structured",
                f"structure used ({cc['ops_step_structured']} per step, {cc['ops_predict_structured']} per "
                f"prediction), {cc['three_point_evals_between']} three-point evaluations")), acc)),
            "ops-structured-weights": Conjunction((("simpler", counted(
                "improved_ops_structured_weights", "s3_ops_structured",
                f"structure used, {cc['weight_sets_between']} set of three-point weights computed once")), acc)),
            "s3-period-unchanged": Conjunction((("simpler", same_grid),
                                                ("keeps the accuracy", _c(mc, IMPROVED, S3)))),  # type: ignore[arg-type]
            "real-time": Conjunction((("simpler", simpler), ("keeps the accuracy", kept(CAUSAL_IMPROVED))))}


def _ev_few_restrictions(st: Mapping[str, object]) -> Evidence:
    """``shi-few-restrictions``: 'few restrictions on its application' names no comparison (reason in the claim file)."""
    return Unverifiable("see the record's reason")


def _ev_ls_info(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-ls-info``: least squares fused with sensor 2 (against fusing the stale sample, and sensor 2 alone), and
    registered (against no registration, the raw sample it replaces and two-point extrapolation)."""
    mc, t1, t2 = st["mc"], st["t1"], st["t2"]
    nf = {n: sc.noise_free_mse(n, t1, t2) for n in ("least squares", EXTRAP)}

    def unreg(m: sc.MonteCarlo) -> Comparison:
        return Comparison(m.per_run["least squares"], unregistered_runs(m, t1, t2), "least squares",
                          UNREGISTERED, "less", MSE, seed=m.seed)

    rob = st["robust"]["integer-ratio"]  # type: ignore[index]
    t2_6 = sc.instants(6.0)[1]
    dec = affine_decomposition(sc.registrar("least squares", t1, t2_6, 1.0, window=6.0), sc.truth(t1))
    b6 = float(np.mean((dec.f0 - sc.truth(t2_6)) ** 2))
    fr = st["fusion"]
    fu, fm = fr.per_run, "fused MSE at sensor-2 instants (m²)"  # type: ignore[attr-defined]

    def fused(b: str) -> Comparison:
        return Comparison(fu["fused, least squares"], fu[b], "fused, least squares", b, "less", fm,
                          seed=fr.seed)  # type: ignore[attr-defined]

    return {"primary": fused("fused, unregistered (last sample)"), "sensor-2-alone": fused("sensor 2 alone"),
            "registration-mse": unreg(mc), **{_key(s): unreg(m) for s, m in st["sweep"].items()},  # type: ignore[attr-defined]
            "replaced-precision": Comparison(rob.per_run["least squares"] - b6, rob.per_run[TWO], "least squares",
                                             "the raw sample it replaces", "less", "noise-added MSE (m²)",
                                             seed=rob.seed),
            "replaced-mse": Comparison(rob.per_run["least squares"], rob.per_run[TWO], "least squares",
                                       "the raw sample it replaces", "less", MSE, seed=rob.seed),
            "vs-extrapolation": _c(mc, "least squares", EXTRAP),
            "cv-integer-ratio": _c(st["cv_integer"], "least squares", EXTRAP),
            "precision-only": Comparison(mc.per_run["least squares"] - nf["least squares"],
                                         mc.per_run[EXTRAP] - nf[EXTRAP], "least squares", EXTRAP, "less",
                                         "noise-added MSE (m²)", seed=mc.seed)}


def _ev_validated(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-validated``: both classic methods on the noise-free scenario against no registration (exact, R9), the
    book's 1 % and below-noise thresholds, and the source's own figures (shi-figs23)."""
    t1, t2, s = st["t1"], st["t2"], float(st["sigma"])
    x2 = sc.truth(t2)
    reg = {n: sc.register(n, t1, sc.truth(t1), t2, s) for n in (TWO, "least squares")}
    err = {n: float(np.abs(v - x2).max()) for n, v in reg.items()}
    stale = float(np.mean((sc.truth(t1[np.searchsorted(t1, t2, side="right") - 1]) - x2) ** 2))
    worst = max(err.values())
    nf = "noise-free registration MSE (m², exact)"
    return {"primary": Conjunction(tuple(
                (n, ExactComparison(float(np.mean((v - x2) ** 2)), stale, n, UNREGISTERED, "less", nf))
                for n, v in reg.items())),
            "one-percent": Proposition(bool(worst < 0.01 * float(x2.max())),
                                       f"largest noise-free errors {err[TWO]:.2f} m and {err['least squares']:.2f} m, "
                                       f"against {float(x2.max()):.0f} m covered"),
            "below-noise": Proposition(bool(worst < s), f"largest noise-free errors {err[TWO]:.2f} m and "
                                                        f"{err['least squares']:.2f} m against σ_x = {s:g} m"),
            "published-figures": _ev_figs23(st)["primary"]}


def _ev_fig4_axis(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-fig4-axis``: cannot be checked without the noise level (the reasons are in the claim file)."""
    why = "the noise level is not given (the reading states what the chapter computed at 1 m)"
    return {"primary": Unverifiable("see the record's reason"), "rmse": Unverifiable(why),
            "per-instant": Unverifiable(why)}


def _ev_fusion(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-fusion``: fusing sensor 1 registered by the improved method with sensor 2."""
    fr = st["fusion"]
    fu, m = fr.per_run, "fused MSE at sensor-2 instants (m²)"  # type: ignore[attr-defined]
    impr, two, alone = f"fused, {IMPROVED}", f"fused, {TWO}", "sensor 2 alone"

    def cmp(a: str, b: str) -> Comparison:
        return Comparison(fu[a], fu[b], a, b, "less", m, seed=fr.seed)  # type: ignore[attr-defined]

    return {"primary": cmp(impr, "fused, unregistered (last sample)"), "two-point": cmp(two, "fused, unregistered (last sample)"),
            "improved-vs-two-point": cmp(impr, two), "sensor-2-alone": cmp(impr, alone)}


#: Noise level of the primary readings (m): the source gives none.
PRIMARY_SIGMA = 1.0


@functools.lru_cache(maxsize=2)
def cached_study(seed: int, runs: int) -> dict[str, object]:
    """:func:`study` of the source's scenario at :data:`PRIMARY_SIGMA`, with the fusion runs (seed ``seed + 49``),
    computed once per ``(seed, runs)``: the chapter and every evidence function share it.

    Parameters
    ----------
    seed, runs : int
        As in :func:`study`.

    Returns
    -------
    dict
        :func:`study`'s keys and ``fusion`` (:func:`fusion.scenarios.time_registration.fusion_runs` of the
        improved method, two-point interpolation, the §3 prediction and least squares).
    """
    t1, t2 = sc.instants()
    st = study(t1, t2, PRIMARY_SIGMA, runs, seed)
    st["fusion"] = sc.fusion_runs([IMPROVED, TWO, S3, "least squares"], PRIMARY_SIGMA, runs, seed + 49)
    return st


#: Record id -> the function that computes every reading's evidence from the study.
_RECORDS = {"shi-few-restrictions": _ev_few_restrictions, "shi-samples": _ev_samples, "shi-figs23": _ev_figs23, "shi-eqs": _ev_eqs, "shi-metric": _ev_metric,
            "shi-interp-vs-ls": _ev_interp_vs_ls, "shi-curve-fitting": _ev_curve_fitting,
            "shi-kalman-s3": _ev_kalman_s3, "shi-three-noise": _ev_three_noise,
            "shi-improved": _ev_improved, "shi-improved-fair": _ev_improved_fair, "shi-simplifies": _ev_simplifies,
            "shi-ls-info": _ev_ls_info, "shi-validated": _ev_validated, "shi-fig4-axis": _ev_fig4_axis,
            "shi-fusion": _ev_fusion}


def ledger_evidence(seed: int, runs: int) -> dict[str, object]:
    """The evidence of every record of chapter 07, by record id (for :func:`fusion.book.claims.build_ledger`).

    Parameters
    ----------
    seed, runs : int
        Of :func:`cached_study`.

    Returns
    -------
    dict
        Record id -> {reading key -> Evidence} (or one Evidence for a record without readings).
    """
    st = cached_study(seed, runs)
    return {rid: fn(st) for rid, fn in _RECORDS.items()}


def _reading(rid: str, settings: Mapping[str, object] | None, seed: int, runs: int) -> Evidence:
    """One reading's evidence (``settings["reading"]``, default the primary) of record ``rid``."""
    ev = _RECORDS[rid](cached_study(seed, runs))
    key = dict(settings or {}).get("reading", "primary")
    if not isinstance(ev, Mapping):
        if key != "primary":
            raise ValueError(f"settings: record {rid} has no reading {key!r}")
        return ev
    if key not in ev:
        raise ValueError(f"settings: record {rid} has no reading {key!r}; it has {sorted(ev)}")
    return ev[key]


def ev_samples(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-samples``: a reading's evidence (settings ``{"reading": key}``) for :func:`fusion.book.claims.evaluate`."""
    return _reading("shi-samples", settings, seed, runs)


def ev_figs23(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-figs23``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-figs23", settings, seed, runs)


def ev_eqs(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-eqs``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-eqs", settings, seed, runs)


def ev_metric(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-metric``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-metric", settings, seed, runs)


def ev_interp_vs_ls(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-interp-vs-ls``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-interp-vs-ls", settings, seed, runs)


def ev_curve_fitting(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-curve-fitting``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-curve-fitting", settings, seed, runs)


def ev_kalman_s3(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-kalman-s3``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-kalman-s3", settings, seed, runs)


def ev_three_noise(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-three-noise``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-three-noise", settings, seed, runs)


def ev_improved(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-improved``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-improved", settings, seed, runs)


def ev_improved_fair(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-improved-fair``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-improved-fair", settings, seed, runs)


def ev_simplifies(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-simplifies``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-simplifies", settings, seed, runs)


def ev_ls_info(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-ls-info``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-ls-info", settings, seed, runs)


def ev_validated(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-validated``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-validated", settings, seed, runs)


def ev_fig4_axis(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-fig4-axis``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-fig4-axis", settings, seed, runs)


def ev_few_restrictions(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-few-restrictions``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-few-restrictions", settings, seed, runs)


def ev_fusion(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-fusion``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-fusion", settings, seed, runs)


def keep(store: dict[str, object], values: Mapping[str, object]) -> Mapping[str, object]:
    """Add ``values`` to ``store`` and return them: the chapter glues a dict and keeps it for the claim texts.

    Parameters
    ----------
    store : dict
        The chapter's glue values so far (changed in place).
    values : mapping
        Values to glue.

    Returns
    -------
    mapping
        ``values``.
    """
    store.update(values)
    return values


def stress_table(sigma: float, names: Sequence[str] = STUDY_METHODS) -> pd.DataFrame:
    """Exact E[MSE] (m²) of every method on the source's truth and under each unmodelled change (rule R6).

    Every method runs under the same change: the acceleration stops or reverses at 20 s, or sensor 1's
    samples are taken 10 ms before (or after) their stamps; the Kalman methods are also shown with a
    driving noise that allows for manoeuvres (q_v = 1, q_a = 0.1 per step).

    Parameters
    ----------
    sigma : float
        Noise level (m), also assumed by the filters.
    names : sequence of str
        Methods (keys of :data:`fusion.scenarios.time_registration.METHODS`).

    Returns
    -------
    DataFrame
        Index: method; columns: information used, the source's truth, each change of :data:`STRESS`, and the
        two manoeuvres with the manoeuvre tuning (Kalman methods only, else NaN); 2 decimals.
    """
    rows = {}
    for n in names:
        r: dict[str, object] = {"information": sc.METHODS[n], "source's truth": sc.expected(n, sigma)}
        for k, kw in STRESS.items():
            r[k] = sc.expected(n, sigma, **kw)  # type: ignore[arg-type]
        kal = "Kalman" in n or "smoother" in n or n.startswith("improved") or n.startswith("causal")
        for k in ("manoeuvre-stop", "manoeuvre-reverse"):
            r[k + ", q_v = 1, q_a = 0.1"] = (sc.expected(n, sigma, q_v=1.0, q_a=0.1, **STRESS[k])  # type: ignore[arg-type]
                                             if kal else float("nan"))
        rows[n] = r
    out = pd.DataFrame(rows).T.infer_objects()
    out.index.name = "method"
    num = out.select_dtypes("number").columns
    out[num] = out[num].round(2) + 0.0
    return out.sort_values(["information", "source's truth"], kind="stable")


def _true_state(t: np.ndarray, a_after: float | None, t_change: float = 20.0) -> np.ndarray:
    """True [x, v, a] (n, 3) of :func:`fusion.scenarios.time_registration.manoeuvre_truth` at times ``t``."""
    v0, a0 = float(sc.SCENARIO["v0"]), float(sc.SCENARIO["a"])
    after = (t > t_change) if a_after is not None else np.zeros(t.shape, dtype=bool)
    a = np.where(after, 0.0 if a_after is None else a_after, a0)
    v = np.where(after, v0 + a0 * t_change + a * (t - t_change), v0 + a0 * t)
    return np.column_stack([sc.manoeuvre_truth(t, a_after), v, a])


def nees_table(sigma: float, runs: int, seed: int) -> pd.DataFrame:
    r"""Filter consistency: the normalised estimation error squared (NEES) of the chapter's Kalman filter.

    At each sample :math:`\epsilon_i = \mathbf e_i^\top P_i^{-1}\mathbf e_i`, :math:`\mathbf e_i` the filtered
    state's error against the true [x, v, a]; for a consistent filter its mean over runs is 3 (the state's
    dimension) and lies in the two-sided 95 % chi-square interval :math:`[\chi^2_{3R}(0.025), \chi^2_{3R}(0.975)]/R`
    (Bar-Shalom, Li & Kirubarajan 2001, §5.4).

    Parameters
    ----------
    sigma : float
        Noise level (m), also assumed by the filter.
    runs : int
        Runs (R).
    seed : int

    Returns
    -------
    DataFrame
        Index (truth, tuning); columns: mean NEES over runs and samples, largest mean over runs at a sample,
        share of samples whose mean lies inside the 95 % interval (3 decimals).
    """
    from scipy import stats

    from fusion import registration as reg

    t1, _ = sc.instants()
    rng = np.random.default_rng(seed)
    noise = sigma * rng.standard_normal((int(runs), t1.size))
    lo, hi = (stats.chi2.ppf(q, 3 * runs) / runs for q in (0.025, 0.975))
    rows = {}
    for truth_label, a_after in (("source's truth", None), ("acceleration 2 → 0 m/s² at 20 s", 0.0)):
        x = _true_state(t1, a_after)
        for tune_label, (qv, qa) in (("q_v = 10⁻², q_a = 10⁻³", (sc.Q_V, sc.Q_A)), ("q_v = 1, q_a = 0.1", (1.0, 0.1))):
            fs = reg.kalman_runs(t1, x[:, 0] + noise, sigma, qv, qa)
            e = fs.x - x                                          # (runs, n, 3)
            eps = np.einsum("rni,nij,rnj->rn", e, np.linalg.inv(fs.P), e).mean(axis=0)
            rows[(truth_label, tune_label)] = {"mean NEES": float(eps.mean()), "largest at a sample": float(eps.max()),
                                               "share inside 95 % interval": float(np.mean((eps >= lo) & (eps <= hi)))}
    out = pd.DataFrame(rows).T
    out.index.names = ["truth", "tuning"]
    return out.round(3)


def blue_whole_record(sigma: float) -> float:
    r"""Exact E[MSE] (m²) of the best linear unbiased registration with the whole record, on the source's truth.

    The truth is one quadratic over the window, so least squares of a quadratic through every sample is the
    best linear unbiased estimate of :math:`x(t_k)` (Gauss-Markov): a lower bound for every linear unbiased
    method, whatever information it uses (the global quadratic through every past sample and the next one is the
    same bound with the improved method's information).

    Parameters
    ----------
    sigma : float
        Noise level (m), > 0.

    Returns
    -------
    float
    """
    from functools import partial

    from fusion import registration as reg

    t1, t2 = sc.instants()
    fit = partial(reg.quadratic_ls, t1, t_query=t2, lookahead=t1.size)
    return float(reg.expected_mse(fit, sc.truth(t1), sc.truth(t2), sigma))


def cost_values(t1: ArrayLike, t2: ArrayLike, t2_ratio: ArrayLike, sigma: float) -> dict[str, float]:
    """The glue values of the cost and staleness paragraph and the constant-velocity check (chapter bookkeeping).

    Parameters
    ----------
    t1, t2 : array_like
        The sensors' sample instants (s).
    t2_ratio : array_like
        Sensor 2's instants at the integer period ratio (6 s).
    sigma : float
        Measurement noise (m).

    Returns
    -------
    dict
        ``reg_cc_*`` (filter steps, periods and operations of the §3 and §4 routes, :func:`cost_count`), ``reg_ops_*``
        (the operation counts per step), ``reg_stale_min`` /
        ``reg_stale_max`` (m: the last sample taken as simultaneous), ``reg_cv_ls`` / ``reg_cv_extrap`` (exact
        E[MSE] of a constant-velocity target, m²).
    """
    t1, t2 = np.asarray(t1, dtype=float), np.asarray(t2, dtype=float)
    cc = cost_count(t1, t2)
    stale = sc.truth(t2) - sc.truth(t1[np.searchsorted(t1, t2, side="right") - 1])
    cv = {n: sc.expected(n, sigma, t_dst=t2_ratio, window=6.0, a_after=0.0, t_change=0.0)
          for n in (EXTRAP, "least squares")}
    return {"reg_cc_impr_steps": cc["improved_steps"], "reg_cc_s3_steps": cc["s3_steps"],
            "reg_cc_s3_periods": cc["s3_periods"], "reg_cc_impr_ops": cc["improved_ops"], "reg_cc_s3_ops": cc["s3_ops"],
            "reg_cc_s3_unchanged_ops": cc["s3_unchanged_ops"], "reg_ops_step": KF_PREDICT_OPS + KF_UPDATE_OPS,
            "reg_ops_predict": KF_PREDICT_OPS, "reg_ops_state": STATE_PREDICT_OPS, "reg_ops_three": THREE_POINT_OPS,
            "reg_cc_impr_ops_weights": cc["improved_ops_weights"], "reg_cc_impr_ops_struct": cc["improved_ops_structured"],
            "reg_cc_impr_ops_struct_weights": cc["improved_ops_structured_weights"],
            "reg_cc_s3_ops_struct": cc["s3_ops_structured"], "reg_ops_step_struct": cc["ops_step_structured"],
            "reg_ops_predict_struct": cc["ops_predict_structured"], "reg_ops_three_pre": THREE_POINT_PRECOMPUTED_OPS,
            "reg_ops_weights": THREE_POINT_WEIGHTS_OPS, "reg_ops_transition": TRANSITION_OPS,
            "reg_cc_evals_between": cc["three_point_evals_between"],
            "reg_stale_min": float(np.abs(stale).min()),
            "reg_stale_max": float(np.abs(stale).max()), "reg_cv_ls": cv["least squares"], "reg_cv_extrap": cv[EXTRAP]}


def manoeuvre_values(manoeuvre: Mapping[float, Mapping[str, float]], sigma: float) -> dict[str, float]:
    """The glue values of the manoeuvre paragraph (chapter bookkeeping).

    Parameters
    ----------
    manoeuvre : mapping
        Acceleration after the change (m/s²) → method → exact E[MSE] (m²), as the chapter computes it.
    sigma : float
        Measurement noise (m).

    Returns
    -------
    dict
        ``reg_man_*``: the improved method, two-point and three-point when the acceleration stops, the improved
        method when it reverses, and the improved method with a manoeuvre-allowing driving noise (q_v = 1, q_a = 0.1).
    """
    return {"reg_man_impr": manoeuvre[0.0][IMPROVED], "reg_man_two": manoeuvre[0.0][TWO],
            "reg_man_three": manoeuvre[0.0]["three-point"], "reg_man_impr_neg": manoeuvre[-2.0][IMPROVED],
            "reg_man_impr_q": sc.expected(IMPROVED, sigma, a_after=0.0, q_v=1.0, q_a=0.1)}


def latency_values(be: Mapping[float, float], sigma: float) -> dict[str, float]:
    """Break-even latencies in milliseconds at ``sigma`` and over the noise levels run (chapter bookkeeping).

    Parameters
    ----------
    be : mapping
        Noise level (m) → break-even latency (s).
    sigma : float
        The chapter's noise level (a key of ``be``).

    Returns
    -------
    dict
        ``reg_be_ms``, ``reg_be_lo_ms``, ``reg_be_hi_ms``.
    """
    return {"reg_be_ms": 1e3 * be[sigma], "reg_be_lo_ms": 1e3 * min(be.values()), "reg_be_hi_ms": 1e3 * max(be.values())}


def gain_values(values: Mapping[str, float], closed: pd.DataFrame) -> dict[str, float]:
    """Three-point's noise-gain excess over two-point (%) and extrapolation's closed-form constants.

    Parameters
    ----------
    values : mapping
        The chapter's glue values so far, holding ``reg_gain_three`` and ``reg_gain_two``.
    closed : DataFrame
        The closed-form table (rows: methods; columns ``b (m²)`` and ``g``).

    Returns
    -------
    dict
        ``reg_gain_excess_pct``; ``reg_gain_three_between``, ``reg_gain_two_between``, ``reg_gain_between_pct`` and
        ``reg_n_between`` (the same gains at the instants between samples only); ``reg_cf_extrap_b``,
        ``reg_cf_extrap_g``.
    """
    t1, t2 = sc.instants()
    between = t2[~np.isin(t2, t1)]
    gi = {n: sc.mse_coefficients(n, 1.0, t_dst=between)[1] for n in ("three-point", TWO)}
    return {"reg_gain_excess_pct": 100 * (values["reg_gain_three"] / values["reg_gain_two"] - 1),
            "reg_gain_three_between": gi["three-point"], "reg_gain_two_between": gi[TWO],
            "reg_gain_between_pct": 100 * (gi["three-point"] / gi[TWO] - 1), "reg_n_between": int(between.size),
            "reg_cf_extrap_b": closed.loc[EXTRAP, "b (m²)"], "reg_cf_extrap_g": closed.loc[EXTRAP, "g"]}


def noise_gain_by_instant(t1: ArrayLike, t2: ArrayLike) -> pd.DataFrame:
    r"""Noise gain :math:`\lVert a_k\rVert^2` of three-point and two-point interpolation at each instant.

    At an instant that is a sensor-1 sample time both return the sample (gain 1); between samples the weights
    are (−1/8, 3/4, 3/8) and (1/2, 1/2) at mid-interval, gains 46/64 and 1/2. The record's gain
    :math:`g` is the mean over the instants.

    Parameters
    ----------
    t1, t2 : array_like
        Sample times and registration instants (s).

    Returns
    -------
    DataFrame
        Index: instant (s); columns: whether it is a sample time, the two gains and three-point's excess (%).
    """
    t1, t2 = np.asarray(t1, dtype=float), np.asarray(t2, dtype=float)
    g = {n: [sc.mse_coefficients(n, 1.0, t_dst=[t])[1] for t in t2] for n in ("three-point", TWO)}
    out = pd.DataFrame({"sample time": np.isin(t2, t1), "g three-point": g["three-point"], "g two-point": g[TWO]},
                       index=pd.Index(t2, name="instant (s)"))
    out["excess (%)"] = 100 * (out["g three-point"] / out["g two-point"] - 1)
    return out


def exact_check(sigma: float) -> pd.DataFrame:
    """The Monte-Carlo primaries of the fixed-weight and Kalman comparisons judged again on their exact E[MSE] (R9).

    Every method compared by a Monte-Carlo record has a closed-form expected MSE (eq. reg-mse, the Kalman filters
    with fixed gains); the records compare per-run MSEs with paired intervals, and this table shows that the exact
    comparison, under the same 5 % margin, gives the same status.

    Parameters
    ----------
    sigma : float
        Measurement noise (m).

    Returns
    -------
    DataFrame
        One row per record: A, B, exact E[MSE] of each (m²), the status of
        :class:`~fusion.book.exact.ExactComparison` ("A less") and the record's status in the stored ledger
        (``book/ledger/shi2023time.json``, from its paired Monte-Carlo runs; for shi-simplifies the record's,
        which needs its accuracy member).
    """
    path = ledger_dir() / "shi2023time.json"
    stored = ({c["id"]: c["status"] for c in json.loads(path.read_text(encoding="utf-8"))["claims"]}
              if path.exists() else {})
    pairs = (("shi-interp-vs-ls", EXTRAP, "least squares", {}), ("shi-kalman-s3", S3, EXTRAP, {"a": PC}),
             ("shi-improved", IMPROVED, TWO, {}), ("shi-improved-fair", IMPROVED, FIXED_LAG, {}),
             ("shi-simplifies (keeps the accuracy)", IMPROVED, S3, {"b": PC}))
    rows = []
    for rid, a, b, kf in pairs:
        ea = sc.expected(a, sigma, kf=kf.get("a"))
        eb = sc.expected(b, sigma, kf=kf.get("b"))
        rows.append({"record": rid, "A": a, "B": b, "exact E[MSE] A (m²)": ea, "exact E[MSE] B (m²)": eb,
                     "exact status (A less)": ExactComparison(ea, eb, a, b, "less", "exact E[MSE] (m²)").status(),
                     "ledger status (Monte Carlo)": stored.get(rid.split(" ")[0], "not in the ledger")})
    return pd.DataFrame(rows).set_index("record")
