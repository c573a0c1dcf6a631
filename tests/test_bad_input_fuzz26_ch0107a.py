"""Fuzz 26d, class A and the debatable DB1 (issue 35; chapters 02-04): a chapter function given a valid study made at
other valid settings.

The rule of the class (one helper, ``fusion.book.chapters.lecture._holds``): a chapter function reads what it needs
from the study by key (a level, a setting of n sensors, a change, a case, a sensor, a problem size), never by
position or by the default setting's value; a study that does not hold it is refused by a ValueError naming the
argument and what it lacks. Before: KeyError/IndexError from inside, an unnamed ValueError, or a plausible number of
another row glued (``glue_22`` read "5 sensors" as row 3, ``glue_changes`` named the changes by position,
``glue_24`` subtracted a hard-coded 900, ``glue_coupling`` numbered the cases by the study's order).
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from fusion.book.chapters import lecture_correlated as ch4  # noqa: E402
from fusion.book.chapters import lecture_weighting as ch2  # noqa: E402
from fusion.book.chapters.lecture import _holds  # noqa: E402
from fusion.book.chapters.lecture_wavelets import mechanism as mech  # noqa: E402
from fusion.book.chapters.lecture_wavelets import variance as wvar  # noqa: E402
from fusion.scenarios import correlated_sensors as cs  # noqa: E402
from fusion.scenarios import lecture_correlated as lsc  # noqa: E402
from fusion.scenarios import lecture_weighting as lw  # noqa: E402
from fusion.scenarios import wavelet_sensors as ws  # noqa: E402
from fusion.scenarios.lecture_weighting.regime import VARIANCE_CHANGES  # noqa: E402

sys.path.insert(0, str(Path(__file__).parent))

THREE = dict(gains=(1.0, 1.5, 0.8), sigma=(0.05, 0.1, 0.2))   # a valid wavelet study of three sensors


def _refused(call, name: str) -> str:
    with pytest.raises(ValueError) as exc:
        call()
    assert str(exc.value).startswith(name + " "), exc.value
    return str(exc.value)


def test_holds_names_the_argument_and_what_it_lacks() -> None:
    _holds((0.0, 100.0), (0.0,), "s", "levels", "f")          # held: no error
    msg = _refused(lambda: _holds((0.0,), (0.0, 100.0), "s", "levels", "f"), "s")
    assert "[100.0]" in msg and "f reads" in msg


# ---- E2.1: the levels the figures and the guard table read ---------------------------------------------------------

def test_figure_21a_refuses_a_study_without_the_band_at_100() -> None:
    """The bands are the study's levels among 0 and 100 (``mse``/``sq`` are always at 0 and 900)."""
    s = lw.awf_study(levels=(0.0, 900.0), runs=5, k_max=100, ks=(10, 100), k_compare=100)
    assert "levels X of s.band [100.0]" in _refused(lambda: ch2.figure_21a(s), "s")


# ---- E2.2: the settings of 5 and 2 sensors, by size --------------------------------------------------------------

@settings(max_examples=8, deadline=None)
@given(st.permutations(range(3)), st.lists(st.floats(0.1, 50.0), min_size=5, max_size=5),
       st.lists(st.floats(0.1, 50.0), min_size=2, max_size=2))
def test_glue_22_reads_the_settings_by_their_number_of_sensors(order, r5, r2) -> None:
    """lec_ls_r5_* / lec_ls_r2_* are the 5- and the 2-sensor settings' (exact min Rᵢ and optimal variance) in any
    order of r_sets (they were rows 3 and 0: the default order's)."""
    sets = [tuple(r5), tuple(r2), (1.0, 2.0, 4.0)]
    s = lw.learning_study(r_sets=[sets[i] for i in order], epochs=20, runs=5, last=10)
    g = ch2.glue_22(s)
    assert g["lec_ls_r5_min"] == pytest.approx(min(r5), abs=6e-5)
    assert g["lec_ls_r2_min"] == pytest.approx(min(r2), abs=6e-5)
    assert g["lec_ls_r5_opt"] == pytest.approx(1 / sum(1 / np.array(r5)), abs=6e-5)


def test_learning_glues_refuse_a_study_without_their_settings() -> None:
    two = lw.learning_study(r_sets=((1.0, 4.0),), epochs=20, runs=5, last=10)
    assert "settings of n sensors [5]" in _refused(lambda: ch2.glue_22(two), "s")
    _refused(lambda: ch2.glue_learning_check(lw.learned_limit_check(draws=20), two), "s22")


# ---- E2.4: sensor 4 and the study's own true value ---------------------------------------------------------------

@settings(max_examples=5, deadline=None)
@given(st.floats(-1e4, 1e4))
def test_glue_24_offsets_are_from_the_study_true_value(x) -> None:
    """The draws are the same at any x (shifted): the offsets glued do not depend on x (a hard-coded 900 before:
    -891.92 at x = 0 for sensor 4's +8.08)."""
    a, b = ch2.glue_24(lw.belief_study(snapshots=200)), ch2.glue_24(lw.belief_study(x=x, snapshots=200))
    for key in ("lec_bel_s4_offset", "lec_bel_fused_d0", "lec_bel_fused_peak"):
        assert b[key] == pytest.approx(a[key], abs=0.0101), key


def test_glue_24_refuses_a_study_without_sensor_4() -> None:
    assert "sensor [4]" in _refused(lambda: ch2.glue_24(lw.belief_study(sigma=(0.5, 1.0, 2.0), snapshots=200)), "s")


# ---- E2.1c: X = 0, where the antithetic pairs cancel exactly ------------------------------------------------------

def test_glue_lumv_refuses_a_study_whose_pairs_cancel_exactly() -> None:
    assert ch2.glue_lumv(lw.lumv_study(runs=100))["lec_lumv_runs"] == 100
    _refused(lambda: ch2.glue_lumv(lw.lumv_study(x=0.0, runs=100)), "sl")


# ---- E2.1b: the changes by their keys ----------------------------------------------------------------------------

@settings(max_examples=4, deadline=None)
@given(st.permutations(range(3)))
def test_glue_changes_names_each_change_by_its_key(order) -> None:
    """The same draws for every change (one seed): any order of ``changes`` glues the same values under the same
    keys (by position before: the improvement's MSE glued as the swap's)."""
    kw = dict(samples=20, runs=100, change_at=10)
    want = ch2.glue_changes(lw.variance_change_study(**kw))
    got = ch2.glue_changes(lw.variance_change_study(**kw, changes=[VARIANCE_CHANGES[i] for i in order]))
    assert got == want


def test_glue_changes_refuses_a_study_without_a_change() -> None:
    s = lw.variance_change_study(samples=20, runs=100, change_at=10, changes=VARIANCE_CHANGES[1:])
    assert "lec_chg_swap" in _refused(lambda: ch2.glue_changes(s), "s")


# ---- chapter 04 --------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("kw", [dict(xs=(1.0, 10.0)), dict(xs=(0.5, 1.0, 3.0)), dict(ks_fixed=(1.0,)),
                                dict(ks_fixed=(0.1, 1.0))])
def test_glue_25_refuses_a_study_without_its_xs_or_ks(kw) -> None:
    s = lsc.ridge_study(draws=2, **kw)
    _refused(lambda: ch4.glue_25(s), "s")


def test_glue_25_reads_x_far_by_key_and_ridge_study_refuses_x_far_among_xs() -> None:
    """x_far is the study's, not its largest x (an x of 1000 was read as x_far)."""
    want = ch4.glue_25(lsc.ridge_study(draws=2))["lec_rg_relk001_far"]
    assert ch4.glue_25(lsc.ridge_study(xs=(0.5, 1.0, 3.0, 10.0, 1000.0), draws=2))["lec_rg_relk001_far"] == want
    _refused(lambda: lsc.ridge_study(x_far=10.0, draws=2), "x_far")


def test_glue_27_refuses_a_study_without_size_600() -> None:
    assert "[600]" in _refused(lambda: ch4.glue_27(lsc.correlated_study(runs=2, sizes=(6, 60))), "s")


@pytest.mark.parametrize("ds, ratios", [((3,), (1.0,)), ((2,), (0.0, 1.0)), ((3, 5), (1.0, 3.0))])
def test_glue_james_stein_refuses_a_table_without_its_rows(ds, ratios) -> None:
    tab = ch4.table_james_stein(ds=ds, ratios=ratios, runs=100, seed=3)
    _refused(lambda: ch4.glue_james_stein(tab, 100), "tab")


def test_glue_coupling_numbers_the_cases_by_their_keys() -> None:
    """Case j is SCENARIOS' j-th whatever the study's order (the exact values; the Monte-Carlo ones are the study's
    draws); a study without one of the cases is refused naming s."""
    want = ch4.glue_coupling(cs.coupling_study(runs=100))
    got = ch4.glue_coupling(cs.coupling_study(dict(reversed(list(cs.SCENARIOS.items()))), runs=100))
    for j in range(1, 6):
        for key in ("ratio", "minw", "peak", "peak_env", "far"):
            assert got[f"lec_cc2_{key}_{j}"] == want[f"lec_cc2_{key}_{j}"], (key, j)
    one = cs.coupling_study({cs.CouplingCase.EQUAL: cs.SCENARIOS[cs.CouplingCase.EQUAL]}, runs=100)
    _refused(lambda: ch4.glue_coupling(one), "s")


def test_ledger_evidence_refuses_a_wide_study_without_the_wide_case() -> None:
    import test_bad_input_calls_ch0204 as reg

    st_ = reg._ch04()["st"]
    bad = dataclasses.replace(st_, cpl_wide=cs.coupling_study({cs.CouplingCase.EQUAL: cs.SCENARIOS[cs.CouplingCase.EQUAL]},
                                                              runs=100))
    _refused(lambda: ch4.ledger_evidence(bad), "st.cpl_wide")


# ---- chapter 03: sensor 4 of the wavelet studies ----------------------------------------------------------------

def test_wavelet_readers_of_sensor_4_refuse_three_sensors_the_others_read_them() -> None:
    m = ws.mechanism_study(runs=100, **THREE)
    for fn in (mech.table_sensitivity, mech.table_sensitivity_display):
        assert "sensor [4]" in _refused(lambda: fn(m), "m")
    mech.figure_mechanism(m)                                      # sensor 1's columns and every sensor's curve
    assert mech.glue_mechanism(m)["lec_wm_n_cfg"] == len(m.labels)
    v = ws.variance_study(runs=100, **THREE)
    assert "sensor [4]" in _refused(lambda: wvar.glue_variance(v), "v")
