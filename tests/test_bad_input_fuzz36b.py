"""Fuzz 35b follow-ups (issue 35), chapter layer.

- B5: the batched EM sets its own underflow state (``own_underflow`` back on ``_em_arrays``, fuzz 33b D6's rule);
- B1/D1: one run is refused naming ``runs`` (entry checks; a one-run Comparison without a reason is rule R4's refusal);
- B2: an ESS share clipped to its exact bounds (round-off of equal weights);
- B3/B4: the chapter layer's file readers read through ``fusion._paths`` and name the caller's ``root``;
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st


# --- B5: the EM's intended underflow under a caller's np.errstate(under="raise") ----------------------------------

def _far_clusters():
    rng = np.random.default_rng(0)
    x = np.concatenate([rng.normal(size=(40, 2)), rng.normal(size=(40, 2)) + 60.0])
    return x, np.ones(len(x))


def test_weighted_em_keeps_callers_underflow_state():
    from fusion.estimates import mixtures as mx
    x, w = _far_clusters()
    plain = mx.weighted_em(x, w, 2, np.random.default_rng(1))
    with np.errstate(under="raise"):
        strict = mx.weighted_em(x, w, 2, np.random.default_rng(1))
        batch = mx.weighted_em_batch(x[None], w[None], 2, [np.random.default_rng(1)])
        assert np.geterr()["under"] == "raise"
    assert np.array_equal(plain.mixture.means, strict.mixture.means)
    assert len(batch) == 1


# --- B1/D1: one run is refused naming runs (the caller's argument), not the comparison's inner "a and b" -----------

@pytest.mark.parametrize("fn", ["ev_awf_estimated", "ev_cc_accuracy", "ev_belief_objective"])
def test_chapter02_readings_refuse_one_run_by_name(fn):
    from fusion.book.chapters import lecture_weighting as lw
    with pytest.raises(ValueError, match=r"^runs must be an integer >= 2"):
        getattr(lw, fn)({"reading": "primary"}, runs=1)


def test_chapter03_reading_refuses_one_run_by_name():
    from fusion.book.chapters import lecture_wavelets as lwv
    with pytest.raises(ValueError, match=r"^runs must be an integer >= 2"):
        lwv.ev_wavelet_better({"reading": "primary"}, runs=1)


def test_ofs_evidence_refuses_one_run_by_name():
    from fusion.book.chapters import ofs
    with pytest.raises(ValueError, match=r"^runs must be an integer >= 2"):
        ofs.evidence(0, 1)


def test_evidence_at_names_the_entry_and_runs():
    from fusion.book.chapters import lecture
    with pytest.raises(ValueError, match=r"records\['lec-awf-estimated'\]: runs must be an integer >= 2"):
        lecture.evidence_at({"lec-awf-estimated": 1}, 2100)


def test_one_paired_run_without_reason_is_rule_r4_renamed_by_runs():
    from fusion.book._few_runs import FewRunsError, runs_named
    from fusion.book.ledger import Comparison
    with pytest.raises(FewRunsError, match=r"^a and b hold 1 runs < "):
        Comparison([1.0], [2.0], "x", "y", "less", "m")
    with pytest.raises(ValueError, match=r"^runs gives paired comparisons of 1 runs"):
        with runs_named("runs", "the argument runs"):
            Comparison([1.0], [2.0], "x", "y", "less", "m")
    with pytest.raises(ValueError, match=r"\(>= 2\) of paired runs"):  # with a reason: the shape rule, as before
        Comparison([1.0], [2.0], "x", "y", "less", "m", reason="why")
    with pytest.raises(ValueError, match=r"same number"):               # different lengths: not a run count
        Comparison([1.0], [2.0, 3.0], "x", "y", "less", "m")


def test_chapter01_reader_names_runs_and_keeps_propositions_at_one_run():
    from fusion.book.chapters import ofs
    with pytest.raises(ValueError, match=r"^runs gives paired comparisons of 1 runs"):
        ofs.ev_fig4_unaffected({}, runs=1)
    assert type(ofs.ev_eq3_5_rejects({}, runs=1)).__name__ == "Proposition"


# --- B2: an ESS share cannot leave [1/R, 1] by round-off ------------------------------------------------------------

@pytest.mark.parametrize("seed, r", [(1, 3)])
def test_defensive_study_accepts_equal_weights(seed, r):
    from fusion.book.chapters import chernoff_steps as cs
    st = cs.defensive_study(np.random.default_rng(seed), runs=2, r=r)
    assert all(np.all((v >= 1.0 / r) & (v <= 1.0)) for v in st.ess.values())


def test_ess_share_of_near_equal_log_weights_stays_in_bounds():
    from fusion.book.chapters import chernoff_steps as cs
    rng = np.random.default_rng(0)
    for r in (2, 3, 5, 7, 10, 64):
        lw = rng.normal(size=(200, 1)) + rng.normal(size=(200, r)) * 1e-15  # equal weights up to round-off
        e = cs._ess(lw)
        assert np.all(e <= 1.0) and np.all(e >= 1.0 / r)


# --- B3/B4: the chapter layer's file readers read through fusion._paths (one reader), malformed files named ------------

def _repo(tmp_path):
    r = tmp_path / "repo"
    for d in ("book/claims", "book/ledger", "notebooks"):
        (r / d).mkdir(parents=True)
    (r / "_toc.yml").write_text("root: x\n")
    (r / "book" / "a.md").write_text("hello lec_x\n")
    return r


def test_book_words_reads_a_valid_tree(tmp_path):
    from fusion.book.chapters import lecture
    r = _repo(tmp_path)
    (r / "notebooks" / "n.ipynb").write_text(json.dumps({"cells": [
        {"cell_type": "markdown", "source": ["see ", "lec_y\r\n"]}, {"cell_type": "code", "source": "lec_z = 1"},
        {"cell_type": "markdown", "source": "and lec_w"}]}))
    assert lecture.book_words(r) >= {"hello", "lec_x", "lec_y", "lec_w"} and "lec_z" not in lecture.book_words(r)


@pytest.mark.parametrize("make", ["folder", "huge", "latin1"])
def test_book_words_refuses_unreadable_files_naming_root(tmp_path, make):
    from fusion.book.chapters import lecture
    r = _repo(tmp_path)
    p = r / "book" / "b.md"
    if make == "folder":
        p.mkdir()
    elif make == "huge":
        with open(p, "wb") as fh:
            fh.truncate(17 << 20)   # sparse: beyond the one reader's 16 MB, refused before reading
    else:
        p.write_bytes("caf\xe9".encode("latin-1"))
    with pytest.raises(ValueError, match=r"^root: 'book/b\.md': not"):
        lecture.book_words(r)


_JSON = st.recursive(st.none() | st.booleans() | st.integers() | st.text(max_size=3),
                     lambda c: st.lists(c, max_size=3) | st.dictionaries(st.sampled_from(["cells", "cell_type", "source", "x"]), c,
                                                                        max_size=3), max_leaves=8)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(doc=_JSON | st.fixed_dictionaries({"cells": st.lists(_JSON, max_size=3)}))
def test_book_words_malformed_notebook_named_by_root(tmp_path, doc):
    from fusion.book.chapters import lecture
    r = tmp_path / "h"
    if not r.exists():
        r = _repo(tmp_path)
        r.rename(tmp_path / "h")
        r = tmp_path / "h"
    (r / "notebooks" / "x.ipynb").write_text(json.dumps(doc))
    try:
        lecture.book_words(r)
    except ValueError as e:
        assert str(e).startswith("root: 'notebooks/x.ipynb': ")


_RECORD = {"committed": "reproduced", "reseeds": ["reproduced"] * 5, "scaled": "reproduced", "k": 5, "K": 5,
           "flag": False, "failed": [], "runs_factor": 3}
_RECORDS = [{"id": "lec-awf-estimated", "status": "reproduced", "runs": 300}]


def _stability(tmp_path, content):
    r = _repo(tmp_path)
    (r / "book" / "ledger" / "stability.json").write_text(content)
    return r


def test_reseeding_glue_reads_a_whole_record(tmp_path):
    from fusion.book.chapters.lecture_weighting import records as rs
    r = _stability(tmp_path, json.dumps({"runs_factor": 10, "records": {"lec-awf-estimated": _RECORD}}))
    assert rs.reseeding_glue(_RECORDS, r) == {
        "lec_rs_awf_estimated": "reproduced at the chapter's 300 runs, stable in 5 of 5 reseeds and at 3× the runs"}


@pytest.mark.parametrize("content, what", [
    (json.dumps({"records": {"lec-awf-estimated": {k: v for k, v in _RECORD.items() if k != "k"}}}), "lacks the field 'k'"),
    (json.dumps({"records": {"lec-awf-estimated": {**_RECORD, "reseeds": 5}}}), "'reseeds' must be"),
    ("[1, 2]", "not a stability file"),
    (json.dumps({"records": [1]}), "'records' must be an object"),
    ("{", "not JSON"),
])
def test_reseeding_glue_refuses_a_malformed_stability_file_naming_root(tmp_path, content, what):
    from fusion.book.chapters.lecture_weighting import records as rs
    r = _stability(tmp_path, content)
    with pytest.raises(ValueError, match=r"^root: book/ledger/stability\.json.*" + re.escape(what)):
        rs.reseeding_glue(_RECORDS, r)


# --- D3: a glue-key prefix is ASCII letters, digits and underscores (no spelling that prints like another) ------------

@settings(max_examples=60, deadline=None)
@given(prefix=st.text(max_size=4) | st.sampled_from(["é", "e\u0301", "ﬁ", "Ⅸ", "𝐱", "ｘ", "ok_1", "_a", "A9"]))
def test_glue_prefix_is_an_ascii_identifier(prefix):
    from fusion.book.chapters import chernoff_steps as cs
    a, b = np.arange(6.0), np.arange(6.0) + 1.0
    if prefix.isascii() and f"{prefix}_x".isidentifier():
        assert f"{prefix}_stat" in cs.paired_numbers(a, b, prefix)
    else:
        with pytest.raises(ValueError, match=r"^prefix must be a glue key prefix \(ASCII"):
            cs.paired_numbers(a, b, prefix)
