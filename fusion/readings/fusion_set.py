r"""Readings-level fusion: simultaneous scalar readings of one quantity.

Every method here takes ``n`` readings :math:`s_1, \dots, s_n` of the same quantity taken
at the same instant and returns a convex combination :math:`\hat x = \sum_i w_i s_i` with
:math:`w_i \ge 0` and :math:`\sum_i w_i = 1`. The weights differ between methods:

* :func:`arithmetic_mean`: :math:`w_i = 1/n`.
* :func:`optimal_fusion_set`: the method of Yang, Feng & Fan (2012), eqs. 2-12.
* :func:`support_degree`: the support-degree ("reliability") fusion of Sun & Jing (2005),
  Yang, Feng & Fan's (2012) reference [11], *rebuilt* from the literature (see its docstring).

Each public function has a single-epoch form (1-D input, returns :class:`ReadingsFusion`);
:func:`fuse_epochs` applies any of them row by row to a 2-D array of epochs, vectorised
with numpy, which is what the Monte-Carlo experiments use. The belief-degree fusion of the
lecture notes (§2.4; Jiao, Xiong, Zhang & Xu 2008) is here too (:func:`belief_degree`).

References
----------
* Yang, G., Feng, X., & Fan, L. (2012). Multi-sensor data fusion algorithm based on optimal
  fusion set. *Journal of Software*, 23(Suppl. 1), 134-140 (in Chinese).
* Sun, Y., & Jing, B. (2005). Consistent and reliable fusion of multi-sensor based on support
  degree. *Chinese Journal of Sensors and Actuators*, 18(3), 537-539 (in Chinese).
* Yager, R. R. (2001). The power average operator. *IEEE Transactions on Systems, Man, and
  Cybernetics, Part A*, 31(6), 724-731.
* Jiao, Z., Xiong, W., Zhang, L., & Xu, B. (2008). Multi-sensor data fusion method based on
  belief degree and its applications. *Journal of Southeast University (Natural Science
  Edition)*, 38(9), 253-257 (in Chinese).
* Perron, O. (1907). Zur Theorie der Matrices. *Mathematische Annalen*, 64, 248-263.
* Frobenius, G. (1912). Über Matrizen aus nicht negativen Elementen. *Sitzungsberichte der
  Königlich Preussischen Akademie der Wissenschaften*, 456-477.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Callable, Literal, TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

from fusion._guards import own_underflow
from fusion._limits import DENSE_CUBE, dense_work
from fusion._frozen import constant, fresh, frozen_arrays
from fusion._validation import (_numeric, FloatArray, as_reading_rows, as_readings, check_magnitude, flag, keywords,
                                one_of, positive_scalar, scalar, shown, text)
from fusion.readings._row_blocks import (_BLOCK_ELEMENTS, CUBIC, PAIRS, _belief_rows, _row_blocks,  # noqa: F401
                                         _support_block)  # (the blocks of kernels)

__all__ = [
    "binary_deletion",
    "MeanDistances",
    "ReadingsFusion",
    "EpochFusion",
    "arithmetic_mean",
    "optimal_fusion_set",
    "support_degree",
    "fusion_set_weights",
    "fuse_epochs",
    "distance_matrix",
    "mean_distances",
    "optimal_set_members",
    "fusion_degree_matrix",
    "consistency_degree",
    "distribution_balance",
    "METHODS",
    "belief_matrix",
    "belief_matrices",
    "row_sum_weights",
    "perron_weights",
    "perron_gap",
    "belief_degree",
]

Threshold = Literal["mean", "sum"]
BalanceForm = Literal["left", "right", "root"]

#: Relative tolerance used when comparing a distance with the mean distance (eq. 5),
#: so that ties are not decided by floating-point rounding of the sums.
TIE_RTOL = 1e-9


@dataclass(frozen=True)
@frozen_arrays
class ReadingsFusion:
    """Result of fusing one epoch of readings.

    Attributes
    ----------
    value : float
        Fused estimate :math:`\\hat x = \\sum_i w_i s_i`, in the readings' unit.
    weights : ndarray, shape (n,)
        Non-negative weights summing to one; zero for readings outside ``members``.
    members : ndarray of bool, shape (n,)
        Readings that take part in the fusion (all ``True`` except for
        :func:`optimal_fusion_set`, where it is the optimal fusion set :math:`\\Phi`).
    method : str
        Name of the method that produced the result.
    """

    value: float
    weights: FloatArray
    members: NDArray[np.bool_]
    method: str


@dataclass(frozen=True)
@frozen_arrays
class EpochFusion:
    """Result of fusing many epochs at once (see :func:`fuse_epochs`).

    Attributes
    ----------
    values : ndarray, shape (n_epochs,)
    weights : ndarray, shape (n_epochs, n_sensors)
    members : ndarray of bool, shape (n_epochs, n_sensors)
    method : str
    """

    values: FloatArray
    weights: FloatArray
    members: NDArray[np.bool_]
    method: str


# ---------------------------------------------------------------------------
# Building blocks of Yang, Feng & Fan (2012) (eqs. 2-9), exposed for the derivation
# ---------------------------------------------------------------------------


def distance_matrix(x: ArrayLike) -> FloatArray:
    r"""Absolute distances :math:`\mathrm{dis}_{ij} = |s_i - s_j|` (Yang, Feng & Fan (2012), eq. 2).

    Parameters
    ----------
    x : array_like, shape (n,)
        Readings.

    Returns
    -------
    ndarray, shape (n, n)
        Symmetric, zero diagonal, in the readings' unit.
    """
    s = as_readings(x, pairs=2)
    return np.abs(s[:, None] - s[None, :])


@dataclass(frozen=True)
@frozen_arrays
class MeanDistances:
    """Mean distance of each reading to the others, and their mean.

    Arrays are read-only.

    Attributes
    ----------
    d : ndarray, shape (n,)
        Mean distance of each reading to the others.
    d_bar : float
        The threshold: their mean (or sum, as printed).
    """

    d: FloatArray
    d_bar: float


def mean_distances(x: ArrayLike, threshold: Threshold = "mean") -> MeanDistances:
    r"""Distance of each reading to all readings, and the threshold (Yang, Feng & Fan (2012), eqs. 3-4).

    The source names :math:`d_i` "the mean distance of :math:`s_i` to all readings" and
    :math:`\bar d` "the mean distance among all readings", but prints both as plain sums.

    Parameters
    ----------
    x : array_like, shape (n,)
    threshold : {"mean", "sum"}
        ``"mean"`` (default, the source's words): :math:`d_i = \frac1n\sum_j \mathrm{dis}_{ij}`
        and :math:`\bar d = \frac1n \sum_i d_i`. ``"sum"`` (the source's printed formulas):
        :math:`d_i = \sum_j \mathrm{dis}_{ij}` and :math:`\bar d = \sum_i d_i`.

    Returns
    -------
    MeanDistances
        ``d`` and ``d_bar``.
    """
    threshold = one_of(threshold, ("mean", "sum"), "threshold")
    dis = distance_matrix(x)
    if threshold == "mean":
        d = dis.mean(axis=1)
        return MeanDistances(d=d, d_bar=float(d.mean()))
    d = dis.sum(axis=1)
    return MeanDistances(d=d, d_bar=float(d.sum()))


def _members_rows(s: FloatArray, threshold: Threshold) -> NDArray[np.bool_]:
    """Optimal-fusion-set mask for each row of ``s`` (shape (N, n)); see eq. 5. Computed in row blocks."""
    blocks = _row_blocks(s)
    if len(blocks) == 1:
        return _members_block(s, threshold)
    out = np.empty(s.shape, dtype=bool)
    for b in blocks:
        out[b] = _members_block(s[b], threshold)
    return out


def _members_block(s: FloatArray, threshold: Threshold) -> NDArray[np.bool_]:
    """:func:`_members_rows` of one block of rows."""
    dis = np.subtract(s[:, :, None], s[:, None, :])
    np.abs(dis, out=dis)
    if threshold == "mean":
        d = dis.mean(axis=2)
        d_bar = d.mean(axis=1, keepdims=True)
    else:
        d = dis.sum(axis=2)
        d_bar = d.sum(axis=1, keepdims=True)
    members = d < d_bar * (1.0 - TIE_RTOL)
    # No reading strictly closer than average: every reading is equally central
    # (n = 1, n = 2, identical readings, symmetric configurations). Keep them all.
    empty = ~members.any(axis=1)
    members[empty] = True
    return members


def optimal_set_members(x: ArrayLike, threshold: Threshold = "mean") -> NDArray[np.bool_]:
    r"""Membership of the optimal fusion set :math:`\Phi` (Yang, Feng & Fan (2012), eq. 5).

    A reading belongs to :math:`\Phi` when its distance :math:`d_i` to the others is
    strictly smaller than the threshold :math:`\bar d` of :func:`mean_distances`.

    Degenerate case: when no reading is strictly below the threshold (one reading, two
    readings, identical readings, or any configuration where all :math:`d_i` are equal)
    the source's set would be empty; we keep every reading instead, since none is less
    central than another. Ties are judged with relative tolerance ``TIE_RTOL`` (1e-9).

    Parameters
    ----------
    x : array_like, shape (n,)
    threshold : {"mean", "sum"}
        See :func:`mean_distances`. With ``"sum"`` every reading is a member whenever
        ``n >= 2`` and the readings are not all identical, so no reading is ever rejected.

    Returns
    -------
    ndarray of bool, shape (n,)
        True for the readings of the optimal fusion set, in the order of ``x``.
    """
    threshold = one_of(threshold, ("mean", "sum"), "threshold")
    return _members_rows(as_readings(x, pairs=2)[None, :], threshold)[0]


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def fusion_degree_matrix(x: ArrayLike, scale: float = 2.0) -> FloatArray:
    r"""Fusion-degree matrix :math:`C` (Yang, Feng & Fan (2012), eqs. 6-7).

    .. math:: c_{ij} = \exp\left(-\frac{|s_i - s_j|}{\text{scale}}\right)

    The source fixes the factor 1/2, i.e. ``scale = 2`` *in the unit of the readings*
    (°C in its example): the weights therefore depend on the unit (see the chapter).

    Parameters
    ----------
    x : array_like, shape (m,)
        Readings of the optimal fusion set.
    scale : float
        Length scale, in the readings' unit. Must be positive.

    Returns
    -------
    ndarray, shape (m, m)
        Symmetric, ones on the diagonal, entries in (0, 1].
    """
    scale = positive_scalar(scale, "scale")
    return np.exp(-distance_matrix(x) / scale)


def consistency_degree(C: ArrayLike) -> FloatArray:
    r"""Consistency degree :math:`\mu_i = \frac1m \sum_{j=1}^m c_{ij}` (Yang, Feng & Fan (2012), eq. 8).

    Parameters
    ----------
    C : array_like, shape (m, m)
        Fusion-degree matrix (:func:`fusion_degree_matrix`): symmetric, in [0, 1], ones on the diagonal, to 1e-9.

    Returns
    -------
    ndarray, shape (m,)
        Entry i: the mean of row i of the fusion-degree matrix ``C``.
    """
    C = _as_fusion_degree_matrix(C)
    return C.mean(axis=1)


def _as_fusion_degree_matrix(C: ArrayLike) -> FloatArray:
    arr = _numeric(C, "C")
    if arr.ndim != 2 or arr.shape[0] != arr.shape[1] or arr.shape[0] == 0:
        raise ValueError(f"C must be a non-empty square matrix, got shape {arr.shape}")
    if not (np.all((arr >= 0.0) & (arr <= 1.0)) and np.abs(np.diagonal(arr) - 1.0).max() <= 1e-9
            and np.abs(arr - arr.T).max() <= 1e-9):  # eqs. 6-7: exp(-d_ij / scale), tiny ones valid (far readings)
        raise ValueError("C must be a fusion-degree matrix: symmetric, entries in [0, 1], ones on its diagonal")
    return arr


def distribution_balance(
    C: ArrayLike, include_self: bool = True, form: BalanceForm = "left"
) -> FloatArray:
    r"""Distribution-balance degree :math:`\tau_i` (Yang, Feng & Fan (2012), eq. 9).

    The source prints :math:`\tau_i = 1/\sqrt{\sum_j (\mu_i - c_{ij})^2}/m`, which can be
    parenthesised three ways; with :math:`S_i = \sum_j (\mu_i - c_{ij})^2`:

    * ``"left"``:  :math:`(1/\sqrt{S_i})/m`
    * ``"right"``: :math:`1/(\sqrt{S_i}/m) = m/\sqrt{S_i}`
    * ``"root"``:  :math:`1/\sqrt{S_i/m}`

    The three differ by a factor that depends on :math:`m` only, so the normalised weights
    of eq. 11 are identical (the chapter shows it numerically).

    Parameters
    ----------
    C : array_like, shape (m, m)
        Fusion-degree matrix (:func:`fusion_degree_matrix`): symmetric, in [0, 1], ones on the diagonal, to 1e-9.
    include_self : bool
        Whether the sum over :math:`j` includes :math:`j = i` (where :math:`c_{ii} = 1`).
        The source does not say; default ``True`` (the row of :math:`C` as printed).
    form : {"left", "right", "root"}

    Returns
    -------
    ndarray, shape (m,)
        Positive; ``inf`` where :math:`S_i` is zero to rounding, :math:`S_i \le m^3\epsilon^2` with
        :math:`\epsilon` the float spacing at 1 (a row whose fusion degrees are all equal up to
        rounding, e.g. a one-element set or readings equal to within a few ulps): below that floor
        :math:`S_i` is rounding noise of the :math:`c_{ij}` and :math:`\mu_i`, whose ratios would
        decide eq. 11 at random.
    """
    flag(include_self, "include_self")
    form = one_of(form, ("left", "right", "root"), "form")
    C = _as_fusion_degree_matrix(C)
    m = C.shape[0]
    mu = C.mean(axis=1)
    dev = (mu[:, None] - C) ** 2
    if not include_self:
        np.fill_diagonal(dev, 0.0)
    S = dev.sum(axis=1)
    S[S <= _s_floor(m)] = 0.0
    with np.errstate(divide="ignore"):
        if form == "left":
            return (1.0 / np.sqrt(S)) / m
        if form == "right":
            return 1.0 / (np.sqrt(S) / m)
        return 1.0 / np.sqrt(S / m)


# ---------------------------------------------------------------------------
# Weight rules, vectorised over rows (epochs)
# ---------------------------------------------------------------------------


def _mean_weights(s: FloatArray) -> tuple[FloatArray, NDArray[np.bool_]]:
    n = s.shape[1]
    return np.full(s.shape, 1.0 / n), np.ones(s.shape, dtype=bool)


def _s_floor(m: float | FloatArray) -> float | FloatArray:
    """The rounding floor of :math:`S_i` in eq. 9 for a set of ``m`` members: :math:`m^3\\epsilon^2`.

    The :math:`c_{ij}` lie in (0, 1]; :math:`\\mu_i` carries a rounding error up to about
    :math:`m\\epsilon`, so each squared deviation one of :math:`(m\\epsilon)^2` and their sum one of
    :math:`m^3\\epsilon^2`. An :math:`S_i` at or below it is zero to rounding.
    """
    return np.asarray(m, dtype=float) ** 3 * np.finfo(float).eps ** 2


def _set_weights(
    s: FloatArray, members: NDArray[np.bool_], scale: float, include_self: bool
) -> FloatArray:
    """Eqs. 6-11 applied to the readings marked in ``members`` (row-wise, shape (N, n)), in row blocks."""
    blocks = _row_blocks(s)
    if len(blocks) == 1:
        return _set_weights_block(s, members, scale, include_self)
    out = np.empty(s.shape, dtype=float)
    for b in blocks:
        out[b] = _set_weights_block(s[b], members[b], scale, include_self)
    return out


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _set_weights_block(
    s: FloatArray, members: NDArray[np.bool_], scale: float, include_self: bool
) -> FloatArray:
    """:func:`_set_weights` of one block of rows."""
    mf = members.astype(float)
    m = mf.sum(axis=1, keepdims=True)  # (N, 1)
    outside = ~(members[:, :, None] & members[:, None, :])  # pairs with a non-member: weight 0
    C = np.subtract(s[:, :, None], s[:, None, :])  # eqs. 6-7, in place: exp(-|s_i - s_j| / scale) on pairs
    np.abs(C, out=C)
    np.negative(C, out=C)
    np.divide(C, scale, out=C)
    np.exp(C, out=C)
    C[outside] = 0.0
    mu = C.sum(axis=2) / m  # eq. 8, zero-padded outside the set
    dev = np.subtract(mu[:, :, None], C, out=C)  # C is not needed any more
    np.square(dev, out=dev)
    dev[outside] = 0.0
    if not include_self:
        dev[:, np.arange(s.shape[1]), np.arange(s.shape[1])] = 0.0
    S = dev.sum(axis=2)
    S[S <= _s_floor(m)] = 0.0  # zero to rounding (see distribution_balance)
    # eq. 9 up to a factor depending on m only (irrelevant after eq. 11): tau = 1/sqrt(S).
    # Rows where a member has S = 0 (tau infinite): those members take all the weight,
    # shared in proportion to mu (the limit of eq. 11 as their S -> 0).
    infinite = members & (S == 0.0)
    has_inf = infinite.any(axis=1, keepdims=True)
    with np.errstate(divide="ignore", invalid="ignore"):
        omega_finite = np.where(members, mu / np.sqrt(S), 0.0)
    omega = np.where(has_inf, np.where(infinite, mu, 0.0), omega_finite)  # eq. 10
    return omega / omega.sum(axis=1, keepdims=True)  # eq. 11


def _ofs_weights(
    s: FloatArray,
    scale: float = 2.0,
    threshold: Threshold = "mean",
    include_self: bool = True,
) -> tuple[FloatArray, NDArray[np.bool_]]:
    """Selection (eq. 5) then weights (eqs. 6-11) for each row of ``s`` (N, n)."""
    members = _members_rows(s, threshold)
    return _set_weights(s, members, scale, include_self), members


def _fusion_set_weights(
    s: FloatArray, scale: float = 2.0, include_self: bool = True
) -> tuple[FloatArray, NDArray[np.bool_]]:
    """Eqs. 6-11 on all readings of each row (no selection)."""
    members = np.ones(s.shape, dtype=bool)
    return _set_weights(s, members, scale, include_self), members


def _support_weights(s: FloatArray, alpha: float = 0.25) -> tuple[FloatArray, NDArray[np.bool_]]:
    """Row-sum weights of the support matrix exp(-alpha (s_i - s_j)^2), per row (in row blocks)."""
    blocks = _row_blocks(s)
    if len(blocks) == 1:
        return _support_block(s, alpha), np.ones(s.shape, dtype=bool)
    weights = np.empty(s.shape, dtype=float)
    for b in blocks:
        weights[b] = _support_block(s[b], alpha)
    return weights, np.ones(s.shape, dtype=bool)


_WeightRule = Callable[..., tuple[FloatArray, NDArray[np.bool_]]]

#: Registered readings-level methods: name -> (weight rule, validated option names).
METHODS: dict[str, tuple[_WeightRule, tuple[str, ...]]] = {
    "mean": (_mean_weights, ()),
    "optimal_fusion_set": (_ofs_weights, ("scale", "threshold", "include_self")),
    "fusion_set_weights": (_fusion_set_weights, ("scale", "include_self")),
    "support_degree": (_support_weights, ("alpha",)),
}


#: A method's validated keyword options (``scale``, ``alpha``: float; ``threshold``: str; ``include_self``: bool).
_Options: TypeAlias = "dict[str, float | str | bool | np.bool_]"


def _check_options(method: str, options: Mapping[str, object]) -> _Options:
    """``options`` checked against ``method``'s option names and each option's rule (ValueError naming it)."""
    _, allowed = METHODS[method]
    keywords(options, {k for _, names in METHODS.values() for k in names}, "fuse_epochs")  # a misspelt keyword
    unknown = set(options) - set(allowed)
    if unknown:
        raise ValueError(f"unknown option(s) {shown(sorted(unknown))} for method {shown(method)}")
    checked: dict[str, object] = dict(options)
    if "scale" in checked:
        checked["scale"] = positive_scalar(checked["scale"], "scale")  # type: ignore[arg-type]
    if "alpha" in checked:
        checked["alpha"] = positive_scalar(checked["alpha"], "alpha")  # type: ignore[arg-type]
    if "threshold" in checked:
        one_of(checked["threshold"], ("mean", "sum"), "threshold")  # type: ignore[arg-type]
    if "include_self" in checked:
        flag(checked["include_self"], "include_self")
    return checked  # type: ignore[return-value]


def fuse_epochs(x: ArrayLike, method: str = "optimal_fusion_set", **options: object) -> EpochFusion:
    """Fuse every row (epoch) of ``x`` with one readings-level method, vectorised.

    Parameters
    ----------
    x : array_like, shape (n_epochs, n_sensors) or (n_sensors,)
        Readings; each row is one epoch.
    method : {"mean", "optimal_fusion_set", "fusion_set_weights", "support_degree", "belief_degree"}
        A key of ``METHODS``.
    **options
        Keyword options of the method (see :func:`optimal_fusion_set`, :func:`support_degree` and
        :func:`belief_degree`).

    Returns
    -------
    EpochFusion
        ``values`` has shape (n_epochs,); ``weights`` and ``members`` (n_epochs, n_sensors).

    Raises
    ------
    TypeError
        A keyword that is an option of no method (a misspelling).
    ValueError
        Unknown method, an option of another method, non-finite input, wrong number of dimensions.
    """
    if not isinstance(method, str):
        raise TypeError(f"method must be a string, one of {sorted(METHODS)}, got {type(method).__name__}")
    method = text(method, "method")  # rule 19: matched by its text
    if method not in METHODS:
        raise ValueError(f"unknown method {shown(method)}; choose from {sorted(METHODS)}")
    s = as_reading_rows(x, pairs=PAIRS[method], cubic=method in CUBIC)
    rule, _ = METHODS[method]
    weights, members = rule(s, **_check_options(method, options))
    values = np.einsum("ij,ij->i", weights, s)
    return fresh(EpochFusion, values=values, weights=weights, members=members, method=method)  # computed here


def _single(x: ArrayLike, method: str, **options: object) -> ReadingsFusion:
    s = as_readings(x)
    res = fuse_epochs(s[None, :], method, **options)
    return fresh(ReadingsFusion, value=float(res.values[0]), weights=res.weights[0], members=res.members[0],
                 method=method)  # views of res, computed here


# ---------------------------------------------------------------------------
# Public single-epoch entry points
# ---------------------------------------------------------------------------


def arithmetic_mean(x: ArrayLike) -> ReadingsFusion:
    r"""Arithmetic mean of the readings, :math:`w_i = 1/n` (Yang, Feng & Fan (2012), "均值法").

    Parameters
    ----------
    x : array_like, shape (n,)

    Returns
    -------
    ReadingsFusion
        The mean of the readings as ``value``, every weight 1/n, every reading a member, method ``"mean"``.
    """
    return _single(x, "mean")


def optimal_fusion_set(
    x: ArrayLike,
    *,
    scale: float = 2.0,
    threshold: Threshold = "mean",
    include_self: bool = True,
) -> ReadingsFusion:
    r"""Optimal-fusion-set fusion of Yang, Feng & Fan (2012), eqs. 2-12.

    1. Keep the readings whose mean distance to all readings is below the mean of those
       distances (eqs. 2-5): the optimal fusion set :math:`\Phi`, of size :math:`m`.
    2. Fusion degrees :math:`c_{ij} = \exp(-|s_i - s_j|/\text{scale})` inside :math:`\Phi`
       (eqs. 6-7).
    3. Consistency :math:`\mu_i = \frac1m\sum_j c_{ij}` (eq. 8) and balance
       :math:`\tau_i \propto 1/\sqrt{\sum_j (\mu_i - c_{ij})^2}` (eq. 9).
    4. Weights :math:`w_i = \mu_i\tau_i / \sum_k \mu_k\tau_k` (eqs. 10-11), fused value
       :math:`\hat x = \sum_i w_i s_i` (eq. 12).

    Parameters
    ----------
    x : array_like, shape (n,)
        Simultaneous readings of one quantity (any unit; see ``scale``).
    scale : float, default 2.0
        Length scale of eq. 6 in the readings' unit; the source's factor 1/2 is
        ``scale = 2`` (°C in its example).
    threshold : {"mean", "sum"}, default "mean"
        Reading of eqs. 3-4: ``"mean"`` follows the source's words ("average distance");
        ``"sum"`` follows its printed sums, under which no reading is ever rejected.
    include_self : bool, default True
        Whether eq. 9's sum includes :math:`j = i`.

    Returns
    -------
    ReadingsFusion
        ``value`` (°C if the readings are), ``weights`` (zero outside the set, sum one),
        ``members`` (the optimal fusion set).

    Notes
    -----
    Degenerate cases, where eq. 9 divides by zero, are resolved by their limits:

    * one reading, or one member: that reading, weight 1;
    * identical readings: equal weights (fused value = the common reading);
    * no reading strictly below the threshold (e.g. two readings): all readings are kept;
    * members with :math:`S_i = 0` (infinite balance) share all the weight in proportion
      to :math:`\mu_i`.

    With exactly two members the weights are always 1/2 each, whatever ``scale``.

    Raises
    ------
    ValueError
        If ``x`` is not 1-D, is empty or not finite, or an option is invalid.

    Examples
    --------
    The outlying reading is left out of the set; the two readings on either side of 20.1 °C get
    equal weights:

    >>> from fusion.readings.fusion_set import optimal_fusion_set
    >>> r = optimal_fusion_set([20.1, 20.3, 19.9, 25.0])
    >>> r.members
    array([ True,  True,  True, False])
    >>> r.weights.round(2)
    array([0.46, 0.27, 0.27, 0.  ])
    >>> round(r.value, 3)
    20.1
    """
    return _single(x, "optimal_fusion_set", scale=scale, threshold=threshold, include_self=include_self)


def fusion_set_weights(
    x: ArrayLike, *, scale: float = 2.0, include_self: bool = True
) -> ReadingsFusion:
    r"""Eqs. 6-12 of Yang, Feng & Fan (2012) applied to *all* given readings, without the selection.

    This is :func:`optimal_fusion_set` with the optimal fusion set forced to be the
    whole input; the chapter uses it to ask which sets could have produced a published
    value. Degenerate cases are resolved as in :func:`optimal_fusion_set`.

    Parameters
    ----------
    x : array_like, shape (m,)
        Readings treated as the fusion set :math:`\Phi`.
    scale, include_self
        As in :func:`optimal_fusion_set`.

    Returns
    -------
    ReadingsFusion
        The fused ``value`` and the ``weights`` of eqs. 6-12 over all readings, every reading a member.
    """
    return _single(x, "fusion_set_weights", scale=scale, include_self=include_self)


def support_degree(x: ArrayLike, *, alpha: float = 0.25) -> ReadingsFusion:
    r"""Support-degree ("reliability") fusion, Yang, Feng & Fan's (2012) reference [11], **rebuilt**.

    Sun & Jing (2005) is not available to us; this is the standard support-degree scheme
    of that literature, i.e. Yager's power average (Yager 2001):

    .. math::

        r_{ij} = \exp\bigl(-\alpha (s_i - s_j)^2\bigr), \qquad
        w_i = \frac{\sum_j r_{ij}}{\sum_k \sum_j r_{kj}}, \qquad
        \hat x = \sum_i w_i s_i .

    A reading supported by many others gets a larger weight; no reading is discarded.

    Parameters
    ----------
    x : array_like, shape (n,)
    alpha : float, default 0.25
        Support sharpness in 1/unit² (0.25 /°C²: support :math:`e^{-1}` at 2 °C).
        Both limits :math:`\alpha \to 0` and :math:`\alpha \to \infty` give the mean.

    Returns
    -------
    ReadingsFusion
        ``members`` is all ``True``.

    Raises
    ------
    ValueError
        If ``x`` is not 1-D, is empty or not finite, or ``alpha`` is not positive.
    """
    return _single(x, "support_degree", alpha=alpha)


# ---------------------------------------------------------------------------
# Lecture notes, §2.4: belief-degree fusion (Jiao, Xiong, Zhang & Xu 2008)
# ---------------------------------------------------------------------------

#: Relative tolerance deciding that two eigenvalues of a belief matrix are equal
#: (a repeated Perron root, possible only for a reducible, e.g. binary, matrix). It also
#: covers *nearly* repeated roots (readings far apart relative to the scale make B close to
#: the identity): an eigenvector is computed to about eps / gap, so with a gap below
#: 1e-6 * lambda the solver's vector would be decided by round-off (measured: weights then
#: changed by up to 1e-6 under a permutation of the readings). Within the tolerance the
#: eigenspace is treated as repeated, which bounds that error near eps / 1e-6 ~ 1e-10.
PERRON_RTOL = 1e-6


def belief_matrix(x: ArrayLike, scale: float = 1.0, binary_eps: float | None = None,
                  limit: float | None = None) -> FloatArray:
    r"""Belief (trust) matrix :math:`B = [b_{ij}]` of the lecture notes, §2.4.

    Fuzzy exponential belief (the function is **reconstructed**: the lecture's formula is
    illegible; this is the function Yang, Feng & Fan (2012) use in their own eq. 6, without a
    citation, with a scale):

    .. math:: b_{ij} = \exp\left(-\frac{|x_i - x_j|}{2\,\text{scale}}\right),

    so ``scale = 1`` gives Yang et al.'s :math:`\exp(-\frac12|x_i-x_j|)` in the readings' unit.
    The lecture "generally gives a fusion upper limit" :math:`m_{ij}` (一般给出融合上限) and calls B
    non-negative: with ``limit`` the belief is truncated, :math:`b_{ij} = 0` for
    :math:`|x_i - x_j| > m` (the same :math:`m` for every pair). Binary belief (the version the
    lecture rejects): :math:`b_{ij} = 1` if :math:`|x_i - x_j| \le \varepsilon`, else 0 (the
    lecture's :math:`m_{ij}` in that role).

    Parameters
    ----------
    x : array_like, shape (n,)
        Readings.
    scale : float
        Length scale in the readings' unit (fuzzy belief only).
    binary_eps : float, optional
        If given, the binary belief with threshold :math:`\varepsilon` (readings' unit).
    limit : float, optional
        Fusion upper limit :math:`m \ge 0` of the fuzzy belief (readings' unit); ``None``: no limit.

    Returns
    -------
    ndarray, shape (n, n)
        Symmetric, unit diagonal, entries in [0, 1].
    """
    s = as_readings(x, pairs=3)
    return _belief_rows(s[None, :], positive_scalar(scale, "scale"), _eps(binary_eps), _eps(limit, "limit"))[0]


def _eps(binary_eps: float | None, name: str = "binary_eps") -> float | None:
    if binary_eps is None:
        return None
    return scalar(binary_eps, name, lo=0.0)


def row_sum_weights(B: ArrayLike) -> FloatArray:
    r"""Row-sum ("support degree") weights of a belief matrix: :math:`\sum_j b_{ij}/\sum_{ij} b_{ij}`.

    The alternative to the Perron eigenvector of sec. 2.4 (the eigenvector is the limit of
    repeatedly multiplying the row sums by :math:`B`).

    Parameters
    ----------
    B : array_like, shape (n, n) or (N, n, n)
        Non-negative matrix (or stack), e.g. from :func:`belief_matrix`.

    Returns
    -------
    ndarray, shape (n,) or (N, n)
        Non-negative weights summing to one.
    """
    arr = _numeric(B, "B")
    if arr.ndim not in (2, 3) or arr.shape[-1] != arr.shape[-2] or arr.shape[-1] == 0:
        raise ValueError(f"B must be square (n, n) or a stack (N, n, n), got shape {arr.shape}")
    check_magnitude(arr, "B", subnormal=False)  # exp(-d²) entries may underflow: valid
    if np.any(arr < 0):
        raise ValueError("B must be non-negative")
    tot = arr.sum(axis=(-2, -1))[..., None]
    if np.any(tot == 0):
        raise ValueError("B has a zero matrix: row-sum weights are undefined")
    return arr.sum(axis=-1) / tot


def belief_matrices(x: ArrayLike, scale: float = 1.0) -> FloatArray:
    r"""Fuzzy belief matrices of many snapshots at once (see :func:`belief_matrix`).

    Parameters
    ----------
    x : array_like, shape (N, n)
        N snapshots of n readings.
    scale : float
        Length scale in the readings' unit.

    Returns
    -------
    ndarray, shape (N, n, n)
        Entry k: the fuzzy belief matrix of the snapshot ``x[k]``.
    """
    arr = _numeric(x, "x")
    if arr.ndim != 2:
        raise ValueError(f"x must have shape (N, n), got {arr.shape}")
    arr = as_reading_rows(arr, pairs=2 * arr.shape[0])  # the stack is returned whole
    return _belief_rows(arr, positive_scalar(scale, "scale"), None)


#: Units of one ``n**3`` of :func:`perron_weights` (eigh) and :func:`perron_gap` (eigvalsh) a matrix: eigh 0.13 ns
#: measured at n = 4,800 (14 CPU-s, fuzz 38a C9); eigvalsh 0.13 ns at n = 300, 0.085 at 1,000, 0.055 at 2,000
#: (time.process_time, OPENBLAS_NUM_THREADS=1, shared machine) and 0.11 at 5,792 (21.4 CPU-s unchecked, fuzz 57b D2).
_PERRON_CUBE = 1.3 * DENSE_CUBE


def _belief_stack(B: ArrayLike) -> tuple[FloatArray, bool]:
    """``B`` as a stack (N, n, n) of finite, non-negative, symmetric matrices, and whether it was one matrix. Raises
    ``ValueError`` naming ``B`` for any other shape, NaN/inf, a negative entry or asymmetry, or for eigen-decompositions
    beyond the work budget (``_PERRON_CUBE`` units a ``n**3``, rule 17), checked before its O(N n**2) checks (the
    symmetry check of a 4,300 x 4,300 B took 0.66 CPU-s)."""
    arr = _numeric(B, "B")
    single = arr.ndim == 2
    if single:
        arr = arr[None]
    if arr.ndim != 3 or arr.shape[1] != arr.shape[2] or arr.shape[1] == 0:
        raise ValueError(f"B must be square (n, n) or a stack (N, n, n), got shape {np.shape(B)}")
    dense_work(arr.shape[0], arr.shape[-1], "B", _PERRON_CUBE)
    check_magnitude(arr, "B", subnormal=False)  # exp(-d²) entries may underflow: valid
    if np.any(arr < 0):
        raise ValueError("B must be non-negative")
    if not np.allclose(arr, np.swapaxes(arr, 1, 2)):
        raise ValueError("B must be symmetric")
    return arr, single


def perron_weights(B: ArrayLike) -> FloatArray:
    r"""Normalised principal eigenvector of a symmetric non-negative matrix (sec. 2.4).

    For :math:`B` with positive entries (the fuzzy belief) the Perron-Frobenius theorem gives a
    simple largest eigenvalue :math:`\lambda = \rho(B)` whose eigenvector :math:`A` can be chosen
    positive; the weights are :math:`\omega_i = a_i / \sum_j a_j`.

    If :math:`\lambda` is repeated (a reducible :math:`B`, e.g. a binary belief matrix whose
    readings fall into separate groups), the eigenvector is not unique. We then take the limit of
    power iteration started from the uniform vector: the projection of :math:`\mathbf 1` onto the
    eigenspace of :math:`\lambda`. It shares the weight among the dominant groups and gives zero
    weight to the others. The sign returned by the eigen-solver is fixed so the weights are
    non-negative.

    Parameters
    ----------
    B : array_like, shape (n, n) or (N, n, n)
        Symmetric, non-negative matrix (or a stack of them).

    Returns
    -------
    ndarray, shape (n,) or (N, n)
        Non-negative weights summing to one.
    """
    arr, single = _belief_stack(B)  # with its dense work (rule 17, fuzz 38a C9)
    w = _perron_rows(arr)
    return w[0] if single else w



def perron_gap(B: ArrayLike) -> FloatArray | float:
    r"""Relative gap between the two largest eigenvalues of a symmetric non-negative matrix (sec. 2.4).

    :math:`(\lambda_1 - \lambda_2)/\lambda_1` with :math:`\lambda_1 = \rho(B)`. The
    Perron-Frobenius theorem makes it positive for a matrix with positive entries (the fuzzy
    belief): the Perron root is simple and its eigenvector, positive, is unique up to scale. A
    reducible matrix (a binary belief matrix whose readings fall into separate groups) can have a
    repeated Perron root, gap 0, and then its eigenvector is not unique (:func:`perron_weights`
    takes the projection of :math:`\mathbf 1`). A gap below ``PERRON_RTOL`` is treated as a
    repeated root by :func:`perron_weights`.

    Parameters
    ----------
    B : array_like, shape (n, n) or (N, n, n)
        Symmetric, non-negative matrix (or a stack), e.g. from :func:`belief_matrix`, with
        :math:`\rho(B) > 0`.

    Returns
    -------
    float or ndarray, shape (N,)
        The relative gap in [0, 1] (1.0 for a 1 × 1 matrix, whose only eigenvalue is simple).

    Raises
    ------
    ValueError
        ``B`` not square, not finite, negative, not symmetric, or with :math:`\rho(B) = 0`, or beyond the work
        budget (``N x n**3``: one matrix of ``n`` above about 4,250).

    References
    ----------
    * Perron, O. (1907). Zur Theorie der Matrices. *Mathematische Annalen*, 64, 248-263.
    * Frobenius, G. (1912). Über Matrizen aus nicht negativen Elementen. *Sitzungsberichte der
      Königlich Preussischen Akademie der Wissenschaften*, 456-477.
    """
    arr, single = _belief_stack(B)  # with its dense work (rule 17, fuzz 57b D2: n = 5,792 ran 21.4 CPU-s unchecked)
    lam = np.linalg.eigvalsh(arr)
    top = lam[:, -1]
    if np.any(top <= 0):
        raise ValueError("B must have a positive spectral radius (B = 0 has no Perron vector)")
    gap = np.ones(arr.shape[0]) if arr.shape[1] == 1 else np.clip((top - lam[:, -2]) / top, 0.0, 1.0)
    return float(gap[0]) if single else gap


def _perron_rows(B: FloatArray) -> FloatArray:
    lam, V = np.linalg.eigh(B)  # ascending eigenvalues, (N, n) and (N, n, n)
    top = lam >= lam[:, -1:] - PERRON_RTOL * np.abs(lam[:, -1:])
    proj = np.einsum("nij,nj->ni", V, np.where(top, V.sum(axis=1), 0.0))  # P_top 1
    proj = np.abs(proj)  # removes round-off signs; P_top 1 >= 0 for non-negative B
    # Two power-iteration steps (B a / lambda leaves the eigenvector unchanged) restore the
    # relative accuracy of tiny entries, which eigh only has to absolute round-off: for a
    # positive B they come out strictly positive.
    lam_top = np.where(lam[:, -1:] > 0, lam[:, -1:], 1.0)
    for _ in range(2):
        proj = np.einsum("nij,nj->ni", B, proj) / lam_top
    total = proj.sum(axis=1, keepdims=True)
    n = B.shape[1]
    return np.where(total > 0, proj / np.where(total > 0, total, 1.0), 1.0 / n)


def _belief_weights(
    s: FloatArray, scale: float = 1.0, binary_eps: float | None = None, limit: float | None = None
) -> tuple[FloatArray, NDArray[np.bool_]]:
    """Perron weights of the belief matrix of each row of ``s`` (N, n), in row blocks."""
    eps, lim = _eps(binary_eps), _eps(limit, "limit")
    w = np.concatenate([_perron_rows(_belief_rows(s[b], scale, eps, lim)) for b in _row_blocks(s)])
    return w, np.ones(s.shape, dtype=bool)


METHODS = constant({**METHODS, "belief_degree": (_belief_weights, ("scale", "binary_eps", "limit"))})  # built once


def belief_degree(x: ArrayLike, *, scale: float = 1.0, binary_eps: float | None = None,
                  limit: float | None = None) -> ReadingsFusion:
    r"""Belief-degree fusion of Jiao, Xiong, Zhang & Xu (2008), lecture notes, §2.4.

    1. Belief matrix :math:`b_{ij} = \exp(-|x_i-x_j|/(2\,\text{scale}))` (:func:`belief_matrix`).
    2. Perron root and vector :math:`BA = \lambda A`, :math:`\lambda = \rho(B)`, :math:`a_i > 0`.
    3. Comprehensive belief :math:`w_i = \sum_j b_{ij}a_j = \lambda a_i`, normalised:
       :math:`\omega_i = a_i/\sum_j a_j` (:func:`perron_weights`).
    4. :math:`\hat x = \sum_i \omega_i x_i`.

    Parameters
    ----------
    x : array_like, shape (n,)
        Simultaneous readings of one quantity.
    scale : float, default 1.0
        Belief length scale in the readings' unit (1 reproduces the paper's factor 1/2 in that
        unit, so the weights depend on the unit, as in Yang, Feng & Fan's (2012) eq. 6).
    binary_eps : float, optional
        Use the binary belief with this threshold instead (see :func:`perron_weights` for
        the non-unique eigenvector it can produce).
    limit : float, optional
        Fusion upper limit :math:`m` of the fuzzy belief: :math:`b_{ij} = 0` beyond it
        (:func:`belief_matrix`); B can then be reducible, like the binary one.

    Returns
    -------
    ReadingsFusion
        Weights positive (fuzzy belief without a limit), summing to one; ``members`` all ``True``.
        Identical readings give equal weights; one reading gets weight 1.

    Raises
    ------
    ValueError
        If ``x`` is not 1-D, empty or not finite, or an option is invalid.
    """
    return _single(x, "belief_degree", scale=scale, binary_eps=binary_eps, limit=limit)


def binary_deletion(x: ArrayLike, eps: float, min_support: float = 0.5) -> ReadingsFusion:
    r"""The lecture's binary-belief rule as written (§2.4): delete the readings few others trust, average the rest.

    With the binary belief :math:`b_{ij} = 1` if :math:`|x_i - x_j| \le \varepsilon`, else 0, a reading
    "not trusted by the other sensors, or trusted only by a few" is deleted. "A few" is not defined; here
    a reading is kept when at least a share ``min_support`` of the other readings trust it, and the kept
    readings are averaged with equal weights. When no reading is kept, all are kept (the rule would
    otherwise leave nothing to fuse).

    Parameters
    ----------
    x : array_like, shape (n,)
        Simultaneous readings of one quantity (n >= 2).
    eps : float
        Threshold :math:`\varepsilon` of the binary belief, in the readings' unit (> 0).
    min_support : float, default 0.5
        Share of the other readings that must trust a reading for it to be kept, in (0, 1].

    Returns
    -------
    ReadingsFusion
        ``members``: the kept readings; weights :math:`1/|\text{kept}|` on them.

    Raises
    ------
    ValueError
        If ``x`` is not 1-D with at least two finite readings, ``eps`` is not positive and finite, or
        ``min_support`` lies outside (0, 1].

    References
    ----------
    * Jiao, Z., Xiong, W., Zhang, L., & Xu, B. (2008). Multi-sensor data fusion method based on belief
      degree and its applications (in Chinese). *Journal of Southeast University (Natural Science
      Edition)*, 38(9), 253-257 (the lecture's §2.4 source, which contrasts its fuzzy belief with this
      binary rule).
    """
    s = as_readings(x, pairs=2)
    if s.size < 2:
        raise ValueError(f"x must hold at least two readings, got {s.size}")
    e = positive_scalar(eps, "eps")
    q = scalar(min_support, "min_support")
    if not 0.0 < q <= 1.0:
        raise ValueError(f"min_support must lie in (0, 1], got {shown(min_support)}")
    trust = np.abs(s[:, None] - s[None, :]) <= e
    support = (trust.sum(axis=1) - 1) / (s.size - 1)
    keep = support >= q - 1e-12
    if not keep.any():
        keep = np.ones(s.size, dtype=bool)
    w = keep / keep.sum()
    return fresh(ReadingsFusion, value=float(w @ s), weights=w, members=keep, method="binary_deletion")
