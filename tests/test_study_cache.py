"""The per-run shared study cache (fusion/book/study_cache.py, issue 37)."""

from __future__ import annotations

import dataclasses
import json
import os
import pickle
import subprocess
import sys
import textwrap
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

from fusion.book import study_cache as sc
from _helpers import parsed

ROOT = Path(__file__).resolve().parents[1]


def test_a_cached_study_equals_the_uncached_one_bitwise(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Chapter 06's Gaussian checks (a cheap seeded study): computed, stored, and loaded by a fresh process are bitwise equal."""
    from fusion.book.chapters.chernoff import studies

    monkeypatch.delenv(sc.ENV, raising=False)
    plain = studies.checks_study.__wrapped__(2017)            # no cache at all
    monkeypatch.setenv(sc.ENV, str(tmp_path))
    studies.checks_study.cache_clear()
    stored = studies.checks_study(2017)                        # computes and stores
    assert len(list(tmp_path.glob("*.pkl"))) == 1
    studies.checks_study.cache_clear()
    loaded = studies.checks_study(2017)                        # loads the stored copy
    studies.checks_study.cache_clear()
    assert loaded is not stored
    assert pickle.dumps(plain) == pickle.dumps(stored) == pickle.dumps(loaded)


def test_without_the_variable_nothing_is_written(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(sc.ENV, raising=False)
    calls = []

    @sc.study_cache(maxsize=2)
    def f(seed: int) -> float:
        calls.append(seed)
        return seed / 3

    assert f(1) == f(1) == 1 / 3 and calls == [1]            # the in-process cache, as lru_cache
    assert f.cache_info().hits == 1
    assert not list(tmp_path.iterdir())


def test_read_only_arrays_stay_read_only(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(sc.ENV, str(tmp_path))

    @sc.study_cache(maxsize=1)
    def f(n: int) -> tuple[np.ndarray, np.ndarray]:
        a = np.arange(float(n))
        b = a.copy()
        b.setflags(write=False)
        return a, b

    f(4)
    f.cache_clear()
    a, b = f(4)
    assert not b.flags.writeable                      # loaded read-only (numpy's pickling would restore it writeable)
    assert not a.flags.writeable                      # and every array of a cached result is made read-only
    assert np.array_equal(a, b)


@dataclasses.dataclass(frozen=True)
class _Scenario:
    frames: int = 30
    noise: float = 0.5
    readings: bool = False


def test_the_key_changes_with_each_argument_and_the_sources() -> None:
    """Every argument, its type, the function's name and the source digest enter the key; equal calls share one."""
    base = {"seed": 2017, "runs": 100, "key": "s23", "sc": _Scenario(), "flag": True}
    k = sc.study_key("m.f", base, digest="d")
    assert sc.study_key("m.f", dict(base), digest="d") == k
    variants = [dict(base, seed=2018), dict(base, runs=101), dict(base, key="s24"), dict(base, flag=False),
                dict(base, sc=_Scenario(frames=31)), dict(base, sc=_Scenario(noise=0.5000000000000001)),
                dict(base, sc=_Scenario(readings=True)), dict(base, runs=100.0), dict(base, seed=np.int32(2017))]
    keys = {sc.study_key("m.f", v, digest="d") for v in variants}
    assert len(keys) == len(variants) and k not in keys
    assert sc.study_key("m.g", base, digest="d") != k
    assert sc.study_key("m.f", base, digest="e") != k
    with pytest.raises(TypeError):
        sc.study_key("m.f", {"x": object()}, digest="d")


def test_study_key_names_a_bad_qualname_key_or_a_container_that_contains_itself() -> None:
    """bytes names and self-containing arguments are TypeErrors naming the argument; shared (acyclic) parts are fine."""
    with pytest.raises(TypeError, match="qualname"):
        sc.study_key(b"m.f", {"x": 1}, digest="d")
    with pytest.raises(TypeError, match="arguments"):
        sc.study_key("m.f", {b"x": 1}, digest="d")
    with pytest.raises(TypeError, match="arguments"):
        sc.study_key("m.f", [("x", 1)], digest="d")  # type: ignore[arg-type]
    d: dict = {"x": 1}
    d["x"] = d
    with pytest.raises(TypeError, match=r"arguments\['x'\].*contains itself"):
        sc.study_key("m.f", d, digest="d")
    loop: list = [1]
    loop.append(loop)
    with pytest.raises(TypeError, match=r"arguments\['a'\].*contains itself"):
        sc.study_key("m.f", {"a": (2, loop)}, digest="d")
    shared = [1.5, 2.5]
    assert sc.study_key("m.f", {"a": [shared, shared]}, digest="d") == sc.study_key(
        "m.f", {"a": [[1.5, 2.5], [1.5, 2.5]]}, digest="d")


def test_the_source_digest_follows_every_source_file(tmp_path: Path) -> None:
    pkg = tmp_path / "pkg"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "a.py").write_text("x = 1\n")
    (pkg / "sub" / "b.py").write_text("y = 2\n")
    d0 = sc._source_digest.__wrapped__(pkg)
    (pkg / "sub" / "b.py").write_text("y = 3\n")
    d1 = sc._source_digest.__wrapped__(pkg)
    (pkg / "sub" / "b.py").rename(pkg / "sub" / "c.py")
    d2 = sc._source_digest.__wrapped__(pkg)
    (pkg / "notes.txt").write_text("not a source")
    assert len({d0, d1, d2}) == 3 and sc._source_digest.__wrapped__(pkg) == d2


_SUMMED: list = []


@sc.study_cache(maxsize=4)
def _summed(seed: int, runs: int = 100) -> int:
    """Module-level: only a function its module holds under its name reaches the disk (fuzz 34a D2)."""
    _SUMMED.append((seed, runs))
    return seed + runs


def test_defaults_and_keywords_share_one_entry(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(sc.ENV, str(tmp_path))
    f, calls = _summed, _SUMMED
    f.cache_clear()
    calls.clear()
    assert f(1) == f(1, 100) == f(seed=1, runs=100) == 101
    assert calls == [(1, 100)]                                 # one computation
    f.cache_clear()
    assert f(seed=1) == 101 and calls == [(1, 100)]            # loaded from the disk
    assert len(list(tmp_path.glob("*.pkl"))) == 1


def test_unencodable_arguments_bypass_the_disk(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(sc.ENV, str(tmp_path))

    class Opaque:
        pass

    @sc.study_cache(maxsize=1)
    def f(x: object) -> int:
        return 1

    assert f(Opaque()) == 1
    assert not list(tmp_path.glob("*.pkl"))


# the racers load fusion/book/study_cache.py by its path: the module under test, without the imports of the
# ``fusion.book`` package (pandas, the ledger: about 2 CPU-seconds per process, the rest of the test is 1 s of sleep)
_RACER = textwrap.dedent("""
    import importlib.util, json, os, sys, time
    spec = importlib.util.spec_from_file_location("fusion.book.study_cache", sys.argv[2])
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import racing                          # a module's function: a script's (__main__) is kept in the process only

    print(json.dumps(racing.slow(7)))
""")
_RACING = textwrap.dedent("""
    import os, sys, time
    study_cache = sys.modules["fusion.book.study_cache"].study_cache   # the racer's, loaded by its path

    @study_cache(maxsize=1)
    def slow(seed: int) -> list:
        with open(sys.argv[1], "a") as fh:
            fh.write(f"{os.getpid()}\\n")
        time.sleep(1.0)
        return [seed, seed * 2]
""")


def test_two_processes_racing_compute_once(tmp_path: Path) -> None:
    """Two processes ask for one study at once: one computes it, the other waits and loads it."""
    script, marks, cache = tmp_path / "racer.py", tmp_path / "computed.txt", tmp_path / "cache"
    script.write_text(_RACER)
    (tmp_path / "racing.py").write_text(_RACING)
    env = dict(os.environ, **{sc.ENV: str(cache)})
    procs = [subprocess.Popen([sys.executable, str(script), str(marks), sc.__file__], env=env, stdout=subprocess.PIPE, text=True)
             for _ in range(2)]
    outs = [p.communicate(timeout=120)[0] for p in procs]
    assert all(p.returncode == 0 for p in procs)
    assert [json.loads(o) for o in outs] == [[7, 14], [7, 14]]
    assert len(marks.read_text().split()) == 1


@pytest.mark.parametrize("maxsize", [np.timedelta64(1, "s"), np.int8(-1), -1, Fraction(4), np.float16(4), 4.0, True,
                                     "4"])
def test_a_maxsize_that_is_not_a_count_is_refused_at_once(maxsize: object) -> None:
    """fuzz12 bug 9: maxsize is checked when the decorator is made, naming it (not by functools, later, unnamed)."""
    with pytest.raises((TypeError, ValueError), match=r"^maxsize\b"):
        sc.study_cache(maxsize=maxsize)


@pytest.mark.parametrize("maxsize", [None, 0, 3, np.int64(3)])
def test_a_count_or_none_is_a_maxsize(maxsize: object) -> None:
    f = sc.study_cache(maxsize=maxsize)(lambda x: 2 * x)
    assert f(2) == 4 and f(2) == 4
    assert f.cache_info().maxsize == (None if maxsize is None else int(maxsize))


def test_a_frozen_mapping_argument_has_a_key_of_its_own() -> None:
    """A frozen result's mapping field (fusion._frozen.ReadOnlyMapping) is encoded, not refused (which would bypass
    the disk), and told apart from a plain dict of the same items and from another mapping."""
    from fusion._frozen import ReadOnlyMapping
    from fusion.book.study_cache import study_key

    frozen = study_key("m.f", {"options": ReadOnlyMapping({"a": 1.0})})
    assert frozen == study_key("m.f", {"options": ReadOnlyMapping({"a": 1.0})})
    assert frozen != study_key("m.f", {"options": {"a": 1.0}})
    assert frozen != study_key("m.f", {"options": ReadOnlyMapping({"a": 2.0})})


def test_the_in_process_cache_tells_equal_values_of_other_types_and_signed_zeros_apart() -> None:
    """Keyed as on disk (fuzz 15): 1, 1.0 and True are three calls, 0.0 and -0.0 two; a warm cache never serves an
    argument the function would refuse cold, nor 0.0's answer to -0.0."""
    import math

    from fusion.book.study_cache import study_cache

    seen: list[object] = []

    def f(x: object) -> float:
        seen.append(x)
        if not isinstance(x, float):
            raise TypeError("x must be a float")
        return math.copysign(1.0, x)

    g = study_cache()(f)
    assert g(0.0) == 1.0 and g(-0.0) == -1.0 and g(0.0) == 1.0
    for bad in (0, False):
        with pytest.raises(TypeError, match="x must be a float"):
            g(bad)
    assert len(seen) == 4 and g.cache_info().hits == 1
    h = study_cache()(lambda fn: fn(2.0))          # an argument without a canonical encoding: cached by equality
    assert h(abs) == 2.0 and h(abs) == 2.0 and h.cache_info().hits == 1


# --- a caller's edit never reaches a later call (fuzz 17, class A: cache poisoning) ---------------------------------


@dataclasses.dataclass
class _Mutable:
    values: np.ndarray
    label: str = "x"


@dataclasses.dataclass(frozen=True)
class _Frozen:
    values: np.ndarray
    table: dict[str, np.ndarray]


# the studies of _edits at module level: only a function its module holds under its name reaches the disk (fuzz 34a D2)
def _arr() -> np.ndarray:
    return np.arange(4.0)


def _dict_of_arrays() -> dict[str, np.ndarray]:
    return {"mean": np.arange(4.0).reshape(2, 2)}


def _list_of_arrays() -> list[np.ndarray]:
    return [np.arange(3.0), np.ones(2)]


def _frame() -> object:
    import pandas as pd

    return pd.DataFrame({"a": [1.0, 2.0], "b": ["u", "v"]})


def _mutable() -> _Mutable:
    return _Mutable(np.arange(3.0))


def _frozen_with_dict() -> _Frozen:
    return _Frozen(np.arange(3.0), {"k": np.zeros(2)})


def _edits() -> dict[str, tuple[object, object]]:
    """Name -> (a study's result, an in-place edit of it that must not reach the next call: a callable)."""
    import pandas as pd

    def set_array(a: np.ndarray) -> None:
        a[0] = -1.0

    def frame_edit(t: pd.DataFrame) -> None:
        t.iloc[0, 0] = -1.0
        t["c"] = 0

    def mutable_edit(m: _Mutable) -> None:
        m.label = "edited"
        m.values = np.zeros(3)

    return {"array": (_arr, set_array),
            "array, whole": (_arr, lambda a: a.__setitem__(slice(None), -1.0)),
            "dict of arrays, item": (_dict_of_arrays, lambda d: set_array(d["mean"][0])),
            "dict of arrays, key": (_dict_of_arrays, lambda d: d.clear()),
            "list, item": (_list_of_arrays, lambda ls: set_array(ls[0])),
            "list, append": (_list_of_arrays, lambda ls: ls.append(np.ones(1))),
            "DataFrame": (_frame, frame_edit),
            "mutable dataclass": (_mutable, mutable_edit),
            "mutable dataclass, array": (_mutable, lambda m: set_array(m.values)),
            "frozen dataclass, dict field": (_frozen_with_dict, lambda f: f.table.clear()),
            "frozen dataclass, array field": (_frozen_with_dict, lambda f: set_array(f.values))}


def _equal(a: object, b: object) -> bool:
    return pickle.dumps(a) == pickle.dumps(b)


@pytest.mark.parametrize("disk", [False, True], ids=["in process", "through the disk"])
@pytest.mark.parametrize("case", sorted(_edits()))
def test_a_callers_edit_never_reaches_a_later_call(case: str, disk: bool, tmp_path: Path,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    """Whatever a caller does to a cached result in place (an edit, or an attempt that raises) leaves the next call's
    result equal to a fresh computation; also when the result was stored on disk and loaded."""
    make, edit = _edits()[case]
    if disk:
        monkeypatch.setenv(sc.ENV, str(tmp_path))
    else:
        monkeypatch.delenv(sc.ENV, raising=False)
    cached = sc.study_cache(maxsize=2)(make)
    for _ in range(2 if disk else 1):      # through the disk: computed and stored, then (cache cleared) loaded
        first = cached()
        try:
            edit(first)
        except (ValueError, TypeError, AttributeError, dataclasses.FrozenInstanceError):
            pass                           # refused: the array is read-only, the mapping or dataclass frozen
        assert _equal(cached(), make()), case
        assert _equal(cached(), make()), case
        cached.cache_clear()
    if disk:
        assert len(list(tmp_path.glob("*.pkl"))) == 1


@pytest.mark.parametrize("case", sorted(_edits()))
def test_process_cache_applies_the_same_rule(case: str) -> None:
    make, edit = _edits()[case]
    cached = sc.process_cache(maxsize=2)(make)
    first = cached()
    try:
        edit(first)
    except (ValueError, TypeError, AttributeError, dataclasses.FrozenInstanceError):
        pass
    assert _equal(cached(), make()), case


def test_an_immutable_result_is_shared_and_a_mutable_one_copied_with_its_arrays_shared(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """The rule's cost: an immutable result without arrays is the object itself at every call; any other is a new
    container per call whose arrays are new read-only array objects over the cached memory (not copied; fuzz 37a C1)."""
    import pandas as pd

    monkeypatch.delenv(sc.ENV, raising=False)

    def immutable() -> tuple[object, ...]:
        return np.arange(3.0), "a", 1.5, frozenset({1})

    def mutable() -> dict[str, object]:
        return {"a": np.arange(3.0), "t": pd.DataFrame({"x": [1.0]})}

    atoms = sc.study_cache(maxsize=1)(lambda: ("a", 1.5, frozenset({1})))
    assert atoms() is atoms()
    tup = sc.study_cache(maxsize=1)(immutable)
    one, two = tup(), tup()
    assert one[0] is not two[0] and one[0].base is two[0].base and not one[0].flags.writeable
    assert one[3] is two[3]                                # its parts without arrays are shared
    d = sc.study_cache(maxsize=1)(mutable)
    one, two = d(), d()
    assert one is not two and type(one) is dict           # the container's type is kept (no caller breaks)
    assert one["a"] is not two["a"] and one["a"].base is two["a"].base and not one["a"].flags.writeable
    assert one["t"] is not two["t"]                        # a DataFrame cannot be frozen: each caller has its own


def test_an_object_array_is_copied_not_shared(monkeypatch: pytest.MonkeyPatch) -> None:
    """An object array's items can be changed through it even when read-only: it is copied per call."""
    monkeypatch.delenv(sc.ENV, raising=False)

    def lists() -> np.ndarray:
        out = np.empty(2, dtype=object)
        out[:] = [[1], [2]]
        return out

    f = sc.study_cache(maxsize=1)(lists)
    a = f()
    a[0].append(5)
    assert f()[0] == [1]


# --- no bare functools cache in the package (a shared, mutable result) ----------------------------------------------

#: Bare functools caches allowed in fusion/: private helpers whose results are immutable, each with a call the test
#: checks (module, function name, arguments).
BARE_CACHE_ALLOWED = {
    ("fusion/book/study_cache.py", "_source_digest"): (sc._PACKAGE,),
    ("fusion/estimates/mixtures.py", "_triu"): (3,),
    ("fusion/readings/biased.py", "_quadrature"): (8, 5),
    ("fusion/book/chapters/chernoff/glue.py", "_referenced_keys"): (),
    ("fusion/book/rulebook.py", "_clopper_pearson"): (3, 10, 0.95),
    ("fusion/book/style.py", "_figure_keywords"): (),
    ("fusion/book/chapters/lecture_weighting/records.py", "_claim_readings"): ("lec-awf-estimated",),
    ("fusion/book/_claim_text.py", "_refused_class"): (),
    ("fusion/book/_claim_text.py", "_visible_class"): (),
}


def _bare_caches() -> list[tuple[str, str]]:
    import ast

    found = []
    for path in sorted((ROOT / "fusion").rglob("*.py")):
        tree = parsed(path)
        for node in ast.walk(tree):
            if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            for dec in node.decorator_list:
                target = dec.func if isinstance(dec, ast.Call) else dec
                name = target.attr if isinstance(target, ast.Attribute) else getattr(target, "id", "")
                if name in ("lru_cache", "cache"):
                    found.append((path.relative_to(ROOT).as_posix(), node.name))
    return found


def test_no_bare_functools_cache_outside_the_allow_list() -> None:
    """A bare ``functools.lru_cache``/``cache`` hands every caller one object: only the allow-listed helpers use one
    (the others go through ``study_cache``/``process_cache``, which apply the sharing rule)."""
    found = _bare_caches()
    assert found, "the AST scan found no decorator at all: it is broken"
    extra = sorted(set(found) - set(BARE_CACHE_ALLOWED))
    assert not extra, f"bare functools caches (use study_cache or process_cache): {extra}"
    assert set(BARE_CACHE_ALLOWED) <= set(found), "an allow-listed cache is gone: drop it from the list"


@pytest.mark.parametrize("where", sorted(BARE_CACHE_ALLOWED), ids=lambda w: w[1])
def test_an_allowed_bare_cache_returns_an_immutable_value(where: tuple[str, str]) -> None:
    import importlib

    module = importlib.import_module(where[0].removesuffix(".py").replace("/", "."))
    value = getattr(module, where[1])(*BARE_CACHE_ALLOWED[where])
    arrays: list[np.ndarray] = []

    def immutable(v: object) -> bool:
        if isinstance(v, np.ndarray):
            arrays.append(v)
            return not v.flags.writeable and v.dtype != object
        if isinstance(v, (tuple, frozenset)):
            return all(immutable(x) for x in v)
        return isinstance(v, (str, int, float, bytes))

    assert immutable(value), f"{where}: {type(value).__name__} holds something mutable"


def test_a_result_that_contains_itself_is_copied(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(sc.ENV, raising=False)

    def loop() -> list[object]:
        out: list[object] = [np.zeros(2)]
        out.append(out)
        return out

    f = sc.study_cache(maxsize=1)(loop)
    a = f()
    a.append(1)
    b = f()
    assert len(b) == 2 and b[1] is b
