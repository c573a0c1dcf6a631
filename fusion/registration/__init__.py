r"""Time registration of asynchronous sensors (Shi, Suo & Ma 2023).

Modules:

methods
    Time registration (时间配准): a fast sensor's samples onto a slow sensor's instants.
analysis
    Exact error statistics of a linear registration (its affine decomposition and expected MSE).
"""

from fusion.registration.methods import *  # noqa: F403
from fusion.registration.methods import __all__ as _methods_all
from fusion.registration.analysis import *  # noqa: F403
from fusion.registration.analysis import __all__ as _analysis_all

__all__ = [*_methods_all, *_analysis_all]
