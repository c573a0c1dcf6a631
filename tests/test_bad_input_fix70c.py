"""Fix70c: sequences whose entries each run per-entry work, counted by len() before any entry is read.

``plugin_conjunction`` ran one ``plugin_risk`` per x (280-420 us each: 10**7 xs are hours), ``belief_accuracy`` and
``table_shift_weight`` read and matched every grid value or shift (3 and 9-18 us each) and then selected a
(runs or draws) x n block of their study: none had a work budget. Each now counts its entries by ``len()`` first
("sequence -> budget by len() -> entries"); the inputs are built outside the timing.
"""

from __future__ import annotations

import numpy as np
import pytest

from fusion._limits import work
from _helpers import refused_quickly

N = 10**7   # MAX_COUNT: the most entries a sequence argument may hold


@pytest.fixture(scope="module")
def plugin():
    from fusion.scenarios.ridge_sensors import plugin_study
    return plugin_study(runs=10)


@pytest.fixture(scope="module")
def s24b():
    from fusion.book.chapters.lecture_weighting import studies
    return studies.study("s24b", 1, 100)


@pytest.fixture(scope="module")
def shifts():
    from fusion.book.chapters.lecture_weighting.belief import shift_weight_draws
    return shift_weight_draws(5)


@pytest.mark.parametrize("key, edge", [("ridge_plugin_known", 7_692), ("ridge_plugin_est", 6_896)])
def test_plugin_conjunction_counts_xs(plugin, key, edge):
    """The edge accepted by the budget alone (its member of the Conjunction counted: below the Conjunction's own
    10,000 parts); one x more (2-3 CPU-s of quadratures before, accepted) and 10**7 (hours) refused at once naming
    xs."""
    from fusion.book.chapters.lecture_correlated.propositions import _PLUGIN_X_UNITS, plugin_conjunction
    from fusion.book.ledger.evidence import _MEMBER
    assert work((edge,), "xs", weight=_PLUGIN_X_UNITS[key] + _MEMBER) <= 10**9
    assert work((edge,), "parts", weight=_MEMBER) <= 10**9
    with pytest.raises(ValueError, match="xs"):
        work((edge + 1,), "xs", weight=_PLUGIN_X_UNITS[key] + _MEMBER)
    for n in (edge + 1, N):
        xs = np.linspace(0.01, 10.0, n).tolist()
        refused_quickly(lambda: plugin_conjunction(plugin, key, xs=xs), ValueError, r"^xs ask for")


def test_plugin_conjunction_entries_kept(plugin):
    """The xs are still read after the budget: a repeat and a NaN refused by name."""
    from fusion.book.chapters.lecture_correlated.propositions import plugin_conjunction
    with pytest.raises(ValueError, match="xs"):
        plugin_conjunction(plugin, xs=(1.0, 1.0))
    with pytest.raises(ValueError, match=r"xs\[1\]"):
        plugin_conjunction(plugin, xs=(1.0, float("nan")))


def test_belief_accuracy_counts_values(s24b):
    """At 100 runs 2.5 million values are the edge (the budget alone); one more and 10**7 (about 30 CPU-s of reading
    and an 8 GB selection before) refused at once naming values."""
    from fusion.book.chapters.lecture_weighting.belief import _VALUE_UNITS, belief_accuracy
    kind = list(s24b.sq)[0]
    runs = s24b.sq[kind].shape[0]
    assert runs == 100
    assert work((2_500_000,), "values", weight=_VALUE_UNITS + runs) <= 10**9
    for n in (2_500_001, N):
        values = [0.25] * n
        refused_quickly(lambda: belief_accuracy(s24b, kind, values), ValueError, r"^values and s \(its runs\)")
    with pytest.raises(ValueError, match=r"values\[1\]"):
        belief_accuracy(s24b, kind, (0.25, 123.0))


def test_table_shift_weight_counts_at(shifts):
    """At 5 draws 1,092,896 shifts are the edge (the budget alone); one more and 10**7 (about 90 CPU-s of matching
    and quartiles before) refused at once naming at."""
    from fusion.book.chapters.lecture_weighting.belief import _SHIFT_UNITS, table_shift_weight
    draws = shifts.W.shape[0]
    assert draws == 5
    edge = 10**9 // (_SHIFT_UNITS + 3 * draws)
    assert edge == 1_092_896 and work((edge,), "at", weight=_SHIFT_UNITS + 3 * draws) <= 10**9
    for n in (edge + 1, N):
        at = [0.0] * n
        refused_quickly(lambda: table_shift_weight(shifts, at), ValueError, r"^at and s \(its draws\)")
    with pytest.raises(ValueError, match=r"at\[1\]"):
        table_shift_weight(shifts, (0.0, 0.05))


def test_table_seeds_counts_sensors():
    """More sensors than the study has must repeat one: refused by len() at once (10**7 were read first, the
    repeat refused after about 14 CPU-s); the study's own number of distinct sensors is still read."""
    from fusion.book.chapters.lecture_wavelets import e26
    from fusion.book.chapters.lecture_wavelets import appendix as wa
    study = wa.length_study(64)
    n = study.gains.size
    many = [0] * N
    refused_quickly(lambda: e26.table_seeds(study, sensors=many), ValueError, r"^sensors must hold at most")
    refused_quickly(lambda: e26.table_seeds(study, sensors=list(range(n)) + [0]), ValueError,
                    r"^sensors must hold at most")
    assert len(e26.table_seeds(study, sensors=tuple(range(n)))) > 0
    with pytest.raises(ValueError, match="sensors"):
        e26.table_seeds(study, sensors=(1, 1))


def test_figure_readings_counts_highlight():
    """The edge of 5 sensors accepted by the budget alone; one entry more and 10**7 (13 CPU-s of reading before)
    refused at once naming highlight."""
    from fusion.book.chapters.ofs.figures import _HIGHLIGHT_UNITS, figure_readings
    z = np.random.default_rng(0).normal(900.0, 1.0, size=(100, 5))
    edge = 10**9 // (_HIGHLIGHT_UNITS + 5)
    assert work((edge,), "highlight", weight=_HIGHLIGHT_UNITS + 5) <= 10**9
    for n in (edge + 1, N):
        hl = [1] * n
        refused_quickly(lambda: figure_readings(z, highlight=hl), ValueError, r"^highlight ask for")


def test_belief_parameter_comparison_counts_grid(s24b):
    """Both grids counted together: at 100 runs 2,222,222 values are the edge (the budget alone); one more and
    2 x 10**7 (4.2 us a value before, about 84 CPU-s) refused at once naming grid."""
    from fusion.book.chapters.lecture_weighting.belief import (_GRID_UNITS, belief_objectivity,
                                                               belief_parameter_comparison)
    edge = 10**9 // (_GRID_UNITS + 100)
    assert edge == 2_222_222 and work((edge,), "grid", weight=_GRID_UNITS + 100) <= 10**9
    half = [0.25] * (edge // 2)
    refused_quickly(lambda: belief_parameter_comparison(s24b, grid=(half, half + [0.25])), ValueError,
                    r"^grid and s \(its runs\)")
    many = [0.25] * N
    for f in (belief_parameter_comparison, belief_objectivity):
        refused_quickly(lambda: f(s24b, grid=(many, many)), ValueError, r"^grid and s \(its runs\)")
    with pytest.raises(ValueError, match="grid"):
        belief_parameter_comparison(s24b, grid=((0.25, 123.0), (0.25,)))
