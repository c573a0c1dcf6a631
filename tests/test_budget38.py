"""Work budgets of fuzz 36a's Python loops (C5 filter steps, C2 ldl_recurrences, C6 Grubbs passes): a request
beyond ``fusion._limits.MAX_WORK`` is refused at entry, naming the caller's argument, before any loop runs.

The refused requests are built as cheap views (``np.broadcast_to``) or small arrays so that no test runs a loop.
"""
import numpy as np
import pytest


class _Ran(Exception):
    """Raised by a patched loop body: the request reached the loop (before the budget, a run of minutes)."""


def _stop(*args, **kwargs):
    raise _Ran


def _cv():
    from fusion.filtering.kalman import cv_model
    m = cv_model(1.0)
    return m, np.diag([0.0, 1.0, 0.0, 1.0]), np.eye(2), 10 * np.eye(4)


def test_fusion_loop_steps_refused_naming_z1(monkeypatch):
    from fusion.filtering import feedback
    from fusion.filtering.feedback import fusion_loop
    monkeypatch.setattr(feedback, "_local_update", _stop)
    m, Q, R, P0 = _cv()
    z = np.broadcast_to(np.zeros(2), (1, 10**6, 2))
    x0 = np.zeros((1, 4))
    with pytest.raises(ValueError, match="z1 and z2"):
        fusion_loop(z, z, x0, x0, m.F, m.H, Q, R, 2 * R, 0.5 * P0, 0.5 * P0, 0.5 * P0, "split", "split")


def test_local_track_steps_refused_naming_z(monkeypatch):
    from fusion.filtering import tracks
    from fusion.filtering.tracks import local_track
    monkeypatch.setattr(tracks, "gain_sequence", _stop)
    m, Q, R, P0 = _cv()
    z = np.broadcast_to(np.zeros(2), (1, 10**6, 2))
    with pytest.raises(ValueError, match=r"^z \(its steps K\)"):
        local_track(z, m.F, m.H, Q, R, np.zeros((1, 4)), 0.5 * P0, 0.5 * P0)


def test_posterior_crb_frames_refused_naming_truths(monkeypatch):
    from fusion.scenarios import range_bearing as rb
    from fusion.scenarios import range_bearing_bounds
    monkeypatch.setattr(range_bearing_bounds, "ncv_model", _stop)
    sc = rb.RangeBearingScenario(frames=2, n_particles=60, n_samples=60, n_central=100, em_iterations=2,
                                 n_components=1)
    tr = np.broadcast_to(np.array([900.0, 0.01, 800.0, 0.01]), (1, 10**6, 4))
    with pytest.raises(ValueError, match="truths"):
        rb.posterior_crb(sc, tr)


def test_filter_step_budget_keeps_the_books_sizes():
    """The budget is a count of units: chapter-size requests (2,000 steps of 100 runs) stay inside it, counted with
    every weight fusion_loop and local_track pass (their step, cube, run, product and matrix weights: review 18, the
    runs were not counted here), so that a bad weight of any kind fails this test."""
    from fusion.filtering import kalman as K

    def fusion_loop(steps: int, rule: str) -> None:
        searched = rule in ("split", "printed")
        return K._steps_work(steps, 100, 4, 2, K.FUSION_LOOP_SPLIT_STEP if searched else K.FUSION_LOOP_STEP, "z",
                             K.FUSION_LOOP_PRINTED_CUBE if rule == "printed" else K.FUSION_LOOP_SPLIT_CUBE if searched
                             else K.FUSION_LOOP_CUBE, K.FUSION_LOOP_SPLIT_M_CUBE if searched else K.FUSION_LOOP_M_CUBE,
                             run=K.FUSION_LOOP_RUN, product=K.FUSION_LOOP_PRODUCT,
                             matrix=K.FUSION_LOOP_PRINTED_MATRIX if rule == "printed" else K.FUSION_LOOP_SPLIT_MATRIX
                             if searched else K.FUSION_LOOP_MATRIX)

    for rule in ("convex", "split", "printed"):
        fusion_loop(2000, rule)
    K._steps_work(20000, 100, 4, 2, K.LOCAL_TRACK_STEP, "z", K.LOCAL_TRACK_CUBE, K.LOCAL_TRACK_M_CUBE,
                  run=K.LOCAL_TRACK_RUN, product=K.LOCAL_TRACK_PRODUCT, matrix=K.LOCAL_TRACK_MATRIX)
    # the runs count: the same steps with 10**6 runs are refused (without the run weights they were not)
    with pytest.raises(ValueError, match="^z"):
        K._steps_work(2000, 10**6, 4, 2, K.LOCAL_TRACK_STEP, "z", K.LOCAL_TRACK_CUBE, K.LOCAL_TRACK_M_CUBE,
                      run=K.LOCAL_TRACK_RUN, product=K.LOCAL_TRACK_PRODUCT, matrix=K.LOCAL_TRACK_MATRIX)


class _Unread(np.ndarray):
    """An array whose entries raise :class:`_Ran` when the loop reads them: before the budget, the loop starts."""

    def __getitem__(self, key):
        raise _Ran


def test_ldl_recurrences_size_refused_naming_r(monkeypatch):
    """n = 2,100 (2.2e6 entries of ~3.5 us: ~8 CPU-s and more as n grows) is refused before the loop reads R."""
    from fusion.readings import correlated
    R = np.broadcast_to(np.zeros(1), (2100, 2100)).view(_Unread)
    monkeypatch.setattr(correlated, "as_array", lambda R, name: R)   # no copy in the test
    monkeypatch.setattr(correlated, "as_covariance", _stop)   # its O(n^3) checks come after the budget
    with pytest.raises(ValueError, match=r"^R \(its size n\)"):
        correlated.ldl_recurrences(R)
    correlated.loop_work((2000 * 1999 // 2,), 0, "R", step=correlated.LOOP_STEP // 2)   # n = 2,000 (7.5 CPU-s) stays


def test_grubbs_worst_case_refused_naming_x(monkeypatch):
    """One epoch of 10**6 readings (~20 min when each pass drops one) is refused before the first pass; 40,000
    (7.1 CPU-s measured) stays inside the budget."""
    from fusion.readings import robust
    monkeypatch.setattr(robust, "_grubbs", _stop)
    x = np.broadcast_to(np.arange(10**6, dtype=float), (1, 10**6))
    with pytest.raises(ValueError, match=r"^x \(its readings"):
        robust.robust_fuse(x, "grubbs")
    with pytest.raises(_Ran):   # the budget keeps 40,000 readings
        robust.robust_fuse(np.arange(40000, dtype=float)[None], "grubbs")
