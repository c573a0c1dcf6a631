r"""Chapter 01 (Yang, Feng & Fan 2012): the support-degree variants that could have produced Table 3's column.

The source does not give its support-degree method; these functions run the kernels and aggregations of the
support-degree literature over a grid of sharpness values and ask which printed values each can reach. Documented
and re-exported by :mod:`fusion.book.chapters.ofs_audit`, whose API page lists them.

References
----------
* Yang G. N., Feng X. F., Fan L. J. (2012). Multi-sensor data fusion algorithm based on
  optimal fusion set. *Journal of Software* 23(Suppl. 1), 134-140.
* Sun Y., Jing B. (2005). Consistent and reliable fusion of multi-sensor based on support degree.
  *Chinese Journal of Sensors and Actuators* 18(3), 537-539.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from numpy.typing import ArrayLike
from scipy import optimize

from fusion._guards import own_underflow
from fusion._frozen import constant
from fusion import data
from fusion._counts import allocation
from fusion._limits import LOOP_STEP, work
from fusion._validation import FloatArray, as_array, one_of

__all__ = ["SUPPORT_KERNELS", "SUPPORT_AGGREGATIONS", "support_values", "support_variants"]

_TOL = 5e-5  # half a unit of the printed 4th decimal (the audit of Table 2 reads it too)

# The work of support_values (rule 17; book audit 76: it had no budget, a (40000, 3) t1 under the self-reliability
# weights ran about 50 CPU-s, 2 * 10**5 alphas on a (6, 5) t1 under the principal eigenvector 6 CPU-s and more
# alphas without end). Measured with time.process_time, OPENBLAS_NUM_THREADS=1, minimum of 2, shared 2-core machine:
# an entry of the (k, n_obs, n, n) support matrices cost 11 to 27 ns over the five kernels under the row sums
# (k = 2 * 10**5, t1 (6, 5): 0.33 to 0.82 CPU-s), 38 ns under the accumulated row sums (1.14 CPU-s): 8 units each;
# a (n, n) matrix's principal eigenvector 5 us (k = 2 * 10**4, t1 (6, 5): 0.61 CPU-s), 1,000 units each besides
# perron_weights' own dense budget; the self-reliability loop 22 us a step plus 17 ns an entry of the readings it
# takes the variance of (t1 (2000, 3): 0.15 CPU-s, (4000, 3): 0.50 CPU-s): 5 * LOOP_STEP a step, 4 units an entry.
_SUPPORT_ENTRY = 8
_EIGEN_MATRIX = 1000
_RELIABILITY_STEP = 5 * LOOP_STEP
_RELIABILITY_ENTRY = 4
# support_variants: 80 calls of support_values over the grid (40 variants, two tables), 2.3 ms an alpha measured
# (600 - 20 alphas: 0.74 - 0.56 CPU-s for 100 - 20, one run each), weighed 500,000 units (5 ms) an alpha besides
# the roots refined by Brent's method (book audit 76: 10**6 alphas, accepted, would run about 40 minutes).
_VARIANT_ALPHA = 500_000
# Each sign change of a residual between adjacent alphas is a root refined by Brent's method (about 30 calls of
# support_values) and tested: 4.4 ms a root (20 log-spaced alphas: 158 roots in 0.69 CPU-s; the default 600: 198 in
# 0.61 CPU-s; process_time, minimum of 2, OPENBLAS_NUM_THREADS=1, shared 2-core machine): 900,000 units a root. The
# alphas are sorted and their repeats dropped first (fuzz 68b C4: 500 alphas alternating between 1e-6 and 1e3 made
# every adjacent pair a crossing of every observation, 30.1 CPU-s; sorted, a residual changes sign only at its roots).
_VARIANT_ROOT = 900_000


def _alphas_length(alphas: object) -> int | None:
    """The number of alphas of a list or tuple, read before any is converted (None for another array_like)."""
    return len(alphas) if isinstance(alphas, (list, tuple)) else None


def _support_budget(shape: tuple[int, int], k: int, aggregation: str) -> None:
    """Refuse a :func:`support_values` call beyond the work budget or the memory budget, naming ``alphas and t1``."""
    n_obs, n = shape
    names = "alphas and t1"
    allocation((k, n_obs, n, n), names, arrays=2)
    units = k * n_obs * n * n * _SUPPORT_ENTRY
    if aggregation == SUPPORT_AGGREGATIONS[1]:
        units += k * n_obs * _EIGEN_MATRIX
    if aggregation == SUPPORT_AGGREGATIONS[3]:
        units += n_obs * _RELIABILITY_STEP + (n_obs * (n_obs + 1) // 2) * n * _RELIABILITY_ENTRY
    work((units,), names)

#: Support kernels of the support-degree literature: name -> support of a distance d at sharpness α.
SUPPORT_KERNELS: dict[str, str] = constant({
    "Gaussian exp(-α d²)": "gauss",
    "Laplace exp(-α |d|)": "laplace",
    "Cauchy 1/(1 + α d²)": "cauchy",
    "arctan 1 - (2/π) arctan(α |d|)": "arctan",
    "linear max(0, 1 - α |d|)": "linear",
})

#: How the support matrix becomes weights.
SUPPORT_AGGREGATIONS: tuple[str, ...] = ("row sums", "principal eigenvector", "row sums, accumulated over time",
                                         "row sums × self-reliability")


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def support_values(t1: ArrayLike, kernel: str, aggregation: str, alphas: ArrayLike) -> FloatArray:
    """Support-degree fusion of every observation for every α (variants of Sun & Jing 2005).

    Parameters
    ----------
    t1 : array_like, shape (n_obs, n)
        Readings, observations by sensors (°C).
    kernel : str
        A key of :data:`SUPPORT_KERNELS`.
    aggregation : str
        One of :data:`SUPPORT_AGGREGATIONS`: row sums of the support matrix (Yager's power average),
        its principal eigenvector, row sums of the support matrices summed over the observations
        so far (history-based support), or row sums times a per-sensor self-reliability, the inverse
        of the sensor's sample variance over the observations so far (equal at the first
        observation; a "consistent and reliable" fusion in the sense of the title of Sun & Jing 2005).
    alphas : array_like, shape (k,)
        Sharpness values (°C⁻² for the Gaussian and Cauchy kernels, °C⁻¹ for the Laplace, arctan and linear
        kernels).

    Returns
    -------
    ndarray, shape (k, n_obs)
        Fused values (°C).

    Raises
    ------
    ValueError
        An unknown ``kernel`` or ``aggregation``, an α not positive, or the support matrices (``k * n_obs * n**2``
        entries, 8 units each; 1,000 more a matrix under the principal eigenvector; the self-reliability's
        ``n_obs`` steps of 5,000 units and 4 units an entry of its variances) beyond the work budget
        (``fusion._limits.MAX_WORK``) or the memory budget, naming ``alphas and t1`` (a list's length counted
        before its entries are converted).
    """
    kernel = one_of(kernel, tuple(SUPPORT_KERNELS), "kernel")
    aggregation = one_of(aggregation, SUPPORT_AGGREGATIONS, "aggregation")
    s = as_array(t1, "t1", ndim=(2,))
    k = _alphas_length(alphas)
    if k is not None:  # a list's length counted before its entries are converted (book audit 76)
        _support_budget(s.shape, k, aggregation)
    a = as_array(alphas, "alphas", ndim=(1,))
    _support_budget(s.shape, a.size, aggregation)
    if np.any(a <= 0):
        raise ValueError("alphas must be positive")
    d = np.abs(s[:, :, None] - s[:, None, :])[None]  # (1, n_obs, n, n)
    al = a[:, None, None, None]
    kind = SUPPORT_KERNELS[kernel]
    R = {"gauss": lambda: np.exp(-al * d**2), "laplace": lambda: np.exp(-al * d),
         "cauchy": lambda: 1.0 / (1.0 + al * d**2), "arctan": lambda: 1.0 - 2.0 / np.pi * np.arctan(al * d),
         "linear": lambda: np.maximum(0.0, 1.0 - al * d)}[kind]()
    if aggregation == "row sums":
        w = R.sum(axis=3)
    elif aggregation == "row sums, accumulated over time":
        w = np.cumsum(R, axis=1).sum(axis=3)
    elif aggregation == "row sums × self-reliability":
        n_obs = s.shape[0]
        rel = np.ones(s.shape)
        for o in range(1, n_obs):
            var = s[: o + 1].var(axis=0, ddof=1)
            rel[o] = 1.0 / np.maximum(var, 1e-12)
        w = R.sum(axis=3) * rel[None]
    else:
        from fusion.readings.fusion_set import perron_weights

        k, n_obs, n, _ = R.shape
        w = perron_weights(R.reshape(-1, n, n)).reshape(k, n_obs, n)
    w = w / w.sum(axis=2, keepdims=True)
    return np.einsum("kon,on->ko", w, s)


def support_variants(alphas: ArrayLike | None = None) -> pd.DataFrame:
    """Which observations of Table 3 each support-degree variant can reach, on Table 1 as printed and corrected.

    An observation is reachable when the variant's value crosses or meets the printed one for some α
    on the grid (the value is continuous in α).

    Parameters
    ----------
    alphas : array_like, optional
        Grid of α (default: 600 values log-spaced over 1e-6 to 1e3), sorted and its repeats dropped; every sign
        change of an observation's residual between adjacent values is refined by Brent's method and all six
        are tested at that α.

    Returns
    -------
    DataFrame
        Rows: (kernel, aggregation); columns: for Table 1 as printed and with the joint audit's
        correction, the reachable observations and whether one α reaches all six.

    Raises
    ------
    ValueError
        More α than the work budget (``fusion._limits.MAX_WORK``, 500,000 units an α: at most 2,000), by their
        number before any is converted, or more sign changes to refine than it (900,000 units each), counted
        before the first is refined, naming ``alphas``.
    """
    k = _alphas_length(alphas)
    if k is not None:  # counted before any α is converted (book audit 76)
        work((k,), "alphas", weight=_VARIANT_ALPHA)
    a = np.logspace(-6, 3, 600) if alphas is None else as_array(alphas, "alphas", ndim=(1,))
    work((a.size,), "alphas", weight=_VARIANT_ALPHA)
    pub = np.asarray(data.YANG2012_TABLE3.columns["reliability"])
    t_print = np.array(data.YANG2012_TABLE1.values, dtype=float).T
    t_fix = t_print.copy()
    t_fix[4, 0] = 889.9  # the joint audit's full explanation (tests check it is the one found)
    a = np.unique(a)  # a grid: sorted, repeats dropped (fuzz 68b C4: alternating alphas made every pair a crossing)
    tables = (("Table 1 as printed", t_print), ("obs. 5 sensor 1 = 889.9", t_fix))
    residuals = {(kern, agg, label): support_values(t, kern, agg, a) - pub
                 for kern in SUPPORT_KERNELS for agg in SUPPORT_AGGREGATIONS for label, t in tables}
    crossings = sum(int(np.count_nonzero(np.signbit(v[1:]) != np.signbit(v[:-1]))) for v in residuals.values())
    if crossings:  # every crossing's root refined by Brent's method, counted before the first
        work((crossings,), "alphas", weight=_VARIANT_ROOT)
    rows = {}
    for kern in SUPPORT_KERNELS:
        for agg in SUPPORT_AGGREGATIONS:
            row = {}
            for label, t in tables:
                v = residuals[(kern, agg, label)]
                hit = np.abs(v) < _TOL
                cross = np.signbit(v[1:]) != np.signbit(v[:-1])
                reach = hit.any(axis=0) | cross.any(axis=0)
                # a common α must be a root of every observation: refine each root of one and test all six there
                common = bool(hit.all(axis=1).any())
                for j, o in zip(*np.nonzero(cross)):
                    f = lambda la, o=o: float(support_values(t[: o + 1], kern, agg, [np.exp(la)])[0, o]  # noqa: E731
                                              - pub[o])
                    la = optimize.brentq(f, np.log(a[j]), np.log(a[j + 1]), xtol=1e-10)
                    common |= bool(np.all(np.abs(support_values(t, kern, agg, [np.exp(la)])[0] - pub) < _TOL))
                row[(label, "reachable observations")] = ", ".join(str(k + 1) for k in np.flatnonzero(reach)) or "none"
                row[(label, "one α for all six")] = common
            rows[(kern, agg)] = row
    df = pd.DataFrame(rows).T
    df.index.names = ["kernel", "weights from"]
    return df
