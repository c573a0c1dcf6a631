"""Fuzz 64a C1-C6: glue_all weighs every kind of artist a figure holds (broadcast lines, 3-D artists, meshes by their
cells, texts, patches, collections drawn per offset) before auditing or rendering it, naming values['k']."""

from __future__ import annotations

import functools
import gc
import time

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.collections import QuadMesh  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

from _helpers import glue_refused  # noqa: E402


def _units(make, n: int) -> int:
    from fusion.book import glue as G
    fig = make(n)
    try:
        return G._glue_work(fig, "k")
    finally:
        plt.close(fig)


def _both_bounds(make, weight: int) -> None:
    """``make(n)``'s units grow by ``weight`` an ``n``: the last ``n`` within the budget is accepted by the glue's
    count (not run: up to about 10 CPU-s); the first whose figure alone is beyond the budget (at most 6 more: the
    glue's ``_GLUE_VALUE`` of 10,000 units is 5 points) is refused naming values['k'] within 1 CPU-s."""
    from fusion._limits import MAX_WORK
    from fusion.book import glue as G

    two, three = _units(make, 2), _units(make, 3)   # two: a scatter of one offset stamps one marker
    assert three - two == weight
    n = 2 + (MAX_WORK - G._GLUE_VALUE - two) // weight
    assert G._GLUE_VALUE + _units(make, n) <= MAX_WORK
    fig = make(3 + (MAX_WORK - two) // weight)
    glue_refused({"k": fig}, ValueError, r"values\['k'\] is a figure drawing")
    plt.close(fig)


def _axes(projection: str | None = None):
    fig = plt.figure()
    ax = fig.add_subplot(projection=projection)
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    if projection == "3d":
        ax.set_zlim(0, 1)
    return fig, ax


def _broadcast_line(n: int):
    fig, ax = _axes()
    ax.add_line(Line2D([0.0], np.sin(np.arange(n, dtype=float)), color="0.3"))
    return fig


def _poly3d(n: int):
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    fig, ax = _axes("3d")
    x = np.arange(float(n))
    ax.add_collection3d(Poly3DCollection([np.c_[x, np.sin(x), np.cos(x)]], facecolor="0.5", edgecolor="0.3"))
    return fig


def _text(n: int):
    fig, ax = _axes()
    ax.text(0.1, 0.5, "a" * n, fontsize=9)
    return fig


def _stairs(n: int):
    fig, ax = _axes()
    ax.stairs(np.sin(np.arange(float(n))), np.linspace(0, 1, n + 1), color="0.3")
    return fig


def _rectangles(n: int):
    fig, ax = _axes()
    for _ in range(n):
        ax.add_artist(Rectangle((0, 0), 0.1, 0.1))
    return fig


def _markers(n: int):
    fig, ax = _axes()
    ax.scatter(np.linspace(0, 1, n), np.linspace(0, 1, n), s=np.arange(n) % 50 + 5, marker=(2000, 0, 0),
               edgecolors=["0.2", "0.6"] * (n // 2) + ["0.2"] * (n % 2))
    return fig


def test_a_broadcast_line_is_weighed_by_its_drawn_rows() -> None:
    """C1: Line2D([0.], y) draws len(y) points (4 such lines of 3e5 were counted 4 and ran 31.7 CPU-s)."""
    from fusion.book import _glue_figure as F
    _both_bounds(_broadcast_line, F.POINT)


def test_3d_polygons_are_weighed_by_their_vertices() -> None:
    """C2: a Poly3DCollection has no 2-D paths until drawn (counted 0, 3 x 4e5 vertices ran 37.5 CPU-s)."""
    from fusion.book import _glue_figure as F
    _both_bounds(_poly3d, F.POINT)


def test_a_text_is_weighed_by_its_characters() -> None:
    """C5: one text of 10**5 lines ran 28.5 CPU-s, 40,000 texts 33.1, both counted 0."""
    from fusion.book import _glue_figure as F
    _both_bounds(_text, F.CHARACTER)


def test_a_step_patch_is_weighed_by_its_vertices() -> None:
    """C5: 3 ax.stairs of 3e5 values (a Patch, counted 0) ran 44.4 CPU-s; a step adds two vertices."""
    from fusion.book import _glue_figure as F
    _both_bounds(_stairs, 2 * F.POINT)


def test_every_artist_is_weighed() -> None:
    """C5: 80,000 Rectangles (counted 0) ran 31.6 CPU-s; each is an artist of 5 vertices."""
    from fusion.book import _glue_figure as F
    _both_bounds(_rectangles, F.ARTIST + 5 * F.POINT)


def test_markers_drawn_per_offset_are_weighed_by_their_vertices(monkeypatch: pytest.MonkeyPatch) -> None:
    """C6: 10**5 2000-sided markers of varying sizes (counted 102,065 points) ran 30.5 CPU-s; each offset draws the
    marker's 2001 vertices."""
    from fusion.book import _glue_figure as F
    monkeypatch.setitem(F._WEIGHTS, F._MARKER_AREA, 0)   # the markers' boxes: their own test
    _both_bounds(_markers, F.MARKER + 2001 * F.MARKER_VERTEX)


@pytest.mark.parametrize("side", [350, 1500])
def test_a_mesh_is_weighed_by_its_cells_without_building_paths(monkeypatch: pytest.MonkeyPatch, side: int) -> None:
    """C3/C4: pcolormesh(350 x 350) was refused (612,565 "points", glued in 0.6-0.8 CPU-s) and the count of a
    1500 x 1500 one built every cell's path (refused after 7.6-9.6 CPU-s; glued in 0.58): counted from the
    coordinates' shape in under 0.1 CPU-s, within the budget."""
    from fusion._limits import MAX_WORK
    from fusion.book import _glue_figure as F
    from fusion.book import glue as G

    fig, ax = plt.subplots()
    ax.pcolormesh(np.random.default_rng(0).random((side, side)))
    monkeypatch.setattr(QuadMesh, "get_paths", lambda self: pytest.fail("a mesh's paths built"))
    gc.disable()   # a collection of a full run's heap inside the timed call cost 1.16 CPU-s late in a worker
    try:
        t = time.process_time()
        units = G._glue_work(fig, "k")
        spent = time.process_time() - t
    finally:
        gc.enable()
    assert spent < 0.1
    assert F._tally(fig)["mesh cells"] == side * side
    assert G._GLUE_VALUE + units <= MAX_WORK
    plt.close(fig)


def test_a_mesh_beyond_the_budget_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    """The refusal at the mesh's bound, its weight scaled 1,000 times (the bound itself, 2.5e7 cells, needs 1 GB of
    coordinates to build): one cell more than the budget holds is refused naming values['k'] within 1 CPU-s."""
    from fusion.book import _glue_figure as F

    monkeypatch.setitem(F._WEIGHTS, "mesh cells", 1000 * F.CELL)
    make = functools.partial(_mesh, rng=np.random.default_rng(1))
    _both_bounds(make, 1000 * F.CELL)


def _mesh(n: int, rng: np.random.Generator):
    fig, ax = _axes()
    ax.pcolormesh(np.linspace(0, 1, n + 1), [0.0, 1.0], rng.random((1, n)))
    return fig


def _figimages(n: int, image: np.ndarray):
    fig = plt.figure()
    for i in range(n):
        fig.figimage(image, xo=i, yo=i)
    return fig


def test_a_figure_image_is_weighed_by_its_pixels() -> None:
    """Fuzz 65a C3: a figimage (a FigureImage, no AxesImage) was counted one artist: 400 of 2000 x 2000 uint8 were
    glued in 29.9 CPU-s; each is an artist and its pixels."""
    from fusion.book import _glue_figure as F
    image = np.zeros((600, 600), dtype=np.uint8)
    _both_bounds(functools.partial(_figimages, image=image), F.ARTIST + 600 * 600 * F.FIGURE_PIXEL)


def _effects_line(n: int, marker: str = ""):
    import matplotlib.patheffects as pe
    fig, ax = _axes()
    line, = ax.plot(np.linspace(0, 1, 10_000), np.sin(np.arange(10_000.0)), color="0.3", marker=marker)
    line.set_path_effects([pe.Normal()] * n)
    return fig


def _effects_scatter(n: int):
    import matplotlib.patheffects as pe
    fig, ax = _axes()
    ax.scatter(np.linspace(0, 1, 10_000), np.linspace(0, 1, 10_000), s=9, color="0.3").set_path_effects(
        [pe.Normal()] * n)
    return fig


def _effects_text(n: int):
    import matplotlib.patheffects as pe
    fig, ax = _axes()
    ax.text(0.1, 0.5, "ab\n" * 300, fontsize=9).set_path_effects([pe.Normal()] * n)
    return fig


def test_a_line_is_weighed_once_per_path_effect(monkeypatch: pytest.MonkeyPatch) -> None:
    """Fuzz 65a C4: one line of 1e5 points with 1,000 ``pe.Normal()`` (its points counted once) ran 40.1 CPU-s; each
    effect redraws its path (and its markers, one ``draw_path`` each)."""
    from fusion.book import _glue_figure as F
    monkeypatch.setitem(F._WEIGHTS, F._MARKER_AREA, 0)   # the markers' boxes: their own test
    _both_bounds(_effects_line, F.ARTIST + 10_000 * F.POINT)
    _both_bounds(functools.partial(_effects_line, marker="o"), F.ARTIST + 10_000 * (F.POINT + F.EFFECT_MARKER))


def test_a_collection_and_a_text_are_weighed_once_per_path_effect(monkeypatch: pytest.MonkeyPatch) -> None:
    """Fuzz 65a C4: each effect redraws a scatter's markers one ``draw_path`` each, and a text (laid out once)."""
    from fusion.book import _glue_figure as F
    monkeypatch.setitem(F._WEIGHTS, F._MARKER_AREA, 0)   # the markers' boxes: their own test
    _both_bounds(_effects_scatter, F.ARTIST + 10_026 * F.POINT + 10_000 * F.EFFECT_MARKER)  # the circle: 26 vertices
    _both_bounds(_effects_text, F.ARTIST + 900 * F.EFFECT_CHARACTER)


def _large_markers(n: int):
    fig, ax = _axes()
    fig.set_dpi(72)                             # a box of 300 x 300 pixels
    ax.plot(np.linspace(0, 1, n), np.linspace(0, 1, n), "o", markersize=300, color="0.3")
    return fig


def test_large_markers_are_weighed_by_their_boxes() -> None:
    """A line's markers of markersize 300 (1.7e5 pixels a box at 100 dpi) cost 69 us each, 3.5 times a point's
    weight: weighed by their boxes' pixels (a hundred at MARKER_AREA)."""
    from fusion.book import _glue_figure as F
    _both_bounds(_large_markers, F.POINT + 900 * F.MARKER_AREA)


def _diagonal_points(ax) -> float:
    """The length in points of the diagonal of ``ax`` (limits 0 to 1), as Agg strokes a line from (0, 0) to (1, 1)."""
    return float(np.hypot(ax.bbox.width, ax.bbox.height)) * 72.0 / ax.figure.dpi


def _dashed_lines(n: int, dash: float = 1e-4):
    fig, ax = _axes()
    for _ in range(n):
        ax.plot([0, 1], [0, 1], color="0.3", lw=1.5, dashes=(dash, dash))
    return fig


def _ticked_lines(n: int, spacing: float = 1e-3):
    from matplotlib import patheffects as pe
    fig, ax = _axes()
    for _ in range(n):
        ax.plot([0, 1], [0, 1], color="0.3", path_effects=[pe.withTickedStroke(spacing=spacing, length=1)])
    return fig


def _hatched(n: int, hatch: str = "oooooo"):
    fig, ax = _axes()
    for _ in range(n):
        ax.add_patch(Rectangle((0.1, 0.1), 0.05, 0.05, hatch=hatch, fill=False))
    return fig


def test_a_dashed_line_is_weighed_by_its_dashes() -> None:
    """Fuzz 66a C4: 10 two-point lines of dashes (1e-5, 1e-5) were counted 9.0e6 units and ran 35.7 CPU-s: a dash
    every period (the pattern scaled by the line width, 1.5) of the line's length in points."""
    from fusion.book import _glue_figure as F
    fig = _dashed_lines(1)
    dashes = int(_diagonal_points(fig.axes[0]) / (2 * 1e-4 * 1.5)) + 1
    plt.close(fig)
    assert dashes > 10**6
    _both_bounds(_dashed_lines, F.ARTIST + 2 * F.POINT + dashes * F.DASH)


def test_a_ticked_stroke_is_weighed_by_its_ticks() -> None:
    """Fuzz 66a C3: 16 two-point lines under ``withTickedStroke(spacing=1e-4)`` were counted 9.3e6 units and ran 33.3
    CPU-s: a tick every ``spacing`` points of the line's length."""
    from fusion.book import _glue_figure as F
    fig = _ticked_lines(1)
    ticks = int(_diagonal_points(fig.axes[0]) / 1e-3 + 1)
    plt.close(fig)
    assert ticks > 10**5
    _both_bounds(_ticked_lines, F.ARTIST + 2 * F.POINT + ticks * F.TICK)


def test_a_hatch_is_weighed_by_its_tile() -> None:
    """A hatch is rasterised into a tile at every patch drawn: 400 small Rectangles hatched 'oooooo' (70,252 vertices
    a tile) ran 4.2 CPU-s, weighed 400 artists."""
    from matplotlib.path import Path

    from fusion.book import _glue_figure as F
    tile = Path.hatch("oooooo", 6.0)
    length = sum(float(np.hypot(*np.diff(q, axis=0).T).sum()) for q in tile.to_polygons(closed_only=False))
    _both_bounds(_hatched, F.ARTIST + 5 * F.POINT + len(tile.vertices) * F.HATCH_VERTEX
                 + int(np.ceil(length)) * F.HATCH_LENGTH)


def test_solid_and_default_dashed_lines_count_no_more_than_their_dashes() -> None:
    """A solid line counts no dash; a default '--' line of 10 points its length over its period (lines.dashed_pattern,
    3.7 + 1.6 points, x its width 1.5)."""
    from fusion.book import _glue_figure as F
    # matplotlib's defaults, whatever style an earlier test of the worker left (a fresh clone's make test: 60 != 56)
    with plt.rc_context({"lines.linewidth": 1.5, "lines.dashed_pattern": [3.7, 1.6], "lines.scale_dashes": True}):
        fig, ax = _axes()
        before = F._tally(fig)[F._DASHES]                   # the axes' own lines (grid styles vary with rcParams)
        ax.plot([0, 1], [0, 1])
        assert F._tally(fig)[F._DASHES] == before
        ax.plot(np.linspace(0, 1, 10), np.linspace(0, 1, 10), "--")
        assert F._tally(fig)[F._DASHES] - before == int(_diagonal_points(ax) / ((3.7 + 1.6) * 1.5)) + 1
    plt.close(fig)
