"""The cross-check against a peer library: Stone Soup's ChernoffUpdater.

Part of :mod:`fusion.book.chapters.chernoff` (chapter 06, patent CN107330468B), which re-exports its public names."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from fusion._counts import _first_repeat
from fusion._covariances import as_covariance
from fusion._shown import shown
from fusion._validation import as_array, scalar
from fusion._validation import record as _record
from fusion.book.glue import GlueValues
from fusion._paths import file_json

__all__ = ["stonesoup_check", "STONESOUP_RECORD"]


#: Stone Soup's ChernoffUpdater outputs, recorded by ``benchmarks/crosscheck_stonesoup.py`` in a side environment.
STONESOUP_RECORD = Path(__file__).resolve().parents[3] / "data" / "peers" / "stonesoup_chernoff.json"


def stonesoup_check(record: dict[str, Any] | None = None) -> tuple[pd.DataFrame, GlueValues]:
    r"""Stone Soup's ``ChernoffUpdater`` at ω ≠ 0.5 against the Chernoff normaliser and our fusion.

    For a measurement :math:`\mathcal N(a, A)` weighted :math:`\omega` and a prediction :math:`\mathcal N(b, B)`
    weighted :math:`1-\omega`, the normaliser is :math:`Z \propto \exp(-\tfrac12 (a-b)^\top V^{-1}(a-b))` with
    :math:`V = A/\omega + B/(1-\omega)`: the covariance a gate on :math:`a - b` should use. Here :math:`V` is
    obtained independently, as the inverse Hessian in :math:`a` of :math:`-\log Z`
    (:func:`fusion.estimates.chernoff.log_normaliser_two_gaussians`, central differences).

    Parameters
    ----------
    record : dict, optional
        The recorded outputs (default: :data:`STONESOUP_RECORD`); a record lacking a key read here is refused
        by name (ValueError).

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

    Raises
    ------
    TypeError
        ``record`` or a part of it not a mapping, a recorded number not a real number.
    ValueError
        ``record`` lacking a key read here, no rows, a recorded number NaN or infinite, an array of another shape
        than the measurement's dimension gives, an ω outside (0, 1), or two rows at one ω (each named by its place
        in the record).

    References
    ----------
    * Hurley, M. B. (2002). An information theoretic justification for covariance intersection and its
      generalization. Proc. FUSION 2002, 505-511.
    * Stone Soup (dstl), ``stonesoup.updater.chernoff.ChernoffUpdater``.
    """
    from fusion.estimates.chernoff import chernoff_fuse_gaussians, log_normaliser_two_gaussians

    rec = record if record is not None else file_json(STONESOUP_RECORD, "the Stone Soup record")
    _record(rec, "record", ("measurement", "prediction", "rows", "stonesoup_version"), extra=True)
    for part in ("measurement", "prediction"):
        _record(rec[part], f"record[{part!r}]", ("mean", "covariance"), extra=True)
    version = rec["stonesoup_version"]  # glued as the version in the prose (fuzz 24b SS6: None or NaN was glued)
    if not isinstance(version, str):
        raise TypeError(f"record['stonesoup_version'] must be a string, got {type(version).__name__}")
    if not version.strip():
        raise ValueError("record['stonesoup_version'] must be a non-empty string")
    rows_in = rec["rows"]  # read twice (checked, then compared): a list, not a one-pass iterator (fuzz 24b SS7)
    if not isinstance(rows_in, (list, tuple)):
        raise TypeError(f"record['rows'] must be a list of recorded rows, got {type(rows_in).__name__}")
    if not rows_in:
        raise ValueError("record['rows'] must be a non-empty list of recorded rows")
    for i, r in enumerate(rows_in):
        _record(r, f"record['rows'][{i}]", ("omega", "innovation_covariance", "posterior_mean", "posterior_covariance"),
                extra=True)
    # every recorded number checked by its place in the record (issue 35: a NaN or a wrong shape was refused, if at
    # all, by an inner function naming its own argument; fuzz 24b SS5: an indefinite A named "A" or "covs[0]")
    a = as_array(rec["measurement"]["mean"], "record['measurement']['mean']", ndim=1)
    d = a.size
    A = as_covariance(rec["measurement"]["covariance"], d, "record['measurement']['covariance']")
    b = as_array(rec["prediction"]["mean"], "record['prediction']['mean']", shape=(d,))
    B = as_covariance(rec["prediction"]["covariance"], d, "record['prediction']['covariance']")
    checked = []   # the values checked are the values used (fuzz 58b C1: a second read of r[key] could differ)
    for i, r in enumerate(rows_in):
        at = f"record['rows'][{i}]"
        row = {"omega": scalar(r["omega"], f"{at}['omega']", 0.0, 1.0, lo_open=True, hi_open=True)}
        for key, shape in (("innovation_covariance", (d, d)), ("posterior_mean", (d,)),
                           ("posterior_covariance", (d, d))):
            row[key] = as_array(r[key], f"{at}[{key!r}]", shape=shape)
        checked.append(row)
    rows_in = checked
    repeat = _first_repeat(float(r["omega"]) for r in rows_in)  # the table has one row per ω (fuzz 36b B7: the last
    if repeat is not None:                                        # row of a repeated ω replaced the first silently)
        i, j, w = repeat
        raise ValueError(f"record['rows'] must hold one row per omega: record['rows'][{i}] and record['rows'][{j}] "
                         f"are both at omega {shown(w)}")
    if not any(float(r["omega"]) == 0.8 for r in rows_in):  # chf_ss_v_08 is read there (fuzz 24b SS1: KeyError)
        raise ValueError("record['rows'] must hold a row with omega 0.8 (the value chf_ss_v_08 reports)")
    rel = lambda x, y: float(np.linalg.norm(np.asarray(x) - np.asarray(y)) / np.linalg.norm(y))  # noqa: E731

    def rel_mean(x: Any, y: Any) -> float:
        """A posterior mean's difference relative to the larger norm (0 for two zero means; fuzz 24b SS4)."""
        x, y = np.asarray(x, float), np.asarray(y, float)
        top = max(np.linalg.norm(x), np.linalg.norm(y))
        return float(np.linalg.norm(x - y) / top) if top > 0 else 0.0

    rows = {}
    for r in rows_in:
        w = float(r["omega"])
        H = np.empty((d, d))
        f = lambda x: -log_normaliser_two_gaussians(x, A, b, B, w)  # noqa: E731
        # -log Z is quadratic in a, so central differences are exact for any step but for rounding, which a step
        # of a tenth of the standard deviation the curvature implies keeps relative (fuzz 24b SS2/SS3: an absolute
        # step of 1e-3 lost the curvature to cancellation in other units or at omega 1e-12, LinAlgError). The
        # step only scales the differences: the curvature measured is still that of -log Z.
        h = 0.1 * np.sqrt(np.diagonal(A) / w + np.diagonal(B) / (1 - w))
        for i in range(d):
            for j in range(d):
                ei, ej = np.eye(d)[i] * h[i], np.eye(d)[j] * h[j]
                H[i, j] = (f(a + ei + ej) - f(a + ei - ej) - f(a - ei + ej) + f(a - ei - ej)) / (4 * h[i] * h[j])
        V = np.linalg.inv((H + H.T) / 2)
        ours = chernoff_fuse_gaussians(np.stack([a, b]), np.stack([A, B]), [w, 1 - w])
        Vs = np.array(r["innovation_covariance"], float)
        rows[w] = {"innovation covariance vs V = A/ω + B/(1−ω)": rel(Vs, V),
                   "vs the swapped A/(1−ω) + B/ω": rel(Vs, A / (1 - w) + B / w),
                   "posterior mean vs our fusion": rel_mean(r["posterior_mean"], ours.x),
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
        _record(case, "record['detection_case']", ("omega", "detection_covariance", "innovation_covariance",
                                                   "posterior_mean", "posterior_covariance"), extra=True)
        w = scalar(case["omega"], "record['detection_case']['omega']", 0.0, 1.0, lo_open=True, hi_open=True)
        A2 = as_covariance(case["detection_covariance"], d, "record['detection_case']['detection_covariance']")
        Vd = as_array(case["innovation_covariance"], "record['detection_case']['innovation_covariance']", shape=(d, d))
        case = {key: as_array(case[key], f"record['detection_case'][{key!r}]", shape=shape)   # used as checked
                for key, shape in (("posterior_mean", (d,)), ("posterior_covariance", (d, d)))}
        ours = chernoff_fuse_gaussians(np.stack([a, b]), np.stack([A2, B]), [w, 1 - w])
        g3 = lambda x: float(f"{x:.3g}") if x > 1e-6 else 0.0  # noqa: E731
        values.update(chf_ss_det_model=g3(rel(Vd, A / (1 - w) + B / w)), chf_ss_det_v=g3(rel(Vd, A2 / w + B / (1 - w))),
                      chf_ss_det_post=g3(max(rel_mean(case["posterior_mean"], ours.x), rel(case["posterior_covariance"], ours.P))))
        for key in ("chf_ss_det_model", "chf_ss_det_post"):  # the same words as above for a difference below 1e-6
            values[key + "_text"] = ("to round-off (relative difference below 10⁻⁶)" if values[key] == 0.0
                                     else f"up to a relative difference of {values[key]:.3g}")
    return table, values
