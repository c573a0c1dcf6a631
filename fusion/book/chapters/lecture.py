r"""Helpers shared by the three chapters on the lecture notes (source ``lecture003``).

Chapters 02 (:mod:`fusion.book.chapters.lecture_weighting`, sections 2.1-2.4), 03
(:mod:`fusion.book.chapters.lecture_wavelets`, section 2.6) and 04
(:mod:`fusion.book.chapters.lecture_correlated`, sections 2.5 and 2.7) each build their part of
the source's claims ledger; this module holds the source key and the glue helpers they share.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure

from fusion.book.tables import rounded

__all__ = ["SOURCE", "below", "glue_figures", "legend_below", "sci"]

SOURCE = "lecture003"


def _r(d: dict[str, tuple[float, int]]) -> dict[str, float]:
    """``{key: (value, decimals)}`` → ``{"lec_" + key: rounded value}``."""
    return {f"lec_{k}": rounded(v, dec) for k, (v, dec) in d.items()}


def glue_figures(figures: dict[str, Figure]) -> None:
    """Glue each figure under its key (not displayed) and close it, so the page shows it once.

    Parameters
    ----------
    figures : dict of str to matplotlib Figure
        Glue keys and figures; each figure is closed after gluing.
    """
    from fusion.book.figures import glue_figure

    for key, fig in figures.items():
        glue_figure(key, fig)   # checks the book's figure rules, glues, closes



def legend_below(fig: Figure, ncol: int = 3) -> None:
    """One legend for the whole figure, below the axes (never over data), 9 pt.

    Collects the labelled artists of every axes (each label once, in drawing order) and places a
    figure legend under the figure's bottom edge, so it can cover neither data nor axis labels.

    Parameters
    ----------
    fig : matplotlib Figure
        The finished figure.
    ncol : int
        Number of legend columns.
    """
    handles, labels = [], []
    for ax in fig.axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
        if ax.get_legend() is not None:
            ax.get_legend().remove()
    if handles:
        fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=ncol, fontsize=9,
                   frameon=False)


_SUP = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def sci(value: float, digits: int = 2) -> str:
    """A number for the reader in ``a × 10ⁿ`` form (no ``e`` notation); 0 is written ``0``.

    Parameters
    ----------
    value : float
        The number.
    digits : int
        Significant digits of the mantissa.

    Returns
    -------
    str
        E.g. ``sci(1.75e11, 3) == "1.75 × 10¹¹"``.
    """
    v = float(value)
    if v == 0.0 or not np.isfinite(v):
        return f"{v:g}"
    e = int(np.floor(np.log10(abs(v))))
    m = round(v / 10.0**e, digits - 1)
    if abs(m) >= 10:
        m, e = m / 10, e + 1
    return f"{m:.{digits - 1}f} × 10{str(e).translate(_SUP)}"


def below(value: float, bound: float) -> str:
    """A round-off difference for the record: ``"below 10⁻¹²"`` when ``value < bound``, else the value.

    Differences at the level of round-off (10⁻¹⁷ to 10⁻¹⁵) change with the BLAS kernel and the
    thread count; a stored record must not. The bound is the check's own tolerance, so the text and
    the check's verdict always agree.

    Parameters
    ----------
    value : float
        The computed difference (>= 0).
    bound : float
        The tolerance of the check, a power of ten.

    Returns
    -------
    str
        ``"below 10⁻ⁿ"`` or, when the check fails, the value itself (:func:`sci`).
    """
    v, b = float(value), float(bound)
    if not (np.isfinite(b) and b > 0):
        raise ValueError(f"bound must be a positive finite number, got {bound!r}")
    if v < b:
        return f"below 10{str(int(round(np.log10(b)))).translate(_SUP)}"
    return sci(v, 2)
