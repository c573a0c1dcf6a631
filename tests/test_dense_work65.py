"""Fix 65a: the remainder of fuzz 57b's D2 (public functions running O(n**3) dense kernels on an argument at the
input budget with no work check, their measured CPU-s at ``n = 5,792`` in the commits) and of its C4 (``nees`` read
two 256 MB inputs before refusing their broadcast). Report: /work/tmp/fuzz57b/report.md."""

from __future__ import annotations

import time

import numpy as np
import pytest


def _refused(call, match):
    t0 = time.process_time()
    with pytest.raises(ValueError, match=match):
        call()
    assert time.process_time() - t0 < 1.0  # before any work


# --- C4 remainder: nees ------------------------------------------------------------------------------------------

def test_c4_nees_refuses_an_oversized_broadcast_before_reading_its_inputs(monkeypatch):
    from fusion.filtering import kalman
    e = np.ones((2**22, 1, 8))  # each at the input budget (2**25 entries, 256 MB), their broadcast 2.2e12 elements
    P = np.broadcast_to(2.0 * np.eye(8), (2**19, 8, 8)).copy()
    def unread(*args, **kwargs):
        raise AssertionError("an input was read before its broadcast was refused")
    monkeypatch.setattr(kalman, "as_array", unread)  # the old code read both (0.76 CPU-s here, 2.3 in the fuzz)
    _refused(lambda: kalman.nees(e, P), r"^errors and covariances \(their broadcast shape\) .*memory budget")
    _refused(lambda: kalman.nees(np.ones((512, 1, 64)), np.ones((1024, 64, 64))),
             r"^errors and covariances \(their broadcast matrices\) .*work budget")  # P not even read: not PD


def test_c4_nees_reads_what_its_shapes_do_not_decide():
    from fusion.filtering.kalman import nees
    assert nees([1.0, 2.0], [[1.0, 0.0], [0.0, 4.0]]) == pytest.approx(2.0)  # lists: checked after conversion
    with pytest.raises(ValueError, match="do not match"):
        nees(np.ones((3, 2)), np.ones((3, 3, 3)))
    with pytest.raises(ValueError, match="do not broadcast"):
        nees(np.ones((3, 2)), np.broadcast_to(np.eye(2), (4, 2, 2)))
    with pytest.raises(ValueError, match="^errors has .*input budget"):
        nees(np.broadcast_to(1.0, (2**25 + 1, 1)), np.eye(1))
