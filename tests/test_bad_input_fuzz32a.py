"""Fuzz 32a: rule 19 of ``fusion._validation`` (a text is its plain text) at every site that keeps, compares, prints
or stores a caller's text, entries of nested arguments named by their place, and the cache's environment.

* C1-C3: a ``(str, Enum)`` member (whose ``str()`` and f-string give its *name*, ``'E.A'``) is read as its text and
  kept as a plain ``str``; a ``BadEq`` subclass (whose ``==`` calls every string equal) is refused with a TypeError
  naming the argument, also as a mapping key (``kf``: it silently dropped an option) and as an entry.
* C4, C5: an entry of a sequence or mapping of texts or options is refused under its place in the caller's argument
  (``names[0]``, ``readings[0][0]``, ``methods['mean']``, ``configs[0]``).
* C6: ``nees_per_frame`` names ``runs`` and ``key`` for singular sample covariances of a valid scenario.
* D1 (decided): a misconfigured cache environment is a ValueError naming the variable, before any work.
* D2 (decided, documented): a cached function returning its array argument froze the caller's array; since fuzz 37a
  C1 the cache keeps a sealed copy and leaves the caller's array as it is.

Each case builds only what it needs (no registry import): the file's CPU cost stays about a second.
"""
from __future__ import annotations

import dataclasses
import enum
from collections.abc import Mapping

import numpy as np
import pandas as pd
import pytest


class BadEq(str):
    """A str subclass whose comparison disagrees with its text (rule 19: refused)."""

    def __eq__(self, other: object) -> bool:
        return True

    def __ne__(self, other: object) -> bool:
        return False

    __hash__ = str.__hash__


def _enum(value: str) -> str:
    """A str-mixin Enum member of text ``value``: ``str()`` of it is ``'E.A'``, not its text."""
    return enum.Enum("E", {"A": value}, type=str).A


def _leaves(obj: object, depth: int = 0):
    """Every str reachable in a result (dataclass fields, containers, mapping keys, a table's labels)."""
    if depth > 6:
        return
    if isinstance(obj, str):
        yield obj
    elif isinstance(obj, pd.DataFrame):
        yield from (c for c in [*obj.columns, obj.index.name] if isinstance(c, str))
    elif dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        for f in dataclasses.fields(obj):
            yield from _leaves(getattr(obj, f.name, None), depth + 1)
    elif isinstance(obj, Mapping):
        for k, v in obj.items():
            yield from _leaves(k, depth + 1)
            yield from _leaves(v, depth + 1)
    elif isinstance(obj, (list, tuple)):
        for v in obj:
            yield from _leaves(v, depth + 1)


def _plain(result: object) -> None:
    """Every text of ``result`` is a plain str, none printed as an Enum's name."""
    for s in _leaves(result):
        assert type(s) is str and "E.A" not in s, (type(s).__name__, s)


def _subst(value: object, f) -> object:
    """``value`` with each str leaf (top level, or in tuples, lists and dict values, two levels) replaced by f(leaf)."""
    if isinstance(value, str):
        return f(value)
    if isinstance(value, (tuple, list)):
        return type(value)(_subst(v, f) for v in value)
    if isinstance(value, dict):
        return {k: _subst(v, f) for k, v in value.items()}
    return value


# -- the calls: a builder of valid keyword arguments for each public callable, and its text arguments ------------------

def _proposition():
    from fusion.book.ledger import Proposition
    return Proposition(True, "holds")


def _runs(shift: float) -> np.ndarray:
    return np.linspace(0.0, 1.0, 30) + shift


def _calls():
    from fusion.book import exact, ledger, recommend, rulebook, tables
    from fusion.scenarios import thermocouples, two_sensor, wavelet_sensors
    ev = recommend.Evidence("a", ("reproduced",), "role")
    z = 900.0 + np.random.default_rng(0).normal(size=(4, 10))
    return {
        "Source": (ledger.Source, dict(key="k", short="A (2000)", title="T", chapter="notebooks/x", order=1,
                                       chapters=("notebooks/x",)), ("key", "short", "title", "chapter", "chapters")),
        "PublishedValues": (ledger.PublishedValues, dict(published=np.array([1.25, 2.5]), ours=np.array([1.25, 2.5]),
                                                         decimals=2, unit="m"), ("unit",)),
        "Comparison": (ledger.Comparison, dict(a=_runs(0.0), b=_runs(0.5), a_name="A", b_name="B", claim="less",
                                               metric="MSE", seed=1, reason="r", conditions=("c", "c")),
                       ("a_name", "b_name", "metric", "reason", "conditions", "claim")),
        "Proposition": (ledger.Proposition, dict(holds=True, ours="it holds"), ("ours",)),
        "Conjunction": (ledger.Conjunction, dict(parts=(("one", _proposition()), ("two", _proposition()))), ("parts",)),
        "ExactComparison": (exact.ExactComparison, dict(a=0.9, b=1.0, a_name="A", b_name="B", claim="less",
                                                        metric="exact MSE", margin=0.05), ("a_name", "b_name", "metric")),
        "Unverifiable": (ledger.Unverifiable, dict(reason="no data"), ("reason",)),
        "Alternative": (ledger.Alternative, dict(choice="guard", reading="|x|", evidence=_proposition(),
                                                 kind="open-choice"), ("choice", "reading", "kind")),
        "Claim": (ledger.Claim, dict(id="yang-x", source="yang2012optimal", where="Table 1", claim="A is smaller",
                                     published="qualitative", evidence=_proposition(), link="sec-x",
                                     assumptions=("a",)), ("id", "source", "where", "claim", "published", "link",
                                                           "assumptions")),
        "Evidence": (recommend.Evidence, dict(claim="a", expect=("reproduced",), role="role"), ("claim", "expect", "role")),
        "Recommendation": (recommend.Recommendation, dict(task="t", use="u", why="w", avoid="a", avoid_why="b",
                                                          evidence=(ev,), chapters=("c",)),
                           ("task", "use", "why", "avoid", "avoid_why", "chapters")),
        "check": (recommend.check, dict(records=[{"id": "a", "status": "reproduced"}],
                                        recommendations=[recommend.Recommendation("t", "u", "w", "a", "b", (ev,), ())]),
                  ("records",)),
        "record_status": (rulebook.record_status, dict(primary="reproduced", readings=(("open-choice", "reproduced", 100),),
                                                       primary_runs=100, assumptions=False), ("primary", "readings")),
        "counted": (rulebook.counted, dict(kind="stand-in", runs=100, primary_runs=100, status="reproduced"),
                    ("kind", "status")),
        "side_by_side": (tables.side_by_side, dict(published=np.array([1.0, 2.0]), reproduced=np.array([1.1, 2.1]),
                                                   index=[1, 2], name="m", index_name="observation"),
                         ("name", "index_name")),
        "fixed_weight_rule": (two_sensor.fixed_weight_rule, dict(reading="shared", omega=0.5), ("reading",)),
        "absolute_errors": (thermocouples.absolute_errors, dict(z=z, methods={"mean": {"method": "mean"}}, truth=900.0),
                            ("methods",)),
        "config_label": (wavelet_sensors.config_label, dict(cfg={"wavelet": "db4", "level": 4, "threshold": "universal",
                                                                 "mode": "soft"}), ("cfg",)),
    }


_CASES = [
    ("Source", "key"), ("Source", "short"), ("Source", "title"), ("Source", "chapter"), ("Source", "chapters"),
    ("PublishedValues", "unit"), ("Comparison", "a_name"), ("Comparison", "b_name"), ("Comparison", "metric"),
    ("Comparison", "reason"), ("Comparison", "conditions"), ("Proposition", "ours"), ("Conjunction", "parts"),
    ("ExactComparison", "a_name"), ("ExactComparison", "b_name"), ("ExactComparison", "metric"),
    ("Unverifiable", "reason"), ("Alternative", "choice"), ("Alternative", "reading"), ("Alternative", "kind"),
    ("Claim", "id"), ("Claim", "source"), ("Claim", "where"), ("Claim", "claim"), ("Claim", "published"),
    ("Claim", "link"), ("Claim", "assumptions"), ("Evidence", "claim"), ("Evidence", "expect"), ("Evidence", "role"),
    ("Recommendation", "task"), ("Recommendation", "avoid_why"), ("Recommendation", "chapters"),
    ("check", "records"), ("record_status", "primary"), ("record_status", "readings"), ("counted", "kind"),
    ("counted", "status"), ("side_by_side", "name"), ("side_by_side", "index_name"), ("fixed_weight_rule", "reading"),
    ("absolute_errors", "methods"), ("config_label", "cfg"),
]


@pytest.fixture(scope="module")
def calls():
    return _calls()


@pytest.mark.parametrize("name, arg", _CASES, ids=[f"{n}-{a}" for n, a in _CASES])
def test_c2_c3_a_str_enum_text_is_kept_as_its_plain_text(calls, name: str, arg: str) -> None:
    fn, kw, _ = calls[name]
    plain = fn(**kw)
    got = fn(**{**kw, arg: _subst(kw[arg], _enum)})
    _plain(got)
    if not dataclasses.is_dataclass(plain):  # a record compares its fields; a function's result is the plain one's
        assert (got.equals(plain) if isinstance(plain, pd.DataFrame) else
                repr(got) == repr(plain) if not isinstance(plain, dict) else
                all(np.array_equal(got[k], plain[k]) for k in plain) and list(got) == list(plain))


@pytest.mark.parametrize("name, arg", _CASES, ids=[f"{n}-{a}" for n, a in _CASES])
def test_c3_c4_a_disagreeing_subclass_is_refused_under_the_callers_argument(calls, name: str, arg: str) -> None:
    fn, kw, _ = calls[name]
    with pytest.raises(TypeError, match=rf"^{arg}\b|^{arg}\[|\b{arg}\b"):
        fn(**{**kw, arg: _subst(kw[arg], BadEq)})


def test_c1_a_kf_key_is_read_as_its_text() -> None:
    from fusion.scenarios import time_registration as tr
    kw = dict(name="reg_kalman_two_point", sigma_filter=2.0, t_src=np.arange(1.0, 21.0, 2.0),
              t_dst=np.array([3.0, 8.0, 13.0]), q_v=0.01, q_a=0.001)
    once = tr.mse_coefficients(**kw, kf={"init": "once"})
    np.testing.assert_array_equal(tr.mse_coefficients(**kw, kf={_enum("init"): "once"})[0], once[0])
    for value in ("once", "bogus"):  # before: the key was dropped (a silent wrong number), its value never checked
        with pytest.raises(TypeError, match=r"^kf keys"):
            tr.mse_coefficients(**kw, kf={BadEq("init"): value})


def test_c2_glue_all_glues_a_text_as_its_plain_text(monkeypatch) -> None:
    import myst_nb

    from fusion.book.glue import glue_all
    glued: list[tuple[str, object]] = []
    monkeypatch.setattr(myst_nb, "glue", lambda name, variable, display=True: glued.append((name, variable)))
    glue_all({_enum("k-a"): _enum("reproduced")})
    assert glued == [("k-a", "reproduced")] and all(type(x) is str for pair in glued for x in pair)
    with pytest.raises(TypeError, match=r"^values\["):
        glue_all({"k-a": BadEq("reproduced")})


def test_c4_sequence_entries_are_named_by_their_place() -> None:
    from fusion.scenarios import time_registration as tr
    with pytest.raises(TypeError, match=r"^names\[0\]"):
        tr.fusion_runs(names=(BadEq("reg_two_point"), "reg_kalman_two_point"), sigma=2.0, runs=2, seed=1)
    with pytest.raises(TypeError, match=r"^names\[1\]"):
        tr.monte_carlo(("reg_two_point", BadEq("reg_kalman_two_point")), 2.0, 2, 1)


@pytest.mark.parametrize("spec, pattern", [
    ({"method": "bogus"}, r"^methods\['mean'\]: method must be one of"),
    ({"method": "mean", "zz": 1}, r"^methods\['mean'\]: .*unexpected keyword"),
    ({"method": "support_degree", "alpha": "x"}, r"^methods\['mean'\]: alpha"),
])
def test_c5_thermocouple_method_options_are_named_by_their_entry(spec: dict, pattern: str) -> None:
    from fusion.scenarios.thermocouples import absolute_errors
    with pytest.raises((TypeError, ValueError), match=pattern):
        absolute_errors(900.0 + np.zeros((2, 10)), {"mean": spec}, 900.0)


@pytest.mark.parametrize("key, value", [("mode", "bogus"), ("threshold", "bogus"), ("wavelet", "nope"),
                                        ("transform", "bogus")])
def test_c5_wavelet_configuration_options_are_named_by_their_entry(key: str, value: str) -> None:
    from fusion.scenarios.wavelet_sensors import config_label
    cfg = {"wavelet": "db4", "level": 4, "threshold": "universal", "mode": "soft", key: value}
    with pytest.raises(ValueError, match=rf"^cfg\['{key}'\]"):
        config_label(cfg)


def test_c6_nees_per_frame_names_runs_and_key_for_singular_covariances() -> None:
    from fusion.scenarios import range_bearing as rb
    sc = rb.RangeBearingScenario(frames=2, n_particles=60, n_samples=60, n_central=4, em_iterations=2, n_components=1)
    runs = rb.monte_carlo(sc, 1, 1, all_nodes_first=False)
    with pytest.raises(ValueError, match=r"^runs: the covariances of key 'centralised_pf'"):
        rb.nees_per_frame(runs, "centralised_pf")


@pytest.mark.parametrize("env, log", [("file", None), ("blank", None), ("dir", "dir"), ("dir", "missing")])
def test_d1_a_misconfigured_cache_environment_is_named_before_any_work(tmp_path, monkeypatch, env, log) -> None:
    from fusion.book import study_cache as scache
    (tmp_path / "afile").write_text("")
    where = {"file": str(tmp_path / "afile"), "blank": "   ", "dir": str(tmp_path),
             "missing": str(tmp_path / "no" / "log.jsonl")}
    monkeypatch.setenv(scache.ENV, where[env])
    if log is not None:
        monkeypatch.setenv(scache.LOG_ENV, where[log])
    calls: list[float] = []

    @scache.study_cache(maxsize=0)
    def double(x: float) -> float:
        calls.append(x)
        return 2 * x

    name = scache.LOG_ENV if log is not None else scache.ENV
    with pytest.raises(ValueError, match=rf"environment variable {name} "):
        double(3.0)
    assert calls == []  # refused before the computation, whose result an OS error used to lose
    monkeypatch.delenv(scache.LOG_ENV, raising=False)
    monkeypatch.setenv(scache.ENV, str(tmp_path / "cache"))  # a directory, created on first use: valid
    assert double(3.0) == 6.0


def test_d2_a_cached_function_returning_its_argument_leaves_it_as_documented() -> None:
    from fusion.book.study_cache import study_cache

    @study_cache(maxsize=8)
    def ident(x: np.ndarray) -> np.ndarray:
        return x

    mine = np.ones(3)
    got = ident(mine)   # the documented rule (study_cache's Notes; fuzz 37a C1: the cache keeps a sealed copy)
    assert got is not mine and mine.flags.writeable and not np.shares_memory(got, mine)
    assert "leaves the caller's own array as it is" in " ".join(study_cache.__doc__.split())
