"""fusion: the algorithms, simulations and published data of *fusion-book*.

Modules
-------
readings
    Fusion of simultaneous scalar readings (source 001; source 003 later).
thermocouples
    The simulated thermocouple bank and Monte-Carlo study of source 001.
data
    Numbers published by the sources, with provenance.
report
    Published-vs-reproduced tables.
plotting
    The book's single figure style.
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("fusion-book")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0.0.0"

__all__ = ["__version__"]
