"""Book audit 76 (the lecture and optimal-fusion-set chapters): work budgets of loops that had none or that counted
less than their measured cost; each refused by its argument before any work, and a nearby legitimate call accepted."""

from __future__ import annotations

import numpy as np
import pytest
from _helpers import refused_quickly

from fusion.book.chapters import ofs_audit, ofs_fair, ofs_support
from fusion.book.chapters.ofs import readings

GAUSS = "Gaussian exp(-α d²)"
SELF = "row sums × self-reliability"
EIGEN = "principal eigenvector"


def _readings(*shape: int) -> np.ndarray:
    return 900.0 + np.random.default_rng(76).normal(size=shape)


def test_support_values_self_reliability_counted() -> None:
    # 13,000 observations: about 5 CPU-s before (no budget), 40,000 about 50
    refused_quickly(lambda: ofs_support.support_values(_readings(13_000, 3), GAUSS, SELF, [1.0]), ValueError,
                    "alphas and t1")
    assert ofs_support.support_values(_readings(200, 3), GAUSS, SELF, [1.0, 2.0]).shape == (2, 200)


def test_support_values_alphas_counted_before_conversion() -> None:
    t1 = _readings(6, 5)
    refused_quickly(lambda: ofs_support.support_values(t1, GAUSS, EIGEN, np.ones(200_000)), ValueError, "alphas and t1")
    many = [1.0] * 2**22  # a list: its length counted before its entries are converted
    refused_quickly(lambda: ofs_support.support_values(t1, GAUSS, "row sums", many), ValueError, "alphas and t1")
    assert ofs_support.support_values(t1, GAUSS, EIGEN, np.ones(100)).shape == (100, 6)


def test_support_variants_alphas_counted() -> None:
    refused_quickly(lambda: ofs_support.support_variants(np.logspace(-6, 3, 2001)), ValueError, "alphas")
    refused_quickly(lambda: ofs_support.support_variants([1.0] * 10**6), ValueError, "alphas")


def test_run_program_loop_counted() -> None:
    t1 = _readings(1, 25_000, 3)  # about 5 CPU-s before, 10**7 observations about 2,000
    refused_quickly(lambda: ofs_audit.run_program(t1, "buffer, previous pass"), ValueError, "t1")
    assert ofs_audit.run_program(t1[:, :500], "buffer, previous pass").shape == (1, 500)
    assert ofs_audit.run_program(_readings(200, 6, 3), "set not reset").shape == (200, 6)


def test_corrections_counted() -> None:
    refused_quickly(lambda: ofs_audit.corrections(_readings(3, 200)), ValueError, "t1 and window")
    refused_quickly(lambda: ofs_audit.corrections(_readings(3, 6), window=1000.0), ValueError, "t1 and window")
    assert len(ofs_audit.corrections(_readings(3, 4), window=1.0)) > 1


def test_joint_audit_window_counted() -> None:
    refused_quickly(lambda: ofs_audit.joint_audit(window=170.0), ValueError, "window")
    refused_quickly(lambda: ofs_audit.joint_audit(window=70.0, order_search="slips"), ValueError, "window")
    assert ofs_audit.joint_audit(window=2.0).n_hypotheses > 0


def test_eq9_readings_epochs_counted() -> None:
    z = _readings(10_100, 3)
    refused_quickly(lambda: readings.eq9_readings(z, None), ValueError, "z and weight_epochs")
    refused_quickly(lambda: readings.eq9_readings(z, 10**7), ValueError, "z and weight_epochs")
    assert readings.eq9_readings(z[:300], None)["n_sets"] >= 0
    assert readings.eq9_readings(z, 200)["n_sets"] >= 0  # the book's call: its first 200 epochs


def test_family_mae_families_counted() -> None:
    z = _readings(1, 1, 3)
    many = {str(i): "gauss" for i in range(17_000)}
    refused_quickly(lambda: readings.family_mae(z, many), ValueError, "families and z")
    assert set(readings.family_mae(_readings(20, 30, 5))) == set(readings.FAMILIES)


def test_ew_variance_fuse_samples_counted() -> None:
    z = _readings(1, 500_000, 3)  # about 5 CPU-s before, 1.6 * 10**7 samples about 160
    refused_quickly(lambda: ofs_fair.ew_variance_fuse(z), ValueError, "z")
    assert ofs_fair.ew_variance_fuse(z[:, :1000]).shape == (1, 1000)


@pytest.mark.parametrize("aggregation", ofs_support.SUPPORT_AGGREGATIONS)
def test_support_values_small_accepted(aggregation: str) -> None:
    v = ofs_support.support_values(_readings(6, 3), GAUSS, aggregation, [0.1, 1.0])
    assert v.shape == (2, 6) and np.isfinite(v).all()


def test_table_sequential_counted_first() -> None:
    from fusion.book.chapters.lecture_correlated import appendix

    # 10**6 sigma were converted and checked one by one before their number was refused (3.1 CPU-s)
    refused_quickly(lambda: appendix.table_sequential([1.0] * 10**6, 1.5, 1), ValueError, "sigma and m")
    refused_quickly(lambda: appendix.table_sequential(np.ones(10**6), 1.5, 1), ValueError, "sigma and m")
    # 600 sensors of one reading: about 7 CPU-s before, 2,000 about 130-250
    refused_quickly(lambda: appendix.table_sequential(np.linspace(1.0, 3.0, 600), 1.5, 1), ValueError, "sigma and m")
    assert len(appendix.table_sequential(np.linspace(1.0, 3.0, 40), 1.5, 2)) == 40


def test_spread_check_half_widths_counted() -> None:
    from fusion.book.chapters.lecture_weighting import learning

    # 5,000 half-widths of one draw: about 5.6 CPU-s before (159,000 accepted, about 180)
    refused_quickly(lambda: learning.spread_check(tuple(1.0 + i * 1e-4 for i in range(5000)), 1), ValueError,
                    "log_ranges and draws")
    assert len(learning.spread_check((1.0, 2.0), 50)) == 2
