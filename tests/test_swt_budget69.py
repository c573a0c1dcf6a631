"""Fuzz 61b C2 (fix69b): the stationary transform (``transform="swt"``) costs about ``I * 2**level`` (``pywt.swt``'s
dilated filter over its zeros once it is longer than the signal, ``pywt.iswt``'s loop over ``2**level`` shifts), which
no budget counted: ``denoise`` of 2**17 samples at level 17 ran 54.7 CPU-s, ``reconstruct`` of (2, 2**15) at level 15
9.8, ``mechanism_study`` of a level-15 stationary config 39.6. One rule, ``fusion.readings.wavelet._swt_work``,
counts it for every caller, before the transform.

fix69f: its first weights (``5 level**2`` a sample) refused a 1-D signal of 2**21 samples at level 10 (1.7 CPU-s) and
under-counted 4 signals of 2**18 at level 14 (12.3 CPU-s): ``pywt.iswtn`` (every array of more than one axis) copies
the whole array at each of its ``2**level`` shifts, ``pywt.iswt`` (1-D) does not; now counted as such."""
import numpy as np
import pytest

from _helpers import refused_quickly
from fusion._validation import MAX_WORK
from fusion.readings import wavelet as wv
from fusion.scenarios.wavelet_sensors import mechanism_study


def test_denoise_swt_deep_level_refused_naming_x_and_level():
    x = np.random.default_rng(0).standard_normal(2**17)
    refused_quickly(lambda: wv.denoise(x, "db4", 17, transform="swt"), ValueError, r"x, level and wavelet")


def test_denoise_swt_edge_by_the_budget_alone():
    # 2**15 samples at level 15 (db4, one 1-D signal) counts ~6.1e8 units, and as one row of a 2-D array ~9.2e8
    # (measured 5.5 CPU-s): accepted; the same at level 16 over 2**16 samples (measured 13.4 CPU-s in fuzz 61b) is
    # refused, as are 8 such rows at level 15
    assert wv._swt_work(1, 2**15, 15, "db4", "x, level and wavelet", flat=True) <= MAX_WORK
    assert wv._swt_work(1, 2**15, 15, "db4", "x, level and wavelet") <= MAX_WORK
    for rows, samples, level in ((1, 2**16, 16), (8, 2**15, 15)):
        with pytest.raises(ValueError, match=r"x, level and wavelet"):
            wv._swt_work(rows, samples, level, "db4", "x, level and wavelet", flat=rows == 1)


class _Transformed(Exception):
    """Raised in place of ``pywt.swt``: the budget let the call through."""


def test_denoise_swt_long_1d_signal_accepted(monkeypatch):
    # one 1-D signal of 2**21 samples at level 10 (db4) ran 1.7 CPU-s, yet the first weights counted 1.1e9 units and
    # refused it: now ~1.7e8 (the call itself stopped at the transform, after the budget)
    def transformed(*args, **kwargs):
        raise _Transformed

    assert wv._swt_work(1, 2**21, 10, "db4", "x, level and wavelet", flat=True) < MAX_WORK / 3
    monkeypatch.setattr(wv.pywt, "swt", transformed)
    with pytest.raises(_Transformed):
        wv.denoise(np.zeros(2**21), "db4", 10, transform="swt")


def test_denoise_swt_rows_at_a_high_level_refused():
    # 4 signals of 2**18 at level 14 (db4) ran 12.3 CPU-s (``iswtn`` copies the 8 MB array at each of 2**14
    # shifts), counted 6.1e8 by the first weights: now ~2.4e9, refused before the transform
    X = np.zeros((4, 2**18))
    refused_quickly(lambda: wv.denoise(X, "db4", 14, transform="swt"), ValueError, r"x, level and wavelet")
    # one 1-D signal has no such copies: 2**16 samples at level 16 (haar) ran 1.7 CPU-s and is inside; the same
    # samples as one row of a 2-D array ran 6.0 CPU-s and are refused
    assert wv._swt_work(1, 2**16, 16, "haar", "x", flat=True) < MAX_WORK / 2
    refused_quickly(lambda: wv.denoise(np.zeros((1, 2**16)), "haar", 16, transform="swt"), ValueError,
                    r"x, level and wavelet")


def test_denoise_swt_long_filter_counts_its_taps():
    # the same depth with db38 (76 taps) instead of haar (2): the dilated filter's zeros are counted per tap
    assert wv._swt_work(1, 2**12, 12, "haar", "x") < wv._swt_work(1, 2**12, 12, "db38", "x") / 2


def test_reconstruct_swt_counts_every_block_and_names_X():
    X = np.random.default_rng(0).standard_normal((2, 2**15))
    refused_quickly(lambda: wv.reconstruct(X, "db4", 15, transform="swt"), ValueError, r"X, level and wavelet")
    with pytest.raises(ValueError, match="level"):
        wv.reconstruct(X, "db4", -1, transform="swt")
    with pytest.raises(ValueError, match="wavelet"):
        wv.reconstruct(X, "no-such-wavelet", 4, transform="swt")


def test_mechanism_study_counts_its_stationary_configs_levels():
    cfg = {"wavelet": "db4", "level": 15, "threshold": "universal", "mode": "hard", "transform": "swt"}
    refused_quickly(lambda: mechanism_study(length=2**15, runs=2, configs=[cfg]), ValueError, r"configs \(levels")
    # the book's own call (300 runs of CONFIGS, two stationary configs at level 4) stays well inside: counted alone
    from fusion.scenarios.wavelet_sensors import _blocks
    calls = 2 * len(_blocks(300, 4 * 1024))
    assert 2 * wv._swt_work(300 * 5, 1024, 4, "db4", "configs", calls) < MAX_WORK / 3
