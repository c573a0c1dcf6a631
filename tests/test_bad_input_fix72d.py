"""Fuzz 64b C6 and C8 (fix72d): lecture_weighting's tail_study and wavelet_sensors' signal_study.

C6: tail_study printed every threshold (its glue key) before the budget counted them by length: 10**7 thresholds
(runs=100) were refused after 17.6 CPU-s. Now refused by the budget, by the length, before any entry is printed.
C8: signal_study accepted repeated signal names (the result kept one case) and weighed its Python step (a signal's,
rule's or normaliser's few validated calls, 205-300 us measured at 2 runs x 2 sensors x 64 samples) as LOOP_STEP
(10 us): 80,000 copies of one signal ran 44.7 CPU-s, accepted. Now a repeated signal, mode or normaliser is refused
after the budget, and a step weighs 60 LOOP_STEP.
"""

from functools import partial

import numpy as np
import pytest

from _helpers import refused_quickly

KW = dict(modes=["hard"], normalisers=["max"], runs=2, length=64, gains=(1.0, 1.5), sigma=(0.1, 0.1), level=2)


def test_tail_study_counts_thresholds_before_printing_them():
    from fusion.scenarios.lecture_weighting import estimators as es
    t = np.arange(1.0, 2 * 10**6 + 1).tolist()   # each was printed first (~3 us each), refused by a printed repeat
    refused_quickly(partial(es.tail_study, thresholds=t, runs=1000), ValueError, r"^thresholds and runs ask for")


def test_tail_study_edge_by_the_budget():
    from fusion._limits import LOOP_STEP, loop_work
    n = 10**9 // (3 * LOOP_STEP + 100)           # 322,580 thresholds at 100 runs: 1.3 CPU-s measured, accepted
    loop_work((n,), 100, "thresholds and runs", step=3 * LOOP_STEP)
    with pytest.raises(ValueError, match="thresholds and runs"):
        loop_work((n + 1,), 100, "thresholds and runs", step=3 * LOOP_STEP)


@pytest.mark.parametrize("arg, names", [("signals", ["sig_two_tones", "sig_slow", "sig_two_tones"]),
                                        ("modes", ["hard", "hard"]), ("normalisers", ["max", "median", "max"])])
def test_signal_study_refuses_a_repeated_name(arg, names):
    from fusion.scenarios import wavelet_sensors as ws
    kw = {**KW, "signals": ["sig_two_tones"], arg: names}
    with pytest.raises(ValueError, match=rf"^{arg} must not repeat an entry: {arg}\[0\] and {arg}\[2|1\]"):
        ws.signal_study(**kw)


def test_signal_study_weighs_its_step():
    """The edge by the budget alone: 7,678 signals x 1 mode x 2 steps of 65,120 units (60,000 and 20 x 2 x 2 x 64)
    are within it, 7,679 beyond; the old weight (LOOP_STEP) accepted 80,000 (44.7 CPU-s)."""
    from fusion.scenarios import wavelet_sensors as ws
    from fusion.scenarios._wavelet_names import _SIGNAL_STEP
    from fusion._limits import loop_work
    assert list(ws.signal_study(signals=["sig_two_tones"], **KW).signals) == ["sig_two_tones"]
    loop_work((7678, 1, 2), 20 * 2 * 2 * 64, "x", step=_SIGNAL_STEP)
    refused_quickly(partial(ws.signal_study, signals=["sig_two_tones"] * 7679, **KW), ValueError,
                    r"^signals, modes, normalisers, runs, gains and length ask for")
    refused_quickly(partial(ws.signal_study, signals=["sig_two_tones"] * 7678, **KW), ValueError,
                    r"^signals must not repeat")
