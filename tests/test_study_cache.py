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
    assert a.flags.writeable and not b.flags.writeable
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
    d0 = sc.source_digest.__wrapped__(pkg)
    (pkg / "sub" / "b.py").write_text("y = 3\n")
    d1 = sc.source_digest.__wrapped__(pkg)
    (pkg / "sub" / "b.py").rename(pkg / "sub" / "c.py")
    d2 = sc.source_digest.__wrapped__(pkg)
    (pkg / "notes.txt").write_text("not a source")
    assert len({d0, d1, d2}) == 3 and sc.source_digest.__wrapped__(pkg) == d2


def test_defaults_and_keywords_share_one_entry(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(sc.ENV, str(tmp_path))
    calls = []

    @sc.study_cache(maxsize=4)
    def f(seed: int, runs: int = 100) -> int:
        calls.append((seed, runs))
        return seed + runs

    assert f(1) == f(1, 100) == f(seed=1, runs=100) == 101
    assert calls == [(1, 100)]                                 # the later calls load the stored result
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
    study_cache = module.study_cache

    @study_cache(maxsize=1)
    def slow(seed: int) -> list:
        with open(sys.argv[1], "a") as fh:
            fh.write(f"{os.getpid()}\\n")
        time.sleep(1.0)
        return [seed, seed * 2]

    print(json.dumps(slow(7)))
""")


def test_two_processes_racing_compute_once(tmp_path: Path) -> None:
    """Two processes ask for one study at once: one computes it, the other waits and loads it."""
    script, marks, cache = tmp_path / "racer.py", tmp_path / "computed.txt", tmp_path / "cache"
    script.write_text(_RACER)
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
