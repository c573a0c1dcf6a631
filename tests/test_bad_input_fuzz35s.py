"""Fuzz 34 follow-ups (issue 35): sites of already-fixed classes that the fixers named but had not converted.

- a caller's mapping read once (``fusion._guards.read_mapping``, decision 31a C2);
- frozen result specs with float keys check their keys by meaning when rebuilt (decision 32b, ``real_key``);
- result tables refuse, when built, cells their readers cannot compute (decision 33b, ``_results.table(cells=)``).
"""

from __future__ import annotations

import dataclasses
from collections import UserDict

import numpy as np
import pytest


class Later(UserDict):
    """A mapping (not a dict) whose values are ``first`` on the first read of a key and ``later`` after it."""

    def __init__(self, first, later):
        super().__init__(first)
        self.later, self.seen = dict(later), set()

    def __getitem__(self, k):
        first = k not in self.seen
        self.seen.add(k)
        return self.data[k] if first else self.later[k]


# --- a caller's mapping read once (31a C2) -----------------------------------------------------------------------

def test_kf_options_are_read_once_for_register_and_monte_carlo():
    """``kf`` was checked by one read and used by another: p0 given valid, then NaN, filtered with the NaN."""
    from fusion.scenarios import time_registration as sc

    t1, t2 = sc.instants()
    t1, t2 = t1[:40], t2[t2 <= t1[-1]][:10]
    z = sc.truth(t1) + np.random.default_rng(1).standard_normal(t1.size)
    good = {"p0": (100.0, 100.0)}
    flip = Later(good, {"p0": (np.nan, np.nan)})
    want = sc.register(sc.RegMethod.IMPROVED, t1, z, t2, 1.0, kf=good)
    np.testing.assert_array_equal(sc.register(sc.RegMethod.IMPROVED, t1, z, t2, 1.0, kf=flip), want)
    kw = dict(t_src=t1, t_dst=t2)
    want = sc.monte_carlo([sc.RegMethod.IMPROVED], 1.0, 3, 0, kf=good, **kw).per_run
    got = sc.monte_carlo([sc.RegMethod.IMPROVED], 1.0, 3, 0, kf=Later(good, {"p0": (np.nan, np.nan)}), **kw).per_run
    np.testing.assert_array_equal(got[sc.RegMethod.IMPROVED], want[sc.RegMethod.IMPROVED])
    reg = sc.registrar(sc.RegMethod.IMPROVED, t1, t2, 1.0, kf=Later(good, {"p0": (np.nan, np.nan)}))
    np.testing.assert_array_equal(reg(z), sc.register(sc.RegMethod.IMPROVED, t1, z, t2, 1.0, kf=good))


def test_chapter07_tables_read_their_mappings_once():
    """``noise_level_table``'s ``mcs`` and the ``exact`` of mc_table and its siblings are read once."""
    from fusion.book.chapters import time_registration as ch
    from fusion.scenarios import time_registration as sc

    t1, t2 = sc.instants()
    t1, t2 = t1[:40], t2[t2 <= t1[-1]][:10]
    mc = sc.monte_carlo(list(ch.FIG4), 1.0, 4, 0, t_src=t1, t_dst=t2)
    a, b = ch.FIG4
    other = dataclasses.replace(mc, per_run={**mc.per_run, a: mc.per_run[b] * 1e3, b: mc.per_run[a] * 1e3})
    want = ch.noise_level_table({1.0: mc}, 50.0, block=2)
    got = ch.noise_level_table(Later({1.0: mc}, {1.0: other}), 50.0, block=2)
    pd_equal(got, want)
    exact = {n: 1.0 for n in mc.per_run}
    want = ch.mc_table(mc, exact)
    pd_equal(ch.mc_table(mc, Later(exact, {n: np.nan for n in exact})), want)


def test_manoeuvre_values_reads_its_mappings_once():
    """``manoeuvre`` and its inner mappings were checked by one read (keys present) and glued from another."""
    from fusion.book.chapters.time_registration_ledger.values import manoeuvre_values
    from fusion.scenarios import time_registration as sc

    M = sc.RegMethod
    inner = {n: sc.expected(n, 1.0, a_after=0.0) for n in (M.IMPROVED, M.TWO_POINT, M.THREE_POINT)}
    neg = {M.IMPROVED: sc.expected(M.IMPROVED, 1.0, a_after=-2.0)}
    want = manoeuvre_values({0.0: inner, -2.0: neg}, 1.0)
    assert manoeuvre_values(Later({0.0: inner, -2.0: neg}, {0.0: {}, -2.0: {}}), 1.0) == want


def test_chapter05_readers_read_a_mapping_once():
    """Chapter 05's shared readers (``_entries``: nees_numbers and 20 others; ``_results``: the architecture and
    weight-search tables) checked one read of a caller's mapping and computed with another."""
    from fusion.book.chapters.ci import nees as ci_nees
    from fusion.book.chapters.ci.checks import _results

    nees = {k: 4.0 + i for i, k in enumerate(ci_nees._NEES_READ)}
    want = ci_nees.nees_numbers(nees, 10)
    assert ci_nees.nees_numbers(Later(nees, dict.fromkeys(nees, np.nan)), 10) == want
    got = _results(Later({"a": 1.5}, {"a": "not a float"}), "res", float, "maker")
    assert got["a"] == 1.5 and got["a"] == 1.5


def pd_equal(a, b):
    import pandas as pd

    pd.testing.assert_frame_equal(a, b)


# --- float keys of frozen result specs checked by meaning (32b) ---------------------------------------------------

_RUNS = np.ones(3)
# (module:class, field, an entry, keys the producer makes, a key outside the meaning)
_REAL_KEYED = [
    ("fusion.scenarios.lecture_weighting.estimators:AwfStudy", "sweep", {"m": _RUNS}, (0.0, 900.0), np.nan),
    ("fusion.scenarios.lecture_weighting.estimators:AwfStudy", "mse", {"m": _RUNS}, (0.0, -3.0), np.inf),
    ("fusion.scenarios.lecture_weighting.estimators:AwfStudy", "sq", {"m": _RUNS}, (0.0,), -np.inf),
    ("fusion.scenarios.lecture_weighting.estimators:AwfStudy", "err", {"m": _RUNS}, (900.0,), np.nan),
    ("fusion.scenarios.ridge_sensors:PluginStudy", "sq", {"m": _RUNS}, (0.0, -1.0), np.nan),
    ("fusion.scenarios.ridge_sensors:PluginStudy", "hit", {"m": _RUNS}, (2.0,), np.inf),
    ("fusion.scenarios.ridge_sensors:PluginStudy", "hits", {0.5: {"m": _RUNS}}, (1.0, 8.0), -1.0),
    ("fusion.scenarios.ridge_sensors:PluginStudy", "hits", {0.5: {"m": _RUNS}}, (1.0,), 0.0),
    ("fusion.scenarios.lecture_correlated:RidgeStudy", "mse", _RUNS, (0.5, -2.0), np.nan),
    ("fusion.scenarios.lecture_correlated:RidgeStudy", "rel", _RUNS, (0.5,), np.inf),
    ("fusion.scenarios.two_sensor.architecture:QScaling", "run_rmse", _RUNS, (0.5, 1.0), 0.0),
    ("fusion.scenarios.two_sensor.architecture:QScaling", "model_rmse", _RUNS, (2.0,), -1.0),
    ("fusion.scenarios.two_sensor.architecture:QScaling", "nees", 4.0, (1.0,), np.nan),
]


@pytest.mark.parametrize("cls, field, entry, good, bad", _REAL_KEYED)
def test_scenario_results_check_their_float_keys_by_meaning(cls, field, entry, good, bad):
    """A result rebuilt by ``dataclasses.replace`` took a NaN, infinite or (for a factor or a tolerance) non-positive
    key: the field's spec refuses it by the field's name; the producer's keys still pass."""
    import importlib

    from fusion._results import _check

    mod, name = cls.split(":")
    spec = getattr(importlib.import_module(mod), name).__result_spec__.fields[field]
    assert set(_check(spec, dict.fromkeys(good, entry), field, {})) == set(good)
    with pytest.raises(ValueError, match=f"{field}'s key"):
        _check(spec, {**dict.fromkeys(good, entry), bad: entry}, field, {})


def test_plugin_study_inner_keys_checked():
    """``PluginStudy.hits[c]`` is keyed by the true values x: a NaN there is refused by the field's name."""
    from fusion._results import _check
    from fusion.scenarios.ridge_sensors import PluginStudy

    spec = PluginStudy.__result_spec__.fields["hits"]
    with pytest.raises(ValueError, match=r"hits\[1.0\]'s key"):
        _check(spec, {1.0: {0.5: {"m": _RUNS}, np.nan: {"m": _RUNS}}}, "hits", {})


# --- result tables refuse, when built, cells their readers cannot compute (33b) ---------------------------------

_TABLES = [("fusion.book.chapters.chernoff_snis:SnisBiasStudy", "table"),
           ("fusion.book.chapters.chernoff_snis:ChosenBiasStudy", "table"),
           ("fusion.book.chapters.chernoff_first_order:SigmaFirstOrderStudy", "runs"),
           ("fusion.book.chapters.chernoff.importance:IsVarianceStudy", "table"),
           ("fusion.book.chapters.ofs.reproduction:TableReproduction", "table2"),
           ("fusion.book.chapters.ofs.reproduction:TableReproduction", "table3"),
           ("fusion.book.chapters.ofs.reproduction:TableReproduction", "totals"),
           ("fusion.book.chapters.ofs.reproduction:TableReproduction", "audit"),
           ("fusion.book.chapters.ofs.reproduction:TableReproduction", "alpha"),
           ("fusion.book.chapters.ofs_audit:AuditResult", "full")]


def _frame(args):
    """A table the field accepts: one row (the rows of its index if it names them), each cell inside its rule."""
    import pandas as pd

    cells = args["cells"]
    index = list(args["index"]) or [1]
    row = {c: (cells[c][0] if np.isfinite(cells[c][0]) else (cells[c][1] if np.isfinite(cells[c][1]) else 0.5))
           if c in cells else "a" for c in args["columns"]}
    frame = pd.DataFrame([row] * len(index), index=index)
    if args["key"] and len(index) > 1:  # pragma: no cover - no keyed table here names index rows
        raise AssertionError("a keyed table with several rows")
    return frame


@pytest.mark.parametrize("cls, field", _TABLES)
def test_result_tables_refuse_cells_their_readers_cannot_compute(cls, field):
    """A table rebuilt by ``dataclasses.replace`` took NaN, infinite or out-of-range cells (an R of 1.5, a count of
    -1, an exponent of 2), which its glue or display then computed with: refused by the field's name and column."""
    import importlib

    from fusion._results import _check

    mod, name = cls.split(":")
    spec = getattr(importlib.import_module(mod), name).__result_spec__.fields[field]
    cells = spec.args["cells"]
    assert cells, f"{name}.{field} checks no cell"
    good = _frame(spec.args)
    _check(spec, good, f"{name}.{field}", {})
    for col, (lo, hi, whole) in cells.items():
        for bad in (np.nan, np.inf, lo - 1.0, hi + 1.0, lo + 0.5 if whole else None):
            if bad is None or (np.isinf(lo) and bad == lo - 1.0) or (np.isinf(hi) and bad == hi + 1.0):
                continue
            frame = good.copy()
            frame[col] = bad
            with pytest.raises(ValueError, match=rf"{name}\.{field}[\[:]"):
                _check(spec, frame, f"{name}.{field}", {})


def test_an_empty_table_has_no_cells_to_refuse():
    """``joint_audit`` keeps ``full``'s columns when no hypothesis explains all 26 values (dtype object, no row):
    the cell rule does not refuse that valid table."""
    import pandas as pd

    from fusion._results import _check
    from fusion.book.chapters.ofs_audit import _FULL_COLUMNS, AuditResult

    spec = AuditResult.__result_spec__.fields["full"]
    assert _check(spec, pd.DataFrame(columns=list(_FULL_COLUMNS)), "AuditResult.full", {}).empty
