r"""Two local Kalman filters and a fusion centre, with or without feedback, vectorised over runs.

In the *independent* architecture each sensor's filter runs on its own measurements and the
fusion centre combines the two tracks at every step (:mod:`fusion.filtering.tracks`). In the
*feedback* architecture of Wang & Tang's (2024) Fig. 2 the fused estimate (and its covariance)
is sent back to both local filters, which predict the next step from it. Then the fused
covariance a rule reports changes the local gains, so rules that return the same estimate
without feedback (every symmetric rule on two identical sensors) no longer do.

Every rule here is linear with gains that depend on the covariances only, so the covariance
recursion is run once per step and the estimates of all runs are propagated together.

Rules (:data:`FEEDBACK_RULES`)
------------------------------
``"convex"``
    :math:`P^{-1} = P_1^{-1} + P_2^{-1}` (Wang & Tang eqs. 3-4; errors assumed independent).
``"ci"``
    Covariance intersection with the trace-optimal weight (:func:`fusion.estimates.ci.covariance_intersection`).
``"split"``
    Split CI with :math:`\omega` and :math:`1-\omega` (Julier & Uhlmann 2001; Li et al. 2013),
    trace-optimal :math:`\omega`.
``"printed"``
    Split CI with one :math:`\omega` dividing both correlated parts (eqs. 11-12 as printed).
``"bsc"``
    Bar-Shalom & Campo (1986): the best linear combination of the two tracks given their
    cross-covariance :math:`P_{12}`, which is propagated exactly.
``"lossless"``
    Feedback only. After feedback both filters predict from the same fused estimate, so the
    fusion centre knows their common prior :math:`(\hat{\mathbf x}^-, M)` and can remove it once:
    :math:`P^{-1} = P_1^{-1} + P_2^{-1} - M^{-1}`,
    :math:`P^{-1}\hat{\mathbf x} = P_1^{-1}\hat{\mathbf x}_1 + P_2^{-1}\hat{\mathbf x}_2 - M^{-1}\hat{\mathbf x}^-`
    (the information filter's track-to-track fusion; Chong, Mori & Chang 1990). Each local update
    adds only its measurement's information :math:`H^\top R_j^{-1}H` to :math:`M^{-1}`, so this is the
    centralised Kalman filter on both sensors' measurements, exactly; at step 0, where the two
    priors share only ``P0d``, it is the Bar-Shalom–Campo fusion. Bar-Shalom–Campo, which sees only
    the two tracks, loses information with feedback: both local gains lie in the column space of
    :math:`MH^\top`.

Where the process noise enters the split (``process_noise``): ``"shared"`` adds :math:`Q` to the
correlated part :math:`P_d` (both filters see the same target, so its random manoeuvres are common
to their errors; the chapter's derivation); ``"own"`` adds it to the independent part :math:`P_i`
(the labels of the source's eq. 6). Only the split rules depend on this choice.

With ``feedback="split"`` the split rules feed back their own fused split, :math:`P_{i,g} =
W_1P_{1,i}W_1^\top + W_2P_{2,i}W_2^\top` and :math:`P_{d,g} = W_1P_{1,d}W_1^\top/\omega_1 +
W_2P_{2,d}W_2^\top/\omega_2` (:math:`P_{d,g} + P_{i,g} = P_g`; the split CI filter of Li et al. 2013),
which goes on treating :math:`P_{i,g}` as independent although both filters now carry the same
fused error. With ``feedback="common"`` the whole :math:`P_g` is fed back as the common part
(:math:`P_{d} = P_g`, :math:`P_{i} = 0`), which is what the fused error is after feedback. The
other rules use only :math:`P_g`, so for them the two feedback options coincide.

References
----------
* Bar-Shalom, Y., & Campo, L. (1986). The effect of the common process noise on the
  two-sensor fused-track covariance. *IEEE Transactions on Aerospace and Electronic Systems*,
  AES-22(6), 803-805.
* Chong, C.-Y., Mori, S., & Chang, K.-C. (1990). Distributed multitarget multisensor tracking.
  In Y. Bar-Shalom (Ed.), *Multitarget-Multisensor Tracking: Advanced Applications*, 247-295.
  Artech House.
* Julier, S. J., & Uhlmann, J. K. (2001). General decentralized data fusion with covariance
  intersection. In D. L. Hall & J. Llinas (Eds.), *Handbook of Multisensor Data Fusion*. CRC Press.
* Li, H., Nashashibi, F., & Yang, M. (2013). Split covariance intersection filter: theory and its
  application to vehicle localization. *IEEE Transactions on Intelligent Transportation Systems*,
  14(4), 1860-1871.
* Wang, Z., & Tang, X. (2024). Research on multi-sensor data fusion based on covariance cross
  fusion. *Electronic Measurement Technology*.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fusion._frozen import frozen_arrays
from fusion._validation import (derived, singular_system, FloatArray, as_array, as_covariance, as_semidefinite, computed_part,
                               one_of, scalar)
from fusion.estimates import ci as es
from fusion.filtering.kalman import (FUSION_LOOP_CUBE, FUSION_LOOP_M_CUBE, FUSION_LOOP_MATRIX,
                                    FUSION_LOOP_PRINTED_CUBE, FUSION_LOOP_PRINTED_MATRIX, FUSION_LOOP_PRODUCT,
                                    FUSION_LOOP_RUN, FUSION_LOOP_SPLIT_CUBE, FUSION_LOOP_SPLIT_M_CUBE,
                                    FUSION_LOOP_SPLIT_MATRIX, FUSION_LOOP_SPLIT_STEP, FUSION_LOOP_STEP, _model,
                                    FUSION_LOOP_PRINTED_FEEDBACK_STEP,
                                    _steps_allocation, _steps_work)
from fusion._shown import shown

__all__ = ["FEEDBACK_RULES", "ARCHITECTURES", "PROCESS_NOISE", "FusionLoop", "fusion_loop"]

#: Fusion rules of :func:`fusion_loop`.
FEEDBACK_RULES = ("convex", "ci", "split", "printed", "bsc", "lossless")
#: ``"none"``: independent local filters; ``"split"``: fused estimate and the rule's fused split fed
#: back; ``"common"``: fused estimate fed back with its whole covariance as the common part.
ARCHITECTURES = ("none", "split", "common")
#: Where the process noise enters the covariance split.
PROCESS_NOISE = ("shared", "own")


@dataclass(frozen=True)
@frozen_arrays
class FusionLoop:
    """Output of :func:`fusion_loop`. Arrays are read-only.

    Attributes
    ----------
    est : ndarray, shape (runs, K, n)
        Fused estimates.
    P : ndarray, shape (K, n, n)
        Covariance the rule reports.
    omega : ndarray, shape (K,)
        Weight used at each step (``nan`` for rules without one).
    local_P : ndarray, shape (K, n, n)
        Covariance of sensor 1's local filter after its update (what feedback does to it).
    """

    est: FloatArray
    P: FloatArray
    omega: FloatArray
    local_P: FloatArray


def _local_update(F: FloatArray, H: FloatArray, Qd: FloatArray, Qi: FloatArray, R: FloatArray, Pd: FloatArray,
                  Pi: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """One local filter's predict and update of its split: prior covariance, gain, ``I - GH`` and the new parts."""
    Pdm = F @ Pd @ F.T + Qd
    Pim = F @ Pi @ F.T + Qi
    Pm = Pdm + Pim
    S = H @ Pm @ H.T + R
    G = np.linalg.solve(S, H @ Pm).T
    A = np.eye(F.shape[0]) - G @ H
    # parts the loop computes: the tiny-variance rule of inputs does not apply (a part that decays is a valid state)
    return (Pm, G, A, computed_part(_semidefinite(A @ Pdm @ A.T)),
            computed_part(_semidefinite(A @ Pim @ A.T + G @ R @ G.T)))


def _semidefinite(M: FloatArray) -> FloatArray:
    """``M``, semidefinite by construction (congruences of semidefinite parts), with the negative eigenvalues that
    rounding leaves removed; ``M`` itself when it has none.

    A part that loses rank (no process noise in it, a small weight ``omega`` dividing it at every fusion) is formed
    from products whose rounding, relative to its largest entry, grows with its condition: a negative eigenvalue of
    9e-8 of the largest entry at ``omega = 0.0033`` (T = 8 s), beyond the round-off (1e-9) that
    ``fusion._covariances.as_semidefinite`` tolerates in the validated parts of split CI. The part is semidefinite in
    exact arithmetic, so those eigenvalues are set to zero. Measured on chapter 05's architecture studies (100 runs,
    T = 1 s and 8 s), against the same loops without this step: the fused covariances move by at most 1.5e-9 of
    their largest entry; the trace-optimal split-CI weights, whose criterion is flat near its minimum, move by up to
    1.3e-3.
    """
    lam, V = np.linalg.eigh(0.5 * (M + M.T))
    if lam[0] >= 0.0:
        return M
    neg = lam < 0.0
    return 0.5 * (M + M.T) - (V[:, neg] * lam[neg]) @ V[:, neg].T


def _split_weights(F: FloatArray, H: FloatArray, Qd: FloatArray, Qi: FloatArray, Rs: list[FloatArray], P0d: FloatArray,
                   P0i: list[FloatArray], K: int, same_omega: bool) -> tuple[FloatArray, list[FloatArray]]:
    """The trace-optimal split-CI weight of every step of independent local filters, all steps searched at once: (K,),
    and the validated parts of every step (four arrays (K, n, n)).

    The local splits are the loop's own recursion (:func:`_local_update`); the weights are those
    :func:`fusion.estimates.ci.split_covariance_intersection` finds step by step, bit for bit
    (:func:`fusion.estimates.ci._split_ci_weights`: scipy's bounded Brent steps, one batched evaluation per iteration).
    """
    n = F.shape[0]
    Pd, Pi = [P0d.copy(), P0d.copy()], [P0i[0].copy(), P0i[1].copy()]
    steps = []
    for k in range(K):
        if k > 0:
            for j in range(2):
                _, _, _, Pd[j], Pi[j] = _local_update(F, H, Qd, Qi, Rs[j], Pd[j], Pi[j])
        steps.append(es._split_parts(Pd[0], Pi[0], Pd[1], Pi[1], n))
    parts = [np.stack(x) for x in zip(*steps)]
    return es._split_ci_weights(*parts, criterion="trace", same_omega=same_omega), parts


def _fuse(rule: str, P1: FloatArray, P2: FloatArray, Pd: list[FloatArray], Pi: list[FloatArray],
          P12: FloatArray, omega: float | None = None, parts: list[FloatArray] | None = None
          ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, float]:
    """Gains W1, W2, fused P, its correlated and independent parts and the weight of one step (``parts``: the step's
    split parts, already validated, with ``omega`` searched on them: split CI's covariance without the checks again)."""
    n = P1.shape[0]
    zero = np.zeros(n)
    if rule == "convex":
        r = es.convex_combination(zero, P1, zero, P2)
        W1, W2 = r.P @ np.linalg.inv(P1), r.P @ np.linalg.inv(P2)
        return W1, W2, r.P, r.P, np.zeros((n, n)), float("nan")
    if rule == "ci":
        r = es.covariance_intersection(zero, P1, zero, P2)
        W1 = r.omega * r.P @ np.linalg.inv(P1)
        W2 = (1.0 - r.omega) * r.P @ np.linalg.inv(P2)
        return W1, W2, r.P, r.P, np.zeros((n, n)), r.omega
    if rule in ("bsc", "lossless"):   # lossless: Bar-Shalom-Campo at step 0, handled by the loop after it
        C = P1 - P12
        D = P1 + P2 - P12 - P12.T
        G = C @ np.linalg.pinv(0.5 * (D + D.T), hermitian=True)
        P = 0.5 * (P1 - G @ C.T + (P1 - G @ C.T).T)
        return np.eye(n) - G, G, P, P, np.zeros((n, n)), float("nan")
    same = rule == "printed"
    if parts is not None and omega is not None:
        r = es.FusedEstimate(x=zero, P=es._split_ci_covariance(*parts, omega, same), omega=omega)
    else:
        r = es.split_covariance_intersection(zero, Pd[0], Pi[0], zero, Pd[1], Pi[1], omega=omega, same_omega=same)
    w2 = r.omega if same else 1.0 - r.omega
    W1 = r.P @ np.linalg.inv(Pd[0] / r.omega + Pi[0])
    W2 = r.P @ np.linalg.inv(Pd[1] / w2 + Pi[1])
    Pig = W1 @ Pi[0] @ W1.T + W2 @ Pi[1] @ W2.T
    Pdg = W1 @ Pd[0] @ W1.T / r.omega + W2 @ Pd[1] @ W2.T / w2   # Pdg + Pig = P, both semidefinite
    return W1, W2, r.P, 0.5 * (Pdg + Pdg.T), 0.5 * (Pig + Pig.T), r.omega


@singular_system('the covariances (Q, R1, R2, P0d, P0i_1, P0i_2)')
def fusion_loop(
    z1: ArrayLike, z2: ArrayLike, x0_1: ArrayLike, x0_2: ArrayLike, F: ArrayLike, H: ArrayLike, Q: ArrayLike,
    R1: ArrayLike, R2: ArrayLike, P0d: ArrayLike, P0i_1: ArrayLike, P0i_2: ArrayLike, rule: str, feedback: str = "none",
    process_noise: str = "shared", omega: float | None = None,
) -> FusionLoop:
    r"""Run two local Kalman filters and fuse them at every step, with or without feedback.

    At step 0 filter :math:`j` holds its initial estimate with covariance ``P0d + P0i_j`` and the two
    are fused; at every later step each filter predicts (from its own last estimate, or from the
    fused one with ``feedback="split"`` or ``"common"``), updates with its own measurement, and the two are fused.
    Local update of filter :math:`j` with :math:`A_j = I - K_jH`:
    :math:`P_{j,d} \leftarrow A_j(FP_{j,d}F^\top + Q_d)A_j^\top`,
    :math:`P_{j,i} \leftarrow A_j(FP_{j,i}F^\top + Q_i)A_j^\top + K_jR_jK_j^\top`, with
    :math:`(Q_d, Q_i) = (Q, 0)` or :math:`(0, Q)` by ``process_noise``; the cross-covariance of
    the two local errors follows :math:`P_{12} \leftarrow A_1(FP_{12}F^\top + Q)A_2^\top`
    (:math:`P_{12} = P_g` after feedback: both filters then carry the fused error); feedback
    replaces both local estimates by the fused one.

    Parameters
    ----------
    z1, z2 : array_like, shape (runs, K, m)
        Measurements of sensor 1 and 2 (step 0 is not used: it is the initialisation).
    x0_1, x0_2 : array_like, shape (runs, n)
        Initial estimates of the two filters.
    F, H : array_like, shape (n, n) and (m, n)
        Transition and measurement matrices.
    Q : array_like, shape (n, n)
        Process-noise covariance (positive semidefinite).
    R1, R2 : array_like, shape (m, m)
        Measurement covariances.
    P0d : array_like, shape (n, n)
        Part of the initial covariance common to both filters (positive semidefinite).
    P0i_1, P0i_2 : array_like, shape (n, n)
        Each filter's own part of its initial covariance (positive semidefinite; ``P0d + P0i_j``
        positive definite).
    rule : {"convex", "ci", "split", "printed", "bsc", "lossless"}
        Fusion rule (module docstring); ``"lossless"`` needs feedback.
    feedback : {"none", "split", "common"}
        Independent local filters, or the fused estimate and covariance fed back to both
        (Wang & Tang 2024, Fig. 2), with the rule's own split or as wholly common (module docstring).
    process_noise : {"shared", "own"}
        Whether ``Q`` enters the correlated or the independent part of the split.
    omega : float, optional
        A fixed weight for ``"split"`` (in (0, 1)) and ``"printed"`` (in (0, 1]) at every step, e.g. the
        published FOA optimum; ``None`` (default) minimises the trace at each step (without feedback the
        local splits do not depend on the fusion, so every step's weight is searched at once: the weights
        of the step-by-step search, bit for bit). Not allowed with the other rules.

    Returns
    -------
    FusionLoop
        The fused estimates ``est`` and covariances ``P`` at every step of every run, the weight ``omega`` per step and
        the local covariances ``local_P``.

    Raises
    ------
    ValueError
        Arrays of the wrong shape or not finite, covariances not valid, an unknown option; the steps ``K`` of ``z1``
        and ``z2`` with the sizes of ``F`` and ``H`` beyond the work budget (``fusion._limits.MAX_WORK``, ~10
        CPU-s: each step's ``n x n`` products and inverses cost about ``n**3``, each run its products with them; one run
        of 300 states and 300 measurements is refused from 91 steps, 48 with ``"split"`` and 31 with ``"printed"``).

    References
    ----------
    * Bar-Shalom, Y., & Campo, L. (1986). *IEEE Trans. AES*, 22(6), 803-805.
    * Li, H., Nashashibi, F., & Yang, M. (2013). *IEEE Trans. ITS*, 14(4), 1860-1871.
    * Wang, Z., & Tang, X. (2024). *Electronic Measurement Technology* (Fig. 2, eqs. 5-12).
    """
    rule = one_of(rule, FEEDBACK_RULES, "rule")
    feedback = one_of(feedback, ARCHITECTURES, "feedback")
    process_noise = one_of(process_noise, PROCESS_NOISE, "process_noise")
    if rule == "lossless" and feedback == "none":
        raise ValueError("rule 'lossless' needs feedback: without it the fusion centre does not know the common prior")
    if omega is not None:
        if rule not in ("split", "printed"):
            raise ValueError(f"omega fixes the weight of 'split' or 'printed', not of rule {shown(rule)}")
        omega = scalar(omega, "omega", 0.0, 1.0, lo_open=True, hi_open=rule == "split")
    F, H = _model(F, H)
    n, m = F.shape[0], H.shape[0]
    zs = []
    for name, z in (("z1", z1), ("z2", z2)):
        arr = as_array(z, name, ndim=3)
        if arr.shape[0] == 0 or arr.shape[1] == 0 or arr.shape[2] != m:
            raise ValueError(f"{name} must be a non-empty (runs, K, {m}) array, got shape {arr.shape}")
        zs.append(arr)
    if zs[0].shape != zs[1].shape:
        raise ValueError(f"z2 must have the shape of z1 {zs[0].shape}, got {zs[1].shape}")
    runs, K = zs[0].shape[:2]
    # the estimates (runs, K, n), the fused and local P (K, n, n) and the split weights' four parts (K, n, n)
    _steps_allocation(K, n, runs + 6 * n, "z1 and the sizes of F and H")
    # each step's dense n x n and m x m algebra too (fuzz 37a C2): the split rules search a weight a step, dearer
    searched = rule in ("split", "printed")
    _steps_work(K, runs, n, m, FUSION_LOOP_PRINTED_FEEDBACK_STEP if rule == "printed" and feedback != "none"
                else FUSION_LOOP_SPLIT_STEP if searched else FUSION_LOOP_STEP,
                "z1 and z2 (their steps K) and the sizes of F and H",
                FUSION_LOOP_PRINTED_CUBE if rule == "printed" else FUSION_LOOP_SPLIT_CUBE if searched else FUSION_LOOP_CUBE,
                FUSION_LOOP_SPLIT_M_CUBE if searched else FUSION_LOOP_M_CUBE, run=FUSION_LOOP_RUN,
                product=FUSION_LOOP_PRODUCT, matrix=FUSION_LOOP_PRINTED_MATRIX if rule == "printed"
                else FUSION_LOOP_SPLIT_MATRIX if searched else FUSION_LOOP_MATRIX)
    xs = []
    for name, x0 in (("x0_1", x0_1), ("x0_2", x0_2)):
        arr = as_array(x0, name, ndim=2)
        if arr.shape != (runs, n):
            raise ValueError(f"{name} must be a ({runs}, {n}) array (one state per run), got shape {arr.shape}")
        xs.append(arr.copy())
    Q = as_semidefinite(Q, n, name="Q")
    Rs = [as_covariance(R1, m, name="R1"), as_covariance(R2, m, name="R2")]
    P0d = as_semidefinite(P0d, n, name="P0d")
    P0i = [as_semidefinite(P0i_1, n, name="P0i_1"), as_semidefinite(P0i_2, n, name="P0i_2")]
    as_covariance(P0d + P0i[0], n, name="P0d + P0i_1")
    as_covariance(P0d + P0i[1], n, name="P0d + P0i_2")
    Qd, Qi = (Q, np.zeros_like(Q)) if process_noise == "shared" else (np.zeros_like(Q), Q)
    Pd, Pi, P12 = [P0d.copy(), P0d.copy()], [P0i[0].copy(), P0i[1].copy()], P0d.copy()
    est = np.empty((runs, K, n))
    P_out = np.empty((K, n, n))
    local_P = np.empty((K, n, n))
    omega_used = np.full(K, np.nan)
    M = xm_common = None   # the common prior of both filters once the fused estimate is fed back
    # a valid F, H and Q (or tiny P0d, P0i) can still leave a direction without uncertainty (F = 0 and a low-rank Q):
    # the local covariance a rule refuses then comes from them, and the message says so
    with derived("F, H, Q, R1, R2, P0d and P0i", "a singular local covariance"):
        step_omega = step_parts = None
        if feedback == "none" and rule in ("split", "printed") and omega is None:
            # without feedback the local covariances do not depend on the fusion: every step's weight searched at once
            step_omega, step_parts = _split_weights(F, H, Qd, Qi, Rs, P0d, P0i, K, same_omega=rule == "printed")
        for k in range(K):
            if k > 0:
                As = []
                for j in range(2):
                    Pm, G, A, Pd[j], Pi[j] = _local_update(F, H, Qd, Qi, Rs[j], Pd[j], Pi[j])
                    xm = xs[j] @ F.T
                    if j == 0:
                        M, xm_common = Pm, xm
                    xs[j] = xm + (zs[j][:, k] - xm @ H.T) @ G.T
                    As.append(A)
                P12 = As[0] @ (F @ P12 @ F.T + Q) @ As[1].T
            P1, P2 = Pd[0] + Pi[0], Pd[1] + Pi[1]
            local_P[k] = P1
            P1s, P2s = 0.5 * (P1 + P1.T), 0.5 * (P2 + P2.T)
            if rule == "lossless" and k > 0:   # information form, the common prior removed once
                I1, I2, IM = np.linalg.inv(P1s), np.linalg.inv(P2s), np.linalg.inv(0.5 * (M + M.T))
                P = np.linalg.inv(I1 + I2 - IM)
                P = 0.5 * (P + P.T)
                xg = xs[0] @ (P @ I1).T + xs[1] @ (P @ I2).T - xm_common @ (P @ IM).T
                Pdg, Pig, w = P, np.zeros_like(P), float("nan")
            else:
                w_k = omega if step_omega is None else float(step_omega[k])
                W1, W2, P, Pdg, Pig, w = _fuse(rule, P1s, P2s, Pd, Pi, P12, w_k,
                                               None if step_parts is None else [p[k] for p in step_parts])
                xg = xs[0] @ W1.T + xs[1] @ W2.T
            est[:, k], P_out[k], omega_used[k] = xg, P, w
            if feedback != "none":
                if feedback == "common":
                    Pdg, Pig = P, np.zeros_like(P)
                xs = [xg.copy(), xg.copy()]
                Pd = [Pdg.copy(), Pdg.copy()]
                Pi = [Pig.copy(), Pig.copy()]
                P12 = P.copy()
    return FusionLoop(est=est, P=P_out, omega=omega_used, local_P=local_P)
