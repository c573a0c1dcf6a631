"""Fuzz 35b follow-ups (issue 35), chapter layer.

- B5: the batched EM sets its own underflow state (``own_underflow`` back on ``_em_arrays``, fuzz 33b D6's rule);
"""

from __future__ import annotations

import numpy as np
import pytest


# --- B5: the EM's intended underflow under a caller's np.errstate(under="raise") ----------------------------------

def _far_clusters():
    rng = np.random.default_rng(0)
    x = np.concatenate([rng.normal(size=(40, 2)), rng.normal(size=(40, 2)) + 60.0])
    return x, np.ones(len(x))


def test_weighted_em_keeps_callers_underflow_state():
    from fusion.estimates import mixtures as mx
    x, w = _far_clusters()
    plain = mx.weighted_em(x, w, 2, np.random.default_rng(1))
    with np.errstate(under="raise"):
        strict = mx.weighted_em(x, w, 2, np.random.default_rng(1))
        batch = mx.weighted_em_batch(x[None], w[None], 2, [np.random.default_rng(1)])
        assert np.geterr()["under"] == "raise"
    assert np.array_equal(plain.mixture.means, strict.mixture.means)
    assert len(batch) == 1
