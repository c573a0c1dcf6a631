"""Fix 65a: the remainder of fuzz 57b's D2 (public functions running O(n**3) dense kernels on an argument at the
input budget with no work check, their measured CPU-s at ``n = 5,792`` in the commits) and of its C4 (``nees`` read
two 256 MB inputs before refusing their broadcast). Report: /work/tmp/fuzz57b/report.md."""

from __future__ import annotations

import numpy as np
import pytest

from _helpers import refused_quickly


# --- C4 remainder: nees ------------------------------------------------------------------------------------------

def test_c4_nees_refuses_an_oversized_broadcast_before_reading_its_inputs(monkeypatch):
    from fusion.filtering import kalman
    e = np.ones((2**22, 1, 8))  # each at the input budget (2**25 entries, 256 MB), their broadcast 2.2e12 elements
    P = np.broadcast_to(2.0 * np.eye(8), (2**19, 8, 8)).copy()
    def unread(*args, **kwargs):
        raise AssertionError("an input was read before its broadcast was refused")
    monkeypatch.setattr(kalman, "as_array", unread)  # the old code read both (0.76 CPU-s here, 2.3 in the fuzz)
    refused_quickly(lambda: kalman.nees(e, P), ValueError, r"^errors and covariances \(their broadcast shape\) .*memory budget")
    refused_quickly(lambda: kalman.nees(np.ones((512, 1, 64)), np.ones((1024, 64, 64))),
             ValueError, r"^errors and covariances \(their broadcast matrices\) .*work budget")  # P not even read: not PD


def test_c4_nees_reads_what_its_shapes_do_not_decide():
    from fusion.filtering.kalman import nees
    assert nees([1.0, 2.0], [[1.0, 0.0], [0.0, 4.0]]) == pytest.approx(2.0)  # lists: checked after conversion
    with pytest.raises(ValueError, match="do not match"):
        nees(np.ones((3, 2)), np.ones((3, 3, 3)))
    with pytest.raises(ValueError, match="do not broadcast"):
        nees(np.ones((3, 2)), np.broadcast_to(np.eye(2), (4, 2, 2)))
    with pytest.raises(ValueError, match="^errors has .*input budget"):
        nees(np.broadcast_to(1.0, (2**25 + 1, 1)), np.eye(1))


# --- D2 remainder: dense work on an argument at the input budget -------------------------------------------------

class _Accepted(Exception):
    pass


def _accepts(monkeypatch, module, name, call):
    """``call`` passes the budget ``module.name`` (the real rule runs; the work after it is not)."""
    real = getattr(module, name)
    def budget(*args, **kwargs):
        real(*args, **kwargs)
        raise _Accepted
    monkeypatch.setattr(module, name, budget)
    with pytest.raises(_Accepted):
        call()
    monkeypatch.setattr(module, name, real)


def _square(n):
    return np.eye(n) + 0.01  # positive definite, full rank


def test_d2_ridge_and_least_squares_refuse_a_dense_H_beyond_the_work_budget(monkeypatch):
    from fusion.readings import biased
    refused_quickly(lambda: biased.ridge(_square(4100), np.ones(4100), 1.0), ValueError, r"^H ask for .*work budget")  # 1.03e9
    refused_quickly(lambda: biased.least_squares(_square(3300), np.ones(3300)), ValueError, r"^H ask for .*work budget")  # k = 0: 1.08e9
    _accepts(monkeypatch, biased, "work", lambda: biased.ridge(_square(4000), np.ones(4000), 1.0))  # 9.6e8
    _accepts(monkeypatch, biased, "work", lambda: biased.least_squares(_square(3200), np.ones(3200)))  # 9.8e8


def test_d2_plugin_ridge_and_ridge_risk_refuse_beyond_the_work_budget(monkeypatch):
    from fusion.readings import biased
    refused_quickly(lambda: biased.plugin_ridge(_square(2750), np.ones(2750), 1.0), ValueError, r"^H ask for .*work budget")  # 1.04e9
    refused_quickly(lambda: biased.ridge_risk(_square(3600), np.ones(3600), 0.5), ValueError, r"^A ask for .*work budget")  # 1.03e9
    _accepts(monkeypatch, biased, "work", lambda: biased.plugin_ridge(_square(2700), np.ones(2700), 1.0))  # 9.8e8
    _accepts(monkeypatch, biased, "dense_work", lambda: biased.ridge_risk(_square(3550), np.ones(3550), 0.5))


def test_d2_wls_refuses_beyond_the_work_budget(monkeypatch):
    from fusion.readings import weighting
    n = 4100  # 1.03e9 units with H one column; a weight vector no longer makes its n x n diagonal first
    refused_quickly(lambda: weighting.wls(np.ones(n), np.ones(n), np.ones(n)), ValueError, r"^H and W ask for .*work budget")
    _accepts(monkeypatch, weighting, "work", lambda: weighting.wls(np.ones(4000), np.ones(4000), np.ones(4000)))


def test_d2_readers_of_H_refuse_its_singular_values_beyond_the_work_budget(monkeypatch):
    from fusion import _covariances
    from fusion.readings import correlated as co
    H = _square(3700)  # its singular values, 1.01e9 units: refused before R (a placeholder) is read
    for call in (lambda: co.gls(H, np.eye(1), np.ones(3700)), lambda: co.gls_weights(H, np.eye(1)),
                 lambda: co.lagrange_weights(H, np.eye(1))):
        refused_quickly(call, ValueError, r"^H ask for .*work budget")
    _covariances.column_rank_work(3650, 3650)  # 9.7e8
    assert _covariances.column_rank_work(2, 3) == 0  # fewer rows than columns: deficient, no singular values
    with pytest.raises(ValueError, match="^H ask for"):
        _covariances.column_rank_deficient(H)
    Hk = np.ones((5792, 2000))  # its singular values pass (4.6e8), its KKT system of 7,792 does not (1.4e9)
    refused_quickly(lambda: co.lagrange_weights(Hk, np.eye(1)), ValueError, r"^H and R ask for .*work budget")
    _accepts(monkeypatch, co, "dense_work", lambda: co.lagrange_weights(np.ones((5792, 1000)), np.eye(1)))


def test_d2_gls_low_rank_refuses_beyond_the_work_budget(monkeypatch):
    from fusion.readings import correlated as co
    n = 3700  # U square, H one column: 1.01e9 units
    refused_quickly(lambda: co.gls_low_rank(np.ones((n, 1)), np.ones(n), _square(n), np.ones(n)), ValueError, r"^H and U ask for .*work")
    _accepts(monkeypatch, co, "work", lambda: co.gls_low_rank(np.ones((3650, 1)), np.ones(3650), _square(3650),
                                                               np.ones(3650)))
