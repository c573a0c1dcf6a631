"""Tests of chapter 03's package code (lecture notes §2.6): the wavelet table and the chapter's claims."""

from __future__ import annotations

import numpy as np

from fusion.book.chapters import lecture_wavelets as ch
from fusion.scenarios import lecture as sc


def test_table_26_matches_the_study_errors_and_claims_follow_them():
    s = sc.wavelet_study(runs=100, length=256)
    tab = ch.table_26(s)
    err = s["err"]
    n = s["gains"].size
    assert tab.shape[1] == n
    for j in range(n):
        col = tab.iloc[:, j]
        assert col["MSE raw"] == round(float(err["raw"][:, j].mean()), 5)
        assert col["P(rec < raw)"] == round(float(np.mean(err["max"][:, j] < err["raw"][:, j])), 5)
    led = ch.claims(s)
    assert led.chapter == "notebooks/03_lecture_wavelets" and led.filename == "lecture003-03.json"
    (c,) = led.claims
    assert not c.headline and c.link == "lec-crit-wavelet"
    # one alternative per other sensor, plus the own-denoised reference
    assert len(c.alternatives) == n
    mean, lo, hi = c.alternatives[-1].evidence.interval()
    d = err["max"][:, 0] - err["denoised"][:, 0]
    assert mean == np.mean(d) and lo < mean < hi
