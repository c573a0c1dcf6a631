r"""Equations exactly as the sources print them, kept for the critiques only.

Nothing here is a method to use: each function reproduces a formula that the book shows to be
misprinted, beside the published numbers of :mod:`fusion.data`, so that a chapter can compute
what the printed formula would give. The corrected method lives in the algorithm packages.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from fusion._validation import singular_system, scalar
from fusion._limits import DENSE_CUBE
from fusion.estimates.ci import FusedEstimate, _two_estimates

__all__ = ["wang2024_eqs_1_2"]


@singular_system('P1 and P2')
def wang2024_eqs_1_2(x1: ArrayLike, P1: ArrayLike, x2: ArrayLike, P2: ArrayLike, omega: float) -> FusedEstimate:
    r"""Wang & Tang (2024), eqs. 1-2 **exactly as printed** (for the critique only).

    Eq. 1 is covariance intersection, :math:`P^{-1} = (P_1/w_1)^{-1} + (P_2/w_2)^{-1}`, but eq. 2
    prints :math:`X = P[(P_1/w_1)X_1 + (P_2/w_2)X_2]` without the inverses. The result is not a
    weighted mean: two identical estimates are not returned unchanged.

    Parameters
    ----------
    x1, x2 : array_like, shape (n,)
        State estimates.
    P1, P2 : array_like, shape (n, n)
        Their covariances; symmetric positive definite.
    omega : float in (0, 1)
        :math:`w_1`; :math:`w_2 = 1 - \omega`.

    Returns
    -------
    FusedEstimate
        What the printed equations give.

    Raises
    ------
    ValueError
        Bad estimates or ``omega`` outside (0, 1).
    """
    x1, P1, x2, P2 = _two_estimates(x1, P1, x2, P2, 3 * DENSE_CUBE)  # 4 inverses (fuzz 36a C3)
    omega = scalar(omega, "omega", 0.0, 1.0, lo_open=True, hi_open=True)
    w1, w2 = omega, 1.0 - omega
    P = np.linalg.inv(np.linalg.inv(P1 / w1) + np.linalg.inv(P2 / w2))
    return FusedEstimate(x=P @ ((P1 / w1) @ x1 + (P2 / w2) @ x2), P=P, omega=omega)
