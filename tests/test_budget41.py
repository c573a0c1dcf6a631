"""Work budgets that missed a factor (fuzz 37a C2-C4): the Kalman loops' ``n**3`` a step, the Python loops over a
gain sequence's or a track's steps, and a Grubbs pass over a 2-D ``x``.

No test runs the refused work: the loop bodies are patched to raise :class:`_Ran`, the inputs are cheap views, and the
long gain sequences and tracks are built by the private constructor from views. A request the budget keeps reaches
the patched body (``_Ran``); a refused one raises ValueError naming the caller's argument at entry.
"""
import numpy as np
import pytest


class _Ran(Exception):
    """Raised by a patched loop body: the request reached the loop."""


def _stop(*args, **kwargs):
    raise _Ran


def test_grubbs_pass_over_a_2d_x(monkeypatch):
    """Fuzz 37a C4: x (2,900, 1,000), 26 CPU-s measured, is refused naming x; (300, 1,000), 4 CPU-s, stays, as
    one epoch of 40,000 readings (7 CPU-s)."""
    from fusion.readings import robust
    monkeypatch.setattr(robust, "_grubbs", _stop)
    with pytest.raises(ValueError, match=r"^x \(its readings"):
        robust.robust_fuse(np.broadcast_to(np.arange(1000.0), (2900, 1000)), "grubbs")
    for x in (np.broadcast_to(np.arange(1000.0), (300, 1000)), np.arange(40000.0)[None]):
        with pytest.raises(_Ran):
            robust.robust_fuse(x, "grubbs")
