"""Fuzz 46b D3: the formatters rounded a ``Decimal`` or ``Fraction`` through its nearest float (2.675 -> 2.67)."""

from __future__ import annotations

from decimal import Decimal
from fractions import Fraction

import pytest

from fusion.book.chapters.lecture import sci as lecture_sci
from fusion.book.ledger.statuses import fmt
from fusion.book.tables import rounded, sci


@pytest.mark.parametrize("value, decimals, want", [
    (Decimal("2.675"), 2, 2.68), (Fraction(2675, 1000), 2, 2.68), (Decimal("2.665"), 2, 2.66),
    (Decimal("0.0050"), 2, 0.0), (Decimal("-0.005"), 2, 0.0), (Decimal("0.015"), 2, 0.02),
    (Fraction(1, 8), 2, 0.12), (Decimal("1e300"), 3, 1e300), (Decimal("-1.0000000000000000000005"), 0, -1.0)])
def test_rounded_rounds_an_exact_value_as_it_is(value: object, decimals: int, want: float) -> None:
    assert rounded(value, decimals) == want  # type: ignore[arg-type]


def test_a_float_keeps_its_rounding() -> None:
    assert rounded(2.675, 2) == 2.67  # the float is 2.67499999999999982...
    assert sci(2.675, 3) == "2.67" and lecture_sci(2.675, 3) == "2.67 × 10⁰"


@pytest.mark.parametrize("value", [Decimal("2.675"), Fraction(2675, 1000)])
def test_significant_digit_formatters_round_an_exact_value_as_it_is(value: object) -> None:
    assert sci(value, 3) == "2.68"  # type: ignore[arg-type]
    assert fmt(value, 3) == "2.68"  # type: ignore[arg-type]
    assert lecture_sci(value, 3) == "2.68 × 10⁰"  # type: ignore[arg-type]


def test_exact_rounding_edges() -> None:
    assert sci(Decimal("0.0050"), 1) == "0.005" and sci(Decimal("2.5"), 1) == "2" and sci(Decimal("3.5"), 1) == "4"
    assert lecture_sci(Decimal("9.995"), 3) == "1.00 × 10¹"
    assert sci(Decimal("1.7976931348623157e308"), 3) == "1.8×10³⁰⁸"  # rounded up beyond float: the float's digits
