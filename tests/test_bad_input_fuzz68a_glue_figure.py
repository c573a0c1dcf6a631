"""Fuzz 68a C1-C4, D1: glue_all weighs what a figure draws before auditing or rendering it, naming values['k']: a
text's path effect dashing or ticking its glyph outlines (C1a, C1b), the artists a text, annotation, table cell or
anchored box draws without listing them as children (C2, C3), a dash pattern by its on/off pairs (C4, C4b); and the
audit reports a text below 9 pt before drawing the figure (D1)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.patheffects as pe  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402

from _helpers import figure_axes as _axes, figure_refused as _refused, figure_glued as _glues  # noqa: E402
from _helpers import refused_quickly  # noqa: E402

#: A path effect's own dash pattern of a hundred-thousandth of a point (unscaled by the line width).
_FINE_GC = {"dash_offset": 0, "dash_list": [5e-5, 5e-5]}








def _text(effect, text: str = "W" * 40):
    fig, _ = _axes()
    fig.text(0.1, 0.5, text, fontsize=40).set_path_effects([effect])
    return fig


@pytest.mark.parametrize("effect", [pe.Stroke(linewidth=2, dashes=_FINE_GC), pe.withTickedStroke(spacing=1e-4),
                                    pe.withStroke(linewidth=2, dashes=_FINE_GC)],
                         ids=["stroke-dashes", "ticked", "withstroke-dashes"])
def test_a_text_dashed_or_ticked_along_its_outlines_is_refused(effect) -> None:
    """Fuzz 68a C1a (MemoryError after 22.8 CPU-s) and C1b (31.6 CPU-s accepted): refused before any rendering."""
    _refused(_text(effect))


def test_a_text_of_a_dashed_path_patch_effect_is_refused() -> None:
    effect = pe.PathPatchEffect(facecolor="none", edgecolor="0.3", linestyle=(0, (1e-4, 1e-4)))
    _refused(_text(effect, "W"))


def test_a_text_under_ordinary_path_effects_is_glued(monkeypatch: pytest.MonkeyPatch) -> None:
    """A text under a solid stroke, a hatched stroke and a shadow is glued (no dashes or ticks)."""
    fig, ax = _axes()
    ax.text(0.1, 0.5, "label", fontsize=12,
            path_effects=[pe.withStroke(linewidth=3, foreground="w"), pe.Stroke(hatch="/"), pe.withSimplePatchShadow()])
    _glues(monkeypatch, fig)


def test_an_annotations_arrow_is_weighed() -> None:
    """Fuzz 68a C2: a filled dashed arrow to 3000 axes widths (31.7 CPU-s accepted) is refused: the arrow is not a
    child of its annotation, and is placed only when drawn."""
    fig, ax = _axes()
    ax.annotate("", xy=(3000, 0.5), xytext=(0.1, 0.1), xycoords="axes fraction",
                arrowprops=dict(arrowstyle="-|>", color="black", linestyle=(0, (0.01, 0.01)), linewidth=1))
    _refused(fig)


def test_a_texts_box_is_weighed() -> None:
    """A text's box patch (not a child of its text) dashed a millionth of a point is refused."""
    fig, ax = _axes()
    ax.text(0.1, 0.5, "box", bbox=dict(facecolor="w", linestyle=(0, (1e-6, 1e-6))))
    _refused(fig)


def test_the_arrow_is_weighed_by_its_drawn_length() -> None:
    """The arrow's dashes grow with the distance it spans (its stand-in placed at the annotation's ends)."""
    from fusion.book import _glue_figure as F

    def dashes(x: float) -> int:
        fig, ax = _axes()
        ax.annotate("a", xy=(x, 0.5), xytext=(0.1, 0.1), xycoords="axes fraction",
                    arrowprops=dict(arrowstyle="-|>", linestyle="--"))
        try:
            return F._tally(fig)[F._DASHES]
        finally:
            plt.close(fig)

    short, far = dashes(1.0), dashes(100.0)
    assert short > 0 and far > 50 * short


def test_ordinary_annotations_and_text_boxes_are_glued(monkeypatch: pytest.MonkeyPatch) -> None:
    fig, ax = _axes()
    ax.annotate("peak", xy=(0.5, 0.5), xytext=(0.1, 0.9), arrowprops=dict(arrowstyle="-|>", linestyle="--"),
                bbox=dict(boxstyle="round", facecolor="w", linestyle=":"))
    ax.annotate("note", xy=(0.7, 0.2), xytext=(0.3, 0.3), arrowprops=dict(facecolor="0.3", shrink=0.05))
    _glues(monkeypatch, fig)


def test_a_table_cells_text_is_weighed() -> None:
    """Fuzz 68a C3: a table cell's text (not a child of its cell) of 10**5 characters, 28.4 CPU-s accepted."""
    fig, ax = _axes()
    ax.table(cellText=[["ab" * 50000]])
    _refused(fig)


def test_a_small_table_is_glued(monkeypatch: pytest.MonkeyPatch) -> None:
    from fusion.book import _glue_figure as F
    fig, ax = _axes()
    ax.table(cellText=[["1.0", "2.0"], ["3.0", "4.0"]], colLabels=["a", "b"])
    assert F._tally(fig)["characters"] >= 14        # the cells' texts counted
    _glues(monkeypatch, fig)


def test_a_dash_pattern_counts_its_pairs() -> None:
    """Fuzz 68a C4: Agg draws one dash per on/off pair: [d] * 32 draws 16 dashes a period, as (d, d) does one."""
    from fusion.book import _glue_figure as F

    def dashes(style) -> int:
        fig, ax = _axes()
        ax.plot([0, 1], [0, 1], color="0.3", linewidth=1.5, linestyle=style)
        try:
            return F._tally(fig)[F._DASHES]
        finally:
            plt.close(fig)

    pair, many = dashes((0, (1e-3, 1e-3))), dashes((0, [1e-3] * 32))
    assert abs(many - pair) <= 0.01 * pair
    assert abs(dashes((0, [1e-3] * 3)) - pair) <= 0.01 * pair      # odd: repeated twice, 3 pairs a double period


def test_a_many_pair_pattern_is_refused() -> None:
    """Fuzz 68a C4: three lines of [5e-6] * 32 (30.5 CPU-s accepted)."""
    fig, ax = _axes()
    for i in range(3):
        ax.plot([0, 1], [0.1 * i, 1], color="black", linewidth=1.5, linestyle=(0, [5e-6] * 32))
    _refused(fig)


def test_a_path_effects_many_pair_pattern_is_refused() -> None:
    """Fuzz 68a C4b: five lines under a Stroke of [3e-5] * 32 (22.2 CPU-s accepted)."""
    fig, ax = _axes()
    for i in range(5):
        line, = ax.plot([0, 1], [0.1 * i, 1], color="black", linewidth=1.5)
        line.set_path_effects([pe.Stroke(dashes={"dash_offset": 0, "dash_list": [3e-5] * 32})])
    _refused(fig)


def test_ordinary_many_pair_patterns_are_glued(monkeypatch: pytest.MonkeyPatch) -> None:
    fig, ax = _axes()
    ax.plot([0, 1], [0, 1], color="0.3", linestyle=(0, [6, 2, 1, 2] * 8))
    ax.plot([0, 1], [1, 0], color="0.3", path_effects=[pe.Stroke(dashes={"dash_offset": 0, "dash_list": [3, 1, 1]})])
    _glues(monkeypatch, fig)


def test_small_text_is_reported_before_drawing() -> None:
    """Fuzz 68a D1: a wrapped text of 1 pt, 30,000 words, was refused by the 9 pt rule after 13.5 CPU-s of drawing."""
    from fusion.book.figures import FigureStyleError, audit_figure
    from fusion.book.glue import glue_all
    fig, ax = _axes()
    fig.text(0.0, 0.5, "a " * 30000, fontsize=1, wrap=True)
    try:
        audit_figure(_axes()[0])                    # imports and caches, untimed
        refused_quickly(lambda: audit_figure(fig), FigureStyleError, "1.0 pt", cpu=2.0)
        with pytest.raises(FigureStyleError, match="1.0 pt"):   # untimed: the first use builds the glue's caches
            glue_all({"k": fig})
        refused_quickly(lambda: glue_all({"k": fig}), FigureStyleError, "1.0 pt", cpu=2.0)   # gc off
    finally:
        plt.close("all")
