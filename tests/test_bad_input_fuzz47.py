"""Fuzz 47's findings (issue 35): regressions of the round before, fixed."""

from __future__ import annotations

import time
from decimal import Decimal

import pytest

from fusion.book.tables import rounded, sci


def _cpu(fn):  # type: ignore[no-untyped-def]
    t = time.process_time()
    try:
        return fn(), time.process_time() - t
    except ValueError as e:
        return e, time.process_time() - t


@pytest.mark.parametrize("text", ["1e10000000", "1e50000000", "-1e10000000"])
def test_rounded_refuses_a_huge_decimal_before_making_it_exact(text: str) -> None:
    # C1: the exact path made a Fraction of ten million digits before the float range was checked (6.1 CPU-s)
    out, cpu = _cpu(lambda: rounded(Decimal(text), 2))
    assert isinstance(out, ValueError) and str(out).startswith("value must be a number of magnitude within")
    assert cpu < 0.5


def test_rounded_and_sci_round_a_long_decimal_in_linear_time() -> None:
    # a Decimal of 200,000 digits took 1 (rounded) and 2 (sci) CPU-s through its Fraction; quantize is linear
    big = Decimal("0." + "3" * 200_000)
    out, cpu = _cpu(lambda: rounded(big, 4))
    assert out == 0.3333 and cpu < 0.5
    out, cpu = _cpu(lambda: sci(big, 3))
    assert out == "0.333" and cpu < 0.5
    assert rounded(Decimal("1e-10000000"), 2) == 0.0
    assert rounded(Decimal("2.675"), 2) == 2.68 and rounded(Decimal("-2.675"), 2) == -2.68
    assert rounded(Decimal("1.7e308"), 17) == 1.7e308


@pytest.mark.parametrize("lo", [-1e8, -1e6, -1e4, -1.0, 0.0])
def test_bounded_minimum_keeps_xatol_on_an_interval_holding_zero(lo: float) -> None:
    # C2 (a regression of a7919f43): the offset from lo made scipy's relative term grow with the distance from lo:
    # |x - 0.3| on [-1e8, 1] returned 1.0 (fun 0.7), on [-1e6, 1] 0.30601
    from fusion.optimise.scalar import bounded_minimum

    r = bounded_minimum(lambda x: abs(x - 0.3), lo, 1.0)
    assert abs(r.x - 0.3) < 1e-8
