"""Fuzz 21b's cases of the lecture chapters 02-04 (issue 35), by class.

Each refusal is a ValueError or TypeError naming the argument; valid input keeps working and degenerate valid input
gets the documented result. The classes:

* W, one template rule (``fusion._validation.template``): a template argument is a str whose fields name the values
  its caller fills in, with a width of two digits at most; ``sensor_conjunction``'s ``metric`` and ``labelled``'s
  ``template`` (d5's widths, by the same rule);
* B, one selection rule (``fusion._validation.selection``): a slice or a boolean mask of the entries' length, never
  an integer index array (a repeated index forges paired runs); ``eig_row_comparison``'s ``select``;
* L, G: a generator is a Generator, a count an integer in its range within the work budget (``ls_special_cases``,
  ``james_stein_linearity``), a figure a Figure (``legend_below``);
* R, one record rule (``_keyed_records``): the ledger records the reseeding and robustness lines read have a
  text id, a rulebook status, integer runs, and no two give one glue key; ``root`` is named;
* d4 (decided: fixed): ``referenced``'s ``words`` as a str is refused (it was matched by substrings).
"""

from __future__ import annotations

import re
import string

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from fusion._validation import selection, template  # noqa: E402
from fusion.book.chapters import lecture as le  # noqa: E402
from fusion.book.chapters import lecture_correlated as lc  # noqa: E402
from fusion.book.chapters import lecture_wavelets as lw  # noqa: E402
from fusion.book.chapters import lecture_weighting as lwt  # noqa: E402
from fusion.book.chapters import time_registration as tr  # noqa: E402
from fusion.book.rulebook import STATUSES  # noqa: E402
from fusion.scenarios.lecture_weighting import belief as sb  # noqa: E402

_RNG = np.random.default_rng(0)
A = _RNG.normal(1.0, 0.1, size=(120, 3))
B = A + 0.5
BS = sb.belief_study(snapshots=200)


def _named(exc: BaseException, name: str) -> bool:
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(name)}(?![A-Za-z0-9_])", str(exc)) is not None


def _fig():
    fig, ax = plt.subplots()
    ax.plot([1, 2], label="a")
    ax.plot([2, 1], label="b")
    return fig


# (case, call, exception, the argument its message names)
REFUSED = [
    ("W1 metric unknown field", lambda: lw.sensor_conjunction(A, B, "A", "B", "rmse {x}", 1), ValueError, "metric"),
    ("W2 metric positional field", lambda: lw.sensor_conjunction(A, B, "A", "B", "rmse {0}", 1), ValueError, "metric"),
    ("W3 metric single brace", lambda: lw.sensor_conjunction(A, B, "A", "B", "rmse {", 1), ValueError, "metric"),
    ("W4 metric int", lambda: lw.sensor_conjunction(A, B, "A", "B", 5, 1), TypeError, "metric"),
    ("W5 metric None", lambda: lw.sensor_conjunction(A, B, "A", "B", None, 1), TypeError, "metric"),
    ("W6 metric width", lambda: lw.sensor_conjunction(A, B, "A", "B", "{j:>999999999}", 1), ValueError, "metric"),
    ("W6 metric width 100", lambda: lw.sensor_conjunction(A, B, "A", "B", "{j:>100}", 1), ValueError, "metric"),
    ("W metric attribute", lambda: lw.sensor_conjunction(A, B, "A", "B", "{j.real}", 1), ValueError, "metric"),
    ("W metric nested", lambda: lw.sensor_conjunction(A, B, "A", "B", "{j:{w}}", 1), ValueError, "metric"),
    ("W metric str precision on int", lambda: lw.sensor_conjunction(A, B, "A", "B", "{j:.3}", 1), ValueError,
     "metric"),
    ("d5 labelled width", lambda: tr.labelled(pd.DataFrame({"a": [1]}), "{:>5000000}"), ValueError, "template"),
    ("B1 select short mask", lambda: lwt.eig_row_comparison(BS, BS.shifted[:10]), ValueError, "select"),
    ("B2 select str", lambda: lwt.eig_row_comparison(BS, "x"), TypeError, "select"),
    ("B3 select floats", lambda: lwt.eig_row_comparison(BS, np.ones(200)), TypeError, "select"),
    ("B4 select index", lambda: lwt.eig_row_comparison(BS, np.array([10**6])), TypeError, "select"),
    ("B5 select tuple", lambda: lwt.eig_row_comparison(BS, (0, 1)), TypeError, "select"),
    ("B6 select None", lambda: lwt.eig_row_comparison(BS, None), TypeError, "select"),
    ("B7 select repeated index", lambda: lwt.eig_row_comparison(BS, np.zeros(200, dtype=int)), TypeError, "select"),
    ("B select 2-D mask", lambda: lwt.eig_row_comparison(BS, np.ones((200, 1), bool)), ValueError, "select"),
    ("B select float bound", lambda: lwt.eig_row_comparison(BS, slice(0.5, None)), TypeError, "select"),
    ("B select zero step", lambda: lwt.eig_row_comparison(BS, slice(None, None, 0)), ValueError, "select"),
    ("B select too few", lambda: lwt.eig_row_comparison(BS, slice(0, 50)), ValueError, "select"),
    ("L1 m zero", lambda: lc.ls_special_cases(np.random.default_rng(0), 0), ValueError, "m"),
    ("L2 m negative", lambda: lc.ls_special_cases(np.random.default_rng(0), -1), ValueError, "m"),
    ("L3 m float", lambda: lc.ls_special_cases(np.random.default_rng(0), 2.5), TypeError, "m"),
    ("L4 m huge", lambda: lc.ls_special_cases(np.random.default_rng(0), 10**8), ValueError, "m"),
    # 100 units a step since fuzz 39a E4 (0.29 us measured): the edge is 9.9e6 steps, about 3 CPU-s
    ("L4 m beyond the loop budget", lambda: lc.ls_special_cases(np.random.default_rng(0), 10**7), ValueError,
     "m"),
    ("L5 rng int", lambda: lc.ls_special_cases(5), TypeError, "rng"),
    ("L js rng", lambda: lc.james_stein_linearity(5), TypeError, "rng"),
    ("L js d", lambda: lc.james_stein_linearity(np.random.default_rng(0), d=2), ValueError, "d"),
    ("L js sigma", lambda: lc.james_stein_linearity(np.random.default_rng(0), sigma=0.0), ValueError, "sigma"),
    ("L js k", lambda: lc.james_stein_linearity(np.random.default_rng(0), k=-1.0), ValueError, "k"),
    ("G1 ncol zero", lambda: le.legend_below(_fig(), 0), ValueError, "ncol"),
    ("G2 ncol float", lambda: le.legend_below(_fig(), 2.5), TypeError, "ncol"),
    ("G3 fig str", lambda: le.legend_below("x"), TypeError, "fig"),
    ("G4 ncol huge", lambda: le.legend_below(_fig(), 10**9), ValueError, "ncol"),
    ("R1 id int", lambda: lwt.robustness_glue([{"id": 5, "robustness": "x"}]), TypeError, "records"),
    ("R id empty", lambda: lwt.robustness_glue([{"id": "", "robustness": "x"}]), ValueError, "records"),
    ("R2 glue-key collision", lambda: lwt.robustness_glue([{"id": "lec-a-b", "robustness": "x"},
                                                            {"id": "lec-a_b", "robustness": "y"}]), ValueError,
     "records"),
    ("R3 repeated id", lambda: lwt.robustness_glue([{"id": "lec-a", "robustness": "x"},
                                                     {"id": "lec-a", "robustness": "y"}]), ValueError, "records"),
    ("R robustness float", lambda: lwt.robustness_glue([{"id": "lec-a", "robustness": float("nan")}]), TypeError,
     "records"),
    ("R4 root missing", lambda: lwt.reseeding_glue([], "/nonexistent"), ValueError, "root"),
    ("R root int", lambda: lwt.reseeding_glue([], 5), TypeError, "root"),
    ("R5 runs str", lambda: lwt.reseeding_glue([{"id": "lec-x", "status": "reproduced", "runs": "x"}]), TypeError,
     "records"),
    ("R runs zero", lambda: lwt.reseeding_glue([{"id": "lec-x", "status": "reproduced", "runs": 0}]), ValueError,
     "records"),
    ("R6 status int", lambda: lwt.reseeding_glue([{"id": "lec-x", "status": 5, "runs": 100}]), TypeError, "records"),
    ("R status unknown", lambda: lwt.reseeding_glue([{"id": "lec-x", "status": "fine", "runs": 100}]), ValueError,
     "records"),
    ("R repeated id, reseeding", lambda: lwt.reseeding_glue([{"id": "lec-x", "status": "reproduced", "runs": 100}] * 2),
     ValueError, "records"),
    ("d4 words str", lambda: le.referenced({"ab": 1}, "xaby"), TypeError, "words"),
    ("d4 words int", lambda: le.referenced({"ab": 1}, 5), TypeError, "words"),
    ("d4 words of ints", lambda: le.referenced({"ab": 1}, {1, 2}), TypeError, "words"),
]


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


@pytest.mark.parametrize("case, call, exc, name", REFUSED, ids=[c[0] for c in REFUSED])
def test_refused_by_name(case, call, exc, name):
    """The refusal is of the documented type and its message names the argument (a whole word)."""
    with pytest.raises(exc, match=rf"(?<![A-Za-z0-9_]){re.escape(name)}(?![A-Za-z0-9_])"):
        call()


# --- W: the template rule -------------------------------------------------------------------------------------------

def test_metric_templates_valid():
    """A metric without a field, with ``{j}``, with a conversion, a type or a doubled brace keeps working."""
    for metric, want in (("MSE", "MSE"), ("RMSE, sensor {j}", "RMSE, sensor 2"), ("{j!r}", "2"), ("{j:d}", "2"),
                         ("{{j}} {j}", "{j} 2"), ("{j:.2f}", "2.00"), ("{j:>3}", "  2")):
        c = lw.sensor_conjunction(A, B, "A", "B", metric, 1)
        assert c.parts[1][1].metric == want


def test_labelled_templates_valid():
    """``labelled``'s documented templates keep working under the shared rule."""
    closed = tr.closed_form_table(1.0, 1.0)
    assert tr.labelled(closed, "fused, {}").shape == closed.shape
    assert tr.labelled(closed, "{0}").shape == closed.shape
    assert tr.labelled(closed, "{!s}").shape == closed.shape
    assert list(tr.labelled(closed.iloc[:1], "{:>99}").index) == [f"{tr.METHOD_LABELS[closed.index[0]]:>99}"]


_FIELD = st.text(alphabet=string.ascii_letters + string.digits + "_.[]", min_size=0, max_size=6)


@settings(max_examples=200, deadline=None)
@given(prefix=st.text(alphabet="ab {}:", max_size=6), field=_FIELD,
       spec=st.text(alphabet="<>^=+- #0123456789_,.sdfr%xz{}", max_size=8), suffix=st.text(alphabet="ab {}", max_size=4))
def test_template_rule_is_all_or_nothing(prefix, field, spec, suffix):
    """Any template either passes the rule and then formats ``j`` to a short text, or is refused naming the
    argument (a ValueError): never a KeyError, IndexError or a huge label."""
    tpl = f"{prefix}{{{field}:{spec}}}{suffix}"
    try:
        out = template(tpl, "metric", j=3)
    except ValueError as exc:
        assert _named(exc, "metric")
        return
    assert out == tpl
    assert len(out.format(j=3)) <= len(tpl) + 200


@settings(max_examples=80, deadline=None)
@given(width=st.integers(0, 10**12), part=st.sampled_from([">{}", "0{}", ".{}f", "<{}.{}"]))
def test_template_width_bounded(width, part):
    """A width (or precision) of two digits pads a label as asked; a larger one is refused before anything is
    formatted (``10**9`` padded one label to a gigabyte)."""
    tpl = "{j:" + part.format(width, width) + "}"
    if width > 99:
        with pytest.raises(ValueError, match="metric"):
            template(tpl, "metric", j=1)
    else:
        assert template(tpl, "metric", j=1.0) == tpl
        assert len(tpl.format(j=1.0)) <= 3 * 99


# --- B: the selection rule ------------------------------------------------------------------------------------------

def test_select_valid():
    """A slice, a mask (array or list of bools) and its negation keep working; the default compares all."""
    full = lwt.eig_row_comparison(BS)
    assert lwt.eig_row_comparison(BS, slice(None)).interval() == full.interval()
    for sel in (BS.shifted, ~BS.shifted, list(~BS.shifted)):
        lwt.eig_row_comparison(BS, sel)
    assert lwt.eig_row_comparison(BS, np.ones(200, bool)).interval() == full.interval()
    lwt.eig_row_comparison(BS, slice(None, None, -1))


@settings(max_examples=60, deadline=None)
@given(idx=st.lists(st.integers(0, 199), min_size=1, max_size=300))
def test_select_integer_index_refused(idx):
    """An integer index array, with or without repeats, is refused naming ``select`` (it could forge runs)."""
    with pytest.raises(TypeError, match="select"):
        lwt.eig_row_comparison(BS, np.array(idx))


@settings(max_examples=60, deadline=None)
@given(n=st.integers(0, 400))
def test_selection_mask_length(n):
    """A mask is accepted exactly when it has one entry per paired entry."""
    if n == 200:
        assert selection(np.ones(n, bool), "select", 200).shape == (200,)
    else:
        with pytest.raises(ValueError, match="select"):
            selection(np.ones(n, bool), "select", 200)


# --- L, G -----------------------------------------------------------------------------------------------------------

def test_ls_special_cases_valid_and_degenerate():
    """m = 1 is the documented degenerate case (every form is the one reading); numpy integers are counts."""
    d = lc.ls_special_cases(np.random.default_rng(0), 1)
    assert d == {"mean": 0.0, "weighted mean": 0.0, "recursive filter": 0.0}
    d = lc.ls_special_cases(np.random.default_rng(0), np.int64(50))
    assert set(d) == {"mean", "weighted mean", "recursive filter"} and max(d.values()) < 1e-12
    assert lc.ls_special_cases(np.random.default_rng(0), 50) == d


def test_legend_below_valid():
    """More columns than entries give the legend of one column per entry (the empty columns took no room)."""
    fig = _fig()
    le.legend_below(fig, 10**6)
    assert fig.legends[0]._ncols == 2
    fig2 = _fig()
    le.legend_below(fig2, np.int64(1))
    assert fig2.legends[0]._ncols == 1
    plt.close("all")


# --- R --------------------------------------------------------------------------------------------------------------

@settings(max_examples=100, deadline=None)
@given(ids=st.lists(st.sampled_from(["lec-a", "lec-b", "lec-a_b", "lec-a-b", "a", "lec-c-d"]), max_size=5))
def test_robustness_glue_no_line_lost(ids):
    """Either every record's line is glued under its own key, or the call is refused naming ``records``."""
    recs = [{"id": i, "robustness": f"line {n}", "status": STATUSES[n % len(STATUSES)], "runs": None}
            for n, i in enumerate(ids)]
    try:
        out = lwt.robustness_glue(recs)
    except ValueError as exc:
        assert _named(exc, "records")
        keys = [i.removeprefix("lec-").replace("-", "_") for i in ids]
        assert len(set(keys)) < len(keys)
        return
    assert sorted(out.values()) == sorted(r["robustness"] for r in recs)


def test_ledger_records_valid():
    """Ledger records as the ledger writes them (runs None or an integer, empty robustness) keep working."""
    recs = [{"id": "lec-x", "status": "reproduced", "runs": None, "robustness": ""},
            {"id": "lec-y", "status": "not distinguishable", "runs": np.int64(200), "robustness": "2 of 3 hold"}]
    assert lwt.robustness_glue(recs) == {"lec_rob_y": "2 of 3 hold"}
    assert isinstance(lwt.reseeding_glue(recs), dict)


# --- d4 -------------------------------------------------------------------------------------------------------------

def test_referenced_words_collections():
    """A frozenset, a set or a list of words is matched whole (``ab`` is not a word of ``{"xaby"}``)."""
    vals = {"ab": 1, "xaby": 2}
    assert le.referenced(vals, frozenset({"xaby"})) == {"xaby": 2}
    assert le.referenced(vals, {"ab"}) == {"ab": 1}
    assert le.referenced(vals, ["ab", "xaby"]) == vals
    assert le.referenced(vals, frozenset()) == {}
