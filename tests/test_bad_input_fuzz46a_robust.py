"""Fuzz 46a: the IRLS passes of robust_fuse's "huber" and "biweight" counted at entry, their worst case refused by
``x`` (C1, C1b), and the fair study's methods weighed per row and per reading (C4, C4b)."""

from __future__ import annotations

import time

import numpy as np
import pytest

from fusion.readings.robust import _robust_limit, robust_fuse


def _refused_fast(f, match: str, limit: float = 1.0) -> None:
    t0 = time.process_time()
    with pytest.raises(ValueError, match=match):
        f()
    assert time.process_time() - t0 < limit


# --- C1, C1b -------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("method", ["huber", "biweight"])
@pytest.mark.parametrize(("n", "edge"), [(3, 344_655), (10, 199_900), (101, 30_944)])
def test_c1_irls_worst_case_counted_both_bounds(method, n, edge):
    # up to 500 passes over every row: the edge's worst case ran 4.5 CPU-s (biweight, c_biweight=0.1, n = 101,
    # measured at a tenth of it); one row more is refused by x before any pass
    _robust_limit(edge, n, method, "x")
    with pytest.raises(ValueError, match="^x"):
        _robust_limit(edge + 1, n, method, "x")
    _refused_fast(lambda: robust_fuse(np.zeros((edge + 1, n)), method), r"^x \(its readings per epoch and epochs\)")


def test_c1_fuzz_calls_refused_before_the_passes():
    # C1: a tiled row of 101 readings with c_biweight=0.1 takes all 500 passes in every row (332,000 rows ran 62.5
    # CPU-s); C1b: default options, rows of 3 near 900 with sensor 0 shifted by 1 (4e6 rows ran 29 CPU-s)
    x = np.tile(np.arange(101.0) ** 1.5, (40_000, 1))
    _refused_fast(lambda: robust_fuse(x, "biweight", c_biweight=0.1), "^x")
    z = 900 + np.random.default_rng(0).standard_normal((400_000, 3))
    z[:, 0] += 1.0
    for method in ("huber", "biweight"):
        _refused_fast(lambda: robust_fuse(z, method), "^x")
    # well inside: the same data, a tenth of the edge, still fused
    assert np.all(np.isfinite(robust_fuse(z[:34_000], "biweight")))


# --- C4, C4b -------------------------------------------------------------------------------------------------------

def test_c4_fair_study_weighs_rows_of_few_sensors(monkeypatch):
    # biweight alone at 3 sensors, one point, 111,111 runs (counted at 300 ns a reading, its edge) ran 89.6 CPU-s:
    # a row of 3 costs up to 7.3 us (IRLS passes), now refused before the draws naming n_runs
    from fusion.book.chapters import ofs_fair
    monkeypatch.setattr(np.random, "default_rng", lambda *a, **k: (_ for _ in ()).throw(AssertionError("drawn")))
    one = dict(n_samples=100, n_sensors=3, sizes=(1.0,), counts=(), spreads=(), opposite=())
    for method in ("huber", "biweight"):
        _refused_fast(lambda: ofs_fair.fair_study(0, n_runs=111_111, methods=(method,), **one), r"^n_runs, n_samples")
        # one point: the worst case of robust_fuse binds (344,655 rows of 3); 23 points: the row's measured cost
        ofs_fair._budget((3_446, 100, 3), 1, (method,), ("a", "b"))
        with pytest.raises(ValueError, match="^b"):
            ofs_fair._budget((3_447, 100, 3), 1, (method,), ("a", "b"))
        ofs_fair._budget((543, 100, 3), 23, (method,), ("a", "b"))
        with pytest.raises(ValueError, match="^b"):
            ofs_fair._budget((544, 100, 3), 23, (method,), ("a", "b"))
    # the optimal set at 2 sensors: 325 ns a row measured, 240 counted before (a reading and a pair only), now 540;
    # mad_reject 151 ns a row, 100 counted before, now 220
    for method, edge in (("optimal_fusion_set", 8_051), ("mad_reject", 19_762)):
        ofs_fair._budget((edge, 100, 2), 23, (method,), ("a", "b"))
        with pytest.raises(ValueError, match="^b"):
            ofs_fair._budget((edge + 1, 100, 2), 23, (method,), ("a", "b"))


def test_c4b_fair_errors_refuses_biweight_rows_of_three_by_z():
    # (11.1e6, 1, 3) ran 87.4 CPU-s; beyond the worst case of its one point (344,655 rows of 3), refused naming z
    from fusion.book.chapters import ofs_fair
    z = 900 + np.random.default_rng(0).standard_normal((400_000, 1, 3))
    z[:, :, 0] += 1.0
    for method in ("huber", "biweight"):
        _refused_fast(lambda: ofs_fair.fair_errors(z, np.ones(3), methods=(method,)), "^z")
