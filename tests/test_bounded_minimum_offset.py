"""bounded_minimum meets its xatol wherever the interval lies (fuzz 46b C4).

scipy's bounded Brent stops once the bracket is within about ``2 (sqrt(eps) |x| + xatol / 3)``: 1.5 on
[1e8, 1e8 + 1], wider than the interval, so it returned its first golden-section point. The search now runs on
the offset from ``lo``.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import minimize_scalar

from fusion.estimates import ci_objective
from fusion.optimise import bounded_minimum

P1 = np.array([[2.0, 0.3], [0.3, 1.0]])
P2 = np.array([[1.0, -0.2], [-0.2, 3.0]])


def test_bounded_minimum_far_from_zero_meets_xatol() -> None:
    c = 1e8
    r = bounded_minimum(lambda x: (x - c - 0.3) ** 2, lo=c, hi=c + 1)
    assert abs(r.x - c - 0.3) < 1e-8 + np.spacing(c)
    assert c <= r.x <= c + 1


@settings(max_examples=100, deadline=None)
@given(st.floats(0.0, 1.0), st.floats(-1e12, 1e12).filter(lambda v: v == 0 or abs(v) >= 1e-100))
def test_bounded_minimum_does_not_depend_on_where_the_interval_is(m: float, lo: float) -> None:
    r = bounded_minimum(lambda x: ((x - lo) - m) ** 2, lo=lo, hi=lo + 1.0)
    # the documented stopping rule: within about 2 (sqrt(eps) |x - s| + xatol / 3) of the minimum, s the point of
    # the interval nearest 0 (|x - s| <= 1 here, whatever lo: the tolerance does not grow with |lo|)
    s = min(max(0.0, lo), lo + 1.0)
    bound = 2 * (np.sqrt(np.finfo(float).eps) * abs(r.x - s) + 1e-8 / 3)
    assert abs((r.x - lo) - m) < bound + 4 * np.spacing(abs(lo) + 1.0)
    assert lo <= r.x <= lo + 1.0


def test_bounded_minimum_from_zero_is_scipys_bit_for_bit() -> None:
    f = lambda w: ci_objective(w, P1, P2)  # noqa: E731
    ref = minimize_scalar(f, bounds=(0.0, 1.0), method="bounded", options={"xatol": 1e-8})
    r = bounded_minimum(f)
    assert r.x == ref.x and r.fun == ref.fun and r.n_evaluations == ref.nfev + 2

