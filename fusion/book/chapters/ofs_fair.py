"""A fair comparison for the optimal-fusion-set chapter: the baselines a practitioner would use.

Ten thermocouples, persistent faults (a constant bias on some sensors for the whole run), and three
sweeps on common random numbers: the fault size (in units of the noise σ, two faulty sensors),
the number of faulty sensors (bias 5σ) and the spread of the noise levels (no fault). Every method
sees the same readings; each is compared with the optimal fusion set by the paired 95 % interval of
the per-run mean absolute error.

References
----------
* Yang G. N., Feng X. F., Fan L. J. (2012). Multi-sensor data fusion algorithm based on
   optimal fusion set. *Journal of Software* 23(Suppl. 1), 134-140.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any
from dataclasses import dataclass

import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from matplotlib.ticker import ScalarFormatter
from numpy.typing import ArrayLike

from fusion import readings as rd
from fusion._results import ResultSpec, array, dict_of, integer, validated_post_init
from fusion._validation import FloatArray, as_array, count, instance_of, one_of, read_mapping, scalar
from fusion.book._few_runs import runs_named
from fusion.book.ledger import Comparison
from fusion.book.style import _MAX_PANELS, METHOD_LABELS, color, new_figure
from fusion.book.tables import rounded
from fusion.readings._row_blocks import epochs_limit
from fusion.readings.robust import _robust_limit, ROBUST_METHODS, robust_fuse
from fusion.book.glue import GlueValues
from fusion._counts import seed as check_seed
from fusion._counts import allocation, distinct, sequence
from fusion._limits import LOOP_STEP, MAX_MAGNITUDE, loop_work, work
from fusion._structures import record, records_of
from fusion._shown import shown

__all__ = ["FAIR_METHODS", "information", "fair_errors", "FairStudy", "fair_study", "verdicts", "figure_fair", "fair_numbers",
           "margin_sensitivity", "fault_shapes_study", "fault_shapes_table"]

#: Methods of the fair study, in display order.
FAIR_METHODS: tuple[str, ...] = ("optimal_fusion_set", "uniform_set", "mean", "median", "trimmed_mean",
                                 "trimmed_mean_25", "huber", "biweight", "grubbs", "mad_reject", "inverse_variance")

#: Line style of each method in :func:`figure_fair` (solid where absent), to tell shared colours apart.
_LINESTYLE = {"uniform_set": "--", "trimmed_mean_25": "--", "biweight": "-.", "mad_reject": ":"}


def information(method: str) -> str:
    """The information a method of :data:`FAIR_METHODS` uses.

    Parameters
    ----------
    method : str

    Returns
    -------
    str
        The information it uses: ``"readings only"``, or ``"readings and known noise standard deviations"`` for
        inverse-variance weights.
    """
    method = one_of(method, FAIR_METHODS, "method")
    if method in ("optimal_fusion_set", "mean", "trimmed_mean_25"):
        return "readings only"
    return ROBUST_METHODS[method]


def _methods(methods: Sequence[str]) -> tuple[str, ...]:
    """``methods`` as a tuple, each checked to be one of :data:`FAIR_METHODS`, at least one and none twice (each keys
    the result: a repeat would collapse silently); ValueError naming ``methods``."""
    out = (methods,) if isinstance(methods, str) else tuple(sequence(methods, "methods"))
    if not out:
        raise ValueError("methods must name at least one method of FAIR_METHODS, got none")
    out = tuple(one_of(m, FAIR_METHODS, "methods") for m in out)
    return tuple(distinct(list(out), "methods"))


def fair_errors(z: ArrayLike, sigma: ArrayLike, truth: float = 900.0,
                methods: Sequence[str] = FAIR_METHODS) -> dict[str, FloatArray]:
    """Per-run mean absolute error of every method of :data:`FAIR_METHODS` (or of ``methods``).

    Parameters
    ----------
    z : array_like, shape (n_runs, n_samples, n_sensors)
        Readings (°C).
    sigma : array_like, shape (n_sensors,)
        Noise standard deviations, given to the inverse-variance mean only.
    truth : float
        True value (°C).
    methods : sequence of str
        The methods computed, each of :data:`FAIR_METHODS` (default: all); each method's errors do not depend
        on which others are computed.

    Returns
    -------
    dict of str to ndarray, shape (n_runs,)
        Mean absolute error over the samples of each run (°C), rounded to 1e-9, by method in the order of ``methods``.

    Raises
    ------
    ValueError
        ``z`` not three-dimensional, ``methods`` empty, a method not of :data:`FAIR_METHODS` or one named twice;
        ``z`` beyond a method's own limits (its pairwise kernel, Grubbs' passes) or the work budget, named ``z``.
    """
    methods = _methods(methods)
    arr = as_array(z, "z", ndim=3)
    if np.any(as_array(sigma, "sigma", shape=(arr.shape[-1],)) <= 0):
        raise ValueError("sigma must be positive (one standard deviation per sensor)")
    truth = scalar(truth, "truth")
    # each method's limits and the work of this one point, by the study's rule, before any fusion and naming z (the
    # inner fusions named their own ``x``: 30,000 sensors refused as "x (30,000 readings, ...)")
    _budget(arr.shape, 1, methods, ("z", "z"))
    flat = arr.reshape(-1, arr.shape[-1])
    out: dict[str, FloatArray] = {}
    for m in methods:
        if m in ("optimal_fusion_set", "mean"):
            v = rd.fuse_epochs(flat, m).values
        elif m == "trimmed_mean_25":
            v = robust_fuse(flat, "trimmed_mean", cut=0.25)
        else:
            v = robust_fuse(flat, m, sigma=sigma)
        out[m] = np.round(np.abs(v - truth).reshape(arr.shape[:2]).mean(axis=1), 9)
    return out


@dataclass(frozen=True)
class FairStudy:
    """Per-run mean absolute errors of every method at every point of the three sweeps.

    Attributes
    ----------
    mae : dict of (str, float) to dict of str to ndarray
        (sweep, value) -> method -> per-run mean absolute error (°C).
    n_runs, n_samples, seed : int
    """

    mae: Mapping[tuple[str, float], Mapping[str, FloatArray]]
    n_runs: int
    n_samples: int
    seed: int

    __result_spec__ = ResultSpec({"mae": dict_of(dict_of(array("runs", bounds=(0.0, np.inf))), key=tuple),
                                  "n_runs": integer(1), "n_samples": integer(1), "seed": integer(0)},
                                 relations=(lambda v, cls: _fair_relation(v, cls),))
    __post_init__ = validated_post_init


def _fair_relation(values: Mapping[str, Any], cls: str) -> None:
    """Every key of ``mae`` a (sweep, value) pair, every error array one value per run."""
    for key, errs in values["mae"].items():
        if not (len(key) == 2 and isinstance(key[0], str) and isinstance(key[1], (float, int))):
            raise ValueError(f"{cls}.mae has a key {shown(key, 60)} that is not a (sweep, value) pair")
        for method, arr in errs.items():
            if arr.shape != (values["n_runs"],):
                raise ValueError(f"{cls}.mae[{shown(key)}][{shown(method)}] must hold one error per run "
                                 f"({cls}.n_runs = {values['n_runs']}), got shape {arr.shape}")


#: Names of the three sweeps.
SIZE, COUNT, SPREAD = "fault size (σ), 2 faulty sensors", "faulty sensors (bias 5σ)", "noise spread σ_max/σ_min"

#: Name of the opposite-sign sweep: two faulty sensors, one biased by +b, one by -b.
OPPOSITE = "fault size (σ), 2 faulty sensors of opposite signs"

#: Units of work (rule 17, ``fusion._limits.work``) of one reading fused by one method at one sweep point, the
#: average over the methods of :data:`FAIR_METHODS`: measured 80 ns a reading, method and point on this machine (the
#: default sweeps, 23 points x 11 methods, ran 20 CPU-s at 1,000 runs x 100 samples x 10 sensors). :func:`fair_study`
#: weighs each method by its own cost (:data:`_FAIR_WEIGHTS`); :func:`fault_shapes_study`'s four cheaper fusions by
#: this average.
FAIR_WORK = 3

#: Units of work of one reading fused by each method at one sweep point of :func:`fair_study` (fuzz 45b C4: the
#: average :data:`FAIR_WORK` let ``methods=("huber",)`` at the budget's edge run 72 CPU-s). Measured with
#: ``time.process_time`` (``OPENBLAS_NUM_THREADS=1``, minimum of 3, the machine shared with other jobs) on
#: ``fair_errors`` of 400 runs x 100 samples x 10 sensors with two sensors biased by 3 sigma, in ns a reading:
#: optimal_fusion_set 193, uniform_set 64, mean 18, median 31, trimmed_mean 35, trimmed_mean_25 42, huber 226,
#: biweight 233, grubbs 103, mad_reject 50, inverse_variance 20; one unit is 10 ns, rounded up, and huber and biweight
#: at the largest fuzz 45b measured over its data (IRLS iterations depend on it: up to 291 ns a reading). The two
#: optimal-set methods' pairwise part is :data:`_FAIR_PAIR_WEIGHTS`'s (here the linear part, fitted at 10 sensors).
#: Fuzz 46a C4: fitted at 10 sensors only, huber and biweight cost up to 7.3 us a row of 3 (counted 0.9), so
#: ``methods=("biweight",)`` at 3 sensors at the edge ran 89.6 CPU-s. Each method is now weighed a row
#: (:data:`_FAIR_ROW_WEIGHTS`) plus a reading (here), fitted on ``fair_errors`` (as above, the maximum of two data:
#: two sensors +3 sigma, or sensor 0 +1 sigma) at 2, 3, 4, 5, 6, 7, 8, 10, 15 and 30 sensors, in ns a row at n = 2, 3,
#: 10 and 30:
#: optimal_fusion_set 325, 503, 1576, 8237; uniform_set 166, 182, 560, 2040; mean 42, 54, 137, 360; median 77, 86,
#: 260, 750; trimmed_mean 75, 94, 344, 1049; huber 176, 4794, 2514, 5312; biweight 3701, 7266, 2410, 4530; grubbs 59,
#: 75, 1043, 3150; mad_reject 151, 171, 603, 1650; inverse_variance 54, 63, 131, 360 (huber up to 6,523 at 5 sensors).
_FAIR_WEIGHTS = {"optimal_fusion_set": 10, "uniform_set": 4, "mean": 2, "median": 4, "trimmed_mean": 4,
                 "trimmed_mean_25": 5, "huber": 18, "biweight": 18, "grubbs": 11, "mad_reject": 6,
                 "inverse_variance": 2}
#: Units of work of one row (epoch) fused by each method at one sweep point of :func:`fair_study`, beside
#: :data:`_FAIR_WEIGHTS`' per reading (the fit above: e.g. optimal_fusion_set 30 + 10 n + n**2 units, 540 ns counted at
#: 2 sensors against 325 measured, 2.3 us at 10 against 1.6; huber 120 + 18 n, 3.0 us at 10 against 2.5, 6.6 at 30
#: against 5.3).
_FAIR_ROW_WEIGHTS = {"optimal_fusion_set": 30, "uniform_set": 12, "mean": 1, "median": 1, "trimmed_mean": 1,
                     "trimmed_mean_25": 0, "huber": 120, "biweight": 120, "grubbs": 0, "mad_reject": 10,
                     "inverse_variance": 2}
#: Units of a row of at most :data:`_FAIR_FEW` readings fused by huber or biweight: the MAD scale of so few readings
#: lets some rows iterate to the 500-pass cap (fuzz 46a C4; measured up to 7.3 us a row, 3 sensors, above).
_FAIR_FEW, _FAIR_FEW_IRLS = 5, 800
#: Units of work of one pair of readings of a row in the n x n kernel of the optimal-set methods (fuzz 45b C5: their
#: cost grows as n**2, 10,000 sensors ran 16 CPU-s at 80 runs counted as 2.4e6 linear units). Measured as above on
#: 4,000 x 100, 40 x 1,000 and 5 x 3,000 readings: optimal_fusion_set 6.1, 4.9 and 9.7 ns a pair, uniform_set 1.2,
#: 0.8 and 1.5 ns a pair (with :data:`_FAIR_WEIGHTS`' linear part: 2.0 and 0.6 us a row of 10 measured, 2.0 and 0.6
#: counted).
_FAIR_PAIR_WEIGHTS = {"optimal_fusion_set": 1.0, "uniform_set": 0.2}


def _budget(shape: tuple[int, int, int], points: int, methods: Sequence[str], names: tuple[str, str]) -> None:
    """Refuse a fair study whose draws, of ``shape`` (runs, samples, sensors), are beyond the memory budget or whose
    ``points`` fusions of them by each of ``methods`` are beyond the work budget (each method weighed by its own
    cost, :data:`_FAIR_ROW_WEIGHTS` a row, :data:`_FAIR_WEIGHTS` a reading and :data:`_FAIR_PAIR_WEIGHTS` a pair of
    a row), naming ``names`` (the
    memory's, the work's): :func:`fair_study` and its cached entries (``fusion.book.chapters.ofs.fair``) call it
    before anything is drawn, each naming its own arguments. Each method's own refusal of one point's readings
    (its pairwise kernel, Grubbs' passes: what ``fuse_epochs`` and ``robust_fuse`` would refuse after the draws)
    is checked here too, and its super-linear units added."""
    allocation(shape, names[0])
    runs, samples, n = (int(v) for v in shape)
    rows = runs * samples
    per_point = 0.0
    for m in methods:
        units = rows * (_FAIR_ROW_WEIGHTS[m] + n * (_FAIR_WEIGHTS[m] + n * _FAIR_PAIR_WEIGHTS.get(m, 0.0)))
        if m in ("huber", "biweight") and n <= _FAIR_FEW:
            units = max(units, rows * _FAIR_FEW_IRLS)
        if m in ("optimal_fusion_set", "mean"):
            epochs_limit(rows, n, m, names[1])
        else:
            # the refusal of one point's fusion; its units are the shared kernel count (PAIR_WORK a pair, for any
            # caller): the measured weights above count this study, but Grubbs' worst case (a pass a reading of a
            # row, when every pass drops one) is beyond its measured clean-data cost
            worst = _robust_limit(rows, n, "trimmed_mean" if m == "trimmed_mean_25" else m, names[1])
            units = max(units, worst) if m == "grubbs" else units
        per_point += units
    work((points, rows, n), names[1], weight=max(per_point / (rows * n), 1e-9))


#: Largest float spacing at ``truth`` accepted, as a fraction of the smallest noise SD of a study: the readings
#: ``truth + noise`` are rounded to that spacing (fuzz 68b D1: at ``truth = 1e150`` the noise and the faults of
#: :func:`fault_shapes_study` were below one ulp, and every method's MAE was exactly 0).
_TRUTH_SPACING = 1e-3


def _resolved_truth(truth: float, smallest_sd: float, names: str) -> None:
    """Refuse a ``truth`` at which a float's spacing is beyond :data:`_TRUTH_SPACING` of the smallest noise SD."""
    ulp = float(np.spacing(abs(truth)))
    if ulp > _TRUTH_SPACING * smallest_sd:
        raise ValueError(f"{names}: readings near truth = {truth:g} are rounded to {ulp:.3g} °C, beyond "
                         f"{_TRUTH_SPACING:g} of the smallest noise SD ({smallest_sd:.3g} °C): the noise and the "
                         f"faults would be lost in the rounding; give a truth nearer 0 or a larger SD")


def _readings_in_range(top: float, names: str) -> None:
    """Refuse readings derived from the arguments (``truth + noise``, faults) whose magnitude may reach ``top``,
    beyond :data:`MAX_MAGNITUDE`, by name."""
    if not top <= MAX_MAGNITUDE:
        raise ValueError(f"{names}: the readings derived from them may reach magnitude {top:.3g}, beyond the "
                         f"representable range (at most {MAX_MAGNITUDE:g}); give a smaller sigma or truth")


def fair_study(seed: int, n_runs: int = 100, n_samples: int = 100, sizes: Sequence[float] = (0, 1, 2, 3, 4, 6, 8, 10),
               counts: Sequence[int] = (0, 1, 2, 3, 4, 5), spreads: Sequence[float] = (1, 2, 4, 8, 16),
               n_sensors: int = 10, truth: float = 900.0, opposite: Sequence[float] = (2, 3, 4, 6),
               methods: Sequence[str] = FAIR_METHODS) -> FairStudy:
    """Run the three sweeps on common random numbers.

    The noise is standard normal times σ (1 °C for the fault sweeps; geometric from
    ``spread**-0.5`` to ``spread**0.5`` °C for the spread sweep, no fault); the faulty sensors of
    each run are the first ones of a random permutation drawn once per run, and get a constant
    positive bias for the whole run.

    Parameters
    ----------
    seed : int
    n_runs, n_samples : int
    sizes : sequence of float
        Fault sizes (units of σ = 1 °C) with two faulty sensors: magnitudes (the bias is +size), so >= 0; 0 is the
        point without a fault (it fuses the clean readings). A negative size is refused by name: the sign of a
        fault is the ``opposite`` sweep's.
    counts : sequence of int
        Numbers of faulty sensors, bias 5σ.
    spreads : sequence of float
        Ratios of the largest to the smallest σ (>= 1), no fault.
    n_sensors : int
    truth : float
    opposite : sequence of float
        Fault sizes b (units of σ) with two faulty sensors of opposite signs, +b and -b (the sweep
        ``OPPOSITE``; the first two sensors of each run's permutation): magnitudes, >= 0.
    methods : sequence of str
        The methods run at every point (default: all of :data:`FAIR_METHODS`): the draws, and so each method's
        errors, do not depend on which methods or sweep points are run. A subset is for reading
        :attr:`FairStudy.mae` directly (a cheaper look at some methods): :func:`verdicts`, :func:`fair_numbers`
        and :func:`figure_fair` read every method of :data:`FAIR_METHODS` and refuse such a study by name.

    Returns
    -------
    FairStudy
        A sweep given no points is not run (its points are absent from :attr:`FairStudy.mae`).

    Raises
    ------
    TypeError
        A count or a sweep point not of its type, ``methods`` not strings.
    ValueError
        Every sweep empty (nothing to run), a sweep repeating a point (its results are keyed by it), a point out
        of range (a count beyond ``n_sensors``, a spread below 1, a size not finite), ``sizes`` or ``opposite``
        given points with fewer than two sensors (each of their points biases two), ``methods`` empty, unknown or
        repeated; the draws beyond the memory budget (naming ``n_runs, n_samples and n_sensors``) or the study
        beyond the work budget (``fusion._limits.MAX_WORK``; each method weighed by its measured cost a reading and
        point, the optimal-set methods' n x n kernel by its pairs: about 360 runs of the default sweeps, 2,000 of
        ``methods=("mean",)``), refused before anything is drawn; ``truth`` (``truth and spreads`` with a spread
        above 1) when the float spacing at ``truth`` is beyond 1e-3 of the smallest noise SD (1 °C, or the widest
        spread's ``spread**-0.5``): the noise and the faults would be lost in the rounding.
    """
    seed = check_seed(seed)
    n_runs, n_samples, n_sensors = (count(v, k) for v, k in ((n_runs, "n_runs"), (n_samples, "n_samples"),
                                                                (n_sensors, "n_sensors")))
    methods = _methods(methods)
    truth = scalar(truth, "truth")
    # the sweeps' points counted by their lengths: the checks and budgets below that need no entry come before any
    # entry is read (fuzz 61a C1: 10**7 sizes were read and hashed first, refused after 25.6 CPU-s, four sweeps)
    items = {name: sequence(v, name) for name, v in (("sizes", sizes), ("counts", counts), ("opposite", opposite),
                                                    ("spreads", spreads))}
    if not any(items.values()):
        raise ValueError("sizes, counts, opposite and spreads are all empty: the study would run no point")
    for name in ("sizes", "opposite"):
        # both sweeps bias two sensors (fuzz 26d D1-D2): one sensor cannot hold them
        if items[name] and n_sensors < 2:
            raise ValueError(f"{name}: its sweep biases two faulty sensors, but n_sensors = {n_sensors}; give "
                             f"n_sensors >= 2 or {name}=()")
    # the memory and work budgets before anything is drawn (fuzz 26d D3): the draws are one (n_runs, n_samples,
    # n_sensors) array, and every sweep point runs every method over it (a repeated point, refused below, counted)
    _budget((n_runs, n_samples, n_sensors), sum(len(v) for v in items.values()), methods,
            ("n_runs, n_samples and n_sensors", "n_runs, n_samples, n_sensors, the sweeps and methods"))
    # fault sizes are magnitudes (0: no fault); the signs are the opposite sweep's
    sizes = [scalar(v, f"sizes[{i}]", lo=0.0) for i, v in enumerate(items["sizes"])]
    opposite = [scalar(v, f"opposite[{i}]", lo=0.0) for i, v in enumerate(items["opposite"])]
    counts = [count(v, f"counts[{i}]", minimum=0, maximum=n_sensors) for i, v in enumerate(items["counts"])]
    spreads = [scalar(v, f"spreads[{i}]", lo=1.0) for i, v in enumerate(items["spreads"])]
    for name, points in (("sizes", sizes), ("counts", counts), ("opposite", opposite), ("spreads", spreads)):
        distinct(points, name)
    widest = max(spreads, default=1.0)   # the smallest SD: 1 °C, or the spread sweep's widest**-0.5 (fuzz 68b D1)
    _resolved_truth(truth, min(1.0, widest ** -0.5), "truth and spreads" if widest > 1.0 else "truth")
    rng = np.random.default_rng(count(seed, "seed", minimum=0, maximum=None))
    e = rng.standard_normal((n_runs, n_samples, n_sensors))
    perm = np.argsort(rng.random((n_runs, n_sensors)), axis=1)
    ones = np.ones(n_sensors)
    mae: dict[tuple[str, float], dict[str, FloatArray]] = {}

    def faulty(k: int, size: float) -> FloatArray:
        bias = np.zeros((n_runs, n_sensors))
        np.put_along_axis(bias, perm[:, :k], float(size), axis=1)
        return truth + e + bias[:, None, :]

    clean = truth + e
    clean_errors: list[dict[str, FloatArray]] = []

    def errors(z: FloatArray, sigma: FloatArray) -> dict[str, FloatArray]:
        # the points without a fault and with equal noise (size 0, no faulty sensor, spread 1) fuse the same readings:
        # fused once, the arrays shared
        if not (np.array_equal(z, clean) and np.array_equal(sigma, ones)):
            return fair_errors(z, sigma, truth, methods)
        if not clean_errors:
            clean_errors.append(fair_errors(z, sigma, truth, methods))
        return dict(clean_errors[0])

    for size in sizes:
        mae[(SIZE, float(size))] = errors(faulty(2, size), ones)
    for k in counts:
        mae[(COUNT, float(k))] = errors(faulty(int(k), 5.0), ones)
    for size in opposite:
        bias = np.zeros((n_runs, n_sensors))
        np.put_along_axis(bias, perm[:, :1], float(size), axis=1)
        np.put_along_axis(bias, perm[:, 1:2], -float(size), axis=1)
        mae[(OPPOSITE, float(size))] = fair_errors(truth + e + bias[:, None, :], ones, truth, methods)
    for r in spreads:
        if not r >= 1:
            raise ValueError(f"spreads must be >= 1, got {r}")
        sig = float(r) ** np.linspace(-0.5, 0.5, n_sensors)
        mae[(SPREAD, float(r))] = errors(truth + e * sig, sig)
    return FairStudy(mae=mae, n_runs=n_runs, n_samples=n_samples, seed=seed)


#: Verdict words by the region of the paired interval against zero and the chapter's 5 % margin (rule R2).
WORDS: dict[str, str] = {"lower": "better", "higher": "worse", "equivalent": "within ±5 %",
                         "undecided": "not distinguishable"}


def _fair_study(study: object, name: str = "study") -> FairStudy:
    """``study`` when it is a :class:`FairStudy` whose every sweep point holds the errors of every method of
    :data:`FAIR_METHODS` (what :func:`verdicts` and :func:`fair_numbers` read); TypeError/ValueError naming ``name``."""
    instance_of(study, FairStudy, name)   # its constructor checked its keys, errors and counts
    for key, errs in study.mae.items():
        missing = [m for m in FAIR_METHODS if not isinstance(errs, Mapping) or m not in errs]
        if missing:
            raise ValueError(f"{name}.mae[{shown(key)}] lacks the errors of {missing} (every method of FAIR_METHODS "
                             "is read)")
    return study


def _word(cmp: Comparison) -> str:
    return WORDS[cmp.judgement().region]


def _row(method: str) -> str:
    """The row label of a method in :func:`verdicts`."""
    return f"{METHOD_LABELS.get(method, method)} ({information(method)})"


def verdicts(study: FairStudy, reference: str = "optimal_fusion_set") -> pd.DataFrame:
    """Each method against the reference at every sweep point, worded by the paired 95 % interval.

    Parameters
    ----------
    study : FairStudy
        Of at least :data:`~fusion.book.ledger.MIN_RUNS` runs (rule R4: the verdicts are paired comparisons and
        this function takes no ``reason``); fewer are refused naming ``study`` (:func:`figure_fair` draws any).
    reference : str
        Method every other is compared with.

    Returns
    -------
    DataFrame
        Rows: methods (with the information each uses); columns: (sweep, value); entries
        ``WORDS`` ("better" or "worse" than the reference beyond the practical margin of 5 % of the
        reference's error, "within ±5 %", or "not distinguishable"), or its mean error (°C) in the
        reference's row.
    """
    _fair_study(study)
    reference = one_of(reference, FAIR_METHODS, "reference")
    with runs_named("study", "fair_study's n_runs"):  # rule R4 named by the argument (fuzz 22b A2)
        return _verdicts(study, reference)


def _verdicts(study: FairStudy, reference: str) -> pd.DataFrame:
    """:func:`verdicts` of a checked study."""
    cols = {}
    for key, errs in study.mae.items():
        col = {}
        for m in FAIR_METHODS:
            if m == reference:
                col[m] = f"{errs[m].mean():.3f} °C"
            else:
                col[m] = _word(Comparison(errs[m], errs[reference], m, reference, "less", "per-run MAE (°C)",
                                          seed=study.seed))
        cols[key] = col
    df = pd.DataFrame(cols)
    df.columns = pd.MultiIndex.from_tuples(
        [(s, f"{v:g}") for s, v in df.columns], names=["sweep", "value"])
    df.index = pd.Index([_row(m) for m in df.index], name="method")
    return df


def figure_fair(study: FairStudy) -> Figure:
    """Mean absolute error of every method along each sweep (one panel each).

    Parameters
    ----------
    study : FairStudy

    Returns
    -------
    Figure
        One panel per sweep: each method's mean absolute error over the runs (°C, log scale) against the swept value.

    Raises
    ------
    ValueError
        ``study`` holding more than 32 sweeps (two rows of at most 16 panels), naming it.
    """
    _fair_study(study)
    sweeps = list(dict.fromkeys(s for s, _ in study.mae))
    if len(sweeps) > 2 * _MAX_PANELS:   # two rows of panels (fix71d's report: new_figure's "ncols" named instead)
        raise ValueError(f"study must hold at most {2 * _MAX_PANELS} sweeps (one panel each, in two rows), got "
                         f"{len(sweeps)}")
    rows = 1 if len(sweeps) <= 3 else 2
    cols = -(-len(sweeps) // rows)
    fig, axes = new_figure(rows, cols, figsize=(7.5, 4.6 if rows == 1 else 7.4), sharey=True)
    axes = np.atleast_1d(axes).ravel()
    for ax, sw in zip(axes, sweeps):
        xs = [v for s, v in study.mae if s == sw]
        for m in FAIR_METHODS:
            ys = [study.mae[(sw, v)][m].mean() for v in xs]
            ax.plot(xs, ys, marker="o", ms=3, color=color(m), label=METHOD_LABELS.get(m, m),
                    ls=_LINESTYLE.get(m, "-"))
        ax.set_xlabel(sw)
        ax.set_yscale("log")
        ax.yaxis.set_major_formatter(ScalarFormatter())
        ax.yaxis.set_minor_formatter(ScalarFormatter())
    for ax in axes[::cols]:
        ax.set_ylabel(f"mean absolute error (°C), {study.n_runs} runs")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=3)
    return fig


def fair_numbers(study: FairStudy) -> GlueValues:
    """The numbers chapter 01's prose quotes from the fair study (glue keys ``ofs_fair_*``).

    Parameters
    ----------
    study : FairStudy
        The result of :func:`fair_study`, of at least :data:`~fusion.book.ledger.MIN_RUNS` runs (its
        :func:`verdicts`; fewer are refused naming ``study``).

    Returns
    -------
    GlueValues
        Glue key -> value: mean absolute errors (°C, 3 decimals) of the clean, largest-fault, most-faults
        and widest-spread settings; the settings where the optimal fusion set beats every other method (listed in
        ascending order, whatever the order of the sweeps);
        the equal-weight ablation's largest relative change and its verdict counts; the spread settings
        where the arithmetic mean is better or worse.

    References
    ----------
    * Yang G. N., Feng X. F., Fan L. J. (2012). Multi-sensor data fusion algorithm based on optimal fusion set.
    """
    _fair_study(study)
    for sweep, first in ((SIZE, (SIZE, 0.0)), (COUNT, None), (SPREAD, None)):
        if (first is not None and first not in study.mae) or not any(k[0] == sweep for k in study.mae):
            raise ValueError(f"study must hold the sweep {shown(sweep)}" + (" with the point 0" if first else "")
                             + " (fair_numbers reads it), as fair_study's default sweeps do")
    F = {k: {m: float(v.mean()) for m, v in e.items()} for k, e in study.mae.items()}
    V = verdicts(study)  # names study when its runs are fewer than rule R4's minimum
    others = [_row(m) for m in FAIR_METHODS if m not in ("optimal_fusion_set", "uniform_set")]
    # the points in ascending order, whatever the sweeps' order (fuzz 26d DB3: "8, 6, 4" glued for a reversed sweep,
    # and the "largest" size, count and spread read as the last point given, not the largest)
    size_keys = sorted(k for k in study.mae if k[0] == SIZE)
    opp_keys = sorted(k for k in study.mae if k[0] == OPPOSITE)
    beaten = ("mean", "huber", "trimmed_mean_25")
    opp_lose = [k[1] for k in opp_keys if all(V.loc[_row(m), (k[0], f"{k[1]:g}")] == "better" for m in beaten)]
    size_win = [k[1] for k in size_keys if (V.loc[others, (k[0], f"{k[1]:g}")] == "worse").all()]
    count_keys = sorted(k for k in study.mae if k[0] == COUNT)
    spread_keys = sorted(k for k in study.mae if k[0] == SPREAD)
    count_win = [k[1] for k in count_keys if (V.loc[others, (k[0], f"{k[1]:g}")] == "worse").all()]
    abl = [abs(F[k]["uniform_set"] / F[k]["optimal_fusion_set"] - 1) for k in study.mae]
    k_abl = list(study.mae)[int(np.argmax(abl))]
    return {
        "ofs_fair_runs": study.n_runs, "ofs_fair_samples": study.n_samples,
        "ofs_fair_clean_ofs": rounded(F[(SIZE, 0.0)]["optimal_fusion_set"], 3),
        "ofs_fair_clean_mean": rounded(F[(SIZE, 0.0)]["mean"], 3),
        "ofs_fair_clean_median": rounded(F[(SIZE, 0.0)]["median"], 3),
        "ofs_fair_clean_huber": rounded(F[(SIZE, 0.0)]["huber"], 3),
        "ofs_fair_clean_all_better": bool((V.loc[others, (SIZE, "0")] == "better").all()),
        "ofs_fair_size_win": ", ".join(f"{s:g}" for s in size_win) or "none",
        "ofs_fair_big_biweight": rounded(F[size_keys[-1]]["biweight"], 3),
        "ofs_fair_big_madrej": rounded(F[size_keys[-1]]["mad_reject"], 3),
        "ofs_fair_big_ofs": rounded(F[size_keys[-1]]["optimal_fusion_set"], 3),
        "ofs_fair_big_median": rounded(F[size_keys[-1]]["median"], 3),
        "ofs_fair_big_huber": rounded(F[size_keys[-1]]["huber"], 3),
        "ofs_fair_big_mean": rounded(F[size_keys[-1]]["mean"], 3),
        "ofs_fair_big_size": f"{size_keys[-1][1]:g}",
        "ofs_fair_count_win": ", ".join(f"{c:g}" for c in count_win) or "none",
        "ofs_fair_max_count": f"{count_keys[-1][1]:g}",
        "ofs_fair_halfway": {m: rounded(F[count_keys[-1]][m], 3) for m in ("optimal_fusion_set", "median")}["optimal_fusion_set"],
        "ofs_fair_halfway_median": rounded(F[count_keys[-1]]["median"], 3),
        "ofs_fair_spread_max": f"{spread_keys[-1][1]:g}",
        "ofs_fair_spread_ivar": rounded(F[spread_keys[-1]]["inverse_variance"], 3),
        "ofs_fair_spread_ofs": rounded(F[spread_keys[-1]]["optimal_fusion_set"], 3),
        "ofs_fair_spread_median": rounded(F[spread_keys[-1]]["median"], 3),
        "ofs_fair_abl_max": rounded(max(abl), 3), "ofs_fair_abl_where": f"{k_abl[0]} = {k_abl[1]:g}",
        "ofs_fair_abl_ofs": rounded(F[k_abl]["optimal_fusion_set"], 3), "ofs_fair_abl_uni": rounded(F[k_abl]["uniform_set"], 3),
        "ofs_fair_abl_median": rounded(float(np.median(abl)), 4),
        "ofs_fair_abl_n": len(study.mae),
        "ofs_fair_opp_lose": ", ".join(f"{b:g}" for b in opp_lose) or "none",
        "ofs_fair_opp_size": f"{opp_keys[0][1]:g}" if opp_keys else "none",
        **({f"ofs_fair_opp_{m}": rounded(F[opp_keys[0]][m], 3) for m in ("optimal_fusion_set",) + beaten}
           if opp_keys else {}),
        **{f"ofs_fair_abl_n_{k}": int((V.loc[_row("uniform_set")] == w).sum())
           for k, w in (("better", "better"), ("worse", "worse"), ("nd", "not distinguishable"),
                        ("eq", WORDS["equivalent"]))},
        "ofs_fair_spread_mean_better_upto": ", ".join(f"{k[1]:g}" for k in spread_keys
                                                       if V.loc[_row("mean"), (k[0], f"{k[1]:g}")] == "better"),
        "ofs_fair_spread_ofs_better_from": ", ".join(f"{k[1]:g}" for k in spread_keys
                                                      if V.loc[_row("mean"), (k[0], f"{k[1]:g}")] == "worse"),
        "ofs_fair_spread_median_words": ", ".join(f"{V.loc[_row('median'), (SPREAD, f'{k[1]:g}')]} at {k[1]:g}"
                                                  for k in spread_keys),
    }


def _ledger_comparisons(ledger: Mapping) -> list[tuple[object, str, object, Mapping]]:
    """The paired comparisons a stored ledger's records hold, checked as they are read (fuzz 21b M): (record id,
    reading, status, evidence) of each primary reading, counted alternative and part of a conjunction whose evidence
    is a comparison. A nested record that is not a mapping, lacks a key read here or holds a value that is not a
    finite number is refused with an error naming ``ledger`` and the record's path. ``None`` is read where
    ``Ledger.records()`` stores it for valid evidence (fuzz 40b C1, D1), and only there: ``mean_b`` of an infinite
    mean (B's; any end of its interval then, an end of R3's median interval of two infinite means included, each
    ``None`` for an infinite or undefined end); with a finite ``mean_b``, both ends (an infinite A's mean: no
    interval) or neither. ``margin`` is always a number."""
    out = []
    for i, r in enumerate(ledger["claims"]):
        path = f"ledger['claims'][{i}]"
        readings = [("primary", r["primary_status"], r["evidence"], f"{path}['evidence']")]
        for j, a in enumerate(records_of(r.get("alternatives", []), f"{path}['alternatives']")):
            if a.get("counted"):
                where = f"{path}['alternatives'][{j}]"
                record(a, where, ("reading", "status", "evidence"), extra=True)
                if not isinstance(a["reading"], str):
                    raise TypeError(f"{where}['reading'] must be a str, got {type(a['reading']).__name__}")
                readings.append((a["reading"].split("; ")[0].split(" (")[0], a["status"], a["evidence"],
                                 f"{where}['evidence']"))
        for name, status, ev, where in readings:
            record(ev, where, (), extra=True)
            parts = [("", status, ev, where)]
            if ev.get("kind") == "conjunction":
                record(ev, where, ("parts",), extra=True)
                parts = [(p["label"], p["status"], p["evidence"], f"{where}['parts'][{k}]['evidence']") for k, p in
                         enumerate(records_of(ev["parts"], f"{where}['parts']", ("label", "status", "evidence")))]
            for label, st, e, at in parts:
                if record(e, at, (), extra=True).get("kind") != "comparison":
                    continue
                record(e, at, ("mean_b", "ci_low", "ci_high", "margin"), extra=True)
                ends = ("ci_low", "ci_high")
                if e["mean_b"] is None:   # B's mean infinite: an end may be infinite (stored None) or finite
                    ends = tuple(k for k in ends if e[k] is not None)
                elif e["ci_low"] is None and e["ci_high"] is None:   # a finite B's mean and no interval: A's infinite
                    ends = ()
                for key in ("margin",) + (() if e["mean_b"] is None else ("mean_b",)) + ends:
                    scalar(e[key], f"{at}[{key!r}]")
                out.append((r["id"], label or name, st, e))
    return out


def margin_sensitivity(ledger: dict, low: float = 0.025, high: float = 0.10) -> pd.DataFrame:
    """Where a nearby practical margin would change a comparison's status: break-even margins from a stored ledger.

    A paired comparison's status depends on its margin m only through the order of m and the interval's ends, so it
    can change only where m, relative to the baseline's value, crosses ``abs(lo) / abs(baseline)`` or
    ``abs(hi) / abs(baseline)``.

    Parameters
    ----------
    ledger : dict
        A stored ledger (``book/ledger/<source>.json``, parsed).
    low, high : float
        Relative margins kept: only comparisons with a break-even margin in ``[low, high]`` are listed.

    Returns
    -------
    DataFrame
        One row per primary reading, counted reading or part of one, whose status would change at a relative
        margin in ``[low, high]``: record, reading, status, 95 % interval, margin used and the break-even margins.
        A comparison without an interval (both ends ``None``: an infinite mean), with an infinite baseline mean
        (``mean_b`` ``None``: no relative margin) or with a baseline of 0 has no break-even margin and no row.

    Raises
    ------
    TypeError
        ``ledger`` is not a mapping, a nested record not a mapping, or a value read here not a number.
    ValueError
        ``low`` or ``high`` out of range; ``ledger`` lacks the list ``claims``, or a record (a claim, a counted
        alternative, a part of a conjunction, a comparison) lacks a key read here or holds a number that is not
        finite; the message names ``ledger`` and the record's path.
    """
    low = scalar(low, "low", lo=0.0)
    high = scalar(high, "high", lo=low)
    if not isinstance(ledger, Mapping):
        raise TypeError(f"ledger must be a dict (a parsed stored ledger), got {type(ledger).__name__}")
    if not isinstance(ledger.get("claims"), list):
        raise ValueError("ledger must hold a list under 'claims' (a parsed book/ledger/<source>.json)")
    for i, r in enumerate(ledger["claims"]):
        need = ("id", "primary_status", "evidence")
        if not isinstance(r, Mapping) or any(k not in r for k in need):
            raise ValueError(f"ledger['claims'][{i}] must be a record with the keys {need}")
    rows = []
    for rid, label, st, e in _ledger_comparisons(ledger):
        if not e["mean_b"] or e["ci_low"] is None:   # no relative margin / no interval: nothing to cross
            continue
        even = sorted({abs(e["ci_low"]) / abs(e["mean_b"]), abs(e["ci_high"]) / abs(e["mean_b"])})
        near = [v for v in even if low <= v <= high]
        if near:
            rows.append({"record": rid, "reading": label, "status": st,
                         "95 % interval": f"[{e['ci_low']:.4f}, {e['ci_high']:.4f}]",
                         "margin": f"±{e['margin']:.4f}", "status changes at a margin of":
                         " or ".join(f"{v:.1%}" for v in near)})
    return pd.DataFrame(rows).set_index(["record", "reading"]) if rows else pd.DataFrame(rows)


#: Fault shapes of :func:`fault_shapes_study`, in table order.
FAULT_SHAPES: tuple[str, ...] = ("no fault", "drift (ramp to +4, +8 °C)", "stuck at the last healthy reading",
                                 "noise inflated ×4, ×8", "offsets N(0, 1 °C²), no failure",
                                 "offsets N(0, 1 °C²) + the source's failure", "true value 905 °C, not 900 °C")


def ew_variance_fuse(z: ArrayLike, lam: float = 0.2, floor: float = 1e-3) -> FloatArray:
    """A baseline that uses time: inverse-variance weights from an exponentially weighted per-sensor variance.

    Each sensor's variance is tracked as the exponentially weighted mean (factor ``lam``) of its squared
    residual to the cross-sensor median, using the samples *before* the current one (the first sample is fused
    by the mean); the current sample is fused by the weighted mean with weights 1 / variance. A sensor whose
    readings leave the others for several samples loses its weight; no noise level is given to it.

    Parameters
    ----------
    z : array_like, shape (n_runs, n_samples, n_sensors)
    lam : float
        Weight of the newest squared residual, in (0, 1].
    floor : float
        Lower bound of a variance (°C²).

    Returns
    -------
    ndarray, shape (n_runs, n_samples)
        Fused values.

    Raises
    ------
    ValueError
        ``z`` not a finite 3-D array or beyond the work budget (``fusion._limits.MAX_WORK``: 2,000 units a sample
        plus 8 a reading), ``lam`` not in (0, 1], ``floor`` not positive.
    """
    arr = as_array(z, "z", ndim=3)
    lam = scalar(lam, "lam", lo=0.0, hi=1.0, lo_open=True)
    floor = scalar(floor, "floor", lo=0.0, lo_open=True)
    # book audit 76 (no budget: a (1, 1.6 * 10**7, 2) z, accepted, about 160 CPU-s): the loop over the samples cost
    # 10 us a step (z (1, 10**5, 3): 0.98 CPU-s) and 40 ns a reading (z (1000, 100, 10): 0.04 CPU-s; process_time,
    # OPENBLAS_NUM_THREADS=1, minimum of 2, shared 2-core machine): 2 * LOOP_STEP a step, 8 units a reading
    loop_work((arr.shape[1],), 8 * arr.shape[0] * arr.shape[2], "z", step=2 * LOOP_STEP)
    res2 = (arr - np.median(arr, axis=2, keepdims=True)) ** 2
    out = np.empty(arr.shape[:2])
    out[:, 0] = arr[:, 0].mean(axis=1)
    var = np.maximum(res2[:, 0], floor)
    for t in range(1, arr.shape[1]):
        w = 1.0 / var
        out[:, t] = (w * arr[:, t]).sum(axis=1) / w.sum(axis=1)
        var = np.maximum((1.0 - lam) * var + lam * res2[:, t], floor)
    return out


def fault_shapes_study(seed: int, n_runs: int = 500, sigma: ArrayLike = np.linspace(0.5, 2.0, 10),
                       truth: float = 900.0) -> dict[str, dict[str, FloatArray]]:
    """Per-run mean absolute error over samples 50-80 under fault shapes the source does not simulate.

    Ten sensors, 100 samples, noise σ as given (default: the chapter's primary reading, 0.5-2.0 °C), the same
    standard-normal draws for every shape and method. Sensors 4 and 10 fail at samples 50-80 as in the source,
    in other shapes: a drift rising linearly to +4 and +8 °C at sample 80; stuck at their sample-49 reading; noise
    multiplied by 4 and 8. Then per-sensor offsets drawn once per run from N(0, 1 °C²) (E[v_i] ≠ 0, which source
    eq. 1 allows), alone and with the source's failure (+4, +8 °C); and a true value of 905 °C instead of the
    900 °C set point (every method here is translation-equivariant, so its errors equal those of "no fault").

    Parameters
    ----------
    seed : int
        Seed of the draws.
    n_runs : int
        Runs (each of 100 samples of the 10 sensors).
    sigma : array_like, shape (10,)
        Noise SD of each sensor (°C), or one SD for all.
    truth : float
        The set point (°C).

    Returns
    -------
    dict
        shape (``FAULT_SHAPES``, this module's five shapes) -> method ("optimal_fusion_set", "mean", "median",
        "ew_variance") ->
        per-run mean absolute error over samples 50-80 (°C), rounded to 1e-9.

    Raises
    ------
    TypeError
        ``seed`` or ``n_runs`` not an integer, ``sigma`` or ``truth`` not numeric.
    ValueError
        ``n_runs`` below 1, or the draws of every shape (``n_runs`` x 100 x 10 each) beyond the memory budget
        (``fusion._counts.MAX_ELEMENTS``) or their fusions beyond the work budget (``fusion._limits.MAX_WORK``: about
        12,000 runs, 6 CPU-s); ``sigma`` not one positive SD or 10; ``truth`` not finite; ``truth and sigma`` when
        the float spacing at ``truth`` is beyond 1e-3 of the smallest SD (the noise and the faults lost in the
        rounding); ``sigma and truth`` when the readings derived from them (truth plus noise, the noise inflated
        x8, faults up to 8 °C) exceed the representable range (``MAX_MAGNITUDE``), before any fusion.
    """
    seed = check_seed(seed)
    n_runs = count(n_runs, "n_runs")
    # before anything is drawn (fuzz 29b D4: 10**6 runs drew 7.45 GiB): the draws and the cases built from them held
    # at once, then each method's fusion of each case (FAIR_WORK per element, as fair_study's budget)
    allocation((len(FAULT_SHAPES) + 2, n_runs, 100, 10), "n_runs")
    work((len(FAULT_SHAPES), len(_FAULT_METHODS), n_runs, 100, 10, FAIR_WORK), "n_runs")
    truth = scalar(truth, "truth")
    sig_in = as_array(sigma, "sigma", ndim=(0, 1))
    if sig_in.shape not in ((), (1,), (10,)) or np.any(sig_in <= 0):
        raise ValueError(f"sigma must be one positive SD or 10 (one per sensor), got shape {sig_in.shape}")
    _resolved_truth(truth, float(np.min(sig_in)), "truth and sigma")   # fuzz 68b D1
    rng = np.random.default_rng(seed)
    sig = np.broadcast_to(sig_in, (10,))   # the array read (fuzz 29b B1)
    e = rng.standard_normal((n_runs, 100, 10)) * sig
    offsets = rng.standard_normal((n_runs, 1, 10))
    # the readings' bound (noise inflated x8; offsets and 8 °C faults; +5 °C) before any is built or fused (fuzz 68b
    # C6: sigma = 3e149 was refused by an internal fusion naming "x", not an argument; 2.1 CPU-s at 10,000 runs)
    big, off_big = float(np.max(np.abs(e))), float(np.max(np.abs(offsets)))
    _readings_in_range(abs(truth) + max(8.0 * big, big + off_big + 8.0, big + 5.0), "sigma and truth")
    cols, win = np.array([3, 9]), slice(49, 80)
    ramp = np.zeros((100, 1))
    ramp[win, 0] = np.linspace(1.0 / 31.0, 1.0, 31)
    base = truth + e
    drift = base.copy()
    drift[:, :, cols] += ramp * np.array([4.0, 8.0])
    stuck = base.copy()
    stuck[:, win, cols] = base[:, 48:49, cols]
    noisy = base.copy()
    noisy[:, win, cols] = truth + e[:, win, cols] * np.array([4.0, 8.0])
    off = base + offsets
    off_fail = off.copy()
    off_fail[:, win, cols] += np.array([4.0, 8.0])
    cases = dict(zip(FAULT_SHAPES, ((base, truth), (drift, truth), (stuck, truth), (noisy, truth), (off, truth),
                                    (off_fail, truth), (base + 5.0, truth + 5.0))))
    out: dict[str, dict[str, FloatArray]] = {}
    for name, (z, true) in cases.items():
        zw = z[:, win].reshape(-1, 10)
        vals = {"optimal_fusion_set": rd.fuse_epochs(zw, "optimal_fusion_set").values,
                "mean": zw.mean(axis=1), "median": np.median(zw, axis=1),
                "ew_variance": ew_variance_fuse(z)[:, win].ravel()}
        out[name] = {m: np.round(np.abs(v - true).reshape(n_runs, 31).mean(axis=1), 9) for m, v in vals.items()}
    return out


#: The methods of each fault shape of :func:`fault_shapes_study`.
_FAULT_METHODS = ("optimal_fusion_set", "mean", "median", "ew_variance")


def fault_shapes_table(study: Mapping[str, Mapping[str, FloatArray]], seed: int | None = None) -> pd.DataFrame:
    """The optimal set against the mean and the median, and the time-using baseline against the optimal set.

    Each comparison is the paired 95 % interval of the per-run difference (rows of :func:`fault_shapes_study`)
    against the chapter's one margin, 5 % of the second method's mean error, worded as in :func:`verdicts`.

    Parameters
    ----------
    study : dict
        The output of :func:`fault_shapes_study`.
    seed : int or None

    Returns
    -------
    DataFrame
        One row per fault shape: the four mean errors (°C) and, for each pair, the word and the interval.

    Raises
    ------
    TypeError
        ``study`` not a mapping of mappings, an error array not numeric.
    ValueError
        ``study`` empty, a shape's entry not holding exactly the four methods of :func:`fault_shapes_study`, or
        its error arrays not finite, 1-D and of one length (naming ``study[shape]``).
    """
    seed = None if seed is None else check_seed(seed)
    instance_of(study, Mapping, "study")
    if not study:
        raise ValueError("study must hold at least one fault shape (the output of fault_shapes_study), got none")
    checked = {}  # read once, and the arrays the checks return are what the table reads (fuzz 31a C2, C3)
    for shape, errs in read_mapping(study, "study").items():
        where = f"study[{shown(shape)}]"
        errs = read_mapping(errs, where)
        record(errs, where, _FAULT_METHODS)
        arrays = [as_array(errs[m], f"{where}[{shown(m)}]", ndim=1) for m in _FAULT_METHODS]
        if len({a.size for a in arrays}) != 1:
            raise ValueError(f"{where} must hold one error per run for every method, got the lengths "
                             f"{[a.size for a in arrays]}")
        checked[shape] = {m: arrays[_FAULT_METHODS.index(m)] for m in errs}
    pairs = (("optimal_fusion_set", "mean"), ("optimal_fusion_set", "median"), ("ew_variance", "optimal_fusion_set"))
    label = {"optimal_fusion_set": "optimal set", "mean": "mean", "median": "median", "ew_variance": "EW variance"}
    rows = {}
    for shape, errs in checked.items():
        row: dict[str, str] = {f"{label[m]} (°C)": f"{errs[m].mean():.3f}" for m in errs}
        for a, b in pairs:
            with runs_named("study", "fault_shapes_study's runs"):  # rule R4 named (fuzz 22b A2)
                cmp = Comparison(errs[a], errs[b], a, b, "less", "per-run MAE (°C)", seed=seed)
            _, lo, hi = cmp.interval()
            row[f"{label[a]} vs {label[b]}"] = f"{_word(cmp)} [{lo:+.3f}, {hi:+.3f}]"
        rows[shape] = row
    df = pd.DataFrame(rows).T
    df.index.name = "fault shape (sensors 4, 10; samples 50-80)"
    return df
