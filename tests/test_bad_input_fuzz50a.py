"""fuzz 50a C1 and D5 (fix 57a): linearised_errors' best combination checked by the bounds its exact value obeys,
and a one-sensor scenario refused at entry.

C1's reference: the BLUE is a linear unbiased combination at least as good as the naive product and as each node
alone, so its position variance is at most theirs; the record broke that by 23 % (rmse_best 255.9 m above
rmse_uniform 230.5 m) at a round-off estimate of 2.7e-12 (its KKT system is singular at the first frame when the nodes
share the prior and the process noise).
"""

import time

import numpy as np
import pytest

from fusion.scenarios.range_bearing import RangeBearingScenario, linearised_errors

_C1 = dict(sensors=[(1931.8359388399608, 738.3735480249497), (1400.8787098783523, 725.40647308078)],
           sigma_r=773.8685009693575, sigma_theta=0.1809961208384313, T=0.03390604671519382, q=15.735421877748726,
           frames=5, p0_std=(34.493056139013596, 6523.380398673191, 34.493056139013596, 6523.380398673191))


def test_a_best_combination_worse_than_the_naive_product_is_refused_naming_sc():
    with pytest.raises(ValueError, match=r"^sc \(its noise levels.*best combination's position variance exceeds"):
        linearised_errors(RangeBearingScenario(**_C1))


def test_accepted_records_obey_the_bounds():
    # without a shared prior the first frame's KKT system is regular: accepted, and the bound holds
    r = linearised_errors(RangeBearingScenario(**_C1), common_prior=False)
    assert (r.rmse_best <= r.rmse_uniform * (1 + 1e-7)).all()
    r = linearised_errors(RangeBearingScenario(frames=8))   # the book's scenario: accepted
    assert (r.rmse_best <= r.rmse_uniform * (1 + 1e-7)).all()


@pytest.mark.parametrize("frames", [8, 10**7])
def test_one_sensor_is_refused_at_entry_naming_sc(frames):
    # refused before with "LinearisedErrors.corr_position contains NaN or infinite values", after the work
    sc = RangeBearingScenario(sensors=[(0.0, 0.0)], frames=frames)
    t = time.process_time()
    with pytest.raises(ValueError, match=r"^sc has 1 sensor; linearised_errors needs at least two: .*correlation"):
        linearised_errors(sc)
    assert time.process_time() - t < 1.0
