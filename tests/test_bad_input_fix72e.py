"""Fix 72e (the audit of fuzz 64b's class in chapter 02-04's and the infrared chapter's scenario modules): a loop step
weighed far below its measured cost, and a sequence argument printed before the rule that needs only its length."""

from __future__ import annotations

import functools

import numpy as np
import pytest

from _helpers import refused_quickly
from fusion.scenarios import infrared_radar as ir
from fusion.scenarios._infrared_budget import _SIMULATE_SCAN_UNITS, _simulate_budget
from fusion.scenarios.lecture_weighting.estimators import ar1_study


def test_simulate_scan_weighs_its_measured_cost():
    # 77-82 us a scan of the three filters measured; 3 LOOP_STEP (30 us) let 1 run of 327,976 scans through (~26 CPU-s)
    assert _SIMULATE_SCAN_UNITS >= 15_000
    _simulate_budget(1, 62_313)  # the edge of 1 run, just inside (about 5 CPU-s): accepted by the rule
    with pytest.raises(ValueError, match=r"T and duration \(with runs\)"):
        _simulate_budget(1, 62_314)


def test_simulate_beyond_its_scans_refused_quickly():
    call = functools.partial(ir.simulate, np.random.default_rng(0), runs=1, T=0.1, duration=100_000 * 0.1)
    refused_quickly(call, ValueError, r"T and duration \(with runs\)")


def test_simulate_book_size_accepted():
    sim = ir.simulate(np.random.default_rng(0), runs=2, T=0.1, duration=10.0)
    assert sim.t.size == 101


def test_sigmas_not_printed_whole():
    # fix72e: every entry of sigma was printed when one was not positive (10**7 of them: a message of 60 million
    # characters, 1.6 CPU-s); the first bad one is shown, and the count is refused first
    sig = np.ones(9_000)
    sig[4_321] = -1.0
    with pytest.raises(ValueError, match=r"sigma\[4321\] = -1\.0") as info:
        ar1_study(sigma=sig)
    assert len(str(info.value)) < 500
    many = -np.ones(10**6)
    refused_quickly(functools.partial(ar1_study, sigma=many), ValueError, "beyond the ceiling")


def test_range_bearing_sensors_refused_by_their_number():
    # fix72e: the rows were checked and stored as tuples before any rule on their number (2 million: 2.1 CPU-s,
    # accepted); the ceiling of a count of sensors (a dimension) now refuses them by the length first
    from fusion.scenarios.range_bearing_scenario import RangeBearingScenario

    S = np.random.default_rng(0).uniform(0.0, 1e4, (10_001, 2))
    refused_quickly(functools.partial(RangeBearingScenario, sensors=S), ValueError, r"sensors holds 10,001 sensors",
                    cpu=0.2)
    many = np.random.default_rng(1).uniform(0.0, 1e4, (2 * 10**6, 2))
    refused_quickly(functools.partial(RangeBearingScenario, sensors=many), ValueError, "beyond the ceiling", cpu=0.5)
    assert len(RangeBearingScenario(sensors=S[:10_000]).sensors) == 10_000   # at the ceiling: accepted
