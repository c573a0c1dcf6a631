"""Sphinx extension: every figure of the book gets a real alt text (issue 28).

myst-nb writes a notebook figure as ``<img alt="../_images/<sha256>.png">``: without an ``:alt:``
option docutils uses the file path, which a screen reader then announces. This extension gives each
image without an explicit alt text

1. the ``Description`` text chunk of its PNG, which the notebook wrote when it drew the figure
   (:func:`fusion.book.style.use_book_style`: the alt text set by ``glue_figure(..., alt=...)``,
   :data:`fusion.book.style.FIGURE_ALT` or, by default, :func:`fusion.book.style.describe_figure`);
2. else, for a PNG stored before that mechanism existed, the first sentence of the figure's caption.

The image's class says which (``alt-from-figure`` or ``alt-from-caption``), so tests can tell.
"""

from __future__ import annotations

import re
from pathlib import Path

from docutils import nodes
from sphinx.application import Sphinx

#: Longest caption-derived alt text (characters).
MAX_CAPTION_ALT = 300


def _caption_alt(image: nodes.image) -> str | None:
    figure = image.parent
    while figure is not None and not isinstance(figure, nodes.figure):
        figure = figure.parent
    if figure is None:
        return None
    caption = next(iter(figure.findall(nodes.caption)), None)
    if caption is None:
        return None
    from fusion.book.style import plain_math

    # formulas in the caption read as text (σ₁², not \sigma_1^2)
    text = "".join(plain_math(t.astext()) if isinstance(t.parent, nodes.math) else t.astext()
                   for t in caption.findall(nodes.Text))
    text = " ".join(text.split())
    first = re.split(r"(?<=[.!?])\s+(?=[A-Z(])", text, maxsplit=1)[0]
    if len(first) > MAX_CAPTION_ALT:
        first = first[:MAX_CAPTION_ALT].rsplit(" ", 1)[0] + " …"
    return first or None


def _image_file(app: Sphinx, image: nodes.image, docname: str) -> Path | None:
    uri = image.get("candidates", {}).get("*") or image.get("uri", "")
    if not uri or "://" in uri or uri.startswith("data:"):
        return None
    path = Path(uri)
    if not path.is_absolute():
        path = Path(app.srcdir) / path
    return path if path.is_file() else None


def add_alt_text(app: Sphinx, doctree: nodes.document, docname: str) -> None:
    """Set ``alt`` on every image of ``doctree`` that has none (see the module docstring)."""
    from fusion.book.style import png_description

    for image in doctree.findall(nodes.image):
        if image.get("alt"):
            continue
        path = _image_file(app, image, docname)
        alt = png_description(path.read_bytes()) if path is not None and path.suffix == ".png" else None
        source = "figure"
        if not alt:
            alt, source = _caption_alt(image), "caption"
        if alt:
            image["alt"] = alt
            image["classes"].append(f"alt-from-{source}")


def setup(app: Sphinx) -> dict[str, object]:
    app.connect("doctree-resolved", add_alt_text)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
