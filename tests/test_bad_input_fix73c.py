"""Fix 73c (fuzz 65a C1, D1): a chapter study whose entry budget counted only part of what it runs.

C1: ``ir_study`` (and ``ir_flown_numbers``) counted the simulation's scans only, so the readings of every rule that
follow (``rmse_by_rule``) were refused after the simulation had run (11.8 and 5.5 CPU-s), naming ``sim`` and
``rules``. D1: ``transient_table`` weighed every method's step as a Kalman filter's, so a smoother alone at its edge
ran 20.1 CPU-s."""

from __future__ import annotations

import functools

import numpy as np
import pytest

from _helpers import refused_quickly
import fusion.book.chapters.time_registration_closed as cl
from fusion.book.chapters.ci import infrared as ci_ir
from fusion.scenarios import infrared_radar as ir
from fusion.scenarios import time_registration as sc


class _Reached(Exception):
    """Raised in place of the work: the call passed its entry budget."""


def _reached(*args: object, **kwargs: object) -> None:
    raise _Reached


def _accepted(call) -> bool:
    try:
        call()
    except _Reached:
        return True
    raise AssertionError("the call neither reached its work nor was refused")


# C1: the simulation and its readings summed at the entry, named by ir_study's own arguments

@pytest.mark.parametrize("args", [(0.1, 1, 150_000, 10.0), (0.001, 1, 1, 62.0), (0.001, 1, 1, 30.0)])
def test_ir_study_refused_before_the_simulation(args: tuple) -> None:
    T, seed, runs, duration = args
    refused_quickly(functools.partial(ci_ir.ir_study, T, seed, runs, duration=duration), ValueError,
                    r"^duration and T \(with runs\) ask for")


def test_ir_study_edges(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(ir, "simulate", _reached)
    # 1 run: 9,126 scans accepted (about 10 CPU-s, nearly all in the readings), 9,127 refused
    assert _accepted(lambda: ci_ir.ir_study(0.001, 1, 1, duration=9.125))
    refused_quickly(lambda: ci_ir.ir_study(0.001, 1, 1, duration=9.126), ValueError, r"^duration and T \(with runs\)")
    # the book's 101 scans: 30,695 runs accepted, 30,696 refused
    assert _accepted(lambda: ci_ir.ir_study(0.1, 1, 30_695))
    refused_quickly(lambda: ci_ir.ir_study(0.1, 1, 30_696), ValueError, r"^duration and T \(with runs\)")


def test_ir_flown_numbers_refused_by_distance() -> None:
    means = {ir.AZIMUTH_MRAD: 0.05, ir.ELEVATION_MRAD: 0.05, ir.X_M: 5.0, ir.Y_M: 7.0}
    # 1e6 m flown at the printed speed: 3,162 s, 31,624 scans of the readings, far beyond; refused before simulating
    refused_quickly(lambda: ci_ir.ir_flown_numbers(1, 1, means, distance=1e6), ValueError, r"^distance \(with runs\)")


# D1: the step weighed by its method's measured cost

def test_transient_table_smoother_edge(monkeypatch: pytest.MonkeyPatch) -> None:
    # 5 LOOP_STEP a smoother's step: 447 samples (horizon up to 895 s) accepted, 448 refused (577 had run 20.1 CPU-s)
    monkeypatch.setattr(np, "arange", _reached)
    for name in ("reg_fixed_lag", "reg_rts_smoother"):
        assert _accepted(lambda: cl.transient_table(894.9, 1.0, [name]))
        refused_quickly(lambda: cl.transient_table(895.0, 1.0, [name]), ValueError, r"^horizon and names ask for")
        refused_quickly(lambda: cl.transient_table(1153.0, 1.0, [name]), ValueError, r"^horizon and names ask for")


def test_transient_table_kalman_and_book_edges(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(np, "arange", _reached)
    assert _accepted(lambda: cl.transient_table(666.0, 1.0))                 # three Kalman methods: unchanged
    refused_quickly(lambda: cl.transient_table(667.0, 1.0), ValueError, r"^horizon and names ask for")
    assert _accepted(lambda: cl.transient_table(1632.9, 1.0, ["reg_qls_next"]))   # a fit per instant: 816 samples
    refused_quickly(lambda: cl.transient_table(1633.0, 1.0, ["reg_qls_next"]), ValueError, "horizon and names")
    assert _accepted(lambda: cl.transient_table(100.0, 1.0, list(sc.METHODS)))   # every method at the book's 100 s


def test_transient_steps_cover_every_method() -> None:
    assert set(cl._TRANSIENT_STEPS) == {m.value for m in sc.METHODS}
    assert cl._TRANSIENT_STEPS["reg_fixed_lag"] > cl._TRANSIENT_STEPS["reg_improved"]
