"""Consistency of the fused covariances: NEES per step, by start and over the runs."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
from scipy.stats import chi2
from numpy.typing import ArrayLike

from fusion._limits import LOOP_STEP, loop_work, recorded_as
from fusion._structures import same_keys
from fusion._validation import as_array, as_covariance, as_mask, as_rng, count, flag, scalar, shown
from fusion.book.tables import rounded, roundoff
from fusion.book.glue import GlueValues
from fusion.book.style import METHOD_LABELS
from fusion.filtering.kalman import cv_model, rmse_per_step
from fusion.filtering.kalman import nees as kalman_nees
from fusion.filtering.tracks import _named_track, fuse_tracks
from fusion.scenarios import two_sensor
from fusion.scenarios.two_sensor import NeesRule
from fusion.book.chapters.ci.text import nees_band
from fusion.book.chapters.ci.checks import _entries
from fusion.book.chapters.ci.records import NeesPerStep, SplitExactness, stream_of
from fusion._shown import shown
from fusion.book.chapters._defaults import study_defaults

__all__ = ["nees_numbers", "nees_per_step", "nees_step_band", "nees_start_table", "nees_start_numbers", "nees_table",
           "model_rmse"]


#: The rules whose mean NEES :func:`nees_numbers` glues.
_NEES_READ = (NeesRule.CONVEX, NeesRule.CI_HALF, NeesRule.PRINTED, NeesRule.SPLIT, NeesRule.LOCAL)


def nees_numbers(nees: Mapping[str, float], nees_runs: int) -> GlueValues:
    """The NEES values the prose quotes (glue keys ``ci_nees_*``).

    Parameters
    ----------
    nees : mapping
        Rule -> mean NEES (``mean_nees`` of :func:`fusion.scenarios.two_sensor.nees_study`).
    nees_runs : int
        Runs averaged.

    Returns
    -------
    dict
        Glue key -> value (2 decimals), and the 97.5 % point of the mean NEES of a consistent estimator.

    Raises
    ------
    TypeError
        ``nees`` is not a mapping, or a value read here not a number; ``nees_runs`` not an integer.
    ValueError
        ``nees`` lacks a rule read here, or a value is not finite; ``nees_runs`` not positive.

    References
    ----------
    * Wang, W., & Tang, Y. (2024), the chapter's source (see the bibliography).
    """
    nees = _entries(nees, "nees", _NEES_READ, "two_sensor.nees_study (its mean_nees)", nonnegative=True)
    NEES_RUNS = count(nees_runs, "nees_runs")
    return {"ci_nees_convex": rounded(nees[NeesRule.CONVEX], 2), "ci_nees_ci": rounded(nees[NeesRule.CI_HALF], 2),
            "ci_nees_printed": rounded(nees[NeesRule.PRINTED], 2),
            "ci_nees_split": rounded(nees[NeesRule.SPLIT], 2),
            "ci_nees_local": rounded(nees[NeesRule.LOCAL], 2), "ci_nees_runs": NEES_RUNS,
            "ci_nees_band_100": rounded(nees_band(NEES_RUNS), 2)}


#: Units of a step of :func:`nees_per_step` (two local filters' step, every rule's fusion, split CI's search among
#: them): twice the 2.24 ms measured (4.48 and 4.57 CPU-s for 2,000 steps of 2 runs, from the true and a drawn
#: velocity; ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the machine shared and loaded; book audit 76).
_NEES_STEP = 450 * LOOP_STEP
#: Units of a run and step of :func:`nees_per_step`: twice the 5.2 us measured (2.44-2.61 CPU-s for 261 steps of
#: 1,500 runs; book audit 76).
_NEES_RUN_STEP = 1_040


def nees_per_step(rng: np.random.Generator, Q: ArrayLike, R1: ArrayLike, R2: ArrayLike, x_start: ArrayLike,
                  n_steps: int, runs: int, T: float = 1.0, velocity_sigma: float = 100.0,
                  random_velocity: bool = False) -> NeesPerStep:
    r"""Mean NEES at every step of the rules :func:`fusion.scenarios.two_sensor.nees_study` averages.

    The same targets, filters and draws as ``nees_study`` (process noise, then sensor 1's noise, then
    sensor 2's), so with ``random_velocity=False`` the mean over the steps after 20 s is its value. With
    ``random_velocity=True`` each run's target starts with a velocity drawn from the filters' prior,
    ``x_start``'s velocity plus :math:`N(0, \sigma_v^2 I)` per axis (drawn after the noise, so the noise
    is the same), while the filters still start at ``x_start``'s velocity: their initial covariance is
    then the true one.

    Parameters
    ----------
    rng : numpy.random.Generator
    Q : array_like, shape (4, 4)
    R1, R2 : array_like, shape (2, 2)
        Measurement covariances (m², diagonal).
    x_start : array_like, shape (4,)
        Initial true state (its velocity is the filters' initial velocity).
    n_steps, runs : int
        Steps and runs, within the memory budget of ``nees_study`` and a work budget of this function's own
        measured steps (about 2,200 steps of 2 runs; a ValueError names them).
    T : float
        Sampling period (s).
    velocity_sigma : float
        Prior velocity standard deviation (m/s), common to both sensors.
    random_velocity : bool
        Draw each target's initial velocity from the prior (``True``) or start at the true one.

    Returns
    -------
    NeesPerStep
        A mapping: rule (the keys of ``nees_study``) -> NEES averaged over the runs at each step, shape
        (n_steps,); it records the start, the runs, the settings and the generator's state when the runs started,
        which :func:`nees_start_table` and :func:`nees_start_numbers` check.

    References
    ----------
    * Bar-Shalom, Li & Kirubarajan (2001), *Estimation with Applications to Tracking and Navigation*, §5.4.2.
    """
    rng = as_rng(rng)
    stream = stream_of(rng)   # before any draw: two runs of one seed record the same one
    R1, R2 = as_covariance(R1, 2, "R1"), as_covariance(R2, 2, "R2")
    Q = as_covariance(Q, 4, "Q")
    x_start = as_array(x_start, "x_start", shape=(4,))
    random_velocity = flag(random_velocity, "random_velocity")
    n_steps, runs = count(n_steps, "n_steps"), count(runs, "runs")
    from fusion._validation import allocation
    from fusion.scenarios.two_sensor.study import _nees_work

    allocation((runs, n_steps, 4), "n_steps and runs")   # the budgets of nees_study, the same runs (fuzz 24c SZ)
    # its own steps, heavier than nees_study's (book audit 76: at nees_study's weights, 58 loop steps and 250 units a
    # run, its edge of about 17,000 steps of 2 runs would run about 38 CPU-s)
    loop_work((n_steps,), _NEES_RUN_STEP * runs, "n_steps and runs", step=_NEES_STEP)
    _nees_work(n_steps, runs)
    T = scalar(T, "T", lo=0.0, lo_open=True)
    velocity_sigma = scalar(velocity_sigma, "velocity_sigma", lo=0.0, lo_open=True)
    model = cv_model(T)
    F, H = model.F, model.H
    Xm = two_sensor.model_truth(rng, F, Q, x_start, n_steps, runs)
    noise = [rng.standard_normal((runs, n_steps, 2)) * np.sqrt(np.diag(R)) for R in (R1, R2)]
    if random_velocity:
        d = np.zeros((runs, 4))
        d[:, [1, 3]] = rng.standard_normal((runs, 2)) * velocity_sigma
        for k in range(n_steps):   # the offset moves with the model: F^k d
            Xm[:, k] += d
            d = d @ F.T
    P0d = np.diag([0.0, velocity_sigma**2, 0.0, velocity_sigma**2])
    tracks = []
    for R, v in zip((R1, R2), noise):
        z = Xm[:, :, [0, 2]] + v
        x0 = np.column_stack([z[:, 0, 0], np.zeros(runs), z[:, 0, 1], np.zeros(runs)]) + x_start * [0, 1, 0, 1]
        tracks.append(_named_track("velocity_sigma", z, F, H, Q, R, x0, P0d, np.diag([R[0, 0], 0.0, R[1, 1], 0.0])))
    out = {NeesRule.LOCAL: kalman_nees(tracks[0].est - Xm, tracks[0].gains.P).mean(axis=0)}
    for name, rule, w in two_sensor.NEES_RULES:
        f = fuse_tracks(tracks[0], tracks[1], rule, omega=w)
        out[name] = kalman_nees(f.est - Xm, f.P).mean(axis=0)
    return NeesPerStep(out, random_velocity, runs, T, velocity_sigma, Q, R1, R2, x_start, stream)


def nees_step_band(runs: int, n: int = 4) -> tuple[float, float]:
    """Central 95 % band of one step's NEES averaged over ``runs`` runs of a consistent estimator.

    Parameters
    ----------
    runs : int
        Runs averaged at the step.
    n : int
        State dimension.

    Returns
    -------
    tuple of float
        ``chi2.ppf(0.025, n * runs) / runs`` and ``chi2.ppf(0.975, n * runs) / runs`` (the upper point is
        the one ``nees_band`` returns).

    References
    ----------
    Bar-Shalom, Li & Kirubarajan (2001), *Estimation with Applications to Tracking and Navigation*, §5.4.2.
    """
    runs, n = count(runs, "runs"), count(n, "n")
    return float(chi2.ppf(0.025, n * runs) / runs), nees_band(runs, n)


def _same_runs(true_start: object, random_start: object, runs: int, T: float) -> None:
    """Check what the results of :func:`nees_per_step` record (issue 35, swaps; fuzz 26c q6): ``true_start`` from
    the true initial velocity, ``random_start`` from a drawn one, each averaging ``runs`` runs (their period ``T``:
    ``_per_step``), and the two of the same settings and the same generator state (their noise is then the same
    draws). A plain mapping records none of it and is not checked."""
    recorded = [(name, d) for name, d in (("true_start", true_start), ("random_start", random_start))
                if isinstance(d, NeesPerStep)]
    for name, d in recorded:
        want = name == "random_start"
        if d.random_velocity != want:
            raise ValueError(f"{name} must be the runs from {'a random' if want else 'the true'} initial velocity "
                             f"(nees_per_step with random_velocity={want}), got those with random_velocity={not want}"
                             " (true_start and random_start swapped, or one start twice?)")
        if d.runs != runs:
            raise ValueError(f"runs = {runs} must be the number of runs {name} averages ({d.runs})")
    if len(recorded) == 2:
        a, b = true_start, random_start
        assert isinstance(a, NeesPerStep) and isinstance(b, NeesPerStep)
        for field in ("Q", "R1", "R2", "x_start", "velocity_sigma"):
            if not np.array_equal(getattr(a, field), getattr(b, field)):
                raise ValueError(f"random_start's runs have another {field} than true_start's: pass the two starts "
                                 "of one study (nees_per_step with the same settings)")
        if a.stream != b.stream:
            raise ValueError("random_start's runs start from another generator state than true_start's (another "
                             "seed, or a generator already drawn from): the two starts must share their draws "
                             "(nees_per_step with two generators of one seed)")


def _exact_case(exact: object, true_start: object, T: float, t_steady: float) -> None:
    """Check that a :class:`SplitExactness` is of the runs' case: ``T``, ``t_steady``, their steps and, where
    ``true_start`` records them, ``Q``, the prior and ``R`` (one of the runs' ``R1``, ``R2``)."""
    if not isinstance(exact, SplitExactness):
        return
    steps = next(iter(true_start.values())).size if isinstance(true_start, NeesPerStep) else None
    for what, mine, theirs in (("T", T, exact.T), ("t_steady", t_steady, exact.t_steady)):
        if not recorded_as(mine, theirs):
            raise ValueError(f"exact is split_ci_exactness at {what} = {theirs:g} s, the runs' is {what} = {mine:g} s")
    if steps is not None and exact.n_steps != steps:
        raise ValueError(f"exact is split_ci_exactness of {exact.n_steps} steps, the runs' are {steps}")
    if isinstance(true_start, NeesPerStep):
        if not np.array_equal(exact.Q, true_start.Q) or exact.velocity_sigma != true_start.velocity_sigma:
            raise ValueError("exact is split_ci_exactness of another Q or velocity_sigma than the runs of true_start")
        if not any(np.array_equal(exact.R, R) for R in (true_start.R1, true_start.R2)):
            raise ValueError("exact is split_ci_exactness of an R that is neither sensor's of the runs (R1, R2)")


def _per_step(true_start: object, random_start: object, T: float, t_steady: float) -> tuple[float, float]:
    """Check the per-step NEES of both starts (fuzz 19, F9): two mappings with the same rules (a rule of
    METHOD_LABELS), one finite non-negative value per step, the same steps in every array, ``T`` the period the runs
    record (a :class:`NeesPerStep`; checked first, fuzz 39b C3) and ``t_steady`` splitting them (steps before and
    after it), so that no mean is taken over no step; ``(T, t_steady)`` as floats."""
    for name, d in (("true_start", true_start), ("random_start", random_start)):
        if not isinstance(d, Mapping):
            raise TypeError(f"{name} must be a mapping of rule -> NEES per step (nees_per_step), got {type(d).__name__}")
        if not d:
            raise ValueError(f"{name} is empty (it must map each rule to its NEES per step)")
    same_keys(random_start, "random_start", true_start, "true_start")
    T = scalar(T, "T", lo=0.0, lo_open=True)
    t_steady = scalar(t_steady, "t_steady", lo=0.0, lo_open=True)
    steps = None
    for name, d in (("true_start", true_start), ("random_start", random_start)):
        for rule, v in d.items():
            if not isinstance(rule, str) or rule not in METHOD_LABELS:
                raise ValueError(f"{name} holds a key that is not a rule: {shown(rule)}")
            v = as_array(v, f"{name}[{shown(rule)}]", ndim=1, nonnegative=True)   # a NEES (fuzz 24c, NEG)
            if steps is None:
                steps = v.size
            elif v.size != steps:
                raise ValueError(f"{name}[{shown(rule)}] holds {v.size} steps, the other arrays of true_start and "
                                 f"random_start {steps}: both starts must cover the same steps")
    assert steps is not None
    for name, d in (("true_start", true_start), ("random_start", random_start)):   # T first: the t_steady check
        if isinstance(d, NeesPerStep) and not recorded_as(T, d.T):                  # reads it (fuzz 39b C3)
            raise ValueError(f"T = {T:g} s must be the sampling period of {name}'s runs ({d.T:g} s)")
    if not 0.0 < t_steady <= (steps - 1) * T:
        raise ValueError(f"t_steady = {t_steady:g} s must leave steps before and after it: the {steps} steps "
                         f"of true_start run from 0 to {(steps - 1) * T:g} s (T = {T:g} s)")
    return T, t_steady


@study_defaults("true_start", "T", "t_steady")  # a default the study does not fit, named by it (fuzz 36b D1, 38b D1)
def nees_start_table(true_start: Mapping[str, np.ndarray], random_start: Mapping[str, np.ndarray], runs: int,
                     T: float = 1.0, t_steady: float = 20.0) -> pd.DataFrame:
    """Per-step NEES against its 95 % band, from the true and from a random initial velocity (appendix table).

    Parameters
    ----------
    true_start, random_start : mapping of str to ndarray, shape (K,)
        Rule -> NEES averaged over the runs at each step (:func:`nees_per_step`), from the true
        initial velocity and from one drawn from the filters' prior. The results of :func:`nees_per_step`
        (:class:`NeesPerStep`) record their start, runs, settings and generator state, and are checked: the two
        swapped, one start twice, or runs of other settings or of another seed are refused. A plain mapping records
        none of it and is not checked.
    runs : int
        Runs averaged at each step (sets the band, :func:`nees_step_band`); the runs the results record.
    T : float
        Sampling period (s), that of the results' runs.
    t_steady : float
        Start of the steady-state average (s).

    Returns
    -------
    pandas.DataFrame
        One row per rule: mean NEES before and after ``t_steady`` and the steps whose mean NEES lies in
        the band (after ``t_steady``, and over all steps), for each start.

    Raises
    ------
    TypeError
        ``true_start`` or ``random_start`` not a mapping, or a value not an array of numbers.
    ValueError
        ``true_start`` or ``random_start`` empty, a key not a rule, their keys differ, their arrays not of one
        length of finite values, or ``t_steady`` leaves no step before or after it; a :class:`NeesPerStep` of the
        other start, of other runs, settings or generator state than the other one, or than ``runs`` and ``T``.
    """
    T, t_steady = _per_step(true_start, random_start, T, t_steady)
    runs = count(runs, "runs")
    _same_runs(true_start, random_start, runs, T)
    lo, hi = nees_step_band(runs)
    rows = {}
    for rule in true_start:
        row = {}
        for start, d in (("true v₀", true_start), ("random v₀", random_start)):
            v = np.asarray(d[rule], dtype=float)
            steady = np.arange(v.size) * T >= t_steady
            inside = (v >= lo) & (v <= hi)
            row[(start, f"NEES, t < {t_steady:g} s")] = round(float(v[~steady].mean()), 2)
            row[(start, f"NEES, t ≥ {t_steady:g} s")] = round(float(v[steady].mean()), 2)
            row[(start, f"steps in band, t ≥ {t_steady:g} s")] = f"{int(inside[steady].sum())}/{int(steady.sum())}"
            row[(start, "steps in band, all")] = f"{int(inside.sum())}/{v.size}"
        rows[METHOD_LABELS[rule]] = row
    df = pd.DataFrame(rows).T
    df.columns = pd.MultiIndex.from_tuples(df.columns)
    return df


#: The rules whose per-step NEES :func:`nees_start_numbers` glues.
_START_READ = (NeesRule.SPLIT, NeesRule.LOCAL, NeesRule.CI_HALF, NeesRule.CONVEX, NeesRule.PRINTED)


@study_defaults("true_start", "T", "t_steady")  # a default the study does not fit, named by it (fuzz 36b D1, 38b D1)
def nees_start_numbers(true_start: Mapping[str, np.ndarray], random_start: Mapping[str, np.ndarray], runs: int,
                       exact: Mapping[str, float], T: float = 1.0, t_steady: float = 20.0) -> GlueValues:
    """The numbers the appendix quotes from the per-step NEES and split CI's exactness (glue keys ``ci_nps_*``).

    Parameters
    ----------
    true_start, random_start : mapping of str to ndarray, shape (K,)
        As in :func:`nees_start_table`.
    runs : int
        Runs averaged at each step.
    exact : mapping of str to float
        :func:`split_ci_exactness`, at the same ``T``, ``t_steady``, steps and noises as the runs: its result
        (:class:`SplitExactness`) records them and is checked against ``T``, ``t_steady``, the steps and what
        ``true_start`` records (``Q``, the prior, ``R`` one of the runs' ``R1`` and ``R2``). A plain mapping is not
        checked.
    T, t_steady : float
        Sampling period and start of the steady-state average (s).

    Returns
    -------
    dict
        Glue key -> value (the table itself under ``ci_tab_nees_start``).

    Raises
    ------
    TypeError
        As :func:`nees_start_table`; ``exact`` not a mapping.
    ValueError
        As :func:`nees_start_table`; ``true_start`` lacks a rule read here, or ``exact`` a value read here, or
        ``exact`` is a :class:`SplitExactness` of another case.
    """
    runs = count(runs, "runs")
    T, t_steady = _per_step(true_start, random_start, T, t_steady)
    _same_runs(true_start, random_start, runs, T)
    _exact_case(exact, true_start, T, t_steady)
    missing = [r for r in _START_READ if r not in true_start]
    if missing:
        raise ValueError(f"true_start lacks the rules {missing} (a result of nees_per_step holds them)")
    exact = _entries(exact, "exact", ("rel_diff_random", "nees_random_min", "nees_random_max", "nees_true_first",
                              "nees_true_transient", "nees_true_steady", "nees_true_steady_min"), "split_ci_exactness",
                      nonnegative=True)
    lo, hi = nees_step_band(runs)
    split, loc = NeesRule.SPLIT, NeesRule.LOCAL
    out: dict[str, Any] = {"ci_nps_lo": rounded(lo, 2), "ci_nps_hi": rounded(hi, 2), "ci_nps_runs": runs,
                           "ci_tab_nees_start": nees_start_table(true_start, random_start, runs, T, t_steady)}
    for tag, d in (("t", true_start), ("r", random_start)):
        steady = np.arange(np.asarray(d[split]).size) * T >= t_steady
        for key, rule in (("split", split), ("local", loc), ("ci", NeesRule.CI_HALF), ("cvx", NeesRule.CONVEX),
                          ("printed", NeesRule.PRINTED)):
            v = np.asarray(d[rule], dtype=float)
            out[f"ci_nps_{key}_{tag}_in"] = f"{int(((v >= lo) & (v <= hi)).sum())} of {v.size}"
            if key == "split":   # its mean after and before the start-up
                out[f"ci_nps_{key}_{tag}"] = rounded(float(v[steady].mean()), 2)
                out[f"ci_nps_{key}_{tag}_start"] = rounded(float(v[~steady].mean()), 2)
    out.update({"ci_nps_ex_rel": roundoff(exact["rel_diff_random"]),   # round-off: its digits vary with the BLAS kernel
                "ci_nps_ex_rmin": rounded(exact["nees_random_min"], 6), "ci_nps_ex_rmax": rounded(exact["nees_random_max"], 6),
                "ci_nps_ex_first": rounded(exact["nees_true_first"], 2),
                "ci_nps_ex_trans": rounded(exact["nees_true_transient"], 2),
                "ci_nps_ex_steady": rounded(exact["nees_true_steady"], 4),
                "ci_nps_ex_steady_min": rounded(exact["nees_true_steady_min"], 4)})
    return out


def nees_table(nees: Mapping[str, float]) -> pd.DataFrame:
    """Mean NEES by rule (:func:`fusion.scenarios.two_sensor.nees_study`) as a one-column table (2 decimals).

    Parameters
    ----------
    nees : mapping
        Rule -> mean NEES (dimensionless; 4 for a consistent estimator of the 4-state).

    Returns
    -------
    pandas.DataFrame
        One row per rule (its label), one column ``"mean NEES (consistent: ≈ 4 or less)"``, 2 decimals.

    Raises
    ------
    TypeError
        ``nees`` is not a mapping, or a value is not a number.
    ValueError
        ``nees`` is empty, a key is not a rule, or a value is not finite and non-negative.
    """
    if not isinstance(nees, Mapping):
        raise TypeError(f"nees must be a mapping of rule -> mean NEES, got {type(nees).__name__}")
    if not nees:
        raise ValueError("nees is empty (it must map each rule to its mean NEES)")
    read = {}
    for rule, v in nees.items():
        if not isinstance(rule, str) or rule not in METHOD_LABELS:
            raise ValueError(f"nees holds a key that is not a rule: {shown(rule)}")
        read[rule] = scalar(v, f"nees[{rule!r}]", lo=0.0)   # the float read (fuzz 22b, FR)
    return pd.Series({METHOD_LABELS[rule]: v for rule, v in read.items()},
                     name="mean NEES (consistent: ≈ 4 or less)").round(2).to_frame()


def model_rmse(nees_est: Mapping[str, np.ndarray], steady: ArrayLike,
               rule: str = NeesRule.SPLIT) -> dict[str, float]:
    """RMSE of ``rule`` for targets that follow the model (:func:`fusion.scenarios.two_sensor.nees_study`), x and y.

    Parameters
    ----------
    nees_est : mapping
        The estimates ``est`` of :func:`fusion.scenarios.two_sensor.nees_study` (``"truth"`` and each rule, shape
        (runs, K, 4)).
    steady : array_like of bool, shape (K,)
        Steps averaged.
    rule : str
        Rule of ``nees_est``.

    Returns
    -------
    dict
        ``"x"``, ``"y"``: the per-step RMSE over the runs averaged over ``steady`` (m).

    Raises
    ------
    TypeError
        ``nees_est`` not a mapping, its arrays not of numbers, or ``steady`` not of bools.
    ValueError
        ``rule`` or ``"truth"`` not in ``nees_est``, an estimate not of the truth's shape (runs, K, 4), or
        ``steady`` not one bool per step or selecting none.
    """
    if not isinstance(nees_est, Mapping):
        raise TypeError(f"nees_est must be a mapping (the est of two_sensor.nees_study), got {type(nees_est).__name__}")
    if "truth" not in nees_est:
        raise ValueError("nees_est lacks the key 'truth' (the est of two_sensor.nees_study holds it)")
    if rule not in nees_est:
        raise ValueError(f"rule: {shown(rule)} is not in nees_est (has {sorted(map(str, nees_est))})")
    truth = as_array(nees_est["truth"], "nees_est['truth']", ndim=3)
    est = as_array(nees_est[rule], f"nees_est[{shown(rule)}]", shape=truth.shape)
    mask = as_mask(steady, "steady")
    if mask.shape != (truth.shape[1],):
        raise ValueError(f"steady must hold one bool per step of nees_est ({truth.shape[1]}), got shape {mask.shape}")
    if not mask.any():
        raise ValueError("steady selects no step (the RMSE over no step is undefined)")
    per_step = rmse_per_step(est - truth, np.zeros(truth.shape[-2:]))[mask]
    return {"x": float(per_step[:, 0].mean()), "y": float(per_step[:, 2].mean())}
