r"""The lecture's step 3, the variance of the weights (:func:`fusion.scenarios.wavelet_sensors.variance_study`).
"""

from __future__ import annotations

from fusion._validation import instance_of

import numpy as np
import pandas as pd

from fusion.book.chapters.lecture import _holds, _r
from fusion.book.ledger import Comparison, Conjunction
from fusion.book.style import METHOD_SHORT_LABELS
from fusion.book.chapters.lecture_wavelets.verdicts import _metric_label, sensor_conjunction
from fusion.scenarios.wavelet_sensors import VarianceStudy
from fusion.book.glue import GlueValues, _glue_prefix
from fusion.book._few_runs import studies_runs_named
from fusion._docstrings import ParameterDocs

__all__ = ["table_variance", "glue_variance", "glue_weighting"]

#: The parameter of this module's functions, documented once.
_PARAMS = ParameterDocs({"v": "VarianceStudy\n    Result of :func:`fusion.scenarios.wavelet_sensors.variance_study`."})


@_PARAMS("v")
def table_variance(v: VarianceStudy) -> pd.DataFrame:
    """Each reading of step 3: the reconstruction's MSE (×10⁴) for sensors 1 and 4, sensor 1's weight, win fraction.

    Returns
    -------
    pandas.DataFrame
        One row per reading (text, fixed decimals): MSE ×10⁴ of the reconstruction of sensor 1 (the
        most accurate) and sensor 4 (the noisiest), 2 decimals; sensor 1's mean weight at the last
        sample and the SD of its weight along the signal, 3 decimals; the fraction of runs in which
        sensor 1's reconstruction beats its own denoised signal, 2 decimals. The first two rows
        give the raw and denoised MSEs for reference.
    """
    instance_of(v, VarianceStudy, "v")
    last = v.gains.size - 1
    c1, c4 = "sensor 1 ×10⁴", f"sensor {last + 1} ×10⁴"
    cw, cs, cp = "W₁ at the end", "SD of W₁ along the signal", "P(rec. < denoised), sensor 1"
    rows: dict[str, dict[str, str]] = {}
    for key, e in (("raw", v.raw), ("denoised", v.denoised)):
        rows[METHOD_SHORT_LABELS[key]] = {c1: f"{1e4 * e[:, 0].mean():.2f}", c4: f"{1e4 * e[:, last].mean():.2f}", cw: "", cs: "", cp: ""}
    for r in v.readings:
        e = v.err[r]
        rows[f"reconstructed: {r}"] = {c1: f"{1e4 * e[:, 0].mean():.2f}", c4: f"{1e4 * e[:, last].mean():.2f}",
                                       cw: f"{v.w_final[r][0]:.3f}", cs: f"{v.w_spread[r]:.3f}",
                                       cp: f"{np.mean(e[:, 0] < v.denoised[:, 0]):.2f}"}
    tab = pd.DataFrame(rows).T
    tab.index.name = f"MSE against gⱼS, {v.runs} runs"
    return tab


def _vconj(v: VarianceStudy, r: str, ref: str, metric: str = "mse") -> Conjunction:
    a = v.err[r] if metric == "mse" else v.evar[r]
    if ref == "equal-weights":
        b, b_name = (v.err["equal"] if metric == "mse" else v.evar["equal"]), "reconstructed, equal weights"
    else:
        b = {("raw", "mse"): v.raw, ("denoised", "mse"): v.denoised, ("raw", "evar"): v.raw_evar,
             ("denoised", "evar"): v.denoised_evar}[ref, metric]
        b_name = METHOD_SHORT_LABELS[ref]
    return sensor_conjunction(a, b, f"reconstructed, {r} variance", b_name, _metric_label(v, metric), v.seed)


@_PARAMS("v")
@studies_runs_named("v")  # rule R4 named by the study argument
def glue_variance(v: VarianceStudy) -> GlueValues:
    """Glue values of the step-3 study (keys ``lec_wvar_*``).

    Returns
    -------
    GlueValues
        Sensor 1's MSE ×10⁴ under each reading, its final weight, the paired differences (×10⁴)
        of the recursive readings against the batch variance with their 95 % intervals, the oracle
        weights' difference from the sensor's own denoised signal, and the statuses (every sensor) of
        the records under each reading as counts.

    Raises
    ------
    TypeError
        ``v`` not a VarianceStudy.
    ValueError
        ``v`` of fewer than :data:`~fusion.book.rulebook.MIN_RUNS` runs (rule R4: the statuses compare runs), or
        of fewer than 4 sensors (``lec_wvar_rec_*_4`` is sensor 4's).
    """
    instance_of(v, VarianceStudy, "v")
    _holds(range(1, v.gains.size + 1), (4,), "v", "sensor", "glue_variance")
    d: dict[str, tuple[float, int]] = {"wvar_den_1": (1e4 * v.denoised[:, 0].mean(), 2),
                                       "wvar_raw_1": (1e4 * v.raw[:, 0].mean(), 2),
                                       "wvar_w_true_1": (v.w_true[0], 3)}
    for r in v.readings:
        d[f"wvar_rec_{r}_1"] = (1e4 * v.err[r][:, 0].mean(), 2)
        d[f"wvar_rec_{r}_4"] = (1e4 * v.err[r][:, 3].mean(), 2)
        d[f"wvar_w1_{r}"] = (v.w_final[r][0], 3)
        d[f"wvar_wsd_{r}"] = (v.w_spread[r], 3)
        if r != "batch":
            c = Comparison(v.err[r][:, 0], v.err["batch"][:, 0], r, "batch", "less", "MSE", seed=v.seed)
            mean, lo, hi = c.interval()
            d[f"wvar_d_{r}"], d[f"wvar_lo_{r}"], d[f"wvar_hi_{r}"] = (1e4 * mean, 3), (1e4 * lo, 3), (1e4 * hi, 3)
    for j in range(v.gains.size):
        d[f"wvar_w_oracle_{j + 1}"] = (v.w_final["oracle"][j], 3)
        d[f"wvar_w_batch_{j + 1}"] = (v.w_final["batch"][j], 3)
    out = _r(d)
    readings = [r for r in v.readings if r not in ("equal", "oracle")]
    out["lec_wvar_n"] = len(readings)
    for name, ref in (("raw", "raw"), ("den", "denoised")):
        st = [_vconj(v, r, ref).status() for r in readings]
        for s_, short in (("reproduced", "r"), ("contradicted", "c"), ("not distinguishable", "n")):
            out[f"lec_wvar_n_{name}_{short}"] = int(sum(x == s_ for x in st))
    out["lec_wvar_window"] = int(v.window)
    out["lec_wvar_runs"] = int(v.runs)
    return out


def _weighting(v: VarianceStudy, r: str = "batch") -> Comparison:
    """The fused normalised signal's MSE against S/max S (×10⁻⁴): inverse-variance weights of reading ``r`` vs equal."""
    return Comparison(1e4 * np.asarray(v.fused_mse[r]), 1e4 * np.asarray(v.fused_mse["equal"]),
                      f"fused Ŷ, weights from the {r} variance", "fused Ŷ, equal weights", "less",
                      "MSE of Ŷ against S/max S, ×10⁻⁴", seed=v.seed)


@studies_runs_named("v")  # rule R4 named by the study argument
def glue_weighting(v: VarianceStudy, key: str = "wwt") -> GlueValues:
    """Glue values of the weighting claim (keys ``lec_<key>_*``): credibility weights against equal weights.

    Parameters
    ----------
    v : VarianceStudy
        Result of :func:`fusion.scenarios.wavelet_sensors.variance_study` (``"batch"`` and ``"equal"`` among
        its readings).
    key : str
        Glue prefix (``"wwt"``: the record's primary, the lecture's model; ``"wwb"``: the book's model).

    Returns
    -------
    GlueValues
        The fused signal's MSE ×10⁴ under both weightings and their paired difference with its 95 %
        interval (×10⁴, 3 decimals); per sensor, the reconstruction's paired difference (×10⁴, 2 decimals),
        its interval, its median (×10⁴), the share of runs in which the credibility weights win and the tail
        index (R3); the number of sensors whose reconstruction is better with the credibility weights.

    Raises
    ------
    TypeError
        ``v`` not a VarianceStudy, ``key`` not a str.
    ValueError
        ``key`` not a glue key prefix (ASCII letters, digits and underscores), ``v`` of fewer than
        :data:`~fusion.book.rulebook.MIN_RUNS` runs (rule R4) or without ``"batch"`` or ``"equal"`` among its
        readings.
    """
    instance_of(v, VarianceStudy, "v")
    _holds(v.readings, ("batch", "equal"), "v", "readings", "glue_weighting")   # fuzz 39b C8: a raw KeyError before
    key = _glue_prefix(key, "key")
    c = _weighting(v)
    mean, lo, hi = c.interval()
    d: dict[str, tuple[float, int]] = {"fused_batch": (1e4 * float(np.mean(v.fused_mse["batch"])), 3),
                                       "fused_equal": (1e4 * float(np.mean(v.fused_mse["equal"])), 3),
                                       "d": (mean, 3), "lo": (lo, 3), "hi": (hi, 3)}
    conj = _vconj(v, "batch", "equal-weights")
    for j, (_, ev) in enumerate(conj.parts):
        m_, l_, h_ = ev.interval()
        d[f"d_{j + 1}"], d[f"lo_{j + 1}"], d[f"hi_{j + 1}"] = (1e4 * m_, 2), (1e4 * l_, 2), (1e4 * h_, 2)
        jd = ev.judgement()
        d[f"med_{j + 1}"] = (1e4 * float(np.median(v.err["batch"][:, j] - v.err["equal"][:, j])), 2)
        d[f"win_{j + 1}"] = (float(jd.share), 3)
        d[f"tail_{j + 1}"] = (float(jd.tail_index) if np.isfinite(jd.tail_index) else float("nan"), 2)
    out = _r({f"{key}_{k}": x for k, x in d.items()})
    out[f"lec_{key}_n_better"] = int(sum(ev.status() == "reproduced" for _, ev in conj.parts))
    out[f"lec_{key}_n_worse"] = int(sum(ev.status() == "contradicted" for _, ev in conj.parts))
    return out
