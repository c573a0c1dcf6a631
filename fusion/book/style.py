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
}

#: Display label of each method.
METHOD_LABELS: dict[str, str] = {
    "optimal_fusion_set": "optimal fusion set",
    "mean": "arithmetic mean",
    "support_degree": "support degree (ref. [11], rebuilt)",
    "published": "published",
    "truth": "true value",
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
    """Colour of a method; grey for methods without an assigned colour (documented, not an error)."""
    instance_of(method, str, "method")
    return METHOD_COLORS.get(method, "#555555")


def new_figure(nrows: int = 1, ncols: int = 1, **kwargs: object) -> tuple[Figure, Axes]:
    """Create a figure in the book style; keyword arguments go to :func:`plt.subplots`."""
    use_book_style()
    fig, ax = plt.subplots(nrows, ncols, **kwargs)  # type: ignore[arg-type]
    return fig, ax
