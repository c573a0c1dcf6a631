r"""Chapter 07 (Shi, Suo & Ma 2023): the closed form E[MSE] = b + g·σ² of every method, the noise levels at which
two methods change order, and the exact start-up transient of the Kalman methods.

Documented and re-exported by :mod:`fusion.book.chapters.time_registration`, whose API page lists them.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pandas as pd

from fusion._shown import shown
from fusion._limits import LOOP_STEP, work
from fusion._validation import (as_array, as_times, distinct, instance_of, one_of, scalar, sequence,
                                std_scalar, text)
from fusion.book.style import METHOD_LABELS
from fusion.book.tables import _frame, integral_index
from fusion.scenarios import time_registration as sc
from fusion.scenarios.time_registration import RegMethod

__all__ = ["closed_form_table", "crossing_table", "NAMED_CROSSINGS", "named_crossings", "KALMAN_METHODS",
           "transient_table", "transient_end"]

TWO, IMPROVED = RegMethod.TWO_POINT, RegMethod.IMPROVED

#: Column headers of :func:`closed_form_table` and :func:`crossing_table`, named once (the ledger's values read
#: them): the offset b of E[MSE] = b + g·σ² and the two sides of a crossing.
B_OFFSET = "b (m²)"
BETTER_BELOW = "better below σ*"
BETTER_ABOVE = "better above σ*"
SIGMA_STAR = "σ* (m)"


def _method_names(names: object, name: str) -> list:
    """Method keys of :data:`fusion.scenarios.time_registration.METHODS`, each named ``name[i]``; non-empty, none
    repeated (a table's columns are keyed by them: a repeat would collapse into one column)."""
    items = sequence(names, name)
    if not items:
        raise ValueError(f"{name} is empty (it must hold at least one method)")
    items = [one_of(n, tuple(sc.METHODS), f"{name}[{i}]") for i, n in enumerate(items)]
    return distinct(items, name)


def closed_form_table(sigma_filter: float, sigma: float) -> pd.DataFrame:
    r"""Closed form :math:`E[\mathrm{MSE}] = b + g\sigma^2` of every method (filter tuned for ``sigma_filter``).

    Parameters
    ----------
    sigma_filter : float
        Noise level the Kalman methods assume (m).
    sigma : float
        Noise level at which the expectation is also evaluated (m).

    Returns
    -------
    DataFrame
        Index the methods; columns information, b (m²), g, and E[MSE] at ``sigma`` (m²); rounded to 4 decimals.

    Raises
    ------
    TypeError
        ``sigma_filter`` or ``sigma`` is not a number.
    ValueError
        ``sigma_filter`` or ``sigma`` is not a finite positive standard deviation (its square a valid variance).
    """
    # the floats read (fuzz 22b, FR); the column header shows sigma by :g, as given
    sigma_filter, sigma = std_scalar(sigma_filter, "sigma_filter"), std_scalar(sigma, "sigma")
    rows = {}
    for n in sc.METHODS:
        b, g = sc.mse_coefficients(n, sigma_filter)
        rows[n] = {"information": METHOD_LABELS[sc.METHODS[n]], B_OFFSET: b, "g": g, f"E[MSE] at σ = {sigma:g} m (m²)": b + g * sigma**2}
    out = pd.DataFrame(rows).T.infer_objects()
    num = out.select_dtypes("number").columns
    out[num] = out[num].round(4) + 0.0
    return out


def crossing_table(closed: pd.DataFrame) -> pd.DataFrame:
    r"""Noise level at which each pair of methods changes order, :math:`\sigma^* = \sqrt{(b_B - b_A)/(g_A - g_B)}`.

    Parameters
    ----------
    closed : DataFrame
        Output of :func:`closed_form_table`.

    Returns
    -------
    DataFrame
        One row per pair that crosses at a positive level: the method better below σ*, the one
        better above, and σ* (m, 2 decimals); sorted by σ*. A table in which no pair crosses (equal ``g``, or
        ``b`` and ``g`` in the same order, as two-point and least squares) gives no row: an empty table with the
        same three columns (σ* a float column).

    Raises
    ------
    TypeError
        ``closed`` is not a DataFrame, or its ``b (m²)`` or ``g`` column holds a value that is not a number.
    ValueError
        ``closed`` lacks the columns ``b (m²)`` and ``g`` (or holds one twice), holds fewer than two methods, repeats
        a method or a row that is not a method of ``METHODS``, or holds
        a ``b`` or ``g`` that is not finite (a crossing at σ* = NaN or inf) or negative (``b`` is a squared bias and
        ``g`` a sum of squared weights: a negative one is no :func:`closed_form_table`).
    """
    instance_of(closed, pd.DataFrame, "closed")
    lacking = [c for c in (B_OFFSET, "g") if c not in closed.columns]
    if lacking or len(closed) < 2:
        raise ValueError(f"closed must be the output of closed_form_table (columns {shown(B_OFFSET)} and 'g', at least two "
                         f"methods), got the columns {list(closed.columns)[:8]} and {len(closed)} rows")
    if closed.index.has_duplicates:
        raise ValueError(f"closed must not repeat a method (one row each), got "
                         f"{[str(k) for k in closed.index[closed.index.duplicated()].unique()[:5]]} twice")
    # the rows are methods (fuzz 24d T5: an unknown row was listed as a method better below σ*)
    _frame(closed, "closed", (B_OFFSET, "g"), maker="closed_form_table", unique=True, rows=sc.METHODS,
           rows_are="a method of METHODS")
    b_all = as_array(closed[B_OFFSET].to_numpy(), f"closed[{B_OFFSET!r}]", nonnegative=True, subnormal=True)
    g_all = as_array(closed["g"].to_numpy(), "closed['g']", nonnegative=True, subnormal=True)
    names = list(closed.index)
    rows = []
    for i, a in enumerate(names):
        for j in range(i + 1, len(names)):
            ba, ga, bb, gb = b_all[i], g_all[i], b_all[j], g_all[j]
            if ga == gb or (bb - ba) / (ga - gb) <= 0:
                continue
            s = float(np.sqrt((bb - ba) / (ga - gb)))
            low, high = (a, names[j]) if ba < bb else (names[j], a)
            rows.append({BETTER_BELOW: low, BETTER_ABOVE: high, SIGMA_STAR: round(s, 2)})
    out = pd.DataFrame(rows, columns=[BETTER_BELOW, BETTER_ABOVE, SIGMA_STAR]).astype({SIGMA_STAR: float})
    return out.sort_values(SIGMA_STAR, kind="stable").reset_index(drop=True)


#: The four crossings the chapter names (method better below σ*, method better above), in its order.
NAMED_CROSSINGS: tuple[tuple[str, str], ...] = (
    (RegMethod.THREE_POINT, TWO), (IMPROVED, RegMethod.KALMAN_TWO_POINT), (RegMethod.KALMAN_PREDICT, TWO),
    (RegMethod.TWO_POINT_EXTRAPOLATION, RegMethod.LEAST_SQUARES))


def named_crossings(crossings: pd.DataFrame, pairs: Sequence[tuple[str, str]] = NAMED_CROSSINGS) -> pd.DataFrame:
    """The rows of :func:`crossing_table` for the named pairs of methods, in the order of ``pairs``.

    Parameters
    ----------
    crossings : DataFrame
        Output of :func:`crossing_table`.
    pairs : sequence of (str, str)
        (method better below σ*, method better above σ*); default :data:`NAMED_CROSSINGS`.

    Returns
    -------
    DataFrame
        The same columns, one row per pair, index 0, 1, ...; empty ``pairs`` gives an empty table with those
        columns, and a pair given twice gives its row twice.

    Raises
    ------
    TypeError
        ``crossings`` is not a DataFrame, or ``pairs`` not a sequence of pairs of method names (strings), naming
        the pair.
    ValueError
        ``crossings`` lacks the columns of :func:`crossing_table`, holds a pair (row) or a column read more than
        once, or holds a σ* that is not a finite number >= 0
        (TypeError for a non-number), or a pair of ``pairs`` does not cross at a positive noise level (or is named
        in the other order).
    """
    instance_of(crossings, pd.DataFrame, "crossings")
    lacking = [c for c in (BETTER_BELOW, BETTER_ABOVE, SIGMA_STAR) if c not in crossings.columns]
    if lacking:
        raise ValueError(f"crossings lacks the columns {lacking} (it must be the output of crossing_table)")
    if len(crossings):  # the σ* returned: finite and >= 0, as crossing_table gives them (an empty table has none)
        as_array(crossings[SIGMA_STAR].to_numpy(), f"crossings[{SIGMA_STAR!r}]", nonnegative=True, subnormal=True)
    items = sequence(pairs, "pairs")
    for i, p in enumerate(items):
        if isinstance(p, (str, bytes)) or not isinstance(p, Sequence) or len(p) != 2:
            raise TypeError(f"pairs[{i}] must be a (method, method) pair, got {shown(p)}")
    # each pair read once, and the checked pairs looked up (fuzz 58a D1's class: the caller's pairs were iterated
    # again for the rows, a list subclass could give other pairs the second time)
    items = [tuple(sequence(p, f"pairs[{i}]", 2)) for i, p in enumerate(items)]
    # each method named by its text (rule 19): an array or a number in a pair is refused by name, not compared with
    # the table's pairs (fuzz 59a C3: an array raised numpy's "truth value ... is ambiguous" from ``p not in key``)
    items = [tuple(text(m, f"pairs[{i}][{j}]") for j, m in enumerate(p)) for i, p in enumerate(items)]
    key = list(zip(crossings[BETTER_BELOW], crossings[BETTER_ABOVE]))
    if len(crossings):  # one column each, one row a pair (fuzz 24d T); an empty table is crossing_table's too
        _frame(crossings, "crossings", (BETTER_BELOW, BETTER_ABOVE, SIGMA_STAR), maker="crossing_table", unique=True)
    again = next((p for i, p in enumerate(key) if p in key[:i]), None)
    if again is not None:
        raise ValueError(f"crossings holds the pair {shown(again)} more than once (crossing_table gives one row "
                         f"a pair)")
    missing = [p for p in items if p not in key]
    if missing:
        raise ValueError(f"pairs: crossings holds no crossing for {missing}")
    return crossings.iloc[[key.index(p) for p in items]].reset_index(drop=True)


#: The Kalman methods of the source's §3 and §4 and their two-point ablation.
KALMAN_METHODS: tuple[str, ...] = (RegMethod.KALMAN_PREDICT, RegMethod.KALMAN_TWO_POINT, IMPROVED)
#: Units of one step of :func:`transient_table`'s decomposition of a Kalman filter method (the method over the run at
#: one sample, about 24 us measured; ``fusion._limits.MAX_WORK``: a unit is about 10 ns).
_TRANSIENT_STEP = 3 * LOOP_STEP
#: Units of one step of :func:`transient_table`'s decomposition (a registration of the run a sample: ``n1 x n1`` steps
#: a method), by method, measured as ``transient_table(horizon, 1.0, [method])`` at 101, 201, 577 and 1,153 samples
#: (``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the least of two, the machine shared and loaded, about 2.5
#: jobs a core, which inflates each cost some 1.5-2 times; fix73c, fuzz 65a D1: every method weighed the Kalman
#: filters' step, so ``['reg_fixed_lag']`` at its edge, 577 samples, ran 20.1 CPU-s): the Kalman filters 41-52 us a
#: step (:data:`_TRANSIENT_STEP`, the 24 us measured unloaded; the improved method alone 44 us at 333 samples, 4.9
#: CPU-s); the smoothers (RTS, fixed lag) 1.3-1.6 times that, 59-71 us (the fixed lag alone at 500 samples: 17.7
#: CPU-s), ``5 * LOOP_STEP`` (one method is accepted to 447 samples, horizon 894 s: the fixed lag ran 12.3 CPU-s,
#: load 6.9 on the 2 cores); the methods fitting each instant 7-15 us (8-15 at 1,153 samples), 1,500 units (one
#: method to 816 samples: ``reg_qls_next`` ran 9.2 CPU-s);
#: the fixed-weight methods and the cubic spline (one vectorised call a sample) 0.06-0.5 us, the spline the dearest
#: (0.21 us at 3,162 samples), 30 units (one method to 5,773 samples: the spline ran 5.0 CPU-s). Not
#: ``fusion.scenarios._time_registration_work``'s ``FUSION_RUN_WEIGHT``: that weighs a call on 20 samples (its
#: overhead, where the fixed-weight methods cost more than the filters), not a step of this decomposition.
_TRANSIENT_STEPS: dict[str, int] = {
    **{n: _TRANSIENT_STEP for n in ("reg_kalman_predict", "reg_kalman_two_point", "reg_improved",
                                    "reg_causal_improved")},
    **{n: 5 * LOOP_STEP for n in ("reg_rts_smoother", "reg_fixed_lag")},
    **{n: 3 * LOOP_STEP // 2 for n in ("reg_least_squares", "reg_qls_next", "reg_qls_causal", "reg_local_qls")},
    **{n: 30 for n in ("reg_two_point", "reg_three_point", "reg_two_point_extrapolation",
                       "reg_three_point_extrapolation", "reg_cubic_spline")}}


def transient_table(horizon: float, sigma: float, names: Sequence[str] = KALMAN_METHODS) -> pd.DataFrame:
    r"""Exact per-instant bias and variance of each method's error, over a horizon of ``horizon`` seconds.

    The scenario of :func:`fusion.scenarios.time_registration.instants` (sensor 1 every 2 s from 1 s, the instants
    every 5 s from 3 s, the source's quadratic truth) run for ``horizon`` s instead of 40. Each method is affine in
    the samples, :math:`\hat x(t_k) = f_{0,k} + \mathbf a_k^\top\mathbf v`
    (:func:`fusion.registration.analysis.affine_decomposition`), so its error at :math:`t_k` has bias
    :math:`f_{0,k} - x(t_k)` and variance :math:`\sigma^2\lVert\mathbf a_k\rVert^2` exactly.

    Parameters
    ----------
    horizon : float
        Length of the run (s), at least 5.
    sigma : float
        Measurement noise (m), also assumed by the filter.
    names : sequence of str
        Keys of :data:`fusion.scenarios.time_registration.METHODS`.

    Returns
    -------
    DataFrame
        Index the instants (s); columns (method, "bias (m)" / "variance (m²)" / "E[sq. error] (m²)"), 4 decimals.

    Raises
    ------
    TypeError
        ``horizon`` or ``sigma`` is not a number, or ``names`` not a sequence of strings.
    ValueError
        ``horizon`` below 5 s or so long that the exact decomposition (its work grows as the methods' measured
        costs a step, summed, times the square of the number of sensor-1 samples) is beyond the work budget (from
        about 667 s for the three Kalman methods, some 8 CPU-s; 895 s for a smoother alone); ``sigma`` not a valid
        standard deviation; ``names`` empty or holding an unknown method.
    """
    horizon = scalar(horizon, "horizon", lo=5.0)
    sigma = std_scalar(sigma, "sigma")  # the float read (fuzz 22b, FR)
    names = _method_names(names, "names")
    # the decomposition runs each method once per sensor-1 sample over the whole run: (samples)**2 steps per
    # method, each weighed by its method's measured cost (_TRANSIENT_STEPS; a Kalman filter about 24 us: 0.25 CPU-s
    # at 100 s, 3.0 at 400 s, 4.4 at 500 s, three methods; fuzz 30b D2: 1,100 s was accepted at LOOP_STEP a step and
    # ran some 35 CPU-s; fix73c, fuzz 65a D1: a smoother costs more), refused before the time grids
    n1 = int((horizon - 1.0) // 2.0) + 1
    work((n1, n1), "horizon and names", weight=sum(_TRANSIENT_STEPS[n] for n in names))
    t1 = np.arange(1.0, horizon + 1e-9, 2.0)
    t2 = np.arange(3.0, horizon + 1e-9, 5.0)
    from fusion import registration as reg

    cols = {}
    for n in names:
        dec = reg.affine_decomposition(sc.registrar(n, t1, t2, float(sigma), sc.Q_V, sc.Q_A), sc.truth(t1))
        bias, var = dec.f0 - sc.truth(t2), float(sigma) ** 2 * np.sum(dec.A**2, axis=1)
        cols[(n, "bias (m)")], cols[(n, "variance (m²)")], cols[(n, "E[sq. error] (m²)")] = bias, var, bias**2 + var
    out = pd.DataFrame(cols, index=pd.Index(t2, name="instant (s)"))
    return integral_index(out.round(4) + 0.0)


def _steady_from(t: np.ndarray, err: np.ndarray, tol: float, period: float) -> int:
    """Index of the first instant of ``t`` from which every row of ``err`` stays within ``tol`` of the value at the
    last instant of ``t`` at the same position (``t.size`` when none)."""
    ref = np.empty_like(err)
    for k, tk in enumerate(t):
        same = np.flatnonzero(np.isclose(np.mod(t - tk, period), 0.0) & (t >= tk))
        ref[k] = err[same[-1]]
    bad = np.flatnonzero(~np.all(np.abs(err - ref) <= tol * np.abs(ref), axis=1))
    return 0 if bad.size == 0 else int(bad[-1]) + 1


def transient_end(table: pd.DataFrame, tol: float = 0.01, period: float = 10.0) -> float:
    """First instant from which every method's expected squared error stays within ``tol`` of its steady value.

    The instants repeat their position between sensor-1 samples every ``period`` seconds (10 s: 5 such
    periods of sensor 1, 2 of sensor 2), so an instant's steady value is that of the last instant of the
    table at the same position (a whole number of periods later). The instants of the table's last period are
    compared with themselves only, so the answer is taken as steady only when it is confirmed: followed by at least
    two periods of the table, and the same without the table's last period (a horizon too short to tell is refused
    rather than reported as the start of its last periods: 40 s gave 23 s, against 28 s from 55 s on).

    Parameters
    ----------
    table : DataFrame
        Output of :func:`transient_table`, over a horizon long enough to reach the steady state (55 s and more for
        the chapter's Kalman methods at tol 0.01).
    tol : float
        Relative tolerance.
    period : float
        Period (s) of the pattern of instants: it must map the table's instants onto instants (a whole number of
        their spacing) and be shorter than their span. That it is also a period of sensor 1's samples (10 s for
        :func:`transient_table`'s instants) is not visible in the table and is the caller's.

    Returns
    -------
    float
        The instant (s).

    Raises
    ------
    TypeError
        ``table`` is not a DataFrame, or ``tol`` or ``period`` not a number.
    ValueError
        ``table`` is not a :func:`transient_table` (its columns have no "E[sq. error] (m²)" level, it is empty, its
        instants are not finite and strictly increasing or an expected squared error not finite), ``tol`` is
        negative, ``period`` not positive, not shorter than the span of the instants or not a shift that maps them
        onto instants, or no steady state is reached and confirmed within the horizon (fewer than two periods follow
        the answer, or it changes when the table's last period is dropped).
    """
    instance_of(table, pd.DataFrame, "table")
    if (not isinstance(table.columns, pd.MultiIndex) or table.columns.nlevels != 2
            or "E[sq. error] (m²)" not in table.columns.get_level_values(1) or table.empty):
        raise ValueError("table must be an output of transient_table (columns (method, quantity) with "
                         "'E[sq. error] (m²)'), got other columns or no rows")
    tol = scalar(tol, "tol", lo=0.0)
    period = scalar(period, "period", lo=0.0, lo_open=True)
    t = as_times(table.index.to_numpy(), "table.index (the instants)")
    err = as_array(table.xs("E[sq. error] (m²)", axis=1, level=1).to_numpy(), "table's 'E[sq. error] (m²)' columns",
                   subnormal=True)
    span = float(t[-1] - t[0])
    if period >= span:
        raise ValueError(f"period = {shown(period)} s is not shorter than the span of table's instants ({span:g} s): "
                         "no later period to compare with (a horizon too short to tell a steady state)")
    shifted = t[t + period <= t[-1] + 1e-9 * max(1.0, abs(t[-1]))] + period
    off = [float(v) for v in shifted if not np.isclose(t, v).any()]
    if off:
        raise ValueError(f"period = {shown(period)} s is not the pattern of table's instants: shifted by it, "
                         f"{off[0] - period:g} s lands on {off[0]:g} s, not an instant")
    first = _steady_from(t, err, tol, period)
    if first >= t.size:
        raise ValueError("table: no steady state within the horizon")
    slack = 1e-9 * max(1.0, abs(t[-1]))
    keep = t <= t[-1] - period + slack
    if t[first] + 2.0 * period > t[-1] + slack or _steady_from(t[keep], err[keep], tol, period) != first:
        raise ValueError(f"table: its horizon ({t[-1]:g} s) is too short to tell the steady state: the instant "
                         f"{t[first]:g} s found is not confirmed (by two later periods, and the same without the "
                         "last one): a longer transient_table is needed")
    return float(t[first])
