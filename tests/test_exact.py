"""Rule R9's exact comparisons: the practical margin of R2 with a zero-width interval."""
from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from fusion.book import ledger as L
from fusion.book import rulebook as R
from fusion.book.exact import ExactComparison

values = st.floats(-1e6, 1e6, allow_nan=False, allow_subnormal=False)


def test_a_tiny_exact_gain_is_not_better_and_a_large_one_is() -> None:
    assert ExactComparison(0.999999, 1.0, "A", "B", "less", "exact MSE").status() == "not distinguishable"
    assert ExactComparison(0.90, 1.0, "A", "B", "less", "exact MSE").status() == "reproduced"
    assert ExactComparison(1.10, 1.0, "A", "B", "less", "exact MSE").status() == "contradicted"
    assert ExactComparison(1.01, 1.0, "A", "B", "equal", "exact MSE").status() == "reproduced"
    assert ExactComparison(1.0, 1.0, "A", "B", "equal", "ops", margin=1e-3).status() == "reproduced"
    # at margin 0 a tie is undecided, as Comparison judges runs that all tie (R2; fuzz 27a D7)
    assert ExactComparison(1.0, 1.0, "A", "B", "equal", "ops", margin=0.0).status() == "not distinguishable"


@given(a=values, b=values, m=st.floats(0.0, 1e3, allow_subnormal=False))
def test_exact_comparison_is_a_zero_width_paired_comparison(a: float, b: float, m: float) -> None:
    """The same margin decides both: an exact comparison equals R2 on an interval of zero width."""
    ex = ExactComparison(a, b, "A", "B", "less", "q", margin=m)
    d = a - b
    if d == 0.0 and m == 0.0:
        assert ex.status() == "not distinguishable" or ex.region() == "equivalent"
    else:
        assert ex.status() == R.status_from_region(R.region(d, d, m), "less")
    assert ex.with_margin(relative_margin=0.1).margin == pytest.approx(0.1 * abs(b))


def test_bad_input_is_refused() -> None:
    with pytest.raises(ValueError, match="a must be finite"):
        ExactComparison(math.nan, 1.0, "A", "B", "less", "q")
    with pytest.raises(TypeError, match="b must be a real number"):
        ExactComparison(1.0, "x", "A", "B", "less", "q")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="claim"):
        ExactComparison(1.0, 2.0, "A", "B", "lower", "q")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="margin"):
        ExactComparison(1.0, 2.0, "A", "B", "less", "q", margin=-1.0)


def test_exact_comparisons_join_groups_and_records() -> None:
    group = L.Conjunction([("x = 1", ExactComparison(0.5, 1.0, "A", "B", "less", "q")),
                           ("x = 2", ExactComparison(0.999, 1.0, "A", "B", "less", "q"))])
    assert group.status() == "not distinguishable"
    assert group.with_margin(margin=0.0).status() == "reproduced"
