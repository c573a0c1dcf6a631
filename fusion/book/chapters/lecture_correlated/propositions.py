r"""The closed-form and exact checks behind chapter 04's records: the plug-in ridge against the best fixed k,
the special cases of least squares, the James-Stein estimator's linearity.
"""

from __future__ import annotations

from fusion._counts import distinct, sequence
from fusion._limits import loop_work, work
from fusion._validation import as_rng, count, instance_of, nonnegative_scalar, one_of, positive_scalar, scalar


import numpy as np
import pandas as pd

from fusion.book.exact import ExactComparison
from fusion.book.ledger import Conjunction
from fusion.book.ledger.evidence import _MEMBER
from fusion.readings import biased as rg
from fusion.scenarios.lecture_correlated import K_LABEL, RidgeStudy
from fusion.book.chapters.lecture_correlated.ridge import _plain
from fusion.book.style import METHOD_SHORT_LABELS
from fusion.scenarios.ridge_sensors import LS, PLUGIN_EST, PLUGIN_KNOWN, PluginStudy, VectorStudy

__all__ = ["plugin_conjunction", "ls_special_cases", "james_stein_linearity"]


def _kstar_prop(s25: RidgeStudy, c: float = 1.0) -> Conjunction:
    """Ridge with k* = σ²/x² against LS at every x of E2.5, reliability with the tolerance c σ/√m (closed form):
    one exact comparison per x, judged by the practical margin (R9)."""
    m, sig = s25.m0, float(s25.sigma)
    delta = c * sig / np.sqrt(m)
    rk = pd.DataFrame(s25.rel_k)
    parts = []
    for x in dict.fromkeys(rk["x"]):
        k = rg.optimal_ridge_k(sig, x)
        mk, m0 = rg.scalar_ridge_moments(m, sig, x, k), rg.scalar_ridge_moments(m, sig, x, 0.0)
        a, b = float(rg.reliability(mk.bias, mk.sd, delta)), float(rg.reliability(m0.bias, m0.sd, delta))
        parts.append((f"x = {x:g} (k* = {_plain(k)})", ExactComparison(
            a, b, "ridge, k*", METHOD_SHORT_LABELS[LS], "greater", f"reliability P(|error| ≤ {c:g}σ/√m), m = {m}")))
    return Conjunction(tuple(parts))


def _fixed_prop(s25: RidgeStudy, label: str) -> Conjunction:
    rk = pd.DataFrame(s25.rel_k)
    r = rk[rk[K_LABEL] == label]
    return Conjunction(tuple((f"x = {x:g}", ExactComparison(float(a), float(b), f"ridge ({label})", METHOD_SHORT_LABELS[LS], "greater",
                                                             f"reliability P(|error| ≤ σ/√m), m = {s25.m0}"))
                             for x, a, b in zip(r["x"], r["rel(k)"], r["rel(0)"])))


#: Units of work of one x of :func:`plugin_conjunction` by plug-in (read, one ``plugin_risk`` and one exact comparison):
#: 280 us with known sigma, 420 us with sigma estimated (m = 5), measured over 1,000 xs (fix70c).
_PLUGIN_X_UNITS = {PLUGIN_KNOWN: 30_000, PLUGIN_EST: 45_000}


def plugin_conjunction(p: PluginStudy, key: str = PLUGIN_KNOWN, c: float = 1.0,
                       xs: tuple[float, ...] = (0.25, 0.5, 1.0, 3.0, 10.0)) -> Conjunction:
    """The plug-in ridge against LS at every true x: the exact reliabilities (quadrature), one member per x.

    Parameters
    ----------
    p : PluginStudy
        Result of :func:`fusion.scenarios.ridge_sensors.plugin_study` (its ``m`` and ``sigma``).
    key : {"ridge_plugin_known", "ridge_plugin_est"}
        Which plug-in.
    c : float
        Tolerance in standard errors.
    xs : tuple of float
        True values (at least two, distinct; any finite x, not only the study's).

    Returns
    -------
    fusion.book.ledger.Conjunction
        One :class:`~fusion.book.exact.ExactComparison` per x: the plug-in's exact reliability
        (:func:`fusion.readings.biased.plugin_risk`) against that of LS, judged by the practical margin (R9).

    Raises
    ------
    TypeError
        ``p`` not a PluginStudy, ``c`` or an entry of ``xs`` not a number, ``xs`` not a sequence.
    ValueError
        ``key`` not a plug-in, ``c`` not positive and finite, an entry of ``xs`` not finite, fewer than two
        ``xs`` or a repeated one; more ``xs`` than the work budget (``fusion._limits.MAX_WORK``, 130,000 units an x
        with known σ, 145,000 estimated, its member of the conjunction included: about 7,700 and 6,900), by their
        number before any is read.
    """
    instance_of(p, PluginStudy, "p")
    key = one_of(key, (PLUGIN_KNOWN, PLUGIN_EST), "key")
    c = scalar(c, "c", lo=0.0, lo_open=True)
    items = sequence(xs, "xs", minimum=2, what="true values")
    # rule 17 by len(xs) before any x is read (fix70c: 10**7 xs were each read, hashed and run through plugin_risk,
    # hours of work before the Conjunction's own budget; 33,334 known-sigma xs were refused by it, naming parts,
    # after 12.9 CPU-s): one x measured 280 us with known sigma, 420 us estimated (1,000 xs, OPENBLAS_NUM_THREADS=1,
    # minimum of 2, the shared machine), counted as 30,000 and 45,000 units, plus its member's life in the
    # Conjunction (``fusion.book.ledger.evidence._MEMBER`` units)
    work((len(items),), "xs", weight=_PLUGIN_X_UNITS[key] + _MEMBER)
    # one member per x: a Conjunction of at least two members with distinct labels (fuzz 18, F25)
    xs = distinct([scalar(x, f"xs[{i}]") for i, x in enumerate(items)], "xs")
    m, sig = p.m, p.sigma
    parts = []
    for x in xs:
        r = rg.plugin_risk(np.sqrt(m) * x / sig, c, None if key == PLUGIN_KNOWN else m)
        parts.append((f"x = {x:g}", ExactComparison(float(r.reliability), float(r.reliability_ls), f"ridge, {METHOD_SHORT_LABELS[key]}", METHOD_SHORT_LABELS[LS],
                                                     "greater", f"reliability P(|error| ≤ {c:g}σ/√m), m = {m}")))
    return Conjunction(tuple(parts))


def _scalar_best(m: int, sig: float, x: float) -> tuple[float, float]:
    """MSE of LS and of scalar ridge with k* = σ²/x² (exact)."""
    mk = rg.scalar_ridge_moments(m, sig, x, rg.optimal_ridge_k(sig, x))
    return sig**2 / m, float(mk.mse)


def _existence(v: VectorStudy, what: str) -> Conjunction:
    """Centralised ridge with the best fixed k for each true x of the vector study against LS, exact MSE: one
    exact comparison per x, judged by the practical margin (R9)."""
    A, tr = v.A, v.tr_ls
    parts = []
    for key, x in v.x.items():
        k, mse = rg.best_ridge_k(A, x)
        parts.append((f"{key[0]}, |x| = {key[1]:g} (k = {_plain(k)})", ExactComparison(
            float(mse), float(tr), "ridge, best fixed k", METHOD_SHORT_LABELS[LS], "less", f"exact MSE ({what})")))
    return Conjunction(tuple(parts))


def ls_special_cases(rng: np.random.Generator, m: int = 50) -> dict[str, float]:
    """Largest differences between three classical estimates and their least-squares forms (§2.5).

    Parameters
    ----------
    rng : numpy.random.Generator
        Draws the readings y (m) and their variances.
    m : int
        Number of readings, from 1 to about ``10**7`` (the work budget of the recursive filter's Python loop,
        ``fusion._limits.loop_work``); ``m = 1`` is degenerate: every form is the one reading, every difference 0.

    Returns
    -------
    dict
        ``"mean"``: |(HᵀH)⁻¹Hᵀy − ȳ| with H = 1; ``"weighted mean"``: |(HᵀWH)⁻¹HᵀWy − Σ(yᵢ/Rᵢ)/Σ(1/Rᵢ)|
        with W = diag(1/Rᵢ); ``"recursive filter"``: |x̂ₘ − ȳ| for x̂ₖ = x̂ₖ₋₁ + (yₖ − x̂ₖ₋₁)/k.

    Raises
    ------
    TypeError
        ``rng`` is not a :class:`numpy.random.Generator`, or ``m`` not an integer.
    ValueError
        ``m`` is below 1 or beyond the work budget.

    References
    ----------
    * Kay, S. M. (1993). *Fundamentals of Statistical Signal Processing: Estimation Theory*, ch. 8 (least
      squares, sequential least squares). Prentice Hall.
    """
    rng, m = as_rng(rng), count(m, "m")
    # the recursive filter below: m Python steps (fuzz 21b, L) of scalar arithmetic, 0.29 us each measured (980,000,
    # the edge at a LOOP_STEP each, ran 0.28 CPU-s; time.process_time, shared machine; fuzz 39a E4): 100 units a step
    loop_work((m,), 1, "m", step=100)
    R = rng.uniform(0.5, 4.0, size=m)
    y = 10.0 + rng.normal(size=m) * np.sqrt(R)
    H = np.ones((m, 1))
    ls = np.linalg.lstsq(H, y, rcond=None)[0][0]
    HtW = H.T / R  # Hᵀ W with W = diag(1/R), without the m x m matrix (m = 30000 asked for 7 GB)
    wls = np.linalg.solve(HtW @ H, HtW @ y)[0]
    x = 0.0
    for k, yk in enumerate(y, start=1):
        x += (yk - x) / k
    return {"mean": abs(ls - y.mean()) / abs(y.mean()),
            "weighted mean": abs(wls - np.sum(y / R) / np.sum(1.0 / R)) / abs(y.mean()),
            "recursive filter": abs(x - y.mean()) / abs(y.mean())}


def james_stein_linearity(rng: np.random.Generator, d: int = 3, sigma: float = 1.0, k: float = 1.0) -> dict[str, float]:
    """How far the James-Stein estimate and ridge are from linear: ``|f(2y) − 2f(y)| / |2f(y)|`` (§2.5).

    Parameters
    ----------
    rng : numpy.random.Generator
        Draws y (d) around x = (1, ..., 1).
    d : int
        Dimension (>= 3).
    sigma : float
        Noise SD.
    k : float
        Ridge parameter (fixed), >= 0.

    Returns
    -------
    dict
        ``"james-stein"`` and ``"ridge"``: the relative departure from linearity (0 for a linear map).

    Raises
    ------
    TypeError
        ``rng`` is not a :class:`numpy.random.Generator`, ``d`` not an integer, ``sigma`` or ``k`` not a number.
    ValueError
        ``d`` is below 3 or beyond the ceiling of a dimension, ``sigma`` is not finite and > 0, or ``k`` not
        finite and >= 0.
    """
    rng, d = as_rng(rng), count(d, "d", minimum=3)
    sigma, k = positive_scalar(sigma, "sigma"), nonnegative_scalar(k, "k")
    y = 1.0 + sigma * rng.normal(size=d)
    H = np.eye(d)
    out = {}
    for name, f in (("james-stein", lambda z: rg.james_stein(z, sigma)), ("ridge", lambda z: rg.ridge(H, z, k))):
        a, b = f(2 * y), 2 * f(y)
        out[name] = float(np.linalg.norm(a - b) / np.linalg.norm(b))
    return out
