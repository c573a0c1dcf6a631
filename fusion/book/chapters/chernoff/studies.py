"""The chapter's studies, cached on (seed, runs, scenario) so that the notebook and the evidence compute each once.

Part of :mod:`fusion.book.chapters.chernoff` (chapter 06, patent CN107330468B), which re-exports its public names."""

from __future__ import annotations

from fusion._counts import seed as check_seed
from fusion.book.study_cache import study_cache
from typing import Any

import numpy as np

from fusion.book.tables import rounded
from fusion.scenarios.fusion_networks import Network, NetworkStudy, premise_scenarios, run_network_study
from fusion.scenarios.range_bearing import RangeBearingScenario, TrackingRun, monte_carlo
from fusion.book.chapters.chernoff.guard import DesignStudy, design_study, guarded_runs
from fusion.book.chapters.chernoff.gaussian import GaussianChecks, common_information_check, gaussian_checks
from fusion.book.chapters.chernoff.importance import IsVarianceStudy, is_variance_study
from fusion.book.chapters.chernoff.premise import (PREMISE_MORE_RUNS, PREMISE_NETWORKS, _check_scenarios,
                                                   _network_scenarios, _pcmp, _premise_work, premise_studies)
from fusion.book.chapters.chernoff.settings import STUDY_RUNS, STUDY_WORKERS, study_scenario
from fusion.book.glue import GlueValues
from fusion.book.ledger import MIN_RUNS
from fusion._counts import count

__all__ = ["tracking_study", "design", "checks_study", "common_study", "isv_study", "premise_study",
           "premise_mixture_scaled"]


# --------------------------------------------------------------------------- evidence of the claim file
# Every record of book/claims/cn107330468b.yaml names one of the functions below as its evidence. Each takes the
# reading's settings (from the claim file), the chapter's root seed and its run count, and returns the evidence;
# the studies behind them are cached on (seed, runs, scenario), so the notebook, which calls the same study
# functions, computes each study once.

@study_cache(maxsize=2)
def _tracking(seed: int, runs: int, sc: RangeBearingScenario) -> tuple[list[TrackingRun], list[TrackingRun]]:
    plain = monte_carlo(sc, seed, runs, workers=STUDY_WORKERS)
    return plain, guarded_runs(plain, sc, seed)


def tracking_study(seed: int, runs: int = STUDY_RUNS, sc: RangeBearingScenario | None = None,
                   ) -> tuple[list[TrackingRun], list[TrackingRun]]:
    """The tracking study, without and with the collapse guard (cached: computed once per seed, runs, scenario).

    Parameters
    ----------
    seed : int
        Root seed of the runs (the same seeds for every method).
    runs : int
    sc : RangeBearingScenario, optional
        Default :func:`study_scenario`.

    Returns
    -------
    plain, guarded : list of TrackingRun
        ``monte_carlo(sc, seed, runs)`` and :func:`guarded_runs` of it (do not modify them: they are cached).
    """
    seed = check_seed(seed)
    runs = count(runs, "runs")
    return _tracking(seed, runs, study_scenario() if sc is None else sc)


@study_cache(maxsize=2)
def _design(seed: int, runs: int, sc: RangeBearingScenario) -> DesignStudy:
    return design_study(sc, seed, runs)


def design(seed: int, runs: int = STUDY_RUNS, sc: RangeBearingScenario | None = None) -> DesignStudy:
    """:func:`design_study` of the study's scenario (or ``sc``), cached.

    Its "more particles" design draws the default ``n_initial`` of :func:`design_study` (the larger of 10,000 and
    5 × ``sc.n_particles``), so every valid scenario has a design.

    Parameters
    ----------
    seed, runs : int
        Seed and runs of the study.
    sc : RangeBearingScenario, optional
        Default: the study's scenario.

    Returns
    -------
    DesignStudy
        First-update effective sample sizes of the nodes under the three designs and their particle-likelihood costs.
    """
    seed = check_seed(seed)
    runs = count(runs, "runs")
    return _design(seed, runs, study_scenario() if sc is None else sc)


@study_cache(maxsize=2)
def checks_study(seed: int) -> GaussianChecks:
    """:func:`gaussian_checks` with ``default_rng(seed)``, cached.

    Parameters
    ----------
    seed : int
        Seed of the generator (an integer, 0 or more).

    Returns
    -------
    GaussianChecks
        Largest errors of the exact checks K1-K5 on the default 100 pairs and 20 triples drawn from this seed.
    """
    seed = check_seed(seed)   # an integer seed (rule 11), named
    return gaussian_checks(np.random.default_rng(seed))


@study_cache(maxsize=2)
def common_study(seed: int) -> tuple[bool, float, float]:
    """:func:`common_information_check` with ``default_rng(seed + 5)``, cached.

    Parameters
    ----------
    seed : int
        Seed of the study (an integer, 0 or more; the generator is seeded with ``seed + 5``).

    Returns
    -------
    tuple of (bool, float, float)
        What :func:`common_information_check` returns.
    """
    seed = check_seed(seed, span=5)   # an integer seed (rule 11), named; seed + 5 a seed too (fuzz 55 C1)
    return common_information_check(np.random.default_rng(seed + 5))


@study_cache(maxsize=2)
def isv_study(seed: int) -> IsVarianceStudy:
    """:func:`is_variance_study` with ``default_rng(seed + 3)``, cached.

    Parameters
    ----------
    seed : int
        Seed of the study (an integer, 0 or more; the generator is seeded with ``seed + 3``).

    Returns
    -------
    IsVarianceStudy
        Ĵ's bias table over ω and the finite second- and third-moment regions of the weights, from this seed.
    """
    seed = check_seed(seed, span=3)   # an integer seed (rule 11), named; seed + 3 a seed too (fuzz 55 C1)
    return is_variance_study(np.random.default_rng(seed + 3))


def _premise_more(runs: int) -> dict[str, int]:
    """The networks :func:`premise_study` runs more often at ``runs`` runs per network -> their runs."""
    return {k: n * runs // STUDY_RUNS for k, n in PREMISE_MORE_RUNS.items()}


@study_cache(maxsize=2)
def _premise(seed: int, runs: int, scenarios: tuple[tuple[str, Any], ...] | None) -> dict[str, NetworkStudy]:
    return premise_studies(seed + 10, runs, None if scenarios is None else dict(scenarios), more=_premise_more(runs))


def premise_study(seed: int, runs: int = STUDY_RUNS, scenarios: dict[str, Any] | None = None) -> dict[str, NetworkStudy]:
    """The designed networks (:func:`premise_studies` with seed ``seed + 10``), cached.

    Parameters
    ----------
    seed : int
        The chapter's root seed.
    runs : int
        Runs per network; the networks of :data:`PREMISE_MORE_RUNS` run ``runs / 100`` times theirs.
    scenarios : dict, optional
        Other networks (tests).

    Returns
    -------
    dict
        Network key -> NetworkStudy (do not modify: cached).

    Raises
    ------
    TypeError
        ``seed`` or ``runs`` not an integer, ``scenarios`` not a mapping of NetworkScenario.
    ValueError
        ``seed`` negative, ``runs`` below 1, ``scenarios`` without one of :data:`PREMISE_NETWORKS`; every network's
        runs together beyond their work budget (the entry of ``fusion._limits.STUDY_WORK`` for the reseeding sweep's
        1,000 runs a network), before the first network runs, naming ``runs`` and ``scenarios``.
    """
    # network j runs with seed + 10 + j: each a seed, checked at entry (fuzz 55 C1: refused after five networks ran)
    seed = check_seed(seed, span=10 + len(PREMISE_NETWORKS) - 1)
    runs = count(runs, "runs")
    scs = None if scenarios is None else _check_scenarios(scenarios)
    # every network counted at entry, before the cache and the first network (fuzz 42b C5)
    _premise_work(_network_scenarios(scs), runs, _premise_more(runs))
    return _premise(seed, runs, None if scs is None else tuple(scs.items()))


@study_cache(maxsize=2)
def premise_mixture_scaled(seed: int, runs: int = STUDY_RUNS, factor: int = 10) -> GlueValues:
    """Record chf-premise-mixture's primary comparison at ``factor`` times the runs, on the chapter's own seed.

    The range-only network with the seed :func:`premise_study` gives it (``seed + 10`` plus its index in
    :data:`PREMISE_NETWORKS`), ``factor * runs`` runs (run ``r`` is the ``r``-th child of the seed's ``SeedSequence``, so the
    first ``runs`` are the chapter's own runs, extended). The reseeding sweep's run at more runs uses a seed of its own; this one answers
    whether the chapter's borderline mean gain holds on its own seed.

    Parameters
    ----------
    seed, runs : int
        The chapter's root seed and runs per network.
    factor : int
        Multiple of the runs (an integer type, 1 or more); ``factor * runs`` at least
        :data:`~fusion.book.ledger.MIN_RUNS` (rule R4: the comparison takes no ``reason`` for fewer runs).

    Returns
    -------
    dict
        Glue values ``chf_pr_ngx_*``: ``runs``, ``seed`` (int), ``d``/``lo``/``hi`` (mixture fusion − CI of Gaussians,
        mean and paired 95 % interval, m²), ``margin`` (R2's, m²), ``status`` (the rulebook's), ``median`` (m²; these
        five rounded as the comparison stores its numbers, :meth:`~fusion.book.ledger.Comparison.at_resolution`),
        ``win`` (share of runs in which the mixtures are more accurate) and ``hill`` (the differences' Hill index).

    Raises
    ------
    TypeError
        An argument not an integer.
    ValueError
        ``seed`` negative, ``runs`` or ``factor`` below 1, or ``runs * factor`` below
        :data:`~fusion.book.ledger.MIN_RUNS`.
    """
    seed = check_seed(seed, span=10 + PREMISE_NETWORKS.index(Network.NON_GAUSSIAN))   # its network's seed (fuzz 55 C1)
    runs = count(runs, "runs")
    factor = count(factor, "factor")
    if runs * factor < MIN_RUNS:  # fuzz 24b D7: rule R4 asked for a reason, which this comparison does not take
        raise ValueError(f"runs * factor must be at least {MIN_RUNS} (rule R4: the comparison takes no reason, so it "
                         f"needs the rulebook's runs), got runs = {runs}, factor = {factor}")
    j = PREMISE_NETWORKS.index(Network.NON_GAUSSIAN)
    st = run_network_study(premise_scenarios()[Network.NON_GAUSSIAN], seed + 10 + j, factor * runs)
    c = _pcmp(st, "chernoff_pso", "ci_gaussian")
    jd = c.judgement()
    d = st.mse("chernoff_pso") - st.mse("ci_gaussian")
    r = c.at_resolution   # the comparison's own rounding: further digits are the runs' round-off (kernel-dependent)
    return {"chf_pr_ngx_runs": int(st.runs), "chf_pr_ngx_seed": int(st.seed), "chf_pr_ngx_d": r(jd.estimate),
            "chf_pr_ngx_lo": r(jd.low), "chf_pr_ngx_hi": r(jd.high), "chf_pr_ngx_margin": r(jd.margin),
            "chf_pr_ngx_status": jd.status, "chf_pr_ngx_median": r(float(np.median(d))),
            "chf_pr_ngx_win": rounded(float(jd.share)), "chf_pr_ngx_hill": rounded(float(jd.tail_index), 2)}
