"""Fuzz 34a D1-D4 and 34b D2 (issue 35), decided: uncopyable cached results, closures on disk, Conjunction margins,
undrawable figures, and refusals of a study at other settings naming the defaults the caller did not pass."""

from __future__ import annotations

import re
import threading

import pytest

from fusion.book import study_cache as sc


# --- 34a D1: a cached result that holds something mutable and cannot be deep-copied is returned uncached


@pytest.mark.parametrize("cache", ["study_cache", "process_cache"])
@pytest.mark.parametrize("kind", ["memoryview", "generator", "lock in a dict"])
def test_an_uncopyable_result_is_returned_uncached(cache: str, kind: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(sc.ENV, raising=False)
    calls = []

    def make(n: int) -> object:
        calls.append(n)
        if kind == "memoryview":
            return memoryview(bytes(n))
        if kind == "generator":
            return (i for i in range(n))
        return {"lock": threading.Lock(), "n": n}

    cached = getattr(sc, cache)(4)(make)
    first, second = cached(3), cached(3)
    assert first is not second and calls == [3, 3]          # each call computes it, as without the cache
    assert (len(first) == 3 if kind == "memoryview" else list(first) == [0, 1, 2] if kind == "generator"
            else first["n"] == 3)


def test_a_copyable_mutable_result_is_still_kept(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(sc.ENV, raising=False)
    calls = []
    cached = sc.study_cache(4)(lambda n: calls.append(n) or [n])
    first = cached(2)
    first.append(9)
    assert cached(2) == [2] and calls == [2]


# --- 34a D2: only a function its module holds under its name reaches the disk


def _factory(k: int):
    @sc.study_cache(8)
    def times(x: int) -> int:
        return x * k
    return times


@sc.study_cache(8)
def _module_level(x: int) -> int:
    return x + 1


def test_closures_of_one_factory_are_kept_in_the_process(tmp_path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(sc.ENV, str(tmp_path))
    assert (_factory(2)(1), _factory(3)(1)) == (2, 3)      # were (2, 2): one disk key make.<locals>.times
    assert sc.study_cache(2)(lambda x: -x)(1) == -1 and sc.study_cache(2)(lambda x: x)(1) == 1
    assert not list(tmp_path.glob("*.pkl"))
    _module_level.cache_clear()
    assert _module_level(1) == 2 and len(list(tmp_path.glob("*.pkl"))) == 1   # a module's function: on disk


# --- 34a D3: Conjunction.with_margin checks the margins whatever its members (one check with Comparison's)


@pytest.mark.parametrize("margin, relative, error", [
    (float("nan"), None, ValueError), (-1.0, None, ValueError), (None, float("inf"), ValueError),
    (10 ** 400, None, ValueError), ("x", None, TypeError), (None, [0.1], TypeError), (True, None, TypeError)])
def test_conjunction_with_margin_checks_the_margins_whatever_its_members(margin, relative, error) -> None:
    from fusion.book.ledger import Conjunction, Proposition

    c = Conjunction([("a", Proposition(True, "holds")), ("b", Proposition(True, "holds"))])
    name = "relative_margin" if margin is None else "margin"
    with pytest.raises(error, match=rf"^{name} must be a finite number >= 0"):
        c.with_margin(margin, relative)
    assert c.with_margin(0.1).status() == c.status() and c.with_margin(None, 0.0).status() == c.status()


# --- 34a D4: a figure matplotlib cannot render is the audit's own error


@pytest.mark.parametrize("how", ["audit_figure", "glue_figure"])
def test_a_figure_matplotlib_cannot_draw_is_a_figure_style_error(how: str) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from fusion.book import figures

    fig, ax = plt.subplots(figsize=(3, 2))
    ax.text(1e5, 0, "far", clip_on=False)        # FreeType's raster overflows: a RuntimeError naming nothing
    try:
        with pytest.raises(figures.FigureStyleError, match="figure cannot be drawn"):
            figures.audit_figure(fig) if how == "audit_figure" else figures.glue_figure("x_far", fig)
    finally:
        plt.close(fig)


# --- 34b D2: a default the caller did not pass that does not fit its study: the refusal names the study


def test_a_default_that_does_not_fit_the_study_is_named_by_the_study() -> None:
    from fusion.book.chapters.lecture_wavelets import e26, mechanism
    from fusion.book.chapters.lecture_weighting import learning
    from fusion.scenarios import lecture_weighting as lw
    from fusion.scenarios import wavelet_sensors as ws

    hard = {"wavelet": "db4", "level": 4, "threshold": "universal", "mode": "hard"}
    m = ws.mechanism_study(length=256, runs=100, configs=(hard,))                   # one setting
    e = ws.signal_study(gains=(1.0, 1.5, 0.8), sigma=(0.05, 0.1, 0.2), length=256, runs=100)   # three sensors
    s = lw.learning_study(r_sets=((1.0, 4.0),), epochs=300, runs=100, last=50)     # only n = 2
    for call, study, default, passed, own in [
            (mechanism.table_mechanism, m, "labels = (0, 6)", {"labels": (0, 6)}, r"labels\[1\] must be"),
            (e26.figure_26, e, "sensor = 3", {"sensor": 3}, "sensor must be"),
            (learning.figure_22a, s, "n = 3", {"n": 3}, "n must be")]:
        name = {mechanism.table_mechanism: "m", e26.figure_26: "e", learning.figure_22a: "s"}[call]
        with pytest.raises(ValueError, match=rf"^{name} does not fit {call.__name__}'s default {re.escape(default)}"):
            call(study)
        with pytest.raises(ValueError, match=rf"^{own}"):        # passed by the caller: named as passed
            call(study, **passed)


def test_study_defaults_names_only_a_default_left_in_place() -> None:
    from fusion.book.chapters._defaults import study_defaults

    @study_defaults("xs", "k")
    def pick(xs: tuple, k: int = 5, j: int = 0) -> object:
        if k >= len(xs):
            raise ValueError(f"k must be an index below {len(xs)}, got {k}")
        if j >= len(xs):
            raise ValueError(f"j must be an index below {len(xs)}, got {j}")
        return xs[k]

    assert pick(tuple(range(9))) == 5
    with pytest.raises(ValueError, match=r"^xs does not fit pick's default k = 5 \(k must be"):
        pick((1, 2))
    for kwargs in ({"k": 5}, {"k": 7}, {"k": 0, "j": 4}):   # the caller's own argument: its own refusal
        with pytest.raises(ValueError, match=r"^[kj] must be"):
            pick((1, 2), **kwargs)
