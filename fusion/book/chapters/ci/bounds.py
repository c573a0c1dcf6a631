"""Bounds by sampling period and process-noise reading: the posterior Cramér-Rao bound, the exact path error, Q
scaling.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
from numpy.typing import ArrayLike

from fusion.book.tables import rounded
from fusion.book.glue import GlueValues
from fusion.scenarios import two_sensor
from fusion.scenarios.two_sensor.bounds import CAUSAL_FLOOR, CENTRALISED_KF, CI_AVERAGE, STRAIGHT_LEG_FLOOR
from fusion._shown import shown
from fusion._structures import derived
from fusion._limits import work
from fusion._validation import scalar
from fusion.book.chapters.ci.checks import PERIOD_KEY, _counted, _frame, _periods

__all__ = ["pcrb_numbers", "pcrb_table", "path_period_table", "path_numbers"]

#: Row of :func:`pcrb_table` for the limit of a short period, which :func:`pcrb_numbers` reads (issue 36: named once).
T_LIMIT = "T → 0"

#: Units of a period of :func:`pcrb_table` (a steady-state bound of each reading of Q): twice the 4 ms measured
#: (0.040 CPU-s for 10 periods, 0.40 for 100; ``time.process_time``, minimum of 2, ``OPENBLAS_NUM_THREADS=1``, the
#: machine shared and loaded; book audit 76: no budget, so 10**4 periods ran about 40 CPU-s, 10**6 hours).
_PCRB_PERIOD = 800_000


def pcrb_table(periods: ArrayLike, sigma: float, delta0: float) -> pd.DataFrame:
    r"""Steady-state PCRB :math:`\sqrt{P_{xx}}` (m) of the source's stochastic model against the period, each reading of Q.

    Parameters
    ----------
    periods : array_like of float
        Sampling periods (s). Float32 ones are read as the numbers they print as (``np.float32(0.02)`` is the
        row 0.02, which :func:`pcrb_numbers` reads), the chapter's one rule for a period that labels a row.
    sigma : float
        Each sensor's noise (m).
    delta0 : float
        :math:`\Delta_0` of the source.

    Returns
    -------
    pandas.DataFrame
        Rows: the periods, then "T → 0" (for Q as printed the limit
        :math:`\sqrt{(-q + \sqrt{q^2 + 4qr})/2}` with :math:`q = \Delta_0^2`, :math:`r = \sigma^2/2`, a
        random walk of the position seen by two sensors; 0 for the other readings); columns the
        readings of :data:`fusion.scenarios.two_sensor.Q_READINGS`. Rounded to 2 decimals.

    Raises
    ------
    TypeError
        ``periods``, ``sigma`` or ``delta0`` not numbers.
    ValueError
        ``periods`` empty, repeated or not positive, or so many that their bounds are beyond the work budget
        (``fusion._limits.MAX_WORK``: about 1,250 periods), before any is read; ``sigma`` or ``delta0`` not valid, or
        together with a period giving a singular steady-state system (``delta0`` far beyond ``sigma``).
    """
    from fusion.scenarios import two_sensor as ts

    periods, n_periods = _counted(periods, "periods")   # read once, counted (fuzz 68b C1, C1b)
    work((n_periods,), "periods", weight=_PCRB_PERIOD)   # before any is checked (book audit 76)
    periods = _periods(periods)
    with derived("periods, sigma and delta0", "a steady-state PCRB"):
        rows = {float(T): {r: ts.pcrb_steady(float(T), sigma, ts.process_noise(float(T), delta0, r))
                           for r in ts.Q_READINGS} for T in periods}
    q, rr = delta0**2, sigma**2 / 2
    rows_t = pd.DataFrame(rows).T
    rows_t.loc[T_LIMIT] = [np.sqrt((-q + np.sqrt(q * q + 4 * q * rr)) / 2), 0.0, 0.0]
    rows_t.index.name = "sampling period T (s)"
    return rows_t.astype(float).round(2)


def _check_rows(rows: object) -> dict[tuple[Any, Any], dict[Any, float]]:
    """Refuse, naming ``rows``, anything but a non-empty mapping of (period, reading) pairs to mappings of column
    names to finite non-negative numbers (RMSEs and floors, m); return them as the plain dict of dicts of floats
    read, the one the callers use (fuzz 29b B5: pandas built no (period, reading) index from a ``mappingproxy``
    or a ``ChainMap``, mappings the docstrings allow)."""
    if not isinstance(rows, Mapping):
        raise TypeError(f"rows must be a mapping of (period, reading) -> values, got {type(rows).__name__}")
    if not rows:
        raise ValueError("rows is empty (it must be the result of fusion.scenarios.two_sensor.path_by_period)")
    out = {}
    for key, value in rows.items():
        if not isinstance(key, tuple) or len(key) != 2:
            raise ValueError(f"rows must be keyed by (period, reading) pairs, got the key {shown(key, 80)}")
        PERIOD_KEY(key[0], f"rows[{shown(key, 80)}]'s period")  # the chapter's rule (fuzz 32b C2)
        if not isinstance(value, Mapping):
            raise TypeError(f"rows[{shown(key)}] must be a mapping of column -> value, got {type(value).__name__}")
        out[key] = {col: scalar(v, f"rows[{shown(key)}][{shown(col)}]", 0.0, tiny=True) for col, v in value.items()}
    return out


def path_period_table(rows: Mapping[tuple[float, str], Mapping[str, float]]) -> pd.DataFrame:
    """:func:`fusion.scenarios.two_sensor.path_by_period` as a table: on the simulated path, per period and reading of Q.

    Parameters
    ----------
    rows : mapping of (float, str) to mapping of str to float
        Its result.

    Returns
    -------
    pandas.DataFrame
        Index: sampling period T (s), reading of Q; columns CI = average (x, then y), centralised KF (x) and the
        straight-leg floors, the smoother's and the causal one (m; exact RMSE over infinitely many runs, averaged
        over t ≥ 20 s). 2 decimals.

    Raises
    ------
    TypeError
        ``rows`` is not a mapping, or an entry not a mapping, or a value not a number.
    ValueError
        ``rows`` is empty, or a key is not a (period, reading) pair or its period not finite and > 0, or a value not
        finite and non-negative.
    """
    t = pd.DataFrame(_check_rows(rows)).T
    t.index.names = ["sampling period T (s)", "reading of Q"]
    return t.astype(float).round(2)


def path_numbers(rows: Mapping[tuple[float, str], Mapping[str, float]]) -> GlueValues:
    """The numbers the prose quotes from :func:`fusion.scenarios.two_sensor.path_by_period` (glue keys ``ci_path_*``).

    Parameters
    ----------
    rows : mapping
        Its result, with the periods 0.1 and 0.02 s and the printed and continuous white-acceleration readings.

    Returns
    -------
    dict
        Glue key -> value (m, 1 decimal).

    Raises
    ------
    TypeError
        ``rows`` is not a mapping of mappings, or a value not a number.
    ValueError
        ``rows`` lacks a (period, reading) row or a column read here, or a value is not finite and non-negative.
    """
    rows = _check_rows(rows)
    qp, qc = two_sensor.Q_READINGS[0], two_sensor.Q_READINGS[2]
    need = {(0.1, qp): (CI_AVERAGE, STRAIGHT_LEG_FLOOR, CAUSAL_FLOOR), (0.02, qp): (CI_AVERAGE, STRAIGHT_LEG_FLOOR,
            CAUSAL_FLOOR), (0.1, qc): (CI_AVERAGE,), (0.02, qc): (CI_AVERAGE,), (1.0, qp): (CI_AVERAGE, CENTRALISED_KF)}
    for key, cols in need.items():
        if key not in rows:
            raise ValueError(f"rows lacks the row {shown(key)} (it must hold the periods 0.1, 0.02 and 1 s)")
        lacking = [c for c in cols if c not in rows[key]]
        if lacking:
            raise ValueError(f"rows[{shown(key)}] lacks the columns {lacking}")
    g = lambda T, q, c: rounded(rows[(T, q)][c], 1)   # noqa: E731
    ci, fl = CI_AVERAGE, STRAIGHT_LEG_FLOOR
    return {"ci_path_ci_01": g(0.1, qp, ci), "ci_path_ci_002": g(0.02, qp, ci), "ci_path_cwa_01": g(0.1, qc, ci),
            "ci_path_cwa_002": g(0.02, qc, ci), "ci_path_floor_01": rounded(rows[(0.1, qp)][fl], 2),
            "ci_path_floor_002": rounded(rows[(0.02, qp)][fl], 2),
            "ci_path_causal_01": rounded(rows[(0.1, qp)][CAUSAL_FLOOR], 2),
            "ci_path_causal_002": rounded(rows[(0.02, qp)][CAUSAL_FLOOR], 2),
            "ci_exact_ci": rounded(rows[(1.0, qp)][ci], 1),
            "ci_exact_central": rounded(rows[(1.0, qp)][CENTRALISED_KF], 1)}


def pcrb_numbers(pcrb: pd.DataFrame, q_printed: str) -> GlueValues:
    """The posterior CRB values the prose quotes (glue keys ``ci_pcrb_*``).

    Parameters
    ----------
    pcrb : pandas.DataFrame
        :func:`pcrb_table` (index: period or "T → 0"; columns: readings of Q), of the chapter's printed noises: the
        table records neither ``sigma`` nor ``delta0``, so one of another case is glued as given (issue 35's class
        of results that no object records).
    q_printed : str
        The column of Q as printed.

    Returns
    -------
    dict
        Glue key -> position bound (m).

    References
    ----------
    * Wang, W., & Tang, Y. (2024), the chapter's source (see the bibliography).

    Raises
    ------
    TypeError
        ``pcrb`` not a DataFrame, or a cell of a reading of Q not a number.
    ValueError
        ``pcrb`` lacks a reading of Q or a row read here (periods 1, 0.02, 0.001 s and "T → 0"), holds a row or
        a reading twice, or a bound that is not finite and non-negative, or ``q_printed`` is not one of its columns.
    """
    _frame(pcrb, "pcrb", two_sensor.Q_READINGS, maker="pcrb_table", nonnegative=two_sensor.Q_READINGS)
    if not pcrb.index.is_unique:
        raise ValueError(f"pcrb must hold each period once (as pcrb_table makes it), got the rows "
                         f"{shown(list(pcrb.index[pcrb.index.duplicated()]), 80)} more than once")
    if not isinstance(q_printed, str) or q_printed not in pcrb.columns:
        raise ValueError(f"q_printed must be a column of pcrb (a reading of Q), got {shown(q_printed, 80)}")
    missing = [r for r in (1.0, 0.02, 0.001, T_LIMIT) if r not in pcrb.index]
    if missing:
        raise ValueError(f"pcrb lacks the rows {missing} (pcrb_table of periods including 1, 0.02 and 0.001 s)")
    return {"ci_pcrb_1": pcrb.loc[1.0, q_printed], "ci_pcrb_limit": pcrb.loc[T_LIMIT, q_printed],
            "ci_pcrb_002": pcrb.loc[0.02, q_printed], "ci_pcrb_dwa_002": pcrb.loc[0.02, two_sensor.Q_READINGS[1]],
            "ci_pcrb_dwa_0001": pcrb.loc[0.001, two_sensor.Q_READINGS[1]],
            "ci_pcrb_cwa_0001": pcrb.loc[0.001, two_sensor.Q_READINGS[2]]}
