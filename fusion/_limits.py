"""The numeric range of the package's inputs (rule 2 of :mod:`fusion._validation`, which re-exports them)."""

from __future__ import annotations

import numpy as np


#: Largest magnitude accepted for a finite input entry: a product of two entries stays finite.
MAX_MAGNITUDE = 1e150
#: Smallest positive normal float.
MIN_NORMAL = float(np.finfo(float).tiny)
#: Smallest non-zero magnitude accepted for an input entry (``1e-150``, the mirror of
#: :data:`MAX_MAGNITUDE`): a product of two entries, a square or a variance, is still a normal float.
#: Subnormals and tiny normals below it (``3e-308``, ``1e-300``) are refused.
MIN_MAGNITUDE = 1e-150
#: Smallest non-zero variance on a covariance's diagonal: a product of two variances stays a normal float.
MIN_VARIANCE = float(np.sqrt(np.finfo(float).tiny))
