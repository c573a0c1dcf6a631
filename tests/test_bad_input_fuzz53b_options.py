"""Fuzz 53b's findings C1, C3, C5, D2 and D5 (issue 35): options and callables read without a check.

* C1: ``fuse_tracks(..., "split" | "printed", criterion="bogus")`` searched the weights by the log-determinant (the
  search read "trace, otherwise det"), bit for bit the ``"det"`` result;
* D2: ``fuse_tracks(..., "convex" | "fuzzy", omega=2.0, criterion="bogus")`` ignored both (omega came back NaN);
* C3: ``crossing_sigma`` refused a Kalman ``a`` or ``b`` naming ``name`` (its helper's argument);
* C5: ``minimise_on_simplex`` trusted ``jac``: NaN, inf, a scalar or a wrong shape returned the start as the
  minimiser; a string, ``None`` or a complex number raised scipy's own error;
* D5: ``bounded_minimum`` with ``xatol`` not smaller than ``hi - lo`` returns its first golden-section point, which
  meets that tolerance (documented; a refusal refused valid narrow intervals at the default xatol: fuzz 54b D1).
"""

from __future__ import annotations

import numpy as np
import pytest


def _tracks():
    from fusion.filtering.tracks import local_track

    one, zero = [[1.0]], [[0.0]]
    a = local_track(np.full((1, 3, 1), 10.0), one, one, zero, one, x0=[[10.0]], P0d=[[0.5]], P0i=[[0.5]])
    b = local_track(np.full((1, 3, 1), 12.0), one, one, zero, [[4.0]], x0=[[12.0]], P0d=[[2.0]], P0i=[[2.0]])
    return a, b


@pytest.mark.parametrize("rule", ["ci", "convex", "split", "printed", "fuzzy"])
@pytest.mark.parametrize(("criterion", "error"), [("bogus", ValueError), ("Trace", ValueError), (5, TypeError)])
def test_fuse_tracks_checks_the_criterion_for_every_rule(rule: str, criterion: object, error: type) -> None:
    from fusion.filtering.tracks import fuse_tracks

    with pytest.raises(error, match="^criterion must be"):
        fuse_tracks(*_tracks(), rule, criterion=criterion)  # type: ignore[arg-type]


def test_the_split_weight_search_checks_its_criterion() -> None:
    # the shared search of fuse_tracks and fusion_loop: an unknown criterion was the log-determinant
    from fusion.estimates.ci import _split_ci_weights

    P = np.eye(2)[None]
    assert _split_ci_weights(P, P, 2 * P, P, criterion="det").shape == (1,)
    with pytest.raises(ValueError, match="^criterion must be"):
        _split_ci_weights(P, P, 2 * P, P, criterion="bogus")  # type: ignore[arg-type]


def test_the_batched_ci_weights_check_their_criterion() -> None:
    from fusion.estimates.chernoff.gaussian import _ci_criterion_batch

    infos = np.stack([np.eye(2), 2 * np.eye(2)])[None]
    assert _ci_criterion_batch(infos, "trace").shape == (1, 2)
    with pytest.raises(ValueError, match="^criterion must be"):
        _ci_criterion_batch(infos, "bogus")


@pytest.mark.parametrize("rule", ["convex", "fuzzy"])
def test_a_rule_without_a_weight_refuses_an_omega_or_a_criterion(rule: str) -> None:
    from fusion.filtering.tracks import fuse_tracks

    a, b = _tracks()
    for omega in (0.5, 2.0, [0.5, 0.5, 0.5]):
        with pytest.raises(ValueError, match=rf"^omega is a weight of .* rule '{rule}' has none"):
            fuse_tracks(a, b, rule, omega=omega)
    with pytest.raises(ValueError, match=rf"^criterion chooses .* rule '{rule}' has none"):
        fuse_tracks(a, b, rule, criterion="det")
    ref = fuse_tracks(a, b, rule)  # the defaults: unchanged
    assert np.isnan(ref.omega).all()
    np.testing.assert_array_equal(fuse_tracks(a, b, rule, omega=None, criterion="trace").est, ref.est)


def test_a_weighted_rule_still_takes_omega_and_criterion() -> None:
    from fusion.filtering.tracks import fuse_tracks

    a, b = _tracks()
    for rule in ("ci", "split", "printed"):
        assert (fuse_tracks(a, b, rule, omega=0.5, criterion="det").omega == 0.5).all()


@pytest.mark.parametrize(("a", "b", "named"), [("reg_two_point", "reg_kalman_predict", "b"),
                                                ("reg_improved", "reg_two_point", "a")])
def test_crossing_sigma_names_the_kalman_argument(a: str, b: str, named: str) -> None:
    from fusion.scenarios import time_registration as sc

    with pytest.raises(ValueError, match=rf"^{named} must be a fixed-weight method, got the Kalman method"):
        sc.crossing_sigma(a, b)
    with pytest.raises(ValueError, match="^name must be a fixed-weight method"):
        sc.noise_gain("reg_kalman_predict")  # noise_gain's own argument is name


_C = np.array([0.1, 0.9])


def _f(e: np.ndarray) -> float:
    return float((e - _C) @ (e - _C))


@pytest.mark.parametrize(("jac", "error", "message"), [
    (lambda e: np.full(2, np.nan), ValueError, "^jac returned a gradient that is not finite"),
    (lambda e: np.array([np.inf, 0.0]), ValueError, "^jac returned a gradient that is not finite"),
    (lambda e: 0.0, ValueError, r"^jac returned a gradient of shape \(\)"),
    (lambda e: np.zeros(3), ValueError, r"^jac returned a gradient of shape \(3,\)"),
    (lambda e: "ab", TypeError, "jac"),
    (lambda e: None, TypeError, "jac"),
    (lambda e: np.array([1j, 0.0]), TypeError, "jac"),
], ids=["nan", "inf", "scalar", "shape3", "str", "None", "complex"])
def test_minimise_on_simplex_checks_jacs_values(jac, error: type, message: str) -> None:
    from fusion.estimates import minimise_on_simplex

    with pytest.raises(error, match=message):
        minimise_on_simplex(_f, 2, jac=jac)


def test_minimise_on_simplex_with_a_right_jac_finds_the_minimum() -> None:
    from fusion.optimise import minimise_on_simplex

    r = minimise_on_simplex(_f, 2, jac=lambda e: 2.0 * (e - _C))
    np.testing.assert_allclose(r.x, _C, atol=1e-6)


@pytest.mark.parametrize(("lo", "hi", "xatol"), [(0.0, 1.0, 1.0), (0.0, 1.0, 1e10), (0.0, 1e-9, 1e-8),
                                                 (1e8, 1e8 + 1.0, 1.0), (0.3, 0.3 + 5e-9, 1e-8)])
def test_bounded_minimum_with_an_xatol_as_wide_as_the_interval_is_within_it(lo: float, hi: float,
                                                                            xatol: float) -> None:
    """Fuzz 53b D5 (first refused, then fuzz 54b D1: the refusal blamed the default xatol for a valid interval
    narrower than 1e-8): any point of the interval meets such a tolerance; the result is a point of it, its
    objective evaluated there."""
    from fusion.optimise import bounded_minimum

    f = lambda x: abs(x - lo - 0.3 * (hi - lo))  # noqa: E731
    r = bounded_minimum(f, lo, hi, xatol=xatol)
    assert lo <= r.x <= hi and abs(r.x - (lo + 0.3 * (hi - lo))) <= xatol and r.fun == f(r.x)


def test_bounded_minimum_keeps_an_xatol_just_below_the_width() -> None:
    from fusion.optimise import bounded_minimum

    r = bounded_minimum(lambda x: abs(x - 0.3), 0.0, 1.0, xatol=np.nextafter(1.0, 0.0))
    assert abs(r.x - 0.3) <= 1.0  # within its (wide) tolerance
    assert abs(bounded_minimum(lambda x: abs(x - 0.3), 0.0, 1.0, xatol=1e-3).x - 0.3) < 1e-3
