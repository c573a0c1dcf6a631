"""The browser checks of ``tests/test_browser.py`` checked themselves: each checker fails on a page made to have its
problem and passes without, and the browser driver reports console errors, keeps pages apart and fails clearly on a
hung page or a dead browser.

These do not need the built book, so they are a work unit of their own: the scheduler (``tests/conftest.py``) runs
them beside the other tests instead of after the book build with the page sweep. Skipped, with the reason, where no
Chromium is installed.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from test_browser import (CHROMIUM, Chromium, _live_processes, bad_alt_texts, broken_images, broken_links,
                          console_errors, not_full_size_on_tap, overflowing, parse_page, probe_found,
                          render_widths_with_probe, render_with_probe, squashed, unrendered_math)


@pytest.fixture(scope="module")
def chromium(tmp_path_factory: pytest.TempPathFactory):  # noqa: ANN201 - a generator fixture
    """One Chromium for this module's own renderings (the checks of the checkers)."""
    with Chromium(tmp_path_factory.mktemp("chromium")) as browser:
        yield browser


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
def test_overflow_probe_detects_wide_content(tmp_path: Path, chromium: Chromium) -> None:
    """The width check must fail on a page with a table wider than its column, and pass without."""
    page = tmp_path / "wide.html"
    cells = "".join(f"<td>column-{i}-with-a-long-unbreakable-word</td>" for i in range(12))
    page.write_text(f"<html><body><main><p>text</p><table><tr>{cells}</tr></table></main></body></html>",
                    encoding="utf-8")
    found = overflowing(page, 800, chromium)
    assert [f["tag"] for f in found] == ["table"]
    page.write_text("<html><body><main><p>narrow</p><table><tr><td>a</td></tr></table></main></body></html>",
                    encoding="utf-8")
    assert overflowing(page, 800, chromium) == []
    eq = ('<div class="math"><span class="eqno" style="display:inline-block;width:{n}px">(1)</span>'
          '<mjx-math style="display:inline-block;width:{m}px">x</mjx-math></div>')
    page.write_text(f"<html><body><main style='width:600px'>{eq.format(n=80, m=560)}</main></body></html>",
                    encoding="utf-8")
    assert [f["tag"] for f in overflowing(page, 800, chromium)] == ["equation + number"]
    page.write_text(f"<html><body><main style='width:600px'>{eq.format(n=80, m=400)}</main></body></html>",
                    encoding="utf-8")
    assert overflowing(page, 800, chromium) == []


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_the_browser_reports_console_errors_in_virtual_time(tmp_path: Path, chromium: Chromium) -> None:
    """What the console check reads: an uncaught exception, a console error over two lines and a failed load,
    each from a file of the page's; and the page's timers run in virtual time (a timer 19 s ahead fires, and
    its exception is reported, in much less than 19 s)."""
    import time

    page = tmp_path / "errors.html"
    page.write_text('<html><body><img src="missing.png"><script>console.log("fine");'
                    'console.error("Error: one\\ntwo"); '
                    "setTimeout(function () { notDefined(); }, 19000);</script></body></html>", encoding="utf-8")
    start = time.monotonic()
    dom, console = chromium.render(page.as_uri(), 800)
    assert time.monotonic() - start < 19
    assert "</html>" in dom
    assert sorted(console_errors(console, tmp_path)) == [
        f"Error: one\\ntwo ({page.as_uri()})",
        f"Failed to load resource: net::ERR_FILE_NOT_FOUND ({(tmp_path / 'missing.png').as_uri()})",
        f"Uncaught ReferenceError: notDefined is not defined ({page.as_uri()})",
    ]
    assert "fine" in console                      # logged, and not an error


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_pages_do_not_see_what_earlier_pages_stored(tmp_path: Path, chromium: Chromium) -> None:
    """The book's theme keeps its light/dark mode in local storage: a page must not see what the page rendered
    before it stored (it would take another code path than a reader's first visit)."""
    page = tmp_path / "store.html"
    page.write_text('<html><body><script>console.log("found " + localStorage.getItem("mode") + " "'
                    ' + sessionStorage.getItem("mode")); localStorage.setItem("mode", "dark");'
                    ' sessionStorage.setItem("mode", "dark");</script></body></html>', encoding="utf-8")
    for _ in range(3):
        assert '"found null null"' in chromium.render(page.as_uri(), 800)[1]


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_a_refused_opaque_origin_is_tolerated_and_nothing_else(tmp_path: Path) -> None:
    """Review 18: the session storage is also cleared under the opaque origin "null" (Chromium 150 keeps a file page's
    there); a Chromium that refuses that origin (a DevTools error) still renders, but any other failure of that command,
    or a refusal of the "file://" one, fails the page."""
    import test_browser as tb

    page = tmp_path / "fine.html"
    page.write_text("<html><body><p>fine</p></body></html>", encoding="utf-8")
    with Chromium(tmp_path / "profile") as browser:
        real = browser.send

        def refusing(failure: type[RuntimeError], origin: str):
            def send(method, params=None, session=None, timeout=tb.COMMAND_TIMEOUT):
                if method == "Storage.clearDataForOrigin" and (params or {}).get("origin") == origin:
                    raise failure(f"{method}: Chromium refused it: {{'code': -32602, 'message': 'Invalid origin'}}")
                return real(method, params, session, timeout)
            return send

        browser.send = refusing(tb.DevToolsRefused, "null")
        assert "<p>fine</p>" in browser.render(page.as_uri(), 800)[0]
        browser.send = refusing(RuntimeError, "null")
        with pytest.raises(RuntimeError, match="fine.html at 800 px: Storage.clearDataForOrigin"):
            browser.render(page.as_uri(), 800)
        browser.send = refusing(tb.DevToolsRefused, "file://")
        with pytest.raises(RuntimeError, match="fine.html at 800 px: Storage.clearDataForOrigin"):
            browser.render(page.as_uri(), 800)


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_a_hung_page_or_an_ended_browser_fails_clearly(tmp_path: Path) -> None:
    """A page that never finishes fails after its timeout, naming it, and the browser renders the next page; a
    browser that has died fails the next page, saying so; either way no process of the browser is left."""
    import os
    import signal

    hung, fine = tmp_path / "hung.html", tmp_path / "fine.html"
    hung.write_text("<html><body><script>for (;;) {}</script></body></html>", encoding="utf-8")
    fine.write_text("<html><body><p>fine</p></body></html>", encoding="utf-8")
    with Chromium(tmp_path / "profile") as browser:
        with pytest.raises(RuntimeError, match=r"hung\.html at 800 px: .*(hung|did not answer)"):
            browser.render(hung.as_uri(), 800, timeout=1)
        assert "<p>fine</p>" in browser.render(fine.as_uri(), 800)[0]
        os.kill(browser.pid, signal.SIGKILL)
        with pytest.raises(RuntimeError, match=r"fine\.html at 800 px: .*(exited or crashed)"):
            browser.render(fine.as_uri(), 800)
    assert _live_processes(browser.pid) == []


def _png(path: Path, width: int, height: int) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(width / 100, height / 100), dpi=100)
    fig.savefig(path, dpi=100)
    plt.close(fig)


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_figure_and_maths_checks_detect_problems(tmp_path: Path, chromium: Chromium) -> None:
    """The figure, alt-text and clipped-formula checks must fail on a page with each problem, and pass
    without; and a 420-px check must really see a 420-px viewport."""
    _png(tmp_path / "f.png", 1400, 700)                          # a 700×350 figure drawn at 2×
    bad = ('<figure><img src="f.png" alt="f.png" style="width:700px;height:350px;max-width:100%"></figure>'
           '<p><span class="math" style="display:inline-flex;max-width:100%;overflow:hidden">'
           '<mjx-container><mjx-math style="display:inline-block;width:600px">x</mjx-math></mjx-container></span></p>')
    page = tmp_path / "bad.html"
    page.write_text(f"<html><body><main>{bad}</main></body></html>", encoding="utf-8")
    dom, _ = render_with_probe(page, 420, chromium)
    figures = probe_found(dom, page.name, "figures")
    assert len(figures) == 1 and len(squashed(figures)) == 1 and len(bad_alt_texts(figures)) == 1
    assert len(not_full_size_on_tap(figures)) == 1
    assert len(probe_found(dom, page.name, "clipped-math")) == 1
    wide, resized = render_widths_with_probe(page, (1400, 420), chromium)   # loaded at 1400 px, then resized
    assert probe_found(wide[0], page.name, "clipped-math") == [] and not_full_size_on_tap(
        probe_found(wide[0], page.name, "figures")) == []
    for what in ("figures", "clipped-math"):
        assert probe_found(resized[0], page.name, what) == probe_found(dom, page.name, what)
    good = ('<figure><a href="f.png"><img src="f.png" alt="Line chart of the error against time; series: mean."'
            ' style="width:700px;height:350px;max-width:100%;height:auto"></a></figure>'
            '<p><span class="math" style="display:inline-flex;max-width:100%;overflow-x:auto">'
            '<mjx-container><mjx-math style="display:inline-block;width:600px">x</mjx-math></mjx-container></span></p>')
    page.write_text(f"<html><body><main>{good}</main></body></html>", encoding="utf-8")
    dom, _ = render_with_probe(page, 420, chromium)
    figures = probe_found(dom, page.name, "figures")
    assert squashed(figures) == [] and bad_alt_texts(figures) == [] and not_full_size_on_tap(figures) == []
    assert probe_found(dom, page.name, "clipped-math") == []
    assert float(figures[0]["width"]) < 420                        # type: ignore[arg-type]


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_published_vs_reproduced_check_detects_hidden_columns(tmp_path: Path, chromium: Chromium) -> None:
    """The key-column check must fail when a table's "reproduced" column lies beyond a phone's screen."""
    cells = "".join(f"<th>notes-{i}-with-a-long-unbreakable-word</th>" for i in range(4))
    page = tmp_path / "pvr.html"
    page.write_text(f"<html><body><main><table><thead><tr><th></th><th>published</th>{cells}<th>reproduced</th>"
                    "</tr></thead><tbody><tr><td>1</td></tr></tbody></table></main></body></html>", encoding="utf-8")
    found = probe_found(render_with_probe(page, 420, chromium)[0], page.name, "pvr-columns")
    assert [f["column"] for f in found] == ["reproduced"]
    page.write_text("<html><body><main><table><thead><tr><th></th><th>published</th><th>reproduced</th></tr>"
                    "</thead><tbody><tr><td>1</td></tr></tbody></table></main></body></html>", encoding="utf-8")
    assert probe_found(render_with_probe(page, 420, chromium)[0], page.name, "pvr-columns") == []
