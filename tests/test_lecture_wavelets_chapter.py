"""Tests of chapter 03's package code (lecture notes §2.6): the E2.6 table, the signal table and the claims."""

from __future__ import annotations

import numpy as np
import pytest

from fusion.book.chapters import lecture_wavelets as ch
from fusion.book.ledger import Conjunction
from fusion.scenarios import lecture as sc
from fusion.scenarios import wavelet_sensors as ws


@pytest.fixture(scope="module")
def small() -> dict:
    sg = ws.signal_study(length=256, runs=100, level=3)
    m = ws.mechanism_study(length=256, runs=100, configs=ws.CONFIGS[:2] + ws.CONFIGS[6:7])
    v = ws.variance_study(length=256, runs=100, readings=("batch", "running"))
    return {"sg": sg, "m": m, "v": v}


def test_table_26_matches_the_study_errors() -> None:
    e = ws.signal_study(signals=("two tones",), modes=("hard",), normalisers=("max", "median", "lsq"), length=256,
                        runs=100, level=3)
    tab = ch.table_26(e)
    c = e["cases"]["two tones", "hard", "max"]
    for j in range(4):
        col = tab.iloc[:, j]
        assert col["MSE raw"] == round(float(c["raw"]["mse"][:, j].mean()), 5)
        assert col["P(rec < raw)"] == round(float(np.mean(c["reconstructed"]["mse"][:, j] < c["raw"]["mse"][:, j])), 5)
        assert col["MSE reconstructed (lsq)"] == round(float(
            e["cases"]["two tones", "hard", "lsq"]["reconstructed"]["mse"][:, j].mean()), 5)
    g = ch.glue_26(e)
    assert 0 <= g["lec_wv_n_spike_worse_4"] <= g["lec_wv_n_spike_4"] <= 100


def test_every_sensor_claims_are_conjunctions_over_the_sensors(small: dict) -> None:
    led = ch.claims(small["sg"], small["m"], small["v"])
    assert led.chapter == "notebooks/03_lecture_wavelets" and led.filename == "lecture003-03.json"
    ids = [c.id for c in led.claims]
    assert ids == ["lec-wavelet-better", "lec-wavelet-accurate", "lec-wavelet-fusion-helps", "lec-wavelet-order"]
    for c in led.claims:
        assert isinstance(c.evidence, Conjunction) and len(c.evidence.parts) == 4
        assert all(isinstance(a.evidence, Conjunction) for a in c.alternatives)
        assert not c.headline and "lec-crit-wavelet" in c.critiques
    helps = led.claims[2]
    # the primary reading is the lecture's hard threshold with the two tones and the maximum normaliser
    key = ch.PRIMARY
    c = small["sg"]["cases"][key]
    d = c["reconstructed"]["mse"][:, 0] - c["denoised"]["mse"][:, 0]
    mean, lo, hi = helps.evidence.parts[0][1].interval()
    assert mean == pytest.approx(np.mean(d)) and lo < mean < hi
    # status of a conjunction: the worst member's
    st = [ev.status() for _, ev in helps.evidence.parts]
    want = "contradicted" if "contradicted" in st else "reproduced" if set(st) == {"reproduced"} else "not distinguishable"
    assert helps.evidence.status() == want
    # one alternative per other (signal, rule) cell, then the metric, the settings and the step-3 reading
    n_cells = len(small["sg"]["signals"]) * len(small["sg"]["modes"]) - 1
    assert len(helps.alternatives) == n_cells + 1 + (len(small["m"]["labels"]) - 1) + 1


def test_status_text_names_the_deciding_sensors(small: dict) -> None:
    tab = ch.table_signals(small["sg"])
    assert tab.shape[0] == 8 and "variance < raw" in tab.columns
    for cell in tab["MSE < own denoised"]:
        assert cell == "reproduced" or cell.split(":")[0] in ("contradicted", "not distinguishable")
    assert tab.loc[("two tones", "hard"), "data variance over time < raw and < own denoised"] == "(signal varies)"


def test_reduced_ledger_from_the_old_study() -> None:
    led = ch.claims(sc.wavelet_study(runs=100, length=256))
    (c,) = led.claims
    assert c.id == "lec-wavelet-accurate" and isinstance(c.evidence, Conjunction)
