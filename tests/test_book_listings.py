"""The built book's static pages, without a browser: redirect stubs resolve, and the source listings
(``_modules/``, highlighted code) have no math, tables or outputs and no broken link or image.

They read the book built once per run (``book_html`` in ``tests/conftest.py``) but need no Chromium, so they run
where it is not installed too; a work unit of their own, beside ``tests/test_browser.py`` at the end of the run
(the two used to run one after the other on one core).
"""

from __future__ import annotations

import re
from pathlib import Path

from test_browser import (REDIRECT, _is_source_listing, _pages, broken_images, broken_links, parse_page,
                          unrendered_math)


def test_redirects_resolve(book_html: Path) -> None:
    stubs = [p for p in book_html.rglob("*.html")
             if REDIRECT.search(p.read_text(encoding="utf-8", errors="replace")[:2000])]
    assert (book_html / "index.html") in stubs
    for stub in stubs:
        url = REDIRECT.search(stub.read_text(encoding="utf-8")[:2000])["url"]
        assert (stub.parent / url).resolve().is_file(), f"{stub.name} redirects to missing {url}"


def test_source_listings_are_static_and_their_links_resolve(book_html: Path) -> None:
    """The ``_modules/`` pages (about 40 of the book's pages) are checked without Chromium.

    They are highlighted source code: no math, no tables, figures or cell outputs (the only elements the
    width probe measures), and the theme's scripts that run on them also run on every rendered page. So
    their static HTML is what a reader's browser shows, and its links and images are checked here; the
    pages with math and outputs are rendered (``rendered`` in ``tests/test_browser.py``). Rendering the
    listings too cost about half of the browser test's time in ``make test``.
    """
    listings = [p for p in _pages(book_html) if _is_source_listing(book_html, p)]
    assert listings, "no _modules pages: viewcode is expected to list the package's source"
    problems: dict[str, list[str]] = {}
    ids_of: dict[Path, set[str]] = {}
    for path in listings:
        html = path.read_text(encoding="utf-8", errors="replace")
        page = parse_page(html)
        for key in (path, path.resolve()):  # a link to an #anchor of this page reads the ids of this same text: not
            ids_of.setdefault(key, page.ids)  # parsed again for them (speed66b: 70 listings each parsed twice)
        issues = [f"math on a source listing: {t}" for t in unrendered_math(page)]
        issues += ["a table, figure or cell output on a source listing"] if re.search(
            r"<(table|figure)\b|class=\"[^\"]*\bcell_output", html) else []
        issues += [f"broken image: {s}" for s in broken_images(page, path)]
        issues += [f"broken link: {h}" for h in broken_links(page, path, ids_of)]
        if issues:
            problems[str(path.relative_to(book_html))] = issues
    assert not problems, "\n".join(f"{k}: {v}" for k, v in problems.items())
