"""Chapter 07 (Shi, Suo & Ma 2023): which noise levels could produce the published Fig. 4.

Fig. 4 shows every run's error inside its axis; these functions ask at which noise levels a figure like it is
likely (the exact compatibility of the printed axis with the registration errors' distribution, and the readings
of the figure's open choices). Documented and re-exported by :mod:`fusion.book.chapters.time_registration`, whose
API page lists them.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import pandas as pd

from fusion._counts import count
from fusion._counts import seed as check_seed
from fusion._validation import distinct, scalar, sequence, std_scalar
from fusion.book.chapters.time_registration_robustness import CI_HIGH, CI_LOW
from fusion.scenarios import time_registration as sc
from fusion.scenarios.time_registration import RegMethod

__all__ = ["fig4_compatibility", "fig4_reading_table"]

IMPROVED, TWO = RegMethod.IMPROVED, RegMethod.TWO_POINT


def _noise_levels(sigmas: object, name: str, budget: Callable[[int], object] | None = None) -> list:
    """The noise levels of a sequence argument (m), each a valid standard deviation named ``name[i]``; non-empty,
    none repeated (a table's rows are keyed by them). ``budget``, given the number of levels, is called before any
    level is read: a sweep's budget needs only their count (fix69g: 10**7 levels were each read and hashed first)."""
    items = sequence(sigmas, name)
    if not items:
        raise ValueError(f"{name} is empty (it must hold at least one noise level)")
    if budget is not None:
        budget(len(items))
    items = [std_scalar(s, f"{name}[{i}]") for i, s in enumerate(items)]  # the floats read (fuzz 22b, FR)
    distinct(items, name)
    return items


def _tuning_work(runs: int, k: int) -> None:
    """Refuse (rule 17), naming ``sigmas and runs`` or ``sigmas``, ``k`` Monte Carlos of ``runs`` runs of the two
    Fig. 4 methods (filtered) and their exact MSEs, before any run: ``tuning_by_noise``'s levels times readings,
    counted in closed form (fix69g: a list of two methods per level and reading was built first)."""
    sc._monte_carlo_work([IMPROVED, TWO], runs, *(t.size for t in sc.instants()), "sigmas and runs", "sigmas",
                         repeat=k)
    sc._exact_work((IMPROVED, TWO), {sc.instants()[1].size: k}, "sigmas")


def _levels(sigmas: Sequence[float], runs: int, seed: int, axis_max: float):  # noqa: ANN202 - a generator
    """Each noise level's Fig. 4 runs: (σ, per-run MSE of each method (rounded to 1e-10), largest expected squared
    error per instant of each method), level ``i`` drawn from ``default_rng(seed + i)`` (the arguments checked first)."""
    from fusion.registration import affine_decomposition

    seed = check_seed(seed)   # also where it meets default_rng (the AST test of rule 11)
    t1, t2 = sc.instants()

    def budget(k: int) -> None:
        # level i: seed + i, a seed too (fuzz 55 C1); rule 17 before the first level is read (fuzz 28b: runs x
        # levels had no budget; fix69g: by their count, in closed form): per level, runs of two methods, each
        # through its weight matrix (no filter per run)
        nonlocal seed
        seed = check_seed(seed, span=k - 1)
        sc._monte_carlo_work([IMPROVED, TWO], runs, t1.size, t2.size, "sigmas and runs", "sigmas", filtered=False,
                             repeat=k)

    sigmas = _noise_levels(sigmas, "sigmas", budget)
    axis_max = scalar(axis_max, "axis_max", lo=0.0, lo_open=True)
    x1, x2 = sc.truth(t1), sc.truth(t2)
    for i, s in enumerate(sigmas):
        rng = np.random.default_rng(seed + i)
        z = x1 + float(s) * rng.standard_normal((runs, t1.size))
        mse, peak = {}, {}
        for n in (IMPROVED, TWO):
            dec = affine_decomposition(sc.registrar(n, t1, t2, float(s)), x1)
            mse[n] = np.round(np.mean((dec.f0 + (z - x1) @ dec.A.T - x2) ** 2, axis=1), 10)
            peak[n] = float(np.max((dec.f0 - x2) ** 2 + float(s) ** 2 * np.sum(dec.A**2, axis=1)))
        yield s, mse, peak


def fig4_compatibility(sigmas: Sequence[float], runs: int, seed: int, axis_max: float, block: int = 20) -> pd.DataFrame:
    """Which noise levels could produce a Fig. 4 like the published one (every run inside the axis).

    For each σ, ``runs`` simulated runs of the two Fig. 4 methods give the per-run probability
    ``p`` that both MSEs lie inside ``[0, axis_max]``, and that in addition the improved method
    wins; runs are independent, so a ``block``-run figure has every run inside with probability
    ``p**block``. The runs use each method's exact affine decomposition ``f0 + A z`` (the Kalman
    filter assumes the true σ), so ``runs`` can be large; the 95 % Clopper-Pearson interval of ``p``
    is raised to the power ``block`` for the interval of ``p**block``.

    Parameters
    ----------
    sigmas : sequence of float
        Noise levels (m).
    runs : int
        Runs per level; ``runs`` x levels is held to the work budget (``fusion._limits.MAX_WORK``, refused by
        name, ``sigmas and runs``, before the first level).
    seed : int
        Seed of the first level (``seed + i`` for the i-th).
    axis_max : float
        Top of Fig. 4's y-axis (m²).
    block : int
        Runs per figure.

    Returns
    -------
    DataFrame
        Index σ; per-run probabilities and the ``block``-run probabilities with 95 % intervals, 3 decimals.
    """
    from scipy import stats

    runs, seed, block = count(runs, "runs"), check_seed(seed), count(block, "block")   # seed: rule 11, named
    rows = {}
    for s, mse, _ in _levels(sigmas, runs, seed, axis_max):
        a, b = mse[IMPROVED], mse[TWO]
        inside = (a <= axis_max) & (b <= axis_max)
        k_in, k_both = int(inside.sum()), int((inside & (a < b)).sum())
        ci = stats.binomtest(k_in, runs).proportion_ci(0.95, method="exact")
        p_in, p_both = k_in / runs, k_both / runs
        rows[float(s)] = {"runs": runs, "P(run inside the axis)": p_in,
                          f"P({block} runs inside)": p_in**block,
                          CI_LOW: ci.low**block, CI_HIGH: ci.high**block,
                          "P(run inside and improved wins)": p_both,
                          f"P({block} runs inside and ordered)": p_both**block}
    out = pd.DataFrame(rows).T
    out.index.name = "σ (m)"
    out["runs"] = out["runs"].astype(int)
    return out.round(3)


def fig4_reading_table(sigmas: Sequence[float], runs: int, seed: int, axis_max: float,
                       block: int = 20) -> pd.DataFrame:
    """Fig. 4's y-axis under three readings of what it plots, against the noise level.

    Readings: (i) x-axis = Monte-Carlo run, y = that run's MSE (the chapter's primary reading;
    :func:`fig4_compatibility`); (ii) x-axis = run, y = that run's root-mean-square error;
    (iii) x-axis = the registration instant, y = the *expected* squared error at that instant
    (no randomness: the curve fits iff its maximum is inside the axis).

    Parameters
    ----------
    sigmas : sequence of float
        Noise levels (m).
    runs : int
        Runs per level for readings (i)-(ii); ``runs`` x levels is held to the work budget
        (``fusion._limits.MAX_WORK``, refused by name, ``sigmas and runs``, before the first level).
    seed : int
        Seed of the first level.
    axis_max : float
        Top of Fig. 4's y-axis.
    block : int
        Runs per figure.

    Returns
    -------
    DataFrame
        Index σ; the probability that a ``block``-run figure fits under (i) and (ii), and the largest
        expected squared error per instant of each Fig. 4 method under (iii), 3 decimals.
    """
    runs, seed, block = count(runs, "runs"), check_seed(seed), count(block, "block")   # seed: rule 11, named
    rows = {}
    for s, mse, peak in _levels(sigmas, runs, seed, axis_max):
        a, b = mse[IMPROVED], mse[TWO]
        p_mse = float(np.mean((a <= axis_max) & (b <= axis_max)))
        p_rmse = float(np.mean((np.sqrt(a) <= axis_max) & (np.sqrt(b) <= axis_max)))
        rows[float(s)] = {f"(i) run MSE: P({block} runs inside)": p_mse**block,
                          f"(ii) run RMSE: P({block} runs inside)": p_rmse**block,
                          "(iii) per instant: largest E[sq. error], improved (m²)": peak[IMPROVED],
                          "(iii) per instant: largest E[sq. error], two-point (m²)": peak[TWO]}
    out = pd.DataFrame(rows).T
    out.index.name = "σ (m)"
    return out.round(3)
