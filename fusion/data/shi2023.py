"""Numbers published by Shi, Suo & Ma (2023), time registration.

The source prints no results table: its numbers are the scenario parameters of §5 and the
axis ranges of Figs. 2-4, read off the tick labels scattered through the extracted text
(marked as read off a figure).
"""

from __future__ import annotations

from fusion._frozen import constant
from fusion.data._published import Published
from fusion.data._published import read_only as _ro

__all__ = ["SHI2023_SCENARIO", "SHI2023_AXES", "SHI2023_CLAIMED_SAMPLES"]

#: §5 scenario, identical in simulations 1-3.
SHI2023_SCENARIO = constant({
    "period_1": 2.0,  # s, sensor 1 (fast)
    "on_1": 1.0,  # s, "开机时长" of sensor 1
    "period_2": 5.0,  # s, sensor 2 (slow)
    "on_2": 3.0,  # s, "开机时长" of sensor 2
    "v0": 1.0,  # m/s, due east
    "a": 2.0,  # m/s^2, direction not stated
    "duration": 40.0,  # s, observation time
    "start": (0.0, 0.0),  # m
})

#: "各自的20个量测值": the text says each sensor gives 20 measurements (simulations 1 and 2).
SHI2023_CLAIMED_SAMPLES = Published(
    values=_ro([20.0, 20.0]),
    source="shi2023time",
    where="§5, simulations 1 and 2",
    note="sensor 1, sensor 2",
)

#: Largest tick label of each published axis (read off the figures).
SHI2023_AXES = Published(
    values=_ro([4000.0, 800.0, 6000.0, 1400.0, 2.0]),
    source="shi2023time",
    where="Figs. 2-4 (tick labels in the extracted text)",
    unit="m (Figs. 2-3), m² (Fig. 4)",
    note="read off a figure: Fig. 2 before, Fig. 2 after, Fig. 3 before, Fig. 3 after, Fig. 4 y-axis",
    columns={
        "fig2_before_y": _ro([4000.0]),
        "fig2_after_y": _ro([800.0]),
        "fig3_before_y": _ro([6000.0]),
        "fig3_after_y": _ro([1400.0]),
        "fig4_mse_y": _ro([2.0]),
        "fig2_before_x": _ro([20.0]),
        "fig2_after_x": _ro([10.0]),
        "fig4_runs_x": _ro([20.0]),
    },
)
