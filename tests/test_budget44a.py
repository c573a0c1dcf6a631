"""Fix44a: the Kalman filters' runs weighed at their measured cost (fuzz 39a C1); ``fusion_runs``' runs counted
(fuzz 39a C4)."""
from __future__ import annotations

import time

import numpy as np
import pytest

from fusion._limits import MAX_WORK


# --- time_registration.fusion_runs: its runs x methods held to the work budget (fuzz 39a C4) --------------------

@pytest.mark.parametrize(("names", "edge"), [(["reg_kalman_two_point"], 200_000), (["reg_two_point"], 100_000),
                                             (["reg_least_squares"], 33_333), (["reg_cubic_spline"], 33_333),
                                             (["reg_improved", "reg_two_point", "reg_kalman_predict",
                                               "reg_least_squares"], 20_000)])
def test_fusion_runs_edge_accepted_one_more_refused_before_any_draw(monkeypatch, names: list[str], edge: int) -> None:
    """``edge`` runs pass the budget (stopped at the first draw: the work is not run), one more is refused by name,
    at once. The edges are the docstring's (measured 43-317 us a run and method: 7.5-14 CPU-s at the edge)."""
    from fusion.scenarios import time_registration as sc

    class Drawn(Exception):
        pass

    def stop(*args, **kwargs):
        raise Drawn

    monkeypatch.setattr(sc.np.random, "default_rng", stop)
    with pytest.raises(Drawn):
        sc.fusion_runs(names, 1.0, edge, 0)
    t0 = time.process_time()
    with pytest.raises(ValueError, match=r"^runs and names ask for .* beyond the work budget"):
        sc.fusion_runs(names, 1.0, edge + 1, 0)
    assert time.process_time() - t0 < 1.0
    if len(names) == 1:
        doc = " ".join(sc.fusion_runs.__doc__.split())
        assert f"{edge:,} runs" in doc or f"{edge:,} of" in doc


def test_fusion_runs_many_methods_refused_by_name() -> None:
    """A long list of methods at two runs weighs each method's weight matrix and runs (counted, refused at once)."""
    from fusion.scenarios import time_registration as sc
    t0 = time.process_time()
    with pytest.raises(ValueError, match=r"^(names|runs and names) ask for"):
        sc.fusion_runs(["reg_least_squares"] * 40_000, 1.0, 2, 0)
    assert time.process_time() - t0 < 1.0


def test_fusion_runs_small_call_unchanged() -> None:
    from fusion.scenarios import time_registration as sc
    fr = sc.fusion_runs(["reg_two_point", "reg_kalman_two_point"], 1.0, 3, 0)
    assert fr.runs == 3 and all(v.shape == (3,) for v in fr.fused.values())
