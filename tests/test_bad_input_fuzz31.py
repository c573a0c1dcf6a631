"""Fuzz 31b C5: chapter functions that checked an ``__index__`` argument and then used the raw object.

Each now uses the int its check returns, so an object with only ``__index__`` gives the plain int's result (before:
a TypeError naming no argument). ``glue_seeds``' ``block`` is the same fix (its study is too costly to build here;
the chapter registry's sweep calls it). Fuzz 31b C2 (``premise_studies``) is tested in test_bad_input_swaps.py.
"""
from __future__ import annotations

import matplotlib
import numpy as np

matplotlib.use("Agg")


class Idx:
    """An integer given only through ``__index__``."""

    def __init__(self, v: int) -> None:
        self.v = int(v)

    def __index__(self) -> int:
        return self.v


def test_ir_readings_reads_runs_once_as_an_int():
    from fusion.book.chapters import ci
    kw = dict(T=0.1, seed=1, duration=2.0, t_min=0.0, scaled_axes=("x",))
    got, want = ci.ir_readings(runs=Idx(2), **kw), ci.ir_readings(runs=2, **kw)
    assert got.runs == 2 and type(got.runs) is int
    for k, by_method in want.run_rmse.items():
        for m, v in by_method.items():
            np.testing.assert_array_equal(got.run_rmse[k][m], v)


def test_figure_readings_reads_its_window_as_ints():
    import matplotlib.pyplot as plt

    from fusion.book.chapters import ofs
    readings = np.random.default_rng(0).normal(20.0, 1.0, (100, 10))
    fig = ofs.figure_readings(readings, highlight=(2,), window=(Idx(5), Idx(15)))
    plt.close(fig)
