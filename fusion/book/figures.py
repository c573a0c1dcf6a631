r"""The book's figure rules, checked on every figure a chapter publishes.

A chapter publishes a figure only through :func:`glue_figure` (or :func:`fusion.book.glue.glue_all`),
which calls :func:`audit_figure` first. The audit raises :class:`FigureStyleError` when the figure
breaks one of the book's rules, so re-executing a chapter (``make notebooks``, nbval in
``make test``) fails on a figure that

1. uses a colour outside the registry's palette (the colours of
   :data:`fusion.book.style.METHOD_COLORS`, the Okabe-Ito palette and neutral greys; colour-mapped
   artists must use a perceptually uniform, colour-blind-safe map);
2. draws a registered method (a legend entry whose text is a registered label) in a colour other
   than the method's registered colour, shows an internal key instead of its label, or shows a legend
   label that is not in the registry (:func:`fusion.book.style.is_registered_label`: a method label,
   a registered non-method series, or a registered parametrised pattern);
3. has text smaller than :data:`MIN_FONT_PT` points or is wider than :data:`MAX_WIDTH_IN` inches
   (the figure is then shrunk on the page and its text with it);
4. puts a legend over data: a vertex of a plotted line (or a scatter point, or a bar) inside a
   legend's box.

References
----------
* Okabe, M., & Ito, K. (2008). Color Universal Design (CUD): how to make figures and presentations
  that are friendly to colorblind people. https://jfly.uni-koeln.de/color/
* van der Walt, S., & Smith, N. (2015). A better default colormap for matplotlib (viridis). SciPy 2015.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import matplotlib as mpl
import numpy as np
from matplotlib import colors as mcolors
from matplotlib.axes import Axes
from matplotlib.collections import Collection, PathCollection
from matplotlib.figure import Figure
from matplotlib.legend import Legend
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.text import Text
from matplotlib.transforms import Bbox

from fusion.book import style

__all__ = ["OKABE_ITO", "MIN_FONT_PT", "MAX_WIDTH_IN", "FigureStyleError", "allowed_colors",
           "audit_figure", "glue_figure"]

#: The Okabe-Ito palette (colour-blind safe), black first.
OKABE_ITO: tuple[str, ...] = ("#000000", "#E69F00", "#56B4E9", "#009E73", "#F0E442", "#0072B2",
                              "#D55E00", "#CC79A7")

#: Smallest text size (points) at the displayed size.
MIN_FONT_PT = 9.0

#: Widest figure (inches at 100 dpi = the text column's 750 CSS pixels); wider figures are shrunk.
MAX_WIDTH_IN = 7.5

#: Colour maps allowed for colour-mapped artists (perceptually uniform, colour-blind safe, or grey).
ALLOWED_CMAPS = frozenset({"viridis", "cividis", "magma", "inferno", "plasma", "Greys", "gray",
                           "binary", "Greys_r", "gray_r", "viridis_r", "cividis_r"})


class FigureStyleError(ValueError):
    """A figure breaks one of the book's figure rules (the message lists every breach).

    Parameters
    ----------
    message : str
        Every breach found, one per line.

    References
    ----------
    * Okabe, M., & Ito, K. (2008). Color Universal Design (CUD).
    """


def allowed_colors() -> frozenset[str]:
    """Hex colours a figure may use besides neutral greys (which carry no method identity).

    Returns
    -------
    frozenset of str
        Upper-case ``#RRGGBB`` strings: the registry's colours and the Okabe-Ito palette.
    """
    return frozenset(c.upper() for c in (*style.METHOD_COLORS.values(), *OKABE_ITO))


def _hex(c: object) -> str | None:
    """``#RRGGBB`` of a colour, or None when it is fully transparent or 'none'."""
    if isinstance(c, str) and c.lower() == "none":
        return None
    rgba = mcolors.to_rgba(c)  # type: ignore[arg-type]
    if rgba[3] == 0:
        return None
    return mcolors.to_hex(rgba, keep_alpha=False).upper()


def _is_grey(h: str) -> bool:
    r, g, b = (int(h[i:i + 2], 16) for i in (1, 3, 5))
    return max(r, g, b) - min(r, g, b) <= 2


def _artist_colors(artist: object) -> list[str]:
    """Every visible colour an artist paints (hex), colour-mapped arrays excluded."""
    out: list[object] = []
    if isinstance(artist, Line2D):
        out += [artist.get_color()]
        if artist.get_marker() not in (None, "None", "", " "):
            out += [artist.get_markerfacecolor(), artist.get_markeredgecolor()]
    elif isinstance(artist, Collection):
        if artist.get_array() is None:
            out += list(artist.get_facecolors()) + list(artist.get_edgecolors())
    elif isinstance(artist, Patch):
        out += [artist.get_facecolor(), artist.get_edgecolor()]
    hexes = []
    for c in out:
        h = _hex(c)
        if h is not None:
            hexes.append(h)
    return hexes


def _data_artists(ax: Axes) -> list[object]:
    return [a for a in (*ax.lines, *ax.collections, *ax.patches) if a.get_visible()]


def _points(artist: object, ax: Axes) -> np.ndarray:
    """Display coordinates of the points an artist draws (lines densified), shape (n, 2)."""
    if isinstance(artist, Line2D):
        xy = np.asarray(artist.get_xydata(), dtype=float)
        if xy.ndim != 2 or xy.shape[0] == 0:
            return np.empty((0, 2))
        if artist.get_linestyle() not in ("None", "", " ") and xy.shape[0] > 1:
            t = np.linspace(0.0, 1.0, 9)[:-1]
            seg = xy[:-1, None, :] + t[None, :, None] * (xy[1:] - xy[:-1])[:, None, :]
            xy = np.vstack([seg.reshape(-1, 2), xy[-1:]])
        pts = artist.get_transform().transform(xy)
    elif isinstance(artist, PathCollection) and len(artist.get_offsets()):
        pts = artist.get_offset_transform().transform(np.asarray(artist.get_offsets(), dtype=float))
    elif isinstance(artist, Patch) and artist.get_label() not in (None, "") and not str(artist.get_label()).startswith("_"):
        bb = artist.get_window_extent()
        pts = np.array([[bb.x0, bb.y0], [bb.x1, bb.y1], [(bb.x0 + bb.x1) / 2, (bb.y0 + bb.y1) / 2]])
    else:
        return np.empty((0, 2))
    pts = pts[np.all(np.isfinite(pts), axis=1)]
    inside = ax.bbox.contains
    return np.array([p for p in pts if inside(*p)]).reshape(-1, 2)


def _legends(fig: Figure) -> list[tuple[Legend, list[Axes]]]:
    found: list[tuple[Legend, list[Axes]]] = []
    for ax in fig.axes:
        leg = ax.get_legend()
        if leg is not None and leg.get_visible():
            found.append((leg, list(fig.axes)))
    for leg in fig.legends:
        if leg.get_visible():
            found.append((leg, list(fig.axes)))
    return found


def audit_figure(fig: Figure) -> list[str]:
    """Check a figure against the book's rules; raise if it breaks any.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A finished figure (drawn here on an Agg canvas to measure text and legends).

    Returns
    -------
    list of str
        Empty (the figure passes). Returned for symmetry with tests.

    Raises
    ------
    TypeError
        If ``fig`` is not a matplotlib Figure.
    FigureStyleError
        Listing every breach: colour outside the palette, registered method in another colour,
        internal key as a label, text below :data:`MIN_FONT_PT`, width above :data:`MAX_WIDTH_IN`,
        legend covering data, a figure or axes background or axis text colour that is not the book style's (a
        figure drawn in a caller's matplotlib style, not through :func:`fusion.book.style.new_figure`); a size or dpi outside :data:`fusion.book.style.FIGURE_SIDE_RANGE_IN` or
        :data:`fusion.book.style.FIGURE_DPI_RANGE` is reported before drawing (the figure is then not drawn);
        a text below :data:`MIN_FONT_PT` too, with the breaches found undrawn (fuzz 68a D1: a wrapped text of 1 pt
        took 13.5 CPU-s to draw);
        a figure matplotlib fails to render (a RuntimeError of its rasteriser: text placed far outside the
        axes, at x = 1e5 say) is reported as not drawable.

    References
    ----------
    * Okabe, M., & Ito, K. (2008). Color Universal Design (CUD).
    """
    if not isinstance(fig, Figure):
        raise TypeError(f"fig must be a matplotlib Figure, got {type(fig).__name__}")
    try:   # before drawing: a figure of 1e6 in or 1e4 dpi would ask for gigabytes (fuzz 22a A)
        style._figure_size(fig.get_size_inches(), fig.get_dpi())
    except ValueError as exc:
        width = fig.get_figwidth()
        wide = ([f"figure is {width:.2f} in wide (> {MAX_WIDTH_IN} in): it would be shrunk on the page"]
                if width > MAX_WIDTH_IN + 1e-9 else [])
        _raise_problems(wide + [f"figure not drawn: its {exc}"])
    _agg_canvas(fig)
    if _small_text(fig):   # before drawing: a wrapped text of 1 pt lays out ~900 words a line (fuzz 68a D1)
        _raise_problems(_problems(fig, fig.get_figwidth()))
    _drawn(fig.canvas.draw)
    _raise_problems(_problems(fig, fig.get_figwidth()))
    return []


def _drawn(draw: Callable[[], Any]) -> Any:
    """``draw()`` (a render of the figure), with matplotlib's own failure to render it (fuzz 34a D4: text at
    x = 1e5 overflows FreeType's rasteriser, a RuntimeError naming nothing) raised as the audit's
    :class:`FigureStyleError`."""
    try:
        return draw()
    except (RuntimeError, OverflowError) as exc:
        raise FigureStyleError("figure breaks the book's figure rules:\n  - figure cannot be drawn: matplotlib "
                               f"fails to render it ({type(exc).__name__}: {str(exc)[:120]}); text or an artist "
                               "placed far outside the axes can overflow its rasteriser") from exc


def _agg_canvas(fig: Figure) -> None:
    """Give ``fig`` an Agg canvas if its canvas cannot render (the audit measures text and legends)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    if not hasattr(fig.canvas, "get_renderer"):
        FigureCanvasAgg(fig)


def _raise_problems(problems: list[str]) -> None:
    if problems:
        unique = list(dict.fromkeys(problems))
        raise FigureStyleError("figure breaks the book's figure rules:\n  - " + "\n  - ".join(unique))


def _book_rc(key: str) -> object:
    """One matplotlib setting in the book's whole style (``style.use_book_style``): the book's, else matplotlib's
    default."""
    return style._STYLE.get(key, mpl.rcParamsDefault[key])


def _style_problems(fig: Figure) -> list[str]:
    """Background and text colours that are not the book style's (fuzz 37a D1: a figure drawn in a caller's
    ``dark_background`` style, black with white text, passed the audit)."""
    def hexed(c: object) -> str:
        return str(mcolors.to_hex(c))   # type: ignore[arg-type]

    problems = []
    face, axes_face = hexed(_book_rc("figure.facecolor")), hexed(_book_rc("axes.facecolor"))
    if hexed(fig.get_facecolor()) != face:
        problems.append(f"figure background {hexed(fig.get_facecolor())} is not the book style's {face} (drawn in "
                        "another matplotlib style? use fusion.book.style.new_figure)")
    ink = hexed(_book_rc("text.color"))
    for ax in fig.axes:
        if hexed(ax.get_facecolor()) != axes_face:
            problems.append(f"axes background {hexed(ax.get_facecolor())} is not the book style's {axes_face}")
        for label in (ax.xaxis.label, ax.yaxis.label, *ax.get_xticklabels()[:1], *ax.get_yticklabels()[:1]):
            if label.get_text() and hexed(label.get_color()) != ink:
                problems.append(f"axis text colour {hexed(label.get_color())} is not the book style's {ink}")
                break
    return problems


def _problems(fig: Figure, width: float) -> list[str]:
    """Every breach of the rules by a figure just drawn (its legends and text where that draw put them).

    ``width`` is the figure's width in inches (taken before a tight-bbox print changes the figure's size).
    """
    problems: list[str] = []
    palette = allowed_colors()
    if width > MAX_WIDTH_IN + 1e-9:
        problems.append(f"figure is {width:.2f} in wide (> {MAX_WIDTH_IN} in): it would be shrunk on the page")
    problems += _style_problems(fig)
    for ax in fig.axes:
        for artist in _data_artists(ax):
            for h in _artist_colors(artist):
                if h not in palette and not _is_grey(h):
                    problems.append(f"colour {h} of {type(artist).__name__} "
                                    f"'{artist.get_label()}' is not in the registry's palette")
            if isinstance(artist, Collection) and artist.get_array() is not None:
                name = artist.get_cmap().name
                if name not in ALLOWED_CMAPS:
                    problems.append(f"colour map '{name}' is not colour-blind safe (use viridis or cividis)")
    label_to_key = {lab: key for key, lab in style.METHOD_LABELS.items()}
    internal = {key for key, lab in style.METHOD_LABELS.items() if key != lab}
    for leg, axes in _legends(fig):
        for handle, text in zip(leg.legend_handles, leg.get_texts()):
            label = text.get_text()
            if label in internal:
                problems.append(f"legend shows the internal key '{label}' instead of "
                                f"'{style.METHOD_LABELS[label]}'")
            elif not style.is_registered_label(label):
                problems.append(f"legend label '{label}' is not in the registry (fusion.book.style: "
                                "METHOD_LABELS, FIGURE_LABELS or LABEL_PATTERNS)")
            key = label_to_key.get(label)
            if key is not None and key in style.METHOD_COLORS and handle is not None:
                want = _hex(style.METHOD_COLORS[key])
                got = _artist_colors(handle)
                if got and want not in got:
                    problems.append(f"'{label}' is drawn in {got[0]}, its registered colour is {want}")
        box: Bbox = leg.get_window_extent().padded(-2.0)
        for ax in axes:
            for artist in _data_artists(ax):
                pts = _points(artist, ax)
                if pts.size and box.count_contains(pts) > 0:
                    problems.append(f"legend covers data ('{artist.get_label()}')")
                    break
    return problems + _small_text(fig)


def _small_text(fig: Figure) -> list[str]:
    """The breaches of :data:`MIN_FONT_PT` by ``fig``'s visible texts, read from their sizes (no draw needed)."""
    return [f"text '{t.get_text()[:30]}' is {t.get_fontsize():.1f} pt (< {MIN_FONT_PT:g} pt)"
            for t in fig.findobj(Text)
            if t.get_visible() and t.get_text().strip() and t.get_fontsize() < MIN_FONT_PT - 1e-9]


#: Run the figure's layout engine once before the PNG is printed, where the audit's own draw used to run it.
#: Constrained layout moves on a second run (tick labels chosen on the first solution shift the second), so
#: this keeps every stored PNG byte for byte as it was; it costs about one layout, the largest part of a
#: draw. ``False``: one layout fewer (``benchmarks/bench_figures.py`` measures both), and every figure's
#: PNG changes by a few pixels of layout (not its content): the notebooks must then be re-executed.
RELAYOUT_BEFORE_PNG = True


def glue_figure(key: str, fig: Figure, alt: str | None = None) -> None:
    """Audit a figure, glue it under ``key`` (not displayed) and close it.

    Parameters
    ----------
    key : str
        Glue key (prefixed with the chapter's short id).
    fig : matplotlib.figure.Figure
        The finished figure.
    alt : str, optional
        Its alt text: what it shows. Default: :data:`fusion.book.style.FIGURE_ALT` ``[key]``, else
        the automatic :func:`fusion.book.style.describe_figure`. Written into the PNG, and from there
        onto the page's ``<img alt=...>`` (``book/_ext/fusion_figures.py``).

    Raises
    ------
    TypeError
        ``key`` is not a str or ``fig`` not a Figure.
    ValueError
        ``key`` empty or not of ASCII letters, digits, underscores and hyphens (the whole-key rule of
        :func:`fusion.book.glue.glue_all`).
    FigureStyleError
        If the figure breaks the book's rules (see :func:`audit_figure`).
    """
    from fusion.book.glue import _glue_key

    key = _glue_key(key, "key", many=False)  # glue_all's whole-key rule, as its plain text (rule 19; fuzz 38b C4)
    if not isinstance(fig, Figure):
        raise TypeError(f"fig must be a matplotlib Figure, got {type(fig).__name__}")
    style.set_figure_alt(fig, alt if alt is not None else style.FIGURE_ALT.get(key))
    import matplotlib.pyplot as plt
    from IPython.core.formatters import format_display_data
    from IPython.display import display
    from myst_nb.ext.glue import GLUE_PREFIX

    # The figure is rendered once, by the PNG the notebook stores, and audited on that render. Before, the
    # audit drew it on its own (a full Agg render), then IPython's PNG formatter drew it twice more (the
    # layout pass of bbox_inches="tight", then the PNG). The audit's draw also ran the figure's layout
    # engine a first time, and constrained layout is not idempotent (tick labels chosen on the first
    # solution move the second), so that layout run is kept, without the render: the PNG bytes stay the same.
    _agg_canvas(fig)
    width = fig.get_figwidth()
    if _small_text(fig):   # before the PNG's render, as the audit (fuzz 68a D1)
        _raise_problems(_problems(fig, width))
    engine = fig.get_layout_engine()
    if RELAYOUT_BEFORE_PNG and engine is not None and fig.axes:
        try:
            engine.execute(fig)  # what Figure.draw runs first (and ignores a ValueError of, as here)
        except ValueError:
            pass
    found: list[list[str]] = []

    def audit_draw(event: object) -> None:  # the PNG's render (the last draw of the print) is audited
        if "draw_path" in vars(event.renderer):  # type: ignore[attr-defined]
            return  # the layout pass of the tight bbox: matplotlib's renderer with its drawing switched off
        found[:] = [_problems(fig, width)]

    cid = fig.canvas.mpl_connect("draw_event", audit_draw)
    try:
        mimebundle, metadata = _drawn(lambda: format_display_data(fig))  # what myst_nb.glue computes: the PNG
    finally:
        fig.canvas.mpl_disconnect(cid)
    if found:
        _raise_problems(found[0])
    else:  # no PNG formatter (not in a notebook kernel): nothing was drawn, so the audit draws
        audit_figure(fig)
    # myst_nb.glue(key, fig, display=False), with the bundle computed above
    metadata["scrapbook"] = dict(name=key, mime_prefix=GLUE_PREFIX)
    display({GLUE_PREFIX + k: v for k, v in mimebundle.items()}, raw=True, metadata=metadata)
    plt.close(fig)
