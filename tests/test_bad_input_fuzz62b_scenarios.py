"""Fuzz 62b C4-C6, D1: a long sequence or mapping argument of a scenario is counted by its length before any entry
is read, and the level a wavelet setting is counted by is the one it runs.

Each function below checked every entry (a method's spec, a name, a config, a seed or flag) before a budget that
needs only the number of entries, and was refused only after 5-10 CPU-s at the input ceiling. The budget now comes
first ("length -> budget -> entries"); the inputs are built outside the timing.
"""

from __future__ import annotations

import numpy as np
import pytest

from _helpers import refused_quickly

N = 10**7   # MAX_COUNT: the most entries a sequence argument may hold


@pytest.fixture(scope="module")
def methods() -> dict:
    """10**6 specs of the mean (8.1-8.3 CPU-s of checks before the fix), built once, outside every timing."""
    return {f"m{i}": {"method": "mean"} for i in range(10**6)}


@pytest.mark.parametrize("call, match", [
    (lambda tc, m: tc.monte_carlo(0, 2, m), "n_runs, n_samples, n_sensors and methods"),
    (lambda tc, m: tc.paired_study(0, 2, m), "n_runs, n_samples, n_sensors and methods"),
    (lambda tc, m: tc.absolute_errors(np.ones((200, 10)), m), "z and methods"),
])
def test_thermocouples_count_methods_by_length(methods, call, match):
    from fusion.scenarios import thermocouples as tc
    refused_quickly(lambda: call(tc, methods), ValueError, match)


def test_thermocouples_methods_floor_is_below_the_methods_work():
    """The count by length is a lower bound: the cheapest method's cost, never above what the specs are counted."""
    from fusion.scenarios import thermocouples as tc
    specs = [{"method": m} for m in ("mean", "support_degree", "belief_degree")]
    for rows, n in ((200, 10), (5000, 3), (1, 100)):
        assert tc._methods_floor(rows, n, 3, "x") <= tc._methods_work(rows, n, specs, "x")
        assert tc._methods_floor(rows, n, 3, "x") == tc._methods_work(rows, n, specs[:1] * 3, "x")
        assert (tc._methods_floor(rows, n, 3, "x", fusions=2, per_reading=tc._PAIRED_READING)
                == tc._methods_work(rows, n, specs[:1] * 3, "x", fusions=2, per_reading=tc._PAIRED_READING))


@pytest.mark.parametrize("arg, entry", [("modes", "hard"), ("normalisers", "max"), ("signals", "slow")])
def test_signal_study_counts_names_by_length(arg, entry):
    """10.3 CPU-s before (every mode read by _names): refused at once, by the same names."""
    from fusion.scenarios import wavelet_sensors as ws
    names = [entry] * N
    refused_quickly(lambda: ws.signal_study(**{arg: names}), ValueError,
                    "signals, modes, normalisers, runs, gains and length")


def test_mechanism_study_counts_configs_by_length():
    from fusion.scenarios import wavelet_sensors as ws
    configs = [dict(ws.CONFIGS[0])] * N
    refused_quickly(lambda: ws.mechanism_study(configs=configs), ValueError, "configs, runs, gains and length")


class _Level:
    """A level whose ``__index__`` (what the run reads) and ``__int__`` disagree."""

    def __init__(self, index: int) -> None:
        self.index = index

    def __index__(self) -> int:
        return self.index

    def __int__(self) -> int:
        return 1


def test_mechanism_study_counts_the_level_it_runs():
    """A level whose int() was 1 and __index__ 8 was counted at 1 and run at 8 (34.5 CPU-s accepted at 8,000 runs);
    the same config with level=8 was refused at once: both are now refused at once."""
    from fusion.scenarios import wavelet_sensors as ws
    cfg = {"wavelet": "db4", "level": _Level(8), "threshold": "universal", "mode": "soft", "transform": "swt"}
    refused_quickly(lambda: ws.mechanism_study(runs=8000, configs=[cfg]), ValueError,
                    r"configs \(levels, wavelets\), runs, gains and length")
    refused_quickly(lambda: ws.mechanism_study(runs=8000, configs=[dict(cfg, level=8)]), ValueError,
                    r"configs \(levels, wavelets\), runs, gains and length")


def test_mechanism_study_records_the_level_read():
    """The result's configs hold the int read, not the caller's object."""
    from fusion.scenarios import wavelet_sensors as ws
    cfg = {"wavelet": "db4", "level": _Level(2), "threshold": "universal", "mode": "soft", "transform": "swt"}
    res = ws.mechanism_study(length=64, runs=2, configs=[cfg])
    assert type(res.configs[0]["level"]) is int and res.configs[0]["level"] == 2
    assert isinstance(cfg["level"], _Level)   # the caller's dict is not changed


@pytest.mark.parametrize("kw", [{"faults": [True] * N}, {"seeds": list(range(N))}])
def test_benchmark_counts_keys_by_length(kw):
    """faults: 0.5 CPU-s at 10**6 (~5 at 10**7) of flag() before the repeat was refused; seeds: 3.8 CPU-s."""
    from fusion.scenarios.lecture_weighting import readings_benchmark as rb
    refused_quickly(lambda: rb.benchmark(**kw), ValueError, "seeds, levels, faults, runs, samples and sigma")


@pytest.fixture(scope="module")
def floats() -> list[float]:
    """10**7 distinct floats, built once, outside every timing."""
    return np.linspace(0.1, 0.9, N).tolist()


def test_repeat_checks_come_after_the_budget(floats):
    """distinct() hashed every entry before the budget (10**7 floats: 13.4 CPU-s for awf_study's levels, 12.9 for
    ridge_study's xs, 3.1 for seed_study's seeds): the budget by the length now comes first. The conversion to an
    array (1.0 CPU-s at 10**7 entries) stays before it, hence 2.5 CPU-s."""
    from fusion.scenarios import lecture_correlated as lc
    from fusion.scenarios import wavelet_sensors as ws
    from fusion.scenarios.lecture_weighting import estimators as est
    refused_quickly(lambda: lc.ridge_study(xs=floats), ValueError, "xs and ks_fixed", cpu=2.5)
    refused_quickly(lambda: est.awf_study(levels=floats), ValueError, "levels, runs, k_max and sigma", cpu=2.5)
    seeds = list(range(N))
    refused_quickly(lambda: ws.seed_study(seeds), ValueError, "seeds, runs, length and gains", cpu=2.5)
