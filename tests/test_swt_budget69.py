"""Fuzz 61b C2 (fix69b): the stationary transform (``transform="swt"``) costs about ``I * 2**level`` (``pywt.swt``'s
dilated filter over its zeros once it is longer than the signal, ``pywt.iswt``'s loop over ``2**level`` shifts), which
no budget counted: ``denoise`` of 2**17 samples at level 17 ran 54.7 CPU-s, ``reconstruct`` of (2, 2**15) at level 15
9.8, ``mechanism_study`` of a level-15 stationary config 39.6. One rule, ``fusion.readings.wavelet._swt_work``,
counts it for every caller, before the transform."""
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
    # 2**15 samples at level 15 (db4, one signal) counts ~7.9e8 units (measured ~2.5 CPU-s): accepted; the same at
    # level 16 over 2**16 samples (measured 13.4 CPU-s in fuzz 61b) is refused, as are 8 such signals at level 15
    assert wv._swt_work(1, 2**15, 15, "db4", "x, level and wavelet") <= MAX_WORK
    for rows, samples, level in ((1, 2**16, 16), (8, 2**15, 15)):
        with pytest.raises(ValueError, match=r"x, level and wavelet"):
            wv._swt_work(rows, samples, level, "db4", "x, level and wavelet")


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
