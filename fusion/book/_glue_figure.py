"""The units of gluing a figure by what it draws (fuzz 63a C3, 64a C1-C6), for :mod:`fusion.book.glue`: every visible
artist, walked without rendering, weighed by its kind (points, image pixels, mesh cells, markers drawn per offset,
characters, dashes: a filled or hatched path's unclipped, fuzz 67a C2), and once per path effect it is drawn with
(fuzz 65a C4), with that effect's own dashes and hatch (fuzz 67a C4)."""

from __future__ import annotations

import numpy as np
from matplotlib.artist import Artist
from matplotlib.collections import Collection, QuadMesh
from matplotlib.figure import Figure
from matplotlib.image import FigureImage, _ImageBase
from matplotlib.lines import Line2D
from matplotlib.patches import BoxStyle, FancyBboxPatch, Patch
from matplotlib.path import Path
from matplotlib.text import Text

from fusion._limits import MAX_WORK
from fusion._shown import shown
from fusion.book.study_cache import process_cache

__all__: list[str] = []

#: Units (``fusion._limits.work``, about 10 ns each) of one figure glued whatever it draws: audited and saved as PNG,
#: 31-34 ms (one axes).
FIGURE = 5_000_000
#: Units of one drawn point (a line's vertex, a collection's offset or path vertex, an image's pixel): the audit and
#: the glue render a figure with Agg about five times (fuzz 63a C3, cProfile: 22 ``draw_path`` calls for a 2-line
#: figure). Measured by fuzz 63a (time.process_time, OPENBLAS_NUM_THREADS=1, machine shared, zig-zag lines
#: ``np.sin(x + j)``): one line of 10**5 points 1.3 CPU-s (13 us a point), of 3e5 16.9 (56 us: a line's cost grows
#: faster than its points), 4 lines of 3e5 23.7 (20 us), 12 lines of 3e5 59.9 (17 us); one line of 10**6 points was
#: refused by Agg (OverflowError, "Exceeded cell block limit") after 7.1 CPU-s, of 10**7 a raw MemoryError. Weighed
#: 20 us a point (2,000 units): the edge, one such line of 497,000 points, is glued in 15.9 CPU-s (measured here, as
#: above, machine shared with nbval running); 4 x 3e5 and more, and a line of 5e5 or more points, are refused before
#: any rendering.
POINT = 2_000
#: Units of one image pixel (``imshow``): far cheaper than a line's vertex, the image is resampled once a render, not
#: stroked. Measured (glue_all of one ``imshow`` of random n x n floats, this weight off, process_time,
#: OPENBLAS_NUM_THREADS=1): 2.5e5 pixels 0.17 CPU-s, 1e6 0.15, 4e6 0.75, 1.6e7 2.17 (0.14 us a pixel); weighed twice
#: that, 30 units (a 1000 x 1000 image, refused at POINT's weight, is glued).
PIXEL = 30
#: Units of one pixel of a figure's own image (``fig.figimage``, a ``FigureImage``, fuzz 65a C3: counted one
#: artist, 400 figimages of 2000 x 2000 uint8 ran 29.9 CPU-s): drawn unresampled at its size, normalised and converted
#: at every render. Measured (glue_all of k figimages of one 2000 x 2000 array, every weight off, process_time,
#: OPENBLAS_NUM_THREADS=1, machine shared): uint8 k=5 0.77 CPU-s, k=20 2.36 (29 ns a pixel); float64 k=5 0.55, k=20
#: 2.96 (37 ns); weighed about twice, 80 ns (the edge, 1.25e8 pixels, about 31 such figimages, 4-5 CPU-s).
FIGURE_PIXEL = 8


#: Units of one QuadMesh cell (``pcolormesh``, drawn by ``draw_quad_mesh`` like an image, fuzz 64a C3/C4): glue_all
#: of one ``pcolormesh`` of random n x n floats (this weight off, process_time, OPENBLAS_NUM_THREADS=1, minimum of 2,
#: machine shared): 1500 x 1500 0.58 CPU-s, 3000 x 3000 1.75 (0.19 us a cell); weighed twice that. Counted from the
#: mesh's coordinates' shape: building its cells' paths (``get_paths``) took 7.6-9.6 CPU-s for 1500 x 1500.
CELL = 40
#: Units of one marker stamped by a collection drawn per offset (``draw_path_collection``: sizes, colours or widths
#: varying, fuzz 64a C6), and of each vertex of its path at each offset: glue_all of one scatter of n points of
#: varying sizes and colours (as above): an empty axes 0.035 CPU-s; 10**4 4-sided markers 0.063 (2.8 us a marker),
#: 26-sided 0.133 (0.3 us a further vertex); 2 x 10**4 200-sided 0.687 (0.15 us a vertex; fuzz 64a's 10**5
#: 2000-sided 30.5, 0.15 us); weighed about twice: 6 us a marker, 0.3 us a vertex.
MARKER = 600
MARKER_VERTEX = 30
#: Units of any artist the figure holds (axes, ticks, patches, texts, unknown kinds), so none is counted 0 (fuzz 64a
#: C5: 80,000 Rectangles ran 31.6 CPU-s, 0.4 ms each with their 5 vertices; 2,000 texts of 2-5 characters 1.205
#: CPU-s here, 0.59 ms each, 0.27 ms but their characters): 0.5 ms. A default axes holds about 115 artists (5.8e6).
ARTIST = 50_000
#: Units of one character of a text (newlines included): one text of 10**4 characters (one line) 0.678 CPU-s, of
#: 10**5 6.38 (64 us a character); fuzz 64a's 'ab\n' * 10**5 28.5 (95 us a character); weighed 150 us.
CHARACTER = 15_000

#: Units of a marker (a Line2D's at each vertex, a collection's at each offset) drawn under a path effect, once per
#: effect: ``PathEffectRenderer`` draws markers and collections by one Python ``draw_path`` call each (fuzz 65a C4).
#: Measured (glue_all, every weight off, process_time, OPENBLAS_NUM_THREADS=1, machine shared; 10**4 markers, per
#: ``pe.Normal()`` added): a line's 'o' markers 0.30 CPU-s (30 us a marker), a scatter's 0.22-0.31 (22-31 us, sizes
#: varying or not); against 0.049-0.059 CPU-s with no effect. Weighed twice, 60 us.
EFFECT_MARKER = 6_000
#: Units of a text's character drawn under a path effect, once per effect (the text laid out once, at
#: ``CHARACTER``, then drawn as a path by each effect): one text of 10**4 characters, 10 to 50 ``pe.Normal()`` 32 ms
#: an effect (3.2 us a character); of 2,000 lines 'ab', 5 to 20 effects 3.7 us a character; weighed twice, 7.5 us.
EFFECT_CHARACTER = 750

#: Units of a hundred pixels of markers' boxes (a Line2D's markers, a collection's sizes: Agg fills each marker's
#: pixels at each vertex or offset, a cost the points' weight misses for large markers). Measured (glue_all of 10**4
#: markers, every weight off, process_time, OPENBLAS_NUM_THREADS=1, machine shared, 100 dpi): a line's 'o' markers of
#: markersize 3 0.054 CPU-s, 30 0.107, 300 (417 pixels a side, 1.7e5 a box) 0.691 (0.37 ns a box pixel); a scatter
#: of s=9 0.075, of s=90,000 (the same box) 0.747, sizes varying (drawn per offset) 0.170 and 1.608 (0.84 ns a box
#: pixel). Weighed 1 ns a pixel. A box is counted at most the figure's pixels (drawn clipped to it).
MARKER_AREA = 10

#: Units of one dash of a dashed line, patch edge or collection (fuzz 66a C4: Agg's dasher emits one segment per dash
#: along the drawn path, path length / the pattern's period, the period scaled by the line width as matplotlib does,
#: ``_dash_pattern``; 10 two-point lines of dashes (1e-5, 1e-5) were weighed 9.0e6 units and ran 35.7 CPU-s).
#: Measured (glue_all of one two-point diagonal line, 405 points long, of dashes (d, d) at width 1.5, every weight off,
#: process_time, OPENBLAS_NUM_THREADS=1, minimum of 2, machine shared; an undashed line 0.03 CPU-s): d=1e-4 1.35e6
#: dashes 0.39 CPU-s, 3e-5 4.5e6 1.36, 1e-5 1.35e7 4.19 (0.30-0.31 us a dash); weighed twice, 0.6 us: the
#: edge, one line of dashes (8.6e-6, 8.6e-6) counted 9.5e8 units, glued in 5.6 CPU-s (as above). A filled or hatched
#: path is dashed unclipped (fuzz 67a C2: a filled Rectangle of 1e6 axes widths dashed (1e-3, 1e-3) ran 44.4 CPU-s):
#: a filled Rectangle of 1e3 axes widths, width 1, dashes (d, d) (as above): d=0.5 1.25e6 dashes 0.20 CPU-s, 0.15
#: 4.15e6 0.56 (0.14-0.16 us a dash), a filled scatter of two markers of s=1e8 0.2-0.33 us; the edge, d=0.04 1.56e7
#: dashes (9.43e8 units), glued in 2.8 CPU-s.
DASH = 60
#: Units of one tick of a ticked stroke (``patheffects.TickedStroke`` / ``withTickedStroke``, fuzz 66a C3: one tick
#: every ``spacing`` points of the drawn path, unclipped; 16 two-point lines of spacing 1e-4 ran 33.3 CPU-s). Measured
#: (as ``DASH``, one such line, ``withTickedStroke(spacing=s, length=1)``): s=1e-3 4.0e5 ticks 0.21 CPU-s, 3e-4
#: 1.35e6 0.92, 1e-4 4.05e6 2.93 (0.68-0.72 us a tick); weighed about twice, 1.5 us: the edge, one
#: line of spacing 6.2e-5 counted 9.88e8 units, glued in 7.0 CPU-s.
TICK = 150
#: Units of one dash of a path effect's own dash pattern (its ``dashes`` gc keyword: ``pe.Stroke``,
#: ``pe.withStroke``, ``pe.SimpleLineShadow``, ``pe.TickedStroke``, fuzz 67a C4: 34.0 CPU-s accepted, the pattern
#: not read). Measured (as ``DASH``, one two-point diagonal line of width 1.5 under ``pe.Stroke(dashes={"dash_offset":
#: 0, "dash_list": [d, d]})``): d=1e-3 2.2e5 dashes 0.24 CPU-s, 1e-4 2.2e6 1.97, 3e-5 7.4e6 8.3 (0.9-1.1 us a dash);
#: the same pixel pattern as the line's own dashes 3.92 CPU-s against 2.02 (0.79 against 0.41 us): twice a dash of
#: ``DASH``; weighed 2.2 us. At d=1e-5 Agg refused the stroke ("Exceeded cell block limit"). A ``pe.PathPatchEffect``'s
#: patch's dashes measured 0.30-0.47 us (2.2e6-7.4e6 dashes) and a line's own under ``pe.Normal()`` 0.47: ``DASH``.
#: The edge, one such line of d=5.1e-5 (4.4e6 dashes, 9.68e8 units), glued in 4.5 CPU-s.
EFFECT_DASH = 220

#: Units of a hatch tile's vertex and of its stroke's length (a unit tile's side): Agg rasterises a patch's hatch path
#: into a tile each time it draws it (each patch, each path of a hatched collection), whatever the patch's area.
#: Measured (glue_all of 400 hatched Rectangles of 0.05 axes, every weight off, process_time, OPENBLAS_NUM_THREADS=1,
#: minimum of 2, machine shared; less 400 unhatched, 0.062 CPU-s; ``Path.hatch(h, 6)``'s vertices V and stroke length
#: L): '/' (V 14, L 9.9) 0.05 ms a patch, '|' x 12 (144, 72) 0.26, 'x' x 6 (148, 105) 1.8, 'o' x 6 (70,252, 91) 10.4,
#: '.' x 6 (35,126, 24) 4.5, '*' x 6 (14,861, 83) 5.2 ms: 0.13-0.15 us a vertex of circles, up to 36 us a unit of
#: length ('*'); weighed 0.3 us a vertex and 50 us a unit (1.6-4x over, lines 5-19x over: a hatched patch's tile of
#: '//' about one artist). 200 axes-sized Rectangles of '//////' ran 0.30 CPU-s, the same small: not by area.
HATCH_VERTEX = 30
HATCH_LENGTH = 5_000
#: Units of a text drawn with a path effect that dashes or ticks its glyph outlines (an effect's own ``dashes``, a
#: ``PathPatchEffect``'s dashed patch, a ``TickedStroke``), fuzz 68a C1a, C1b: the outlines' length is that of the
#: glyphs (a 'W' of 40 pt about 240 points), not read without laying the text out in its font, and such a stroke of
#: 40 'W's of 40 pt dashed (5e-5, 5e-5) ran out of memory after 22.8 CPU-s, 60 ticked every 1e-4 points ran 31.6:
#: counted beyond the budget (a text is drawn with path effects of no dashes or ticks, ``pe.withStroke`` say).
TEXT_OUTLINE = MAX_WORK + 1

#: The kinds a figure is tallied by (``_tally``), named once (a header used in several functions, issue 36).
_PIXELS, _CELLS, _MARKER_VERTICES = "image pixels", "mesh cells", "marker vertices"
_FIGURE_PIXELS, _EFFECT_MARKERS = "figure image pixels", "markers drawn per path effect"
_EFFECT_CHARACTERS = "characters drawn per path effect"
_MARKER_AREA = "hundreds of marker box pixels"
_DASHES, _TICKS = "dashes", "ticks of ticked strokes"
_EFFECT_DASHES = "dashes of path effects' own patterns"
_HATCH_VERTICES, _HATCH_LENGTH = "hatch tile vertices", "hatch tile stroke lengths"
_TEXT_OUTLINES = "texts dashed or ticked along their glyph outlines by a path effect"
_WEIGHTS = {"points": POINT, _PIXELS: PIXEL, _FIGURE_PIXELS: FIGURE_PIXEL, _CELLS: CELL, "markers": MARKER,
            _MARKER_VERTICES: MARKER_VERTEX, "artists": ARTIST, "characters": CHARACTER, _EFFECT_MARKERS: EFFECT_MARKER,
            _EFFECT_CHARACTERS: EFFECT_CHARACTER, _MARKER_AREA: MARKER_AREA, _DASHES: DASH,
            _TICKS: TICK, _EFFECT_DASHES: EFFECT_DASH, _HATCH_VERTICES: HATCH_VERTEX, _HATCH_LENGTH: HATCH_LENGTH,
            _TEXT_OUTLINES: TEXT_OUTLINE}


def _size(*arrays: object) -> int:
    """The rows a broadcast of ``arrays`` holds (matplotlib broadcasts a line's x and y, fuzz 64a C1)."""
    shapes = [np.shape(a)[:1] for a in arrays if a is not None]
    try:
        shape = np.broadcast_shapes(*shapes)
    except ValueError:            # not drawable as given: the largest, an over-count
        shape = (max((s[0] for s in shapes if s), default=1),)
    return int(np.prod(shape, dtype=object))


def _vertices(a: Artist) -> int | None:
    """The 3-D vertices of an mplot3d artist (projected to 2-D paths only when drawn, fuzz 64a C2), or None."""
    if hasattr(a, "_verts3d"):                       # Line3D
        return _size(*a._verts3d)
    if hasattr(a, "_faces"):                         # Poly3DCollection (plot_surface, add_collection3d)
        faces = np.shape(a._faces)
        return int(np.prod(faces[:2], dtype=object)) if len(faces) >= 2 else 0
    if hasattr(a, "_segments3d"):                    # Line3DCollection
        return sum(len(s) for s in a._segments3d)
    if hasattr(a, "_segment3d"):                     # Patch3D, PathPatch3D
        return len(a._segment3d)
    if hasattr(a, "_offsets3d"):                     # Path3DCollection, Patch3DCollection (scatter in 3-D)
        return _size(*a._offsets3d)
    return None


def _per_offset(a: Collection) -> bool:
    """Whether Agg draws ``a``'s path at each offset (``draw_path_collection``) rather than stamping one marker
    (``Collection.draw``'s single path optimisation), read as that method does but the extents test (colours mapped
    from an array, ``scatter(c=...)``, are set only when drawn: varying)."""
    return a.get_array() is not None or not (
        len(a.get_paths()) == 1 and len(a.get_transforms()) <= 1 and len(a.get_facecolor()) == 1
        and len(a.get_edgecolor()) == 1 and len(a.get_linewidth()) == 1 and a.get_hatch() is None)


def _collection(a: Collection, tally: dict[str, int]) -> None:
    """Add the collection ``a``'s drawn points to ``tally``: its offsets, and its paths' vertices once (one marker
    stamped at every offset) or at every offset (``_per_offset``; paths cycle over the offsets)."""
    offsets = len(a.get_offsets())
    paths = a.get_paths()
    vertices = sum(len(p.vertices) for p in paths)
    if offsets > 1 and paths and _per_offset(a):
        draws = max(offsets, len(paths))
        tally["markers"] += draws
        tally[_MARKER_VERTICES] += -(-draws // len(paths)) * vertices
    else:
        tally["points"] += offsets + vertices


def _artists(fig: Figure) -> list[Artist]:
    """``fig``'s visible artists, itself included, walked without ``Artist.findobj``'s list sums (quadratic in the
    children: 40,000 texts took 1.6 CPU-s to walk)."""
    out, stack, seen = [], [fig], set()
    while stack:
        a = stack.pop()
        if id(a) in seen:
            continue
        seen.add(id(a))
        if a.get_visible():
            out.append(a)
            stack.extend(a.get_children())
            stack.extend(_drawn_parts(a))
    return out


#: The attributes holding artists an artist draws without listing them among its children (fuzz 68a C2, C3): an
#: annotation's arrow (``arrow_patch``), a text's box (``_bbox_patch``), a table cell's text (``_text``), an anchored
#: box's frame (``patch``).
_PARTS = ("arrow_patch", "_bbox_patch", "_text", "patch")


def _drawn_parts(a: Artist) -> list[Artist]:
    """The artists ``a`` draws but does not list in ``get_children()`` (``_PARTS``), an annotation's arrow and a
    text's box as stand-ins at their drawn size (``_arrow``, ``_text_box``: their positions are set only when drawn)."""
    parts = []
    for name in _PARTS:
        part = a.__dict__.get(name) if hasattr(a, "__dict__") else None
        if not isinstance(part, Artist):
            continue
        if name == "arrow_patch" and isinstance(a, Text):
            part = _arrow(a, part)
        elif name == "_bbox_patch" and isinstance(a, Text):
            part = _text_box(a, part)
        parts.append(part)
    return parts


#: A bound of a text's box side in font sizes per character of its longest line plus one per line (a glyph's advance
#: and a line's height are below 2 font sizes in the book's fonts), for the stand-ins of ``_drawn_parts``.
_SIZES_PER_CHARACTER = 2.0


def _text_sides(t: Text, fig: Figure) -> tuple[float, float]:
    """A bound in pixels of the width and height of ``t``'s box, read without laying it out: its longest line's
    characters plus one and its lines, times ``_SIZES_PER_CHARACTER`` font sizes (either way: it may be rotated), the
    height times its line spacing when above 1 (the drawn line pitch, fuzz 69a C4)."""
    lines = str(t.get_text()).split("\n")
    size = float(t.get_fontsize()) * float(fig.dpi) / 72.0 * _SIZES_PER_CHARACTER
    try:
        spacing = max(1.0, float(t.get_linespacing()))
    except (TypeError, ValueError):
        spacing = 1.0
    return (max(len(line) for line in lines) + 1) * size, len(lines) * size * spacing


def _text_box(t: Text, patch: Artist) -> Artist:
    """A copy of ``t``'s box patch at a bound of its drawn size (``_text_sides``, its mutation scale the font
    size in pixels, as ``Text.update_bbox_position_size`` sets them when drawn)."""
    import copy
    fig = t.get_figure(root=True)
    if fig is None or not hasattr(patch, "set_bounds"):
        return patch
    box = copy.copy(patch)
    box.set_bounds(0.0, 0.0, *_text_sides(t, fig))
    box._mutation_scale = float(t.get_fontsize()) * float(fig.dpi) / 72.0
    box._parent_figure = fig
    return box


def _arrow(t: Text, arrow: Artist) -> Artist:
    """A copy of the annotation ``t``'s arrow from beyond its text's anchor to the point it annotates: as far as the
    anchor plus ``_text_sides`` (the arrow starts in the text's box, ``Annotation.update_positions``), in pixels, its
    mutation scale and dpi correction as drawn; the arrow itself when its ends cannot be read (not drawable)."""
    import copy
    fig = t.get_figure(root=True)
    if fig is None or not hasattr(t, "_get_position_xy"):
        return arrow
    try:
        renderer = fig._get_renderer()
        end = np.asarray(t._get_position_xy(renderer), dtype=float)
        anchor = np.asarray(t._get_xy_transform(renderer, t.anncoords).transform(t.get_position()), dtype=float)
        span = anchor - end
        reach = float(np.hypot(*span))
        direction = span / reach if reach > 0 and np.isfinite(reach) else np.array([1.0, 0.0])
        start = end + direction * (reach + sum(_text_sides(t, fig)))
    except (TypeError, ValueError, RuntimeError, AttributeError):
        return arrow
    stand_in = copy.copy(arrow)
    stand_in._posA_posB = [tuple(start), tuple(end)]
    stand_in.patchA = None
    props = t.arrowprops if isinstance(t.arrowprops, dict) else {}
    stand_in._mutation_scale = props.get("mutation_scale", t.get_size())
    stand_in._dpi_cor = float(fig.dpi) / 72.0
    stand_in._parent_figure = fig
    return stand_in


def _effects(a: Artist) -> int:
    """The path effects ``a`` is drawn with (each redraws its path, markers and text, fuzz 65a C4), 0 if none."""
    try:
        return len(a.get_path_effects() or ())
    except TypeError:                           # an iterable of no length: one (matplotlib checks it is not empty)
        return 1


def _under_effects(a: Artist, one: dict[str, int], effects: int, tally: dict[str, int]) -> None:
    """Add to ``tally`` what ``a`` (``one``, its tally drawn once) draws with ``effects`` path effects: its path (its
    points, pixels, cells, markers and artist's overhead) once per effect, its markers each by one ``draw_path`` call
    per effect (``EFFECT_MARKER``; a line's at each vertex when it has a marker, a collection's at each offset or
    path), its text laid out once (``CHARACTER``) and drawn once per effect (``EFFECT_CHARACTER``)."""
    for k, n in one.items():
        tally[k] += n if k == "characters" else n * effects
    tally[_EFFECT_CHARACTERS] += one["characters"] * effects
    if isinstance(a, Line2D) and _has_marker(a):
        tally[_EFFECT_MARKERS] += one["points"] * effects
    elif isinstance(a, Collection) and not isinstance(a, QuadMesh):
        tally[_EFFECT_MARKERS] += max(len(a.get_offsets()), len(a.get_paths())) * effects


def _marker_area(a: Line2D | Collection, markers: int) -> int:
    """Hundreds of pixels of ``markers`` of ``a``'s marker boxes (a line's ``markersize``, a collection's largest
    ``sizes``, points at the figure's dpi), each at most the figure's pixels."""
    fig = a.get_figure(root=True)
    if fig is None:
        return 0
    if isinstance(a, Line2D):
        side = float(a.get_markersize()) if _has_marker(a) else 0.0
        box = side * side
    else:
        sizes = np.asarray(a.get_sizes(), dtype=float) if hasattr(a, "get_sizes") else np.zeros(0)
        box = float(np.nanmax(np.abs(sizes))) if sizes.size else 0.0          # points squared
    if not np.isfinite(box):
        box = float("inf")
    pixels = min(box * (fig.dpi / 72.0) ** 2, fig.bbox.width * fig.bbox.height)
    return int(markers * pixels) // 100


def _has_marker(a: Line2D) -> bool:
    """Whether the line ``a`` draws a marker at its vertices."""
    return a.get_marker() not in (None, "", " ", "None", "none")


def _paths_points(a: Artist, clipped: bool) -> tuple[float, int]:
    """The length in points of the paths ``a`` (a line, patch or collection) draws, read without rendering (its
    paths through its transform, a Bezier's control polygon an upper bound of its curve), and their count; each
    segment at most the figure's diagonal when ``clipped`` (Agg clips a stroke to the figure before dashing it), and
    a collection drawn at offsets or with per-path transforms bounded by its vertices times that diagonal."""
    fig = a.get_figure(root=True)
    if fig is None:
        return 0.0, 0
    scale = 72.0 / float(fig.dpi)
    diagonal = float(np.hypot(fig.bbox.width, fig.bbox.height))
    paths = a.get_paths() if isinstance(a, Collection) else [a.get_path()]
    draws = 1
    if isinstance(a, Collection) and (len(a.get_offsets()) > 1 or len(a.get_transforms())):
        draws = max(len(a.get_offsets()), 1)
        return sum(len(p.vertices) for p in paths) * draws * diagonal * scale, len(paths) * draws
    length, transform = 0.0, a.get_transform()
    for p in paths:
        try:
            xy = np.asarray(transform.transform_path(p).vertices, dtype=float)
            steps = np.hypot(*np.diff(xy, axis=0).T) if len(xy) > 1 else np.zeros(0)
        except (TypeError, ValueError):          # not transformable as given: every segment the diagonal
            steps = np.full(max(len(p.vertices) - 1, 0), diagonal)
        steps = np.where(np.isfinite(steps), steps, diagonal if clipped else np.inf)
        length += float(np.minimum(steps, diagonal).sum() if clipped else steps.sum())
    return length * scale, len(paths)


def _steps(xy: np.ndarray, nonfinite: float) -> np.ndarray:
    """The lengths of the segments between the rows of ``xy``; ``nonfinite`` for one with a non-finite end (Agg's NaN
    remover drops it: 0 when drawn), infinite for finite ends too far apart to measure."""
    if len(xy) < 2:
        return np.zeros(0)
    ends = np.isfinite(xy).all(axis=1)
    with np.errstate(all="ignore"):
        steps = np.hypot(*np.diff(xy, axis=0).T)
    return np.where(ends[1:] & ends[:-1], np.where(np.isfinite(steps), steps, np.inf), nonfinite)


def _unclipped_points(a: Artist, nonfinite: float) -> tuple[float, int]:
    """The length in points of the paths ``a`` draws, unclipped (a filled or hatched stroke, a path effect's ticks),
    and the paths drawn: a line's or patch's path through its transform; a collection's paths each through its
    transform's non-affine part (as ``Collection.draw``), then at most the largest per-path transform's and the
    affine part's spectral norms, each path drawn once an offset (paths cycling), read without rendering (a Bezier's
    control polygon an upper bound of its curve; a segment with a non-finite end ``nonfinite``)."""
    fig = a.get_figure(root=True)
    if fig is None:
        return 0.0, 0
    scale = 72.0 / float(fig.dpi)
    transform = a.get_transform()
    if not isinstance(a, Collection):
        try:
            xy = np.asarray(transform.transform_path(a.get_path()).vertices, dtype=float)
        except (TypeError, ValueError):          # not transformable as given: not drawable, an infinite length
            return float("inf"), 1
        return float(_steps(xy, nonfinite).sum()) * scale, 1
    paths = a.get_paths()
    if not paths:
        return 0.0, 0
    try:
        if not transform.is_affine:
            paths = [transform.transform_path_non_affine(p) for p in paths]
        affine = np.asarray(transform.get_affine().get_matrix(), dtype=float)[:2, :2]
        per_path = np.asarray(a.get_transforms(), dtype=float).reshape(-1, 3, 3)[:, :2, :2]
        norm = float(np.linalg.svd(affine, compute_uv=False).max())
        if len(per_path):
            norm *= float(np.linalg.svd(per_path, compute_uv=False).max())
        lengths = [float(_steps(np.asarray(p.vertices, dtype=float), nonfinite).sum()) for p in paths]
    except (TypeError, ValueError, np.linalg.LinAlgError):   # not drawable as given: an infinite length
        return float("inf"), len(paths)
    draws = max(len(a.get_offsets()), len(paths))
    with np.errstate(all="ignore"):
        length = -(-draws // len(paths)) * float(np.sum(lengths)) * norm * scale
    return (float("inf") if np.isnan(length) else length), draws


def _dash_periods(a: Artist) -> list[float]:
    """The periods in points of the dash patterns ``a`` strokes with (scaled by its line width as matplotlib does),
    none if it is solid or draws no edge."""
    if isinstance(a, Collection):
        patterns = list(getattr(a, "_linestyles", ()))
    else:
        patterns = [getattr(a, "_dash_pattern", (0, None))]
    periods = [_per_dash(seq) for _, seq in patterns if seq is not None and len(seq)]
    if isinstance(a, (Line2D, Patch)) and periods and not (a.get_linewidth() and
                                                           (isinstance(a, Line2D) or a.get_edgecolor()[3])):
        return []
    return periods


@process_cache(maxsize=256)
def _hatch_tile(hatch: str) -> tuple[int, int]:
    """The vertices of the hatch path Agg rasterises for ``hatch`` (``Path.hatch`` at the default density 6), and its
    stroke length in unit tiles (rounded up)."""
    path = Path.hatch(hatch, 6.0)
    if path is None:
        return 0, 0
    length = sum(float(np.hypot(*np.diff(q, axis=0).T).sum()) for q in path.to_polygons(closed_only=False))
    return len(path.vertices), int(np.ceil(length))


def _hatch(a: Artist, tally: dict[str, int]) -> None:
    """Add ``a``'s hatch tiles to ``tally``: a patch draws one, a hatched collection one a path it draws."""
    hatch = a.get_hatch() if isinstance(a, (Patch, Collection)) else None
    if not hatch:
        return
    tiles = max(len(a.get_offsets()), len(a.get_paths()), 1) if isinstance(a, Collection) else 1
    vertices, length = _hatch_tile(str(hatch))
    tally[_HATCH_VERTICES] += tiles * vertices
    tally[_HATCH_LENGTH] += tiles * length


def _filled(a: Artist) -> bool:
    """Whether Agg draws ``a`` (a patch or collection) filled or hatched, and so strokes it unclipped (Agg clips a
    stroke to the figure only when the path is neither, src/_backend_agg.h, fuzz 67a C2): a patch whose face is
    not transparent or that is hatched (its ``rgbFace`` is None otherwise), a collection with any face colour or a
    hatch."""
    if isinstance(a, Collection):
        return len(a.get_facecolor()) > 0 or bool(a.get_hatch())
    if isinstance(a, Patch):
        return bool(a.get_facecolor()[3]) or bool(a.get_hatch())
    return False


def _dash_count(a: Artist, periods: list[float], unclipped: bool, gaps: int = 1) -> int:
    """The dashes of ``periods`` (points) along ``a``'s drawn path: its length over the shortest period, plus one a
    path, ``gaps`` times (twice with a gap colour); the length clipped to the figure unless ``unclipped``."""
    if not periods:
        return 0
    length, paths = _unclipped_points(a, 0.0) if unclipped else _paths_points(a, clipped=True)
    period = min(periods)
    count = length / period if period > 0 and np.isfinite(period) else float("inf")
    if not np.isfinite(count):
        return 2 * MAX_WORK
    return gaps * (int(count) + paths)


def _dashes(a: Artist) -> int:
    """The dashes ``a`` strokes: its drawn path's length over its shortest dash period (twice with a gap colour),
    the whole length when it is filled or hatched (``_filled``)."""
    gaps = 2 if getattr(a, "_gapcolor", None) is not None else 1
    return _dash_count(a, _dash_periods(a), _filled(a), gaps)


def _gc_period(dashes: object) -> list[float]:
    """The period in points of a path effect's ``dashes`` keyword (``gc.set_dashes(**dashes)``, the dash list
    unscaled by the line width), none when it sets no pattern or matplotlib could not apply it (it raises then,
    drawing); a non-finite or non-positive period as is (counted beyond the budget)."""
    if not dashes or not isinstance(dashes, dict) or dashes.get("dash_list") is None:
        return []
    try:
        seq = np.asarray(dashes["dash_list"], dtype=float).ravel()
    except (TypeError, ValueError):
        return []
    return [_per_dash(seq)] if seq.size else []


#: The on/off pairs Agg's dasher keeps of a pattern (``agg::vcgen_dash``'s ``max_dashes``, 32 lengths), fuzz 68a C4.
_AGG_DASH_PAIRS = 16


def _per_dash(seq: object) -> float:
    """The length in points along a stroke of one dash of the pattern ``seq`` (on/off lengths): Agg's dasher draws
    one dash per on/off pair (fuzz 68a C4, C4b: a 32-length pattern draws 16 dashes a period), an odd-length pattern
    repeated twice (as matplotlib passes it); the shorter of its period over its pairs and of the period Agg keeps
    (``_AGG_DASH_PAIRS``) over those, so a bound either way; the period as is when it is not positive and finite."""
    lengths = np.asarray(seq, dtype=float).ravel()
    pairs = lengths.size / 2.0
    period = float(np.sum(lengths))
    if not (np.isfinite(period) and period > 0):
        return period
    per_dash = period / pairs
    if lengths.size % 2:
        lengths = np.concatenate([lengths, lengths])
    kept = lengths[: 2 * _AGG_DASH_PAIRS]
    with np.errstate(all="ignore"):
        kept_per_dash = float(np.sum(kept)) / (kept.size / 2.0)
    return min(per_dash, kept_per_dash)


def _effect_list(a: Artist) -> list:
    """``a``'s path effects, none when they are not iterable (matplotlib refuses them when drawing)."""
    try:
        return list(a.get_path_effects() or ())
    except TypeError:
        return []


def _tick_periods(stroke: object, periods: list[float]) -> list[float]:
    """``periods`` over a ticked stroke's ``length`` (its ticks' path is ``length`` times the path it ticks), none
    for ticks of no length or a length matplotlib could not draw."""
    try:
        reach = abs(float(getattr(stroke, "_length", 1.0)))
    except (TypeError, ValueError):
        return []
    return [p / reach for p in periods] if reach else []


def _effect_strokes(a: Artist, tally: dict[str, int]) -> None:
    """Add to ``tally`` the dashes and hatch tiles each of ``a``'s path effects draws along its path (fuzz 67a C4): a
    ``PathPatchEffect`` its patch's (its own dash pattern, hatch, face), another its ``gc`` keywords' (``dashes``
    unscaled, ``hatch``, ``linewidth``) over ``a``'s own; unclipped when that draw is filled or hatched (a
    ``SimplePatchShadow`` is filled, its edge of width 0 unless set); a ``TickedStroke``'s dashes along its ticks
    (``length`` times the path)."""
    from matplotlib.patheffects import PathPatchEffect, SimpleLineShadow, SimplePatchShadow, TickedStroke
    own_periods, own_filled = _dash_periods(a), _filled(a)
    own_hatch = a.get_hatch() if isinstance(a, (Patch, Collection)) else None
    draws = max(len(a.get_offsets()), len(a.get_paths()), 1) if isinstance(a, Collection) else 1
    for e in _effect_list(a):
        if isinstance(e, PathPatchEffect):
            patch = e.patch
            periods, filled, hatch = _dash_periods(patch), _filled(patch), patch.get_hatch()
            key = _DASHES
        else:
            keywords = getattr(e, "_gc", None)
            keywords = keywords if isinstance(keywords, dict) else {}
            hatch = keywords.get("hatch")        # ``a``'s own hatch: counted once an effect with its tally
            periods = _gc_period(keywords.get("dashes"))
            key = _EFFECT_DASHES if periods else _DASHES
            periods = periods or own_periods
            width = keywords.get("linewidth", 0 if isinstance(e, SimplePatchShadow) else 1)
            if not isinstance(width, (int, float, np.number)) or width == 0:
                periods = []
            shadow = isinstance(e, SimplePatchShadow) or (own_filled and not isinstance(e, SimpleLineShadow))
            filled = shadow or bool(hatch) or bool(own_hatch)
            if isinstance(e, TickedStroke):      # its ticks' path, not ``a``'s: ``length`` times as long
                periods = _tick_periods(e, periods)
        tally[key] += _dash_count(a, periods, filled)
        if hatch:
            vertices, length = _hatch_tile(str(hatch))
            tally[_HATCH_VERTICES] += draws * vertices
            tally[_HATCH_LENGTH] += draws * length


def _text_strokes(a: Text, tally: dict[str, int]) -> None:
    """Add to ``tally`` the text ``a``'s path effects' hatch tiles (one a draw) and, when one dashes or ticks its
    glyph outlines, the text at ``TEXT_OUTLINE`` (fuzz 68a C1a, C1b)."""
    from matplotlib.patheffects import PathPatchEffect, TickedStroke
    outlined = False
    for e in _effect_list(a):
        if isinstance(e, PathPatchEffect):
            hatch, outlined = e.patch.get_hatch(), outlined or bool(_dash_periods(e.patch))
        else:
            keywords = getattr(e, "_gc", None)
            keywords = keywords if isinstance(keywords, dict) else {}
            hatch = keywords.get("hatch")
            outlined = outlined or isinstance(e, TickedStroke) or bool(_gc_period(keywords.get("dashes")))
        if hatch:
            vertices, length = _hatch_tile(str(hatch))
            tally[_HATCH_VERTICES] += vertices
            tally[_HATCH_LENGTH] += length
    tally[_TEXT_OUTLINES] += int(outlined)


def _ticks(a: Artist) -> int:
    """The ticks ``a``'s ticked strokes draw (``TickedStroke``: one every ``spacing`` points of its whole path)."""
    from matplotlib.patheffects import TickedStroke
    try:
        strokes = [e for e in (a.get_path_effects() or ()) if isinstance(e, TickedStroke)]
    except TypeError:                           # not iterable: matplotlib would refuse it when drawing
        return 0
    if not strokes or not isinstance(a, (Line2D, Patch, Collection)):
        return 0
    length, paths = _unclipped_points(a, float("inf"))
    total = 0.0
    for e in strokes:
        spacing = float(e._spacing)
        total += length / spacing + paths if spacing > 0 else float("inf")
    return int(total) if np.isfinite(total) else 2 * MAX_WORK


def _artist(a: Artist, tally: dict[str, int]) -> None:
    """Add what the artist ``a`` draws once to ``tally`` (``_WEIGHTS``' keys), read without rendering."""
    tally["artists"] += 1
    n = three_d = _vertices(a)
    if n is not None:
        tally["points"] += n
    elif isinstance(a, Line2D):
        n = _size(a.get_xdata(orig=True), a.get_ydata(orig=True))
        tally["points"] += n
        tally[_MARKER_AREA] += _marker_area(a, n)
    elif isinstance(a, QuadMesh):               # its cells from its coordinates' shape, no paths built
        rows, cols = np.shape(a.get_coordinates())[:2]    # (rows + 1, cols + 1, 2) corners
        tally[_CELLS] += max(rows - 1, 0) * max(cols - 1, 0)
    elif isinstance(a, Collection):
        _collection(a, tally)
        tally[_MARKER_AREA] += _marker_area(a, len(a.get_offsets()))
    elif isinstance(a, _ImageBase):             # every image kind, a figure's own (figimage) too (fuzz 65a C3)
        arr = a.get_array()
        pixels = int(np.prod(np.shape(arr)[:2], dtype=object)) if arr is not None else 0
        tally[_FIGURE_PIXELS if isinstance(a, FigureImage) else _PIXELS] += pixels
    elif isinstance(a, Patch):
        tally["points"] += len(a.get_path().vertices)
    elif isinstance(a, Text):
        tally["characters"] += len(a.get_text())
    if isinstance(a, (Line2D, Patch, Collection)) and not isinstance(a, QuadMesh) and three_d is None:
        tally[_DASHES] += _dashes(a)
        _hatch(a, tally)


#: The artist classes the tally weighs, by exact class (``type(a)``, a subclass may draw otherwise), found by the kinds
#: the book's figures and the glue tests draw (fuzz 69a: a ``Quiver`` makes its arrows and an ``AnnotationBbox`` places
#: its arrow only when drawn, weighed as nothing): any other visible artist is refused by name (``_unweighed``).
_WEIGHED = frozenset({
    "matplotlib.figure.Figure", "matplotlib.figure.SubFigure", "matplotlib.axes._axes.Axes",
    "matplotlib.axis.XAxis", "matplotlib.axis.YAxis", "matplotlib.axis.XTick", "matplotlib.axis.YTick",
    "matplotlib.spines.Spine", "matplotlib.colorbar._ColorbarSpine", "matplotlib.legend.Legend",
    "matplotlib.offsetbox.DrawingArea", "matplotlib.offsetbox.HPacker", "matplotlib.offsetbox.VPacker",
    "matplotlib.offsetbox.TextArea", "matplotlib.table.Table", "matplotlib.table.Cell",
    "matplotlib.text.Text", "matplotlib.text.Annotation", "matplotlib.lines.Line2D",
    "matplotlib.patches.Rectangle", "matplotlib.patches.Polygon", "matplotlib.patches.PathPatch",
    "matplotlib.patches.Circle", "matplotlib.patches.Ellipse", "matplotlib.patches.Wedge",
    "matplotlib.patches.StepPatch", "matplotlib.patches.FancyArrowPatch", "matplotlib.patches.FancyBboxPatch",
    "matplotlib.collections.PathCollection", "matplotlib.collections.LineCollection",
    "matplotlib.collections.PolyCollection", "matplotlib.collections.FillBetweenPolyCollection",
    "matplotlib.collections.QuadMesh", "matplotlib.contour.QuadContourSet",
    "matplotlib.image.AxesImage", "matplotlib.image.FigureImage",
    "mpl_toolkits.mplot3d.axes3d.Axes3D", "mpl_toolkits.mplot3d.axis3d.XAxis", "mpl_toolkits.mplot3d.axis3d.YAxis",
    "mpl_toolkits.mplot3d.axis3d.ZAxis", "mpl_toolkits.mplot3d.art3d.Line3D", "mpl_toolkits.mplot3d.art3d.Text3D",
    "mpl_toolkits.mplot3d.art3d.Poly3DCollection", "mpl_toolkits.mplot3d.art3d.Line3DCollection",
    "mpl_toolkits.mplot3d.art3d.Path3DCollection", "mpl_toolkits.mplot3d.art3d.Patch3DCollection",
    "mpl_toolkits.mplot3d.art3d.Patch3D", "mpl_toolkits.mplot3d.art3d.PathPatch3D",
})
#: The box styles of a ``FancyBboxPatch`` whose path has a fixed number of vertices; a sawtooth's or roundtooth's
#: grows as its perimeter over its tooth size (``_box_vertices``), any other (a callable) is refused.
_FIXED_BOXES = ("Square", "Circle", "Ellipse", "LArrow", "RArrow", "DArrow", "Round", "Round4")
_TOOTHED_BOXES = ("Sawtooth", "Roundtooth")


def _kind(a: Artist) -> str:
    """The full name of ``a``'s exact class."""
    return f"{type(a).__module__}.{type(a).__qualname__}"


def _unweighed(a: Artist) -> str | None:
    """Why the tally cannot weigh ``a`` without building more than the budget (a kind not in ``_WEIGHED``, a
    ``FancyBboxPatch`` of a box style not known), or None."""
    if _kind(a) not in _WEIGHED:
        return f"draws a {_kind(a)}, a kind of artist the work budget does not weigh"
    if isinstance(a, FancyBboxPatch):
        style = type(a.get_boxstyle())
        known = style.__module__ == BoxStyle.__module__ and style.__qualname__.startswith("BoxStyle.")
        if not (known and style.__name__ in _FIXED_BOXES + _TOOTHED_BOXES):
            return f"draws a FancyBboxPatch of box style {style.__qualname__}, a style the work budget does not weigh"
    return None


def _box_vertices(a: Artist) -> int:
    """A bound of the vertices of the path of ``a``, a ``FancyBboxPatch`` of a sawtooth or roundtooth box style, read
    before the path is built (fuzz 69a C1a, C1b: a tooth of 1e-6 built about 1e9 vertices, MemoryError): four per
    tooth size of its padded perimeter (``BoxStyle.Sawtooth._get_sawtooth_vertices``), the height squeezed by its
    mutation aspect; 0 for another style (a fixed count, read from its path)."""
    style = a.get_boxstyle()
    if type(style).__name__ not in _TOOTHED_BOXES:
        return 0
    try:
        scale = float(a.get_mutation_scale())
        pad = abs(float(style.pad) * scale)
        tooth = abs(float(style.pad) * 0.5 if style.tooth_size is None else float(style.tooth_size)) * scale
        sides = abs(float(a.get_width())) + abs(float(a.get_height()) / float(a.get_mutation_aspect()))
        with np.errstate(all="ignore"):
            count = 4.0 * (sides + 4.0 * pad + 2.0 * tooth) / tooth + 16.0
    except (TypeError, ValueError, ZeroDivisionError):
        return 2 * MAX_WORK
    return int(count) if np.isfinite(count) and count < 2 * MAX_WORK else 2 * MAX_WORK


def _tally(fig: Figure, key: str | None = None) -> dict[str, int]:
    """What ``fig`` draws, by kind (``_WEIGHTS``' keys), read from its visible artists without rendering; a
    sawtooth box of more vertices than the budget counted so without building its path.

    Raises
    ------
    ValueError
        When a visible artist is of a kind it does not weigh (``_unweighed``), naming ``values[key]``.
    """
    tally = dict.fromkeys(_WEIGHTS, 0)
    artists = _artists(fig)
    for a in artists:
        why = _unweighed(a)
        if why is not None:
            raise ValueError(f"values[{shown(key)}] is a figure that {why} without rendering it (fuzz 69a); draw it "
                             f"with the kinds of artists the book's figures use")
    for a in artists:
        if isinstance(a, FancyBboxPatch):
            vertices = _box_vertices(a)
            if vertices * POINT > MAX_WORK:     # beyond the budget: counted so, its path never built
                tally["artists"] += 1
                tally["points"] += vertices
                continue
        effects = _effects(a)
        if not effects:
            _artist(a, tally)
            continue
        one = dict.fromkeys(_WEIGHTS, 0)
        _artist(a, one)
        one[_DASHES] = 0                        # each effect's own (``_effect_strokes``)
        _under_effects(a, one, effects, tally)
        if isinstance(a, (Line2D, Patch, Collection)) and not isinstance(a, QuadMesh) and _vertices(a) is None:
            _effect_strokes(a, tally)
        elif isinstance(a, Text):
            _text_strokes(a, tally)
        tally[_TICKS] += _ticks(a)
    return tally


def drawn_points(fig: Figure) -> int:
    """The points ``fig`` draws at ``POINT`` units each, read from its artists without rendering: lines' vertices
    (their x and y broadcast), 3-D artists' vertices, patches' path vertices, collections' offsets and path vertices
    (but paths drawn at each offset: ``MARKER`` and ``MARKER_VERTEX``; meshes' cells: ``CELL``; images' pixels:
    ``drawn_pixels``)."""
    return _tally(fig)["points"]


def drawn_pixels(fig: Figure) -> int:
    """The pixels of ``fig``'s axes' images (each image's first two dimensions; a figure's own images, ``figimage``, at
    ``FIGURE_PIXEL``), read without rendering."""
    return _tally(fig)[_PIXELS]


def figure_units(fig: Figure, key: str) -> int:
    """``FIGURE`` plus each drawn kind's count at its weight (``POINT`` a point, ``PIXEL`` an image pixel,
    ``FIGURE_PIXEL`` a figure image's pixel, ``CELL`` a mesh cell, ``MARKER`` and ``MARKER_VERTEX`` a marker drawn per
    offset and its vertices, ``ARTIST`` an artist, ``CHARACTER`` a text's character, ``DASH`` a dash of a dashed stroke,
    ``TICK`` a tick of a ticked stroke, ``EFFECT_DASH`` a dash of a path effect's own pattern, ``HATCH_VERTEX`` and
    ``HATCH_LENGTH`` a hatch tile's vertices and stroke; an artist drawn with path effects once per effect, its
    markers at ``EFFECT_MARKER`` and its characters at ``EFFECT_CHARACTER`` per effect).

    Raises
    ------
    ValueError
        Beyond ``fusion._limits.MAX_WORK`` units, naming ``values[key]``, before the figure is audited or rendered.
    """
    tally = _tally(fig, key)
    units = FIGURE + sum(_WEIGHTS[k] * n for k, n in tally.items())
    if units > MAX_WORK:
        drawn = ", ".join(f"{tally[k]:,} {k} at {w:,}" for k, w in _WEIGHTS.items() if tally[k])
        pixels = tally[_PIXELS] + tally[_FIGURE_PIXELS]
        raise ValueError(f"values[{shown(key)}] is a figure drawing {tally['points']:,} points (lines', patches' and "
                         f"3-D vertices, collections' offsets and paths) and {pixels:,} image pixels "
                         f"({drawn} units each), {units:.3g} units of work rendered, beyond the work budget (at most "
                         f"{MAX_WORK:.3g} units, fusion._limits.MAX_WORK, about 10 CPU-s)")
    return units
