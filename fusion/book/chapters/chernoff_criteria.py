r"""Chapter 06 (patent CN107330468B): other criteria and a known-common-information baseline in the static networks.

The designed networks of :mod:`fusion.scenarios.fusion_networks` keep every node's first local posterior as its
moments (``NetworkStudy.local_mean``, ``local_cov``: the inputs of the Gaussian pipelines). In the networks with one
frame the Gaussian pipelines see nothing else, so their exchanges can be run again here on exactly the same inputs,
with other exponent rules (:func:`gaussian_exchange`):

* ``ci_gaussian``: covariance intersection with the Chernoff exponents (the study's own pipeline; the parity test
  of this module recomputes it digit for digit);
* ``ci_mean_free``: the Chernoff criterion with the means set equal: :math:`\log Z` of zero-mean Gaussians,
  :math:`\tfrac12\log\det P(\varepsilon) - \tfrac12\sum_i\varepsilon_i\log\det P_i`, which does not react to the
  realised disagreement of the local means;
* ``ci_det``: the determinant criterion (Julier & Uhlmann 1997), :math:`\min\log\det P(\varepsilon)`, which can
  pick a vertex of the simplex (the Chernoff criterion cannot: :math:`\log Z = 0`, its maximum, there);
* ``ci_uniform``: covariance intersection with uniform exponents;
* ``naive_product``: exponents 1 (the study's own pipeline);
* ``channel_filter``: the known common information removed, as a channel filter does (Grime & Durrant-Whyte
  1994): in information form each node adds what a neighbour sends minus what the two already share, the shared
  prior before the first exchange, and after each synchronous exchange the channel holds
  :math:`C_{jk} \leftarrow m_j + m_k - C_{jk}` (:func:`channel_filter`). On a tree (every network here) this counts
  each node's likelihood and the prior once; it does not know a relay's repeated information, which is no common
  prior.

Every method gets the same local posteriors; the channel filter also gets the shared prior (its mean is the study's
own draw, :func:`prior_means`), the information it exists to remove.

References
----------
* Grime, S., & Durrant-Whyte, H. F. (1994). Data fusion in decentralized sensor networks. *Control Engineering
  Practice* 2(5), 849-863.
* Julier, S. J., & Uhlmann, J. K. (1997). A non-divergent estimation algorithm in the presence of unknown
  correlations. *Proceedings of the 1997 American Control Conference*.
* Bar-Shalom, Y., & Campo, L. (1986). The effect of the common process noise on the two-sensor fused-track
  covariance. *IEEE Transactions on Aerospace and Electronic Systems* 22(6), 803-805.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from fusion._docstrings import with_sections
from fusion._limits import work
from fusion._validation import (FloatArray, _numeric, as_covariances, check_magnitude, count, instance_of, mapping_of,
                                one_of)
from fusion._validation import seed as check_seed
from fusion.book.ledger import Comparison
from fusion.book.tables import rounded, roundoff
# the batched kernels of the package (private: array-level), as fusion.scenarios.fusion_networks uses them
from fusion.estimates.chernoff.gaussian import _ci_criterion_batch, _gaussian_chernoff_batch, _product_terms
from fusion.book.style import METHOD_LABELS
from fusion.book.chapters.chernoff.premise import RMSE_ROW, _enough_runs, _known_networks
from fusion.scenarios.fusion_networks import Network, NetworkScenario, NetworkStudy
from fusion.book._json import read_argument
from fusion.book.glue import GlueValues
from fusion._shown import shown

__all__ = ["GAUSSIAN_RULES", "CRITERIA_NETWORKS", "prior_means", "exponent_rule", "gaussian_exchange", "channel_filter",
           "network_mse", "baseline_table", "criteria_table", "criteria_values", "appendix_referenced"]

#: Exponent rules of :func:`gaussian_exchange` (keys; display labels in :data:`fusion.book.style.METHOD_LABELS`).
GAUSSIAN_RULES: tuple[str, ...] = ("ci_gaussian", "ci_mean_free", "ci_det", "ci_uniform", "naive_product")

#: The designed networks with one frame (their Gaussian pipelines see only the stored first local posteriors).
CRITERIA_NETWORKS = (Network.UNEQUAL, Network.NON_GAUSSIAN, Network.CHAIN, Network.RELAY, Network.OVERCONFIDENT)

_PMSE = "per-run squared position error averaged over the nodes (m²)"


def _one_frame(study: NetworkStudy, name: str = "study") -> NetworkScenario:
    instance_of(study, NetworkStudy, name)
    if study.scenario.frames != 1:
        raise ValueError(f"{name} must be of a network with one frame (its later local posteriors are not kept), got "
                         f"{study.scenario.frames} frames")
    return study.scenario


#: Units (``fusion._limits.MAX_WORK``'s 10 ns) of one run of :func:`prior_means` (two SeedSequence spawns, a Generator
#: and two draws): about 52 us (runs 1,000 -> 10,000: 0.050 -> 0.521 CPU-s, process_time, minimum of 2, the shared
#: machine loaded), weighed twice (book audit 76: no budget, so 10**7 runs, about 9 CPU-minutes, were accepted).
_PRIOR_RUN = 10_000


def prior_means(sc: NetworkScenario, seed: int, runs: int) -> FloatArray:
    """The shared prior's mean in every run of :func:`~fusion.scenarios.fusion_networks.run_network_study`.

    The study draws it first from each run's measurement stream (the first of three children of the run's
    ``SeedSequence``); this repeats that draw and nothing else.

    Parameters
    ----------
    sc : NetworkScenario
    seed : int
        The study's root seed (``NetworkStudy.seed``).
    runs : int
        Runs of the study.

    Returns
    -------
    ndarray, shape (runs, 2)
        Per run, the truth plus ``prior_std`` times one standard normal draw (m): the shared prior's mean that run used.

    Raises
    ------
    ValueError
        ``runs`` below 1 or beyond the work budget (``fusion._limits.MAX_WORK``: 100,000 runs).
    """
    instance_of(sc, NetworkScenario, "sc")
    seed = check_seed(seed)
    runs = count(runs, "runs", minimum=1)
    work((runs,), "runs", weight=_PRIOR_RUN)  # before the first spawn (book audit 76)
    truth = np.asarray(sc.truth, dtype=float)
    return np.stack([truth + sc.prior_std * np.random.default_rng(s.spawn(3)[0]).standard_normal(2)
                     for s in np.random.SeedSequence(seed).spawn(runs)])


def exponent_rule(rule: str, means: FloatArray, covs: FloatArray) -> FloatArray:
    """Exponents of one exchange of Gaussians for B problems of M inputs, by ``rule``.

    Parameters
    ----------
    rule : str
        A key of :data:`GAUSSIAN_RULES`.
    means : ndarray, shape (B, M, d)
        Finite (B, M, d >= 1).
    covs : ndarray, shape (B, M, d, d)
        Symmetric positive definite (the package's covariance rule, ``fusion._covariances.as_covariances``).

    Returns
    -------
    ndarray, shape (B, M)
        On the simplex (all ones for ``naive_product``).

    Raises
    ------
    TypeError
        ``rule`` not a str, ``means`` or ``covs`` not real numbers.
    ValueError
        ``rule`` not a key of :data:`GAUSSIAN_RULES`; ``means`` not (B, M, d) with every size >= 1, NaN, infinite or
        beyond the magnitude rule; ``covs`` not (B, M, d, d) or a matrix of it not a valid covariance (named by
        its index).
    """
    rule = one_of(rule, GAUSSIAN_RULES, "rule")
    m = check_magnitude(_numeric(means, "means"), "means")
    if m.ndim != 3 or 0 in m.shape:
        raise ValueError(f"means must be (B, M, d) with B, M and d >= 1, got shape {m.shape}")
    P = as_covariances(covs, dim=m.shape[-1], name="covs")
    if P.shape != m.shape + (m.shape[-1],):
        raise ValueError(f"means must be (B, M, d) and covs (B, M, d, d), got {m.shape} and {P.shape}")
    return _rule_eps(rule, m, np.linalg.inv(P), np.linalg.slogdet(2 * np.pi * P)[1])


def _rule_eps(rule: str, m: FloatArray, infos: FloatArray, logdets: FloatArray) -> FloatArray:
    """Kernel of :func:`exponent_rule` on information matrices and log-determinants of 2πP."""
    B, M, _ = m.shape
    if rule == "naive_product":
        return np.ones((B, M))
    if rule == "ci_uniform":
        return np.full((B, M), 1.0 / M)
    if rule == "ci_det":
        return _ci_criterion_batch(infos, "det")
    return _gaussian_chernoff_batch(np.zeros_like(m) if rule == "ci_mean_free" else m, infos, logdets)


def _inputs(study: NetworkStudy) -> tuple[FloatArray, FloatArray]:
    """The Gaussian pipelines' inputs: the first local moments, covariances with the study's floor."""
    sc = study.scenario
    floor = 1e-9 * sc.prior_std**2 * np.eye(2)
    return np.array(study.local_mean), np.array(study.local_cov) + floor


#: Relative difference below which two inputs of a node count as the same density (``_first_of_identical``).
SAME_RTOL = 1e-6


def _first_of_identical(e: FloatArray, m: FloatArray, infos: FloatArray) -> FloatArray:
    """The exponents ``e`` (B, M) with the sum over inputs that are the same density reported on the first of them.

    Two inputs with the same mean and information enter the product only through the sum of their exponents, so a
    criterion is flat along their split and the optimiser's split is decided by round-off (in chapter 06's chain one
    run's middle node kept 0 or 0.18 of its own density, the same 0.37 in both, under two BLAS kernels). Inputs equal
    to a relative :data:`SAME_RTOL` count as the same (an earlier round's optimiser leaves differences of about
    1e-8: the criterion is then flat within its tolerance). The fused density is computed with ``e`` as returned; the
    reported split gives the sum to the first input (a node's own density: ``NetworkScenario.neighbours`` lists it
    first), so that it is the same on every machine.
    """
    out = np.array(e, dtype=float)
    close = lambda a, b, axes: np.all(np.abs(a - b) <= SAME_RTOL * np.maximum(np.abs(a), np.abs(b)), axis=axes)  # noqa: E731
    for a in range(out.shape[1]):
        for b in range(a + 1, out.shape[1]):
            same = close(m[:, a], m[:, b], -1) & close(infos[:, a], infos[:, b], (-2, -1))
            out[same, a] += out[same, b]
            out[same, b] = 0.0
    return out


def gaussian_exchange(study: NetworkStudy, rule: str) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Every exchange round of a one-frame network's Gaussian pipeline, with the exponents of ``rule``.

    The same steps as the study's Gaussian pipelines: with full connectivity node 1 fuses every node's density once
    and every node takes the result; otherwise each node fuses itself and its neighbours, round after round.

    Parameters
    ----------
    study : NetworkStudy
        A one-frame network (ValueError otherwise).
    rule : str
        A key of :data:`GAUSSIAN_RULES`.

    Returns
    -------
    estimates : ndarray, shape (runs, N, 2)
        Each node's fused mean (m) after the last round.
    covariances : ndarray, shape (runs, N, 2, 2)
        Each node's fused covariance (m²) after the last round.
    eps : ndarray, shape (runs, rounds, N, N)
        Per round and node, the exponent of each node's density (NaN for a node it does not hear; over identical
        densities, their sum on the first of them: ``_first_of_identical``).
    """
    sc = _one_frame(study)
    rule = one_of(rule, GAUSSIAN_RULES, "rule")
    mu, P = _inputs(study)
    B, N, _ = mu.shape
    nb, full = sc.neighbours, sc.edges is None
    eps = np.full((B, sc.rounds, N, N), np.nan)
    for r in range(sc.rounds):
        infos, logdets = np.linalg.inv(P), np.linalg.slogdet(2 * np.pi * P)[1]
        out_m, out_P = np.empty_like(mu), np.empty_like(P)
        for j in ([0] if full else range(N)):
            idx = nb[j]
            m_, i_, l_ = mu[:, idx], infos[:, idx], logdets[:, idx]
            e = _rule_eps(rule, m_, i_, l_)
            x, Pf, _ = _product_terms(m_[:, None], i_[:, None], l_[:, None], e)
            out_m[:, j], out_P[:, j] = x[:, 0], Pf[:, 0]
            eps[:, r, j, idx] = _first_of_identical(e, m_, i_)
        if full:
            out_m[:, 1:], out_P[:, 1:], eps[:, r, 1:] = out_m[:, :1], out_P[:, :1], eps[:, r, :1]
        mu, P = out_m, out_P
    return mu, P, eps


def channel_filter(study: NetworkStudy) -> tuple[FloatArray, FloatArray, FloatArray]:
    r"""The known common information removed: channel filters on every edge, in information form.

    Node :math:`j` holds :math:`(Y_j, y_j)` (information matrix and vector), first its local posterior's. In each
    synchronous round every node sends its belief :math:`m_k` and sets :math:`m_j + \sum_k (m_k - C_{jk})` over its
    neighbours :math:`k`; the channel then holds :math:`C_{jk} \leftarrow m_j + m_k - C_{jk}`, starting from the
    shared prior. With full connectivity and one round this is :math:`\sum_i Y_i - (N-1)Y_0`.

    Parameters
    ----------
    study : NetworkStudy
        A one-frame network (ValueError otherwise).

    Returns
    -------
    estimates : ndarray, shape (runs, N, 2)
        Each node's fused mean (m) after the last round; NaN where its fused information is not positive definite.
    covariances : ndarray, shape (runs, N, 2, 2)
        NaN for a node whose fused information is not positive definite (counted by :func:`baseline_table`).
    not_pd : ndarray of bool, shape (runs, N)
        Nodes whose fused information is not positive definite (the particle posterior's information minus the
        prior's can be indefinite when the particles do not resolve a node's likelihood).
    """
    sc = _one_frame(study)
    mu, P = _inputs(study)
    B, N, d = mu.shape
    Y = np.linalg.inv(P)
    y = np.einsum("bnij,bnj->bni", Y, mu)
    m0 = prior_means(sc, study.seed, B)
    Y0 = np.broadcast_to(np.eye(d) / sc.prior_std**2, (B, d, d))
    y0 = m0 / sc.prior_std**2
    nb = sc.neighbours
    C = {(j, k): (Y0.copy(), y0.copy()) for j in range(N) for k in nb[j] if k != j}
    for _ in range(sc.rounds):
        sent = (Y.copy(), y.copy())
        newY, newy = Y.copy(), y.copy()
        for j in range(N):
            for k in nb[j][1:]:
                newY[:, j] += sent[0][:, k] - C[(j, k)][0]
                newy[:, j] += sent[1][:, k] - C[(j, k)][1]
        for (j, k), (cY, cy) in list(C.items()):
            C[(j, k)] = (sent[0][:, j] + sent[0][:, k] - cY, sent[1][:, j] + sent[1][:, k] - cy)
        Y, y = 0.5 * (newY + np.swapaxes(newY, -1, -2)), newy
    not_pd = np.linalg.eigvalsh(Y)[..., 0] <= 0
    Ysafe = np.where(not_pd[..., None, None], np.eye(d), Y)
    Pf = np.linalg.inv(Ysafe)
    est = np.einsum("bnij,bnj->bni", Pf, y)
    return np.where(not_pd[..., None], np.nan, est), np.where(not_pd[..., None, None], np.nan, Pf), not_pd


def network_mse(study: NetworkStudy, estimates: FloatArray) -> FloatArray:
    """Per-run squared position error averaged over the nodes, m², as ``NetworkStudy.mse`` rounds it.

    Parameters
    ----------
    study : NetworkStudy
    estimates : ndarray, shape (runs, N, 2)
        Finite positions (m) within the magnitude rule (:func:`channel_filter`'s NaN estimates are not:
        :func:`baseline_table` leaves out their runs before it scores the rest).

    Returns
    -------
    ndarray, shape (runs,)
        Per run, the squared distance of the estimates from the truth averaged over the nodes (m², 6 decimals).

    Raises
    ------
    TypeError
        ``study`` not a NetworkStudy, ``estimates`` not real numbers.
    ValueError
        ``estimates`` not of the study's shape, NaN, infinite or beyond the magnitude rule.
    """
    instance_of(study, NetworkStudy, "study")
    e = check_magnitude(_numeric(estimates, "estimates"), "estimates", subnormal=False)
    if e.shape != study.estimates["exact_posterior"].shape:
        raise ValueError(f"estimates must have shape {study.estimates['exact_posterior'].shape}, got {e.shape}")
    return _mse(study, e)


def _mse(study: NetworkStudy, e: FloatArray) -> FloatArray:
    """Kernel of :func:`network_mse` (a NaN estimate gives its run a NaN, which the callers leave out)."""
    return np.round(np.mean(np.sum((e - study.truth) ** 2, axis=-1), axis=-1), 6)


def _cell(cmp: Comparison) -> str:
    d, lo, hi = cmp.interval()
    return f"{d:.1f} [{lo:.1f}, {hi:.1f}] ({cmp.judgement().region})"


def _networks(studies: object, labels: object, reason: object) -> str:
    """The networks' studies and their column labels (fuzz 19, class D): the shared rule ``mapping_of`` for both,
    every network of :data:`CRITERIA_NETWORKS` in each, and rule R4 on their runs (``_enough_runs``, fuzz 21b class
    A), before any work; returns ``reason``."""
    mapping_of(studies, "studies", "NetworkStudy", values=NetworkStudy, maker="premise_study")
    _known_networks(studies)  # type: ignore[arg-type]  # issue 35: a study under an unknown key was left out silently
    mapping_of(labels, "labels", "column label", values=str)
    _known_networks(labels, "labels")  # type: ignore[arg-type]  # fuzz 26b D6: a label of no network, as studies
    seen: dict[str, str] = {}
    for key in CRITERIA_NETWORKS:
        _one_frame(_key(studies, key), f"studies[{shown(key)}]")  # type: ignore[arg-type]  # fuzz 24b WN2: by its key
        if key not in labels:  # type: ignore[operator]
            raise ValueError(f"labels must hold the network {shown(key)}, got {sorted(map(str, labels))}")  # type: ignore[call-overload]
        # the labels are the tables' column headers (fuzz 24b LB): a repeated one would put one network's numbers
        # under another's header and drop a column, an empty one would head a column with nothing
        label = labels[key]  # type: ignore[index]
        if not label.strip():
            raise ValueError(f"labels[{shown(key)}] is empty: a column label is needed")
        if label in seen:
            raise ValueError(f"labels must not repeat a label: labels[{shown(seen[label])}] and labels[{shown(key)}] "
                             f"are both {shown(label)} (each labels one network's column)")
        seen[label] = key
    return _enough_runs({k: studies[k] for k in CRITERIA_NETWORKS}, reason)  # type: ignore[index]


#: The Raises section of the functions of the networks' studies and labels (:func:`_networks`), written once.
_on_networks = with_sections(raises="""TypeError
    ``studies`` or ``labels`` not a mapping, a study not a NetworkStudy, a label or ``reason`` not a str.
ValueError
    ``studies`` or ``labels`` without a network of :data:`CRITERIA_NETWORKS`, two of these networks with one label
    or one with an empty label (the labels head the tables' columns), ``studies`` or ``labels`` with a key that is
    not a network of :data:`~fusion.book.chapters.chernoff.PREMISE_LABELS`, a study of these networks of several frames
    (or, under a key of ``ORACLE_NETWORKS``, of several exchanges), or a network of fewer than
    :data:`~fusion.book.ledger.MIN_RUNS` runs without a ``reason`` (rule R4).""")


def _key(studies: dict[str, NetworkStudy], key: str) -> NetworkStudy:
    key = one_of(key, tuple(map(str, CRITERIA_NETWORKS)), "network")
    if key not in studies:
        raise ValueError(f"studies must hold the network {shown(key)}, got {sorted(studies)}")
    return studies[key]


@_on_networks
def baseline_table(studies: dict[str, NetworkStudy], labels: dict[str, str], reason: str = ""
                   ) -> tuple[pd.DataFrame, GlueValues]:
    """The channel filter beside the chapter's methods, network by network, paired on the same runs.

    Parameters
    ----------
    studies : dict
        Network key -> study (:func:`fusion.book.chapters.chernoff.premise_study`); the one-frame networks of
        :data:`CRITERIA_NETWORKS` are read.
    labels : dict
        Network key -> column label: non-empty, one label per network read.
    reason : str
        Why fewer than 100 runs are enough, when they are (rule R4; tests of small studies).

    Returns
    -------
    table : DataFrame
        One column per network: runs, RMSE of the channel filter and the centralised posterior (m), and the paired
        MSE difference channel filter − each method with its 95 % interval and the region of rule R2 (margin 5 %
        of the method's mean MSE, as the chapter's records), m².
    values : dict
        Glue ``chf_cf_<net>_<method>_d/_lo/_hi`` (m², 1 decimal), ``chf_cf_<net>_rmse`` (m, 2 decimals),
        ``chf_cf_runs`` (fewest runs of a network) and ``chf_cf_not_pd`` (node estimates without a positive definite
        fused information, over every network).
    """
    reason = _networks(studies, labels, reason)
    cols: dict[str, dict[str, str]] = {}
    v: dict[str, Any] = {}
    not_pd_total, runs = 0, []
    for key in CRITERIA_NETWORKS:
        st = _key(studies, key)
        est, _, not_pd = channel_filter(st)
        not_pd_total += int(not_pd.sum())
        ok = ~np.any(not_pd, axis=1)
        a = _mse(st, est)[ok]  # the runs with a NaN estimate (not positive definite) left out
        runs.append(int(ok.sum()))
        col = {"runs": f"{int(ok.sum())}", RMSE_ROW.format("known common information removed"): f"{np.sqrt(a.mean()):.2f}",
               RMSE_ROW.format(METHOD_LABELS["exact_posterior"]): f"{np.sqrt(st.mse('exact_posterior')[ok].mean()):.2f}"}
        v[f"chf_cf_{key}_rmse"] = rounded(float(np.sqrt(a.mean())), 2)
        for m in ("chernoff_pso", "ci_gaussian", "naive_product", "exact_posterior"):
            cmp = Comparison(a, st.mse(m)[ok], "known common information removed", METHOD_LABELS[m], "less", _PMSE,
                             seed=st.seed, reason=reason)
            col[f"removed − {METHOD_LABELS[m]} (m², 95 %)"] = _cell(cmp)
            d, lo, hi = cmp.interval()
            v.update({f"chf_cf_{key}_{m}_d": rounded(d, 1), f"chf_cf_{key}_{m}_lo": rounded(lo, 1),
                      f"chf_cf_{key}_{m}_hi": rounded(hi, 1)})
        cols[labels[key]] = col
    v.update({"chf_cf_runs": min(runs), "chf_cf_not_pd": not_pd_total})
    return pd.DataFrame(cols), v


@_on_networks
def criteria_table(studies: dict[str, NetworkStudy], labels: dict[str, str], reason: str = ""
                   ) -> tuple[pd.DataFrame, GlueValues]:
    """The mean-free Chernoff and determinant criteria beside the Chernoff criterion, against uniform exponents.

    Parameters
    ----------
    studies : dict
        As in :func:`baseline_table`.
    labels : dict
        Network key -> column label, as in :func:`baseline_table`.
    reason : str
        As in :func:`baseline_table`.

    Returns
    -------
    table : DataFrame
        One column per network: the RMSE of CI with each rule (m), the paired MSE difference of each criterion
        against uniform exponents with its 95 % interval and the region of rule R2 (margin 5 % of the uniform
        exponents' mean MSE), m², and in the chain the middle node's mean exponent on its own density in the last
        round.
    values : dict
        Glue ``chf_crit_<net>_<rule>_d/_lo/_hi`` (m², 1 decimal), ``chf_crit_<net>_<rule>_self`` (the chain's
        middle node, last round, 3 decimals) and ``chf_crit_parity`` (largest difference of this module's
        Chernoff-exponent pipeline from the study's, m).
    """
    reason = _networks(studies, labels, reason)
    cols: dict[str, dict[str, str]] = {}
    v: dict[str, Any] = {}
    parity = 0.0
    for key in CRITERIA_NETWORKS:
        st = _key(studies, key)
        res = {r: gaussian_exchange(st, r) for r in ("ci_uniform", "ci_gaussian", "ci_mean_free", "ci_det")}
        parity = max(parity, float(np.max(np.abs(res["ci_gaussian"][0] - st.estimates["ci_gaussian"]))))
        base = network_mse(st, res["ci_uniform"][0])
        col = {RMSE_ROW.format(METHOD_LABELS[r]): f"{np.sqrt(network_mse(st, res[r][0]).mean()):.2f}" for r in res}
        for r in ("ci_gaussian", "ci_mean_free", "ci_det"):
            cmp = Comparison(network_mse(st, res[r][0]), base, METHOD_LABELS[r], METHOD_LABELS["ci_uniform"], "less",
                             _PMSE, seed=st.seed, reason=reason)
            col[f"{METHOD_LABELS[r]} − uniform ε (m², 95 %)"] = _cell(cmp)
            d, lo, hi = cmp.interval()
            v.update({f"chf_crit_{key}_{r}_d": rounded(d, 1), f"chf_crit_{key}_{r}_lo": rounded(lo, 1),
                      f"chf_crit_{key}_{r}_hi": rounded(hi, 1)})
            if st.scenario.edges is not None:
                mid = len(st.scenario.nodes) // 2
                self_eps = float(np.mean(res[r][2][:, -1, mid, mid]))
                col[f"middle node's own exponent, last round: {METHOD_LABELS[r]}"] = f"{self_eps:.3f}"
                v[f"chf_crit_{key}_{r}_self"] = rounded(self_eps, 3)
        cols[labels[key]] = col
    v["chf_crit_parity"] = roundoff(parity, -9)   # round-off (m): its bound, not its digits
    return pd.DataFrame(cols).fillna("—"), v


@_on_networks
def criteria_values(studies: dict[str, NetworkStudy], labels: dict[str, str], reason: str = "") -> GlueValues:
    """Both tables' glue values (:func:`baseline_table`, :func:`criteria_table`).

    Parameters
    ----------
    studies, labels : dict
        As in :func:`baseline_table`.
    reason : str
        As in :func:`baseline_table`.

    Returns
    -------
    dict
        The ``chf_cf_*`` values of :func:`baseline_table` and the ``chf_crit_*`` values of :func:`criteria_table`, by
        glue key.
    """
    reason = _networks(studies, labels, reason)
    return baseline_table(studies, labels, reason)[1] | criteria_table(studies, labels, reason)[1]


#: The chapter's appendix, whose markdown reads this module's glue values.
APPENDIX = Path(__file__).resolve().parents[3] / "notebooks" / "06_chernoff_fusion_appendix.ipynb"


def appendix_referenced(values: GlueValues, notebook: Path = APPENDIX) -> GlueValues:
    """The glue values that the appendix's markdown reads in a ``{glue}`` role of its own (no value nobody uses).

    Parameters
    ----------
    values : dict
        Glue key -> value.
    notebook : Path
        The notebook whose markdown is read (default the chapter's appendix).

    Returns
    -------
    dict
        The subset of ``values`` whose keys appear as ``{glue:...}`key``` roles without a notebook prefix.

    Raises
    ------
    TypeError
        ``values`` not a mapping, ``notebook`` not a path.
    ValueError
        ``notebook`` not an existing file holding a JSON object (``fusion.book._json.read_argument``), or not a
        notebook: no list ``cells`` of objects, or a markdown cell whose ``source`` is not a str or a list of str.
    """
    from collections.abc import Mapping

    instance_of(values, Mapping, "values")
    cells = read_argument(notebook, "notebook", "notebook").get("cells")
    if not isinstance(cells, list) or not all(isinstance(c, dict) for c in cells):
        raise ValueError(f"notebook {notebook}: cells must be a list of objects, got {shown(cells, 80)}")
    sources = []
    for i, c in enumerate(cells):
        if c.get("cell_type") != "markdown":
            continue
        src = c.get("source", "")
        if isinstance(src, list) and all(isinstance(line, str) for line in src):
            src = "".join(src)
        if not isinstance(src, str):
            raise ValueError(f"notebook {notebook}: cells[{i}].source must be a str or a list of str, got "
                             f"{shown(src, 80)}")
        sources.append(src)
    text = "".join(sources)
    keys = set(re.findall(r"\{glue(?::\w+)?\}`([A-Za-z0-9_]+)[:`]", text))
    return {k: v for k, v in values.items() if k in keys}
