"""Arguments broadcast against each other are held to the memory and work budgets by their broadcast shape (fuzz 57b C5).

Each argument of 10**5 entries is within the input budget, but a column and a row broadcast to 10**10 elements: the
readers raised a raw MemoryError ("Unable to allocate 74.5 GiB"), and ``cumulative_fusion`` refused naming an inner
"estimates". ``fusion._counts.broadcast`` checks the broadcast shape, naming every broadcast argument, before any work.
"""

from __future__ import annotations

import time

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from fusion._counts import MAX_ELEMENTS, broadcast
from fusion._limits import MAX_WORK
from fusion.readings.biased import reliability, scalar_ridge_moments
from fusion.readings.weighting import cumulative_fusion, fuse_current, lecture_variance_sd
from fusion.scenarios.infrared_radar import spherical_to_cartesian
from fusion.scenarios.two_sensor.study import run_rmse


def _col(n: int) -> np.ndarray:
    return np.linspace(0.1, 1.0, n)[:, None]


def _row(m: int) -> np.ndarray:
    return np.linspace(0.2, 0.9, m)[None, :]


# name -> (call on a column of n and a row of m, the broadcast arguments it names)
CALLS = {
    "scalar_ridge_moments": (lambda a, b: scalar_ridge_moments(3, 1.0, a, b), ("x", "k")),
    "reliability": (lambda a, b: reliability(a, b, 1.0), ("bias", "sd")),
    "spherical_to_cartesian": (lambda a, b: spherical_to_cartesian(a, b, 0.1), ("r", "az", "el")),
    "run_rmse": (lambda a, b: run_rmse(a[..., None], b[..., None], np.ones(b.shape[1], bool), 0), ("est", "truth")),
    "fuse_current": (lambda a, b: fuse_current(np.repeat(a[..., None], 2, axis=-1), np.repeat(b[..., None], 2, axis=-1) + 1.0),
                     ("X", "variances")),
    "cumulative_fusion": (lambda a, b: cumulative_fusion(np.repeat(a[..., None], 2, axis=-1),
                                                         np.repeat(b[..., None], 2, axis=-1) + 1.0), ("X", "variances")),
    "lecture_variance_sd": (lambda a, b: lecture_variance_sd(2.0, a[:, 0] * 10 + 1.0, b[0] + 1.0), ("k", "variances")),
}


@settings(max_examples=8, deadline=None)
@given(name=st.sampled_from(sorted(CALLS)), n=st.integers(2**14 + 1, 2**19), m=st.integers(2**14 + 1, 2**19))
def test_broadcast_beyond_the_memory_budget_is_refused_by_name_quickly(name: str, n: int, m: int) -> None:
    """A column of n and a row of m (n * m beyond MAX_ELEMENTS, each within the input budget): a ValueError naming
    every broadcast argument, in well under a second (before any work)."""
    call, names = CALLS[name]
    a, b = _col(n), _row(m)
    t = time.process_time()
    with pytest.raises(ValueError, match="broadcast together") as info:
        call(a, b)
    assert time.process_time() - t < 1.0
    for arg in names:
        assert f"{arg}," in str(info.value) or f"{arg} " in str(info.value)
    assert "estimates" not in str(info.value)


@settings(max_examples=25, deadline=None)
@given(name=st.sampled_from(sorted(CALLS)), n=st.integers(1, 6), m=st.integers(2, 7))
def test_small_broadcasts_give_the_results_of_the_materialised_arrays(name: str, n: int, m: int) -> None:
    """A compatible broadcast within the budgets is accepted and equals the call on the arrays broadcast by hand."""
    call, _ = CALLS[name]
    a, b = _col(n), _row(m)
    got = call(a, b)
    full_a, full_b = (np.ascontiguousarray(v) for v in np.broadcast_arrays(a, b))
    want = call(full_a, full_b)
    if isinstance(got, np.ndarray):
        np.testing.assert_array_equal(got, want)
    else:  # RidgeMoments
        for field in ("bias", "sd", "mse"):
            np.testing.assert_array_equal(getattr(got, field), getattr(want, field))


def test_broadcast_bounds() -> None:
    """The helper's edge: arrays x the broadcast shape at MAX_ELEMENTS accepted, one row more refused by name; work
    refused at weight x elements beyond MAX_WORK; shapes that do not broadcast refused naming all of them."""
    assert broadcast((("x", (2**13, 1)), ("k", (1, 2**13))), arrays=4) == (2**13, 2**13)  # 4 * 2**26 = MAX_ELEMENTS
    assert 4 * 2**13 * 2**13 == MAX_ELEMENTS
    with pytest.raises(ValueError, match=r"x and k \(broadcast together\).*memory budget"):
        broadcast((("x", (2**13 + 1, 1)), ("k", (1, 2**13))), arrays=4)
    assert broadcast((("x", (10**4, 1)), ("k", (1, 10**4))), weight=10) == (10**4, 10**4)  # 10**9 units: at the edge
    assert 10 * 10**4 * 10**4 == MAX_WORK
    with pytest.raises(ValueError, match=r"x and k \(broadcast together\).*work budget"):
        broadcast((("x", (10**4 + 1, 1)), ("k", (1, 10**4))), weight=10)
    with pytest.raises(ValueError, match=r"r, az and el must broadcast together, got shapes \(3,\), \(4,\), \(1,\)"):
        broadcast((("r", (3,)), ("az", (4,)), ("el", (1,))))
