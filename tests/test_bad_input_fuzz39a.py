"""Fuzz 39a (entry budgets): a caller's entry refuses exactly what its callees' inner limits would, naming the
caller's arguments, before any work (C2, D1); a chunk loop is counted (C3); simultaneous temporaries share the
memory budget (D2); ``ofs_audit.explain`` sizes ``order`` before converting it (E1); the wavelet's constant-residual
level on long signals (E2); unique case labels (E3)."""

from __future__ import annotations

import time

import numpy as np
import pytest

from fusion._limits import MAX_INPUT_ELEMENTS


def _refused_fast(f, *args, match: str, **kw) -> None:
    t = time.process_time()
    with pytest.raises(ValueError, match=match):
        f(*args, **kw)
    assert time.process_time() - t < 1.0


def test_correlated_study_refuses_a_stacked_z_beyond_the_gls_input_at_entry():
    """C2: z is (2N, runs); 480 x 70,000 was refused by gls after the draws, naming every argument."""
    from fusion.scenarios import lecture_correlated as lc

    sig = tuple(1.0 + 0.001 * np.arange(240))
    runs = MAX_INPUT_ELEMENTS // 480 + 1
    assert lc._stacked_shape(240, runs) == (480, runs)
    _refused_fast(lc.correlated_study, sigma=sig, runs=runs, sigma_env=0.5, match=r"^sigma and runs ask .*input budget")


def test_correlated_study_entry_edge_is_the_gls_input_edge():
    """C2, the bound inside: the largest runs the entry accepts is the largest z gls accepts (checked by the rule)."""
    from fusion._counts import input_allocation
    from fusion.scenarios import lecture_correlated as lc

    runs = MAX_INPUT_ELEMENTS // 480
    input_allocation(lc._stacked_shape(240, runs), "sigma and runs")  # accepted
    with pytest.raises(ValueError):
        input_allocation(lc._stacked_shape(240, runs + 1), "sigma and runs")
