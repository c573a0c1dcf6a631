"""Fuzz 39b (chapter layer): a reader given a valid producer output at other documented settings refuses it by name,
never a raw KeyError (C4, C6-C8); one-run studies refused by name (C5); the default T named when it misfits (C3);
benchmark_cost's printed ratios (C2, D1); a stale stability sweep (C1)."""

from __future__ import annotations

import warnings
from functools import cache

import numpy as np
import pytest


@cache
def _scenario(runs: int):
    from fusion.book.chapters import ci
    from fusion.scenarios import two_sensor

    Q, R1, R2 = ci.printed_covariances()
    return two_sensor.two_sensor_scenario(R1, R2, Q, np.random.default_rng(5), runs=runs, T=1.0)


@pytest.mark.parametrize("given", [(), ("w",), ("p",), ("w", "p"), ("w", "w")])
@pytest.mark.parametrize("reader", ["rmse_figure", "rmse_table", "slip_table", "rmse_numbers"])
def test_ch05_readers_refuse_a_study_without_its_optional_rules(reader, given):
    """C4: fusion_study without the weights or the published ω is valid; the readers of every curve refuse it when
    they read the rule left out (the published ω: rmse_numbers only; the figures and tables draw the weights)."""
    from fusion.book.chapters import ci
    from fusion.scenarios import two_sensor

    sc = _scenario(2)
    w = np.full(sc.t.size, 0.5)
    args = [w for g in given if g == "w"]
    study = two_sensor.fusion_study(sc, *args, published_omega=0.5 if "p" in given else None)
    calls = {"rmse_figure": lambda: ci.rmse_figure(study, np.ones(sc.t.size, bool), np.ones(sc.t.size)),
             "rmse_table": lambda: ci.rmse_table(study), "slip_table": lambda: ci.slip_table(study),
             "rmse_numbers": lambda: ci.rmse_numbers(study, np.ones(3), np.ones(3, bool), {"x": 1.0})}
    if given == ("w", "w") and reader != "rmse_numbers":
        plt_close = calls[reader]()   # both weights given: accepted (the published ω is rmse_numbers' only)
        if reader == "rmse_figure":
            import matplotlib.pyplot as plt
            plt.close(plt_close)
        return
    with pytest.raises(ValueError, match="^study lacks the rules"):
        calls[reader]()


@pytest.mark.parametrize("reader", ["rmse_table", "rmse_numbers"])
def test_ch05_standard_error_readers_refuse_one_run(reader):
    """C5: a one-run study has no Monte-Carlo standard error: refused naming study, with no numpy warning."""
    from fusion.book.chapters import ci
    from fusion.scenarios import two_sensor

    sc = _scenario(1)
    w = np.full(sc.t.size, 0.5)
    study = two_sensor.fusion_study(sc, w, w, published_omega=0.5)
    leg = ci.straight_leg(study, 1.0, 150.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ValueError, match="^study holds 1 run"):
            if reader == "rmse_table":
                ci.rmse_table(study)
            else:
                ci.rmse_numbers(study, leg.floor, leg.steady, leg.rmse, leg.causal)
