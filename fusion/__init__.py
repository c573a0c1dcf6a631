"""fusion: the algorithms, simulations and published data of *fusion-book*.

Modules
-------
readings
    Fusion of simultaneous scalar readings (source 001; source 003's belief degree, 2.4).
weighting
    Adaptive and least-squares weighted fusion with estimated variances (source 003, 2.1-2.2).
consistency
    Adjacent-difference consistency check + adaptive weighting (source 003, 2.3).
ridge
    Biased (ridge) estimation fusion, centralised and distributed (source 003, 2.5).
wavelet
    Wavelet denoising and normalised fusion reconstruction (source 003, 2.6).
correlated
    GLS (Markov) estimate and LDL^T decorrelation for correlated noise (source 003, 2.7).
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
