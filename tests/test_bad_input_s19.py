"""Bad input found by the nineteenth session's own reading (issue 35), besides the fuzz rounds' files."""

from __future__ import annotations

import time

import numpy as np
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


@pytest.mark.parametrize("value", [np.clongdouble(complex(0.5, -2.25)), np.array(np.clongdouble(complex(0.5, -2.25)))])
def test_glue_all_glues_a_complex_longdouble_as_a_complex(monkeypatch, value):
    """Left open by the last session: a complex longdouble was glued as itself (``.item()`` keeps it), printing
    numpy's ``np.clongdouble(...)`` repr where a complex128 prints a Python complex. Each part converted by the
    longdouble rule; a part beyond float's range refused by name."""
    from fusion.book import glue as G

    glued = []
    monkeypatch.setattr("myst_nb.glue", lambda key, v, display: glued.append(v))
    G.glue_all({"x-a": value})
    assert glued == [complex(0.5, -2.25)] and type(glued[0]) is complex


@pytest.mark.skipif(np.finfo(np.longdouble).tiny >= np.finfo(np.float64).tiny, reason="longdouble is float64 here")
def test_glue_all_refuses_a_complex_longdouble_beyond_float_range(monkeypatch):
    from fusion.book import glue as G

    glued = []
    monkeypatch.setattr("myst_nb.glue", lambda key, v, display: glued.append(v))
    with pytest.raises(ValueError, match=r"^values\[.x-b.\] must be a number within float's range"):
        G.glue_all({"x-a": 1.0, "x-b": np.clongdouble(1) + np.clongdouble(1j) * np.longdouble("1e-400")})
    assert glued == []
