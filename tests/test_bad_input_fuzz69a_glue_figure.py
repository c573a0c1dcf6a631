"""Fuzz 69a C1-C4: glue_all weighs what a figure draws before auditing or rendering it, naming values['k']: a
sawtooth or roundtooth box bounded by its perimeter over its tooth before its path is built (C1a, C1b), an artist of
a kind the weigher has no rule for (a Quiver, C2; an AnnotationBbox, C3) refused by its class, and a text box's
height by its line spacing (C4); the kinds the book's figures draw still glued."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.patches import FancyBboxPatch  # noqa: E402

from _helpers import figure_axes as _axes, figure_refused as _refused, figure_glued as _glues  # noqa: E402








def _text_box(boxstyle: str, **kw):
    fig, ax = _axes()
    ax.text(0.1, 0.5, "hello", bbox=dict(boxstyle=boxstyle), **kw)
    return fig


def _figure_box(boxstyle: str):
    fig, _ = _axes()
    fig.add_artist(FancyBboxPatch((0.1, 0.1), 0.5, 0.5, boxstyle=boxstyle, transform=fig.transFigure))
    return fig


def test_a_text_box_of_a_fine_sawtooth_is_refused_before_its_path_is_built() -> None:
    """Fuzz 69a C1a (tooth 1e-6: MemoryError inside the weigher after 5.5 CPU-s; 1e-5 refused after 3.6)."""
    _refused(_text_box("sawtooth,pad=0.3,tooth_size=1e-5"))


def test_a_figure_box_of_a_fine_roundtooth_is_refused_before_its_path_is_built() -> None:
    """Fuzz 69a C1b (tooth 1e-7: MemoryError after 8.2 CPU-s), at a tooth of 1e-6 (5.6e6 vertices)."""
    _refused(_figure_box("roundtooth,pad=0.1,tooth_size=1e-6"))


def test_a_box_of_a_style_not_known_is_refused_by_name() -> None:
    """A callable box style: its path's size is not read without building it."""
    from matplotlib.path import Path
    fig, _ = _axes()
    patch = FancyBboxPatch((0.1, 0.1), 0.5, 0.5, transform=fig.transFigure)
    patch.set_boxstyle(lambda x0, y0, w, h, mutation_size: Path.unit_rectangle())
    fig.add_artist(patch)
    _refused(fig, r"values\['k'\].*box style")


@pytest.mark.parametrize("make", [lambda: _text_box("sawtooth"), lambda: _text_box("roundtooth,pad=0.3"),
                                  lambda: _figure_box("roundtooth,pad=0.1,tooth_size=0.05"),
                                  lambda: _text_box("round4"), lambda: _text_box("darrow")],
                         ids=["text-sawtooth", "text-roundtooth", "figure-roundtooth", "round4", "darrow"])
def test_ordinary_boxes_are_still_glued(monkeypatch: pytest.MonkeyPatch, make) -> None:
    _glues(monkeypatch, make())


def test_a_quiver_is_refused_by_its_class() -> None:
    """Fuzz 69a C2 (20 dashed arrows accepted, 29.6 CPU-s): its arrows are made only when drawn; refused by name."""
    fig, ax = _axes()
    ax.quiver([0.5], [0.5], [1], [0])
    _refused(fig, r"values\['k'\].*Quiver")


def test_an_annotation_box_is_refused_by_its_class() -> None:
    """Fuzz 69a C3 (2 dashed arrows to a far point accepted, 33.2 CPU-s): its arrow's ends are set only when drawn."""
    from matplotlib.offsetbox import AnnotationBbox, TextArea
    fig, ax = _axes()
    ax.add_artist(AnnotationBbox(TextArea("x"), xy=(0.5, 0.5), xybox=(0.1, 0.1), xycoords="axes fraction",
                                 boxcoords="axes fraction", arrowprops=dict(arrowstyle="-|>")))
    _refused(fig, r"values\['k'\].*AnnotationBbox")


def _spaced(linespacing: float):
    fig, ax = _axes()
    ax.text(0.1, 0.5, "a\nb", linespacing=linespacing,
            bbox=dict(boxstyle="square", facecolor="w", edgecolor="k", linestyle=(0, (1e-4, 1e-4))))
    return fig


def test_a_text_box_is_weighed_by_its_line_spacing() -> None:
    """Fuzz 69a C4 (linespacing 1000, a dashed box: accepted, 30.3 CPU-s)."""
    _refused(_spaced(1000.0))


def test_a_dashed_text_box_of_ordinary_line_spacing_is_still_glued(monkeypatch: pytest.MonkeyPatch) -> None:
    fig, ax = _axes()
    ax.text(0.1, 0.5, "a\nb", linespacing=1.5,
            bbox=dict(boxstyle="square", facecolor="w", edgecolor="k", linestyle="--"))
    _glues(monkeypatch, fig)


def test_the_kinds_the_book_draws_are_still_weighed() -> None:
    """Lines, bars, bands, error bars, contours and a colour bar, spans, scatter, image, mesh, an annotation, a
    legend: none refused by its class, weighed within the budget (colours and labels off the book's registry, so
    weighed rather than glued: the audit refuses those)."""
    from fusion._limits import MAX_WORK
    from fusion.book import _glue_figure as F
    fig, (ax, bx) = plt.subplots(1, 2)
    x = np.linspace(0, 1, 20)
    ax.plot(x, x, label="line")
    ax.bar([0.5], [0.5], width=0.1, label="bar")
    ax.fill_between(x, x, x + 0.1, alpha=0.3, label="band")
    ax.errorbar([0.3], [0.3], yerr=[0.1], label="error")
    ax.axvspan(0.1, 0.2, alpha=0.2)
    ax.axhline(0.5)
    ax.hlines([0.7], 0, 1)
    ax.scatter(x, x, s=10, label="scatter")
    ax.annotate("here", xy=(0.5, 0.5), xytext=(0.2, 0.8), arrowprops=dict(arrowstyle="->"))
    ax.legend()
    grid = np.add.outer(x, x)
    cs = bx.contour(x, x, grid)
    bx.pcolormesh(x, x, grid[:-1, :-1], alpha=0.2)
    bx.imshow(grid, extent=(0, 1, 0, 1), alpha=0.2)
    fig.colorbar(cs, ax=bx)
    try:
        assert F.figure_units(fig, "k") < MAX_WORK
    finally:
        plt.close(fig)
