"""Fuzz 33b (chapter layer): the cases B1-B4 and D1-D6 of /work/tmp/fuzz33b/report.md, fixed by class.

* B1: ``plugin_study`` refuses tolerances ``deltas`` whose exact crossing ``plugin_exact`` cannot compute (above 8),
  naming ``deltas``; ``plugin_exact`` names ``p.deltas`` for a rebuilt study.
* B2, D3: a table field's spec checks the cells its producer makes (``fusion._results.table(cells=...)``):
  LedgerInputs' FOA step tables and ``fig5_hyp``, AuditResult's counts.
* B3, D1: the glue readers of chapter 04's appendix tables refuse a repeated row naming ``tab``;
  ``glue_james_stein`` names ``tab.attrs['runs']`` for a bad record.
* B4, D2: the chapters' ``keep`` read ``values`` once and store a 0-d array as its plain number.
* D4: ``manoeuvre_values`` refuses a ``manoeuvre`` not computed at ``sigma``.
* D5: study mappings check the setup each key's study records (the swaps rule).
* D6: functions whose ``exp`` underflows by design run under their own underflow state (``own_underflow``).
"""

from __future__ import annotations

import dataclasses
import types
from collections.abc import Mapping

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings, strategies as st_

from fusion import _results


class FlipMap(Mapping):
    """A Mapping whose ``items()`` gives the real values on the first call and NaN afterwards (31a C3's kind)."""

    def __init__(self, d: dict) -> None:
        self.d, self.n = d, 0

    def __getitem__(self, k):
        return self.d[k]

    def __iter__(self):
        return iter(self.d)

    def __len__(self) -> int:
        return len(self.d)

    def items(self):
        self.n += 1
        return [(k, v if self.n == 1 else float("nan")) for k, v in self.d.items()]


# ------------------------------------------------------------------------------------------------------------- B1
def test_plugin_study_refuses_deltas_beyond_the_crossing_range() -> None:
    from fusion.scenarios import ridge_sensors as rs

    kw = dict(xs=(0.0,), m=2, sigma=1.0, runs=2, seed=1, curve=(0.0,))
    for d in (8.5, 10.0, 2e8):
        with pytest.raises(ValueError, match=r"^deltas must hold tolerances of at most 8"):
            rs.plugin_study(**kw, deltas=(1.0, d))
    p = rs.plugin_study(**kw, deltas=(1.0, 8.0))  # the valid edge: plugin_exact computes it (c <= 8.29)
    assert p.deltas == (1.0, 8.0)
    from fusion.book.chapters.lecture_correlated import ridge

    with pytest.raises(ValueError, match=r"^p\.deltas must hold tolerances"):
        ridge.plugin_exact(dataclasses.replace(p, deltas=(1.0, 10.0), hits={1.0: p.hits[1.0], 10.0: p.hits[8.0]}))


# ------------------------------------------------------------------------------------------------------- B2, D3
def _foa_table(runs: float = 3) -> pd.DataFrame:
    """A table as ``fruit_fly_step_study`` makes it (its rows, columns and kinds of cells)."""
    from fusion.book.chapters.ci import fruit_fly_step as ff

    rows = (*ff.FRUIT_FLY_STEP_RULES, ff.EXHAUSTIVE)
    return pd.DataFrame({ff.CANDIDATES_BELOW: [0.654, 0.242, 0.1], ff.CANDIDATES_ABOVE: [0.013, 0.031, 0.5],
                         ff.MEDIAN_ERROR: [0.00192, 0.0032, 0.0], ff.LARGEST_ERROR: [0.00633, 0.0042, 0.0005],
                         ff.RUNS_WITHIN: [3, 3, 3], "runs": [runs] * 3}, index=list(rows))


def _check_field(name: str, value: object) -> object:
    from fusion.book.chapters.ci import claim_inputs as ci_in

    return _results._check(ci_in._LEDGER_FIELDS[name], value, f"LedgerInputs.{name}", {})


def _valid_cell(col: int, v: float) -> bool:
    """The producer's rule of a cell of :func:`_foa_table` (runs 3): shares and errors in [0, 1], whole counts,
    the runs within 0.05 at most the runs."""
    if not np.isfinite(v):
        return False
    if col < 4:
        return 0.0 <= v <= 1.0
    return v == round(v) and (0.0 <= v <= 3.0 if col == 4 else v >= 3.0)


@settings(max_examples=25, deadline=None)
@given(col=st_.integers(0, 5), row=st_.integers(0, 2),
       bad=st_.sampled_from([np.nan, np.inf, -np.inf, -1.0, 1.5, 2.0, 4.0, 1e300]))
def test_ledger_inputs_step_tables_check_their_cells(col: int, row: int, bad: float) -> None:
    from fusion.book.chapters.ci import claim_inputs as ci_in

    t = _foa_table().astype(float)
    t.iloc[row, col] = bad
    if _valid_cell(col, bad):
        return
    for name in ("fruit_fly_step_study", "fruit_fly_step_targets"):
        tab = t if name == "fruit_fly_step_study" else t.set_axis([0.1, 0.2, 0.5])
        with pytest.raises(ValueError, match=rf"^LedgerInputs\.{name}"):
            _check_field(name, tab)
            ci_in._foa_targets_relation({"fruit_fly_step_study": _foa_table(), "fruit_fly_step_targets": _foa_table(
                ).set_axis([0.1, 0.2, 0.5]), name: tab}, "LedgerInputs")


def test_ledger_inputs_step_tables_keep_valid_tables() -> None:
    assert _check_field("fruit_fly_step_study", _foa_table()) is not None
    assert _check_field("fruit_fly_step_targets", _foa_table().astype(float).set_axis([0.1, 0.2, 0.5])) is not None
    t = _foa_table()
    t["runs within 0.05 of the minimum"] = t["runs within 0.05 of the minimum"].astype(str)
    with pytest.raises(TypeError, match=r"^LedgerInputs\.fruit_fly_step_study\['runs within 0\.05"):
        _check_field("fruit_fly_step_study", t)
    h = pd.DataFrame({"ω found": [0.0, 0.5], "tr P": [10.0, np.inf]})
    with pytest.raises(ValueError, match=r"^LedgerInputs\.fig5_hyp\['tr P'\]"):
        _check_field("fig5_hyp", h)


def test_audit_result_refuses_counts_joint_audit_never_makes() -> None:
    from fusion.book.chapters import ofs_audit as oa

    row = {c: "x" for c in oa._TABLE_COLUMNS} | {oa.VALUES_EXPLAINED: 20}
    full = pd.DataFrame(columns=list(oa._FULL_COLUMNS))
    ok = oa.AuditResult(table=pd.DataFrame([row]), full=full, n_hypotheses=1, same_sets=pd.DataFrame())
    for bad in (np.inf, 27, 2.5, -1):
        t = pd.DataFrame([row | {oa.VALUES_EXPLAINED: bad}])
        with pytest.raises(ValueError, match=r"^AuditResult\.table\['values explained"):
            dataclasses.replace(ok, table=t)


# ------------------------------------------------------------------------------------------------------- B3, D1
def _js_table() -> pd.DataFrame:
    idx = pd.MultiIndex.from_tuples([(2, 0.0), (3, 0.0), (3, 1.0)], names=("d", "‖x‖/σ"))
    t = pd.DataFrame({"exact": [1.0, 2 / 3, 0.8], "Monte Carlo": [np.nan, 0.66, 0.81]}, index=idx)
    t.attrs["runs"] = 1000
    return t


def test_glue_james_stein_refuses_a_repeated_row_and_names_the_record() -> None:
    from fusion.book.chapters.lecture_correlated import appendix as ap

    tab = _js_table()
    assert ap.glue_james_stein(tab)["lec_js_min_3"] == pytest.approx(2 / 3)
    t2 = pd.concat([tab.iloc[1:2], tab])
    t2.attrs = dict(tab.attrs)
    with pytest.raises(ValueError, match=r"^tab holds the row \(3, 0\.0\) more than once"):
        ap.glue_james_stein(t2)
    for bad in (1000.0, "1000", True, 5):
        t3 = tab.copy()
        t3.attrs = {"runs": bad}
        with pytest.raises((TypeError, ValueError), match=r"^tab\.attrs\['runs'\]"):
            ap.glue_james_stein(t3)


def test_appendix_glue_readers_count_each_row_once() -> None:
    from fusion.book.chapters.lecture_correlated import appendix as ap

    seq = pd.DataFrame({ap.M_LARGEST: [0.0, 0.0], ap.VS_BATCH: ["less than 1e-12", "less than 1e-12"],
                        "multiplications": [0, 3], ap.FULL_M: [9, 9]}, index=["sensor 1", "sensor 2"])
    assert ap.glue_sequential(seq)["lec_seq_n"] == 2
    with pytest.raises(ValueError, match=r"^tab holds the row 'sensor 1' more than once"):
        ap.glue_sequential(pd.concat([seq.iloc[:1], seq]))
    LS = ap.METHOD_SHORT_LABELS[ap.LS]
    sh = pd.DataFrame({ap.BEST_RIDGE: [1.0, 2.0], ap.BEST_SCALED_LS: [1.5, 1.0], LS: [3.0, 3.0]}, index=["a", "b"])
    assert ap.glue_shrunken(sh)["lec_sh_n"] == 2
    with pytest.raises(ValueError, match=r"^tab holds the row 'a' more than once"):
        ap.glue_shrunken(pd.concat([sh.iloc[:1], sh]))


# ------------------------------------------------------------------------------------------------------- B4, D2
def _keeps():
    from fusion.book.chapters import lecture_correlated as lc
    from fusion.book.chapters.lecture_correlated import records as rr
    from fusion.book.chapters.time_registration_ledger import values as lg

    return ((lc.keep, sorted(rr.GLUED)[0]), (lg.keep, "reg_any"))


def test_keep_reads_values_once() -> None:
    for keep, key in _keeps():
        store: dict = {}
        out = keep(store, FlipMap({key: 1.5}))
        assert store == {key: 1.5} and dict(out) == {key: 1.5}


def test_keep_stores_a_0d_array_as_its_number() -> None:
    for keep, key in _keeps():
        store: dict = {}
        a = np.array(2.5)
        keep(store, {key: a})
        a[()] = np.nan
        assert store[key] == 2.5 and type(store[key]) is float
        plain = {key: 1.25}
        assert keep({}, plain) == plain


# ------------------------------------------------------------------------------------------------------------ D4
def test_manoeuvre_values_refuses_another_noise_level() -> None:
    from fusion.book.chapters import time_registration as ch
    from fusion.book.chapters.time_registration_ledger import values as lg
    from fusion.scenarios import time_registration as sc

    man = {a: {n: sc.expected(n, 1.0, a_after=a) for n in (ch.IMPROVED, ch.TWO, sc.RegMethod.THREE_POINT)}
           for a in (0.0, -2.0)}
    assert lg.manoeuvre_values(man, 1.0)["reg_man_impr"] == man[0.0][ch.IMPROVED]
    with pytest.raises(ValueError, match=r"^manoeuvre\[0\.0\]\['reg_improved'\] = .* not the exact E\[MSE\] at sigma"):
        lg.manoeuvre_values(man, 1.1)


# ------------------------------------------------------------------------------------------------------------ D5
def test_chapter03_studies_checked_by_their_recorded_setup() -> None:
    from fusion.book.chapters.lecture_wavelets import records as wr
    from fusion.scenarios import wavelet_sensors as ws

    one = dict(signals=(ws.Signal.TWO_TONES,), modes=("soft",), runs=2, length=64)
    g1 = ws.signal_study(normalisers=("max", "max-raw"), gains=(1, 1, 1, 1), **one)
    sg = ws.signal_study(normalisers=("max", "max-raw", "median"), **one)
    e26 = ws.signal_study(normalisers=("max", "median", "lsq"), **one)
    v = dict(length=64, runs=2, window=8)
    v26, v1 = ws.variance_study(**v), ws.variance_study(gains=(1, 1, 1, 1), **v)
    v1r = ws.variance_study(gains=(1, 1, 1, 1), normaliser="max-raw", **v)
    m26 = ws.mechanism_study(length=64, runs=2, configs=ws.CONFIGS[:1])
    st = {"sg": sg, "m26": m26, "v26": v26, "g1": g1, "e26": e26, "v1": v1, "v1r": v1r}
    assert wr._need(st) == 2
    assert wr._need({**st, "e26": ws.signal_study(normalisers=("max",), **one)}) == 2  # the normalisers it reads
    for key, other in (("v26", v1), ("sg", g1), ("g1", sg), ("e26", g1), ("v1", v1r), ("v1r", v26)):
        with pytest.raises(ValueError, match=rf"^st\['{key}'\] must be study\('{key}'\)"):
            wr._need({**st, key: other})


def test_chapter02_e23_studies_checked_by_their_x() -> None:
    from fusion.book.chapters.lecture_weighting import study_evidence as se
    from fusion.scenarios.lecture_weighting import consistency as c

    kw = dict(sigma=(0.5, 1.0, 1.5), samples=100, runs=2, seed=1, curve_draws=10)
    s0 = c.consistency_study(x=0.0, **kw)
    se._need({"s23": dataclasses.replace(s0, x=900.0)}, "s23")
    with pytest.raises(ValueError, match=r"^st\['s23'\] must be study\('s23'\), E2\.3 at X = 900"):
        se._need({"s23": s0}, "s23")
    with pytest.raises(ValueError, match=r"^st\['s23x0'\] must be study\('s23x0'\)"):
        se._level_x0({"s23": s0, "s23x0": dataclasses.replace(s0, x=900.0)})


def test_chapter04_vector_cases_checked_by_their_condition() -> None:
    from fusion.book.chapters.lecture_correlated import records as rr

    ill, well = types.SimpleNamespace(cond=2646.0), types.SimpleNamespace(cond=15.9)
    rr._conditioning_relation({"v25": ill, "v25_well": well}, "Studies")
    for a, b in ((well, ill), (well, well)):
        with pytest.raises(ValueError, match=r"^Studies\.v25 must be the ill-conditioned"):
            rr._conditioning_relation({"v25": a, "v25_well": b}, "Studies")
    assert any(getattr(r, "__code__", None) and "_conditioning_relation" in r.__code__.co_names
               for r in rr.Studies.__result_spec__.relations)


# ------------------------------------------------------------------------------------------------------------ D6
def test_by_design_underflow_runs_under_a_callers_errstate() -> None:
    from fusion.book.chapters import ofs_support
    from fusion.estimates import mixtures as mx
    from fusion.readings import fusion_set

    t1 = np.array([[0.0, 1.0, 60.0], [0.5, 1.5, 61.0]])
    with np.errstate(under="raise"):
        kernel = next(k for k in ofs_support.SUPPORT_KERNELS if k.startswith("Gaussian"))
        assert np.isfinite(ofs_support.support_values(t1, kernel, ofs_support.SUPPORT_AGGREGATIONS[0], [1.0])).all()
        assert float(mx.logsumexp(np.array([0.0, -1000.0]))) == pytest.approx(0.0)
        assert np.isfinite(fusion_set.fusion_degree_matrix(np.array([0.0, 1.0, 800.0]))).all()
