"""Fuzz 34b (chapter layer): the cases B1-B8 and D1-D3 of /work/tmp/fuzz34b/report.md, fixed by class.

* B1-B7 (one class): a reader that needs a particular key or setting of a valid but partial study checks it first
  and refuses by the caller's argument name (``fusion.book.chapters.lecture._holds``, or ``required=`` on the
  frozen result's field spec), never a KeyError or StopIteration from inside; float32 weights of
  ``PrintedWeightFacts.trace`` are read as they print.
* B8: a conjunction a record builds from a study's cases names the study (``st.p25``, ``st.s25``) when it has fewer
  than two (``lecture._members``), not the Conjunction's inner ``parts``.
* D1: ``glue_mechanism`` / ``figure_mechanism`` key the "hard" glue and the solid curves by the first hard setting.
* D2 (decided: documented): a default argument a small study cannot serve is refused naming that parameter.
* D3: ``glue_part(-0.0)`` is ``'0'``, as for 0.0.
"""

from __future__ import annotations

import dataclasses
import types
import warnings

import numpy as np
import pytest

HARD = {"wavelet": "db4", "level": 4, "threshold": "universal", "mode": "hard"}
SOFT = {**HARD, "mode": "soft"}


def _mechanism(configs):
    from fusion.scenarios import wavelet_sensors as ws

    with warnings.catch_warnings():  # pywt: level 4 of a 256-sample db4 transform has boundary effects
        warnings.simplefilter("ignore", UserWarning)
        return ws.mechanism_study(length=256, runs=100, configs=configs)


# ------------------------------------------------------------------------------------------------------- B1, D1
def test_mechanism_readers_name_m_without_a_soft_or_hard_setting() -> None:
    from fusion.book.chapters.lecture_wavelets import mechanism as mech

    for configs, lacking in (((HARD,), "soft"), ((SOFT,), "hard")):
        m = _mechanism(configs)
        for f in (mech.glue_mechanism, mech.figure_mechanism):
            with pytest.raises(ValueError, match=rf"^m lacks the threshold modes .*'{lacking}'.* {f.__name__} reads"):
                f(m)


def test_glue_mechanism_keys_hard_by_the_first_hard_setting() -> None:
    from fusion.book.chapters.lecture_wavelets import mechanism as mech

    g_hs = mech.glue_mechanism(_mechanism((HARD, SOFT)))
    g_sh = mech.glue_mechanism(_mechanism((SOFT, HARD)))
    for key in ("lec_wm_h_rms_bias_1", "lec_wm_s_rms_bias_1", "lec_wm_h_corr12"):
        assert g_sh[key] == g_hs[key]
    assert g_sh["lec_wm_h_rms_bias_1"] != g_sh["lec_wm_s_rms_bias_1"]


def test_table_mechanism_default_labels_beyond_a_small_study_name_labels() -> None:
    """D2 (fuzz 35d: fixed): a default the study cannot serve is refused naming the study, the default and its bound."""
    from fusion.book.chapters.lecture_wavelets import mechanism as mech

    m = _mechanism((HARD, SOFT))
    with pytest.raises(ValueError, match=r"^m does not fit table_mechanism's default labels = \(0, 6\) "
                                         r"\(labels\[1\] must be an index below 2, got 6\)"):
        mech.table_mechanism(m)
    assert len(mech.table_mechanism(m, labels=(0, 1))) == 2 * m.gains.size


# ----------------------------------------------------------------------------------------------------------- B2
def _printed(trace):
    from fusion.book.chapters.ci.printed import PrintedWeightFacts
    from fusion.scenarios.two_sensor import FruitFlySeeds

    ff = FruitFlySeeds(seeds=np.array([1]), fruit_fly_x=np.array([0.5]), fruit_fly_fun=np.array([1.0]), grid_x=0.5,
                       grid_fun=1.0, rtol=1e-6)
    return PrintedWeightFacts(ones=1, steps=1, fruit_fly=ff, monotone=True, trace_ratio=2.0, trace=trace)


def test_ledger_inputs_require_the_trace_weights_their_readers_read() -> None:
    from fusion.book.chapters.ci import claim_inputs

    full = {0.0018: 1.07e6, 0.0033: 5.9e5, 1.0: 7553.0}
    assert _printed(full).trace == full and _printed({}).trace == {}  # the facts alone: any weights (printed_numbers)
    claim_inputs._trace_relation({"printed": _printed(full)}, "LedgerInputs")
    for w in full:
        with pytest.raises(ValueError, match=rf"^LedgerInputs\.printed\.trace misses the weights \[{w:g}"):
            claim_inputs._trace_relation({"printed": _printed({k: v for k, v in full.items() if k != w})},
                                         "LedgerInputs")
    pf = _printed({np.float32(k): v for k, v in full.items()})  # float32 weights read as they print
    assert pf.trace[0.0018] == full[0.0018] and all(type(k) is float for k in pf.trace)
    claim_inputs._trace_relation({"printed": pf}, "LedgerInputs")


# ----------------------------------------------------------------------------------------------------------- B3
def test_ledger_slip_weights_require_the_published_weights() -> None:
    from fusion import _results
    from fusion.book.chapters import ci

    spec = ci.LedgerInputs.__result_spec__.fields["slip_weights"]
    ok = {0.0018: (4.7, 4.8), 0.0033: (4.6, 4.9), 0.5: (1.0, 2.0)}
    assert set(_results._check(spec, ok, "LedgerInputs.slip_weights", {})) == set(ok)
    for sw, lacking in (({0.5: (1.0, 2.0)}, r"0\.0018, 0\.0033"), ({0.0033: (4.7, 4.8)}, r"0\.0018"),
                        ({0.0018: (4.7, 4.8)}, r"0\.0033")):
        with pytest.raises(ValueError, match=rf"^LedgerInputs\.slip_weights misses the keys \[{lacking}\]"):
            _results._check(spec, sw, "LedgerInputs.slip_weights", {})


# ----------------------------------------------------------------------------------------------------------- B4
def test_plugin_exact_known_requires_tolerance_one() -> None:
    from fusion.book.chapters.lecture_correlated import ridge
    from fusion.scenarios import ridge_sensors as rsn

    p = rsn.plugin_study(xs=(0.0, 1.0), runs=200, deltas=(1.0, 2.0))
    x = ridge.plugin_exact(p)
    assert set(dataclasses.replace(x, known={1.0: x.known[1.0]}).known) == {1.0}
    with pytest.raises(ValueError, match=r"^PluginExact\.known misses the keys \[1\.0\]"):
        dataclasses.replace(x, known={2.0: x.known[2.0]})


# ----------------------------------------------------------------------------------------------------------- B5
def test_mechanism_study_requires_the_periods_its_glue_reads() -> None:
    m = _mechanism((HARD, SOFT))
    assert 64 in m.bias_share_period and {64, 256} <= set(m.tone_bands)
    for field, keep, lacking in (("bias_share_period", 256, 64), ("tone_bands", 64, 256), ("tone_bands", 256, 64)):
        with pytest.raises(ValueError, match=rf"^MechanismStudy\.{field} misses the keys \[{lacking}\]"):
            dataclasses.replace(m, **{field: {keep: getattr(m, field)[keep]}})


# ----------------------------------------------------------------------------------------------------------- B6
@pytest.mark.parametrize(("levels", "lacking"), [((0.0, 300.0), r"900"), ((100.0, 900.0), r"0")])
def test_ev_awf_unbiased_names_s21_at_other_levels(levels, lacking) -> None:
    from fusion.book.chapters.lecture_weighting import study_evidence as se
    from fusion.scenarios import lecture_weighting as lw

    s21 = lw.awf_study(levels=levels, k_max=100, runs=100, ks=(10, 100), seed=5)
    with pytest.raises(ValueError, match=rf"^st\['s21'\] lacks the levels X .*\[{lacking}\.0\] that ev_awf_unbiased"):
        se.ev_awf_unbiased({"s21": s21})


# ----------------------------------------------------------------------------------------------------------- B7
def test_ir_reading_numbers_names_readings_without_scaled_x() -> None:
    from fusion.book.chapters import ci
    from fusion.scenarios import infrared_radar as irr

    rd = ci.ir_readings(0.5, 1, 1, duration=1.0, t_min=0.5, scaled_axes=("y",))
    with pytest.raises(ValueError, match=r"^readings lacks the readings .*scaled_axes must include 'x'.* "
                                         r"ir_reading_numbers reads"):
        ci.ir_reading_numbers(rd, rd.sims["x"], irr.rmse_by_rule(rd.sims["x"]))


# ----------------------------------------------------------------------------------------------------------- B8
def test_members_names_the_study_with_fewer_than_two_cases() -> None:
    from fusion.book.chapters.lecture import _members
    from fusion.book.ledger import Conjunction, Proposition

    parts = [("a", Proposition(True, "a")), ("b", Proposition(True, "b"))]
    assert isinstance(_members(parts, "st.p25", "x", "r"), Conjunction)
    with pytest.raises(ValueError, match=r"^st\.p25 must hold at least two positive x, which r reads"):
        _members(parts[:1], "st.p25", "positive x", "r")


def test_ridge_variance_names_st_s25_of_one_fixed_k() -> None:
    from fusion.book.chapters.lecture_correlated import records
    from fusion.scenarios import lecture_correlated as lcs

    s25 = lcs.ridge_study(draws=200, ks_fixed=(0.1,))
    st = types.SimpleNamespace(s25=s25, x25=None)
    with pytest.raises(ValueError, match=r"^st\.s25 must hold at least two fixed ridge parameters"):
        records._ev_ridge_variance(st)


# ----------------------------------------------------------------------------------------------------------- D3
def test_glue_part_of_negative_zero_is_zero() -> None:
    from fusion._counts import glue_part

    for z in (-0.0, np.float32(-0.0), np.float64(-0.0), 0.0, 0):
        assert glue_part(z) == "0"
    assert glue_part(-1.5) == "m15" and glue_part((-0.0, -2)) == ("0", "m2")
