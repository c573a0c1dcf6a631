"""Fuzz 67a C2/C4: glue_all weighs a filled or hatched dashed patch or collection by its whole dashed length (Agg clips
a stroke to the figure before dashing it only when the path is neither filled nor hatched), and a path effect's own
dashes and hatch, before auditing or rendering the figure, naming values['k']."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.patheffects as pe  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.patches import Polygon, Rectangle  # noqa: E402

from _helpers import figure_axes as _axes, figure_refused as _refused  # noqa: E402

#: A dash pattern of a thousandth of a point (fuzz 67a's), and a path effect's (unscaled by the line width).
_FINE = (0, (1e-3, 1e-3))
_FINE_GC = {"dash_offset": 0, "dash_list": [1e-5, 1e-5]}




def _glues(monkeypatch: pytest.MonkeyPatch, fig) -> None:
    """glue_all glues ``fig`` (audited and rendered; ``myst_nb.glue`` replaced for the test)."""
    import myst_nb

    from fusion.book.glue import glue_all
    monkeypatch.setattr(myst_nb, "glue", lambda *args, **kwargs: None)
    glue_all({"k": fig})




def _within(fig) -> int:
    """``fig``'s units, within the budget."""
    from fusion._limits import MAX_WORK
    from fusion.book import _glue_figure as F
    try:
        units = F.figure_units(fig, "k")
    finally:
        plt.close(fig)
    assert units <= MAX_WORK
    return units


def _huge_rectangle(**kw) -> object:
    fig, ax = _axes()
    ax.add_patch(Rectangle((0, 0), 1e6, 1e6, edgecolor="0.3", linestyle=_FINE, **kw))
    return fig


def _huge_polygon(**kw) -> object:
    fig, ax = _axes()
    ax.add_patch(Polygon([(0, 0), (1e6, 0), (1e6, 1e6)], edgecolor="0.3", linestyle=_FINE, **kw))
    return fig


def _huge_scatter(**kw) -> object:
    fig, ax = _axes()
    ax.scatter([0.4, 0.6], [0.5, 0.5], s=[1e12, 1e12], edgecolor="0.3", linestyle=_FINE, **kw)
    return fig


@pytest.mark.parametrize("make", [
    lambda: _huge_rectangle(facecolor="0.5"),
    lambda: _huge_rectangle(fill=False, hatch="/"),
    lambda: _huge_polygon(facecolor="0.5"),
    lambda: _huge_scatter(facecolor="0.5"),
    lambda: _huge_scatter(facecolor="none", hatch="/"),
], ids=["filled rectangle", "hatched rectangle", "filled polygon", "filled scatter", "hatched scatter"])
def test_a_filled_or_hatched_dashed_path_is_weighed_by_its_whole_length(make) -> None:
    """Fuzz 67a C2: a filled Rectangle spanning 1e6 axes widths dashed (1e-3, 1e-3) was counted its length clipped
    to the figure's diagonal and ran 44.4 CPU-s: Agg dashes a filled or hatched path unclipped."""
    _refused(make())


def test_an_unfilled_dashed_path_is_still_weighed_clipped() -> None:
    """The same patches and scatter neither filled nor hatched are clipped before dashing: within the budget."""
    _within(_huge_rectangle(fill=False))
    _within(_huge_polygon(fill=False))
    _within(_huge_scatter(facecolor="none"))


def test_a_filled_dashed_rectangle_counts_its_perimeter() -> None:
    """A filled Rectangle's dashes: its perimeter in points over its period (the pattern x its width), plus one."""
    from fusion.book import _glue_figure as F
    fig, ax = _axes()
    ax.add_patch(Rectangle((0, 0), 3, 2, facecolor="0.5", edgecolor="0.3", linewidth=2, linestyle=(0, (0.5, 0.5))))
    scale = 72.0 / fig.dpi
    perimeter = 2 * (3 * ax.bbox.width + 2 * ax.bbox.height) * scale
    try:
        assert F._tally(fig)[F._DASHES] - F._tally(_axes()[0])[F._DASHES] == int(perimeter / 2.0) + 1
    finally:
        plt.close("all")


def test_small_filled_dashed_patches_and_scatters_are_glued(monkeypatch: pytest.MonkeyPatch) -> None:
    """A legitimate figure of a filled dashed rectangle and a dashed scatter is glued."""
    fig, ax = _axes()
    ax.add_patch(Rectangle((0.1, 0.1), 0.5, 0.4, facecolor="0.8", edgecolor="0.3", linestyle="--"))
    ax.scatter([0.3, 0.7], [0.6, 0.7], s=[200, 400], facecolor="0.6", edgecolor="0.3", linestyle=":")
    try:
        _glues(monkeypatch, fig)
    finally:
        plt.close(fig)


def _line(effect, **kw) -> object:
    fig, ax = _axes()
    ax.plot([0, 1], [0, 1], color="0.3", path_effects=[effect], **kw)
    return fig


@pytest.mark.parametrize("effect", [
    lambda: pe.Stroke(dashes=_FINE_GC),
    lambda: pe.withStroke(dashes=_FINE_GC),
    lambda: pe.SimpleLineShadow(dashes=_FINE_GC),
    lambda: pe.TickedStroke(spacing=100, dashes=_FINE_GC),
    lambda: pe.PathPatchEffect(edgecolor="0.3", linestyle=(0, (1e-5, 1e-5))),
], ids=["Stroke", "withStroke", "SimpleLineShadow", "TickedStroke", "PathPatchEffect"])
def test_a_path_effects_own_dashes_are_weighed(effect) -> None:
    """Fuzz 67a C4: a path effect's own dash pattern (its gc keyword ``dashes``, or a PathPatchEffect's patch's
    linestyle) was not read: 34.0 CPU-s accepted."""
    _refused(_line(effect()))


def test_a_path_effects_hatch_makes_the_dashes_unclipped() -> None:
    """An effect's ``hatch`` (and a PathPatchEffect's filled patch) makes Agg dash the artist's path unclipped: a line
    spanning 1e6 axes widths, dashed (1e-3, 1e-3), under ``SimpleLineShadow(hatch='/')``."""
    for effect in (pe.SimpleLineShadow(hatch="/"), pe.Normal()):
        fig, ax = _axes()
        ax.plot([0, 1e6], [0, 1e6], color="0.3", dashes=(1e-3, 1e-3), path_effects=[effect])
        if isinstance(effect, pe.Normal):
            _within(fig)                         # clipped to the figure: within the budget
        else:
            _refused(fig)
    fig, ax = _axes()
    ax.add_patch(Rectangle((0, 0), 1e6, 1e6, fill=False, edgecolor="0.3",
                           path_effects=[pe.PathPatchEffect(facecolor="0.5", edgecolor="0.3", linestyle=_FINE)]))
    _refused(fig)


def test_a_path_effects_hatch_tile_is_counted() -> None:
    """A ``SimplePatchShadow(hatch=...)`` rasterises its hatch tile once a draw: counted as the patch's own."""
    from fusion.book import _glue_figure as F
    fig, ax = _axes()
    ax.add_patch(Rectangle((0.1, 0.1), 0.2, 0.2, facecolor="0.5", path_effects=[pe.SimplePatchShadow(hatch="oooo")]))
    try:
        assert F._tally(fig)[F._HATCH_VERTICES] == F._hatch_tile("oooo")[0] > 0
    finally:
        plt.close(fig)


def test_a_path_effects_dashes_count_at_their_weight() -> None:
    """A Stroke's own pattern (unscaled by the line width) along the diagonal: its length over the period, plus one,
    at EFFECT_DASH."""
    from fusion.book import _glue_figure as F
    fig = _line(pe.Stroke(dashes={"dash_offset": 0, "dash_list": [0.5, 0.5]}))
    ax = fig.axes[0]
    diagonal = float(np.hypot(ax.bbox.width, ax.bbox.height)) * 72.0 / fig.dpi
    try:
        assert F._tally(fig)[F._EFFECT_DASHES] == int(diagonal / 1.0) + 1
    finally:
        plt.close(fig)


@pytest.mark.parametrize("dashes", [3, "ab", {"dash_offset": 0, "dash_list": "ab"}, {"dash_offset": 0},
                                    {"dash_offset": 0, "dash_list": [[1, 2], [3]]}, {"dash_offset": 0, "dash_list": []},
                                    {"dash_offset": 0, "dash_list": [float("nan"), 1.0]}])
def test_odd_effect_dashes_raise_nothing_but_the_budget(dashes) -> None:
    """An effect's odd ``dashes`` (not a mapping, no list, not numbers, nan) is counted or refused by the budget,
    never another error while weighing (matplotlib refuses what it cannot apply when drawing)."""
    from fusion.book import _glue_figure as F
    fig = _line(pe.Stroke(dashes=dashes))
    try:
        F.figure_units(fig, "k")
    except ValueError as exc:
        assert "values['k']" in str(exc)
    finally:
        plt.close(fig)


def test_legitimate_effect_dashes_are_glued(monkeypatch: pytest.MonkeyPatch) -> None:
    """A line under a Stroke of an ordinary pattern and a hatched patch shadow are glued."""
    fig, ax = _axes()
    ax.plot([0, 1], [0, 1], color="0.3", path_effects=[pe.Stroke(dashes={"dash_offset": 0, "dash_list": [3, 2]})])
    ax.add_patch(Rectangle((0.1, 0.5), 0.3, 0.3, facecolor="0.5", edgecolor="0.3", linestyle="--",
                           path_effects=[pe.SimplePatchShadow(hatch="/"), pe.Normal()]))
    try:
        _glues(monkeypatch, fig)
    finally:
        plt.close(fig)


def test_a_sketched_line_of_tiny_segments_is_glued_quickly(monkeypatch: pytest.MonkeyPatch) -> None:
    """Agg's sketch filter does not segment a path every ``length`` pixels without bound: a diagonal line sketched
    (1, 1e-6, 1) was glued in 0.04 CPU-s (0.26 the first time, imports), as one of (1, 0.1, 1); not weighed."""
    import time
    fig, ax = _axes()
    ax.plot([0, 1], [0, 1], color="0.3")[0].set_sketch_params(1, 1e-6, 1)
    try:
        _glues(monkeypatch, _axes()[0])             # imports and caches, untimed
        t = time.process_time()
        _glues(monkeypatch, fig)
        assert time.process_time() - t < 2.0
    finally:
        plt.close("all")
