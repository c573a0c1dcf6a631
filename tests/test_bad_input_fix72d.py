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


# --- the class audited (fuzz 64b): a loop step weighed far below its measured cost ----------------------------------

def test_awf_study_weighs_its_levels_steps():
    """A level (a running-estimates pass, four validated rows) measured 700-750 us at 1 run x 100 x 4, counted 2
    LOOP_STEP under the study's 7e9: 175,000 levels (~120 CPU-s) were accepted. Now 140 LOOP_STEP a level within
    MAX_WORK: 7,142 levels accepted by the budget (6.8 CPU-s measured), 7,143 refused at once."""
    from fusion._limits import loop_work
    from fusion.scenarios.lecture_weighting import estimators as es
    loop_work((7142,), 0, "levels", step=es._AWF_LEVEL)
    kw = dict(runs=1, k_max=100, ks=(100,), k_compare=100)
    for n in (7143, 175_000):
        lv = [0.0, 900.0, 100.0] + list(np.arange(1000.0, 1000.0 + n - 3))
        refused_quickly(partial(es.awf_study, levels=lv, **kw), ValueError, r"^levels ask for")


def test_benchmark_weighs_its_keys():
    """A key (~20 methods' validated calls) measured 1.6-2.3 ms, counted 100 LOOP_STEP under the study's 3e9: 29,865
    keys of 1 run x 2 samples (~60 CPU-s) were accepted. Now 400 LOOP_STEP a key within MAX_WORK: 2,500 keys (3.6
    CPU-s measured) accepted by the budget, 2,501 refused at once."""
    from fusion._limits import loop_work
    from fusion.scenarios.lecture_weighting import readings_benchmark as rb
    loop_work((1, 2500, 1), 0, "keys", step=rb._BENCH_KEY)
    for n in (2501, 29_865):
        lv = list(np.arange(1.0, n + 1))
        refused_quickly(partial(rb.benchmark, seeds=(1,), levels=lv, faults=(False,), runs=1, samples=2, fault_from=1),
                        ValueError, r"^seeds, levels and faults ask for")


def test_belief_study_counts_its_sensors_calls():
    """~210 belief_degree calls on one n x n snapshot (and the Perron statistics) were uncounted: 1,666 sensors of 2
    snapshots were accepted (3.98 and 11.05 CPU-s at 400 and 600 sensors, some 90 at 1,666). Now counted: 600
    refused at once; 400 (about 4 CPU-s) within the budget."""
    from fusion.scenarios.lecture_weighting import belief as b
    from fusion._limits import work
    n = 400
    work((2 * 180 * n**2 + 2650 * n**2 + 6 * n**3,), "snapshots and sigma")
    for n in (600, 1666):
        sig = tuple(np.linspace(0.5, 4.0, n))
        refused_quickly(partial(b.belief_study, sigma=sig, snapshots=2), ValueError, r"^snapshots and sigma ask for")


def test_belief_parameter_study_budgets_params_before_hashing_them():
    """grid <= params was checked (each entry of both hashed) before the budget by their number: 2**24 params
    refused after 1.7 CPU-s (3.8 at 2**25). Now the budget comes first (0.26 CPU-s, the array's checks)."""
    from fusion.scenarios.lecture_weighting import belief as b
    vals = np.arange(1.0, 2**24 + 1)
    refused_quickly(partial(b.belief_parameter_study, params=vals, grid=vals[:3] + 0.5), ValueError,
                    r"^params and snapshots ask for")
    with pytest.raises(ValueError, match="^grid must be a subset of params"):
        b.belief_parameter_study(params=(1.0, 2.0), grid=(1.0, 2.0, 3.0), snapshots=2)


def test_seed_study_counts_each_seeds_samples():
    """A seed (a signal_study) measured 53-77 ms at 100 runs x 1,024 x 4 gains, counted 1 unit a sample: 1,409 seeds
    (~75 CPU-s) were accepted. Now 40 units a sample (signal_study's two steps of 20): 59 seeds within the budget."""
    from fusion._limits import LOOP_STEP, loop_work
    from fusion.scenarios import wavelet_sensors as ws
    loop_work((59,), 40 * 100 * 1024 * 4, "seeds", step=300 * LOOP_STEP)
    for n in (60, 1409):
        refused_quickly(partial(ws.seed_study, seeds=list(range(n)), runs=100, length=1024), ValueError,
                        r"^seeds, runs, length and gains ask for")
