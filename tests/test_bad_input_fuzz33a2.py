"""Fuzz 33a (issue 35), the cases of fixer 33a2: the study cache's key and sharing rules (C4, C8, D2), its
environment check (C6), method labels (C5), chapter 07's spline budget (C9) and ``python -OO`` (D1)."""

from __future__ import annotations

import collections
import dataclasses

import numpy as np
import pytest

from fusion.book import study_cache as sc

_P = collections.namedtuple("_P", "x y")


class _Other:
    _P = collections.namedtuple("_P", "y x")   # the same class name, the fields the other way round


def _fresh(fn):
    """A study_cache-wrapped ``fn`` with an empty cache, without the disk (``ENV`` unset)."""
    return sc.study_cache(8)(fn)


def test_same_named_tuple_classes_get_their_own_results(monkeypatch: pytest.MonkeyPatch, tmp_path) -> None:
    # C4: the key named a tuple's class by its short name: two named tuples "_P" shared one result, on disk too
    for env in (None, str(tmp_path)):
        if env is None:
            monkeypatch.delenv(sc.ENV, raising=False)
        else:
            monkeypatch.setenv(sc.ENV, env)
        first = _fresh(lambda p: p.x)
        assert first(_P(1, 2)) == 1
        assert first(_Other._P(1, 2)) == 2
        inner = _fresh(lambda t: t[0].x)
        assert inner((_P(1, 2),)) == 1 and inner((_Other._P(1, 2),)) == 2
    local = collections.namedtuple("_P", "y x")    # not found under its name in this module: kept in the process
    monkeypatch.setenv(sc.ENV, str(tmp_path))
    inner = _fresh(lambda t: t[0].x)
    assert inner((_P(1, 2),)) == 1 and inner((local(1, 2),)) == 2 and inner((local(1, 2),)) == 2
    for other in (local, _Other._P):      # a named tuple's qualified name is its typename: both look like _P
        with pytest.raises(TypeError, match="not found under that name"):
            sc.study_key("m.f", {"p": (other(1, 2),)}, digest="d")
    assert sc.study_key("m.f", {"p": _P(1, 2)}, digest="d") == sc.study_key("m.f", {"p": _P(1, 2)}, digest="d")


def test_a_structured_record_is_not_shared() -> None:
    # C8: a np.void taken from a structured array is a writable view: shared, one caller's edit reached the next
    def record(n):
        a = np.zeros(3, dtype=[("x", float), ("y", float)])
        a["x"] = n
        return a[0]

    for cached in (sc.study_cache(4)(record), sc.process_cache(4)(lambda n: (record(n), n))):
        got = cached(1)
        (got if isinstance(got, np.void) else got[0])["x"] = 99.0
        again = cached(1)
        assert float((again if isinstance(again, np.void) else again[0])["x"]) == 1.0


@dataclasses.dataclass(frozen=True)
class _Scaled:
    value: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "scale", 2.0)


def test_a_dataclass_is_keyed_by_its_fields_only() -> None:
    # D2 (decided, documented in study_cache's Notes): the key is the dataclass's fields, as its == compares
    assert "outside its fields" in sc.study_cache.__doc__
    calls = []
    cached = _fresh(lambda s: calls.append(1) or s.value * s.scale)
    a, b = _Scaled(1.0), _Scaled(1.0)
    object.__setattr__(b, "scale", 3.0)
    assert a == b and cached(a) == 2.0 and cached(b) == 2.0 and len(calls) == 1


@pytest.mark.parametrize("where", ["file", "proc"])
def test_an_unusable_cache_directory_is_named(where: str, monkeypatch: pytest.MonkeyPatch, tmp_path) -> None:
    # C6: a path through a file, or a directory in which no file can be created, gave an OS error from every call
    blocker = tmp_path / "f.txt"
    blocker.write_text("x")
    root = str(blocker / "sub") if where == "file" else "/proc/self"
    monkeypatch.setenv(sc.ENV, root)
    calls = []
    with pytest.raises(ValueError, match=sc.ENV):
        _fresh(lambda x: calls.append(x) or x)(3)
    assert calls == []                       # refused before any work
    monkeypatch.setenv(sc.ENV, str(tmp_path / "new" / "dir"))   # a missing directory is created
    assert _fresh(lambda x: x * x)(3) == 9


def test_stability_main_runs_without_docstrings(monkeypatch: pytest.MonkeyPatch, capsys) -> None:
    # D1: python -OO strips docstrings; main(["--help"]) read the module's docstring for its description
    from fusion.book import stability
    monkeypatch.setattr(stability, "__doc__", None)
    with pytest.raises(SystemExit) as done:
        stability.main(["--help"])
    assert done.value.code == 0 and "reseeding" in capsys.readouterr().out


# --------------------------------------------------------------------------- C5: labels that key a result are text
_NOT_TEXT = [1, None, float("nan"), b"mean", ("mean",), 1.5]


@pytest.mark.parametrize("label", _NOT_TEXT, ids=repr)
def test_a_method_label_must_be_text(label: object) -> None:
    from fusion.scenarios import thermocouples as tc
    z = np.full((2, 3), 900.0)
    with pytest.raises(TypeError, match=r"^methods keys must be a string"):
        tc.absolute_errors(z, {label: {"method": "mean"}})
    with pytest.raises(TypeError, match=r"^methods keys must be a string"):
        tc.monte_carlo(1, 1, {"mean": {"method": "mean"}, label: {"method": "mean"}}, n_samples=2)


def test_paired_study_names_methods_not_its_result_field() -> None:
    from fusion.scenarios import thermocouples as tc
    methods = {1: {"method": "optimal_fusion_set"}, "mean": {"method": "mean"}}
    with pytest.raises(TypeError, match=r"^methods keys must be a string"):
        tc.paired_study(1, 2, methods, n_samples=90)


def test_late_means_keys_are_text() -> None:
    from fusion.scenarios import infrared_radar as ir
    t, r = np.arange(4.0), np.ones((4, 4))
    for label in _NOT_TEXT:
        with pytest.raises(TypeError, match=r"^rmse keys must be a string"):
            ir.late_means({label: r}, t)
    got = ir.late_means({np.str_("kf"): r, next(iter(ir.IrMethod)): r}, t)
    assert all(type(k) is str for k in got) and got["kf"][ir.X_M] == 1.0


# --------------------------------------------------------------------------- C9: the spline's registration cost
def test_the_cubic_spline_is_weighed_by_its_cost() -> None:
    # the largest accepted spline Monte Carlo (22,664 samples) ran 27-46 CPU-s; it weighs 5 units per sample and
    # instant now (42-50 ns measured): 10,899 samples, 8.8 CPU-s, is the largest accepted
    from fusion.scenarios import time_registration as tr
    n = 10_900
    t_src = np.arange(n) * 0.05 + 1.0
    t_dst = np.arange(n // 2) * 0.1 + 1.03
    t_dst = t_dst[t_dst < t_src[-1]]
    with pytest.raises(ValueError, match="work budget"):      # the budget alone first: the old one let it run
        tr._monte_carlo_work(["reg_cubic_spline"], 2, n, t_dst.size, "runs", "t_src")
    tr._monte_carlo_work(["reg_two_point"], 2, n, t_dst.size, "runs", "t_src")   # a one-weight method: accepted
    with pytest.raises(ValueError, match=r"t_src and t_dst ask for .* beyond the work budget"):
        tr.monte_carlo(["reg_cubic_spline"], 2.0, 2, 1, t_src=t_src, t_dst=t_dst)
    n = 15_000
    t_src, t_dst = np.arange(n) * 0.05 + 1.0, np.arange(n // 2) * 0.1 + 1.03
    for call in (lambda: tr.expected("reg_cubic_spline", 2.0, t_src=t_src, t_dst=t_dst),
                 lambda: tr.mse_coefficients("reg_cubic_spline", 1.0, t_src=t_src, t_dst=t_dst)):
        with pytest.raises(ValueError, match="work budget"):
            call()
