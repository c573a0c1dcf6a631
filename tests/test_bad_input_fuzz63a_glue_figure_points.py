"""Fuzz 63a C3: glue_all counts a figure's drawn points before auditing or rendering it, naming values['k']."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from _helpers import glue_refused  # noqa: E402


def _lines(lines: int, points: int):
    fig, ax = plt.subplots()
    x = np.linspace(0, 1000, points)
    for j in range(lines):
        ax.plot(x, np.sin(x + j))
    return fig


def test_a_figure_is_weighed_by_its_drawn_points_at_both_bounds() -> None:
    """The edge (``(MAX_WORK - _GLUE_VALUE - FIGURE) // POINT`` points) is within the budget by the glue's count (one
    line of 3e5 points was glued in 16.9 CPU-s: not run); one point more, 12 lines of 3e5 points (accepted after
    59.9 CPU-s before) and one line of 10**7 (a raw MemoryError) are refused naming values['k'] within 1 CPU-s."""
    from fusion._limits import MAX_WORK
    from fusion.book import _glue_figure as F
    from fusion.book import glue as G

    edge = (MAX_WORK - G._GLUE_VALUE - F.FIGURE) // F.POINT
    # its axes' ticks are one-point lines too (fewer than 200); its about 115 artists and their characters are
    # weighed too since fuzz 64a C5 (ARTIST, CHARACTER: about 7e6 units, 3,500 points)
    fig = _lines(1, edge - 5000)
    assert edge - 5000 < F.drawn_points(fig) <= edge
    assert G._GLUE_VALUE + G._glue_work(fig, "k") <= MAX_WORK
    plt.close(fig)
    for lines, points in ((1, edge + 1), (12, 300_000), (1, 10**7)):
        fig = _lines(lines, points)
        glue_refused({"k": fig}, ValueError, r"values\['k'\] is a figure drawing")
        plt.close(fig)


def test_scatter_and_image_points_are_counted() -> None:
    """A scatter's offsets are drawn points too; an image's pixels are counted at their own (lower) weight."""
    from fusion.book import _glue_figure as F

    fig, ax = plt.subplots()
    ax.scatter(np.arange(1000), np.arange(1000))
    ax.imshow(np.zeros((30, 40)))
    assert F.drawn_points(fig) >= 1000 and F.drawn_pixels(fig) == 1200
    plt.close(fig)


def test_an_image_is_weighed_by_its_pixels_at_both_bounds() -> None:
    """A 1000 x 1000 image (glued in 0.15 CPU-s; refused when a pixel weighed as a line's vertex) is within the budget;
    one of more pixels than the budget holds at ``PIXEL`` units each is refused naming values['k'] within 1 CPU-s."""
    from fusion._limits import MAX_WORK
    from fusion.book import _glue_figure as F
    from fusion.book import glue as G

    fig, ax = plt.subplots()
    ax.imshow(np.zeros((1000, 1000)))
    assert G._GLUE_VALUE + G._glue_work(fig, "k") <= MAX_WORK
    plt.close(fig)
    side = int(np.sqrt((MAX_WORK - G._GLUE_VALUE - F.FIGURE) // F.PIXEL)) + 1
    fig, ax = plt.subplots()
    ax.imshow(np.zeros((side, side), dtype=np.uint8))
    glue_refused({"k": fig}, ValueError, r"values\['k'\] is a figure drawing .* image pixels")
    plt.close(fig)
