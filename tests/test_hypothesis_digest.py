"""The conftest's cached hypothesis function digest is hypothesis's own, bit for bit (issue 37).

Derandomised hypothesis draws each test's examples from a seed made of this digest: an equal digest is the
same examples, so the cache changes the cost of the run and nothing it tests.
"""

from __future__ import annotations

import functools

import hypothesis.core
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.internal import reflection

import conftest


def _plain(x: int, *, y: float = 1.0) -> float:
    # a comment, which hypothesis leaves out of the digest
    return x + y


@given(st.integers())
def _wrapped(n: int) -> None:
    assert n == n


def _with_case(key: bytes):  # noqa: ANN202 - a fresh function carrying a parametrised case's digest
    def f(a: int) -> int:
        return a

    f._hypothesis_internal_add_digest = key
    return f


_EXECUTED: dict = {}
exec("def no_source(a, b=2):\n    return a * b\n", _EXECUTED)  # noqa: S102 - a function whose source cannot be read


CALLABLES = [_plain, _wrapped.hypothesis.inner_test, lambda v: v * 2, len, _EXECUTED["no_source"],
             functools.partial(_plain, 1), _with_case(b"tests/x.py::test[a]"), _with_case(b"tests/x.py::test[b]"),
             conftest.function_digest, str.upper]


@pytest.mark.parametrize("fn", CALLABLES, ids=lambda f: getattr(f, "__name__", type(f).__name__))
def test_the_cached_digest_is_hypothesiss(fn: object) -> None:
    expected = conftest._ORIGINAL_DIGEST(fn)
    assert conftest.function_digest(fn) == expected
    assert conftest.function_digest(fn) == expected          # from the cache


def test_each_parametrised_case_keeps_its_own_digest() -> None:
    """One function, the digest of its case read at every call: two cases, two digests, each hypothesis's."""
    f = _with_case(b"case 1")
    first = conftest.function_digest(f)
    f._hypothesis_internal_add_digest = b"case 2"
    second = conftest.function_digest(f)
    assert first != second and second == conftest._ORIGINAL_DIGEST(f)
    del f._hypothesis_internal_add_digest
    assert conftest.function_digest(f) == conftest._ORIGINAL_DIGEST(f) not in (first, second)


@pytest.mark.skipif(conftest.PLAIN_HYPOTHESIS, reason="FUSION_TEST_PLAIN_HYPOTHESIS: hypothesis as installed")
def test_hypothesis_calls_the_cached_digest() -> None:
    assert hypothesis.core.function_digest is conftest.function_digest
    assert reflection.function_digest is conftest.function_digest
    assert conftest._ORIGINAL_DIGEST is not conftest.function_digest
    assert conftest._ORIGINAL_DIGEST.__module__ == "hypothesis.internal.reflection"


class _Unhashable:
    __hash__ = None  # type: ignore[assignment]

    def __call__(self, a: int) -> int:
        return a


def test_an_unhashable_callable_takes_hypothesiss_path() -> None:
    fn = _Unhashable()
    assert conftest.function_digest(fn) == conftest._ORIGINAL_DIGEST(fn)


# --------------------------------------------------------------------------------------------
# the settings of a parametrised test: the same at every case (conftest.pytest_runtest_call)
# --------------------------------------------------------------------------------------------

_SEEN: list[tuple[int, int, bool, object, frozenset]] = []


@pytest.mark.parametrize("case", range(5))
@settings(max_examples=2)
@given(st.integers())
def test_a_parametrised_case_runs_under_its_tests_settings(case: int, n: int) -> None:
    current, depth = settings.default, 0      # inside a test, hypothesis's default is the test's settings
    s = current
    while s is not None:
        depth += 1
        s = s._fallback
    _SEEN.append((case, depth, current.max_examples, current.derandomize, current.database,
                  frozenset(current.suppress_health_check)))


@pytest.mark.skipif(conftest.PLAIN_HYPOTHESIS, reason="FUSION_TEST_PLAIN_HYPOTHESIS: hypothesis as installed")
def test_every_case_had_the_same_settings() -> None:
    """The chain of settings does not grow with the cases; each case had the test's values (its own max_examples,
    the profile's derandomisation, no database, the plugin's suppressed health check beside the profile's)."""
    from hypothesis import HealthCheck

    cases = {c for c, *_ in _SEEN}
    if cases != set(range(5)):
        pytest.skip("runs after the parametrised test above, in the same process")
    assert len({tuple(rest) for _, *rest in _SEEN}) == 1, _SEEN
    _, _, max_examples, derandomize, database, suppressed = _SEEN[0]
    assert max_examples == 2 and derandomize == settings.get_profile("fusion").derandomize and database is None
    assert {HealthCheck.differing_executors, HealthCheck.too_slow} <= suppressed


# ---------------------------------------------------------------------------------------------- the shared rewrite
def test_the_shared_rewrite_is_pytests_own(tmp_path, monkeypatch, pytestconfig) -> None:
    """``conftest.shared_rewrite``: the process that rewrites a test module stores it, the next one reads it back; both
    give pytest's own rewritten code (marshalled, byte for byte) and its source hash; a module outside ``tests/`` and a
    changed source are rewritten by pytest itself."""
    import marshal

    from _pytest.assertion import rewrite

    if conftest.PLAIN_REWRITE:
        pytest.skip("pytest's own rewriting (FUSION_TEST_PLAIN_REWRITE, or another pytest release)")
    assert rewrite._rewrite_test is conftest.shared_rewrite
    monkeypatch.setenv(conftest._REWRITE_DIR_ENV, str(tmp_path))
    fn = conftest.TESTS / "test_module_size.py"
    own_hash, own = conftest._ORIGINAL_REWRITE(fn, pytestconfig)
    first = conftest.shared_rewrite(fn, pytestconfig)                # rewritten here, stored
    stored = tmp_path / f"test_module_size.{conftest.rewrite_key(pytestconfig)}.pyc"
    assert stored.exists()
    second = conftest.shared_rewrite(fn, pytestconfig)               # read back
    for h, co in (first, second):
        assert h == own_hash and marshal.dumps(co) == marshal.dumps(own)
    # a stored module whose source changed is rewritten again (pytest's reader checks the source's hash)
    copy = tmp_path / "elsewhere" / "test_copy.py"
    copy.parent.mkdir()
    copy.write_text(fn.read_text(encoding="utf-8") + "\nassert True\n", encoding="utf-8")
    (tmp_path / "test_copy.pyc").write_bytes(stored.read_bytes())
    assert rewrite._read_pyc(copy, tmp_path / "test_copy.pyc") is None
    outside = conftest.shared_rewrite(copy, pytestconfig)             # not under tests/: pytest's own, not stored
    assert marshal.dumps(outside[1]) == marshal.dumps(conftest._ORIGINAL_REWRITE(copy, pytestconfig)[1])


def _foreign_pyc(path, fn) -> None:
    """A pyc valid for ``fn``'s current source (pytest's header and hash) holding other code."""
    import importlib.util

    from _pytest.assertion import rewrite

    with open(path, "wb") as fp:
        rewrite._write_pyc_fp(fp, importlib.util.source_hash(fn.read_bytes()), compile("FOREIGN = 1", str(fn), "exec"))


def test_the_shared_rewrite_reads_only_its_own_tag(tmp_path, monkeypatch, pytestconfig) -> None:
    """fix46 (review 18, points 3-4): a module stored under another pytest's tag, or another rewrite option, or the
    earlier name without a tag, is never read: each is rewritten by pytest itself (under the pass hook, with it)."""
    import marshal

    if conftest.PLAIN_REWRITE:
        pytest.skip("pytest's own rewriting (FUSION_TEST_PLAIN_REWRITE, or another pytest release)")
    monkeypatch.setenv(conftest._REWRITE_DIR_ENV, str(tmp_path))
    fn = conftest.TESTS / "test_module_size.py"
    key = conftest.rewrite_key(pytestconfig)
    for name in ("test_module_size.pyc", "test_module_size.cpython-311-pytest-8.3.5-passhook0.pyc",
                 f"test_module_size.{key.replace('passhook0', 'passhook1')}.pyc"):
        _foreign_pyc(tmp_path / name, fn)
    got = conftest.shared_rewrite(fn, pytestconfig)[1]
    assert "FOREIGN" not in got.co_names
    assert marshal.dumps(got) == marshal.dumps(conftest._ORIGINAL_REWRITE(fn, pytestconfig)[1])
    # the pass hook on: another key, its own rewrite (not the one stored without it)
    getini = pytestconfig.getini
    monkeypatch.setattr(pytestconfig, "getini", lambda name: True if name == "enable_assertion_pass_hook"
                        else getini(name))
    (tmp_path / f"test_module_size.{key.replace('passhook0', 'passhook1')}.pyc").unlink()
    hooked = conftest.shared_rewrite(fn, pytestconfig)[1]
    assert marshal.dumps(hooked) == marshal.dumps(conftest._ORIGINAL_REWRITE(fn, pytestconfig)[1])
    assert marshal.dumps(hooked) != marshal.dumps(got)


def test_the_shared_rewrite_needs_pytests_contract() -> None:
    """fix46: pytest 8's helpers (a stat of the source, not its hash) are not the contract: pytest's own path."""
    import types

    from _pytest.assertion import rewrite

    assert conftest.rewrite_contract(rewrite)
    eight = types.SimpleNamespace(PYTEST_TAG="cpython-311-pytest-8.3.5", _rewrite_test=lambda fn, config: None,
                                  _read_pyc=lambda source, pyc, trace=None: None,
                                  _write_pyc_fp=lambda fp, source_stat, co: None)
    assert not conftest.rewrite_contract(eight)
    assert not conftest.rewrite_contract(types.SimpleNamespace(PYTEST_TAG="x"))
    nine = {**vars(eight), "_write_pyc_fp": lambda fp, source_hash, co: None}
    assert conftest.rewrite_contract(types.SimpleNamespace(**nine))
