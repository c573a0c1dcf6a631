"""Shared test configuration: deterministic hypothesis runs, and the book built once per session."""

from __future__ import annotations

import hashlib
import inspect
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, settings
import hypothesis.core as hypothesis_core
from hypothesis.internal import reflection as hypothesis_reflection
from _pytest.assertion import rewrite as assertion_rewrite

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


# --------------------------------------------------------------------------------------------
# hypothesis's function digest, its source part computed once per test function (issue 37)
# --------------------------------------------------------------------------------------------

_ORIGINAL_DIGEST = hypothesis_reflection.function_digest
_CLEAN_SOURCES: dict[object, bytes] = {}
_NO_ADD = object()


def function_digest(function: object) -> bytes:
    """hypothesis's ``function_digest(function)``, bit for bit, with the cleaned source of ``function`` computed once.

    Derandomised, hypothesis seeds each test from this digest, and keys its run by it: two calls per parametrised
    case, each reading the test's source with ``inspect.getsource`` and cleaning it with the tokenizer and the
    parser (about 10 ms). The bad-input property files run about 5,000 parametrised cases of some 60 functions:
    that was about a fifth of their CPU. The source of a function does not change during a run, so it is cleaned
    once per function; the signature and the per-case digest (``_hypothesis_internal_add_digest``, the case's
    node id) are read at every call, as hypothesis does. ``tests/test_hypothesis_digest.py`` checks the parity.
    """
    try:
        source = _CLEAN_SOURCES.get(function)
    except TypeError:                              # an unhashable callable: hypothesis's own path
        return _ORIGINAL_DIGEST(function)
    if source is None:
        try:
            source = hypothesis_reflection._clean_source(inspect.getsource(function))
        except (OSError, TypeError):
            try:
                source = function.__name__.encode()
            except AttributeError:
                source = b""
        _CLEAN_SOURCES[function] = source
    hasher = hashlib.sha384()
    hasher.update(source)
    try:
        hasher.update(repr(hypothesis_reflection.get_signature(function)).encode())
    except Exception:  # noqa: BLE001 - as hypothesis: a callable without a signature adds nothing
        pass
    add = getattr(function, "_hypothesis_internal_add_digest", _NO_ADD)
    if add is not _NO_ADD:
        hasher.update(add)
    return hasher.digest()


#: ``FUSION_TEST_PLAIN_HYPOTHESIS=1``: hypothesis as installed, without the two savings of this section
#: (``benchmarks/bench_unit_tests.py`` runs both sides).
#: Also on when the installed hypothesis lacks the private helpers the first saving reads (another release than the
#: lock's): then hypothesis runs as installed.
PLAIN_HYPOTHESIS = (bool(os.environ.get("FUSION_TEST_PLAIN_HYPOTHESIS"))
                    or not all(hasattr(hypothesis_reflection, n) for n in ("_clean_source", "get_signature",
                                                                           "function_digest"))
                    or not hasattr(hypothesis_core, "function_digest"))
if not PLAIN_HYPOTHESIS:
    hypothesis_reflection.function_digest = function_digest
    hypothesis_core.function_digest = function_digest

# --------------------------------------------------------------------------------------------
# assertion rewriting: each test module rewritten once per run, not once per worker
# --------------------------------------------------------------------------------------------

#: Environment variable naming this run's directory of rewritten test modules (set by the controller).
_REWRITE_DIR_ENV = "FUSION_TEST_REWRITE_DIR"
_REWRITE_DIR_KEY = pytest.StashKey[Path]()
TESTS = ROOT / "tests"
#: pytest's own function (kept on its module: a second import of this file must not wrap the wrapper)
_ORIGINAL_REWRITE = getattr(assertion_rewrite, "_fusion_original_rewrite", getattr(assertion_rewrite, "_rewrite_test", None))


def shared_rewrite(fn: Path, config: pytest.Config) -> tuple[bytes, object]:
    """pytest's ``_rewrite_test(fn, config)`` of a test module of ``tests/``, computed by one process of the run.

    Every xdist worker collects every test module, and pytest rewrites each module's asserts (parse, rewrite,
    compile: about 9 CPU-s for ``tests/``) in each worker: its own cache of rewritten modules (``__pycache__``) is
    not written under ``PYTHONDONTWRITEBYTECODE``, and in a fresh clone both workers miss it at the same time. Here
    the first process to reach a module rewrites it under a file lock and stores the code in pytest's own format
    (its ``_write_pyc_fp``); the others read it back with pytest's own reader (``_read_pyc``: checked against the
    hash of the current source, else rewritten again). The code is the same (``marshal``, as pytest's cache):
    every assert is rewritten as before. ``tests/test_hypothesis_digest.py`` checks the parity. Each stored file is
    named by :func:`rewrite_key` (pytest's release and the options that change the rewrite), so a file another pytest
    or another setting wrote is never read.
    """
    root = os.environ.get(_REWRITE_DIR_ENV)
    if not root or Path(fn).parent != TESTS:
        return _ORIGINAL_REWRITE(fn, config)
    import fcntl
    import importlib.util

    fn = Path(fn)
    pyc = Path(root) / f"{fn.name[:-3]}.{rewrite_key(config)}.pyc"
    try:
        lock = open(Path(root) / (fn.name + ".lock"), "w", encoding="utf-8")  # noqa: SIM115 - closed below
    except OSError:          # the run's directory is gone (a run that outlived its controller): rewrite here
        return _ORIGINAL_REWRITE(fn, config)
    with lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        co = assertion_rewrite._read_pyc(fn, pyc)
        if co is not None:
            return importlib.util.source_hash(fn.read_bytes()), co
        source_hash, co = _ORIGINAL_REWRITE(fn, config)
        part = pyc.with_name(f"{pyc.name}.{os.getpid()}")
        try:
            with open(part, "wb") as fp:
                assertion_rewrite._write_pyc_fp(fp, source_hash, co)
            os.replace(part, pyc)
        except OSError:      # not stored: the next process rewrites it too
            pass
        return source_hash, co


def rewrite_key(config: pytest.Config) -> str:
    """The name under which :func:`shared_rewrite` stores a rewritten module: pytest's ``PYTEST_TAG`` (the Python
    cache tag and pytest's version, as pytest's own cache) and the ini options the rewriter reads
    (``enable_assertion_pass_hook`` adds code to every assert)."""
    return f"{assertion_rewrite.PYTEST_TAG}-passhook{int(bool(config.getini('enable_assertion_pass_hook')))}"


def rewrite_contract(module: object) -> bool:
    """Whether ``module``'s private rewriting helpers have the contract :func:`shared_rewrite` relies on (pytest 9's):
    ``_rewrite_test(fn, config)`` returning the source's hash, ``_write_pyc_fp(fp, source_hash, co)`` and
    ``_read_pyc(source, pyc, ...)`` checking that hash, and a ``PYTEST_TAG``. pytest 8 (allowed by pyproject) passes a
    stat of the source instead (``_write_pyc_fp(fp, source_stat, co)``): any other contract is pytest's own path."""
    def params(name: str) -> list[str]:
        return list(inspect.signature(getattr(module, name)).parameters)
    try:
        return (params("_rewrite_test") == ["fn", "config"] and params("_write_pyc_fp") == ["fp", "source_hash", "co"]
                and params("_read_pyc")[:2] == ["source", "pyc"]
                and isinstance(getattr(module, "PYTEST_TAG", None), str))
    except (AttributeError, TypeError, ValueError):   # a helper missing, or not a function with a signature
        return False


#: Also off (pytest's own rewriting) when the installed pytest's private helpers have another contract
#: (:func:`rewrite_contract`).
PLAIN_REWRITE = bool(os.environ.get("FUSION_TEST_PLAIN_REWRITE")) or not rewrite_contract(assertion_rewrite)
if not PLAIN_REWRITE:
    assertion_rewrite._fusion_original_rewrite = _ORIGINAL_REWRITE
    assertion_rewrite._rewrite_test = shared_rewrite


#: Each hypothesis test function's own settings (its ``@settings``, or the profile), by function.
_OWN_SETTINGS: dict[object, object] = {}


@pytest.hookimpl(hookwrapper=True, tryfirst=True)
def pytest_runtest_call(item: pytest.Item):  # noqa: ANN201 - hook wrapper
    """Give a parametrised hypothesis test its own settings back before each case (issue 37).

    hypothesis's pytest plugin (``_hypothesis_pytestplugin.pytest_runtest_call``, run after this wrapper) replaces
    the settings of a parametrised test by a child of them that suppresses one health check, at every case: the
    chain of settings grew by one per case, and hypothesis walks it to the root for the example database (``None``
    here, derandomised, so never cached) several times per case: about 6 % of the bad-input property files' CPU,
    growing with the number of cases. Reset here, the plugin makes the same child of the same settings at every case
    (the same values: ``tests/test_hypothesis_digest.py``).
    """
    fn = getattr(item, "obj", None)
    fn = getattr(fn, "__func__", fn)
    own = getattr(fn, "_hypothesis_internal_use_settings", None)
    if own is not None and not PLAIN_HYPOTHESIS:
        try:
            fn._hypothesis_internal_use_settings = _OWN_SETTINGS.setdefault(fn, own)
        except TypeError:  # an unhashable test object: left to hypothesis
            pass
    yield


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
    return subprocess.run(
        [sys.executable, str(ROOT / "tools" / "build_book.py"), str(ROOT), "--config", str(config_path), "--path-output", str(out),
         "--builder", "html", "-W", "-n", "--keep-going"],
        capture_output=True, text=True, timeout=900,
    )


#: Environment variable naming the directory where this run's book is built (set by the controller).
_BOOK_DIR_ENV = "FUSION_TEST_BOOK_DIR"
_BOOK_USERS = ("test_book_build.py", "test_browser.py", "test_backlinks.py", "test_book_listings.py")
_BUILD_KEY = pytest.StashKey[tuple]()
#: Environment variable of the run's shared study cache (:data:`fusion.book.study_cache.ENV`), set by the controller.
_STUDY_CACHE_ENV = "FUSION_STUDY_CACHE"
_STUDY_CACHE_KEY = pytest.StashKey[Path]()


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


def _build_then_sweep(root: Path, sweep: bool) -> None:
    """The background work of a run: the book build, then (``sweep``) every page rendered in Chromium."""
    _build_into(root)
    if sweep:
        try:
            swept_pages(root / "book" / "_build" / "html", _background_sweep)
        except Exception:  # noqa: BLE001 - recorded by swept_pages: the browser tests fail with its message
            pass


def _background_sweep(site: Path) -> dict[tuple[str, int], tuple[str, str]] | None:
    """``tests/test_browser.py``'s :func:`sweep` of ``site`` when the build succeeded and Chromium is installed."""
    import importlib.util
    import json

    build = json.loads((site.parents[2] / "book-build.json").read_text(encoding="utf-8"))
    spec = importlib.util.spec_from_file_location("fusion_browser_sweep", Path(__file__).with_name("test_browser.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)  # type: ignore[union-attr]
    if build["returncode"] != 0 or module.CHROMIUM is None:
        return None
    return module.sweep(site, site.parents[2] / "chromium")


def swept_pages(site: Path, compute) -> dict[tuple[str, int], tuple[str, str]] | None:  # noqa: ANN001
    """The Chromium sweep of this run's book, computed once under ``chromium.lock`` by whoever comes first.

    The controller's background thread starts it as soon as the book is built, so the renderings (one Chromium,
    two pages at a time) run beside nbval instead of after it with one core idle; a browser test that gets there
    first computes it itself (``compute(site)``) and the thread then finds the record. Returns ``None`` when
    ``site`` is not this run's shared book or ``compute`` gives nothing (no Chromium, a failed build). A sweep
    that failed (a crashed or hung browser) is recorded too: every browser test then fails with its message at
    once, instead of rendering the book again.
    """
    import fcntl
    import json
    import os

    shared = os.environ.get(_BOOK_DIR_ENV)
    if not shared or site != Path(shared) / "book" / "_build" / "html":
        return compute(site)
    root = Path(shared)
    record = root / "chromium.json"
    with open(root / "chromium.lock", "w", encoding="utf-8") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not record.exists():
            try:
                swept = compute(site)
            except Exception as exc:
                record.write_text(json.dumps({"error": f"{type(exc).__name__}: {exc}"}), encoding="utf-8")
                raise
            entries = None if swept is None else [[rel, w, dom, err] for (rel, w), (dom, err) in swept.items()]
            record.write_text(json.dumps(entries), encoding="utf-8")
        entries = json.loads(record.read_text(encoding="utf-8"))
    if isinstance(entries, dict):
        raise RuntimeError(f"the Chromium sweep failed: {entries['error']}")
    return None if entries is None else {(rel, w): (dom, err) for rel, w, dom, err in entries}


def _run_needs_the_book(config: pytest.Config) -> bool:
    """Whether this run collects the book tests: the default test paths, or an argument naming them; not with
    ``--collect-only``, which runs no test (it built the book and swept it in Chromium: 58 CPU-s instead of 13)."""
    if config.getoption("collectonly", False):
        return False
    paths = [str(a).split("::")[0].rstrip("/") for a in config.args]
    if not paths or paths == [str(config.rootpath)]:
        return True
    return any(p.endswith(("tests", *_BOOK_USERS)) for p in paths)


def pytest_configure(config: pytest.Config) -> None:
    """In the controlling process, create the run's study cache, and start building the book at once, in a background thread.

    ``make test`` runs pytest on two workers (pytest-xdist). The book build (a subprocess of about a
    minute) used to start only when a book test was reached, and a worker that reached the other book
    test then waited for it, idle. Started here, the build runs beside the unit tests and nbval from the
    first second, and the book tests, wherever they land, only wait for what is left of it.
    """
    import os
    import tempfile
    import threading

    if not os.environ.get("PYTEST_XDIST_WORKER") and not os.environ.get(_STUDY_CACHE_ENV):
        # the run's shared study cache (fusion/book/study_cache.py), inherited by the workers and their notebook
        # kernels: a study the notebook and a unit test both need is computed once; removed when the run ends
        study_dir = Path(tempfile.mkdtemp(prefix="fusion-study-cache-"))
        os.environ[_STUDY_CACHE_ENV] = str(study_dir)
        config.stash[_STUDY_CACHE_KEY] = study_dir
    if not os.environ.get("PYTEST_XDIST_WORKER") and not os.environ.get(_REWRITE_DIR_ENV) and not PLAIN_REWRITE:
        # the run's rewritten test modules (:func:`shared_rewrite`), inherited by the workers; removed when it ends
        rewrite_dir = Path(tempfile.mkdtemp(prefix="fusion-test-rewrite-"))
        os.environ[_REWRITE_DIR_ENV] = str(rewrite_dir)
        config.stash[_REWRITE_DIR_KEY] = rewrite_dir
    if os.environ.get("PYTEST_XDIST_WORKER") or os.environ.get(_BOOK_DIR_ENV) or not _run_needs_the_book(config):
        return
    if os.environ.get("FUSION_TEST_COSTS"):   # recording costs: the build's CPU is the first book test's
        return
    root = Path(tempfile.mkdtemp(prefix="fusion-book-test-"))
    os.environ[_BOOK_DIR_ENV] = str(root)          # inherited by the xdist workers started after this hook
    paths = [str(a).split("::")[0].rstrip("/") for a in config.args]
    sweep = not paths or paths == [str(config.rootpath)] or any(p.endswith(("tests", "test_browser.py")) for p in paths)
    thread = threading.Thread(target=_build_then_sweep, args=(root, sweep), name="book-build", daemon=True)
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
    rewrite_dir = config.stash.get(_REWRITE_DIR_KEY, None)
    if rewrite_dir is not None:
        os.environ.pop(_REWRITE_DIR_ENV, None)
        shutil.rmtree(rewrite_dir, ignore_errors=True)
    study_dir = config.stash.get(_STUDY_CACHE_KEY, None)
    if study_dir is not None:
        os.environ.pop(_STUDY_CACHE_ENV, None)
        shutil.rmtree(study_dir, ignore_errors=True)


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


# --------------------------------------------------------------------------------------------
# scheduling: the longest work units first (issue 37)
# --------------------------------------------------------------------------------------------

#: CPU-seconds of each xdist work unit (a test module, or a notebook under nbval: its kernel's CPU
#: included), recorded by ``FUSION_TEST_COSTS=PATH python -m pytest -n 0`` (see :func:`pytest_runtest_protocol`).
COSTS_FILE = ROOT / "tests" / "data" / "scope_costs.json"


def scope_of(nodeid: str) -> str:
    """The work unit of ``--dist loadscope`` holding ``nodeid`` (pytest-xdist's own split: the module or notebook)."""
    return nodeid.rsplit("::", 1)[0]


#: Work units that read studies another unit computes, through the run's shared study cache
#: (fusion/book/study_cache.py): reader -> the unit that computes them (found with ``FUSION_STUDY_CACHE_LOG``).
#: :func:`schedule_order` queues a reader after its producer; the recorded cost of ``test_ci_book_chapter.py`` and
#: of chapter 03's appendix is the one with the studies already stored, so the longest-first rule puts them later
#: still, and the studies are usually there when they start (a reader that comes first computes them: no loss).
STUDY_READERS = {
    "tests/test_ci_book_chapter.py": "notebooks/05_covariance_intersection.ipynb",          # the ledger studies
    "notebooks/06_chernoff_fusion_appendix.ipynb": "notebooks/06_chernoff_fusion.ipynb",   # the designed networks
    "notebooks/03_lecture_wavelets_appendix.ipynb": "notebooks/03_lecture_wavelets.ipynb",  # the chapter's studies
    "tests/test_lecture_chapter.py": "notebooks/02_lecture_weighting.ipynb",               # the chapter's studies
}


def schedule_order(scopes: list[str], costs: dict[str, float], last: set[str] = frozenset(),
                   after: dict[str, str] | None = None) -> list[str]:
    """The work units, longest recorded cost first; those in ``last`` (they wait for the book build) at the end.

    A unit of ``after`` (default :data:`STUDY_READERS`) that would come before the unit it reads from is moved to
    just after it.

    With two workers, the run ends when the last unit ends: a long unit started late (the chapter 06
    notebook, about a third of a worker's load) leaves the other core idle at the end. Longest first
    (the classic LPT rule) bounds that tail by the shortest units. A unit without a record (a new test
    file) goes after the recorded ones, in collection order; the order is stable and the same on every
    worker, as xdist requires.
    """
    def key(item: tuple[int, str]) -> tuple[bool, float, int]:
        i, scope = item
        return (scope in last, -costs.get(scope, 0.0), i)

    order = [s for _, s in sorted(enumerate(scopes), key=key)]
    for reader, producer in (STUDY_READERS if after is None else after).items():
        if reader in order and producer in order and order.index(reader) < order.index(producer):
            order.remove(reader)
            order.insert(order.index(producer) + 1, reader)
    return order


@pytest.hookimpl(hookwrapper=True)
def pytest_collection(session: pytest.Session):  # noqa: ANN201 - hook wrapper
    """Collect with the cyclic garbage collector off, then collect once and freeze what collection built (speed66b).

    Collection imports every test module and builds the registries, parametrisations and items: the heap grows
    from nothing to millions of objects, and CPython ran a full collection each time it had grown by a quarter (24
    of them, 7.8 of a collection's 26 CPU-s, measured with ``gc.callbacks`` on a loaded machine), in every worker.
    Here one ``gc.collect()`` at its end frees collection's garbage cycles, and ``gc.freeze()`` moves the objects
    that remain (modules, registries, items: alive for the whole run) out of the collector's generations, so the
    full collections during the tests scan only what the tests build (one cost about 1 CPU-s late in a worker).
    The tests run with the collector on, as before; nothing is freed that was freed before, except cycles of
    frozen objects that become garbage during the run (kept until the process ends).
    """
    import gc

    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.collect()
            gc.freeze()
            gc.enable()


def pytest_collection_modifyitems(session: pytest.Session, config: pytest.Config, items: list[pytest.Item]) -> None:
    """Order the items by :func:`schedule_order` of their work units (each unit's items keep their order).

    ``--dist loadscope`` hands out the units in the order their first items were collected (with
    ``--no-loadscope-reorder``, set in ``pyproject.toml``; xdist's default sorts them by their number of
    tests, which put the chapter 06 notebook in the middle of the run). The units with a test of the
    built book (fixture :func:`book_html`) go last: by then the background build is done, and no worker
    waits for it.
    """
    try:
        costs = json.loads(COSTS_FILE.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        costs = {}
    units: dict[str, list[pytest.Item]] = {}
    for item in items:
        units.setdefault(scope_of(item.nodeid), []).append(item)
    waits = {s for s, its in units.items() if any("book_html" in getattr(i, "fixturenames", ()) for i in its)}
    items[:] = [item for scope in schedule_order(list(units), costs, waits) for item in units[scope]]


_COSTS: dict[str, float] = {}


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item: pytest.Item, nextitem: pytest.Item | None):  # noqa: ANN201 - hook wrapper
    """With ``FUSION_TEST_COSTS=PATH``, record each work unit's CPU-seconds (its own and its child processes') into PATH.

    A child's CPU counts once it has ended (``RUSAGE_CHILDREN``): a notebook's kernel when nbval shuts it down
    after the notebook's last cell, a browser when its test ends. (The background book build is not started
    while recording: the first book test builds the book.)
    """
    if not os.environ.get("FUSION_TEST_COSTS"):
        yield
        return
    before = _cpu_now()
    yield
    scope = scope_of(item.nodeid)
    _COSTS[scope] = _COSTS.get(scope, 0.0) + _cpu_now() - before


def _cpu_now() -> float:
    """CPU-seconds of this process and of its ended child processes."""
    import resource

    own, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


def pytest_sessionfinish(session: pytest.Session) -> None:
    """Write the recorded costs (``FUSION_TEST_COSTS``), rounded to a tenth of a second, longest first."""
    path = os.environ.get("FUSION_TEST_COSTS")
    if path and _COSTS and not os.environ.get("PYTEST_XDIST_WORKER"):
        ordered = dict(sorted(((k, round(v, 1)) for k, v in _COSTS.items()), key=lambda kv: -kv[1]))
        Path(path).write_text(json.dumps(ordered, indent=1) + "\n", encoding="utf-8")
