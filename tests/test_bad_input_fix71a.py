"""Fix71a (fuzz 63b C1, C2): chapter 07's Monte Carlo counts the runs through each weight matrix, and the wavelet
mechanism study checks each stationary config's level against ``length`` before the draw.

C1: ``monte_carlo`` of a fixed-weight method (or a Kalman method registering from its filtered states) multiplies the
runs by an ``n_dst x n_src`` weight matrix, ``runs x n_src x n_dst`` multiply-adds, but its budget counted
``runs x (n_src + n_dst)``: 8,000 samples and instants at 16,000 runs were accepted and ran 51-55 CPU-s. C2: an
``"swt"`` config whose ``2**level`` does not divide ``length`` was refused by ``denoise`` after the draw and the
earlier configs (~3.6 CPU-s), naming its own ``x``.
"""

from __future__ import annotations

import numpy as np
import pytest

from _helpers import refused_quickly

RUNS, NAMES = "runs, names, t_src and t_dst", "names, t_src and t_dst"


def _times(n: int) -> tuple[np.ndarray, np.ndarray]:
    t = np.linspace(0.0, 100.0, n)
    return t, t + 1e-3


@pytest.mark.parametrize(("names", "n", "inside", "outside"), [
    (["reg_two_point"], 8000, 1400, 1600),          # 656,000 units a run: the edge about 1,520 runs
    (["reg_kalman_two_point"], 12000, 300, 800),    # the product alone 1.44e6 units a run, the filter's pass too
])
def test_monte_carlo_counts_the_runs_through_each_weight_matrix(names, n, inside, outside):
    from fusion.scenarios import time_registration as tr

    t1, t2 = _times(n)
    tr._monte_carlo_work(names, inside, n, n, RUNS, NAMES, name_units=tr.MC_NAME_UNITS)   # accepted by the rule
    refused_quickly(lambda: tr.monte_carlo(names, 1.0, outside, 1, t_src=t1, t_dst=t2), ValueError,
                    "runs, names, t_src and t_dst")


def test_monte_carlo_the_fuzz_calls_refused():
    from fusion.scenarios import time_registration as tr

    for names, runs, n in ((["reg_two_point"], 16000, 8000), (["reg_kalman_two_point"], 2200, 12000)):
        t1, t2 = _times(n)
        refused_quickly(lambda: tr.monte_carlo(names, 1.0, runs, 1, t_src=t1, t_dst=t2), ValueError,
                        "runs, names, t_src and t_dst")


def test_monte_carlo_small_products_still_accepted():
    from fusion.scenarios import time_registration as tr

    out = tr.monte_carlo(["reg_two_point", "reg_kalman_two_point"], 1.0, 50, 1)   # the scenario's 20 and 8
    assert all(v.shape == (50,) and np.all(np.isfinite(v)) for v in out.per_run.values())


@pytest.mark.parametrize(("length", "level"), [(1024, 11), (1088, 7)])
def test_mechanism_study_swt_level_checked_against_length_first(length, level):
    from fusion.scenarios import wavelet_sensors as ws

    cfg = {**ws.CONFIGS[0], "level": level, "transform": "swt"}
    refused_quickly(lambda: ws.mechanism_study(length=length, runs=2, configs=[ws.CONFIGS[0], cfg]), ValueError,
                    rf"configs\[1\].*length.*{length}")


def test_mechanism_study_swt_level_dividing_length_accepted():
    from fusion.scenarios import wavelet_sensors as ws

    out = ws.mechanism_study(length=64, runs=2, configs=[{**ws.CONFIGS[0], "level": 6, "transform": "swt"}])
    assert len(out.labels) == 1
