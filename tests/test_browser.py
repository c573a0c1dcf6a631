"""The rendered book, as a reader's browser shows it.

Takes the HTML book built once per session by ``tests/conftest.py`` (from the committed
notebook outputs, which the nbval tests prove current; tests/test_book_build.py checks that
build with or without Chromium) and opens every page in headless Chromium. A page fails when it
shows unrendered or erroneous math, a broken image, a broken internal link or anchor, or a
console error from the book's own scripts; and, at a laptop's 1280 px and a phone's 420 px (issue 28),
when a figure is squashed out of its shape, has no alt text in words, cannot be opened full size on a
phone, when an inline formula is cut off, or when a published-vs-reproduced table hides its published
or reproduced column off a phone's screen.

The checkers' own tests (each fails on a page made to have its problem) are in ``tests/test_browser_checks.py``,
which does not wait for the book; the static source listings and redirect stubs in ``tests/test_book_listings.py``.

Skipped, with the reason, where no Chromium is installed (`.ci/run` installs Debian's
``chromium`` when it can).
"""

from __future__ import annotations

import re
import shutil
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
    "--remote-debugging-pipe",
]
#: Virtual milliseconds a page's scripts (MathJax, the theme, the probe) get before its DOM is read: timers run
#: ahead as fast as the CPU allows, and virtual time stands still while a file is still loading (what
#: ``chromium --dump-dom --virtual-time-budget=20000`` did).
VIRTUAL_TIME_BUDGET = 20_000
#: Virtual milliseconds a loaded page gets after its viewport is resized (:meth:`Chromium.render_widths`): the
#: book's resize handlers (fusion.js refits formulas 150 ms after the last resize) and then the probe's (500 ms).
RESIZE_BUDGET = 2_000
#: Wall-clock seconds one page may take before the sweep fails, naming it (a hung renderer), and one DevTools
#: command may take (a hung browser).
PAGE_TIMEOUT, COMMAND_TIMEOUT = 120.0, 60.0
CONSOLE = re.compile(r':CONSOLE(?::\d+)?(?:\(\d+\))?\] "(?P<msg>.*)", source: (?P<src>\S*)')
CONSOLE_ERROR = re.compile(r"Uncaught|Error|Failed to load|ERR_")


# --------------------------------------------------------------------------- checkers


class _PageParser(HTMLParser):
    """Collects math elements, images, links and element ids of one HTML page."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.stack: list[tuple[str, bool]] = []  # (tag, is_math_root)
        self._math_open = 0  # math roots on the stack: _in_math in constant time (speed66b: the scan of the stack at
        # every text and start tag was 13 % of parsing a highlighted source listing)
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
            self._math_open += is_math

    def handle_endtag(self, tag: str) -> None:
        if tag in ("script", "style"):
            self._skip_depth = max(0, self._skip_depth - 1)
        while self.stack:
            top, was_math = self.stack.pop()
            self._math_open -= was_math
            if top == tag:
                break

    def handle_data(self, data: str) -> None:
        if self._skip_depth == 0 and self._in_math():
            self.math_roots[-1]["text"] = str(self.math_roots[-1]["text"]) + data

    def _in_math(self) -> bool:
        return self._math_open > 0   # any(is_math for _, is_math in self.stack)


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


def console_errors(console: str, site: Path) -> list[str]:
    """Console errors (exceptions, failed loads) raised by files inside the book."""
    out = []
    for line in console.splitlines():
        m = CONSOLE.search(line)
        if not m or not CONSOLE_ERROR.search(m["msg"]):
            continue
        src = m["src"]
        if not src or src.startswith(f"file://{site}") or src.startswith("file:///"):
            out.append(f"{m['msg']} ({src})")
    return out


# --------------------------------------------------------------------------- the browser


class DevToolsRefused(RuntimeError):
    """Chromium answered a DevTools command with an error (it was alive and refused it)."""


class Chromium:
    """One headless Chromium for many pages, driven over the DevTools protocol (issue 37).

    Starting a Chromium costs about as much CPU as rendering a page of the book: the sweep starts one and
    renders every page in it, each seeing nothing an earlier page stored (as with the fresh profile each page
    used to get; :meth:`render`). The protocol runs over a pair of pipes (``--remote-debugging-pipe``:
    Chromium reads commands from its descriptor 3 and writes replies and events to 4, each a JSON text ended
    by a NUL byte): no port, and nothing beyond the standard library. Two threads may render at once. Use it
    as a context manager: :meth:`close` always ends the browser and every process it started.

    Parameters
    ----------
    profile : Path
        Directory for the browser's profile (created); ``chromium.log`` there holds its own output.
    """

    def __init__(self, profile: Path) -> None:
        import fcntl
        import os
        import threading

        if CHROMIUM is None:
            raise RuntimeError("no Chromium on PATH")
        profile.mkdir(parents=True, exist_ok=True)
        self.log = profile / "chromium.log"
        to_chromium, from_chromium = os.pipe(), os.pipe()
        # the child's ends must land on 3 and 4: first move them above 4, so no dup2 below clobbers the other
        theirs = [fcntl.fcntl(fd, fcntl.F_DUPFD_CLOEXEC, 5) for fd in (to_chromium[0], from_chromium[1])]
        os.close(to_chromium[0]), os.close(from_chromium[1])
        try:
            self.pid = os.posix_spawn(
                CHROMIUM, [CHROMIUM, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", "about:blank"], dict(os.environ),
                file_actions=[(os.POSIX_SPAWN_OPEN, 0, os.devnull, os.O_RDONLY, 0),
                              (os.POSIX_SPAWN_OPEN, 1, str(self.log), os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644),
                              (os.POSIX_SPAWN_DUP2, 1, 2),
                              (os.POSIX_SPAWN_DUP2, theirs[0], 3), (os.POSIX_SPAWN_DUP2, theirs[1], 4)],
                setsid=True,                       # its own process group: close() ends every process it started
            )
        except BaseException:
            os.close(to_chromium[1]), os.close(from_chromium[0])
            raise
        finally:
            for fd in theirs:
                os.close(fd)
        self._out, self._in = to_chromium[1], from_chromium[0]
        self._lock = threading.Lock()              # guards the fields below and writes to the pipe
        self._next_id = 0
        self._replies: dict[int, dict[str, object]] = {}
        self._waiting: dict[int, threading.Event] = {}
        self._events: dict[str, object] = {}       # session id -> queue.Queue of its events
        self._ended: str | None = None             # why the connection ended
        self._closed = False
        self._idle: list[str] = []                 # browser contexts no page is rendering in
        self._tabs: dict[str, tuple[str, str]] = {}  # browser context -> its tab (target id, session id)
        self._reader = threading.Thread(target=self._read, name="chromium-devtools", daemon=True)
        self._reader.start()
        try:
            self.version = self.send("Browser.getVersion")["product"]
        except BaseException:
            self.close()
            raise

    def __enter__(self) -> Chromium:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # ----------------------------------------------------------------------- protocol

    def _read(self) -> None:
        """Reader thread: hand each reply to its command, each event to its session's queue."""
        import json
        import os
        import queue

        buffer = b""
        while True:
            try:
                chunk = os.read(self._in, 1 << 20)
            except OSError as exc:
                chunk, why = b"", f"the DevTools pipe failed ({exc})"
            else:
                why = "Chromium closed the DevTools pipe (it exited or crashed)"
            if not chunk:
                break
            buffer += chunk
            *messages, buffer = buffer.split(b"\0")
            for raw in messages:
                message = json.loads(raw)
                with self._lock:
                    if "id" in message:
                        self._replies[message["id"]] = message
                        if message["id"] in self._waiting:
                            self._waiting[message["id"]].set()
                    elif "sessionId" in message:
                        session = self._events.setdefault(message["sessionId"], queue.Queue())
                        session.put(message)  # type: ignore[attr-defined]
        with self._lock:
            self._ended = why
            for event in self._waiting.values():
                event.set()
            for q in self._events.values():
                q.put(None)  # type: ignore[attr-defined]

    def _alive_reason(self) -> str:
        tail = self.log.read_text(encoding="utf-8", errors="replace")[-1500:] if self.log.exists() else ""
        return f"{self._ended}; its log ends:\n{tail}"

    def send(self, method: str, params: dict[str, object] | None = None, session: str | None = None,
             timeout: float = COMMAND_TIMEOUT) -> dict[str, object]:
        """Send one DevTools command (to ``session``, a page, or to the browser) and return its result.

        Raises
        ------
        RuntimeError
            When Chromium answers with an error (:class:`DevToolsRefused`), has ended, or does not answer within
            ``timeout`` seconds.
        """
        import json
        import os
        import threading

        with self._lock:
            if self._ended is not None:
                raise RuntimeError(f"{method}: {self._alive_reason()}")
            self._next_id += 1
            ident = self._next_id
            done = self._waiting[ident] = threading.Event()
            message = {"id": ident, "method": method, "params": params or {}}
            if session is not None:
                message["sessionId"] = session
            data = json.dumps(message).encode() + b"\0"
            try:
                while data:
                    data = data[os.write(self._out, data):]
            except OSError as exc:
                del self._waiting[ident]
                raise RuntimeError(f"{method}: cannot write to Chromium ({exc}): it exited or crashed") from exc
        answered = done.wait(timeout)
        with self._lock:
            del self._waiting[ident]
            reply = self._replies.pop(ident, None)
        if reply is None:
            if not answered:
                raise RuntimeError(f"{method}: Chromium did not answer within {timeout:.0f} s (hung)")
            raise RuntimeError(f"{method}: {self._alive_reason()}")
        if "error" in reply:
            raise DevToolsRefused(f"{method}: Chromium refused it: {reply['error']}")
        return reply.get("result", {})  # type: ignore[return-value]

    # ----------------------------------------------------------------------- pages

    def render(self, url: str, width: int, timeout: float = PAGE_TIMEOUT) -> tuple[str, str]:
        """:meth:`render_widths` at one width."""
        return self.render_widths(url, (width,), timeout)[0]

    def render_widths(self, url: str, widths: tuple[int, ...], timeout: float = PAGE_TIMEOUT) -> list[tuple[str, str]]:
        """The DOM of ``url`` in a ``widths[0]``-px-wide, 2000-px-high viewport after
        :data:`VIRTUAL_TIME_BUDGET` virtual milliseconds, and its console, one ``:CONSOLE`` line per message in
        the form of Chromium's own log (:data:`CONSOLE`): console calls, uncaught exceptions and the browser's
        messages (failed loads); then, for each further width, the same loaded page's DOM after its viewport
        is resized to that width and :data:`RESIZE_BUDGET` more virtual milliseconds have passed, and the
        console messages of that time. One (DOM, console) per width.

        The page opens in a browser context (storage, cookies, caches) that no page rendering at the same time
        uses, in that context's one tab, its stored data (local and session storage) cleared first: what one page
        stores, the next does not see. Reusing the contexts (at most one per thread) and their tab keeps their
        renderer process and its compiled scripts: a tab of its own per page started and ended a renderer each
        time, about 0.5 CPU-seconds of the browser's per page (0.57 against 0.06 for an empty page).

        Raises
        ------
        RuntimeError
            Naming the page, when its renderer crashes, when it takes more than ``timeout`` seconds of wall
            time at all its widths (a hung page), or when the browser has ended.
        """
        import time

        deadline = time.monotonic() + timeout
        with self._lock:
            context = self._idle.pop() if self._idle else None
        try:
            if context is None:
                context = str(self.send("Target.createBrowserContext",
                                        timeout=min(timeout, COMMAND_TIMEOUT))["browserContextId"])
            out = self._render(url, widths, context, deadline)
        except RuntimeError as exc:
            if context is not None:                             # not reused after a failure
                with self._lock:
                    self._tabs.pop(context, None)
                self._quietly("Target.disposeBrowserContext", {"browserContextId": context})
            raise RuntimeError(f"{url} at {'/'.join(map(str, widths))} px: {exc}") from exc
        with self._lock:
            self._idle.append(context)
        return out

    def _render(self, url: str, widths: tuple[int, ...], context: str, deadline: float) -> list[tuple[str, str]]:
        import queue
        import time

        def send(method: str, params: dict[str, object] | None = None) -> dict[str, object]:
            return self.send(method, params, session, timeout=max(0.0, deadline - time.monotonic()))

        def viewport(width: int) -> None:
            send("Emulation.setDeviceMetricsOverride", {"width": width, "height": 2000, "deviceScaleFactor": 1,
                                                        "mobile": False})

        with self._lock:
            tab = self._tabs.get(context)
        if tab is None:
            target = str(self.send("Target.createTarget",
                                   {"url": "about:blank", "browserContextId": context})["targetId"])
            session = str(self.send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"])
        else:
            target, session = tab
        with self._lock:
            events = self._events.setdefault(session, queue.Queue())
        out: list[tuple[str, str]] = []
        try:
            if tab is None:
                for domain in ("Runtime", "Log", "Inspector"):
                    send(f"{domain}.enable")
            else:
                # the tab's previous page ends (its unload handlers run) before anything of this page is read
                send("Page.navigate", {"url": "about:blank"})
            while not events.empty():                           # type: ignore[attr-defined]
                if events.get() is None:                        # type: ignore[attr-defined]
                    raise RuntimeError(self._alive_reason())
            # a file page's storage is kept under "file://" by some Chromium releases (156: local and session
            # storage) and, for its session storage, under the serialised opaque origin "null" by others (Debian
            # bookworm's 150: cleared under "file://" only, a page saw the session storage the page before it left)
            send("Storage.clearDataForOrigin", {"origin": "file://", "storageTypes": "all"})
            try:   # another Chromium may refuse the opaque origin (review 18): only its refusal is tolerated, and
                # test_pages_do_not_see_what_earlier_pages_stored still catches storage that leaks
                send("Storage.clearDataForOrigin", {"origin": "null", "storageTypes": "all"})
            except DevToolsRefused:
                pass
            viewport(widths[0])
            send("Emulation.setVirtualTimePolicy", {"policy": "pause"})
            nav = send("Page.navigate", {"url": url})
            if nav.get("errorText"):
                raise RuntimeError(str(nav["errorText"]))
            console: list[str] = []
            for i, width in enumerate(widths):
                if i:
                    # the loaded page, resized: its resize events fire in its next frame, which a page whose
                    # virtual time stands still may not get (the API page did not): time runs until it has passed
                    send("Emulation.setVirtualTimePolicy", {"policy": "advance"})
                    viewport(width)
                    send("Runtime.evaluate", {"expression": "new Promise(r => requestAnimationFrame(() => r(0)))",
                                              "awaitPromise": True})
                send("Emulation.setVirtualTimePolicy", {"policy": "pauseIfNetworkFetchesPending",
                                                        "budget": RESIZE_BUDGET if i else VIRTUAL_TIME_BUDGET})
                while True:
                    try:
                        event = events.get(timeout=max(0.0, deadline - time.monotonic()))  # type: ignore[attr-defined]
                    except queue.Empty:
                        raise RuntimeError(f"no DOM at {width} px in time (a hung page)") from None
                    if event is None:
                        raise RuntimeError(self._alive_reason())
                    if event["method"] == "Emulation.virtualTimeBudgetExpired":
                        break
                    if event["method"] == "Inspector.targetCrashed":
                        raise RuntimeError("the page's renderer crashed")
                    _console_line(event, console)
                dom = send("Runtime.evaluate", {"expression": "document.documentElement.outerHTML",
                                                "returnByValue": True})["result"]["value"]  # type: ignore[index]
                while not events.empty():                       # type: ignore[attr-defined]
                    event = events.get()                        # type: ignore[attr-defined]
                    if event is not None:
                        _console_line(event, console)
                out.append((str(dom), "".join(f"{line}\n" for line in console)))
                console = []
        except BaseException:
            with self._lock:
                self._tabs.pop(context, None)
                self._events.pop(session, None)
            self._quietly("Target.closeTarget", {"targetId": target})
            raise
        with self._lock:
            self._tabs[context] = (target, session)
        return out

    def _quietly(self, method: str, params: dict[str, object]) -> None:
        """Clean up after a failure (the failure is what the caller reports, not this command's)."""
        try:
            if self._ended is None:
                self.send(method, params, timeout=10)
        except RuntimeError:
            pass

    def close(self) -> None:
        """End the browser (politely, then by force) and every process it started; reap it."""
        import os
        import signal
        import time

        if self._closed:
            return
        self._closed = True
        if self._ended is None:
            try:
                self.send("Browser.close", timeout=10)
            except RuntimeError:
                pass
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline:      # exited? (without reaping it: its group id stays ours meanwhile)
            if os.waitid(os.P_PID, self.pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is not None:
                break
            time.sleep(0.05)
        try:
            os.killpg(self.pid, signal.SIGKILL)  # what is left of its process group (all of it, if it hung)
        except ProcessLookupError:
            pass
        os.waitpid(self.pid, 0)
        while _live_processes(self.pid) and time.monotonic() < deadline + 10:
            time.sleep(0.05)                     # SIGKILL is delivered, not yet acted upon
        os.close(self._out)
        self._reader.join(timeout=10)
        os.close(self._in)


def _live_processes(group: int) -> list[int]:
    """Processes of process group ``group`` that are still running (not zombies awaiting their reaper)."""
    live = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue                             # ended meanwhile
        if int(fields[2]) == group and fields[0] != "Z":
            live.append(int(stat.parent.name))
    return live


def _console_line(event: dict[str, object], out: list[str]) -> None:
    """Append the console message a DevTools event carries to ``out`` in Chromium's log form (:data:`CONSOLE`):
    ``[...:CONSOLE:line] "message", source: url (line)``, the message on one line (its line breaks as ``\\n``:
    Chromium's log breaks the line, and the parser missed such messages). A failed load is the browser's log
    entry ``Failed to load resource: net::ERR_...`` (which Chromium's log on stderr did not carry)."""
    p = event["params"]
    method = event["method"]
    if method == "Runtime.consoleAPICalled":
        words = [str(a.get("value", a.get("unserializableValue", a.get("description", a.get("type")))))
                 if a.get("type") != "boolean" else str(a.get("value")).lower() for a in p["args"]]
        frames = (p.get("stackTrace") or {}).get("callFrames") or [{}]
        level, text = p["type"], " ".join(words)
        url, line = frames[0].get("url", ""), frames[0].get("lineNumber", -1) + 1
    elif method == "Runtime.exceptionThrown":
        d = p["exceptionDetails"]
        text = d.get("text", "Uncaught")
        described = str((d.get("exception") or {}).get("description", "")).split("\n")[0]
        if described and described not in text:
            text = f"{text} {described}"
        level, url, line = "error", d.get("url", ""), d.get("lineNumber", -1) + 1
    elif method == "Log.entryAdded":
        e = p["entry"]
        level, text, url, line = e["level"], e["text"], e.get("url", ""), e.get("lineNumber", -1) + 1
    else:
        return
    text = str(text).replace("\\", "\\\\").replace("\n", "\\n")
    out.append(f"[devtools:{level}:CONSOLE:{line}] \"{text}\", source: {url} ({line})")


PROBE = (Path(__file__).parent / "overflow_probe.js").read_text(encoding="utf-8")


def render_with_probe(page: Path, width: int, browser: Chromium) -> tuple[str, str]:
    """The DOM (after MathJax) and the console (:meth:`Chromium.render`) of ``page`` in a ``width``-px viewport,
    with the overflow probe injected (it only measures, and records what it finds in attributes of ``<body>``,
    with the viewport's width it saw in ``data-fusion-viewport``)."""
    return render_widths_with_probe(page, (width,), browser)[0]


def render_widths_with_probe(page: Path, widths: tuple[int, ...], browser: Chromium) -> list[tuple[str, str]]:
    """:func:`render_with_probe` of one load of ``page`` at each of ``widths`` in turn
    (:meth:`Chromium.render_widths`): the probe measures again when the viewport is resized."""
    probe = page.with_name(page.stem + f".overflow-probe-{'-'.join(map(str, widths))}.html")
    probe.write_text(page.read_text(encoding="utf-8").replace("</body>", f"<script>{PROBE}</script></body>"),
                     encoding="utf-8")
    try:
        out = browser.render_widths(probe.as_uri(), widths)
    finally:
        probe.unlink()
    for width, (dom, _) in zip(widths, out):
        m = re.search(r'data-fusion-viewport="(\d+)"', dom)
        assert m and int(m[1]) == width, f"{page.name}: the probe did not see a {width}-px viewport"
    return out


def probe_found(dom: str, name: str, what: str = "overflow") -> list[dict[str, object]]:
    """What the probe recorded in a rendered DOM under ``data-fusion-<what>``: ``overflow`` (elements wider
    than the text column), ``figures`` (every output image: rendered and natural size, alt text, link),
    ``clipped-math`` (inline formulas cut off) or ``pvr-columns`` (key columns of published-vs-reproduced
    tables beyond the column's right edge)."""
    import html
    import json

    m = re.search(f'data-fusion-{what}="(?P<json>[^"]*)"', dom)
    assert m, f"{name}: the probe did not run (no data-fusion-{what})"
    return json.loads(html.unescape(m["json"]))


def overflow_found(dom: str, name: str) -> list[dict[str, object]]:
    """What the overflow probe recorded in a rendered DOM (elements wider than the text column)."""
    return probe_found(dom, name, "overflow")


def overflowing(page: Path, width: int, browser: Chromium) -> list[dict[str, object]]:
    """Elements of ``page`` wider than its text column in a ``width``-px window (Chromium)."""
    return overflow_found(render_with_probe(page, width, browser)[0], page.name)


# --------------------------------------------------------------------------- the book


#: The width of the rendering pass every page gets (the chapters get NARROW_WIDTHS too, the other pages 420 px).
WIDE = 1400


def sweep_jobs(site: Path) -> list[tuple[Path, tuple[int, ...]]]:
    """Every Chromium rendering the browser tests read, as (page, its widths): every page but the source listings
    at 1400 px (rendering and width checks), the chapters (every figure) also at 1280 and 420 px, every other
    page also at 420 px (maths, tables). A page loads once, at 1400 px, and is then resized to its narrower
    widths (:meth:`Chromium.render_widths`)."""
    pages = [p for p in _pages(site) if not _is_source_listing(site, p)]
    return [(p, (WIDE, *NARROW_WIDTHS) if p.parent.name == "notebooks" else (WIDE, 420)) for p in pages]


def sweep(site: Path, tmp: Path) -> dict[tuple[str, int], tuple[str, str]]:
    """Render every job of :func:`sweep_jobs` (one Chromium, two pages at a time): (page relative to ``site``,
    width) -> (DOM with the probe's findings, console). ``tests/conftest.py`` runs it in the background right
    after the book build, beside the unit tests and nbval, so the browser tests at the end of the run only read it."""
    jobs = sweep_jobs(site)
    with Chromium(tmp / "chromium") as browser:
        pool = ThreadPoolExecutor(max_workers=2)
        try:
            out = list(pool.map(lambda job: render_widths_with_probe(job[0], job[1], browser), jobs))
        finally:
            pool.shutdown(cancel_futures=True)          # a failed page: the jobs not started are dropped
    return {(str(p.relative_to(site)), w): (dom, err)
            for (p, widths), renderings in zip(jobs, out) for w, (dom, err) in zip(widths, renderings)}


def _swept(site: Path, tmp_path_factory: pytest.TempPathFactory) -> dict[tuple[str, int], tuple[str, str]]:
    """The sweep of this run: the background one (``conftest.swept_pages``) when the run started it, else here
    (the fixtures that read it run only where the ``site`` fixture found Chromium and the build)."""
    from conftest import swept_pages

    swept = swept_pages(site, lambda s: sweep(s, tmp_path_factory.mktemp("chromium")))
    assert swept is not None, "the Chromium sweep gave nothing although Chromium is installed and the book built"
    return swept


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


def _is_source_listing(site: Path, page: Path) -> bool:
    """A highlighted-source page of sphinx.ext.viewcode (``_modules/``)."""
    return page.relative_to(site).parts[0] == "_modules"


@pytest.fixture(scope="module")
def rendered(site: Path, tmp_path_factory: pytest.TempPathFactory) -> dict[Path, tuple[str, str]]:
    """Every page but the source listings rendered once by Chromium at 1400 px with the overflow probe:
    page -> (DOM, console).

    One pass serves both the rendering checks and the width check (each page used to be rendered twice).
    """
    swept = _swept(site, tmp_path_factory)
    return {site / rel: (dom, err) for (rel, width), (dom, err) in swept.items() if width == WIDE}


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_every_page_renders_cleanly(site: Path, rendered: dict[Path, tuple[str, str]]) -> None:
    pages = list(rendered)
    assert any(p.name == "01_optimal_fusion_set.html" for p in pages), "chapter pages missing from the build"
    problems: dict[str, list[str]] = {}
    ids_of: dict[Path, set[str]] = {}
    n_math = 0
    for path, (dom, console) in rendered.items():
        name = str(path.relative_to(site))
        assert "</html>" in dom, f"{name}: Chromium returned no DOM"
        page = parse_page(dom)
        n_math += len(page.math_roots)
        issues = [f"unrendered math: {t}" for t in unrendered_math(page)]
        issues += [f"{page.math_errors} MathJax error(s)"] if page.math_errors else []
        issues += [f"broken image: {s}" for s in broken_images(page, path)]
        issues += [f"broken link: {h}" for h in broken_links(page, path, ids_of)]
        issues += [f"console error: {e}" for e in console_errors(console, site)]
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
def test_verdicts_page_fits_a_phone(site: Path, narrow: dict[tuple[Path, int], str]) -> None:
    page = site / "book" / "verdicts.html"
    report = _overflow_lines(site, {page: overflow_found(narrow[page, 420], page.name)})
    assert not report, "\n".join(f"{k}: {v}" for k, v in report.items())


# --------------------------------------------------------------------------- figures, maths and tables at a
# laptop's and a phone's width (issue 28)

#: Widths of the figure checks: a 1280-px laptop, where the figures used to be squashed to 86-88 % of
#: their shape, and a 420-px phone (47-49 %).
NARROW_WIDTHS = (1280, 420)
#: Largest difference between a figure's rendered and natural aspect ratio.
ASPECT_TOLERANCE = 0.02
PATH_LIKE = re.compile(r"\.(png|svg|jpe?g|gif|pdf)\b|_images/|^\.{0,2}/|^[\w-]{32,}$", re.IGNORECASE)


def squashed(figures: list[dict[str, object]]) -> list[str]:
    """Figures whose rendered aspect ratio is off their bitmap's by more than :data:`ASPECT_TOLERANCE`."""
    bad = []
    for f in figures:
        nw, nh, w, h = (float(f[k]) for k in ("naturalWidth", "naturalHeight", "width", "height"))  # type: ignore[arg-type]
        if nw <= 0 or nh <= 0:
            continue                            # not loaded: broken images are another test's business
        ratio = (w / h) / (nw / nh) if h > 0 else 0.0
        if abs(ratio - 1.0) > ASPECT_TOLERANCE:
            bad.append(f"{f['src']} near #{f['near']}: {w:.0f}×{h:.0f} px shown, {ratio:.2f} of its shape")
    return bad


def bad_alt_texts(figures: list[dict[str, object]]) -> list[str]:
    """Figures without an alt text, or whose alt text is a file path rather than words."""
    bad = []
    for f in figures:
        alt = str(f.get("alt") or "").strip()
        if not alt or PATH_LIKE.search(alt) or len(alt.split()) < 3:
            bad.append(f"{f['src']} near #{f['near']}: alt {alt!r}")
    return bad


def not_full_size_on_tap(figures: list[dict[str, object]]) -> list[str]:
    """Figures shown smaller than drawn (their text below its drawn size, 9 pt or more) that do not link to
    their full-size bitmap. The PNGs hold twice the drawn pixels (style.use_book_style: retina)."""
    bad = []
    for f in figures:
        drawn = float(f["naturalWidth"]) / 2                      # type: ignore[arg-type]
        if float(f["width"]) >= drawn - 1:                       # type: ignore[arg-type]
            continue
        link = str(f.get("link") or "")
        if not link or link.split("/")[-1][:16] != f["src"]:
            bad.append(f"{f['src']} near #{f['near']}: shown at {float(f['width']) / drawn:.0%} "  # type: ignore[arg-type]
                       "of its drawn size, with no link to the full-size figure")
    return bad


@pytest.fixture(scope="module")
def chromium(tmp_path_factory: pytest.TempPathFactory):  # noqa: ANN201 - a generator fixture
    """One Chromium for this module's own renderings (a page rendered at one width, against the sweep's resize)."""
    with Chromium(tmp_path_factory.mktemp("chromium")) as browser:
        yield browser


@pytest.fixture(scope="module")
def narrow(site: Path, tmp_path_factory: pytest.TempPathFactory) -> dict[tuple[Path, int], str]:
    """The chapters (every figure of the book) at 1280 and 420 px, and every other rendered page at 420 px
    (inline maths, tables): (page, width) -> DOM with the probe's findings."""
    swept = _swept(site, tmp_path_factory)
    return {(site / rel, width): dom for (rel, width), (dom, _) in swept.items() if width != WIDE}


def _found(site: Path, narrow: dict[tuple[Path, int], str], what: str, width: int,
           check=lambda found: found) -> tuple[int, dict[str, list]]:  # type: ignore[no-untyped-def]
    seen, report = 0, {}
    for (page, w), dom in narrow.items():
        if w != width:
            continue
        found = probe_found(dom, page.name, what)
        seen += len(found)
        bad = check(found)
        if bad:
            report[str(page.relative_to(site))] = bad
    return seen, report


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
@pytest.mark.parametrize("width", NARROW_WIDTHS)
def test_figures_keep_their_shape(site: Path, narrow: dict[tuple[Path, int], str], width: int) -> None:
    """Every figure's rendered aspect ratio is within 2 % of its bitmap's, on a laptop and on a phone."""
    seen, report = _found(site, narrow, "figures", width, squashed)
    assert seen >= 30, f"only {seen} figures found at {width} px: the check would be vacuous"
    assert not report, "\n".join(f"{k}: {v}" for k, v in report.items())


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_figures_have_alt_text_in_words(site: Path, narrow: dict[tuple[Path, int], str]) -> None:
    """Every figure has an alt text of a few words, not its file path (a screen reader reads it out)."""
    seen, report = _found(site, narrow, "figures", 1280, bad_alt_texts)
    assert seen >= 30, f"only {seen} figures found: the check would be vacuous"
    assert not report, "\n".join(f"{k}: {v}" for k, v in report.items())


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_figures_alt_text_comes_from_the_code_that_drew_them(site: Path) -> None:
    """Every chapter figure's alt text is the description its notebook wrote into the PNG
    (book/_ext/fusion_figures.py marks it ``alt-from-figure``), not the caption's first sentence."""
    seen, other = 0, {}
    for page in sorted((site / "notebooks").glob("*.html")):
        imgs = re.findall(r"<figure\b[^>]*>\s*(?:<a\b[^>]*>\s*)?(<img\b[^>]*>)", page.read_text(encoding="utf-8"))
        seen += len(imgs)
        n = sum(not re.search(r'class="[^"]*\balt-from-figure\b', img) for img in imgs)
        if n:
            other[page.name] = f"{n} of {len(imgs)}"
    assert seen >= 30, f"only {seen} figures found: the check would be vacuous"
    assert not other, f"figures whose alt text is not the one their notebook drew: {other}"


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_figures_open_full_size_on_a_phone(site: Path, narrow: dict[tuple[Path, int], str]) -> None:
    """On a 420-px phone a figure is shown at about half its drawn size (its 9-pt text at about 5 pt): each
    must link to its full-size bitmap, a tap away."""
    seen, report = _found(site, narrow, "figures", 420, not_full_size_on_tap)
    assert seen >= 30, f"only {seen} figures found at 420 px: the check would be vacuous"
    assert not report, "\n".join(f"{k}: {v}" for k, v in report.items())


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_no_inline_formula_is_cut_off_on_a_phone(site: Path, narrow: dict[tuple[Path, int], str]) -> None:
    """At 420 px no inline formula reaches past the edge of a box that hides its overflow (it may scroll)."""
    _, report = _found(site, narrow, "clipped-math", 420)
    report = {k: [f"near #{f['near']}: {f['width']} px shown in {f['shown']} px ({f['text']!s:.40})" for f in v]
              for k, v in report.items()}
    assert not report, "\n".join(f"{k}: {v}" for k, v in report.items())


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_published_vs_reproduced_tables_fit_a_phone(site: Path, narrow: dict[tuple[Path, int], str]) -> None:
    """At 420 px the published and reproduced columns of every published-vs-reproduced table are on screen
    (their secondary columns are hidden: book/_assets/fusion.js)."""
    _, report = _found(site, narrow, "pvr-columns", 420)
    assert not report, "\n".join(f"{k}: {v}" for k, v in report.items())


#: A chapter with figures, published-vs-reproduced tables and inline maths, loaded afresh at a phone's width to
#: compare with its sweep rendering there (loaded at 1400 px, then resized: :func:`sweep_jobs`).
RESIZE_WITNESS = "notebooks/05_covariance_intersection.html"


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_a_resized_page_measures_as_a_page_loaded_at_that_width(site: Path, narrow: dict[tuple[Path, int], str],
                                                                 chromium: Chromium) -> None:
    """The sweep loads each page once, at 1400 px, and resizes it to its narrower widths: there the probe must
    find what it finds in the page loaded at that width (the book's width-dependent scripts, fusion.js, redo
    their work on a resize; a script that only looked at the width it loaded in would fail this)."""
    page = site / RESIZE_WITNESS
    fresh, _ = render_with_probe(page, 420, chromium)
    assert probe_found(fresh, page.name, "figures"), f"{RESIZE_WITNESS} has no figures: pick another witness"
    assert re.search(r'class="[^"]*\bfusion-pvr\b', fresh), f"{RESIZE_WITNESS} has no published-vs-reproduced table"
    for what in ("overflow", "figures", "clipped-math", "pvr-columns", "layout"):
        assert probe_found(narrow[page, 420], page.name, what) == probe_found(fresh, page.name, what), what


#: A laptop's first screen (CSS px): the introduction's findings must end within it at 1400 px.
FIRST_SCREEN = 900

#: Words a reader sees on the Verdicts page (closed details not counted), at most.
MAX_VERDICTS_WORDS = 10_000


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_intro_findings_fit_the_first_screen(site: Path, rendered: dict[Path, tuple[str, str]]) -> None:
    """A newcomer's one-minute read: at 1400 px the introduction's findings end within the first screen, one
    item per source, each with the source's main finding and our number ("Ours:" and a figure)."""
    from fusion.book.ledger import SOURCES

    page = site / "book" / "intro.html"
    layout = probe_found(rendered[page][0], page.name, "layout")
    f = layout["findings"]
    assert f is not None, "the introduction has no findings list (ul.findings)"
    assert f["bottom"] <= FIRST_SCREEN, f"the findings end {f['bottom']} px down (first screen: {FIRST_SCREEN} px)"
    assert len(f["items"]) == len(SOURCES)
    for item in f["items"]:
        if item.startswith("cannot be checked"):   # nothing to compute (R7, R9): the reason stands for our number
            assert re.search(r"Ours: \S", item), f"a finding that cannot be checked without its reason: {item[:80]}"
        else:
            assert re.search(r"Ours: .*\d", item), f"a finding without our number: {item[:80]}"


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on PATH: install Debian's `chromium` (.ci/run does)")
def test_verdicts_page_reads_in_under_ten_thousand_words(site: Path, rendered: dict[Path, tuple[str, str]]) -> None:
    """The Verdicts page is a table with details on demand: the words a reader sees stay under the limit."""
    page = site / "book" / "verdicts.html"
    words = probe_found(rendered[page][0], page.name, "layout")["words"]
    assert 1000 < words < MAX_VERDICTS_WORDS, f"the Verdicts page shows {words} words"
