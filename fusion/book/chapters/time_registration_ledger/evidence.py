"""Chapter 07 (time registration): the evidence of each record of ``book/claims/shi2023time.yaml``.

Each ``_ev_*`` function computes one record's evidence from the chapter's study
(:func:`~fusion.book.chapters.time_registration_ledger.study`), one Evidence per reading key of the claim
file; every text of the record (claim, readings, assumptions, bound, reason) is in the claim file. The public
``ev_*`` named by the claim file take ``(settings, *, seed, runs)`` (:func:`fusion.book.claims.evaluate`): the
reading is ``settings["reading"]`` and the study is computed once per (seed, runs) (:func:`cached_study`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from fusion import data
from fusion.book._few_runs import runs_first, runs_named
from fusion.book._reader_settings import reads
from fusion.book.chapters.time_registration import (CAUSAL_IMPROVED, FUSION_ALONE, FUSION_UNREGISTERED, IMPROVED, TWO,
                                                     robustness_readings)
from fusion.registration import affine_decomposition
from fusion.book.exact import ExactComparison
from fusion.book.style import METHOD_LABELS
from fusion.book.ledger import Comparison, Conjunction, Evidence, Proposition, Unverifiable
from fusion.scenarios import time_registration as sc
from fusion.scenarios.time_registration import RegMethod
from fusion.book.chapters.time_registration_ledger.costs import cost_count
from fusion.book.chapters.lecture import reading_key, reading_of
from fusion.book.chapters.time_registration_ledger.studies import (EXTRAP, FIXED_LAG, LOCAL_QLS, MSE, QLS, S3, SIGMAS_ALT,
                                                                 UNREGISTERED, _key, cached_study, unregistered_runs)
from fusion.book.chapters.time_registration_ledger.studies import RegistrationStudy
from fusion._counts import seed as check_seed
from fusion._shown import shown

LS = RegMethod.LEAST_SQUARES

__all__ = [
    "ledger_evidence",
    "FIG23_HYPOTHESES",
    "figs23_fits",
]


def _c(m: sc.MonteCarlo, a: str, b: str, claim: str = "less", metric: str = MSE, cond: str = "") -> Comparison:
    return Comparison(m.per_run[a], m.per_run[b], METHOD_LABELS[a], METHOD_LABELS[b], claim, metric, seed=m.seed,  # type: ignore[arg-type]
                      conditions=(cond, cond))


def _noise_levels(st: RegistrationStudy, a: str, b: str, claim: str = "less") -> dict[str, Evidence]:
    return {_key(s): _c(m, a, b, claim) for s, m in st.sweep.items()}


def _stress(st: RegistrationStudy, a: str, b: str, keys: Sequence[str] = ("manoeuvre-stop", "manoeuvre-reverse"),
            claim: str = "less") -> dict[str, Evidence]:
    return {k: _c(st.stress[k], a, b, claim, cond=k) for k in keys}


def _ev_samples(st: RegistrationStudy) -> Evidence:
    """``shi-samples``: how many samples a 5 s sensor can give in 40 s."""
    t1, t2 = st.t1, st.t2
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


# Shortest record (s, exclusive) figs23_fits reads in each direction: a sensor-2 instant (3 s) with two sensor-1
# samples in its window (fast onto slow); two sensor-2 samples (3 s, 8 s) and a sensor-1 time after them (9 s).
_FIGS23_MIN_END = {"fast onto slow": 4.0, "slow onto fast": 9.0}


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

    Raises
    ------
    TypeError
        ``a`` or ``end`` is not a number, or ``direction`` not a str.
    ValueError
        ``a`` is not finite or gives positions beyond the representable range; ``end`` is not finite, not above
        4 s (fast onto slow: a sensor-2 instant, 3 s, with two sensor-1 samples in its window) or 9 s (slow onto
        fast: two sensor-2 samples, 3 s and 8 s, and a sensor-1 time after them), or asks for more samples than a
        record may hold or a fit beyond the work budget (``fusion._limits.MAX_WORK``: from about 5e4 s);
        ``direction`` is not one of the two.
    """
    from fusion.registration import least_squares, two_point
    from fusion._validation import as_array, grid_points, one_of, scalar

    direction = one_of(direction, tuple(_FIGS23_MIN_END), "direction")
    # the floats the reader returns (fuzz 22b, FR6-7: a Decimal was used raw)
    a, end = scalar(a, "a"), scalar(end, "end", lo=_FIGS23_MIN_END[direction], lo_open=True)
    grid_points(end - 1.0, 2.0, "end")  # sensor 1's samples, counted before they are allocated
    t1, t2 = np.arange(1.0, end, 2.0), np.arange(3.0, end - 1.0, 5.0)
    x1, x2 = t1 + a * t1**2 / 2, t2 + a * t2**2 / 2
    as_array(x1, "a and end (the positions they give)")
    fast = direction == "fast onto slow"  # rule 17 by the chapter's rule, named end (fuzz 28b C7: t_query and t)
    sc._registration_work([RegMethod.LEAST_SQUARES], *((t1.size, t2.size) if fast else (t2.size, t1.size)), 1, "end")
    after3 = (least_squares(t1, x1, t2, 5.0) if direction == "fast onto slow"
              else least_squares(t2, x2, t1[t1 >= t2[1]], 10.0))
    top = {"fig2_before_y": x1.max(), "fig2_after_y": two_point(t1, x1, t2).max(),
           "fig3_before_y": max(x1.max(), x2.max()), "fig3_after_y": after3.max()}
    ax = data.SHI2023_AXES.columns
    return {k: bool(0.8 * float(ax[k][0]) < v <= float(ax[k][0])) for k, v in top.items()}


def _ev_figs23(st: RegistrationStudy) -> dict[str, Evidence]:
    """``shi-figs23``: do the registered positions fit under the 'after' axes? (and which program would draw them)"""
    ax = data.SHI2023_AXES.columns
    t1, t2 = st.t1, st.t2
    top2 = float(sc.register(TWO, t1, sc.truth(t1), t2, 1.0).max())          # Fig. 2: two-point interpolation
    top3 = float(sc.register(LS, t1, sc.truth(t1), t2, 1.0).max())  # Fig. 3: least squares
    a2, a3 = float(ax["fig2_after_y"][0]), float(ax["fig3_after_y"][0])
    fits = {label: figs23_fits(a, end, d) for label, a, end, d in FIG23_HYPOTHESES}
    said = "; ".join(f"{label}: {', '.join(k for k, v in f.items() if v) or 'no panel'}" for label, f in fits.items())
    return {"primary": Proposition(bool(top2 <= a2 and top3 <= a3),
                                   f"registered positions reach {top2:.0f} m (two-point, Fig. 2) and {top3:.0f} m "
                                   f"(least squares, Fig. 3; the truth at the last instant: "
                                   f"{float(sc.truth(t2).max()):.0f} m); the 'after' axes stop at {a2:g} and {a3:g} m"),
            "program-hypotheses": Proposition(bool(any(all(f.values()) for f in fits.values())),
                                              f"panels each program would draw with the printed axis: {said}")}


def _ev_eqs(st: RegistrationStudy) -> Evidence:
    """``shi-eqs``: the equations are not in the text (the reason is in the claim file)."""
    return Unverifiable("see the record's reason")


def _ev_metric(st: RegistrationStudy) -> dict[str, Evidence]:
    """``shi-metric``: the mean-square error (Fig. 4's axis) and, literally, the covariance of the two series."""
    t1, t2 = st.t1, st.t2
    ls, x2 = sc.register(LS, t1, sc.truth(t1), t2, 1.0), sc.truth(t2)
    cov, cov_shift = float(np.cov(ls, x2)[0, 1]), float(np.cov(ls + 100.0, x2)[0, 1])
    mse, mse_shift = float(np.mean((ls - x2) ** 2)), float(np.mean((ls + 100.0 - x2) ** 2))
    return {"primary": Proposition(bool(mse_shift > mse), f"a 100 m offset raises the MSE from {mse:.2f} to "
                                                          f"{mse_shift:.0f} m²: it measures accuracy"),
            "literal-covariance": Proposition(bool(not np.isclose(cov, cov_shift)),
                                              f"a 100 m offset leaves the covariance unchanged ({cov:.0f} m²)")}


def _ev_interp_vs_ls(st: RegistrationStudy) -> dict[str, Evidence]:
    """``shi-interp-vs-ls``: two-point interpolation against least squares."""
    mc = st.mc
    t1, t2 = st.t1, st.t2
    nf = {n: sc.noise_free_mse(n, t1, t2) for n in (TWO, EXTRAP, LS)}
    return {"primary": _c(mc, EXTRAP, LS),
            "interpolation": _c(mc, TWO, LS),
            "noise-free": Conjunction((("interpolation", Proposition(bool(nf[TWO] < nf[LS]),
                                                                     f"noise-free MSE {nf[TWO]:.4f} vs "
                                                                     f"{nf[LS]:.4f} m²")),
                                       ("extrapolation", Proposition(bool(nf[EXTRAP] < nf[LS]),
                                                                     f"noise-free MSE {nf[EXTRAP]:.4f} vs "
                                                                     f"{nf[LS]:.4f} m²")))),
            **_noise_levels(st, EXTRAP, LS),
            **{"interpolation-" + k: v for k, v in _noise_levels(st, TWO, LS).items()},
            **_stress(st, EXTRAP, LS),
            "quadratic-global": _c(mc, TWO, QLS),
            "quadratic-local": _c(mc, TWO, LOCAL_QLS),
            "quadratic-causal": _c(mc, EXTRAP, RegMethod.QLS_CAUSAL),
            "integer-ratio": _c(st.robust["integer-ratio"], TWO, LS),
            "cv-integer-ratio": _c(st.cv_integer, TWO, LS)}


def _ev_curve_fitting(st: RegistrationStudy) -> dict[str, Evidence]:
    """``shi-curve-fitting``: a quadratic fitted by least squares against the straight line (and locally, look-ahead)."""
    mc, qc = st.mc, RegMethod.QLS_CAUSAL
    return {"primary": _c(mc, qc, LS), "local-look-ahead": _c(mc, LOCAL_QLS, TWO),
            "last-three": _c(st.s3_fair[float(st.sigma)], RegMethod.THREE_POINT_EXTRAPOLATION,
                             LS),
            "manoeuvre-stop": _c(st.stress["manoeuvre-stop"], qc, LS, cond="manoeuvre-stop"),
            "manoeuvre-stop-local": _c(st.stress["manoeuvre-stop"], LOCAL_QLS, TWO,
                                       cond="manoeuvre-stop")}


def _ev_kalman_s3(st: RegistrationStudy) -> dict[str, Evidence]:
    """``shi-kalman-s3``: the §3 Kalman prediction against the raw samples (both causal)."""
    mc, pc = st.mc, st.s3_pc
    out: dict[str, Evidence] = {
        "primary": Comparison(st.s3_period.per_run[S3], mc.per_run[EXTRAP], METHOD_LABELS[S3], METHOD_LABELS[EXTRAP],
                              "less", MSE,
                              seed=mc.seed),  # type: ignore[attr-defined]
        "period-unchanged": _c(mc, S3, EXTRAP),  # type: ignore[arg-type]
        **{_key(s): _c(pc[_key(s)], S3, EXTRAP) for s in SIGMAS_ALT}}  # type: ignore[index]
    for s, m in st.s3_fair.items():
        out["three-point-baseline-" + _key(s)] = _c(m, S3, RegMethod.THREE_POINT_EXTRAPOLATION)
    for k, m in st.s3.items():
        out[k] = _c(m, S3, EXTRAP)
    for k in ("manoeuvre-stop", "manoeuvre-reverse", "manoeuvre-stop-tuned"):
        out[k] = _c(pc[k], S3, EXTRAP, cond=k)  # type: ignore[index]
    return out


def _ev_three_noise(st: RegistrationStudy) -> dict[str, Evidence]:
    r"""``shi-three-noise``: is three-point interpolation comparatively (比较) more affected by noise? (exact, R9)

    The noise-added MSE of a fixed-weight method is exactly :math:`g\sigma^2` and its total expected MSE
    :math:`b + g\sigma^2` (eq. reg-mse), so every reading is judged on the closed form with a zero-width interval
    (:class:`~fusion.book.exact.ExactComparison`). A run's MSE minus :math:`b` still holds the zero-mean cross term
    :math:`2 b_k a_k^\top v`, whose spread grows with :math:`\sigma` while the signal grows with :math:`\sigma^2`:
    at 0.1 and 0.3 m a Monte-Carlo interval of 1000 runs cannot resolve the 15 % the closed form gives exactly.
    """
    t1, t2, s = st.t1, st.t2, float(st.sigma)
    g = {n: sc.noise_gain(n) for n in (RegMethod.THREE_POINT, TWO)}
    between = t2[~np.isin(t2, t1)]          # the instants where interpolation happens (the others are samples)
    gi = {n: sc.mse_coefficients(n, s, t_dst=between)[1] for n in (RegMethod.THREE_POINT, TWO)}
    ext3 = RegMethod.THREE_POINT_EXTRAPOLATION
    gx = {n: sc.mse_coefficients(n, s, t_dst=t2[1:])[1] for n in (ext3, EXTRAP)}
    nam = "noise-added MSE gσ² (m², exact)"
    three, two = "three-point interpolation", "two-point interpolation"

    def added(sig: float) -> ExactComparison:
        return ExactComparison(g[RegMethod.THREE_POINT] * sig**2, g[TWO] * sig**2, three, two, "greater", nam)

    def total(sig: float) -> ExactComparison:
        return ExactComparison(sc.expected(RegMethod.THREE_POINT, sig), sc.expected(TWO, sig), three, two, "greater",
                               "E[MSE] = b + gσ² (m², exact)")

    return {"primary": added(s),
            "amplifies": ExactComparison(g[RegMethod.THREE_POINT] * s**2, s**2, three, "a raw sample (σ²)", "greater",
                                         nam),
            "interpolating-instants": ExactComparison(gi[RegMethod.THREE_POINT] * s**2, gi[TWO] * s**2, three, two,
                                                      "greater",
                                                      nam + f", the {between.size} instants between samples"),
            "total-mse": total(s),
            "total-mse-sigma-3": total(3.0),
            "extrapolation": Conjunction((
                ("three-point", Proposition(bool(gx[ext3] > 1.0),
                                            f"g = {gx[ext3]:.4f}")),
                ("against two-point", Proposition(bool(gx[ext3] > gx[EXTRAP]),
                                                  f"g = {gx[ext3]:.4f} vs {gx[EXTRAP]:.4f}"))))}


def _ev_improved(st: RegistrationStudy) -> dict[str, Evidence]:
    """``shi-improved`` (headline): the improved method against two-point interpolation."""
    out: dict[str, Evidence] = {"primary": _c(st.mc, IMPROVED, TWO), **_noise_levels(st, IMPROVED, TWO),
                                "real-time": _c(st.realtime, CAUSAL_IMPROVED, EXTRAP)}
    stress = {rd.key for rd in robustness_readings(float(st.sigma), st.t2) if rd.key.startswith(("latency", "manoeuvre"))}
    for k, m in st.robust.items():
        out[k] = _c(m, IMPROVED, TWO, cond=k if k in stress else "")
    return out


def _ev_improved_fair(st: RegistrationStudy) -> dict[str, Evidence]:
    """``shi-improved-fair`` (the book's question): the improved method against the same information's best use."""
    mc = st.mc
    return {"primary": _c(mc, IMPROVED, FIXED_LAG),
            "quadratic-global": _c(mc, IMPROVED, QLS),
            "quadratic-local": _c(mc, IMPROVED, LOCAL_QLS),
            "rts": _c(mc, IMPROVED, RegMethod.RTS_SMOOTHER),
            "spline": _c(mc, IMPROVED, RegMethod.CUBIC_SPLINE),
            "real-time-s3": _c(mc, CAUSAL_IMPROVED, S3),
            "real-time-quadratic": _c(mc, CAUSAL_IMPROVED, RegMethod.QLS_CAUSAL),
            **_stress(st, IMPROVED, FIXED_LAG),
            **{f"{k}-global": _c(st.stress[k], IMPROVED, QLS, cond=k)
               for k in ("manoeuvre-stop", "manoeuvre-reverse")},
            "manoeuvre-stop-tuned": _c(st.stress_tuned, IMPROVED, FIXED_LAG, cond="manoeuvre-stop-tuned")}


def _ev_simplifies(st: RegistrationStudy) -> dict[str, Evidence]:
    """``shi-simplifies``: fewer filter steps and one period, and the §3 method's accuracy kept."""
    mc, cc = st.mc, cost_count(st.t1, st.t2)
    s3_pc = st.s3_period.per_run[S3]
    ops = (f"multiplications and divisions over the record ({cc['improved_steps']} filter steps at "
           f"{cc['improved_periods']} period and {cc['three_point_evals']} three-point evaluations")
    simpler = ExactComparison(cc["improved_ops"], cc["s3_ops"], "improved (§4)", "§3, period changed", "less",
                              ops + f"; §3: {cc['s3_steps']} steps at {cc['s3_periods']} periods)")
    same_grid = ExactComparison(cc["improved_ops"], cc["s3_unchanged_ops"], "improved (§4)", "§3, period kept", "less",
                                ops + f"; §3: {cc['improved_steps']} steps and {cc['s3_steps'] - cc['improved_steps']}"
                                      " state predictions)")

    def kept(a: str) -> Comparison:
        return Comparison(mc.per_run[a], s3_pc, METHOD_LABELS[a], METHOD_LABELS[S3] + ", period changed", "less", MSE,
                          seed=mc.seed)  # type: ignore[attr-defined]

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


def _ev_few_restrictions(st: RegistrationStudy) -> Evidence:
    """``shi-few-restrictions``: 'few restrictions on its application' names no comparison (reason in the claim file)."""
    return Unverifiable("see the record's reason")


def _ev_ls_info(st: RegistrationStudy) -> dict[str, Evidence]:
    """``shi-ls-info``: least squares fused with sensor 2 (against fusing the stale sample, and sensor 2 alone), and
    registered (against no registration, the raw sample it replaces and two-point extrapolation)."""
    mc, t1, t2 = st.mc, st.t1, st.t2
    nf = {n: sc.noise_free_mse(n, t1, t2) for n in (LS, EXTRAP)}

    def unreg(m: sc.MonteCarlo) -> Comparison:
        return Comparison(m.per_run[LS], unregistered_runs(m, t1, t2), METHOD_LABELS[LS], UNREGISTERED, "less", MSE, seed=m.seed)

    rob = st.robust["integer-ratio"]
    t2_6 = sc.instants(6.0)[1]
    dec = affine_decomposition(sc.registrar(LS, t1, t2_6, 1.0, window=6.0), sc.truth(t1))
    b6 = float(np.mean((dec.f0 - sc.truth(t2_6)) ** 2))
    fr = st.fusion
    fm = "fused MSE at sensor-2 instants (m²)"

    def fused(b: np.ndarray, label: str) -> Comparison:
        return Comparison(fr.fused[LS], b, "fused, " + METHOD_LABELS[LS], label, "less", fm,
                          seed=fr.seed)  # type: ignore[attr-defined]

    return {"primary": fused(fr.unregistered, METHOD_LABELS[FUSION_UNREGISTERED]),
            "sensor-2-alone": fused(fr.alone, METHOD_LABELS[FUSION_ALONE]),
            "registration-mse": unreg(mc), **{_key(s): unreg(m) for s, m in st.sweep.items()},
            "replaced-precision": Comparison(rob.per_run[LS] - b6, rob.per_run[TWO], METHOD_LABELS[LS],
                                             "the raw sample it replaces", "less", "noise-added MSE (m²)",
                                             seed=rob.seed),
            "replaced-mse": Comparison(rob.per_run[LS], rob.per_run[TWO], METHOD_LABELS[LS],
                                       "the raw sample it replaces", "less", MSE, seed=rob.seed),
            "vs-extrapolation": _c(mc, LS, EXTRAP),
            "cv-integer-ratio": _c(st.cv_integer, LS, EXTRAP),
            "precision-only": Comparison(mc.per_run[LS] - nf[LS], mc.per_run[EXTRAP] - nf[EXTRAP], METHOD_LABELS[LS],
                                         METHOD_LABELS[EXTRAP], "less",
                                         "noise-added MSE (m²)", seed=mc.seed)}


def _ev_validated(st: RegistrationStudy) -> dict[str, Evidence]:
    """``shi-validated``: both classic methods on the noise-free scenario against no registration (exact, R9), the
    book's 1 % and below-noise thresholds, and the source's own figures (shi-figs23)."""
    t1, t2, s = st.t1, st.t2, float(st.sigma)
    x2 = sc.truth(t2)
    reg = {n: sc.register(n, t1, sc.truth(t1), t2, s) for n in (TWO, LS)}
    err = {n: float(np.abs(v - x2).max()) for n, v in reg.items()}
    stale = float(np.mean((sc.truth(t1[np.searchsorted(t1, t2, side="right") - 1]) - x2) ** 2))
    worst = max(err.values())
    nf = "noise-free registration MSE (m², exact)"
    return {"primary": Conjunction(tuple(
                (METHOD_LABELS[n], ExactComparison(float(np.mean((v - x2) ** 2)), stale, METHOD_LABELS[n], UNREGISTERED,
                                                   "less", nf))
                for n, v in reg.items())),
            "one-percent": Proposition(bool(worst < 0.01 * float(x2.max())),
                                       f"largest noise-free errors {err[TWO]:.2f} m and {err[LS]:.2f} m, "
                                       f"against {float(x2.max()):.0f} m covered"),
            "below-noise": Proposition(bool(worst < s), f"largest noise-free errors {err[TWO]:.2f} m and "
                                                        f"{err[LS]:.2f} m against σ_x = {s:g} m"),
            "published-figures": _ev_figs23(st)["primary"]}


def _ev_fig4_axis(st: RegistrationStudy) -> dict[str, Evidence]:
    """``shi-fig4-axis``: cannot be checked without the noise level (the reasons are in the claim file)."""
    why = "the noise level is not given (the reading states what the chapter computed at 1 m)"
    return {"primary": Unverifiable("see the record's reason"), "rmse": Unverifiable(why),
            "per-instant": Unverifiable(why)}


#: Reading key of ``shi-fusion`` (``book/claims/shi2023time.yaml``) for the two-point method: a key of the claims
#: file, which happens to read as the method's display label (:data:`fusion.book.style.METHOD_LABELS`).
_READING_TWO_POINT = "two-point"


def _ev_fusion(st: RegistrationStudy) -> dict[str, Evidence]:
    """``shi-fusion``: fusing sensor 1 registered by the improved method with sensor 2."""
    fr = st.fusion
    m = "fused MSE at sensor-2 instants (m²)"
    runs = {FUSION_ALONE: fr.alone, FUSION_UNREGISTERED: fr.unregistered, **fr.fused}
    label = {k: METHOD_LABELS[k] if k in (FUSION_ALONE, FUSION_UNREGISTERED) else "fused, " + METHOD_LABELS[k]
             for k in runs}

    def cmp(a: str, b: str) -> Comparison:
        return Comparison(runs[a], runs[b], label[a], label[b], "less", m, seed=fr.seed)  # type: ignore[attr-defined]

    return {"primary": cmp(IMPROVED, FUSION_UNREGISTERED), _READING_TWO_POINT: cmp(TWO, FUSION_UNREGISTERED),
            "improved-vs-two-point": cmp(IMPROVED, TWO), "sensor-2-alone": cmp(IMPROVED, FUSION_ALONE)}


#: Record id -> the function that computes every reading's evidence from the study.
_RECORDS = {"shi-few-restrictions": _ev_few_restrictions, "shi-samples": _ev_samples, "shi-figs23": _ev_figs23, "shi-eqs": _ev_eqs, "shi-metric": _ev_metric,
            "shi-interp-vs-ls": _ev_interp_vs_ls, "shi-curve-fitting": _ev_curve_fitting,
            "shi-kalman-s3": _ev_kalman_s3, "shi-three-noise": _ev_three_noise,
            "shi-improved": _ev_improved, "shi-improved-fair": _ev_improved_fair, "shi-simplifies": _ev_simplifies,
            "shi-ls-info": _ev_ls_info, "shi-validated": _ev_validated, "shi-fig4-axis": _ev_fig4_axis,
            "shi-fusion": _ev_fusion}

#: The records of ``_RECORDS`` whose readings (built together) hold a paired comparison of ``runs`` runs without a
#: reason: rule R4 refuses each below ``MIN_RUNS`` runs, so :func:`_reading` does before the study (fuzz 57c).
_PAIRED = frozenset({"shi-interp-vs-ls", "shi-curve-fitting", "shi-kalman-s3", "shi-improved", "shi-improved-fair",
                     "shi-simplifies", "shi-ls-info", "shi-fusion"})


def ledger_evidence(seed: int, runs: int) -> dict[str, Evidence | dict[str, Evidence]]:
    """The evidence of every record of chapter 07, by record id (for :func:`fusion.book.claims.build_ledger`).

    Parameters
    ----------
    seed, runs : int
        Of :func:`cached_study`.

    Returns
    -------
    dict
        Record id -> {reading key -> Evidence} (or one Evidence for a record without readings).

    Raises
    ------
    ValueError
        As :func:`cached_study`; ``runs`` below rule R4's 100 (the records' paired comparisons), named.
    """
    seed = check_seed(seed)
    with runs_named("runs", "the argument runs"):   # as _reading (fuzz 29b B6: "a and b", "the argument reason")
        st = cached_study(seed, runs_first(runs))   # the paired records refuse fewer than R4's runs: before the study
        return {rid: fn(st) for rid, fn in _RECORDS.items()}


def _reading(rid: str, settings: Mapping[str, object] | None, seed: int, runs: int) -> Evidence:
    """One reading's evidence (``settings["reading"]``, default the primary) of record ``rid``; rule R4's refusal
    names the caller's ``runs`` (fuzz 22b A2); the settings are checked before the study (fuzz 52 C7)."""
    reading_key(settings)
    with runs_named("runs", "the argument runs"):   # a paired record: R4's refusal before the study (fuzz 57c)
        return reading_of(rid, _RECORDS[rid](cached_study(seed, runs_first(runs) if rid in _PAIRED else runs)), settings)


@reads("reading")
def ev_samples(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-samples``: a reading's evidence (settings ``{"reading": key}``) for :func:`fusion.book.claims.evaluate`."""
    seed = check_seed(seed)
    return _reading("shi-samples", settings, seed, runs)


@reads("reading")
def ev_figs23(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-figs23``: a reading's evidence (settings ``{"reading": key}``)."""
    seed = check_seed(seed)
    return _reading("shi-figs23", settings, seed, runs)


@reads("reading")
def ev_eqs(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-eqs``: a reading's evidence (settings ``{"reading": key}``)."""
    seed = check_seed(seed)
    return _reading("shi-eqs", settings, seed, runs)


@reads("reading")
def ev_metric(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-metric``: a reading's evidence (settings ``{"reading": key}``)."""
    seed = check_seed(seed)
    return _reading("shi-metric", settings, seed, runs)


@reads("reading")
def ev_interp_vs_ls(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-interp-vs-ls``: a reading's evidence (settings ``{"reading": key}``)."""
    seed = check_seed(seed)
    return _reading("shi-interp-vs-ls", settings, seed, runs)


@reads("reading")
def ev_curve_fitting(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-curve-fitting``: a reading's evidence (settings ``{"reading": key}``)."""
    seed = check_seed(seed)
    return _reading("shi-curve-fitting", settings, seed, runs)


@reads("reading")
def ev_kalman_s3(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-kalman-s3``: a reading's evidence (settings ``{"reading": key}``)."""
    seed = check_seed(seed)
    return _reading("shi-kalman-s3", settings, seed, runs)


@reads("reading")
def ev_three_noise(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-three-noise``: a reading's evidence (settings ``{"reading": key}``)."""
    seed = check_seed(seed)
    return _reading("shi-three-noise", settings, seed, runs)


@reads("reading")
def ev_improved(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-improved``: a reading's evidence (settings ``{"reading": key}``)."""
    seed = check_seed(seed)
    return _reading("shi-improved", settings, seed, runs)


@reads("reading")
def ev_improved_fair(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-improved-fair``: a reading's evidence (settings ``{"reading": key}``)."""
    seed = check_seed(seed)
    return _reading("shi-improved-fair", settings, seed, runs)


@reads("reading")
def ev_simplifies(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-simplifies``: a reading's evidence (settings ``{"reading": key}``)."""
    seed = check_seed(seed)
    return _reading("shi-simplifies", settings, seed, runs)


@reads("reading")
def ev_ls_info(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-ls-info``: a reading's evidence (settings ``{"reading": key}``)."""
    seed = check_seed(seed)
    return _reading("shi-ls-info", settings, seed, runs)


@reads("reading")
def ev_validated(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-validated``: a reading's evidence (settings ``{"reading": key}``)."""
    seed = check_seed(seed)
    return _reading("shi-validated", settings, seed, runs)


@reads("reading")
def ev_fig4_axis(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-fig4-axis``: a reading's evidence (settings ``{"reading": key}``)."""
    seed = check_seed(seed)
    return _reading("shi-fig4-axis", settings, seed, runs)


@reads("reading")
def ev_few_restrictions(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-few-restrictions``: a reading's evidence (settings ``{"reading": key}``)."""
    seed = check_seed(seed)
    return _reading("shi-few-restrictions", settings, seed, runs)


@reads("reading")
def ev_fusion(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-fusion``: a reading's evidence (settings ``{"reading": key}``)."""
    seed = check_seed(seed)
    return _reading("shi-fusion", settings, seed, runs)
