r"""Numbers published by the sources, quoted as data with their provenance.

Nothing here is computed: each module holds one source's published numbers exactly as
printed, as :class:`Published` objects naming the table, figure or equation they come
from, so that the chapters can set them beside the recomputed ones. ``source`` fields
are BibTeX keys of the book's bibliography.

Modules: :mod:`fusion.data.yang2012` (Yang, Feng & Fan 2012), :mod:`fusion.data.wang2024` (Wang & Tang 2024), :mod:`fusion.data.shi2023` (Shi, Suo & Ma 2023).
"""

from fusion.data._published import Published
from fusion.data.wang2024 import (
    WANG2024_FOA,
    WANG2024_IR_RADAR,
    WANG2024_IR_RADAR_RMSE,
    WANG2024_RMSE,
    WANG2024_SCENARIO,
    WANG2024_TIMES,
)
from fusion.data.shi2023 import SHI2023_AXES, SHI2023_CLAIMED_SAMPLES, SHI2023_SCENARIO
from fusion.data.yang2012 import (
    YANG2012_FAILURE,
    YANG2012_TABLE1,
    YANG2012_TABLE2,
    YANG2012_TABLE3,
    YANG2012_TOTALS,
    YANG2012_TRUE_VALUE,
)

__all__ = [
    "Published",
    "WANG2024_SCENARIO",
    "WANG2024_FOA",
    "WANG2024_RMSE",
    "WANG2024_TIMES",
    "WANG2024_IR_RADAR",
    "WANG2024_IR_RADAR_RMSE",
    "SHI2023_SCENARIO",
    "SHI2023_AXES",
    "SHI2023_CLAIMED_SAMPLES",
    "YANG2012_TABLE1",
    "YANG2012_TABLE2",
    "YANG2012_TABLE3",
    "YANG2012_TOTALS",
    "YANG2012_TRUE_VALUE",
    "YANG2012_FAILURE",
]
