"""Fuzz 36b follow-ups (issue 35), chapter layer.

- B1/B2: the chapter layer's JSON reader (``fusion._paths.file_json``) keeps the book's one JSON rule of
  ``fusion.book._json.read_object`` (one decoder, ``fusion._paths.json_document``): nesting beyond the recursion
  limit, an integer too long to convert, NaN, Infinity and overflowing numbers are refused naming the caller's root;
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st


# --- B1/B2: both JSON readers refuse deep nesting, huge integers, NaN and infinities by name ------------------------

_RECORD = {"committed": "contradicted", "reseeds": ["contradicted"] * 5, "scaled": "contradicted", "k": 5, "K": 5,
           "flag": False, "failed": [], "runs_factor": 10}
_RECORDS = [{"id": "lec-awf-estimated", "status": "reproduced", "runs": 300}]
_VALID = json.dumps({"records": {"lec-awf-estimated": _RECORD}, "runs_factor": 3})
_DEEP = "[" * 100_000 + "]" * 100_000
_BAD_JSON = [
    ('{"records": ' + _DEEP + "}", "nested too deep"),
    (_VALID.replace('"k": 5', '"k": ' + "9" * 5000), "digits"),
    (_VALID.replace('"runs_factor": 10', '"runs_factor": NaN'), "NaN"),
    (_VALID.replace('"runs_factor": 10', '"runs_factor": -Infinity'), "Infinity"),
    (_VALID.replace('"runs_factor": 10', '"runs_factor": 1e999'), "overflows"),
]


def _root(tmp_path, stability=None, notebook=None):
    r = tmp_path / "repo"
    for d in ("book/claims", "book/ledger", "notebooks"):
        (r / d).mkdir(parents=True)
    (r / "_toc.yml").write_text("root: x\n")
    if stability is not None:
        (r / "book" / "ledger" / "stability.json").write_text(stability)
    if notebook is not None:
        (r / "notebooks" / "x.ipynb").write_text(notebook)
    return r


def test_reseeding_glue_reads_a_valid_stability_file(tmp_path):
    from fusion.book.chapters.lecture_weighting import records as rs
    glued = rs.reseeding_glue(_RECORDS, _root(tmp_path, stability=_VALID))
    assert "contradicted at 10× the runs" in glued["lec_rs_awf_estimated"]


@pytest.mark.parametrize("content, what", _BAD_JSON)
def test_reseeding_glue_refuses_unreadable_json_naming_root(tmp_path, content, what):
    from fusion.book.chapters.lecture_weighting import records as rs
    with pytest.raises(ValueError, match=r"^root: book/ledger/stability\.json: .*" + re.escape(what)):
        rs.reseeding_glue(_RECORDS, _root(tmp_path, stability=content))


def test_book_words_refuses_a_deeply_nested_notebook_naming_root(tmp_path):
    from fusion.book.chapters import lecture
    with pytest.raises(ValueError, match=r"^root: 'notebooks/x\.ipynb': nested too deep"):
        lecture.book_words(_root(tmp_path, notebook='{"cells": ' + _DEEP + "}"))


@pytest.mark.parametrize("content, what", _BAD_JSON)
def test_read_object_refuses_the_same_json_naming_the_file(tmp_path, content, what):
    from fusion.book._json import read_object
    p = tmp_path / "r.json"
    p.write_text(content)
    with pytest.raises(ValueError, match=r"^ledger file .*r\.json: .*" + re.escape(what)):
        read_object(p, "ledger file")
    p.write_text(_VALID)
    assert read_object(p, "ledger file")["runs_factor"] == 3


# --- B5: a glue-key suffix is ASCII letters, digits and underscores (fix36b's prefix rule at the other end) ----------

@settings(max_examples=60, deadline=None)
@given(suffix=st.text(max_size=4) | st.sampled_from(["", "_an", "é", "e\u0301", "ｘ", "a b", "x.y", "_1"]))
def test_glue_suffix_is_ascii_identifier_text(suffix):
    from fusion.book.glue import _glue_suffix
    if suffix.isascii() and f"k{suffix}".isidentifier():
        assert _glue_suffix(suffix, "suffix") == suffix
    else:
        with pytest.raises(ValueError, match=r"^suffix must be a glue key suffix \(ASCII"):
            _glue_suffix(suffix, "suffix")


def _weight_search_call():
    """The chapter 05 registry's valid weight_search_numbers call, built small (2 runs, one FOA seed)."""
    from fusion.book.chapters import ci
    from fusion.estimates.ci import ci_objective
    Q, R1, _ = ci.printed_covariances()
    wp = ci.weight_pair(R1, R1 / 9, Q, 2, seed=1, search_seed=2, fruit_fly_seeds=[3], runs=2, T=8.0)
    flat = ci_objective(np.linspace(0, 1, 11), R1, R1)
    return ci, wp, dict(res=wp.res, flat=flat, fruit_fly_seeds=wp.fruit_fly_seeds)


def test_weight_search_numbers_suffix_and_flat_named():
    ci, wp, kw = _weight_search_call()
    Q = ci.printed_covariances()[0]
    wp_an = ci.weight_pair(*ci.ANISO_R, Q, 2, seed=4, search_seed=2, fruit_fly_seeds=[3], runs=2, T=8.0)
    assert ci.weight_claim_inputs(wp, wp_an, kw["flat"]).flat_level > 0
    assert "ci_flat_range_an" in ci.weight_search_numbers(**kw, suffix="_an")
    for bad in ("a b", "x.y", "é", "ｘ"):
        with pytest.raises(ValueError, match=r"^suffix must be a glue key suffix"):
            ci.weight_search_numbers(**kw, suffix=bad)
    for flat in (np.zeros(11), -np.ones(11)):   # a mean of zero was divided by, the refusal named "value"
        with pytest.raises(ValueError, match=r"^flat must hold positive values"):
            ci.weight_search_numbers(**dict(kw, flat=flat))
        with pytest.raises(ValueError, match=r"^flat must hold positive values"):
            ci.weight_claim_inputs(wp, wp_an, flat)


# --- B7: a repeated omega in the Stone Soup record is refused by place (the 33b repeated-row rule) --------------------

def test_stonesoup_check_refuses_two_rows_at_one_omega():
    import copy
    from fusion._paths import file_json
    from fusion.book.chapters.chernoff import peers
    rec = file_json(peers.STONESOUP_RECORD, "record")
    assert len(peers.stonesoup_check(rec)[0]) == len(rec["rows"])
    i = [r["omega"] for r in rec["rows"]].index(0.8)
    row = copy.deepcopy(rec["rows"][i])
    row["innovation_covariance"] = (np.array(row["innovation_covariance"]) * 3).tolist()
    rec["rows"].append(row)   # the last row replaced the recorded one at 0.8 silently
    n = len(rec["rows"]) - 1
    with pytest.raises(ValueError, match=re.escape(f"record['rows'][{i}] and record['rows'][{n}] are both at omega")):
        peers.stonesoup_check(rec)


# --- B8: the stage share and ratio from the measured seconds, not from the table's 0.1 ms (no NaN glued) -------------

def test_benchmark_cost_share_of_fast_stages_is_a_number(tmp_path):
    from pathlib import Path
    from fusion.book.chapters.chernoff import swarm
    bench = json.loads((Path(__file__).parents[1] / "benchmarks" / "results" / "chernoff.json").read_text())
    for m in bench["measurements"]:
        if "stage" in m:
            m["value"] = 1e-5   # positive seconds per frame, 0.0 ms at the table's 0.1 ms
    p = tmp_path / "chernoff.json"
    p.write_text(json.dumps(bench))
    values = swarm.benchmark_cost(p)[1]
    patent = len([m for m in bench["measurements"] if "stage" in m and m["stage"] in swarm.PATENT_STAGES])
    assert f"a share {1 / patent:.2f} of the patent's own stages" in values["chf_bench_stage_text"]
    assert "in the study's own stage costs 1.0 times" in values["chf_pso_ratio_text"]


# --- B3/B4: glue_27 on a one-sensor study and on an ill-conditioned one (valid studies of correlated_study) -----------

@pytest.mark.parametrize("kw", [dict(sigma=(1.0,)), dict(sigma=(0.01, 0.02)), dict(sigma_env=300.0)])
def test_glue_27_takes_valid_edge_studies(kw):
    from fusion.book.chapters.lecture_correlated import correlated as co
    from fusion.scenarios import lecture_correlated as lsc
    out = co.glue_27(lsc.correlated_study(runs=100, **kw))
    assert out["lec_cor_runs"] == 100


def test_glue_27_check_is_not_vacuous_on_an_ill_conditioned_study(monkeypatch):
    """The scaled tolerance is capped at 1e-4: on a valid study with cond(R) = 1.8e10 (own SDs 1e-5 and 2e-5), where
    100 eps cond(R) is 4e-4, the unperturbed solvers agree and a structured solver off by 3e-4 (relative) is caught."""
    from fusion.book.chapters.lecture_correlated import correlated as co
    from fusion.scenarios import lecture_correlated as lsc
    from fusion.readings import correlated as rc
    real = rc.gls_low_rank

    class _Off:
        def __init__(self, res):
            self.x = res.x * (1 + 3e-4)

    study = lsc.correlated_study(runs=100, sigma=(1e-5, 2e-5))
    assert co.glue_27(study)["lec_cor_runs"] == 100
    monkeypatch.setattr(co.co, "gls_low_rank", lambda *a, **k: _Off(real(*a, **k)))
    with pytest.raises(RuntimeError, match="Sherman-Morrison-Woodbury"):
        co.glue_27(study)
