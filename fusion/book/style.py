"""One figure style for the whole book.

Every notebook calls :func:`use_book_style` once and takes colours from
:data:`METHOD_COLORS`, so that a method has the same colour in every chapter.
"""

from __future__ import annotations

import matplotlib as mpl
import matplotlib.pyplot as plt
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from fusion._validation import instance_of

__all__ = ["METHOD_COLORS", "METHOD_LABELS", "use_book_style", "new_figure", "color"]

#: Colour of each method, used in every chapter.
METHOD_COLORS: dict[str, str] = {
    "optimal_fusion_set": "#0072B2",
    "mean": "#D55E00",
    "support_degree": "#009E73",
    "published": "#000000",
    "truth": "#777777",
    "bound": "#CC79A7",
    # chapter 07, time registration (Shi, Suo & Ma 2023)
    "two-point": "#E69F00",
    "improved: Kalman + three-point (§4)": "#56B4E9",
    # chapter 02, lecture notes (sections 2.1-2.7); Okabe-Ito, raw data in neutral grey
    "oracle": "#CC79A7",
    "awf_lecture": "#E69F00",
    "awf_centred": "#0072B2",
    "mean_of_means": "#009E73",
    "best_sensor": "#56B4E9",
    "check_awf": "#0072B2",
    "ls_learning": "#E69F00",
    "ls_corrected": "#0072B2",
    "gls": "#0072B2",
    "naive": "#D55E00",
    "raw": "#999999",
    "denoised": "#D55E00",
    "reconstructed": "#0072B2",
    "reconstructed_median": "#009E73",
    "sensor 1": "#0072B2",
    "sensor 2": "#D55E00",
    "sensor 3": "#009E73",
    "sensor 4": "#CC79A7",
    "X=0, no fault": "#0072B2",
    "X=0, fault": "#56B4E9",
    "X=900, no fault": "#D55E00",
    "X=900, fault": "#E69F00",
    "sample_variance": "#009E73",
    "memory_growing": "#E69F00",
    "memory_forgetting": "#0072B2",
    "memory_window": "#56B4E9",
}

#: Display label of each method.
METHOD_LABELS: dict[str, str] = {
    "optimal_fusion_set": "optimal fusion set",
    "mean": "arithmetic mean",
    "support_degree": "support degree (ref. [11], rebuilt)",
    "published": "published",
    "truth": "true value",
    # chapter 02, lecture notes (sections 2.1-2.7)
    "oracle": "oracle (true variances)",
    "awf_lecture": "AWF (lecture)",
    "awf_centred": "AWF (centred)",
    "mean_of_means": "mean of means",
    "best_sensor": "best sensor",
    "check_awf": "check + AWF",
    "ls_learning": "learned (lecture)",
    "ls_corrected": "corrected learning",
    "gls": "GLS = LDLᵀ",
    "naive": "naive (correlation ignored)",
    "raw": "raw",
    "denoised": "denoised",
    "reconstructed": "reconstructed (max)",
    "reconstructed_median": "reconstructed (median)",
    "sample_variance": "sample variance, growing memory",
    "memory_growing": "cross-moments, growing memory (lecture)",
    "memory_forgetting": "centred, forgetting",
    "memory_window": "centred, sliding window",
}

_STYLE = {
    "figure.dpi": 100,
    "savefig.dpi": 100,
    "figure.figsize": (7.0, 3.6),
    "figure.constrained_layout.use": True,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "axes.titlesize": 11,
    "axes.labelsize": 10,
    "legend.fontsize": 9,
    "legend.frameon": False,
    "xtick.labelsize": 9,
    "ytick.labelsize": 9,
    "lines.linewidth": 1.4,
    "svg.hashsalt": "fusion-book",
    "path.simplify": False,
}


def use_book_style() -> None:
    """Apply the book's matplotlib style (call once at the top of a notebook)."""
    mpl.rcParams.update(_STYLE)


def color(method: str) -> str:
    """Colour of a method; grey for methods without an assigned colour.

    Parameters
    ----------
    method : str
        Method key (as in :data:`METHOD_COLORS`).

    Returns
    -------
    str
        Hex colour, e.g. ``"#555555"``.
    """
    instance_of(method, str, "method")
    return METHOD_COLORS.get(method, "#555555")


def new_figure(nrows: int = 1, ncols: int = 1, **kwargs: object) -> tuple[Figure, Axes]:
    """Create a figure in the book style; keyword arguments go to :func:`matplotlib.pyplot.subplots`.

    Parameters
    ----------
    nrows, ncols : int
        Grid of axes.
    **kwargs
        Passed to :func:`matplotlib.pyplot.subplots` (e.g. ``figsize``).

    Returns
    -------
    fig : matplotlib.figure.Figure
    ax : matplotlib.axes.Axes or ndarray of them
    """
    use_book_style()
    fig, ax = plt.subplots(nrows, ncols, **kwargs)  # type: ignore[arg-type]
    return fig, ax
