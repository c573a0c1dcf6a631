"""The units of gluing a figure by the points it draws (fuzz 63a C3), for :mod:`fusion.book.glue`."""

from __future__ import annotations

import numpy as np
from matplotlib.collections import Collection
from matplotlib.figure import Figure
from matplotlib.image import AxesImage
from matplotlib.lines import Line2D

from fusion._limits import MAX_WORK
from fusion._shown import shown

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


def drawn_points(fig: Figure) -> int:
    """The points ``fig`` draws, read from its artists without rendering: each line's vertices, each collection's
    offsets and path vertices (images' pixels: ``drawn_pixels``)."""
    n = 0
    for a in fig.findobj(lambda a: isinstance(a, (Line2D, Collection))):
        if isinstance(a, Line2D):
            n += int(np.size(a.get_xdata(orig=True)))
        else:
            n += len(a.get_offsets()) + sum(len(p.vertices) for p in a.get_paths())
    return n


def drawn_pixels(fig: Figure) -> int:
    """The pixels of ``fig``'s images (each image's first two dimensions), read without rendering."""
    n = 0
    for a in fig.findobj(lambda a: isinstance(a, AxesImage)):
        arr = a.get_array()
        n += int(np.prod(np.shape(arr)[:2], dtype=object)) if arr is not None else 0
    return n


def figure_units(fig: Figure, key: str) -> int:
    """``FIGURE`` plus ``POINT`` a drawn point (``drawn_points``) and ``PIXEL`` an image pixel (``drawn_pixels``).

    Raises
    ------
    ValueError
        Beyond ``fusion._limits.MAX_WORK`` units, naming ``values[key]``, before the figure is audited or rendered.
    """
    points, pixels = drawn_points(fig), drawn_pixels(fig)
    units = FIGURE + POINT * points + PIXEL * pixels
    if units > MAX_WORK:
        raise ValueError(f"values[{shown(key)}] is a figure drawing {points:,} points (lines' vertices, collections' "
                         f"offsets and paths) and {pixels:,} image pixels, {units:.3g} units of work at {POINT:,} a "
                         f"point and {PIXEL} a pixel rendered, beyond the work budget (at most {MAX_WORK:.3g} units, fusion._limits.MAX_WORK, "
                         "about 10 CPU-s)")
    return units
