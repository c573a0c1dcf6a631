"""Fuzz 68b C3, C4, C6 and D1 (the optimal-fusion-set chapter): each refused by its arguments before the work, and a
nearby legitimate call accepted."""

from __future__ import annotations

import numpy as np
import pytest
from _helpers import refused_quickly

from fusion._limits import MAX_WORK
from fusion.book.chapters import _ofs_audit_budget, ofs_audit, ofs_fair, ofs_support


def test_printed_characters_are_the_printed_form() -> None:
    values = [889.9, -889.94, 9.96, 99.95, 0.04, -0.04, 0.0, 1e5, 1.234567e149, -3.2e40]
    values += list(np.random.default_rng(68).normal(scale=1e4, size=50))
    for v in values:
        assert _ofs_audit_budget.printed_characters(np.array([[v]])) == len(f"{v:.1f}"), v


def test_corrections_weigh_a_reading_by_its_digits() -> None:
    # C3: (2, 1000) readings of 1.2e149 (152 characters each) were weighed as typical readings: 25.8 CPU-s
    refused_quickly(lambda: ofs_audit.corrections(np.full((2, 1000), 1.234567e149), slips_only=True), ValueError,
                    "t1 and window")
    assert len(ofs_audit.corrections(np.full((1, 3), 1.234567e149), slips_only=True)) > 1
    typical = np.round(np.random.default_rng(68).uniform(850.0, 950.0, (3, 200)), 1)
    assert len(ofs_audit.corrections(typical, slips_only=True)) > 600
    assert len(ofs_audit.corrections(window=20.0)) > 1   # the printed table, all three kinds


def _alternating(n: int) -> list[float]:
    return [1e-6 * (1 + i * 1e-6) if i % 2 == 0 else 1e3 * (1 + i * 1e-6) for i in range(n)]


def test_support_variants_read_the_alphas_as_a_grid(monkeypatch: pytest.MonkeyPatch) -> None:
    # C4: alphas alternating between the ends of the range made every adjacent pair a crossing (a Brent root each)
    roots: list[int] = []
    brentq = ofs_support.optimize.brentq

    def counted(*args: object, **kwargs: object) -> float:
        roots.append(1)
        return brentq(*args, **kwargs)

    monkeypatch.setattr(ofs_support.optimize, "brentq", counted)
    alphas = _alternating(30)
    given = ofs_support.support_variants(alphas)
    n_given = len(roots)
    roots.clear()
    grid = ofs_support.support_variants(sorted(alphas))
    assert n_given == len(roots) < 100
    assert given.equals(grid)


def test_support_variants_count_the_roots_before_refining(monkeypatch: pytest.MonkeyPatch) -> None:
    def refined(*args: object, **kwargs: object) -> float:
        raise AssertionError("a root was refined before the roots were counted")

    monkeypatch.setattr(ofs_support, "_VARIANT_ROOT", MAX_WORK)
    monkeypatch.setattr(ofs_support.optimize, "brentq", refined)
    with pytest.raises(ValueError, match="alphas"):
        ofs_support.support_variants(np.logspace(-6, 3, 20))


def test_fault_shapes_study_names_sigma_and_truth_for_huge_readings() -> None:
    # C6: refused by an internal fusion naming "x", not an argument
    for kw in ({"sigma": 3e149}, {"sigma": 1e150}, {"truth": -1e150, "sigma": 1e149}):
        refused_quickly(lambda kw=kw: ofs_fair.fault_shapes_study(1, n_runs=2, **kw), ValueError, "sigma and truth")
    refused_quickly(lambda: ofs_fair.fault_shapes_study(1, n_runs=2_000, sigma=3e149), ValueError, "sigma and truth")
    out = ofs_fair.fault_shapes_study(1, n_runs=2, sigma=1e140)
    assert all(np.all(np.isfinite(v)) and np.all(v > 0) for d in out.values() for v in d.values())


def test_fault_shapes_study_refuses_a_truth_that_absorbs_the_noise() -> None:
    # D1: at truth = 1e150 the noise and the faults were below one ulp: every MAE exactly 0
    refused_quickly(lambda: ofs_fair.fault_shapes_study(1, n_runs=2, truth=1e150), ValueError, "truth and sigma")
    refused_quickly(lambda: ofs_fair.fault_shapes_study(1, n_runs=2, sigma=1e-12), ValueError, "truth and sigma")
    for kw in ({"truth": 1e12}, {"truth": 1e149, "sigma": 1e140}, {"truth": -5.0, "sigma": 1e-9}):
        out = ofs_fair.fault_shapes_study(1, n_runs=2, **kw)
        assert np.all(out["drift (ramp to +4, +8 °C)"]["mean"] > 0), kw


def test_fair_study_refuses_a_truth_that_absorbs_the_noise() -> None:
    small = {"n_runs": 2, "n_samples": 10, "sizes": (0, 2), "counts": (), "opposite": ()}
    refused_quickly(lambda: ofs_fair.fair_study(1, truth=1e150, spreads=(), **small), ValueError, "truth")
    refused_quickly(lambda: ofs_fair.fair_study(1, truth=1e13, spreads=(1, 16), **small), ValueError,
                    "truth and spreads")
    study = ofs_fair.fair_study(1, truth=1e12, spreads=(1, 16), **small)
    assert all(np.all(np.isfinite(v)) for d in study.mae.values() for v in d.values())
