"""Tests of chapter 03's package code (lecture notes §2.6): the E2.6 table, the signal table and the claims."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.stats import binomtest

from _helpers import one_computation

from fusion.book.chapters import lecture_wavelets as ch
from fusion.book.ledger import Comparison, Conjunction
from fusion.scenarios import wavelet_sensors as ws


@pytest.fixture(scope="module")
def small() -> dict:
    sg = ws.signal_study(length=256, runs=100, level=3)
    e26 = ws.signal_study(signals=(ws.Signal.TWO_TONES,), modes=("hard",), normalisers=("max", "max-raw", "median", "lsq"),
                          length=256, runs=150, level=3)
    m = ws.mechanism_study(length=256, runs=100, configs=ws.CONFIGS[:2] + ws.CONFIGS[6:7])
    v = ws.variance_study(length=256, runs=100, readings=("batch", "running", "equal"))
    return {"sg": sg, "e26": e26, "m": m, "v": v}


def test_table_26_matches_the_study_errors(small: dict) -> None:
    e = small["e26"]
    tab = ch.table_26_display(e)
    c = e.cases[ws.Signal.TWO_TONES, "hard", "max"]
    for j in range(4):
        col = tab.iloc[:, j]
        assert col["MSE ×10⁴ raw"] == f"{1e4 * c['raw']['mse'][:, j].mean():.2f}"
        assert col["P(rec < raw)"] == f"{np.mean(c['reconstructed']['mse'][:, j] < c['raw']['mse'][:, j]):.2f}"
        assert col["MSE ×10⁴ reconstructed (lsq)"] == (
            f"{1e4 * e.cases[ws.Signal.TWO_TONES, 'hard', 'lsq']['reconstructed']['mse'][:, j].mean():.2f}")
    g = ch.glue_26(e, first=100)
    d3 = c["reconstructed"]["mse"][:, 2] - c["denoised"]["mse"][:, 2]
    assert 0 <= g["lec_wv_n_spike_worse_4"] <= g["lec_wv_n_worse_4"] <= 150
    # the tail statistics split the whole difference: the top 1 % (one run of 150) plus the mean of the rest
    total = 1e4 * d3.sum()
    assert g["lec_wv_top_share_3"] * abs(total) + 149 * g["lec_wv_mean_wo_top_3"] == pytest.approx(
        total, abs=0.005 * abs(total) + 149 * 0.005)
    # the median has at least half of the runs on each side (to its rounding)
    assert min(np.mean(1e4 * d3 <= g["lec_wv_den_med_3"] + 0.005), np.mean(1e4 * d3 >= g["lec_wv_den_med_3"] - 0.005)) >= 0.5
    ci = binomtest(int(np.sum(d3 < 0)), 150).proportion_ci(0.95)
    assert g["lec_wv_win_lo_3"] == pytest.approx(ci.low, abs=6e-4)
    first = Comparison(c["reconstructed"]["mse"][:100, 2], c["denoised"]["mse"][:100, 2], "a", "b", "less", "m")
    assert g["lec_wv_first_d_3"] == pytest.approx(1e4 * first.interval()[0], abs=0.006)
    # the record's verdict is the conjunction over all runs; without `first` no first-runs keys
    whole = ch.sensor_conjunction(c["reconstructed"]["mse"], c["denoised"]["mse"], "r", "d", "m", 1)
    g0 = ch.glue_26(e)
    assert g0["lec_wv_helps_status"] == ch.status_text(whole) and g0["lec_wv_runs"] == 150
    assert not any(k.startswith("lec_wv_first") for k in g0)


def test_the_primary_cell_comes_from_e26(small: dict) -> None:
    sg, e26 = small["sg"], small["e26"]
    assert ch.cell(sg, e26, ch.PRIMARY).runs == 150
    assert ch.cell(sg, e26, (ws.Signal.SLOW, "hard", "max")).runs == 100
    assert ch.cell(sg, None, ch.PRIMARY).runs == 100
    tab = ch.table_signals(sg, e26)
    assert tab.loc[("two tones", "hard"), "runs"] == "150 (E2.6: reading more-runs)" and tab.loc[("slow", "soft"), "runs"] == "100"
    assert "max of the raw data: MSE < own denoised" not in tab.columns        # sg has no raw-maximum case
    sens = ch.table_sensitivity_display(small["m"], e26)
    assert list(sens["runs (verdicts)"]) == ["150 (E2.6: reading more-runs)", "100", "100"]


def test_sign_conjunction_is_the_fraction_of_runs_won(small: dict) -> None:
    c = small["e26"].cases[ws.Signal.TWO_TONES, "hard", "max"]
    s = ch.sign_conjunction(c["reconstructed"]["mse"], c["denoised"]["mse"], "rec", "den", 1)
    for j, (_, ev) in enumerate(s.parts):
        mean, _, _ = ev.interval()
        assert mean + 0.5 == pytest.approx(np.mean(c["reconstructed"]["mse"][:, j] < c["denoised"]["mse"][:, j]))


@pytest.fixture(scope="module")
def full() -> dict:
    """Every study the evidence functions take, small: 100 runs (E2.6: 150), I = 256 (the settings' study 512)."""
    kw = {"length": 256, "runs": 100}
    return {"sg": ws.signal_study(normalisers=("max", "max-raw", "median"), level=3, **kw),
            "m26": ws.mechanism_study(length=512, runs=100), "v26": ws.variance_study(**kw),
            "g1": ws.signal_study(signals=(ws.Signal.TWO_TONES,), modes=("hard",), normalisers=("max", "max-raw"), gains=(1, 1, 1, 1),
                                  level=3, **kw),
            "e26": ws.signal_study(signals=(ws.Signal.TWO_TONES,), modes=("hard",), normalisers=("max",), level=3, length=256,
                                   runs=150),
            "v1": ws.variance_study(gains=(1, 1, 1, 1), **kw),
            "v1r": ws.variance_study(gains=(1, 1, 1, 1), normaliser="max-raw", **kw)}


def test_evidence_of_every_record_and_reading(full: dict) -> None:
    from fusion.book.claims import build_ledger, claims_dir, load

    ev = ch.evidence(full)
    led = build_ledger("lecture003", "notebooks/03_lecture_wavelets", ev, values=ch.ledger_values(full))
    assert [c.id for c in led.claims] == list(ch.EVIDENCE)
    for rid in ("lec-wavelet-better", "lec-wavelet-accurate", "lec-wavelet-fusion-helps"):
        d = ev[rid]
        assert all(isinstance(e, Conjunction) and len(e.parts) == 4 for e in d.values())
        # every reading has at least the primary's runs (rule R4): none is underpowered
        assert all(e.runs >= d["primary"].runs for e in d.values())
    # the primary is the lecture's model (equal gains) with the denoised maximum; lecture-raw-max the same model with
    # the raw maximum; book-model the signal table's cell, raw-max its max-raw case, the extra runs E2.6's
    helps = ev["lec-wavelet-fusion-helps"]
    lit = full["g1"].cases[ch.PRIMARY]
    np.testing.assert_allclose(helps["primary"].parts[2][1].a, lit["reconstructed"]["mse"][:, 2])
    lraw = full["g1"].cases[(*ch.PRIMARY[:2], "max-raw")]
    np.testing.assert_allclose(helps["lecture-raw-max"].parts[2][1].a, lraw["reconstructed"]["mse"][:, 2])
    c = full["sg"].cases[ch.PRIMARY]
    np.testing.assert_allclose(helps["book-model"].parts[2][1].a, c["reconstructed"]["mse"][:, 2])
    raw = full["sg"].cases[(*ch.PRIMARY[:2], "max-raw")]
    np.testing.assert_allclose(helps["raw-max"].parts[0][1].b, raw["denoised"]["mse"][:, 0])
    np.testing.assert_allclose(helps["raw-max"].parts[0][1].a, raw["reconstructed"]["mse"][:, 0])
    assert helps["more-runs"].runs == 150 and helps["lecture-raw-max"].runs == 100
    # no two readings are the same computation
    texts = [e.summary() for e in helps.values()]
    assert len(texts) == len(set(texts))
    # the weighting record: the fused signal against S/max S, credibility weights against equal ones, on the
    # lecture's model (equal gains, the denoised maximum); book-model on the book's gains
    v = full["v1"]
    w = ev["lec-wavelet-weighting"]["primary"]
    assert w.a == pytest.approx(tuple(1e4 * v.fused_mse["batch"]))          # in units of 10⁻⁴
    assert w.b == pytest.approx(tuple(1e4 * v.fused_mse["equal"]))
    wb = ev["lec-wavelet-weighting"]["book-model"]
    assert wb.a == pytest.approx(tuple(1e4 * full["v26"].fused_mse["batch"]))
    # the claim file's reading keys are the evidence's
    cf = load(claims_dir() / "lecture003.yaml")
    for rid, d in ev.items():
        assert {r.key for r in cf.record(rid).readings} | {"primary"} == set(d)


def test_evidence_refuses_studies_with_fewer_runs(full: dict) -> None:
    short = dict(full, v26=ws.variance_study(length=256, runs=50))
    with pytest.raises(ValueError, match="fewer runs"):
        ch.evidence(short)
    with pytest.raises(ValueError, match="studies"):
        ch.evidence({"sg": full["sg"]})


def test_mean_only_status_is_the_t_interval() -> None:
    rng = np.random.default_rng(3)
    b = rng.normal(10, 1, 200)
    assert ch.mean_only_status(b - 2 + rng.normal(0, 0.1, 200), b) == "reproduced"
    assert ch.mean_only_status(b + 2 + rng.normal(0, 0.1, 200), b) == "contradicted"
    assert ch.mean_only_status(b + rng.normal(0, 0.01, 200), b) == "not distinguishable"   # within the 5 % margin
    heavy = np.r_[rng.normal(-0.5, 0.1, 199), 1e4]   # typical run lower, mean carried by one run: undecided
    assert ch.mean_only_status(b + heavy, b) == "not distinguishable"
    with pytest.raises(ValueError, match="paired"):
        ch.mean_only_status([1.0], [2.0])


def test_status_text_names_the_deciding_sensors(small: dict) -> None:
    tab = ch.table_signals(small["sg"])
    assert tab.shape[0] == 8 and "variance < raw" in tab.columns
    for cell in tab["MSE < own denoised"]:
        assert cell == "reproduced" or cell.split(":")[0] in ("contradicted", "not distinguishable")
    assert tab.loc[("two tones", "hard"), "data variance over time < raw and < own denoised"] == "(signal varies)"


def test_seed_table_rows(small: dict) -> None:
    e26 = small["e26"]
    ss = ws.seed_study(seeds=(7,), runs=100, length=256, level=3)
    tab = ch.table_seeds(e26, block=100, ss=ss)
    # whole blocks only (the last 50 runs make no block)
    assert list(tab.index) == ["runs 1-100", "seed 7, 100 runs", "all 150 runs (E2.6, a reading)"]
    # a block is the paired comparison of exactly its runs
    c = e26.cases[ch.PRIMARY]
    d = c["reconstructed"]["mse"][:100, 2] - c["denoised"]["mse"][:100, 2]
    assert tab.loc["runs 1-100", "sensor 3 ×10⁴"].startswith(f"{1e4 * d.mean():.1f} [")
    g = ch.glue_seeds(e26, block=100)
    assert g["lec_wsd_n"] == 1 and g["lec_wsd_n_r"] + g["lec_wsd_n_n"] + g["lec_wsd_n_c"] == 1
    # the counts are the statuses of the table's block rows, the typical-run count that of the sign test
    assert g["lec_wsd_n_r"] == int(tab.loc["runs 1-100", "every sensor"] == "reproduced")
    sign = ch.sign_conjunction(c["reconstructed"]["mse"][:100], c["denoised"]["mse"][:100], "r", "d", 1)
    assert g["lec_wsd_n_typ"] == int(sign.status() == "reproduced")
    # several block sizes side by side, each under its own key; one block of all runs is the record
    gk = ch.glue_seeds(e26, block=150, key="wsdk")
    assert gk["lec_wsdk_runs"] == 150 and gk["lec_wsdk_n"] == 1
    whole = ch.table_seeds(e26, block=150)
    assert list(whole.index) == ["runs 1-150", "all 150 runs (E2.6, a reading)"]
    assert whole.iloc[0].equals(whole.iloc[1])
    assert gk["lec_wsdk_n_r"] == int(whole.iloc[1]["every sensor"] == "reproduced")
    with pytest.raises(ValueError, match="block"):
        ch.table_seeds(e26, block=151)


def test_split_tables_are_the_full_table(small: dict) -> None:
    sg, e26, m = small["sg"], small["e26"], small["m"]
    full = ch.table_signals(sg, e26)
    parts = [ch.table_signals(sg, e26, part=p) for p in ("verdicts", "normalisers")]
    assert sorted(c for p in parts for c in p.columns) == sorted(full.columns)
    sens = ch.table_sensitivity_display(m, e26)
    sp = [ch.table_sensitivity_display(m, e26, part=p) for p in ("numbers", "verdicts")]
    assert sorted(c for p in sp for c in p.columns) == sorted(sens.columns)
    with pytest.raises(ValueError, match="part"):
        ch.table_signals(sg, e26, part="half")


def test_stochastic_record_reseeds_through_the_claims_file() -> None:
    import json
    import math

    from fusion.book import stability
    from fusion.book.claims import claims_dir, evaluate, load
    from fusion.book.ledger import ledger_dir

    def plain(x: object) -> object:
        def fix(v: object) -> object:
            if isinstance(v, float) and not math.isfinite(v):
                return None
            if isinstance(v, dict):
                return {k: fix(w) for k, w in v.items()}
            if isinstance(v, (list, tuple)):
                return [fix(w) for w in v]
            return v
        return fix(json.loads(json.dumps(x)))

    cf = load(claims_dir() / "lecture003.yaml")
    rid = "lec-wavelet-weighting"
    spec = cf.record(rid)
    assert spec.evidence.endswith(":ev_wavelet_weighting")
    led = {r["id"]: r for r in json.loads((ledger_dir() / "lecture003-03.json").read_text(encoding="utf-8"))["claims"]}
    rec = led[rid]
    # the chapter's seed and runs give the committed record: status and numbers, primary and a reading
    prim = stability._judged(evaluate(spec, "primary", ch.SEED, rec["runs"]), cf.margin(spec))
    assert prim.status() == rec["primary_status"] and plain(prim.to_dict()) == plain(rec["evidence"])
    keys = [r.key for r in spec.readings if r.key != "primary"]
    alt = rec["alternatives"][keys.index("every-sensor")]
    ev = stability._judged(evaluate(spec, "every-sensor", ch.SEED, rec["runs"]), cf.margin(spec))
    assert ev.status() == alt["status"] and plain(ev.to_dict()) == plain(alt["evidence"])
    assert one_computation(ch.study("v1"), ch.study("v1", ch.SEED, 300))   # the chapter's study, from the cache
    # another seed: valid evidence of other runs; E2.6's extra runs at the reading's own run count
    other = evaluate(spec, "primary", seed=7, runs=100)
    assert isinstance(other, Comparison) and other.status() in {"reproduced", "contradicted", "not distinguishable"}
    more = evaluate(cf.record("lec-wavelet-better"), "more-runs", seed=7, runs=100)
    assert isinstance(more, Conjunction) and more.runs == 100 and len(more.parts) == 4
    with pytest.raises(ValueError, match="settings"):
        ch.ev_wavelet_accurate({"reading": "no-such-reading"}, seed=7, runs=100)
    assert all(x.settings == {"reading": x.key} for r in ch.EVIDENCE for x in cf.record(r).readings
               if x.key != "primary")
    assert [r.runs for r in cf.record("lec-wavelet-better").readings if r.key == "more-runs"] == [ch.RUNS["e26"]]


def test_typical_run_is_the_sign_conjunction(small: dict) -> None:
    c = small["e26"].cases[ws.Signal.TWO_TONES, "hard", "max"]
    rec, den = c["reconstructed"]["mse"], c["denoised"]["mse"]
    conj = ch.sensor_conjunction(rec, den, "rec", "den", "MSE", 1)
    t, s = ch.typical_run(conj), ch.sign_conjunction(rec, den, "rec", "den", 1)
    assert t.status() == s.status()
    for (_, a), (_, b) in zip(t.parts, s.parts):
        assert a.a == b.a and a.status() == b.status()
    g = ch.typical_run(Comparison(rec[:, 0], den[:, 0], "rec", "den", "greater", "MSE"))
    assert np.mean(g.a) == pytest.approx(np.mean(rec[:, 0] > den[:, 0]))
    with pytest.raises(ValueError, match="equal"):
        ch.typical_run(Comparison(rec[:, 0], den[:, 0], "rec", "den", "equal", "MSE"))


def test_typical_table_keeps_the_ledger_status_and_counts(full: dict) -> None:
    ev = ch.evidence(full)
    tab = ch.table_typical(ev)
    assert len(tab) == sum(len(r) for r in ev.values())
    for (rid, key), row in tab.iterrows():
        e = ev[rid][key]
        assert row["by the mean"].split(":")[0] == e.status()
        assert row["typical run (sign test)"].split(":")[0] == ch.typical_run(e).status()
        assert 0.0 <= row["least share of runs won"] <= 1.0
    g = ch.glue_typical(tab)
    assert g["lec_wtyp_agree"] + g["lec_wtyp_typ_only"] + g["lec_wtyp_mean_only"] <= g["lec_wtyp_n"] == len(tab)
    assert g["lec_wtyp_typ_r"] - g["lec_wtyp_mean_r"] == g["lec_wtyp_typ_only"] - g["lec_wtyp_mean_only"]


def test_length_table_matches_the_primary_study() -> None:
    studies = {n: ch.length_study(n, runs=100) for n in (128, 1024)}
    tab = ch.table_lengths(studies)
    g1 = ch.study("g1", runs=100)
    for rid in ("lec-wavelet-better", "lec-wavelet-accurate", "lec-wavelet-fusion-helps"):
        assert tab.loc[1024, rid] == ch.status_text(ch.EVIDENCE[rid]({"reading": "primary"}, runs=100))
    assert np.array_equal(studies[1024].cases[ch.PRIMARY]["reconstructed"]["mse"],
                          g1.cases[ch.PRIMARY]["reconstructed"]["mse"])
    g = ch.glue_lengths(tab)
    assert (g["lec_wlen_min"], g["lec_wlen_ref"], g["lec_wlen_max"], g["lec_wlen_n"]) == (128, 1024, 1024, 2)
    assert 1 <= g["lec_wlen_same"] <= 2 and g["lec_wlen_gain_128"] > 0
    with pytest.raises(ValueError, match="1024"):
        ch.glue_lengths(tab.drop(index=1024))


def test_evidence_functions_from_one_reader() -> None:
    """The four records' evidence functions, made by :func:`fusion.book.chapters.lecture.reading_function`: each is
    the function its record's ``evidence`` field names, named from the record id, defined in the records module,
    with the chapter's seed and runs as defaults and a docstring that names its record."""
    import importlib
    import inspect

    from fusion.book.claims import claims_dir, load

    cf = load(claims_dir() / "lecture003.yaml")
    for rid, fn in ch.EVIDENCE.items():
        mod, name = cf.record(rid).evidence.split(":")
        assert getattr(importlib.import_module(mod), name) is fn
        assert fn.__name__ == name == "ev_" + rid.removeprefix("lec-").replace("-", "_")
        assert fn.__module__ == "fusion.book.chapters.lecture_wavelets.records"
        params = inspect.signature(fn).parameters
        assert params["seed"].default == ch.SEED and params["runs"].default == ch.N_RUNS
        assert inspect.getdoc(fn).startswith(f"``{rid}``, one reading: ")
    assert len(set(ch.EVIDENCE.values())) == len(ch.EVIDENCE)
