"""Work budgets of fuzz 36a's C3 (dense linear algebra on a caller's covariance dimension) and D2 (``gain_sequence``
at its step count without a fixed point), and D1's whole glue keys.

No test runs the refused work: the d**3 budgets are read from the units counted at small dimensions (a spy on
``fusion._limits.work``), the refused filter loops are patched to raise, and their inputs are cheap views.
"""
import unicodedata

import numpy as np
import pytest

from fusion._limits import MAX_WORK

#: The dimension of fuzz 36a's C3 calls (two covariances of 4,090, inside the input budget: about 94 CPU-s).
FUZZ_D = 4090


class _Ran(Exception):
    """Raised by a patched loop body: the request reached the loop (before the budget, a run of minutes)."""


def _stop(*args, **kwargs):
    raise _Ran


def _covs(d, N=2):
    return np.stack([s * np.eye(d) + 0.1 * np.ones((d, d)) + np.diag(np.linspace(0, 1, d))
                     for s in np.linspace(1.0, 2.0, N)])


def _calls():
    """Each d**3 function of fuzz 36a C3 (and the same kind found by grep), as ``(name, call(d), argument named)``."""
    from fusion.estimates import chernoff as ch
    from fusion.estimates import ci

    def g(f):
        def call(d):
            c = _covs(d)
            m = np.zeros((2, d))
            m[1, 0] = 1.0
            return f(m, c, np.zeros(d))
        return call
    return [
        ("gaussian_chernoff_weights", g(lambda m, c, x: ch.gaussian_chernoff_weights(m, c)), "covs"),
        ("covariance_intersection_weights", g(lambda m, c, x: ch.covariance_intersection_weights(c, "trace")), "covs"),
        ("chernoff_fuse_gaussians", g(lambda m, c, x: ch.chernoff_fuse_gaussians(m, c, [0.5, 0.5])), "covs"),
        ("gaussian_log_normaliser", g(lambda m, c, x: ch.gaussian_log_normaliser(m, c, [0.5, 0.5])), "covs"),
        ("is_second_moment", g(lambda m, c, x: ch.is_second_moment(m, c, [0.5, 0.5], [0.3, 0.7])), "covs"),
        ("log_normaliser_two_gaussians", g(lambda m, c, x: ch.log_normaliser_two_gaussians(x, c[0], x, c[1], 0.5)),
         "A and B"),
        ("gaussian_kl", g(lambda m, c, x: ch.gaussian_kl(x, c[0], x, c[1])), "P0 and P1"),
        ("covariance_intersection", g(lambda m, c, x: ci.covariance_intersection(x, c[0], x + 0.1, c[1])), "P1 and P2"),
        ("ci_weight", g(lambda m, c, x: ci.ci_weight(c[0], c[1])), "P1 and P2"),
        ("convex_combination", g(lambda m, c, x: ci.convex_combination(x, c[0], x + 0.1, c[1])), "P1 and P2"),
        ("ci_objective", g(lambda m, c, x: ci.ci_objective(0.5, c[0], c[1])), "P1 and P2"),
        ("split_ci_objective", g(lambda m, c, x: ci.split_ci_objective(0.5, c[0], c[1], c[1], c[0])), "P1d"),
        ("split_covariance_intersection",
         g(lambda m, c, x: ci.split_covariance_intersection(x, c[0], c[1], x + 0.1, c[1], c[0])), "P1d"),
    ]


def _counted(monkeypatch, call, d):
    """The largest dense work (units of a ``count x d x d x d`` count, ``dense_work``) counted during ``call(d)``, and
    the names of that count (fuzz 38a C4 added a per-covariance loop count, constant in d, to the Gaussians)."""
    from fusion import _limits
    seen = []
    real = _limits.work

    def spy(shape, names, weight=1, limit=MAX_WORK):
        n = real(shape, names, weight, limit)
        if len(shape) == 4 and shape[1] == shape[2] == shape[3]:
            seen.append((n, names))
        return n
    monkeypatch.setattr(_limits, "work", spy)
    call(d)
    return max(seen, default=(0, ""))


@pytest.mark.parametrize("name", [c[0] for c in _calls()])
def test_dense_work_counts_the_cube_of_the_dimension(monkeypatch, name):
    """Fuzz 36a C3: the counted work grows as d**3 (x8 from d = 10 to 20, beyond the small pairs' fast path) and,
    extrapolated to the fuzz's d = 4,090, is beyond the budget, naming the covariances (before, only the N x N
    Newton matrix or nothing was counted)."""
    call, named = {c[0]: (c[1], c[2]) for c in _calls()}[name]
    small, names = _counted(monkeypatch, call, 10)
    large, _ = _counted(monkeypatch, call, 20)
    assert large >= 7 * small > 0
    assert named in names
    assert large * (FUZZ_D / 20) ** 3 > MAX_WORK


def test_dense_work_refuses_by_name_before_the_checks():
    """The refusal itself, from the shapes (``dense_work``), with the weights the functions pass."""
    from fusion._limits import dense_work
    with pytest.raises(ValueError, match=r"^covs ask for .* 0\.12 units each"):
        dense_work(2, FUZZ_D, "covs", 0.12)
    assert dense_work(2, 1000, "covs", 0.12) == 240_000_000


@pytest.mark.parametrize("weighted", ["weighted_em", "weighted_em_batch"])
def test_em_counts_its_covariances_cube(monkeypatch, weighted):
    """Fuzz 36a C3b: 40 points of 5,000 dimensions (about 150 CPU-s; counted 2e7 units before) are refused at
    entry naming x; 40 points of 40 dimensions stay."""
    from fusion.estimates import mixtures
    monkeypatch.setattr(mixtures, "_em_arrays", _stop)
    rng = np.random.default_rng(0)
    for d, refused in ((5000, True), (40, False)):
        x = np.broadcast_to(rng.normal(size=d), (40, d)) + np.arange(40)[:, None]
        args = ((x, np.full(40, 1 / 40), 2, rng) if weighted == "weighted_em"
                else (x[None], np.full((1, 40), 1 / 40), 2, [rng]))
        if refused:
            # by the work budget, or first by the memory budget of its quadratic features (fix 75a: 12.5e6 of them)
            with pytest.raises(ValueError, match=r"^(max_iter, x and n_components|x \(its points and dimension)"):
                getattr(mixtures, weighted)(*args)
        else:
            mixtures._em_work(50, 1, 40, 2, d)  # the budget alone (the fit is not run)


def _unobserved(n_steps, per_step_r=False):
    H = np.eye(4)[:2]
    R = np.broadcast_to(np.eye(2), (n_steps, 2, 2)) if per_step_r else np.eye(2)
    return np.eye(4), H, 0.1 * np.eye(4), R, np.eye(4), n_steps


@pytest.mark.parametrize("n_steps, per_step_r", [(9_000_000, False), (400_000, True)])
def test_gain_sequence_counts_its_worst_case(monkeypatch, n_steps, per_step_r):
    """Fuzz 36a D2: a model that never reaches its fixed point (an unobserved state) at 9e6 steps (about 80 CPU-s)
    and 4e5 steps of one R per step (about 11 CPU-s) are refused at entry naming n_steps."""
    from fusion.filtering import kalman
    for body in ("_gains_matrices", "_gains_axes", "_per_step"):
        monkeypatch.setattr(kalman, body, _stop)
    with pytest.raises(ValueError, match="^n_steps, F and R"):
        kalman.gain_sequence(*_unobserved(n_steps, per_step_r))


def test_gain_sequence_budget_keeps_the_books_sizes():
    """Chapter sizes (10**5 steps of the cv model with one R, 2 x 10**4 with one R per step) stay inside."""
    from fusion.filtering.kalman import _gains_work
    _gains_work(10**5, 4, False, "n_steps")
    _gains_work(2 * 10**4, 4, True, "n_steps")


def test_local_track_names_its_own_arguments_for_its_gains(monkeypatch):
    """local_track with a per-step shared R: its gain_sequence's worst case is refused by local_track's names."""
    from fusion.filtering import kalman, tracks
    from fusion.filtering.kalman import cv_model
    for body in ("_gains_matrices", "_gains_axes"):
        monkeypatch.setattr(kalman, body, _stop)
    monkeypatch.setattr(tracks, "_per_step", _stop)
    m = cv_model(1.0)
    K = 400_000
    z = np.broadcast_to(np.zeros(2), (1, K, 2))
    P0 = 10 * np.eye(4)
    with pytest.raises(ValueError, match=r"^z \(its steps K\) and R"):
        tracks.local_track(z, m.F, m.H, np.diag([0.0, 1.0, 0.0, 1.0]), np.eye(2), np.zeros((1, 4)), 0.5 * P0,
                           0.5 * P0, R_shared=np.eye(2))


def test_belief_parameter_study_edge_reweighted(monkeypatch):
    """budget35's edge (163,934 snapshots, registry call: about 20 CPU-s measured twice at 1/20 and 1/5) is refused
    at entry naming snapshots; half of it (about 10 CPU-s) is the new edge's side that stays."""
    from fusion.scenarios.lecture_weighting import belief
    monkeypatch.setattr(belief, "_seed", _stop)
    kw = dict(sigma=(0.5, 1.0, 2.0, 4.0), x=900.0, params=(0.5, 1.0), grid=(0.5, 1.0))
    with pytest.raises(ValueError, match="^params and snapshots"):
        belief.belief_parameter_study(snapshots=163_934, **kw)
    with pytest.raises(_Ran):
        belief.belief_parameter_study(snapshots=80_000, **kw)


_CAFE = "tr_caf\u00e9"


@pytest.mark.parametrize("key", [unicodedata.normalize("NFC", _CAFE), unicodedata.normalize("NFD", _CAFE),
                                 "tr_\uff58", "tr_\ufb01"])
def test_keep_refuses_non_ascii_keys(key):
    """Fuzz 36a D1: a kept key is held to the prefixes' ASCII rule (NFC/NFD twins printed alike were two keys)."""
    from fusion.book.glue import _checked_keep
    with pytest.raises(ValueError, match="^values must have glue keys"):
        _checked_keep({}, {key: 1.0})
    assert _checked_keep({}, {"tr_cafe": 1.0}) == {"tr_cafe": 1.0}


@pytest.mark.parametrize("key", [unicodedata.normalize("NFD", _CAFE), "fig-\u00e9", "a b", ""])
def test_glue_all_refuses_keys_beyond_ascii(key):
    """Fuzz 36a D1: glue_all's keys are ASCII letters, digits, underscores and hyphens (the book's figure keys
    ``fig-chf-pso`` keep working), refused before anything is glued."""
    from fusion.book import glue
    with pytest.raises(ValueError, match="^values must have glue keys"):
        glue.glue_all({key: 1.0})
    assert glue._GLUE_KEY.fullmatch("fig-chf-pso") and glue._GLUE_KEY.fullmatch("lec_cor_flop_written_gesv_600")
