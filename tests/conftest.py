"""Shared test configuration: deterministic hypothesis runs, and the book built once per session."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, settings

ROOT = Path(__file__).resolve().parents[1]

# Derandomised: the same examples on every machine and every run, so a failure is
# reproducible and CI is not flaky. No deadline: CI machines vary in speed. 100 examples per
# property (hypothesis's default; 200 cost about 30 CPU-seconds of `make test`'s budget).
settings.register_profile(
    "fusion", derandomize=True, deadline=None, max_examples=100,
    suppress_health_check=[HealthCheck.too_slow],
)
# `HYPOTHESIS_PROFILE=explore pytest ...` for an occasional run that draws new examples (random, 1000 per property
# unless a test sets its own count); a failure it finds is printed with its seed and replays in that run.
settings.register_profile(
    "explore", parent=settings.get_profile("fusion"), derandomize=False, max_examples=1000,
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "fusion"))


def build_book(out: Path) -> subprocess.CompletedProcess[str]:
    """Build the HTML book into ``out`` from the committed notebook outputs (no re-execution).

    Warnings are errors (``-W``) and every cross-reference must resolve (``-n``, nitpicky).
    nbval proves that the committed outputs still follow from the code, so building from them
    checks the book that ``make book`` would build, without executing every notebook twice.
    """
    config = yaml.safe_load((ROOT / "_config.yml").read_text(encoding="utf-8"))
    config.setdefault("execute", {})["execute_notebooks"] = "off"
    # paths in the config are relative to its folder: make them absolute for the copy
    config["bibtex_bibfiles"] = [str(ROOT / b) for b in config.get("bibtex_bibfiles", [])]
    sphinx = config.setdefault("sphinx", {})
    sphinx["local_extensions"] = {k: str(ROOT / v) for k, v in sphinx.get("local_extensions", {}).items()}
    conf = sphinx.setdefault("config", {})
    conf["html_static_path"] = [str(ROOT / p) for p in conf.get("html_static_path", [])]
    config_path = out / "_config.yml"
    config_path.write_text(yaml.safe_dump(config, allow_unicode=True), encoding="utf-8")
    jb = Path(sys.executable).with_name("jupyter-book")
    return subprocess.run(
        [str(jb), "build", str(ROOT), "--config", str(config_path), "--path-output", str(out),
         "--builder", "html", "-W", "-n", "--keep-going"],
        capture_output=True, text=True, timeout=900,
    )


#: Environment variable naming the directory where this run's book is built (set by the controller).
_BOOK_DIR_ENV = "FUSION_TEST_BOOK_DIR"
_BOOK_USERS = ("test_book_build.py", "test_browser.py")
_BUILD_KEY = pytest.StashKey[tuple]()


def _build_into(root: Path) -> None:
    """Build the book into ``root/book`` under ``root/book-build.lock`` unless a record of a build exists."""
    import fcntl
    import json

    out, record = root / "book", root / "book-build.json"
    with open(root / "book-build.lock", "w", encoding="utf-8") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not record.exists():
            out.mkdir(exist_ok=True)
            proc = build_book(out)
            record.write_text(json.dumps({"returncode": proc.returncode, "stdout": proc.stdout[-6000:],
                                          "stderr": proc.stderr[-6000:]}), encoding="utf-8")


def _run_needs_the_book(config: pytest.Config) -> bool:
    """Whether this run collects the book tests: the default test paths, or an argument naming them."""
    paths = [str(a).split("::")[0].rstrip("/") for a in config.args]
    if not paths or paths == [str(config.rootpath)]:
        return True
    return any(p.endswith(("tests", *_BOOK_USERS)) for p in paths)


def pytest_configure(config: pytest.Config) -> None:
    """In the controlling process, start building the book at once, in a background thread.

    ``make test`` runs pytest on two workers (pytest-xdist). The book build (a subprocess of about a
    minute) used to start only when a book test was reached, and a worker that reached the other book
    test then waited for it, idle. Started here, the build runs beside the unit tests and nbval from the
    first second, and the book tests, wherever they land, only wait for what is left of it.
    """
    import os
    import tempfile
    import threading

    if os.environ.get("PYTEST_XDIST_WORKER") or os.environ.get(_BOOK_DIR_ENV) or not _run_needs_the_book(config):
        return
    root = Path(tempfile.mkdtemp(prefix="fusion-book-test-"))
    os.environ[_BOOK_DIR_ENV] = str(root)          # inherited by the xdist workers started after this hook
    thread = threading.Thread(target=_build_into, args=(root,), name="book-build", daemon=True)
    thread.start()
    config.stash[_BUILD_KEY] = (thread, root)
    # (a worker that asks before the thread holds the lock builds the book itself; the thread then finds
    # the record and does nothing: one build either way)


def pytest_unconfigure(config: pytest.Config) -> None:
    """Wait for the background build (a run may end first) and remove its directory."""
    import shutil

    started = config.stash.get(_BUILD_KEY, None)
    if started is not None:
        thread, root = started
        thread.join()
        shutil.rmtree(root, ignore_errors=True)


@pytest.fixture(scope="session")
def book_html(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The HTML book, built once per test run (tests/test_book_build.py, tests/test_browser.py).

    ``make test`` runs pytest on every core (pytest-xdist, ``--dist loadscope``: a notebook's cells
    stay together in one worker). The controller starts the build in the background when the run
    begins (:func:`pytest_configure`); the book tests wait for it under a file lock. A run that did not
    start it (e.g. one test file named with ``::``) builds it here, once, shared by the workers.
    """
    import json
    import os

    if os.environ.get(_BOOK_DIR_ENV):
        root = Path(os.environ[_BOOK_DIR_ENV])
    else:
        root = tmp_path_factory.getbasetemp()
        if os.environ.get("PYTEST_XDIST_WORKER"):
            root = root.parent                      # shared by every worker of this run
    _build_into(root)          # waits for a build in progress; builds only if none has been recorded
    result = json.loads((root / "book-build.json").read_text(encoding="utf-8"))
    assert result["returncode"] == 0, f"book build failed:\n{result['stdout']}\n{result['stderr']}"
    return root / "book" / "_build" / "html"
