"""Chapter 07 (time registration): the operation counts of the registration methods.

They check the claim that the improved method simplifies the computation.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from fusion._validation import as_times, derived, std_scalar
from fusion.book.glue import GlueValues
from fusion.scenarios import time_registration as sc
from fusion.scenarios.time_registration import RegMethod
from fusion.book.chapters.time_registration_ledger.studies import EXTRAP
from fusion.book.chapters.time_registration import _record_times  # noqa: F401 (the ledger's modules import it from here)

__all__ = [
    "structured_ops",
    "cost_count",
    "cost_values",
]


#: Multiplications and divisions of one step of the constant-acceleration filter (3 states, dense 3 × 3 matrices, a
#: scalar position measurement): the prediction F x (9) and F P Fᵀ (2 × 27); the update K = P Hᵀ / S (3 divisions),
#: x + K ν (3) and P − K (H P) (9); the state alone predicted to an instant (F x, no covariance); one three-point
#: (Lagrange) evaluation: three weights of two products and one division each, and the three-term sum.
KF_PREDICT_OPS, KF_UPDATE_OPS, STATE_PREDICT_OPS, THREE_POINT_OPS = 63, 15, 9, 12

#: Multiplications and divisions of one three-point evaluation whose weights are precomputed (the three-term sum),
#: and of computing one set of weights (three weights of two products and one division each).
THREE_POINT_PRECOMPUTED_OPS, THREE_POINT_WEIGHTS_OPS = 3, 9

#: Building the transition matrix for one step length T (T² and its half).
TRANSITION_OPS = 2


def structured_ops() -> dict[str, int]:
    r"""Multiplications and divisions of one step of the constant-acceleration filter when the structure is used.

    Counted from the matrices' patterns, not by hand: :math:`F` is upper triangular with ones on the diagonal and
    two other distinct entries (:math:`T`, :math:`T^2/2`; a product by 0 or 1 is free), :math:`P` is symmetric (only
    its upper triangle is computed) and :math:`H = [1\;0\;0]`. The prediction :math:`F x` and
    :math:`F P F^\top` (:math:`A = F P`, only the entries of :math:`A` the upper triangle of :math:`A F^\top`
    needs); the update :math:`K = P H^\top / S` (3 divisions), :math:`x + K\nu` (3) and :math:`P - K (H P)`
    (upper triangle, 6); the state alone predicted (:math:`F x`).

    Returns
    -------
    dict
        ``predict``, ``update``, ``state`` (operations).
    """
    gen = np.array([[0, 1, 1], [0, 0, 1], [0, 0, 0]], dtype=bool)    # F's entries other than 0 and 1
    nz = np.triu(np.ones((3, 3), dtype=bool))                          # F's non-zero entries
    state = int(gen.sum())                                             # F x: one product per general entry
    upper = np.triu(np.ones((3, 3), dtype=bool))
    need_a = np.zeros((3, 3), dtype=bool)
    stage2 = 0
    for i, j in zip(*np.nonzero(upper)):                               # (A Fᵀ)_ij = Σ_k A_ik F_jk
        need_a[i, nz[j]] = True
        stage2 += int(gen[j].sum())
    stage1 = sum(int(gen[i].sum()) for i, _ in zip(*np.nonzero(need_a)))   # A_ik = Σ_l F_il P_lk
    update = 3 + 3 + int(upper.sum())
    return {"predict": state + stage1 + stage2, "update": update, "state": state}


def cost_count(t1: ArrayLike, t2: ArrayLike) -> dict[str, int]:
    """What each Kalman route computes over the record: filter steps and distinct filter periods.

    The §3 method changes the filter period at every registration instant (it steps to the instant, then on to
    the next sample); the improved method of §4 filters at the sampling period only and evaluates a three-point
    formula per instant. A step with a new period needs a new transition matrix and driving noise.

    Parameters
    ----------
    t1, t2 : array_like
        Sample times and registration instants (s), checked by ``_record_times`` (increasing, instants within
        the record).

    Returns
    -------
    dict
        ``s3_steps``, ``improved_steps`` (filter steps), ``s3_periods``, ``improved_periods`` (distinct step
        lengths, to 1e-9 s), ``three_point_evals`` (formula evaluations of the improved method), and the
        multiplications and divisions over the record (``KF_PREDICT_OPS`` and the other module constants):
        ``improved_ops``, ``s3_ops``
        (the period changed: a full prediction to each instant between samples, the filter going on from there)
        and ``s3_unchanged_ops`` (the period kept: the state alone predicted to those instants); the other
        counting conventions: ``improved_ops_weights`` (dense, each distinct set of three-point weights computed
        once, ``weight_sets``, and each evaluation a three-term sum), ``improved_ops_structured`` and
        ``s3_ops_structured`` (the filter's structure used, ``structured_ops``; the transition matrix built
        once per distinct period; the improved method evaluates the formula only at the
        ``three_point_evals_between`` instants between samples, as §3 predicts only there) and
        ``improved_ops_structured_weights`` (both), with ``ops_step_structured`` and ``ops_predict_structured``.
    """
    t1, t2 = _record_times(t1, t2)  # increasing, the instants within the record: named
    grid = np.union1d(t1, t2[(t2 > t1[0]) & (t2 < t1[-1])])
    between = ~np.isin(t2, t1) & (t2 > t1[0]) & (t2 < t1[-1])
    off = int(np.sum(between))   # instants between samples
    n = int(t1.size - 1)
    s3_periods = int(np.unique(np.round(np.diff(grid), 9)).size)
    impr_periods = int(np.unique(np.round(np.diff(t1), 9)).size)

    def patterns(q: np.ndarray) -> int:
        """Distinct sets of three-point weights: the nodes' offsets from the instant (to 1e-9 s)."""
        j = np.clip(np.searchsorted(t1, q, side="right") - 1, 1, t1.size - 2)
        return int(np.unique(np.round(t1[np.stack([j - 1, j, j + 1], axis=1)] - q[:, None], 9), axis=0).shape[0])

    so = structured_ops()
    step, s_step = KF_PREDICT_OPS + KF_UPDATE_OPS, so["predict"] + so["update"]
    return {"s3_steps": int(grid.size - 1), "improved_steps": n,
            "s3_periods": s3_periods, "improved_periods": impr_periods,
            "three_point_evals": int(t2.size), "three_point_evals_between": off,
            "weight_sets": patterns(t2), "weight_sets_between": patterns(t2[between]),
            "improved_ops": n * step + int(t2.size) * THREE_POINT_OPS,
            "s3_ops": n * step + off * KF_PREDICT_OPS,
            "s3_unchanged_ops": n * step + off * STATE_PREDICT_OPS,
            "improved_ops_weights": n * step + int(t2.size) * THREE_POINT_PRECOMPUTED_OPS
                                    + patterns(t2) * THREE_POINT_WEIGHTS_OPS,
            "improved_ops_structured": n * s_step + off * THREE_POINT_OPS + impr_periods * TRANSITION_OPS,
            "improved_ops_structured_weights": n * s_step + off * THREE_POINT_PRECOMPUTED_OPS
                                               + patterns(t2[between]) * THREE_POINT_WEIGHTS_OPS
                                               + impr_periods * TRANSITION_OPS,
            "s3_ops_structured": n * s_step + off * so["predict"] + s3_periods * TRANSITION_OPS,
            "ops_step_structured": s_step, "ops_predict_structured": so["predict"]}


def cost_values(t1: ArrayLike, t2: ArrayLike, t2_ratio: ArrayLike, sigma: float) -> GlueValues:
    """The glue values of the cost and staleness paragraph and the constant-velocity check (chapter bookkeeping).

    Parameters
    ----------
    t1, t2 : array_like
        The sensors' sample instants (s).
    t2_ratio : array_like
        Sensor 2's instants at the integer period ratio (6 s).
    sigma : float
        Measurement noise (m).

    Returns
    -------
    dict
        ``reg_cc_*`` (filter steps, periods and operations of the §3 and §4 routes, :func:`cost_count`), ``reg_ops_*``
        (the operation counts per step), ``reg_stale_min`` /
        ``reg_stale_max`` (m: the last sample taken as simultaneous), ``reg_cv_ls`` / ``reg_cv_extrap`` (exact
        E[MSE] of a constant-velocity target, m²).

    Raises
    ------
    TypeError
        A time array is not numeric, or ``sigma`` not a number.
    ValueError
        ``t1``, ``t2`` or ``t2_ratio`` is not strictly increasing and finite (``t1``: three samples at least),
        ``t2_ratio`` holds an instant whose 6 s window holds fewer than two of the scenario's sensor-1 samples
        (named ``t2_ratio``) or is beyond the work budget (``fusion._limits.MAX_WORK``, chapter 07's rule
        ``_registration_work``: some 4,700 instants), or ``sigma`` is not a valid standard deviation.
    """
    t1, t2 = as_times(t1, "t1", min_len=3), as_times(t2, "t2")  # strictly increasing times, named
    t2_ratio, sigma = as_times(t2_ratio, "t2_ratio"), std_scalar(sigma, "sigma")
    sc._exact_work((EXTRAP, RegMethod.LEAST_SQUARES), [t2_ratio.size], "t2_ratio")  # rule 17 (fuzz 28b D3)
    cc = cost_count(t1, t2)
    stale = sc.truth(t2) - sc.truth(t1[np.searchsorted(t1, t2, side="right") - 1])
    with derived("t2_ratio", "an instant"):  # the registration refuses its own t_query
        cv = {n: sc.expected(n, sigma, t_dst=t2_ratio, window=6.0, a_after=0.0, t_change=0.0)
              for n in (EXTRAP, RegMethod.LEAST_SQUARES)}
    return {"reg_cc_impr_steps": cc["improved_steps"], "reg_cc_s3_steps": cc["s3_steps"],
            "reg_cc_s3_periods": cc["s3_periods"], "reg_cc_impr_ops": cc["improved_ops"], "reg_cc_s3_ops": cc["s3_ops"],
            "reg_cc_s3_unchanged_ops": cc["s3_unchanged_ops"], "reg_ops_step": KF_PREDICT_OPS + KF_UPDATE_OPS,
            "reg_ops_predict": KF_PREDICT_OPS, "reg_ops_state": STATE_PREDICT_OPS, "reg_ops_three": THREE_POINT_OPS,
            "reg_cc_impr_ops_weights": cc["improved_ops_weights"], "reg_cc_impr_ops_struct": cc["improved_ops_structured"],
            "reg_cc_impr_ops_struct_weights": cc["improved_ops_structured_weights"],
            "reg_cc_s3_ops_struct": cc["s3_ops_structured"], "reg_ops_step_struct": cc["ops_step_structured"],
            "reg_ops_predict_struct": cc["ops_predict_structured"], "reg_ops_three_pre": THREE_POINT_PRECOMPUTED_OPS,
            "reg_ops_weights": THREE_POINT_WEIGHTS_OPS, "reg_ops_transition": TRANSITION_OPS,
            "reg_cc_evals_between": cc["three_point_evals_between"],
            "reg_stale_min": float(np.abs(stale).min()),
            "reg_stale_max": float(np.abs(stale).max()), "reg_cv_ls": cv[RegMethod.LEAST_SQUARES],
            "reg_cv_extrap": cv[EXTRAP]}
