r"""Helpers shared by the three chapters on the lecture notes (source ``lecture003``).

Chapters 02 (:mod:`fusion.book.chapters.lecture_weighting`, sections 2.1-2.4), 03
(:mod:`fusion.book.chapters.lecture_wavelets`, section 2.6) and 04
(:mod:`fusion.book.chapters.lecture_correlated`, sections 2.5 and 2.7) each build their part of
the source's claims ledger; this module holds the source key and the glue helpers they share.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
from matplotlib.figure import Figure

from fusion.book.tables import rounded

__all__ = ["SOURCE", "glue_figures"]

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

