"""Fix71d (fuzz 63a C2, C4, C5): chapter 01's and 05's figures and table count what they draw or loop over.

``figure_readings`` drew one line a sensor (290-390 us each) and never counted the sensors: (2, 10**5) readings were
accepted after 35.6 CPU-s. ``architecture_table`` looped over its studies (8.4-9.4 ms each, 19 rows) with no budget:
5,000 labels were accepted after 48 CPU-s. ``architecture_figure`` and ``figure_mc`` drew one panel per study or
noise setting and refused a 17th by ``new_figure``'s ``ncols``, an argument the caller never passed.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from fusion._limits import MAX_WORK, work
from _helpers import refused_quickly


@pytest.fixture(scope="module")
def study():
    """A study of the baseline row only (CI on independent filters), 100 runs: 50,500 units in the table."""
    from fusion.scenarios.two_sensor import Architecture, ArchitectureStudy, ArchRule

    key = (Architecture.INDEPENDENT.value, ArchRule.CI.value)
    return ArchitectureStudy(run_rmse={key: np.linspace(40.0, 60.0, 100)}, nees={key: 4.0}, reported={key: 50.0},
                             model_rmse={key: np.linspace(40.0, 60.0, 100)}, runs=100, nees_runs=100)


#: The most one-row studies of 100 runs ``architecture_table`` takes (50,500 units each) and the most 2-sample sensors
#: ``figure_readings`` draws (40,014 units each).
STUDIES_EDGE, SENSORS_EDGE = 19_801, 24_991


def test_architecture_table_accepts_its_edge(study) -> None:
    from fusion.book.chapters.ci import architecture as a

    assert MAX_WORK // (a._TABLE_ROW_UNITS + a._TABLE_RUN_UNITS * 100) == STUDIES_EDGE
    assert a._table_budget({f"p{i}": study for i in range(STUDIES_EDGE)}) <= MAX_WORK   # just inside: accepted
    assert a.architecture_table({"p": study}).shape[0] == 1                             # a valid table is made


def test_architecture_table_counts_its_studies_before_the_loop(study) -> None:
    from fusion.book.chapters.ci.architecture import architecture_table

    outside = {f"p{i}": study for i in range(STUDIES_EDGE + 1)}
    refused_quickly(lambda: architecture_table(outside), ValueError, r"^studies")


def test_figure_readings_accepts_its_edge() -> None:
    from fusion.book.chapters.ofs import figures as f

    per = f._SENSOR_UNITS + f._SAMPLE_UNITS * 2
    assert MAX_WORK // per == SENSORS_EDGE
    assert work((SENSORS_EDGE,), "readings", weight=per) <= MAX_WORK   # just inside: accepted by the budget


def test_figure_readings_counts_its_sensors_before_drawing() -> None:
    from fusion.book.chapters.ofs.figures import figure_readings

    z = np.full((2, SENSORS_EDGE + 1), 900.0)
    refused_quickly(lambda: figure_readings(z, (), (1, 2)), ValueError, r"^readings")


def test_architecture_figure_refuses_a_17th_study_by_its_name(study) -> None:
    from fusion.book.chapters.ci.architecture import architecture_figure

    refused_quickly(lambda: architecture_figure({f"p{i}": study for i in range(17)}), ValueError,
                    r"^studies must hold at most 16 studies")


def test_figure_mc_refuses_a_17th_noise_setting_by_its_name() -> None:
    from fusion.book.chapters.ofs.figures import BOUND_CLEAN, figure_mc
    from fusion.book.chapters.ofs.settings import METHODS, FailureCase
    from fusion.book.style import METHOD_LABELS

    rows = pd.MultiIndex.from_tuples([(f"s{i}", METHOD_LABELS[c]) for i in range(17) for c in FailureCase])
    table = pd.DataFrame(1.0, index=rows, columns=[METHOD_LABELS[m] for m in METHODS] + [BOUND_CLEAN])
    refused_quickly(lambda: figure_mc(table), ValueError, r"^table must hold at most 16 noise settings")


def test_figure_fair_refuses_a_33rd_sweep_by_its_name() -> None:
    """fix71d's report: figure_fair draws two rows of panels; a study of 33 sweeps raised new_figure's "ncols must be
    at most 16", naming an argument the caller never passed."""
    from fusion.book.chapters.ofs_fair import FAIR_METHODS, FairStudy, figure_fair

    errs = {m: np.ones(2) for m in FAIR_METHODS}
    study = FairStudy(mae={(f"s{i}", 1.0): errs for i in range(33)}, n_runs=2, n_samples=10, seed=0)
    refused_quickly(lambda: figure_fair(study), ValueError, r"^study must hold at most 32 sweeps .*got 33")
