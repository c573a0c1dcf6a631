r"""The signal × threshold-rule verdicts of chapter 03 and the normalisers' numbers (the ``sg`` study).
"""

from __future__ import annotations

from fusion._docstrings import with_sections
from fusion._validation import instance_of

import numpy as np
import pandas as pd

from fusion._validation import one_of
from fusion.book.chapters.lecture import _r
from fusion.book.chapters.lecture_wavelets.verdicts import _q, cell, status_text
from fusion.book.style import METHOD_LABELS
from fusion.scenarios.wavelet_sensors import Signal, SignalStudy
from fusion.book.glue import GlueValues
from fusion.book._few_runs import studies_runs_named

__all__ = ["QUESTIONS", "table_signals", "glue_signals"]

#: The Raises section of the functions that judge the runs of ``sg`` and ``e26`` (written once).
_RAISES = with_sections(raises="""TypeError
    ``sg`` not a SignalStudy, ``e26`` neither None nor a SignalStudy.
ValueError
    ``sg`` or ``e26`` of fewer than :data:`~fusion.book.rulebook.MIN_RUNS` runs (rule R4: the verdicts compare
    runs), named; ``e26`` of another setup than ``sg`` (other gains, sigma or signal length).""")


#: The four questions of the signal table, one per record: (short id, column, A, B, metric).
QUESTIONS: tuple[tuple[str, str, str, str, str], ...] = (
    ("better", "variance < raw", "reconstructed", "raw", "evar"),
    ("accurate", "MSE < raw", "reconstructed", "raw", "mse"),
    ("helps", "MSE < own denoised", "reconstructed", "denoised", "mse"),
    ("order", "lecture's order < fuse first", "reconstructed", "fuse-first", "mse"),
)


#: Columns of :func:`table_signals` shown by ``part="normalisers"`` (the others, with the runs, are ``"verdicts"``).
_NORM_COLUMNS = ("RMS gain error of max, sensor 3", "median normaliser: MSE < own denoised",
                 "max of the raw data: MSE < own denoised", "data variance over time < raw and < own denoised")


@_RAISES
@studies_runs_named("sg", "e26")  # rule R4 named by the study argument
def table_signals(sg: SignalStudy, e26: SignalStudy | None = None, part: str = "all") -> pd.DataFrame:
    """Verdict of each question for every sensor at once, under each signal and threshold rule (max normaliser).

    Parameters
    ----------
    sg : SignalStudy
        Result of :func:`fusion.scenarios.wavelet_sensors.signal_study` (normalisers ``("max", ...)``,
        and ``"median"`` among them; ``"max-raw"`` adds a column).
    e26 : SignalStudy, optional
        E2.6, the primary signal and rule with more runs: its row is taken from it (:func:`cell`). The two
        studies are compared by their setup only (gains, sigma, signal length: a study of another setup is refused,
        fuzz 32b D3, as ``glue_mechanism`` refuses it), not by their roles (fuzz 22b q4): given swapped, the row of
        the study passed as ``e26`` is shown with its runs and the label "E2.6".
    part : {"all", "verdicts", "normalisers"}
        Every column, or one of the two halves that fit the page: the runs and the questions of
        :data:`QUESTIONS`, or the columns about the normaliser and the spread over time.

    Returns
    -------
    pandas.DataFrame
        Rows (signal, by the label of its :class:`~fusion.scenarios.wavelet_sensors.Signal` key; rule); the runs; one column per question of :data:`QUESTIONS` (status, and the sensors
        that decide it), the temporal variance of the data against the raw and the denoised data for the
        constant measurand, the RMS gain error of the maximum for sensor 3, and the question "MSE <
        own denoised" with the median normaliser and with the maximum of the raw data instead.
    """
    instance_of(sg, SignalStudy, "sg")
    rows = {}
    for kind in sg.signals:
        for mode in sg.modes:
            key = (kind, mode, "max")
            n = cell(sg, e26, key).runs
            r = {"runs": f"{n} (E2.6: reading more-runs)" if n != sg.runs else str(n)}
            r.update({col: status_text(_q(sg, key, a, b, m, e26)) for _, col, a, b, m in QUESTIONS})
            r["data variance over time < raw and < own denoised"] = (
                "; ".join(status_text(_q(sg, key, "reconstructed", ref, "tvar", e26)) for ref in ("raw", "denoised"))
                if kind is Signal.CONSTANT else "(signal varies)")
            r["RMS gain error of max, sensor 3"] = f"{np.sqrt(np.mean(cell(sg, e26, key).case['gain_err'][:, 2] ** 2)):.4f}"
            r["median normaliser: MSE < own denoised"] = status_text(
                _q(sg, (kind, mode, "median"), "reconstructed", "denoised", "mse", e26))
            if "max-raw" in sg.normalisers:
                r["max of the raw data: MSE < own denoised"] = status_text(
                    _q(sg, (kind, mode, "max-raw"), "reconstructed", "denoised", "mse", e26))
            rows[METHOD_LABELS[kind], mode] = r                        # the signal's label
    tab = pd.DataFrame(rows).T
    tab.index.names = ["signal", "threshold"]
    part = one_of(part, ("all", "verdicts", "normalisers"), "part")
    if part == "all":
        return tab
    norm = [c for c in _NORM_COLUMNS if c in tab.columns]
    return tab[norm] if part == "normalisers" else tab.drop(columns=norm)


@_RAISES
@studies_runs_named("sg", "e26")  # rule R4 named by the study argument
def glue_signals(sg: SignalStudy, e26: SignalStudy | None = None) -> GlueValues:
    """Glue values of the signal × rule study (keys ``lec_ws_*``).

    Parameters
    ----------
    sg, e26 : SignalStudy
        As :func:`table_signals`.

    Returns
    -------
    GlueValues
        For every signal and rule (tags ``th`` = two tones, hard; ``ss`` = slow, soft; ...): MSEs ×10⁴ of
        every sensor raw / denoised / reconstructed, their error and temporal variances ×10⁴, the RMS
        gain errors of the maximum (and of the median and the raw maximum) and the reconstruction's MSE with
        those normalisers; counts of (signal, rule) cells in which each question holds.
    """
    instance_of(sg, SignalStudy, "sg")
    d: dict[str, tuple[float, int]] = {}
    short = {Signal.TWO_TONES: "t", Signal.SLOW: "s", Signal.CONSTANT: "c", Signal.HEAVISINE: "h"}
    for kind in sg.signals:
        for mode in sg.modes:
            c = cell(sg, e26, (kind, mode, "max")).case
            tag = f"{short[kind]}{mode[0]}"
            for j in range(len(sg.gains)):
                for k in ("raw", "denoised", "reconstructed"):
                    d[f"ws_{tag}_{k[:3]}_{j + 1}"] = (1e4 * c[k]["mse"][:, j].mean(), 2)
                    d[f"ws_{tag}_v{k[:3]}_{j + 1}"] = (1e4 * c[k]["evar"][:, j].mean(), 2)
                    if "tvar" in c[k]:
                        d[f"ws_{tag}_t{k[:3]}_{j + 1}"] = (1e4 * c[k]["tvar"][:, j].mean(), 2)
                d[f"ws_{tag}_gain_{j + 1}"] = (float(np.sqrt(np.mean(c["gain_err"][:, j] ** 2))), 4)
                for nm, short_nm in (("median", "med"), ("max-raw", "rawmax")):
                    if (kind, mode, nm) in sg.cases:
                        cm = cell(sg, e26, (kind, mode, nm)).case
                        d[f"ws_{tag}_gain{short_nm}_{j + 1}"] = (float(np.sqrt(np.mean(cm["gain_err"][:, j] ** 2))), 4)
                        d[f"ws_{tag}_{short_nm}_{j + 1}"] = (1e4 * cm["reconstructed"]["mse"][:, j].mean(), 2)
                        d[f"ws_{tag}_{short_nm}_raw_{j + 1}"] = (1e4 * cm["raw"]["mse"][:, j].mean(), 2)
                        d[f"ws_{tag}_{short_nm}_den_{j + 1}"] = (1e4 * cm["denoised"]["mse"][:, j].mean(), 2)
    out = _r(d)
    for qid, _, a, b, m in QUESTIONS:
        st = [_q(sg, (kind, mode, "max"), a, b, m, e26).status() for kind in sg.signals for mode in sg.modes]
        for s_, short_s in (("reproduced", "r"), ("contradicted", "c"), ("not distinguishable", "n")):
            out[f"lec_ws_n_{qid}_{short_s}"] = int(sum(x == s_ for x in st))
    out["lec_ws_n_cells"] = len(sg.signals) * len(sg.modes)
    out["lec_ws_runs"] = int(sg.runs)
    return out
