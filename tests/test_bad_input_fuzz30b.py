"""Fuzz 30b (issue 35), cases B1-B5, D1 and D3 (report /work/tmp/fuzz30b/report.md).

B1-B5, one class: entries that differ (``distinct`` accepts them) but print alike in the format that keys a result
(``f"{x:g}"``, ``round(x, 6)``) merged silently, the last one winning. The shared rule,
``fusion._counts.distinct_printed`` (and ``dict_of(..., printed=...)`` for result fields), refuses them by the
caller's argument where the study is made, and in the result's spec for results rebuilt by ``dataclasses.replace``.
D1: a float32 pandas Series of periods is read as its array (``_period_key``).
D3: a label template giving two methods one label, an empty label or a control character is refused.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion.book.chapters import ci
from fusion.book.chapters import time_registration as ch
from fusion.book.chapters.ci.constants import W_GRID, W_PUB
from fusion.book.chapters.ci.paired import PairedClaimInputs
from fusion.book.chapters.lecture_weighting import estimators as es
from fusion.book.chapters.ofs import readings as ofs_readings
from fusion.book.chapters.time_registration_ledger import studies as lg
from fusion.scenarios import ridge_sensors as rs
from fusion.scenarios import time_registration as trs
from fusion.scenarios.lecture_correlated import ridge_study
from fusion.scenarios.lecture_weighting import belief as scb
from fusion.scenarios.lecture_weighting import estimators as sce
from fusion.scenarios.lecture_weighting import readings_benchmark as srb
from fusion.scenarios.two_sensor import QScaling, q_scaling_study

FEW = settings(settings.get_profile("fusion"), max_examples=15)


def _alike(x: float, rel: float) -> float:
    """A float other than ``x`` that prints as ``x`` does with ``:g`` (6 significant digits; ``x`` is read as it
    prints, so that ``y`` is far from a rounding boundary)."""
    x = float(f"{x:g}")
    y = x * (1.0 + rel)
    assert y != x and f"{y:g}" == f"{x:g}"
    return y


# --------------------------------------------------------------------------- B1: delay_table
@FEW
@given(st.floats(0.1, 100.0), st.sampled_from([1e-9, 1e-8, 4e-7]))
def test_delay_table_refuses_sigmas_printed_alike(s, rel):
    with pytest.raises(ValueError, match=r"^sigmas .*sigmas\[0\] and sigmas\[1\] print the same"):
        ch.delay_table([0.01], [float(f"{s:g}"), _alike(s, rel)])


def test_delay_table_refuses_delays_labelled_alike():
    with pytest.raises(ValueError, match=r"^delays .*delays\[0\] and delays\[1\]"):
        ch.delay_table([0.01, 0.0100000004], [1.0])


def test_delay_table_keeps_distinct_labels():
    t = ch.delay_table([0.01, 0.0100001], [1.0, 1.00001])  # 10 and 10.0001 ms; 1 and 1.00001 m: distinct
    assert t.shape == (2, 2)


# --------------------------------------------------------------------------- B2: tail thresholds
def test_tail_study_refuses_thresholds_printed_alike():
    with pytest.raises(ValueError, match=r"^thresholds .*thresholds\[0\] and thresholds\[1\]"):
        sce.tail_study(runs=100, chunk=100, thresholds=(10.0, 10.000001, 100.0))


def test_glue_tail_refuses_a_rebuilt_study_with_thresholds_printed_alike():
    tl = sce.tail_study(runs=100, chunk=100, k=2, thresholds=(10.0, 20.0, 100.0))
    assert {"lec_tail_p_10", "lec_tail_p_20", "lec_tail_p_100"} <= set(es.glue_tail(tl))
    bad = dataclasses.replace(tl, t=np.array([10.0, 10.000001, 100.0]))
    with pytest.raises(ValueError, match=r"^tl\.t "):
        es.glue_tail(bad)


# --------------------------------------------------------------------------- B3: chapter 05 keys printed f"{x:g}"
def _paired(**kw: object) -> PairedClaimInputs:
    r = np.linspace(1.0, 2.0, 4)
    fields = dict(paired={"a": r}, paired_runs=4, paired_seed=0, paired_unequal={"a": r}, unequal_seed=1,
                  paired_random=r, random_seed=2, paired_aniso={"a": r}, paired_fig6={W_PUB: r, W_GRID: r},
                  fuzzy_levels={0.001: r, 0.05: r})
    return PairedClaimInputs(**{**fields, **kw})


def test_ledger_fields_refuse_levels_printed_alike():
    r = np.linspace(1.0, 2.0, 4)
    _paired()  # the valid one is built
    with pytest.raises(ValueError, match=r"fuzzy_levels must differ in how its entries print"):
        _paired(fuzzy_levels={0.001: r, 0.0010000001: 3 * r, 0.05: r})


def test_periods_refused_printed_alike():
    with pytest.raises(ValueError, match=r"^periods .*periods\[0\] and periods\[1\]"):
        ci.pcrb_table([0.02, 0.0200000001], 150.0, 10.0)


def test_q_scaling_refuses_scales_printed_alike():
    with pytest.raises(ValueError, match=r"^scales .*scales\[1\] and scales\[2\]"):
        q_scaling_study(np.random.default_rng(0), np.eye(2), np.eye(2), np.eye(4), (1.0, 0.5, 0.5000001), runs=2,
                        nees_runs=2)


def test_q_scaling_result_refuses_scales_printed_alike():
    r = np.linspace(1.0, 2.0, 3)
    ok = dict(scales=(1.0, 0.5), run_rmse={1.0: r, 0.5: r}, model_rmse={1.0: r, 0.5: r}, nees={1.0: 4.0, 0.5: 4.0},
              runs=3, nees_runs=3)
    qs = QScaling(**ok)
    c = 0.5000001
    with pytest.raises(ValueError, match=r"QScaling\.run_rmse must differ in how its entries print"):
        dataclasses.replace(qs, scales=(1.0, 0.5, c), run_rmse={**qs.run_rmse, c: r},
                            model_rmse={**qs.model_rmse, c: r}, nees={**qs.nees, c: 4.0})


# --------------------------------------------------------------------------- D1: a float32 Series of periods
def test_pcrb_table_reads_a_float32_series_as_its_array():
    p = np.array([1.0, 0.02, 0.001], np.float32)
    assert ci.pcrb_table(pd.Series(p), 150.0, 10.0).equals(ci.pcrb_table(p, 150.0, 10.0))


# --------------------------------------------------------------------------- B5 and the other chapter 04 keys
def test_vector_study_refuses_scales_printed_alike():
    with pytest.raises(ValueError, match=r"^scales .*scales\[0\] and scales\[1\]"):
        rs.vector_study(runs=2, scales=(3.0, 3.0000001, 30.0))


def test_vector_study_result_refuses_keys_printed_alike():
    v = rs.vector_study(runs=2, scales=(3.0, 30.0))
    k = ("strong direction", 3.0)
    assert k in v.sq
    k2 = (k[0], 3.0000001)
    with pytest.raises(ValueError, match=r"VectorStudy\.sq must differ in how its entries print"):
        dataclasses.replace(v, sq={**v.sq, k2: v.sq[k]}, x={**v.x, k2: v.x[k]})


@pytest.mark.parametrize("kw, name", [({"xs": (1.5, 15.0)}, "xs"), ({"deltas": (1.0, 0.5, 0.50000001)}, "deltas")])
def test_plugin_study_refuses_entries_printed_alike(kw, name):
    with pytest.raises(ValueError, match=rf"^{name} must differ in how its entries print"):
        rs.plugin_study(runs=2, **kw)


def test_ridge_study_refuses_fixed_ks_printed_alike():
    with pytest.raises(ValueError, match=r"^ks_fixed must differ in how its entries print"):
        ridge_study(ks_fixed=(0.1, 0.10000001))


# --------------------------------------------------------------------------- chapter 02 and 03 keys
def test_belief_parameter_study_refuses_params_printed_alike():
    with pytest.raises(ValueError, match=r"^params must differ in how its entries print"):
        scb.belief_parameter_study(params=(1.0, 1.0000001, 2.0), grid=(1.0, 2.0))


def test_benchmark_refuses_levels_printed_alike():
    with pytest.raises(ValueError, match=r"^levels must differ in how its entries print"):
        srb.benchmark(levels=(900.0, 900.0001))


def test_alpha_methods_keeps_its_rule():
    assert len(ofs_readings.alpha_methods((0.5, 0.50001))) == 3
    with pytest.raises(ValueError, match=r"^alphas must differ in how its entries print"):
        ofs_readings.alpha_methods((0.5, 0.5000001))


# --------------------------------------------------------------------------- chapter 07 ledger study's levels
def test_registration_study_refuses_a_sigma_printed_as_the_fair_level():
    t1, t2 = trs.instants()
    with pytest.raises(ValueError, match=r"^sigma must be 0\.1 m or differ"):
        lg.study(t1, t2, 0.1000001, 1, 0)


# --------------------------------------------------------------------------- D3: labels of a template
@pytest.mark.parametrize("template", ["{:.0}", "{:.1}", "{}\x00", "\u202e{}", "{:\x00>30}"])
def test_labelled_refuses_templates_that_merge_or_hide_labels(template):
    table = pd.DataFrame({"x": [1.0, 2.0]}, index=list(trs.METHODS)[:2])
    with pytest.raises(ValueError, match=r"^template (makes|gives) "):
        ch.labelled(table, template)


@pytest.mark.parametrize("template", ["{}", "fused, {}", "{:>30}", "{:.30}"])
def test_labelled_keeps_distinct_labels(template):
    table = pd.DataFrame({"x": [1.0, 2.0]}, index=list(trs.METHODS)[:2])
    assert ch.labelled(table, template).index.nunique() == 2
