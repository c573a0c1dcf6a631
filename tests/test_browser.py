"""The rendered book, as a reader's browser shows it.

Takes the HTML book built once per session by ``tests/conftest.py`` (from the committed
notebook outputs, which the nbval tests prove current; tests/test_book_build.py checks that
build with or without Chromium) and opens every page in headless Chromium. A page fails when it
shows unrendered or erroneous math, a broken image, a broken internal link or anchor, or a
console error from the book's own scripts.

Skipped, with the reason, where no Chromium is installed (`.ci/run` installs Debian's
``chromium`` when it can).
"""

from __future__ import annotations

import re
import shutil
import subprocess
from concurrent.futures import ThreadPoolExecutor
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlparse

import pytest

ROOT = Path(__file__).resolve().parents[1]
CHROMIUM = next(
    (shutil.which(name) for name in ("chromium", "chromium-browser", "google-chrome") if shutil.which(name)),
    None,
)
CHROMIUM_FLAGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
    "--disable-component-update", "--disable-sync", "--no-first-run", "--disable-quic",
    "--virtual-time-budget=20000", "--enable-logging=stderr", "--v=0",
]
CONSOLE = re.compile(r':CONSOLE(?::\d+)?(?:\(\d+\))?\] "(?P<msg>.*)", source: (?P<src>\S*)')
CONSOLE_ERROR = re.compile(r"Uncaught|Error|Failed to load|ERR_")


# --------------------------------------------------------------------------- checkers


class _PageParser(HTMLParser):
    """Collects math elements, images, links and element ids of one HTML page."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.stack: list[tuple[str, bool]] = []  # (tag, is_math_root)
        self.math_roots: list[dict[str, object]] = []
        self.images: list[str] = []
        self.links: list[str] = []
        self.ids: set[str] = set()
        self.math_errors = 0
        self._skip_depth = 0  # inside <script>/<style>

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        a = {k: (v or "") for k, v in attrs}
        if "id" in a:
            self.ids.add(a["id"])
        if tag in ("script", "style"):
            self._skip_depth += 1
        classes = a.get("class", "").split()
        is_math = tag in ("span", "div") and "math" in classes and "notranslate" in classes
        if is_math:
            self.math_roots.append({"rendered": False, "text": ""})
        if tag == "mjx-container" and self._in_math():
            self.math_roots[-1]["rendered"] = True
        if tag == "mjx-merror":
            self.math_errors += 1
        if tag == "img" and a.get("src"):
            self.images.append(a["src"])
        if tag == "a" and a.get("href"):
            self.links.append(a["href"])
        if tag not in ("img", "br", "hr", "meta", "link", "input", "source", "col"):
            self.stack.append((tag, is_math))

    def handle_endtag(self, tag: str) -> None:
        if tag in ("script", "style"):
            self._skip_depth = max(0, self._skip_depth - 1)
        while self.stack:
            top, _ = self.stack.pop()
            if top == tag:
                break

    def handle_data(self, data: str) -> None:
        if self._skip_depth == 0 and self._in_math():
            self.math_roots[-1]["text"] = str(self.math_roots[-1]["text"]) + data

    def _in_math(self) -> bool:
        return any(is_math for _, is_math in self.stack)


def parse_page(html: str) -> _PageParser:
    parser = _PageParser()
    parser.feed(html)
    return parser


def unrendered_math(page: _PageParser) -> list[str]:
    """TeX sources of math elements that MathJax did not typeset."""
    return [str(m["text"]).strip()[:80] for m in page.math_roots if not m["rendered"]]


def broken_images(page: _PageParser, page_path: Path) -> list[str]:
    """Local images that are missing, empty or not a PNG/JPEG/SVG/GIF file."""
    bad = []
    for src in page.images:
        if src.startswith(("data:", "http:", "https:")):
            continue
        target = (page_path.parent / unquote(urlparse(src).path)).resolve()
        if not target.is_file() or target.stat().st_size == 0:
            bad.append(src)
            continue
        head = target.read_bytes()[:8]
        if not (head.startswith(b"\x89PNG") or head.startswith(b"\xff\xd8") or head.startswith(b"GIF8")
                or b"<svg" in target.read_bytes()[:512] or target.suffix == ".svg"):
            bad.append(src)
    return bad


def broken_links(page: _PageParser, page_path: Path, ids_of: dict[Path, set[str]]) -> list[str]:
    """Internal links whose file, or whose #anchor in that file, does not exist."""
    bad = []
    for href in page.links:
        url = urlparse(href)
        if url.scheme in ("http", "https", "mailto", "javascript") or href.startswith("//"):
            continue
        target = page_path if not url.path else (page_path.parent / unquote(url.path)).resolve()
        if target.is_dir():
            target = target / "index.html"
        if not target.exists():
            bad.append(href)
            continue
        if url.fragment and target.suffix == ".html":
            if target not in ids_of:
                ids_of[target] = parse_page(target.read_text(encoding="utf-8", errors="replace")).ids
            if unquote(url.fragment) not in ids_of[target]:
                bad.append(href)
    return bad


def console_errors(stderr: str, site: Path) -> list[str]:
    """Console errors (exceptions, failed loads) raised by files inside the book."""
    out = []
    for line in stderr.splitlines():
        m = CONSOLE.search(line)
        if not m or not CONSOLE_ERROR.search(m["msg"]):
            continue
        src = m["src"]
        if not src or src.startswith(f"file://{site}") or src.startswith("file:///"):
            out.append(f"{m['msg']} ({src})")
    return out


PROBE = (Path(__file__).parent / "overflow_probe.js").read_text(encoding="utf-8")
OVERFLOW = re.compile(r'data-fusion-overflow="(?P<json>[^"]*)"')


def render_with_probe(page: Path, width: int, profile: Path) -> tuple[str, str]:
    """The DOM (after MathJax) and Chromium's stderr of ``page`` in a ``width``-px window, with the overflow
    probe injected (it only measures, and records what it finds in an attribute of ``<body>``)."""
    probe = page.with_name(page.stem + ".overflow-probe.html")
    probe.write_text(page.read_text(encoding="utf-8").replace("</body>", f"<script>{PROBE}</script></body>"),
                     encoding="utf-8")
    try:
        proc = subprocess.run(
            [str(CHROMIUM), *CHROMIUM_FLAGS, f"--user-data-dir={profile}", f"--window-size={width},2000",
             "--dump-dom", probe.as_uri()],
            capture_output=True, text=True, timeout=120,
        )
    finally:
        probe.unlink()
    return proc.stdout, proc.stderr


def overflow_found(dom: str, name: str) -> list[dict[str, object]]:
    """What the overflow probe recorded in a rendered DOM (elements wider than the text column)."""
    import html
    import json

    m = OVERFLOW.search(dom)
    assert m, f"{name}: the overflow probe did not run"
    return json.loads(html.unescape(m["json"]))


def overflowing(page: Path, width: int, profile: Path) -> list[dict[str, object]]:
    """Elements of ``page`` wider than its text column in a ``width``-px window (Chromium)."""
    return overflow_found(render_with_probe(page, width, profile)[0], page.name)


# --------------------------------------------------------------------------- checker tests


def test_checkers_detect_problems(tmp_path: Path) -> None:
    """The checkers themselves must fail on a page that has every kind of problem."""
    (tmp_path / "good.png").write_bytes(b"\x89PNG\r\n\x1a\n" + b"\0" * 16)
    (tmp_path / "other.html").write_text('<p id="here">x</p>', encoding="utf-8")
    page_html = """
      <div class="math notranslate nohighlight">\\[x^2\\]</div>
      <span class="math notranslate nohighlight"><mjx-container>ok</mjx-container></span>
      <span class="math notranslate nohighlight"><mjx-container><mjx-merror/></mjx-container></span>
      <img src="good.png"><img src="missing.png">
      <a href="other.html#here">ok</a><a href="other.html#nowhere">bad anchor</a>
      <a href="absent.html">bad file</a><a href="https://example.org">external</a>
    """
    page_path = tmp_path / "page.html"
    page_path.write_text(page_html, encoding="utf-8")
    page = parse_page(page_html)
    assert unrendered_math(page) == ["\\[x^2\\]"]
    assert page.math_errors == 1
    assert broken_images(page, page_path) == ["missing.png"]
    assert broken_links(page, page_path, {}) == ["other.html#nowhere", "absent.html"]
    log = (
        '[1:1:INFO:CONSOLE:62] "Uncaught SyntaxError: x", source: file:///site/a.html (62)\n'
        '[1:1:INFO:CONSOLE:1] "[PST]: Changed to auto mode", source: file:///site/b.js (1)\n'
    )
    assert console_errors(log, Path("/site")) == ["Uncaught SyntaxError: x (file:///site/a.html)"]


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_overflow_probe_detects_wide_content(tmp_path: Path) -> None:
    """The width check must fail on a page with a table wider than its column, and pass without."""
    page = tmp_path / "wide.html"
    cells = "".join(f"<td>column-{i}-with-a-long-unbreakable-word</td>" for i in range(12))
    page.write_text(f"<html><body><main><p>text</p><table><tr>{cells}</tr></table></main></body></html>",
                    encoding="utf-8")
    found = overflowing(page, 800, tmp_path / "p1")
    assert [f["tag"] for f in found] == ["table"]
    page.write_text("<html><body><main><p>narrow</p><table><tr><td>a</td></tr></table></main></body></html>",
                    encoding="utf-8")
    assert overflowing(page, 800, tmp_path / "p2") == []
    eq = ('<div class="math"><span class="eqno" style="display:inline-block;width:{n}px">(1)</span>'
          '<mjx-math style="display:inline-block;width:{m}px">x</mjx-math></div>')
    page.write_text(f"<html><body><main style='width:600px'>{eq.format(n=80, m=560)}</main></body></html>",
                    encoding="utf-8")
    assert [f["tag"] for f in overflowing(page, 800, tmp_path / "p3")] == ["equation + number"]
    page.write_text(f"<html><body><main style='width:600px'>{eq.format(n=80, m=400)}</main></body></html>",
                    encoding="utf-8")
    assert overflowing(page, 800, tmp_path / "p4") == []


# --------------------------------------------------------------------------- the book


@pytest.fixture(scope="module")
def site(book_html: Path) -> Path:
    """The book built once per session from the committed notebooks (``book_html`` in conftest.py)."""
    if CHROMIUM is None:
        pytest.skip("no Chromium on PATH: install Debian's `chromium` (.ci/run does) to run the browser test")
    return book_html


REDIRECT = re.compile(r'http-equiv="refresh"[^>]*url=(?P<url>[^"]+)"', re.IGNORECASE)


def _pages(site: Path) -> list[Path]:
    """Every HTML page except redirect stubs (checked by test_redirects_resolve)."""
    return sorted(
        p for p in site.rglob("*.html")
        if "_static" not in p.parts and "_sources" not in p.parts
        and not REDIRECT.search(p.read_text(encoding="utf-8", errors="replace")[:2000])
    )


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_redirects_resolve(site: Path) -> None:
    stubs = [p for p in site.rglob("*.html")
             if REDIRECT.search(p.read_text(encoding="utf-8", errors="replace")[:2000])]
    assert (site / "index.html") in stubs
    for stub in stubs:
        url = REDIRECT.search(stub.read_text(encoding="utf-8")[:2000])["url"]
        assert (stub.parent / url).resolve().is_file(), f"{stub.name} redirects to missing {url}"


def _is_source_listing(site: Path, page: Path) -> bool:
    """A highlighted-source page of sphinx.ext.viewcode (``_modules/``)."""
    return page.relative_to(site).parts[0] == "_modules"


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_source_listings_are_static_and_their_links_resolve(site: Path) -> None:
    """The ``_modules/`` pages (about 40 of the book's pages) are checked without Chromium.

    They are highlighted source code: no math, no tables, figures or cell outputs (the only elements the
    width probe measures), and the theme's scripts that run on them also run on every rendered page. So
    their static HTML is what a reader's browser shows, and its links and images are checked here; the
    pages with math and outputs are rendered (:func:`rendered`). Rendering the listings too cost about
    half of this file's time in ``make test``.
    """
    listings = [p for p in _pages(site) if _is_source_listing(site, p)]
    assert listings, "no _modules pages: viewcode is expected to list the package's source"
    problems: dict[str, list[str]] = {}
    ids_of: dict[Path, set[str]] = {}
    for path in listings:
        html = path.read_text(encoding="utf-8", errors="replace")
        page = parse_page(html)
        issues = [f"math on a source listing: {t}" for t in unrendered_math(page)]
        issues += ["a table, figure or cell output on a source listing"] if re.search(
            r"<(table|figure)\b|class=\"[^\"]*\bcell_output", html) else []
        issues += [f"broken image: {s}" for s in broken_images(page, path)]
        issues += [f"broken link: {h}" for h in broken_links(page, path, ids_of)]
        if issues:
            problems[str(path.relative_to(site))] = issues
    assert not problems, "\n".join(f"{k}: {v}" for k, v in problems.items())


@pytest.fixture(scope="module")
def rendered(site: Path, tmp_path_factory: pytest.TempPathFactory) -> dict[Path, tuple[str, str]]:
    """Every page but the source listings rendered once by Chromium at 1400 px with the overflow probe:
    page -> (DOM, stderr).

    One pass serves both the rendering checks and the width check (each page used to be rendered twice).
    """
    pages = [p for p in _pages(site) if not _is_source_listing(site, p)]
    tmp = tmp_path_factory.mktemp("chromium")
    with ThreadPoolExecutor(max_workers=2) as pool:
        out = list(pool.map(lambda ip: render_with_probe(ip[1], 1400, tmp / f"profile{ip[0]}"), enumerate(pages)))
    return dict(zip(pages, out))


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_every_page_renders_cleanly(site: Path, rendered: dict[Path, tuple[str, str]]) -> None:
    pages = list(rendered)
    assert any(p.name == "01_optimal_fusion_set.html" for p in pages), "chapter pages missing from the build"
    problems: dict[str, list[str]] = {}
    ids_of: dict[Path, set[str]] = {}
    n_math = 0
    for path, (dom, stderr) in rendered.items():
        name = str(path.relative_to(site))
        assert "</html>" in dom, f"{name}: Chromium returned no DOM"
        page = parse_page(dom)
        n_math += len(page.math_roots)
        issues = [f"unrendered math: {t}" for t in unrendered_math(page)]
        issues += [f"{page.math_errors} MathJax error(s)"] if page.math_errors else []
        issues += [f"broken image: {s}" for s in broken_images(page, path)]
        issues += [f"broken link: {h}" for h in broken_links(page, path, ids_of)]
        issues += [f"console error: {e}" for e in console_errors(stderr, site)]
        if issues:
            problems[name] = issues
    assert n_math > 0, "no math found on any page: the math check would be vacuous"
    assert not problems, "\n".join(f"{k}: {v}" for k, v in problems.items())


def _overflow_lines(site: Path, found: dict[Path, list[dict[str, object]]]) -> dict[str, list[str]]:
    return {str(p.relative_to(site)): [f"{f['tag']} near #{f['near']}: {f['width']} px in a {f['column']} px column "
                                       f"({f['text']!s:.40})" for f in fs]
            for p, fs in found.items() if fs}


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_nothing_is_wider_than_the_text_column_at_1400px(site: Path, rendered: dict[Path, tuple[str, str]]) -> None:
    report = _overflow_lines(site, {p: overflow_found(dom, p.name) for p, (dom, _) in rendered.items()})
    assert not report, "\n".join(f"{k}: {v}" for k, v in report.items())


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_verdicts_page_fits_a_phone(site: Path, tmp_path: Path) -> None:
    page = site / "book" / "verdicts.html"
    report = _overflow_lines(site, {page: overflowing(page, 420, tmp_path / "phone")})
    assert not report, "\n".join(f"{k}: {v}" for k, v in report.items())
