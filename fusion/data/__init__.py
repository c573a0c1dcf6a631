r"""Numbers published by the sources, quoted as data with their provenance.

Nothing here is computed: each module holds one source's published numbers exactly as
printed, as :class:`Published` objects naming the table, figure or equation they come
from, so that the chapters can set them beside the recomputed ones. ``source`` fields
are BibTeX keys of the book's bibliography.

Modules: :mod:`fusion.data.yang2012` (Yang, Feng & Fan 2012), :mod:`fusion.data.wang2024` (Wang & Tang 2024), :mod:`fusion.data.shi2023` (Shi, Suo & Ma 2023).
"""

from fusion.data._published import Published
from fusion.data.wang2024 import *  # noqa: F403
from fusion.data.wang2024 import __all__ as _wang2024_all
from fusion.data.shi2023 import SHI2023_AXES, SHI2023_CLAIMED_SAMPLES, SHI2023_SCENARIO
from fusion.data.yang2012 import *  # noqa: F403
from fusion.data.yang2012 import __all__ as _yang2012_all

__all__ = [
    *_wang2024_all,
    *_yang2012_all,
    "Published", "SHI2023_SCENARIO", "SHI2023_AXES", "SHI2023_CLAIMED_SAMPLES",
]
