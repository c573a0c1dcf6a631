"""Chapter 01 (the optimal fusion set): the choices the source leaves open.

The kernel family, the support sharpness α, the units and eq. (9).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from numpy.typing import ArrayLike

from fusion._guards import own_underflow
from fusion._frozen import constant
from fusion import readings as rd
from fusion._counts import count, distinct_printed_as_read, sequence
from fusion._limits import LOOP_STEP, loop_work, work
from fusion._validation import FloatArray, as_array, general, instance_of, one_of, scalar
from fusion._validation import read_mapping, window as check_window
from fusion.readings.robust import robust_fuse
from fusion._docstrings import ParameterDocs
from fusion._shown import shown

__all__ = [
    "unit_dependence",
    "eq9_readings",
    "FAMILIES",
    "family_values",
    "ALPHAS",
    "alpha_key",
    "alpha_methods",
    "family_mae",
    "weight_ablation",
]

#: The parameters of this module's Monte-Carlo summaries, documented once.
_PARAMS = ParameterDocs({
    "window": "(int, int), optional\n    1-based first and last sample averaged (default all samples).",
    "truth": "float\n    True value, °C.",
})


# --------------------------------------------------------------------------- critiques
def unit_dependence(z: ArrayLike) -> dict[str, float | bool]:
    """How the optimal fusion set changes when the same readings are given in °F or K.

    Parameters
    ----------
    z : array_like, shape (n_epochs, n_sensors)
        Readings in °C.

    Returns
    -------
    dict
        ``f_maxdiff``, ``f_meandiff``: largest and mean absolute change (°C) of the fused value
        when fused in °F and converted back; ``k_maxdiff``: the same in kelvin (°C);
        ``members_same``: whether the optimal fusion set is the same in °C and °F.
    """
    z = as_array(z, "z", ndim=2)
    fc = rd.fuse_epochs(z, "optimal_fusion_set")
    ff = rd.fuse_epochs(z * 9 / 5 + 32, "optimal_fusion_set")
    v_f = (ff.values - 32) * 5 / 9
    v_k = rd.fuse_epochs(z + 273.15, "optimal_fusion_set").values - 273.15
    return {"f_maxdiff": float(np.max(np.abs(v_f - fc.values))),
            "f_meandiff": float(np.mean(np.abs(v_f - fc.values))),
            "k_maxdiff": float(np.max(np.abs(v_k - fc.values))),
            "members_same": bool(np.array_equal(fc.members, ff.members))}


def _eq11(mu: FloatArray, tau: FloatArray) -> FloatArray:
    """Eqs. 10-11, the weights ``mu * tau`` normalised; members with an infinite ``tau`` share all the weight in
    proportion to ``mu`` (the package's limit, as :func:`fusion.readings.fusion_set.fuse_epochs` resolves it)."""
    infinite = np.isinf(tau)
    om = np.where(infinite, mu, 0.0) if infinite.any() else mu * tau
    return om / om.sum()


# Book audit 76 (eq9_readings with weight_epochs=None and family_mae's loop over families had no budget: a
# (10**7, 3) z, accepted, would run about 5,000 CPU-s; 10**6 families on a (1, 1, 3) z about 300 CPU-s). Measured
# with time.process_time, OPENBLAS_NUM_THREADS=1, minimum of 2, shared 2-core machine: an epoch of eq9_readings'
# Python loop 0.5 ms (z (5000, 5): 2.5 CPU-s) plus 43 ns a pair of its readings (z (200, 300): 0.89 CPU-s), counted
# 100 * LOOP_STEP a step and 10 units a pair, and 20 units a pair of every epoch for its two fuse_epochs calls;
# family_values 50 ns a pair of readings of an epoch (z (2000, 100): 0.55 to 0.99 CPU-s), 10 units a pair, and
# family_mae 0.3 ms a family besides (z (1, 1, 3), 10**4 families: 3.2 CPU-s), 60 * LOOP_STEP a family.
_EQ9_STEP = 100 * LOOP_STEP
_PAIR_UNITS = 10
_FAMILY_STEP = 60 * LOOP_STEP


def eq9_readings(z: ArrayLike, weight_epochs: int | None = 200) -> dict[str, float | int]:
    """Effect of the open choices of eq. 9 on the weights and fused values.

    Parameters
    ----------
    z : array_like, shape (n_epochs, n_sensors)
        Readings, °C; epochs whose optimal fusion set has fewer than 3 members are skipped for
        the weight comparisons (their weights are 1/2 or 1 under every reading).
    weight_epochs : int, optional
        Only the first ``weight_epochs`` epochs (at least one) enter the weight comparisons (a Python loop);
        ``None`` for all. The fused-value change uses every epoch.

    Returns
    -------
    dict
        ``n_sets``: number of sets compared; ``form_maxdiff``: largest weight difference
        between the three parenthesisations of eq. 9; ``self_maxdiff``: largest weight
        difference between including and excluding :math:`j = i`; ``self_valdiff``: largest
        change of the fused value (°C) over all epochs from that choice. A set whose balance
        degrees are infinite (readings equal to rounding: :func:`fusion.readings.fusion_set.distribution_balance`)
        is weighted by the package's limit (those members share the weight in proportion to their μ of eq. 8), so
        constant readings give equal weights under every reading and differences of 0. When no set has 3 members
        (``n_sets`` = 0) the two weight differences are 0: nothing was compared.

    Raises
    ------
    ValueError
        ``z`` not a finite 2-D array, or ``weight_epochs`` below 1; the epochs compared beyond the work budget
        (``fusion._limits.MAX_WORK``: 100,000 units an epoch compared plus 10 a pair of its readings, and 20 a pair
        of every epoch), naming ``z and weight_epochs``.
    TypeError
        ``weight_epochs`` not an integer.
    """
    z = as_array(z, "z", ndim=2)
    if weight_epochs is not None:
        weight_epochs = count(weight_epochs, "weight_epochs", minimum=1)
    n_epochs, n = z.shape
    steps = n_epochs if weight_epochs is None else min(weight_epochs, n_epochs)
    work((loop_work((steps,), _PAIR_UNITS * n * n, "z and weight_epochs", step=_EQ9_STEP)
          + 2 * _PAIR_UNITS * n_epochs * n * n,), "z and weight_epochs")
    diffs, self_diffs = [], []
    for row in z[:weight_epochs]:
        sel = rd.optimal_set_members(row)
        if sel.sum() < 3:
            continue
        C = rd.fusion_degree_matrix(row[sel])
        mu = rd.consistency_degree(C)
        w = {form: _eq11(mu, rd.distribution_balance(C, form=form)) for form in ("left", "right", "root")}
        diffs.append(max(np.max(np.abs(w["left"] - w["right"])), np.max(np.abs(w["left"] - w["root"]))))
        self_diffs.append(np.max(np.abs(w["left"] - _eq11(mu, rd.distribution_balance(C, include_self=False)))))
    v_self = rd.fuse_epochs(z, "optimal_fusion_set").values
    v_noself = rd.fuse_epochs(z, "optimal_fusion_set", include_self=False).values
    return {"n_sets": len(diffs), "form_maxdiff": float(max(diffs, default=0.0)),
            "self_maxdiff": float(max(self_diffs, default=0.0)),
            "self_valdiff": float(np.max(np.abs(v_self - v_noself)))}


#: Fusion-degree (membership) functions of the distance ``d = abs(s_i - s_j)`` tried in place of
#: eq. 6, each with the length scale ``h`` (°C): eq. 6 itself, a Gaussian and a Cauchy kernel.
FAMILIES: dict[str, str] = constant({
    "eq. 6, exp(-|d|/h)": "laplace",
    "Gaussian, exp(-d²/(2h²))": "gauss",
    "Cauchy, 1/(1 + (d/h)²)": "cauchy",
})


#: The family names of :data:`FAMILIES` (the values; its keys are labels).
_FAMILY_NAMES: tuple[str, ...] = tuple(sorted(set(FAMILIES.values())))


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _kernel(d: FloatArray, family: str, scale: float) -> FloatArray:
    if family == "laplace":
        return np.exp(-d / scale)
    if family == "gauss":
        return np.exp(-0.5 * (d / scale) ** 2)
    if family == "cauchy":
        return 1.0 / (1.0 + (d / scale) ** 2)
    raise ValueError(f"family must be one of {sorted(set(FAMILIES.values()))}, got {shown(family)}")


def family_values(z: ArrayLike, family: str = "laplace", scale: float = 2.0) -> FloatArray:
    r"""Optimal-fusion-set values with another fusion-degree function in place of eq. 6.

    The selection (eqs. 3-5) and eqs. 7-12 are those of
    :func:`fusion.readings.fusion_set.fuse_epochs`; only :math:`c_{ij}` changes. Degenerate
    rows of eq. 9 (a member with :math:`S_i = 0`) are resolved as the package does: those
    members share the weight in proportion to :math:`\mu_i`.

    Parameters
    ----------
    z : array_like, shape (n_epochs, n_sensors)
        Readings, °C; shape (n_sensors,) is one epoch.
    family : {"laplace", "gauss", "cauchy"}
        :math:`\exp(-|d|/h)` (eq. 6), :math:`\exp(-d^2/2h^2)` or :math:`1/(1 + (d/h)^2)`.
    scale : float
        Length scale :math:`h`, °C (eq. 6's factor 1/2 is 2 °C).

    Returns
    -------
    ndarray, shape (n_epochs,)
        Fused values, °C.

    Raises
    ------
    ValueError
        ``family`` not one of those of :data:`FAMILIES`, ``z`` not finite, ``scale`` not positive.

    References
    ----------
    Yang G. N., Feng X. F., Fan L. J. (2012), eqs. 3-12.
    """
    family = one_of(family, _FAMILY_NAMES, "family")
    s = np.atleast_2d(as_array(z, "z", ndim=(1, 2)))
    scale = scalar(scale, "scale", lo=0.0, lo_open=True)
    members = rd.fuse_epochs(s, "optimal_fusion_set").members
    mf = members.astype(float)
    m = mf.sum(axis=1, keepdims=True)
    pair = mf[:, :, None] * mf[:, None, :]
    C = _kernel(np.abs(s[:, :, None] - s[:, None, :]), family, float(scale)) * pair
    mu = C.sum(axis=2) / m
    S = ((mu[:, :, None] - C) ** 2 * pair).sum(axis=2)
    infinite = members & (S == 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        om = np.where(members, mu / np.sqrt(S), 0.0)
    om = np.where(infinite.any(axis=1, keepdims=True), np.where(infinite, mu, 0.0), om)
    return np.einsum("ij,ij->i", om / om.sum(axis=1, keepdims=True), s)


#: Support-degree sharpness parameters (°C⁻²) run as alternatives to the primary α = 0.25.
ALPHAS: tuple[float, ...] = (0.05, 0.1, 0.5, 1.0, 2.0)


def alpha_key(alpha: float) -> str:
    """Method key of the support degree at sharpness ``alpha`` in :func:`alpha_methods` (``support_degree_alpha_<a>``).

    Parameters
    ----------
    alpha : float
        Support-degree parameter, °C⁻².

    Returns
    -------
    str
        The key, ``alpha`` written as ``format(alpha, "g")``.
    """
    return f"support_degree_alpha_{scalar(alpha, 'alpha', lo=0.0, lo_open=True):g}"


#: Units of work of one α of :func:`alpha_methods` (read, printed to 6 digits, hashed, keyed): 3.9 CPU-s for 900,000
#: distinct α (434 units an α; OPENBLAS_NUM_THREADS=1, the shared machine, minimum of 2; fuzz 61a: 5.1 CPU-s for
#: 10**6), counted as 450.
_ALPHA_UNITS = 450


def alpha_methods(alphas: Sequence[float] = ALPHAS) -> dict[str, dict[str, str | float]]:
    """:data:`METHODS`-style specs: the optimal fusion set and the support degree at each α.

    Parameters
    ----------
    alphas : sequence of float
        Support-degree parameters, °C⁻².

    Returns
    -------
    dict
        ``"optimal_fusion_set"`` and :func:`alpha_key` of each α (method key -> method spec), for
        :func:`fusion.scenarios.thermocouples.paired_study` (same seed: the same draws as the
        primary study).

    Raises
    ------
    TypeError
        ``alphas`` not a sequence of numbers.
    ValueError
        ``alphas`` empty (nothing to compare with the optimal fusion set), an α not finite and positive, or two
        α equal to 6 significant digits (they would share one method key); more α than the work budget
        (``fusion._limits.MAX_WORK``, 450 units an α: about 2.2 million), by their number before any is
        read.
    """
    from fusion._limits import work

    out: dict[str, dict[str, str | float]] = {"optimal_fusion_set": {"method": "optimal_fusion_set"}}
    items = sequence(alphas, "alphas")
    if not items:
        raise ValueError("alphas must hold at least one α (the support degree compared with the optimal fusion set)")
    # rule 17 by len(alphas) before any α is read (fuzz 61a C1: 10**7 - 1 alphas were read, printed and hashed
    # first, a repeat refused after 30 CPU-s)
    work((len(items),), "alphas", weight=_ALPHA_UNITS)
    # two alphas equal to 6 significant digits would share one method key (the shared rule, fuzz 30b), refused as soon
    # as the second is read (fuzz 62a D1: every alpha was read and printed first, 6.7 CPU-s for 2.2 million)
    for a in distinct_printed_as_read(items, "alphas", lambda a, i: scalar(a, f"alphas[{i}]", lo=0.0, lo_open=True),
                                      general, "keys a method"):
        out[f"support_degree_alpha_{a:g}"] = {"method": "support_degree", "alpha": a}
    return out


@_PARAMS("window", "truth")
def family_mae(z: ArrayLike, families: Mapping[str, str] = FAMILIES, scale: float = 2.0,
               window: tuple[int, int] | None = None, truth: float = 900.0) -> dict[str, FloatArray]:
    """Per-run mean absolute error of the optimal fusion set under each fusion-degree family.

    Parameters
    ----------
    z : array_like, shape (n_runs, n_samples, n_sensors)
        Readings, °C (e.g. :func:`fusion.scenarios.thermocouples.simulate` with ``n_runs``).
    families : mapping of label to family
        See :data:`FAMILIES` and :func:`family_values`.
    scale : float
        Length scale of every family, °C.

    Returns
    -------
    dict of label to ndarray, shape (n_runs,)
        Mean absolute error, °C.

    Raises
    ------
    TypeError
        ``families`` not a mapping, or a family not a string.
    ValueError
        ``families`` empty, or a family not one of those of :data:`FAMILIES` (naming ``families[label]``); the
        families beyond the work budget (``fusion._limits.MAX_WORK``: 60,000 units a family plus 10 a pair of
        readings of an epoch of ``z``), by their number before any is read, naming ``families and z``.
    """
    arr = as_array(z, "z", ndim=3)
    scale = scalar(scale, "scale", lo=0.0, lo_open=True)
    truth = scalar(truth, "truth")
    instance_of(families, Mapping, "families")
    if not families:
        raise ValueError("families must be a non-empty mapping of label to family, got an empty mapping")
    if window is not None:   # only the window's epochs: each is fused on its own
        first, last = check_window(window, "window", arr.shape[1], one_based=True)
        arr = arr[:, first - 1:last]
    # counted before any family is read (book audit 76)
    loop_work((len(families),), _PAIR_UNITS * arr.shape[0] * arr.shape[1] * arr.shape[2] ** 2, "families and z",
              step=_FAMILY_STEP)
    families = {label: one_of(fam, _FAMILY_NAMES, f"families[{shown(label)}]")  # read once, the checked names used
                for label, fam in read_mapping(families, "families").items()}  # (fuzz 31a C3)
    out = {}
    for label, fam in families.items():
        v = family_values(arr.reshape(-1, arr.shape[-1]), fam, scale).reshape(arr.shape[:2])
        out[label] = np.abs(v - truth).mean(axis=1)
    return out


@_PARAMS("window", "truth")
def weight_ablation(z: ArrayLike, window: tuple[int, int] | None = None,
                    truth: float = 900.0) -> dict[str, FloatArray]:
    """Per-run mean absolute error of the optimal fusion set with the weights of eqs. 6-11 and with equal weights.

    Both use the same set (eqs. 3-5); only the weights inside it differ.

    Parameters
    ----------
    z : array_like, shape (n_runs, n_samples, n_sensors)
        Readings, °C.

    Returns
    -------
    dict
        ``"optimal_fusion_set"`` and ``"uniform_set"`` -> ndarray, shape (n_runs,), °C.

    References
    ----------
    Yang G. N., Feng X. F., Fan L. J. (2012), eqs. 3-12.
    """
    arr = as_array(z, "z", ndim=3)
    truth = scalar(truth, "truth")
    if window is not None:   # only the window's epochs: each is fused on its own
        first, last = check_window(window, "window", arr.shape[1], one_based=True)
        arr = arr[:, first - 1:last]
    flat = arr.reshape(-1, arr.shape[-1])
    out = {"optimal_fusion_set": rd.fuse_epochs(flat, "optimal_fusion_set").values,
           "uniform_set": robust_fuse(flat, "uniform_set")}
    return {k: np.round(np.abs(v - truth).reshape(arr.shape[:2]).mean(axis=1), 9) for k, v in out.items()}
