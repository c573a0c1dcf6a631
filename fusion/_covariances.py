"""The covariance rules of the shared validation (re-exported by :mod:`fusion._validation`).

A covariance is finite, symmetric to a tolerance of its scale, and positive definite (:func:`as_covariance`, by a
Cholesky factorisation) or semidefinite (:func:`as_semidefinite`), with every variance at least
:data:`~fusion._limits.MIN_VARIANCE`; :func:`covariance_pair` checks the two of a fusion in one stacked pass,
:func:`gaussian_pair` a pair of Gaussian estimates, :func:`diagonal_covariance` a diagonal measurement covariance.
Imported by :mod:`fusion._validation` after its own definitions, where the package imports them from.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg.lapack import dpotrf as _potrf

from fusion._limits import DENSE_CUBE, MAX_MAGNITUDE, MIN_VARIANCE, dense_work, work
from fusion._structures import singular_error
from fusion._validation import FloatArray, _magnitude_problem, _numeric, as_state, check_magnitude, scalar


_TINY = float(np.finfo(float).tiny)
_EPS = float(np.finfo(float).eps)
COVARIANCE_RTOL = 1e-9
"""The covariance readers' tolerance, relative to a matrix's largest entry: its asymmetry (every reader) and, for
:func:`as_semidefinite`, its most negative eigenvalue. The default ``rtol`` of the readers here; producers that
repair or refuse round-off before a reader sees it (``fusion.filtering.tracks._symmetric_steps``,
``fusion.scenarios._infrared_budget._semidefinite_tracks``) import it, so producer and reader keep one rule."""
SINGULAR_MARGIN = 2.0
"""The margin of positive definiteness, in units of ``n * eps``: a matrix whose correlation matrix
``D^-1/2 P D^-1/2`` (``D`` its diagonal) has its smallest eigenvalue within ``SINGULAR_MARGIN * n * eps`` of
zero, relative to its largest, is singular to working precision and refused, although LAPACK's Cholesky
factorisation may succeed on it by rounding (``0.41 * ones((2, 2))``, exactly singular, does). The rule is
invariant to the units of each state component (a diagonal rescaling); a correlation matrix of condition
number up to about ``1 / (SINGULAR_MARGIN * n * eps)`` (5.6e14 for n = 4) is accepted; a rounded exactly singular
matrix stays below ``n * eps`` (measured)."""


def _pivot_floor(n: int) -> float:
    return SINGULAR_MARGIN * n * _EPS


#: Units of one ``m d**2`` of :func:`column_rank_deficient`'s singular values of an ``(m, d)`` H (fix 65a, after fuzz
#: 57b D2): 0.18-0.21 ns measured for square H (d = 1,500 and 2,000; 0.10 ns for (6,000, 750)), time.process_time,
#: OPENBLAS_NUM_THREADS=1, the shared machine; a square H of 5,792, the input budget's, ran about 45 CPU-s unchecked.
RANK_CUBE = 2 * DENSE_CUBE


def column_rank_work(m: int, d: int, names: str = "H") -> int:
    """Refuse :func:`column_rank_deficient` of an ``(m, d)`` H beyond the work budget (rule 17), naming ``names``; a
    caller calls it as soon as H's shape is known, before its other arguments' ``O(n**3)`` checks."""
    return work((max(int(m), 1), int(d), int(d)), names, weight=RANK_CUBE) if m >= d else 0


def column_rank_deficient(H: FloatArray, name: str = "H") -> bool:
    """Whether the observation matrix ``H`` (m, d) lacks full column rank to working precision: the rule of
    :data:`SINGULAR_MARGIN` for an ``H`` (fuzz 27a N1). Its columns are scaled to unit norm first (the units of each
    state component), then its smallest singular value within ``SINGULAR_MARGIN * max(m, d) * eps`` of its
    largest is rank deficiency; a zero column or fewer rows than columns is too. ``np.linalg.matrix_rank(H)``
    decided by the units: ``diag(1, 1e16)`` was refused. Its singular values, ``m d**2`` work, are refused beyond
    the work budget first (:func:`column_rank_work`, a ValueError naming ``name``)."""
    m, d = H.shape
    if m < d:
        return True
    column_rank_work(m, d, name)
    top = np.max(np.abs(H), axis=0)
    if not np.all(top > 0):
        return True
    Hs = H / top  # no overflow in the norms
    Hs = Hs / np.linalg.norm(Hs, axis=0)
    s = np.linalg.svd(Hs, compute_uv=False)
    return not bool(s[-1] > SINGULAR_MARGIN * max(m, d) * _EPS * s[0])


def information_singular(A: FloatArray) -> bool:
    """Whether an information matrix ``A`` (d, d; a sum of ``H^T R^-1 H``) is singular to working precision: the
    rule of :data:`SINGULAR_MARGIN` (its correlation matrix, so the units of the state do not decide it; fuzz 27a
    N1). A non-positive diagonal entry (a state component no reading sees) is singular."""
    if not np.all(np.diagonal(A) > 0) or not np.all(np.isfinite(A)):
        return True
    return bool(singular_mask(A))


def singular_mask(arr: FloatArray, factor: FloatArray | None = None) -> np.ndarray:
    """Which matrices of a stack (..., n, n) that passed a Cholesky factorisation are singular to working precision.

    The rule of :data:`SINGULAR_MARGIN`, decided from the factorisation where it can be: with ``r_i = L_ii**2 /
    P_ii`` (the Cholesky pivots of the correlation matrix ``C``, trace ``n``), ``det C = prod r_i`` and the smallest
    eigenvalue lies between ``det C / e`` (the other eigenvalues sum to at most ``n``, so their product is at most
    ``e``) and ``min r_i``, the largest between 1 and ``n``. A matrix with ``min r_i`` within the margin is
    singular; one with ``det C / e`` beyond ``n`` times the margin is not; only those in between (condition
    numbers near ``1 / (n eps)``) need the eigenvalues.

    Parameters
    ----------
    arr : ndarray, shape (..., n, n)
        Symmetric matrices with a positive diagonal.
    factor : ndarray, shape (..., n, n), optional
        Their lower Cholesky factors, when the caller has them (only the diagonal is read); computed otherwise (a
        matrix that is not positive definite counts as singular).

    Returns
    -------
    ndarray of bool, shape (...)
        True where the matrix is numerically singular.
    """
    n = arr.shape[-1]
    if factor is None:
        try:
            factor = np.linalg.cholesky(arr)
        except np.linalg.LinAlgError:  # a stack: one at a time, a failed factorisation counted singular
            flat = arr.reshape((-1,) + arr.shape[-2:])
            return np.array([_one_singular(m) for m in flat], dtype=bool).reshape(arr.shape[:-2])
    piv = np.diagonal(factor, axis1=-2, axis2=-1)
    d = np.diagonal(arr, axis1=-2, axis2=-1)
    with np.errstate(invalid="ignore", over="ignore", under="ignore"):
        r = piv * piv / d
    tol = _pivot_floor(n)
    bad = (~(np.min(r, axis=-1) > tol)).reshape(-1)  # flat over the stack
    with np.errstate(divide="ignore"):
        unsure = ~bad & ~(np.exp(np.sum(np.log(r), axis=-1) - 1.0) > n * tol).reshape(-1)
    if unsure.any():
        stack = arr.reshape((-1, n, n))[unsure]
        s = 1.0 / np.sqrt(np.diagonal(stack, axis1=-2, axis2=-1))
        ev = np.linalg.eigvalsh(stack * s[..., :, None] * s[..., None, :])  # |P_ij| s_i <= sqrt(P_jj)
        bad[unsure] = ev[..., 0] <= tol * ev[..., -1]
    return bad.reshape(arr.shape[:-2])


def _one_singular(m: FloatArray) -> bool:
    try:
        return bool(singular_mask(m, np.linalg.cholesky(m)))
    except np.linalg.LinAlgError:
        return True


#: ``e * n * SINGULAR_MARGIN * n * eps`` by size ``n``: the determinant of a correlation matrix above which it is
#: surely not singular to working precision (:func:`singular_mask`).
_DET_FLOOR = tuple(math.e * n * _pivot_floor(n) for n in range(65))


#: The flat indices of an n x n matrix's diagonal, by n (for :func:`_regular_factors`).
_DIAGONAL = tuple(range(0, n * n, n + 1) for n in range(65))


def _regular_factors(factors: tuple[FloatArray, ...], diags: tuple[list[float], ...]) -> bool:
    """The fast accept of :func:`singular_mask` for small matrices whose ``dpotrf`` factors (only the diagonals are
    read) and diagonals the caller has, in plain floats: True when none is singular to working precision (False:
    one is singular or undecided, for :func:`singular_mask` to settle; also when a product leaves the normal float
    range, so that no underflow can pass a singular matrix)."""
    for factor, diag in zip(factors, diags):
        n = len(diag)
        if n >= len(_DIAGONAL):
            return False
        pivots = math.prod(map(factor.item, _DIAGONAL[n]))  # prod L_ii, without a numpy call
        den = math.prod(diag)
        if not (1e-290 < den < 1e290 and pivots * pivots > _DET_FLOOR[n] * den):
            return False
    return True


def check_invertible(M: FloatArray, names: str) -> None:
    """Refuse a computed positive-definite matrix (or stack) that is about to be inverted when it is singular to
    working precision by the rule of :data:`SINGULAR_MARGIN`.

    For the intermediate matrices of a fusion (``P1d / omega + P1i`` of split CI): valid parts can combine into a
    matrix whose inverse is rounding noise, and :func:`numpy.linalg.inv` raises only when LAPACK happens to meet an
    exact zero pivot; below that it returns plausible wrong numbers.

    Parameters
    ----------
    M : ndarray, shape (..., n, n)
        Symmetric positive-definite matrices (a positive diagonal).
    names : str
        The arguments the matrices come from, named in the message.

    Raises
    ------
    ValueError
        The message of ``singular_error`` (``fusion._structures``), naming ``names``.
    """
    if singular_mask(M).any():
        raise singular_error(names, "a matrix to invert is singular to working precision by its condition number")


def refuse_singular(arr: FloatArray, name: str) -> None:
    """Refuse, naming the first by its index, a matrix of a stack (..., n, n) that passed a Cholesky factorisation
    but is singular to working precision (the rule of :data:`SINGULAR_MARGIN`; the check of :func:`as_covariance`).

    Parameters
    ----------
    arr : ndarray, shape (..., n, n)
        Symmetric matrices with a positive diagonal.
    name : str
        The argument's name, used in the message (``covs[1]``).

    Raises
    ------
    ValueError
        A numerically singular matrix.
    """
    bad = singular_mask(arr)
    if bad.any():
        idx = tuple(int(i) for i in np.argwhere(bad)[0])
        raise ValueError(_singular_message(f"{name}[{', '.join(map(str, idx))}]" if idx else name))


def _singular_message(name: str) -> str:
    return (f"{name} must be positive definite: it is singular to working precision (its correlation matrix has "
            f"an eigenvalue within {SINGULAR_MARGIN:g} n eps of zero, relative to its largest)")


def asymmetric(P: FloatArray, rtol: float = COVARIANCE_RTOL) -> bool:
    """Whether any matrix of the finite stack ``P`` (..., n, n) is asymmetric beyond ``rtol`` of its own largest
    entry: the readers' symmetry rule for a stack whose matrices may differ in scale (each judged by its own, so a
    large matrix does not hide a small one's asymmetry). An empty stack is symmetric."""
    if P.size == 0:
        return False
    scale = np.maximum(np.abs(P).max(axis=(-2, -1)), _TINY)
    return bool((np.abs(P - np.swapaxes(P, -1, -2)).max(axis=(-2, -1)) > rtol * scale).any())


def _finite_symmetric(arr: FloatArray, name: str, rtol: float) -> tuple[FloatArray, float]:
    """Check a square matrix for NaN/inf and asymmetry; return its symmetric part and its scale.

    One pass in the usual case: ``arr - arr.T`` is exactly zero for a finite symmetric matrix,
    and NaN or infinite as soon as any entry is (inf - inf is NaN, so a symmetric pair of
    infinities is caught too). Only a non-zero difference needs the scale of the entries.
    """
    if arr.shape[-1] == 1:
        v = float(arr.flat[0]) if arr.size == 1 else float(np.abs(arr).max())
        if not abs(v) < np.inf:
            raise ValueError(f"{name} contains NaN or infinite values")
        return arr, max(abs(v), _TINY)
    with np.errstate(invalid="ignore"):  # inf - inf is NaN: reported as non-finite just below
        asym = float(np.abs(arr - np.swapaxes(arr, -1, -2)).max())
    if asym == 0.0:
        return arr, -1.0  # exactly symmetric (and finite); scale not needed
    if not asym < np.inf:
        raise ValueError(f"{name} contains NaN or infinite values")
    scale = max(float(np.abs(arr).max()), _TINY)
    if asym > rtol * scale:
        raise ValueError(f"{name} must be symmetric")
    return 0.5 * (arr + np.swapaxes(arr, -1, -2)), scale


def as_covariance(P: ArrayLike, dim: int | None = None, name: str = "P", rtol: float = COVARIANCE_RTOL) -> FloatArray:
    """Return ``P`` as a finite, symmetric, positive-definite (dim, dim) float matrix.

    A scalar or a 1x1 input is accepted for dimension one.

    Raises
    ------
    TypeError
        If ``P`` is not numeric.
    ValueError
        Wrong shape, NaN/inf, asymmetry beyond ``rtol`` (relative to the largest entry),
        or not positive definite (Cholesky fails, or the matrix is singular to working precision by the rule of
        :data:`SINGULAR_MARGIN`).
    """
    arr = _numeric(P, name)
    if arr.ndim == 0:
        arr = arr.reshape(1, 1)
    if arr.ndim != 2 or arr.shape[0] != arr.shape[1] or arr.shape[0] == 0:
        raise ValueError(f"{name} must be a square matrix, got shape {arr.shape}")
    if dim is not None and arr.shape[0] != dim:
        raise ValueError(f"{name} must be {dim}x{dim} to match the state, got {arr.shape}")
    sym, _ = _finite_symmetric(arr, name, rtol)
    # the matrix returned is judged: the symmetric part, not the lower triangle of an asymmetric input (fuzz 49a C5:
    # [[1, 1 + 5e-10], [1 - 1e-10, 1]] passed on its lower triangle while its symmetric part, returned, is indefinite)
    factor, info = _potrf(sym, lower=1, clean=0)
    if info != 0:  # LAPACK Cholesky: info > 0 if not positive definite
        raise ValueError(f"{name} must be positive definite")
    _covariance_magnitude(sym, name)
    if singular_mask(sym, factor):  # Cholesky can succeed by rounding on an exactly singular matrix
        raise ValueError(_singular_message(name))
    return sym


def _covariance_magnitude(arr: FloatArray, name: str) -> None:
    """Rule 2 for a validated positive-(semi)definite matrix: its diagonal bounds every entry.

    ``|P_ij| <= sqrt(P_ii P_jj)``, so the diagonal alone decides whether the entries are within
    :data:`MAX_MAGNITUDE`; a non-zero variance below :data:`MIN_VARIANCE` is refused too (the
    products of two entries that every filter forms would underflow).
    """
    d = np.diagonal(arr, axis1=-2, axis2=-1)
    if d.size <= 64:  # small: plain floats are cheaper than numpy reductions
        dl = d.reshape(-1).tolist()
        if max(dl) <= MAX_MAGNITUDE and min(dl) >= MIN_VARIANCE:
            return
    problem = _magnitude_problem(d)
    if problem is not None:
        raise ValueError(f"{name} {problem.replace('an entry', 'a variance').replace('entry', 'variance')}")
    if ((d != 0) & (np.abs(d) < MIN_VARIANCE)).any():
        raise ValueError(f"{name} has a variance below {MIN_VARIANCE:.3g}: products of its entries underflow")



def as_covariances(P: ArrayLike, dim: int | None = None, name: str = "covs", rtol: float = COVARIANCE_RTOL) -> FloatArray:
    """A stack of covariances, shape (..., dim, dim), each checked by the rule of :func:`as_covariance`.

    The batched form of that rule (finite, symmetric, positive definite, variances within the magnitude rule), for
    the (B, M, d, d) inputs of the package's batched kernels: one stacked pass when every matrix is fine (exactly
    symmetric, a batched Cholesky factorisation, the diagonals' magnitudes), else the matrices one by one, so that the
    message names the first at fault by its index (``covs[1, 0] must be positive definite``).

    Parameters
    ----------
    P : array_like, shape (..., n, n)
        At least one matrix, of size ``n`` >= 1.
    dim : int, optional
        Required size ``n``.
    name : str
        The argument's name, used in the messages.
    rtol : float
        Relative asymmetry tolerance, as :func:`as_covariance`.

    Returns
    -------
    ndarray, shape (..., n, n)
        The covariances (their symmetric parts).

    Raises
    ------
    TypeError
        Not numeric, or complex.
    ValueError
        No matrix, a wrong shape, or a matrix refused by :func:`as_covariance`, naming it.
    """
    arr = _numeric(P, name)
    if arr.ndim < 2 or arr.shape[-1] != arr.shape[-2] or arr.shape[-1] == 0 or 0 in arr.shape[:-2]:
        raise ValueError(f"{name} must be a non-empty stack of square matrices (..., n, n) with n >= 1, got shape "
                         f"{arr.shape}")
    if dim is not None and arr.shape[-1] != dim:
        raise ValueError(f"{name} must hold {dim}x{dim} matrices to match the state, got shape {arr.shape}")
    with np.errstate(invalid="ignore"):  # NaN or inf: the one-by-one checks below say which
        symmetric = not np.abs(arr - np.swapaxes(arr, -1, -2)).max() != 0.0
    if symmetric:
        try:
            factor = np.linalg.cholesky(arr)
        except np.linalg.LinAlgError:
            pass
        else:
            d = np.diagonal(arr, axis1=-2, axis2=-1)
            if (float(d.max()) <= MAX_MAGNITUDE and float(d.min()) >= MIN_VARIANCE
                    and not singular_mask(arr, factor).any()):
                return arr
    out = np.empty_like(arr)
    for idx in np.ndindex(*arr.shape[:-2]):
        label = f"{name}[{', '.join(map(str, idx))}]" if idx else name
        out[idx] = as_covariance(arr[idx], dim=arr.shape[-1], name=label, rtol=rtol)
    return out


_SMALL_PAIR = 8
_F64 = np.dtype(np.float64)


def covariance_pair(P1: ArrayLike, P2: ArrayLike, names: tuple[str, str] = ("P1", "P2"),
                    dim: int | None = None, rtol: float = COVARIANCE_RTOL, weight: float = 0.0) -> tuple[FloatArray, FloatArray]:
    """Two symmetric positive-definite covariances of one size, validated in one stacked pass.

    The same checks as :func:`as_covariance` on each (shape, NaN/inf, symmetry, positive
    definiteness, magnitudes), but the finiteness, symmetry and magnitude checks run once on the
    pair stacked, which halves their fixed cost for the small matrices of covariance intersection.

    Parameters
    ----------
    P1, P2 : array_like, shape (n, n)
        The covariances.
    names : (str, str)
        Their argument names, used in the messages.
    dim : int, optional
        Required size ``n``.
    rtol : float
        Relative asymmetry tolerance.
    weight : float
        The caller's measured units per ``d**3`` of each matrix (``fusion._limits.dense_work``), checked before the
        ``O(d**3)`` checks; 0 for none.

    Returns
    -------
    (ndarray, ndarray)
        The two covariances (their symmetric parts).

    Raises
    ------
    TypeError
        Not numeric, or complex.
    ValueError
        As :func:`as_covariance`, naming the covariance at fault.
    """
    if (type(P1) is np.ndarray and type(P2) is np.ndarray and P1.dtype is _F64 and P2.dtype is _F64
            and P1.ndim == 2 and P1.shape == P2.shape and 2 <= P1.shape[0] == P1.shape[1] <= _SMALL_PAIR
            and (dim is None or dim == P1.shape[0])):
        # the usual case (two small float matrices): plain floats and two LAPACK calls, cheaper than numpy's
        # checks. Symmetry is bitwise equality with the transpose (a -0.0 facing a 0.0 takes the general path
        # below). A NaN or infinity anywhere reaches a pivot of the factorisation (L_ij = NaN gives L_ii = NaN),
        # so the determinant test of _regular_factors fails on it; a huge entry either sits on the diagonal
        # (checked) or makes the matrix indefinite (|P_ij| <= sqrt(P_ii P_jj)). Anything that fails goes
        # through the general path below for the precise message.
        if P1.tobytes() == P1.T.tobytes() and P2.tobytes() == P2.T.tobytes():
            (c1, i1), (c2, i2) = _potrf(P1, 1, 0), _potrf(P2, 1, 0)
            if not i1 and not i2:
                d1, d2 = P1.diagonal().tolist(), P2.diagonal().tolist()
                d = d1 + d2
                if max(d) <= MAX_MAGNITUDE and min(d) >= MIN_VARIANCE:
                    # _regular_factors inlined (the hot path of covariance intersection)
                    n = len(d1)
                    idx, floor = _DIAGONAL[n], _DET_FLOOR[n]
                    p1, p2 = math.prod(map(c1.item, idx)), math.prod(map(c2.item, idx))
                    e1, e2 = math.prod(d1), math.prod(d2)
                    if 1e-290 < e1 < 1e290 and 1e-290 < e2 < 1e290 and p1 * p1 > floor * e1 and p2 * p2 > floor * e2:
                        return P1, P2
    A, B = _numeric(P1, names[0]), _numeric(P2, names[1])
    shape = A.shape
    if weight and A.ndim == 2:
        dense_work(2, max(A.shape), f"{names[0]} and {names[1]}", weight)  # fuzz 36a C3
    n = shape[0] if len(shape) == 2 else 0
    if n < 2 or B.shape != shape or shape[1] != n or (dim is not None and n != dim):
        # the general path (scalars, 1x1, mismatches): one at a time, with the per-matrix messages
        A = as_covariance(A, dim=dim, name=names[0], rtol=rtol)
        return A, as_covariance(B, dim=A.shape[0], name=names[1], rtol=rtol)
    if n <= _SMALL_PAIR:
        # small matrices (the usual 2-6 states): plain floats over both, cheaper than any numpy
        # call. A NaN breaks the equality; an infinity or a huge entry either sits on the diagonal
        # (checked below) or makes the matrix indefinite (|P_ij| <= sqrt(P_ii P_jj)), and a failed
        # Cholesky goes through the per-matrix checks for the precise message.
        la, lb = A.tolist(), B.tolist()
        ok = la == A.T.tolist() and lb == B.T.tolist()
        idx = range(n)
        diag = list(map(list.__getitem__, la, idx)) + list(map(list.__getitem__, lb, idx))
    else:
        S = np.stack((A, B))
        with np.errstate(invalid="ignore"):
            ok = not np.abs(S - S.transpose(0, 2, 1)).max() != 0.0
        diag = np.diagonal(S, axis1=1, axis2=2).reshape(-1).tolist()
    (ca, ia), (cb, ib) = _potrf(A, 1, 0), _potrf(B, 1, 0)
    if not ok or ia or ib:
        # asymmetric, NaN/inf, or not positive definite: the per-matrix checks say which and how
        A = as_covariance(A, dim=dim, name=names[0], rtol=rtol)
        return A, as_covariance(B, dim=A.shape[0], name=names[1], rtol=rtol)
    if not (max(diag) <= MAX_MAGNITUDE and min(diag) >= MIN_VARIANCE):
        _covariance_magnitude(A, names[0])
        _covariance_magnitude(B, names[1])
    for M, c, name in ((A, ca, names[0]), (B, cb, names[1])):  # finite, within the magnitude rule: singular?
        if not _regular_factors((c,), (M.diagonal().tolist(),)) and singular_mask(M, c):
            raise ValueError(_singular_message(name))
    return A, B


def as_semidefinite(P: ArrayLike, dim: int, name: str = "P", rtol: float = COVARIANCE_RTOL) -> FloatArray:
    """Return ``P`` as a finite, symmetric, positive-semidefinite (dim, dim) float matrix.

    For process noise, which is often of low rank (e.g. white acceleration).

    Raises
    ------
    ValueError
        Wrong shape, NaN/inf, asymmetry, an eigenvalue below ``-rtol`` times the largest entry, or a
        non-zero variance below :data:`MIN_VARIANCE` (the rule of :func:`as_covariance`; a zero
        variance, a direction without noise, is valid).
    """
    arr = _numeric(P, name)
    if arr.shape != (dim, dim):
        raise ValueError(f"{name} must be {dim}x{dim}, got shape {arr.shape}")
    sym, scale = _finite_symmetric(arr, name, rtol)
    if scale < 0:
        scale = max(float(np.abs(sym).max()), _TINY)
    if np.linalg.eigvalsh(sym).min() < -rtol * scale:
        raise ValueError(f"{name} must be positive semidefinite")
    check_magnitude(sym, name, subnormal=False)  # huge entries anywhere; subnormal off-diagonals are harmless
    d = np.abs(np.diagonal(sym))  # the covariance rule: a zero variance is valid (low rank), a tiny one is not
    if ((d > 0) & (d < MIN_VARIANCE)).any():
        raise ValueError(f"{name} has a variance below {MIN_VARIANCE:.3g} (non-zero): products of its entries "
                         "underflow")
    return sym


def computed_part(M: FloatArray) -> FloatArray:
    """A semidefinite part a loop computes (not an input), its variances below :data:`MIN_VARIANCE` set to zero.

    The tiny-variance rule of :func:`as_semidefinite` is a rule for inputs (a caller's variance of 1e-160 is a unit
    or typing error). A part a recursion computes can decay to such a variance as a valid state: the correlated
    part of split CI with its process noise in the independent part, fed back at every step, decays geometrically
    (chapter 05's architecture study at T = 0.5 s: below 1.49e-154 after some hundred steps). Such a variance is
    zero to working precision against the covariance it is a part of, so its row and column are set to zero (a
    principal submatrix padded with zeros: still semidefinite, and :func:`as_semidefinite` accepts it); a part
    without one is returned as it is (the same object), so every result that was accepted before is unchanged.
    """
    d = np.abs(np.diagonal(M))
    tiny = (d > 0) & (d < MIN_VARIANCE)
    if not tiny.any():
        return M
    out = np.array(M, dtype=float)
    out[tiny, :] = 0.0
    out[:, tiny] = 0.0
    return out


def gaussian_pair(
    m0: ArrayLike, P0: ArrayLike, m1: ArrayLike, P1: ArrayLike, names: tuple[str, str, str, str], weight: float = 0.0
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Two Gaussians (means of one length, SPD covariances of that size), validated.

    ``names`` are the four argument names used in the messages; ``weight`` the caller's measured units per ``d**3``
    of each covariance (``fusion._limits.dense_work``, checked from the means' length before the covariances'
    ``O(d**3)`` checks; 0 for none).
    """
    a, b = as_state(m0, names[0]), as_state(m1, names[2])
    if a.shape != b.shape:
        raise ValueError(f"{names[0]} and {names[2]} must have the same length, got {a.size} and {b.size}")
    if weight:
        dense_work(2, a.size, f"{names[1]} and {names[3]}", weight)  # fuzz 36a C3
    A = as_covariance(P0, name=names[1])
    if A.shape[0] != a.size:
        raise ValueError(f"{names[1]} must be {a.size}x{a.size} to match {names[0]}, got {A.shape}")
    B = as_covariance(P1, name=names[3])
    if B.shape[0] != a.size:
        raise ValueError(f"{names[3]} must be {a.size}x{a.size} to match {names[0]}, got {B.shape}")
    return a, A, b, B


def diagonal_covariance(R: ArrayLike, dim: int, name: str) -> FloatArray:
    """A (dim, dim) covariance that must be diagonal (issue 35, class 4).

    For a consumer that draws noise per axis from the diagonal alone: a non-diagonal matrix
    would be accepted but its correlations silently ignored.

    Raises
    ------
    ValueError
        As :func:`as_covariance`, or an off-diagonal entry that is not zero.
    """
    arr = as_covariance(R, dim=dim, name=name)
    if np.count_nonzero(arr - np.diag(np.diagonal(arr))):
        raise ValueError(f"{name} must be diagonal (the noise is drawn per axis from its diagonal), got {arr.tolist()}")
    return arr
