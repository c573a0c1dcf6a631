"""Bad input found by the nineteenth session's own reading (issue 35), besides the fuzz rounds' files."""

from __future__ import annotations

import time

import pytest


def test_benchmark_counts_the_checked_awf_pair_arrays_at_entry():
    """The readings benchmark runs the checked AWF on (runs, samples, n) readings, whose eight (runs, samples, n, n)
    pair arrays are held at once: 10 runs x 20 samples of 1,000 sensors (1.6e9 floats) were refused by the callee,
    naming its X under a wrapper listing every argument. Now at entry, by the callee's own rule, naming the three
    arguments that set the size."""
    from fusion.scenarios.lecture_weighting import readings_benchmark as rbm

    t0 = time.process_time()
    with pytest.raises(ValueError, match=r"^runs, samples and sigma ask for an array of 1\.6e\+09 elements .*8 arrays"):
        rbm.benchmark(seeds=(1,), runs=10, samples=20, levels=(0.0,), sigma=[1.0] * 1000)
    assert time.process_time() - t0 < 1.0
