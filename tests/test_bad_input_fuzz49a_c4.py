"""fuzz 49a C4 (fix 56b): linearised_errors' centralised covariance and its round-off check.

Reference values: a 100-digit Decimal recursion of the same equations (F, Q, R, P0 and the float nominal
trajectory's H converted exactly, sqrt at the end; /work/tmp/fix56b/ref.py, agreeing with 160 digits).
"""

import time

import numpy as np
import pytest

from fusion.scenarios.range_bearing import RangeBearingScenario, linearised_errors


@pytest.mark.parametrize("p0, expected", [
    (1e5, [11.3176861758, 11.3118891486, 10.323690834, 9.46414254464, 8.7733144016, 8.22229372916, 7.78462107942,
           7.44122848516]),
    (3e5, [11.3176861921, 11.3118892138, 10.3236908587, 9.46414255769, 8.77331440973, 8.22229373466, 7.78462108329,
           7.44122848792])])
def test_a_wide_prior_gives_the_exact_central_rmse(p0, expected):
    # the simple form (I - K H) P returned rmse_central[0] = 21.74 m (1e5) and 108.06 m (3e5)
    r = linearised_errors(RangeBearingScenario(p0_std=(p0,) * 4, frames=8))
    np.testing.assert_allclose(r.rmse_central, expected, rtol=1e-8)   # measured: within 3e-9
    assert (r.rmse_central <= r.rmse_best * (1 + 1e-9)).all()   # the centralised filter is not worse


def test_an_accurate_call_near_the_threshold_is_accepted():
    # round-off estimate 4.3e-8 (threshold 1e-7), outputs within 2.2e-10 of the reference; refused before (NaN
    # central covariance of the simple form)
    r = linearised_errors(RangeBearingScenario(p0_std=(1e4,) * 4, sigma_r=1e-3, sigma_theta=1e-5, frames=8))
    np.testing.assert_allclose(r.rmse_central, [0.001161778536, 0.001160525906, 0.0011594746521, 0.00115863064641,
                                                0.00115799601474, 0.00115757340413, 0.00115736502816,
                                                0.00115737255619], rtol=1e-9)
    assert r.rmse_uniform[-1] == pytest.approx(0.00115737757293, rel=1e-8)
    assert r.nees_naive[-1] == pytest.approx(7.99400144331, rel=1e-9)


def test_an_inaccurate_call_is_refused_quickly_naming_sc():
    # accepted before with nees_naive, rmse_uniform and rmse_best 2.8 %, 3.3 % and 3.4 % off the reference (and
    # rmse_central 6e5 times it); its nodes' Joseph and information forms differ by 0.039
    sc = RangeBearingScenario(p0_std=(1e4,) * 4, sigma_r=1e-3, T=1e-3, frames=8)
    t = time.process_time()
    with pytest.raises(ValueError, match=r"^sc \(its noise levels .* lose their accuracy to round-off: at frame"):
        linearised_errors(sc)
    assert time.process_time() - t < 1.0


def test_an_inaccurate_naive_combination_is_refused_naming_sc():
    # the nodes' covariances accurate (their two forms within 9.8e-8) but nearly singular at T = 1e3 s: the naive
    # product's rmse_uniform and nees_naive were 2e-4 and 4e-5 off the reference; the whitened combination differs
    # by 3.4e-4
    sc = RangeBearingScenario(p0_std=(1e4,) * 4, sigma_r=0.1, sigma_theta=0.0349, T=1e3, frames=8)
    t = time.process_time()
    with pytest.raises(ValueError, match=r"^sc \(its noise levels .* lose their accuracy to round-off: at frame"):
        linearised_errors(sc)
    assert time.process_time() - t < 1.0
