"""Numbers published by Wang & Tang (2024), covariance intersection.

Values of the text and of Tables 1-2; RMSE values are the approximate figures the text
quotes ("about 3 m") for its Figs. 4-8.
"""

from __future__ import annotations

import math

from fusion._frozen import constant
from fusion.data._published import Published
from fusion.data._published import read_only as _ro

__all__ = ["WANG2024_SCENARIO", "WANG2024_FOA", "WANG2024_RMSE", "WANG2024_TIMES",
           "WANG2024_IR_RADAR", "WANG2024_IR_RADAR_RMSE"]

#: §3.2 scenario as printed (Delta_0 = 10, Delta_1 = Delta_2 = 150; G = [T/2, 1, T/2, 1]).
WANG2024_SCENARIO = constant({
    "delta0": 10.0,  # process noise standard deviation, Q = diag(delta0^2 * 4)
    "delta1": 150.0,  # m, sensor 1
    "delta2": 150.0,  # m, sensor 2
    "runs": 50,
    "area": (0.0, 3500.0, 0.0, 12000.0),  # m: x range, y range
    "foa_population": 30,
    "foa_iterations": 200,
    "foa_step": (30.0, -10.0),  # "30 × rand − 10"
})

#: Fig. 5: optimum found and time taken, FOA vs exhaustive search.
WANG2024_FOA = Published(
    values=_ro([0.0018, 0.0033, 0.1880, 0.6231]),
    source="wang2024covariance",
    where="§3.5 (1)(2), Fig. 5",
    note="FOA optimum, exhaustive optimum, FOA time (s), exhaustive time (s)",
    columns={"foa_optimum": _ro([0.0018]), "grid_optimum": _ro([0.0033]),
             "foa_time_s": _ro([0.1880]), "grid_time_s": _ro([0.6231])},
)

#: RMSE quoted in the text (m, approximate, per axis). Fig. 6 quotes FOA at "about 3 m, lower by
#: 2 m" than exhaustive search, which is therefore read as about 5 m.
WANG2024_RMSE = Published(
    values=_ro([5.0, 4.0, 3.0, 5.0, 6.0, 8.0, 9.0]),
    source="wang2024covariance",
    where="§3.5, Figs. 4, 6-8 and abstract",
    unit="m",
    note=("CI before improvement, CI with convex part, improved CI, CI with exhaustive-search weight "
          "(3 m + 2 m), multi-Bayesian, fuzzy clustering, maximum likelihood"),
    columns={"ci": _ro([5.0]), "ci_convex": _ro([4.0]), "improved": _ro([3.0]), "ci_grid": _ro([5.0]),
             "multi_bayes": _ro([6.0]), "fuzzy": _ro([8.0]), "max_likelihood": _ro([9.0])},
)

#: Tables 1-2: fusion times (s).
WANG2024_TIMES = Published(
    values=_ro([0.83, 0.44, 0.85, 1.08, 1.29]),
    source="wang2024covariance",
    where="Tables 1-2",
    unit="s",
    note="CI, improved CI, multi-Bayesian, fuzzy clustering, maximum likelihood",
    columns={"ci": _ro([0.83]), "improved": _ro([0.44]), "multi_bayes": _ro([0.85]),
             "fuzzy": _ro([1.08]), "max_likelihood": _ro([1.29])},
)

#: §3.5 3) infrared + radar application, as printed. "目标运动的距离为1 km" is read as the
#: target's (initial) range; the sampling period and the duration are not given.
WANG2024_IR_RADAR = constant({
    "sigma_ir": 1e-4,  # rad, infrared angle error (红外测角误差 0.000 1 rad)
    "sigma_angle": 0.02,  # rad, radar angle error
    "sigma_range": 5.0,  # m, radar range error
    "range": 1000.0,  # m
    "azimuth": math.pi / 5,  # rad (π/5)
    "elevation": math.pi / 8,  # rad (π/8)
    "velocity": (300.0, 100.0, 0.0),  # m/s in x, y (z not given: 0)
})

#: Figs. 9-10: RMSE of the improved CI quoted in the text (approximate: "约", "左右"). The
#: baselines (multi-Bayesian, fuzzy clustering, maximum likelihood) are only said to be
#: "clearly higher"; no number is printed for them.
WANG2024_IR_RADAR_RMSE = Published(
    values=_ro([0.00005, 0.00005, 5.0, 7.0]),
    source="wang2024covariance",
    where="§3.5 3), Figs. 9-10",
    note="improved CI: azimuth (rad), elevation (rad), x (m), y (m); approximate values from the text",
    columns={"azimuth_rad": _ro([0.00005]), "elevation_rad": _ro([0.00005]), "x_m": _ro([5.0]), "y_m": _ro([7.0])},
)
