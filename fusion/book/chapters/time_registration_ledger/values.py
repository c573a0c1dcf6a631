"""Chapter 07 (time registration): the tables and values the chapter glues.

Exact MSEs under each unmodelled change, NEES, noise gains, manoeuvre and latency values.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd
from numpy.typing import ArrayLike

from fusion._counts import seed as check_seed
from fusion.book.chapters.time_registration import IMPROVED, TWO
from fusion.book.chapters.time_registration_closed import B_OFFSET
from fusion.book.exact import ExactComparison
from fusion.book.glue import GlueValues, _checked_keep, _glued_cell
from fusion.book.tables import _frame
from fusion.book.style import METHOD_LABELS
from fusion.book.ledger import ledger_dir
from fusion.scenarios import time_registration as sc
from fusion.scenarios.time_registration import RegMethod
from fusion.book.chapters.time_registration_ledger.studies import EXTRAP, FIXED_LAG, PC, S3, STRESS, STUDY_METHODS
from fusion._counts import count
from fusion._validation import as_times, instance_of, read_mapping, record, scalar, std_scalar
from fusion.book.chapters.time_registration_closed import _method_names
from fusion._shown import shown
from fusion._limits import recorded_as, work
from fusion.book.chapters.time_registration_ledger.costs import _record_times
from fusion._paths import file_json

__all__ = [
    "nees_table",
    "manoeuvre_values",
    "latency_values",
    "gain_values",
    "blue_whole_record",
    "stress_table",
    "keep",
    "exact_check",
    "noise_gain_by_instant",
]


def keep(store: GlueValues, values: GlueValues) -> GlueValues:
    """Add ``values`` to ``store`` and return them: the chapter glues a dict and keeps it for the claim texts.

    Parameters
    ----------
    store : dict
        The chapter's glue values so far (changed in place).
    values : mapping
        Values to glue.

    Returns
    -------
    mapping
        ``values`` (read once: a mapping that is not a plain dict, or one holding a 0-d array, as the plain dict
        kept, each 0-d array as its plain number, so that a later edit of the caller's array does not reach
        ``store``).

    Raises
    ------
    TypeError
        ``store`` is not a mutable mapping, ``values`` not a mapping, or a key of ``values`` not a str.
    ValueError
        A key of ``values`` is not an ASCII identifier (a claim text's ``{name}``); a number of ``values`` is not
        finite (NaN or infinite, which the book would print), named ``values[key]``. ``store`` is then left
        unchanged. A key kept again takes its new value (a re-run cell).
    """
    values = _checked_keep(store, values)  # read once, 0-d arrays as numbers (fuzz 33b B4, D2)
    store.update(values)
    return values


def stress_table(sigma: float, names: Sequence[str] = STUDY_METHODS) -> pd.DataFrame:
    """Exact E[MSE] (m²) of every method on the source's truth and under each unmodelled change (rule R6).

    Every method runs under the same change: the acceleration stops or reverses at 20 s, or sensor 1's
    samples are taken 10 ms before (or after) their stamps; the Kalman methods are also shown with a
    driving noise that allows for manoeuvres (q_v = 1, q_a = 0.1 per step).

    Parameters
    ----------
    sigma : float
        Noise level (m), also assumed by the filters.
    names : sequence of str
        Methods (keys of :data:`fusion.scenarios.time_registration.METHODS`).

    Returns
    -------
    DataFrame
        Index: method; columns: information used, the source's truth, each change of :data:`STRESS`, and the
        two manoeuvres with the manoeuvre tuning (Kalman methods only, else NaN); 2 decimals.

    Raises
    ------
    TypeError
        ``sigma`` is not a number, or ``names`` not a sequence of strings.
    ValueError
        ``sigma`` is not a valid standard deviation, or ``names`` is empty or holds an unknown method.
    """
    sigma = std_scalar(sigma, "sigma")  # the float read (fuzz 22b, FR)
    names = _method_names(names, "names")
    rows = {}
    for n in names:
        r: dict[str, object] = {"information": METHOD_LABELS[sc.METHODS[n]], "source's truth": sc.expected(n, sigma)}
        for k, kw in STRESS.items():
            r[k] = sc.expected(n, sigma, **kw)  # type: ignore[arg-type]
        kal = n in sc.FILTER_METHODS
        for k in ("manoeuvre-stop", "manoeuvre-reverse"):
            r[k + ", q_v = 1, q_a = 0.1"] = (sc.expected(n, sigma, q_v=1.0, q_a=0.1, **STRESS[k])  # type: ignore[arg-type]
                                             if kal else float("nan"))
        rows[n] = r
    out = pd.DataFrame(rows).T.infer_objects()
    out.index.name = "method"
    num = out.select_dtypes("number").columns
    out[num] = out[num].round(2) + 0.0
    return out.sort_values(["information", "source's truth"], kind="stable")


def _true_state(t: np.ndarray, a_after: float | None, t_change: float = 20.0) -> np.ndarray:
    """True [x, v, a] (n, 3) of :func:`fusion.scenarios.time_registration.manoeuvre_truth` at times ``t``."""
    v0, a0 = float(sc.SCENARIO["v0"]), float(sc.SCENARIO["a"])
    after = (t > t_change) if a_after is not None else np.zeros(t.shape, dtype=bool)
    a = np.where(after, 0.0 if a_after is None else a_after, a0)
    v = np.where(after, v0 + a0 * t_change + a * (t - t_change), v0 + a0 * t)
    return np.column_stack([sc.manoeuvre_truth(t, a_after), v, a])


#: Units of :func:`nees_table`'s own work at one run, sample and filter pass, beyond the filter's (its own rule): the
#: error and its NEES against the inverse covariances (einsum) measured 114 ns (162 ns in all, 48 of them the
#: filter's; 100,000 runs, ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the least of two, the machine shared;
#: fix60a). The edge, 462,851 runs, is about 6 CPU-s (833,133, counting the filter alone, ran 15.9).
_NEES_WEIGHT = 12


def nees_table(sigma: float, runs: int, seed: int) -> pd.DataFrame:
    r"""Filter consistency: the normalised estimation error squared (NEES) of the chapter's Kalman filter.

    At each sample :math:`\epsilon_i = \mathbf e_i^\top P_i^{-1}\mathbf e_i`, :math:`\mathbf e_i` the filtered
    state's error against the true [x, v, a]; for a consistent filter its mean over runs is 3 (the state's
    dimension) and lies in the two-sided 95 % chi-square interval :math:`[\chi^2_{3R}(0.025), \chi^2_{3R}(0.975)]/R`
    (Bar-Shalom, Li & Kirubarajan 2001, §5.4).

    Parameters
    ----------
    sigma : float
        Noise level (m), also assumed by the filter.
    runs : int
        Runs (R).
    seed : int

    Returns
    -------
    DataFrame
        Index (truth, tuning); columns: mean NEES over runs and samples, largest mean over runs at a sample,
        share of samples whose mean lies inside the 95 % interval (3 decimals).

    Raises
    ------
    TypeError
        ``sigma`` not a number, ``runs`` or ``seed`` not an integer.
    ValueError
        ``sigma`` not a valid standard deviation (finite, positive, its square a representable variance), ``runs``
        below 1 or beyond the work budget (its four filter passes counted by the filter's own rule, fix60a), ``seed``
        negative.
    """
    sigma = std_scalar(sigma, "sigma")  # read before the draws (an unchecked sigma escaped as numpy's error)
    runs = count(runs, "runs")
    seed = check_seed(seed)   # an integer seed (rule 11), named
    from scipy import stats

    from fusion import registration as reg

    t1, _ = sc.instants()
    # rule 17 (fix60a): the four filter passes below (two truths x two tunings), each by the filter's own rule
    # (``fusion.registration.methods._kalman_work``, the same weights), and the NEES of each run and sample of each,
    # so that ``runs`` is refused by its own name, before the draws, never inside as ``t and Z``
    from fusion.registration.methods import _kalman_work
    passes = sum(_kalman_work(t1.size, runs, False, "runs") for _ in range(4))
    work((passes + work((4, runs, t1.size), "runs", weight=_NEES_WEIGHT),), "runs")
    rng = np.random.default_rng(seed)
    noise = sigma * rng.standard_normal((runs, t1.size))
    lo, hi = (stats.chi2.ppf(q, 3 * runs) / runs for q in (0.025, 0.975))
    rows = {}
    for truth_label, a_after in (("source's truth", None), ("acceleration 2 → 0 m/s² at 20 s", 0.0)):
        x = _true_state(t1, a_after)
        for tune_label, (qv, qa) in (("q_v = 10⁻², q_a = 10⁻³", (sc.Q_V, sc.Q_A)), ("q_v = 1, q_a = 0.1", (1.0, 0.1))):
            fs = reg.kalman_runs(t1, x[:, 0] + noise, sigma, qv, qa)
            e = fs.x - x                                          # (runs, n, 3)
            eps = np.einsum("rni,nij,rnj->rn", e, np.linalg.inv(fs.P), e).mean(axis=0)
            rows[(truth_label, tune_label)] = {"mean NEES": float(eps.mean()), "largest at a sample": float(eps.max()),
                                               "share inside 95 % interval": float(np.mean((eps >= lo) & (eps <= hi)))}
    out = pd.DataFrame(rows).T
    out.index.names = ["truth", "tuning"]
    return out.round(3)


def blue_whole_record(sigma: float) -> float:
    r"""Exact E[MSE] (m²) of the best linear unbiased registration with the whole record, on the source's truth.

    The truth is one quadratic over the window, so least squares of a quadratic through every sample is the
    best linear unbiased estimate of :math:`x(t_k)` (Gauss-Markov): a lower bound for every linear unbiased
    method, whatever information it uses (the global quadratic through every past sample and the next one is the
    same bound with the improved method's information).

    Parameters
    ----------
    sigma : float
        Noise level (m), > 0.

    Returns
    -------
    float
        The expected MSE (m²) of a least-squares quadratic through every sample at noise ``sigma``, averaged over
        sensor 2's instants.

    Raises
    ------
    TypeError
        ``sigma`` is not a number.
    ValueError
        ``sigma`` is not a valid standard deviation (finite, positive, its square a representable variance).
    """
    sigma = std_scalar(sigma, "sigma")  # the float read (fuzz 22b, FR)
    from functools import partial

    from fusion import registration as reg

    t1, t2 = sc.instants()
    fit = partial(reg.quadratic_ls, t1, t_query=t2, lookahead=t1.size)
    return float(reg.expected_mse(fit, sc.truth(t1), sc.truth(t2), sigma))


def manoeuvre_values(manoeuvre: Mapping[float, Mapping[str, float]], sigma: float) -> GlueValues:
    """The glue values of the manoeuvre paragraph (chapter bookkeeping).

    Parameters
    ----------
    manoeuvre : mapping
        Acceleration after the change (m/s²) → method → exact E[MSE] (m²), as the chapter computes it.
    sigma : float
        Measurement noise (m).

    Returns
    -------
    dict
        ``reg_man_*``: the improved method, two-point and three-point when the acceleration stops, the improved
        method when it reverses, and the improved method with a manoeuvre-allowing driving noise (q_v = 1, q_a = 0.1).

    Raises
    ------
    TypeError
        ``manoeuvre`` is not a mapping of mappings, or ``sigma`` not a number.
    ValueError
        ``manoeuvre`` lacks the accelerations 0 and -2 m/s² or a method read here, or an MSE read here is not a
        finite non-negative number (named ``manoeuvre[a][method]``; TypeError for a non-number), or not the exact
        E[MSE] at ``sigma`` (``fusion.scenarios.time_registration.expected``, to ``fusion._limits.RECORDED_RTOL``:
        a ``manoeuvre`` computed at another noise level would be glued beside ``reg_man_impr_q`` at ``sigma``), or
        ``sigma`` is not a valid standard deviation.
    """
    record(manoeuvre := read_mapping(manoeuvre, "manoeuvre"), "manoeuvre", (0.0, -2.0), extra=True)  # read once
    manoeuvre = {a: read_mapping(manoeuvre[a], f"manoeuvre[{a!r}]") for a in (0.0, -2.0)}  # (fuzz 31a C2)
    record(manoeuvre[0.0], "manoeuvre[0.0]", (IMPROVED, TWO, RegMethod.THREE_POINT), extra=True)
    record(manoeuvre[-2.0], "manoeuvre[-2.0]", (IMPROVED,), extra=True)
    sigma = std_scalar(sigma, "sigma")

    def mse(a: float, method: str) -> float:  # a glued MSE (fuzz 22b, V1): a finite number >= 0, as a float
        name = f"manoeuvre[{a!r}][{shown(getattr(method, 'value', method))}]"
        v = scalar(manoeuvre[a][method], name, lo=0.0)
        exact = sc.expected(method, sigma, a_after=a)  # one noise level for the five numbers (fuzz 33b D4)
        if not recorded_as(v, exact):
            raise ValueError(f"{name} = {shown(v)} is not the exact E[MSE] at sigma = {shown(sigma)} ({shown(exact)}): "
                             "manoeuvre must be computed at sigma (the paragraph's numbers are at one noise level)")
        return v

    return {"reg_man_impr": mse(0.0, IMPROVED), "reg_man_two": mse(0.0, TWO),
            "reg_man_three": mse(0.0, RegMethod.THREE_POINT), "reg_man_impr_neg": mse(-2.0, IMPROVED),
            "reg_man_impr_q": sc.expected(IMPROVED, sigma, a_after=0.0, q_v=1.0, q_a=0.1)}


def latency_values(be: Mapping[float, float], sigma: float) -> GlueValues:
    """Break-even latencies in milliseconds at ``sigma`` and over the noise levels run (chapter bookkeeping).

    Parameters
    ----------
    be : mapping
        Noise level (m, a finite number > 0, as ``delay_break_even`` takes it) → break-even latency (s, >= 0: the
        latency at which the methods' MSEs meet, as ``delay_break_even`` returns it rounded to 0.1 ms).
    sigma : float
        The chapter's noise level (a key of ``be``).

    Returns
    -------
    dict
        ``reg_be_ms``, ``reg_be_lo_ms``, ``reg_be_hi_ms``.

    Raises
    ------
    TypeError
        ``be`` is not a mapping, a noise level (key) or ``sigma`` not a number.
    ValueError
        ``be`` is empty, holds a noise level (a key) that is not a valid standard deviation or a latency that is
        negative or not finite, or ``sigma`` is not one of its keys.
    """
    instance_of(be, Mapping, "be")
    if not be:
        raise ValueError("be is empty (it must map noise levels to break-even latencies)")
    # the floats the reader returns, not the caller's objects (fuzz 22b, FR4-5: a Decimal, a 0-d array)
    lat = {std_scalar(k, f"the noise level {shown(k)} of be"): scalar(v, f"be[{k!r}]", lo=0.0)
           for k, v in be.items()}  # a latency >= 0 (fuzz 24d M1: -20 ms was glued)
    if len(lat) < len(be):  # keys equal as floats (1 and 1.0 are one key of a dict already)
        raise ValueError("be holds a noise level twice (as two keys of equal value)")
    sigma = scalar(sigma, "sigma")
    if sigma not in lat:
        raise ValueError(f"sigma = {shown(sigma)} is not a noise level of be (its keys: {list(be)[:10]})")
    return {"reg_be_ms": 1e3 * lat[sigma], "reg_be_lo_ms": 1e3 * min(lat.values()), "reg_be_hi_ms": 1e3 * max(lat.values())}


def gain_values(values: Mapping[str, float], closed: pd.DataFrame) -> GlueValues:
    """Three-point's noise-gain excess over two-point (%) and extrapolation's closed-form constants.

    Parameters
    ----------
    values : mapping
        The chapter's glue values so far, holding ``reg_gain_three`` and ``reg_gain_two``.
    closed : DataFrame
        The closed-form table (rows: methods; columns ``b (m²)`` and ``g``).

    Returns
    -------
    dict
        ``reg_gain_excess_pct``; ``reg_gain_three_between``, ``reg_gain_two_between``, ``reg_gain_between_pct`` and
        ``reg_n_between`` (the same gains at the instants between samples only); ``reg_cf_extrap_b``,
        ``reg_cf_extrap_g``.

    Raises
    ------
    TypeError
        ``values`` is not a mapping or ``closed`` not a DataFrame.
    ValueError
        ``values`` lacks ``reg_gain_three`` or ``reg_gain_two`` (or the latter is zero), or ``closed`` lacks the
        extrapolation row or the columns ``b (m²)`` and ``g`` or holds one twice, a row twice or a row that is not a
        method, or a cell read there is not a
        finite non-negative number (TypeError for a non-number), named ``closed``.
    """
    record(values, "values", ("reg_gain_three", "reg_gain_two"), extra=True)
    three = scalar(values["reg_gain_three"], "values['reg_gain_three']", lo=0.0)
    two = scalar(values["reg_gain_two"], "values['reg_gain_two']", lo=0.0, lo_open=True)
    instance_of(closed, pd.DataFrame, "closed")
    if EXTRAP not in closed.index or B_OFFSET not in closed.columns or "g" not in closed.columns:
        raise ValueError(f"closed must be the closed-form table (row {shown(str(EXTRAP))}, columns {shown(B_OFFSET)} and 'g')")
    _frame(closed, "closed", (B_OFFSET, "g"), maker="closed_form_table", unique=True, rows=sc.METHODS,
           rows_are="a method of METHODS")  # one row a method (fuzz 24d T)
    b, g = (_glued_cell(closed, EXTRAP, c, "closed", lo=0.0) for c in (B_OFFSET, "g"))  # fuzz 22b, V2-V5
    t1, t2 = sc.instants()
    between = t2[~np.isin(t2, t1)]
    gi = {n: sc.mse_coefficients(n, 1.0, t_dst=between)[1] for n in (RegMethod.THREE_POINT, TWO)}
    return {"reg_gain_excess_pct": 100 * (three / two - 1),
            "reg_gain_three_between": gi[RegMethod.THREE_POINT], "reg_gain_two_between": gi[TWO],
            "reg_gain_between_pct": 100 * (gi[RegMethod.THREE_POINT] / gi[TWO] - 1), "reg_n_between": int(between.size),
            "reg_cf_extrap_b": b, "reg_cf_extrap_g": g}


def noise_gain_by_instant(t1: ArrayLike, t2: ArrayLike) -> pd.DataFrame:
    r"""Noise gain :math:`\lVert a_k\rVert^2` of three-point and two-point interpolation at each instant.

    At an instant that is a sensor-1 sample time both return the sample (gain 1); between samples the weights
    are (−1/8, 3/4, 3/8) and (1/2, 1/2) at mid-interval, gains 46/64 and 1/2. The record's gain
    :math:`g` is the mean over the instants.

    Parameters
    ----------
    t1, t2 : array_like
        Sensor 1's sample times and the registration instants (s), as for
        :func:`~fusion.book.chapters.time_registration_ledger.cost_count`: the instants within the record
        ``[t1[0], t1[-1]]``, and the gains those of interpolation on ``t1`` itself. Times before the flight's
        start (negative) are accepted (fuzz 26d DB5, documented): the gains depend on the times' differences only,
        so a record shifted in time has the same gains.

    Returns
    -------
    DataFrame
        Index: instant (s); columns: whether it is a sample time (exactly one of ``t1``, as given: an instant a
        few ulps from a sample is flagged False, its gains within round-off of 1; fuzz 26d DB8, documented), the
        two gains and three-point's excess (%).

    Raises
    ------
    ValueError
        As :func:`~fusion.book.chapters.time_registration_ledger.cost_count` for the times, or ``t1`` and ``t2``
        beyond the work budget (``fusion._limits.MAX_WORK``, chapter 07's rule ``_registration_work``: 1,000
        samples and 1,000 instants are refused, 1,000 and 30 accepted).
    """
    t1, t2 = _record_times(t1, t2)  # increasing, the instants within the record: named
    # rule 17 (fuzz 28b C5: no budget, ~0.12 ms x len(t1) x len(t2)): per instant, each gain n1 + 1 registrations
    sc._registration_work((RegMethod.THREE_POINT, TWO), t1.size, 1, t2.size * (t1.size + 1), "t1 and t2")
    # the samples are t1's (they were the scenario's default whatever t1 was: a plausible wrong gain, fuzz 17)
    g = {n: [sc.mse_coefficients(n, 1.0, t_src=t1, t_dst=[t])[1] for t in t2] for n in (RegMethod.THREE_POINT, TWO)}
    out = pd.DataFrame({"sample time": np.isin(t2, t1), "g three-point": g[RegMethod.THREE_POINT],
                        "g two-point": g[TWO]},
                       index=pd.Index(t2, name="instant (s)"))
    out["excess (%)"] = 100 * (out["g three-point"] / out["g two-point"] - 1)
    return out


def exact_check(sigma: float) -> pd.DataFrame:
    """The Monte-Carlo primaries of the fixed-weight and Kalman comparisons judged again on their exact E[MSE] (R9).

    Every method compared by a Monte-Carlo record has a closed-form expected MSE (eq. reg-mse, the Kalman filters
    with fixed gains); the records compare per-run MSEs with paired intervals, and this table shows that the exact
    comparison, under the same 5 % margin, gives the same status.

    Parameters
    ----------
    sigma : float
        Measurement noise (m).

    Returns
    -------
    DataFrame
        One row per record: A, B, exact E[MSE] of each (m²), the status of
        :class:`~fusion.book.exact.ExactComparison` ("A less") and the record's status in the stored ledger
        (``book/ledger/shi2023time.json``, from its paired Monte-Carlo runs; for shi-simplifies the record's,
        which needs its accuracy member).
    """
    path = ledger_dir() / "shi2023time.json"
    stored = ({c["id"]: c["status"] for c in file_json(path, "the stored ledger shi2023time.json")["claims"]}
              if path.exists() else {})
    pairs = (("shi-interp-vs-ls", EXTRAP, RegMethod.LEAST_SQUARES, {}), ("shi-kalman-s3", S3, EXTRAP, {"a": PC}),
             ("shi-improved", IMPROVED, TWO, {}), ("shi-improved-fair", IMPROVED, FIXED_LAG, {}),
             ("shi-simplifies (keeps the accuracy)", IMPROVED, S3, {"b": PC}))
    rows = []
    for rid, a, b, kf in pairs:
        ea = sc.expected(a, sigma, kf=kf.get("a"))
        eb = sc.expected(b, sigma, kf=kf.get("b"))
        rows.append({"record": rid, "A": a, "B": b, "exact E[MSE] A (m²)": ea, "exact E[MSE] B (m²)": eb,
                     "exact status (A less)": ExactComparison(ea, eb, METHOD_LABELS[a], METHOD_LABELS[b], "less",
                                                                      "exact E[MSE] (m²)").status(),
                     "ledger status (Monte Carlo)": stored.get(rid.split(" ")[0], "not in the ledger")})
    return pd.DataFrame(rows).set_index("record")
