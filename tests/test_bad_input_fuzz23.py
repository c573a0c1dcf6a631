"""Fuzz 23 (regressions of the fuzz 21-22 fixes): valid input the new checks refused.

F2: the source's own failure constant, ``fusion.data.YANG2012_FAILURE``, is read-only since the constants rule
(``fusion._frozen.constant``) and must still be taken where a failure mapping is documented. F1: ``sim``'s own RMSE
stored as float32 is ``sim``'s (the check's tolerance is float32's), another simulation's is still refused.
"""

from __future__ import annotations

import numpy as np
import pytest

from fusion import data
from fusion.book.chapters import ci
from fusion.scenarios import infrared_radar as ir
from fusion.scenarios import thermocouples as tc

_OFS = {"ofs": {"method": "optimal_fusion_set"}}


def test_f2_paired_study_takes_the_source_failure_constant() -> None:
    a = tc.paired_study(3, 3, _OFS, failure=data.YANG2012_FAILURE)
    b = tc.paired_study(3, 3, _OFS, failure=dict(data.YANG2012_FAILURE))
    for key in a.__dataclass_fields__:   # every field: arrays, mappings of arrays, numbers
        va, vb = getattr(a, key), getattr(b, key)
        np.testing.assert_equal(dict(va) if hasattr(va, "keys") else va, dict(vb) if hasattr(vb, "keys") else vb)


def test_f2_scale_sweep_takes_the_source_failure_constant() -> None:
    a = tc.scale_sweep(3, 3, [1.0, 2.0], failure=data.YANG2012_FAILURE)
    b = tc.scale_sweep(3, 3, [1.0, 2.0], failure=dict(data.YANG2012_FAILURE))
    np.testing.assert_equal(a, b)   # the constant and a plain copy give the same sweep


def test_f2_failure_of_a_wrong_type_is_still_refused_by_name() -> None:
    with pytest.raises(TypeError, match="failure"):
        tc.paired_study(3, 3, _OFS, failure=[("sensors", (4, 10))])


@pytest.fixture(scope="module")
def readings() -> ci.IrReadings:
    return ci.ir_readings(0.1, 11, 5, duration=4.0)


def test_f1_sims_own_rmse_as_float32_is_taken(readings) -> None:
    sim = readings.sims["x"]
    rmse32 = {k: np.asarray(v, dtype=np.float32) for k, v in ir.rmse_by_rule(sim).items()}
    assert ci.ir_reading_numbers(readings, sim, rmse32) == ci.ir_reading_numbers(readings, sim, ir.rmse_by_rule(sim))


def test_f1_another_simulations_rmse_is_refused(readings) -> None:
    sim = readings.sims["x"]
    other = {k: np.asarray(v) * 1.001 for k, v in ir.rmse_by_rule(sim).items()}
    with pytest.raises(ValueError, match=r"rmse\[.*\] must be sim's RMSE per scan .*got other values"):
        ci.ir_reading_numbers(readings, sim, other)


# Judgement call of fuzz 23: a print resolution (600 dpi) is valid; the memory guard is a pixel budget
@pytest.mark.parametrize("figsize, dpi", [((7.5, 3.6), 600), ((7.5, 3.6), 1200), ((20.0, 20.0), 300)])
def test_print_resolutions_within_the_pixel_budget_are_taken(figsize, dpi) -> None:
    import matplotlib.pyplot as plt
    from fusion.book import style
    fig, _ = style.new_figure(1, 1, figsize=figsize, dpi=dpi)
    try:
        assert tuple(fig.get_size_inches()) == pytest.approx(figsize) and fig.get_dpi() == pytest.approx(dpi)
    finally:
        plt.close(fig)


@pytest.mark.parametrize("figsize, dpi", [((20.0, 20.0), 1200), ((10.0, 10.0), 700)])
def test_a_figure_beyond_the_pixel_budget_is_refused_naming_dpi(figsize, dpi) -> None:
    import matplotlib.pyplot as plt
    from fusion.book import style
    before = plt.get_fignums()
    with pytest.raises(ValueError, match=r"^dpi must be at most \d+ for a figsize of"):
        style.new_figure(1, 1, figsize=figsize, dpi=dpi)
    assert plt.get_fignums() == before
