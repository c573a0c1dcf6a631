"""Fuzz 19's cases of chapters 01-04, 06 and 07 (issue 35), by class.

Each refusal is a ValueError or TypeError naming the argument; valid input keeps working and degenerate valid input
gets the documented result. The classes:

* class D, one rule: a chapter function that reads a table or a mapping another function of the package made checks
  it with one shared rule (``fusion.book.tables._frame`` for tables, ``fusion._validation.mapping_of`` for
  mappings, ``records_of`` for sequences of records), so another object is refused by name, never an
  AttributeError, KeyError, IndexError or StopIteration from inside;
* a derived quantity refused inside (a covariance singular to working precision, a derived sample count) names the
  public arguments it comes from;
* paired arguments that must agree: runs keyed by a noise level they were not run at, a ledger of another chapter;
* validated values used in the body (``highlight`` as an array or a Series), one formatting rule for -0.0;
* empties and duplicates of the keys of a result, unknown settings of the claim files' readings, a reading checked
  before the runs, one rule for sequences of nested results (a list stored as a tuple).
"""

from __future__ import annotations

import dataclasses
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

from fusion._validation import mapping_of, records_of  # noqa: E402
from fusion.book import claims as cl  # noqa: E402
from fusion.book.chapters import chernoff as chf  # noqa: E402
from fusion.book.chapters import chernoff_criteria as ccr  # noqa: E402
from fusion.book.chapters import chernoff_scaling as cs  # noqa: E402
from fusion.book.chapters import lecture as lect  # noqa: E402
from fusion.book.chapters import lecture_correlated as lc  # noqa: E402
from fusion.book.chapters import lecture_wavelets as wv  # noqa: E402
from fusion.book.chapters import lecture_weighting as lw  # noqa: E402
from fusion.book.chapters import ofs  # noqa: E402
from fusion.book.chapters import time_registration as tr  # noqa: E402
from fusion.book.chapters.chernoff import importance as chi  # noqa: E402
from fusion.book.chapters.lecture_wavelets import appendix as wa  # noqa: E402
from fusion.book.ledger import Ledger  # noqa: E402
from fusion.scenarios import thermocouples  # noqa: E402
import fusion.scenarios.time_registration as trsc  # noqa: E402

Z = thermocouples.simulate(np.random.default_rng(0), n_samples=100)


def _named(exc: BaseException, name: str) -> bool:
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(name)}(?![A-Za-z0-9_])", str(exc)) is not None


# (case, call, exception, the argument its message names)
REFUSED = [
    # class D: tables read by a glue function
    ("D6 glue_lengths int", lambda: wa.glue_lengths(5), TypeError, "tab"),
    ("D6 glue_lengths dict", lambda: wa.glue_lengths({1024: 1}), TypeError, "tab"),
    ("D6 glue_lengths no columns", lambda: wa.glue_lengths(pd.DataFrame({"x": [1]}, index=[1024])), ValueError, "tab"),
    ("D7 glue_typical empty", lambda: wa.glue_typical(pd.DataFrame()), ValueError, "tab"),
    ("D7 glue_typical int", lambda: wa.glue_typical(5), TypeError, "tab"),
    ("D7 glue_typical Series", lambda: wa.glue_typical(pd.Series([1.0])), TypeError, "tab"),
    ("D8 table_values empty", lambda: chf.table_values(pd.DataFrame()), ValueError, "table"),
    ("D8 table_values int", lambda: chf.table_values(5), TypeError, "table"),
    ("D8 table_values Series", lambda: chf.table_values(pd.Series([1.0])), TypeError, "table"),
    ("D8 table_values no rows", lambda: chf.table_values(pd.DataFrame(
        {"RMSE from frame 5 (m)": [1.0], "mean NEES (4-D), frames 5-30": [1.0]}, index=["x"])), ValueError, "table"),
    # class D: mappings read by their items
    ("D12 premise_values empty", lambda: chf.premise_values({}), ValueError, "studies"),
    ("D13 premise_table float", lambda: chf.premise_table({"x": 1.0}), TypeError, "studies"),
    ("D13 premise_robust_values float", lambda: chf.premise_robust_values({"x": 1.0}), TypeError, "studies"),
    ("D13 premise_robust_values empty", lambda: chf.premise_robust_values({}), ValueError, "studies"),
    ("D13 premise_table empty", lambda: chf.premise_table({}), ValueError, "studies"),
    ("D14 premise_figure empty", lambda: chf.premise_figure({}), ValueError, "studies"),
    ("D14 premise_figure int", lambda: chf.premise_figure(5), TypeError, "studies"),
    ("criteria baseline_table int", lambda: ccr.baseline_table(5, {}), TypeError, "studies"),
    ("criteria criteria_table int", lambda: ccr.criteria_table(5, {}), TypeError, "studies"),
    ("criteria criteria_values int", lambda: ccr.criteria_values(5, {}), TypeError, "studies"),
    ("chernoff referenced int", lambda: chf.referenced(5), TypeError, "values"),
    ("D19 ev_awf_optimal int", lambda: lw.ev_awf_optimal(5), TypeError, "st"),
    ("D19 ev_ls_tracks int", lambda: lw.ev_ls_tracks(5), TypeError, "st"),
    ("D19 ev_ls_normal int", lambda: lw.ev_ls_normal(5), TypeError, "st"),
    ("D19 ev_awf_optimal empty", lambda: lw.ev_awf_optimal({}), ValueError, "st"),
    ("D20 lw ledger_values int", lambda: lw.ledger_values(5), TypeError, "st"),
    ("D21 wv ledger_values int", lambda: wv.ledger_values(5), TypeError, "st"),
    ("D21 wv ledger_values empty", lambda: wv.ledger_values({}), ValueError, "st"),
    ("D22 robustness_glue str item", lambda: lw.robustness_glue([{"id": "x"}, "y"]), TypeError, "records"),
    ("D22 robustness_glue no id", lambda: lw.robustness_glue([{"robustness": "x"}]), ValueError, "records"),
    ("F16 reseeding_glue dict", lambda: lw.reseeding_glue({"a": 1.0}), TypeError, "records"),
    ("F16 reseeding_glue str", lambda: lw.reseeding_glue("records"), TypeError, "records"),
    ("D23 glue_figures int", lambda: lect.glue_figures(5), TypeError, "figures"),
    ("D23 glue_figures not a figure", lambda: lect.glue_figures({"fig-x": 5}), TypeError, "figures"),
    ("D23 glue_figures empty", lambda: lect.glue_figures({}), ValueError, "figures"),
    # derived quantities name the public arguments
    ("D3 table_sequential sigma_env 1e8", lambda: lc.table_sequential(sigma_env=1e8), ValueError, "sigma_env"),
    ("F5 toy r = 0", lambda: chf.toy(2024, r=0), ValueError, "r"),
    ("F5 toy r = -1", lambda: chf.toy(2024, r=-1), ValueError, "r"),
    ("F5 toy r np.int64(0)", lambda: chf.toy(2024, r=np.int64(0)), ValueError, "r"),
    ("F5 toy r float", lambda: chf.toy(2024, r=2.0), TypeError, "r"),
    ("F6 is_replicate_values runs 1e6", lambda: chi.is_replicate_values(2024, runs=10**6), ValueError, "runs"),
    ("F6 is_replicates r 0", lambda: chi.is_replicates(2024, 0, 2), ValueError, "r"),
    # paired arguments that must agree
    ("E1 noise_level_table other sigma", lambda: tr.noise_level_table({1.0: trsc.monte_carlo(tr.FIG4, 3.0, 20, 1)}, 10.0),
     ValueError, "mcs"),
    ("ofs verdict_table other ledger", lambda: ofs.verdict_table(Ledger("shi2023time")), ValueError, "ledger"),
    ("ofs ledger_numbers other ledger", lambda: ofs.ledger_numbers(Ledger("shi2023time")), ValueError, "ledger"),
    # empties and duplicates of a result's keys
    ("scaling_study rs empty", lambda: cs.scaling_study(0, rs=()), ValueError, "rs"),
    ("scaling_study rs repeated", lambda: cs.scaling_study(0, rs=(250, 250)), ValueError, "rs"),
    ("swarm_study ns empty", lambda: cs.swarm_study(0, ns=()), ValueError, "ns"),
    ("swarm_study ns repeated", lambda: cs.swarm_study(0, ns=(2, 2)), ValueError, "ns"),
    ("within_se_counts ns empty", lambda: cs.within_se_counts(0, ns=()), ValueError, "ns"),
    ("within_se_counts ns repeated", lambda: cs.within_se_counts(0, ns=(3, 3)), ValueError, "ns"),
    ("cost_table ns repeated", lambda: cs.cost_table(ns=(2, 2)), ValueError, "ns"),
    ("cost_table ss repeated", lambda: cs.cost_table(ss=(1, 1)), ValueError, "ss"),
    # settings of the claim files' readings
    ("ch02 settings unknown key", lambda: lw.ev_awf_estimated({"reading": "primary", "bogus": 1}), ValueError, "settings"),
    ("ch03 settings unknown key", lambda: wv.ev_wavelet_accurate({"nope-xyz": 1.0}), ValueError, "settings"),
    ("ch01-03 reading_key unknown key", lambda: lect.reading_key({"runs": 3}), ValueError, "settings"),
    ("ev_belief_accuracy reading first", lambda: lw.ev_belief_accuracy({"reading": "nope"}, runs=3), ValueError,
     "settings"),
]


@pytest.mark.parametrize("case, call, exc, name", REFUSED, ids=[c[0] for c in REFUSED])
def test_refused_by_name(case, call, exc, name):
    with pytest.raises(exc) as info:
        call()
    assert _named(info.value, name), str(info.value)
    plt.close("all")


def test_belief_accuracy_names_the_reading_not_the_runs():
    """The reading is checked before any study runs: the message names it, not the run count."""
    with pytest.raises(ValueError, match="no reading 'nope'"):
        lw.ev_belief_accuracy({"reading": "nope"}, runs=3)


@pytest.mark.parametrize("highlight", [np.array([4, 10]), pd.Series([4, 10]), pd.Series([4, 10], index=[7, 3]),
                                       [4, 10], (4, 10), range(4, 5), np.array([], dtype=int)])
def test_figure_readings_highlight_any_sequence(highlight):
    """F1/F2 (regression): the validated ``highlight`` is the one the body reads; the same sensors are emphasised."""
    fig = ofs.figure_readings(Z, highlight=highlight)
    labels = fig.axes[0].get_legend_handles_labels()[1]
    assert labels == [f"sensor {int(h)}" for h in sorted(np.asarray(list(highlight), dtype=int))]
    plt.close(fig)


def test_sci_negative_zero():
    """E8: "0 is written 0", also -0.0, as the other formatters of the book."""
    assert lect.sci(-0.0) == "0" == lect.sci(0.0)
    assert lect.sci(-1.5e-3).startswith("-")


def test_table_sequential_large_valid_env():
    """D3: a large common environment that still factors keeps working (sigma_env = 1e6)."""
    t = lc.table_sequential(sigma_env=1e6)
    assert t.shape[0] == 3


def test_is_replicate_values_ceiling_is_exact():
    """F6: the derived sample count is bounded by the ceiling of a sample count, the largest run count named."""
    with pytest.raises(ValueError, match="at most 500 runs"):
        chi._sample_sets(501, 20_000)
    assert chi._sample_sets(500, 20_000) == (500, 20_000)


def test_cost_table_valid_and_keyed():
    t = cs.cost_table(ns=np.array([2, 3]), ss=[1])
    assert list(t.index) == [2, 3] and list(t.columns) == ["S = 1"]


def test_chapter_ledger_accepted():
    """The chapter's own ledger (empty here) keeps its documented result."""
    assert ofs.ledger_numbers(Ledger("yang2012optimal")) == {}
    assert ofs.verdict_table(Ledger("yang2012optimal")).empty


def test_noise_level_table_matching_sigma():
    mc = trsc.monte_carlo(tr.FIG4, 3.0, 20, 1)
    assert list(tr.noise_level_table({3.0: mc}, 10.0).index) == [3.0]


def test_toy_study_gms_list_stored_as_tuple():
    """One rule for sequences of nested results: a list is accepted and stored as a tuple (as every ``tuple_of``);
    another length is a ValueError, another type a TypeError, both naming the field."""
    t = chf.toy(2024, r=2000)
    t2 = dataclasses.replace(t, gms=list(t.gms))
    assert isinstance(t2.gms, tuple) and t2.gms == t.gms
    with pytest.raises(ValueError, match="gms"):
        dataclasses.replace(t, gms=t.gms[:1])
    with pytest.raises(TypeError, match="gms"):
        dataclasses.replace(t, gms=5)
    with pytest.raises(TypeError, match=r"gms\[1\]"):
        dataclasses.replace(t, gms=(t.gms[0], 5))


def test_reading_settings_of_claim_files_still_load():
    """Every reading's settings in the claim file of chapters 01-03 holds only keys the readings take."""
    cf = cl.load(cl.claims_dir() / "lecture003.yaml")
    for rid in lw.STOCHASTIC:
        for r in cf.record(rid).readings:
            assert lect.reading_key(r.settings) == r.key


def test_shared_rules():
    assert mapping_of({"a": 1}, "m", "number", values=int) == {"a": 1}
    with pytest.raises(TypeError, match=r"m\['a'\]"):
        mapping_of({"a": "x"}, "m", "number", values=int)
    with pytest.raises(ValueError, match="at least one"):
        mapping_of({}, "m", "number")
    assert records_of(({"id": "a"},), "records", ("id",)) == [{"id": "a"}]
    with pytest.raises(TypeError, match=r"records\[0\]"):
        records_of([5], "records")
    assert lw.robustness_glue([]) == {}
    assert lw.robustness_glue([{"id": "lec-x", "robustness": "r"}]) == {"lec_rob_x": "r"}
