"""Chapter 05's architecture_studies: a fixed weight that prints as w_pub or another weight (``f"{w:g}"``, the key of
the studies' results) is refused naming fixed_omegas, before either study (fuzz 67b's note: 0.0018000001 beside
w_pub 0.0018 was refused inside architecture_study naming printed_omegas, an argument the caller never passed)."""

from __future__ import annotations

import functools

import pytest

from _helpers import refused_quickly


@pytest.mark.parametrize(("fixed", "match"), [((0.0018000001,), r"^fixed_omegas\[0\] repeats w_pub as printed"),
                                              ((0.3, 0.3000001), r"^fixed_omegas\[1\] repeats fixed_omegas\[0\]")])
def test_a_weight_printed_alike_is_refused_naming_fixed_omegas(fixed, match) -> None:
    import numpy as np

    from fusion.book.chapters.ci import architecture as A

    R, Q = np.diag([1.0, 1.0]), np.diag([0.01, 0.01])
    call = functools.partial(A.architecture_studies, R, R, Q, (1, 2), 0.0018, 2, 2, fixed_omegas=fixed)
    refused_quickly(call, ValueError, match)
