r"""Baselines a practitioner would reach for when fusing simultaneous readings with possible faults.

Every method here fuses each row (epoch) of an array of readings to one value, vectorised over
rows. They differ in the information they use:

* ``"median"``, ``"trimmed_mean"`` (scipy), ``"huber"`` (M-estimator, scale from the MAD): the
  readings only;
* ``"grubbs"``: the readings only (iterated Grubbs test at level ``alpha``, then the mean of the
  readings kept);
* ``"biweight"`` (Tukey's redescending M-estimator, tuning constant ``c_biweight`` = 4.685 in units
  of the normalised MAD) and ``"mad_reject"`` (readings farther than ``k`` normalised MADs from
  the median rejected, then the mean of the rest): the readings only; both reject far readings
  completely;
* ``"inverse_variance"``: the readings **and the known noise standard deviations** ``sigma``;
* ``"uniform_set"``: the optimal fusion set of Yang, Feng & Fan (2012) with equal weights, the
  ablation of their eqs. 6-11.

References
----------
* Huber, P. J. (1964). Robust estimation of a location parameter. *Annals of Mathematical
  Statistics*, 35(1), 73-101.
* Beaton, A. E., & Tukey, J. W. (1974). The fitting of power series, meaning polynomials,
  illustrated on band-spectroscopic data. *Technometrics*, 16(2), 147-185.
* Hampel, F. R. (1974). The influence curve and its role in robust estimation. *Journal of the
  American Statistical Association*, 69(346), 383-393.
* Grubbs, F. E. (1969). Procedures for detecting outlying observations in samples.
  *Technometrics*, 11(1), 1-21.
* Yang, G., Feng, X., & Fan, L. (2012). Multi-sensor data fusion algorithm based on optimal
  fusion set. *Journal of Software*, 23(Suppl. 1), 134-140 (in Chinese).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike
from scipy import stats

from fusion._frozen import constant
from fusion._limits import LOOP_STEP, loop_work
from fusion._validation import FloatArray, as_array, as_reading_rows, one_of, positive_scalar, scalar
from fusion.readings.fusion_set import _members_rows

__all__ = ["ROBUST_METHODS", "robust_fuse"]

#: Methods of :func:`robust_fuse`, with the information each uses.
ROBUST_METHODS: dict[str, str] = constant({
    "median": "readings only",
    "trimmed_mean": "readings only",
    "huber": "readings only",
    "grubbs": "readings only",
    "biweight": "readings only",
    "mad_reject": "readings only",
    "inverse_variance": "readings and known noise standard deviations",
    "uniform_set": "readings only",
})

_MAD_TO_SIGMA = 1.0 / stats.norm.ppf(0.75)

#: The IRLS passes ``"huber"`` and ``"biweight"`` may take (the default ``iterations`` of :func:`_huber` and
#: :func:`_biweight`): how many they take depends on the readings (fuzz 46a C1: ``c_biweight=0.1`` on a tiled row of
#: 101 readings takes all 500 in every row, 33.5e6 readings ran 62.5 CPU-s; C1b: default options, 4e6 rows of 3
#: readings near 900 with one sensor shifted by 1 sigma ran 29 CPU-s).
_IRLS_PASSES = 500

#: An IRLS driver (:func:`_irls`): ``(update, s, mu0, par, tol, iterations)`` -> the final estimates.
_Iterate = Callable[[Callable[[FloatArray, FloatArray, FloatArray], FloatArray], FloatArray, FloatArray, FloatArray,
                     FloatArray, int], FloatArray]


def _huber(s: FloatArray, c: float, iterations: int = _IRLS_PASSES, tol: float = 1e-10, irls: _Iterate | None = None
           ) -> FloatArray:
    """Huber M-estimate of location per row, scale fixed at the normalised MAD (IRLS from the median).

    Iterates until no estimate moves by more than ``tol`` times its scale (or ``iterations``). A row whose
    update returns its estimate exactly (a fixed point: every later update returns it again) is set aside
    (:func:`_irls`, or ``irls``: the parity reference in ``benchmarks/_reference_kernels.py`` passes its loop over
    every row): the same numbers as iterating every row to the end, in less time.
    """
    med = np.median(s, axis=1)
    scale = _MAD_TO_SIGMA * np.median(np.abs(s - med[:, None]), axis=1)
    tiny = scale <= 0.0  # half or more of the readings equal: the median is the estimate
    scale = np.where(tiny, 1.0, scale)
    r = np.empty_like(s)
    w = np.empty_like(s)

    def update(sa: FloatArray, mua: FloatArray, col: FloatArray) -> FloatArray:
        n = len(sa)
        ra, wa = r[:n], w[:n]  # the same arithmetic as w = where(r <= c, 1, c / max(r, c)), in place
        np.subtract(sa, mua[:, None], out=ra)
        np.abs(ra, out=ra)
        np.divide(ra, col, out=ra)
        np.maximum(ra, c, out=wa)
        np.divide(c, wa, out=wa)
        wa[ra <= c] = 1.0
        wsum = wa.sum(axis=1)
        np.multiply(wa, sa, out=wa)
        return wa.sum(axis=1) / wsum

    mu = (irls or _irls)(update, s, med, scale[:, None], tol * scale, iterations)
    return np.where(tiny, med, mu)


def _biweight(s: FloatArray, c: float, iterations: int = _IRLS_PASSES, tol: float = 1e-10, irls: _Iterate | None = None
              ) -> FloatArray:
    """Tukey's biweight M-estimate of location per row, scale fixed at the normalised MAD (IRLS from the median).

    Fixed-point rows set aside as in :func:`_huber` (``irls`` likewise)."""
    med = np.median(s, axis=1)
    scale = _MAD_TO_SIGMA * np.median(np.abs(s - med[:, None]), axis=1)
    tiny = scale <= 0.0
    scale = np.where(tiny, 1.0, scale)
    w = np.empty_like(s)

    def update(sa: FloatArray, mua: FloatArray, cs: FloatArray) -> FloatArray:
        wa = w[:len(sa)]  # the same arithmetic as w = where(|u| < 1, (1 - u**2)**2, 0), in place
        np.subtract(sa, mua[:, None], out=wa)
        np.divide(wa, cs, out=wa)
        outside = np.abs(wa) >= 1.0
        np.square(wa, out=wa)
        np.subtract(1.0, wa, out=wa)
        np.square(wa, out=wa)
        wa[outside] = 0.0
        wsum = wa.sum(axis=1)
        np.multiply(wa, sa, out=wa)
        return np.where(wsum > 0, wa.sum(axis=1) / np.where(wsum > 0, wsum, 1.0), mua)

    mu = (irls or _irls)(update, s, med, c * scale[:, None], tol * scale, iterations)
    return np.where(tiny, med, mu)


#: Rows of one block of an IRLS update (:func:`_by_blocks`): its temporaries stay in the core's cache.
_IRLS_BLOCK = 4096


def _by_blocks(update: Callable[[FloatArray, FloatArray, FloatArray], FloatArray], sa: FloatArray, mua: FloatArray,
               pa: FloatArray) -> FloatArray:
    """``update(sa, mua, pa)`` computed :data:`_IRLS_BLOCK` rows at a time: the update is row-wise, so the result is
    the one of a single call bit for bit, with the temporaries in cache (tests/test_kernel_parity.py)."""
    if len(sa) <= _IRLS_BLOCK:
        return update(sa, mua, pa)
    out = np.empty(len(sa))
    for i in range(0, len(sa), _IRLS_BLOCK):
        b = slice(i, i + _IRLS_BLOCK)
        out[b] = update(sa[b], mua[b], pa[b])
    return out


def _irls(update: Callable[[FloatArray, FloatArray, FloatArray], FloatArray], s: FloatArray, mu0: FloatArray,
          par: FloatArray, tol: FloatArray, iterations: int) -> FloatArray:
    """Iterate ``mu <- update(s, mu, par)`` row-wise until no row moves by more than ``tol`` (per row), at most
    ``iterations`` times; returns the final ``mu`` (a new array).

    ``update`` is row-wise (a row's result depends on that row alone). A row whose update returns its ``mu``
    exactly is at a fixed point: every later update returns the same value, so it is set aside (once they are
    a quarter of the rows still iterated) and the result is the one of iterating every row to the end; the
    stopping test is unchanged (such a row moves by 0).
    """
    mu = mu0.copy()
    act = np.arange(len(s))  # the rows still iterated
    sa, mua, pa, ta = s, mu0, par, tol
    for _ in range(iterations):
        new = _by_blocks(update, sa, mua, pa)
        done = np.all(np.abs(new - mua) <= ta)
        fixed = new == mua
        mu[act] = new
        mua = new
        if done:
            break
        n_fixed = int(np.count_nonzero(fixed))
        if n_fixed and 4 * n_fixed >= len(act):
            keep = ~fixed
            act, sa, mua, pa, ta = act[keep], sa[keep], mua[keep], pa[keep], ta[keep]
    return mu


def _mad_reject(s: FloatArray, k: float) -> FloatArray:
    """Mean of the readings within ``k`` normalised MADs of the median (all readings if the MAD is 0)."""
    med = np.median(s, axis=1)
    scale = _MAD_TO_SIGMA * np.median(np.abs(s - med[:, None]), axis=1)
    keep = (np.abs(s - med[:, None]) <= k * scale[:, None]) | (scale[:, None] <= 0.0)
    return np.where(keep, s, 0.0).sum(axis=1) / keep.sum(axis=1)


#: Entries up to which a Grubbs pass works in the cache, at a third of a unit an entry (3.4-4 ns measured with
#: time.process_time on 1 x 20,000 to 40,000, 10 x 4,000 and 30 x 1,000 readings); a larger ``x`` costs 8-14 ns an
#: entry (100 to 3,000 epochs of 100 to 1,000 readings), 1.5 units (fuzz 37a C4: 2,900 x 1,000 ran 26 CPU-s).
_GRUBBS_CACHED = 2**16


def _grubbs_pass(size: int) -> int:
    """The vectorised units of one Grubbs pass over ``size`` entries (:data:`_GRUBBS_CACHED`)."""
    return size // 3 if size <= _GRUBBS_CACHED else math.ceil(1.5 * size)


def _grubbs(s: FloatArray, alpha: float) -> FloatArray:
    """Iterated two-sided Grubbs test: drop the most extreme reading while it is significant."""
    keep = np.ones(s.shape, dtype=bool)
    n_total = s.shape[1]
    for _ in range(max(n_total - 3, 0)):
        n = keep.sum(axis=1)
        mean = np.where(keep, s, 0.0).sum(axis=1) / n
        dev = np.where(keep, np.abs(s - mean[:, None]), -1.0)
        sd = np.sqrt(np.where(keep, (s - mean[:, None]) ** 2, 0.0).sum(axis=1) / (n - 1))
        worst = np.argmax(dev, axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):
            G = dev[np.arange(len(s)), worst] / sd
            un, inv = np.unique(n, return_inverse=True)  # a few distinct counts: the quantile once for each
            t = stats.t.ppf(1.0 - alpha / (2 * un), un - 2)[inv]
            crit = (n - 1) / np.sqrt(n) * np.sqrt(t**2 / (n - 2 + t**2))
        drop = (sd > 0) & (n > 2) & (G > crit)
        if not drop.any():
            break
        keep[np.flatnonzero(drop), worst[drop]] = False
    return np.where(keep, s, 0.0).sum(axis=1) / keep.sum(axis=1)


#: The n x n float64 arrays the pairwise kernel of each method of :func:`robust_fuse` holds at once for one row (absent:
#: no pairwise kernel), declared to the shared reading conversion (``pairs`` of ``fusion._validation.as_reading_rows``,
#: as ``fusion_set.fuse_epochs`` does, rules 9 and 17): ``"uniform_set"``'s membership (eq. 5) holds the n x n
#: distances of a row (fuzz 45b C5: 100,000 readings asked for a 74.5 GiB array, refused only by a MemoryError).
_PAIRS = {"uniform_set": 1}


#: Units of work of one IRLS pass (:func:`_irls`) over one row and over one reading of it. Measured with
#: time.process_time (OPENBLAS_NUM_THREADS=1, minimum of 3, the machine shared with other jobs) on 1e6 readings of
#: 900 + N(0, 1), sensor 0 shifted by 1, every row iterated (none set aside), 20 passes less 0: per row a pass, huber /
#: biweight, n = 2: 44 / 41 ns, 3: 52 / 49, 5: 58 / 51, 10: 85 / 74, 30: 197 / 108, 100: 574 / 317 ns; counted
#: 4 units a row + 0.6 a reading (52, 58, 70, 100, 220, 640 ns): the per-row part dominates at 2-3 readings.
_IRLS_ROW, _IRLS_READING = 4, 0.6


def _irls_pass(rows: int, n: int) -> int:
    """The vectorised units of one IRLS pass over ``rows`` rows of ``n`` readings (:data:`_IRLS_ROW`)."""
    return math.ceil(rows * (_IRLS_ROW + _IRLS_READING * n))


def _robust_limit(rows: int, n: int, method: str, names: str) -> int:
    """Refuse, naming ``names``, what :func:`robust_fuse` refuses of ``rows`` epochs of ``n`` readings fused by
    ``method`` beyond their linear cost: the input budget, the pairwise kernel of :data:`_PAIRS` (memory and work, by
    ``fusion._counts.pairwise``), the Grubbs passes (up to one a reading of a row, each over the whole array) and the
    IRLS passes of ``"huber"`` and ``"biweight"`` (up to :data:`_IRLS_PASSES`, each over every row).
    :func:`robust_fuse` calls it on its ``x``; a caller that draws the readings itself calls it at its entry, once
    per method, before the draws (``fusion.book.chapters.ofs_fair.fair_study``).

    Returns
    -------
    int
        The units of work of the super-linear part (0 for a method without one).
    """
    from fusion._counts import input_allocation, pairwise

    input_allocation((rows, n), names)
    if method in _PAIRS:
        return pairwise(n, names, _PAIRS[method], rows=rows)
    if method == "grubbs":
        # rule 17 (fuzz 36a C6, 37a C4): up to one pass per reading of a row, each a t quantile (~50 us) and its
        # passes over the whole (epochs, readings) array; the worst case is refused
        return loop_work((max(n - 3, 0),), _grubbs_pass(rows * n), names, step=5 * LOOP_STEP)
    if method in ("huber", "biweight"):
        # rule 17 (fuzz 46a C1): the passes a row takes depend on its readings and the tuning constant (up to
        # _IRLS_PASSES, every row in the worst case); the worst case is refused, as Grubbs'
        return loop_work((_IRLS_PASSES,), _irls_pass(rows, n), names)
    return 0


def robust_fuse(x: ArrayLike, method: str = "median", *, sigma: ArrayLike | None = None, cut: float = 0.1,
                c: float = 1.345, alpha: float = 0.05, c_biweight: float = 4.685, k: float = 3.0) -> FloatArray:
    r"""Fuse each row of readings with a standard location estimator.

    Parameters
    ----------
    x : array_like, shape (n_epochs, n_sensors) or (n_sensors,)
        Readings; each row is one epoch.
    method : {"median", "trimmed_mean", "huber", "grubbs", "biweight", "mad_reject", "inverse_variance", "uniform_set"}
        See the module docstring and :data:`ROBUST_METHODS` for the information each uses.
    sigma : array_like, shape (n_sensors,), optional
        Known noise standard deviations; required by ``"inverse_variance"`` only (checked when given, whatever
        the method).
    cut : float
        Fraction cut from each end by ``"trimmed_mean"`` (:func:`scipy.stats.trim_mean`), in [0, 0.5).
    c : float
        Huber's tuning constant in units of the scale (1.345: 95 % efficiency at the normal).
    alpha : float
        Level of each Grubbs test, in (0, 1). ``"grubbs"`` may drop all but three readings of a row, one pass
        each: a ``x`` whose worst case is beyond the work budget (``fusion._limits.MAX_WORK``, ~10 CPU-s; one
        epoch of ~45,000 readings, 665 epochs of 1,000, 100 of ~2,500) is refused, whatever its readings.
    c_biweight : float
        Tukey's biweight tuning constant in units of the scale (4.685: 95 % efficiency at the normal).
        ``"huber"`` and ``"biweight"`` iterate up to 500 times (how many depends on the readings and on ``c`` or
        ``c_biweight``, every row in the worst case): a ``x`` whose worst case is beyond the work budget (one epoch
        of ~3.3 million readings, 199,900 epochs of 10, 344,655 of 3) is refused, whatever its readings.
    k : float
        Rejection threshold of ``"mad_reject"`` in normalised MADs (a reading with
        :math:`|x - \mathrm{median}| > k\,\mathrm{MAD}/0.6745` is dropped).

        Every option is checked whatever the method, also where the method does not use it.

    Returns
    -------
    ndarray, shape (n_epochs,)
        Fused values, in the readings' unit.

    Raises
    ------
    ValueError
        Unknown method, non-finite readings, ``sigma`` missing or of the wrong length, or an
        option out of range; ``"uniform_set"`` on a ``x`` whose n x n distances of a row (eq. 5) are beyond the
        memory or the work budget (``fusion._counts.pairwise``, ``PAIR_WORK`` units a pair: one epoch of 7,071
        readings, 100 epochs of 707), refused naming ``x`` before any of them; ``"grubbs"`` beyond its budget (see
        ``alpha``); ``"huber"`` and ``"biweight"`` beyond theirs (see ``c_biweight``).
    """
    method = one_of(method, tuple(ROBUST_METHODS), "method")
    s = as_reading_rows(x, pairs=_PAIRS.get(method, 0))  # a pairwise kernel refused by x before any of it
    # every option is checked whatever the method (fuzz 24a D4): a bad value is the caller's mistake even where
    # this method ignores it
    cut = scalar(cut, "cut", 0.0, 0.5, hi_open=True)
    c, c_biweight, k = positive_scalar(c, "c"), positive_scalar(c_biweight, "c_biweight"), positive_scalar(k, "k")
    alpha = scalar(alpha, "alpha", 0.0, 1.0, lo_open=True, hi_open=True)
    if sigma is not None:
        sig = as_array(sigma, "sigma", ndim=(0, 1))
        sig = np.broadcast_to(sig, (s.shape[1],)) if sig.ndim == 0 else sig
        if sig.shape != (s.shape[1],):
            raise ValueError(f"sigma must have one entry per sensor ({s.shape[1]}), got shape {sig.shape}")
        if np.any(sig <= 0):
            raise ValueError("sigma must be finite and positive")
    if method == "median":
        return np.median(s, axis=1)
    if method == "trimmed_mean":
        return np.asarray(stats.trim_mean(s, cut, axis=1), dtype=float)
    if method in ("huber", "biweight"):
        _robust_limit(*s.shape, method, "x (its readings per epoch and epochs)")  # its worst case, by x
    if method == "huber":
        return _huber(s, c)
    if method == "grubbs":
        _robust_limit(*s.shape, method, "x (its readings per epoch and epochs)")  # its worst case, by x
        return _grubbs(s, alpha)
    if method == "biweight":
        return _biweight(s, c_biweight)
    if method == "mad_reject":
        return _mad_reject(s, k)
    if method == "uniform_set":
        members = _members_rows(s, "mean")
        return np.where(members, s, 0.0).sum(axis=1) / members.sum(axis=1)
    if sigma is None:
        raise ValueError("sigma (the known noise standard deviations) is required by method 'inverse_variance'")
    w = sig**-2.0
    return (s * w).sum(axis=1) / w.sum()
