"""Chapter 05's shared checks of what its glue and table functions read (issue 35, fuzz 19's class D).

Most of the chapter's number and table functions read a table or a mapping that another function of the package
made (:func:`~fusion.book.chapters.ci.architecture_table`, :func:`~fusion.scenarios.two_sensor.rmse_variants`,
:func:`~fusion.book.chapters.ci.printed_equation_checks`, ...). Each checks it here first, by one rule: a mapping
holds the keys it reads (``_entries``) or only results of the expected class (``_results``), a table the columns
it reads (``_frame``, shared with chapter 01), so that another table or mapping is a ``TypeError``/``ValueError``
naming the argument and its maker, never a ``KeyError``, ``AttributeError`` or ``IndexError`` from inside.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping

import numpy as np
import pandas as pd

from fusion._results import real_key
from fusion._shown import shown
from fusion._limits import MAX_INPUT_ELEMENTS
from fusion._validation import (FloatArray, as_array, distinct_printed, general, given_entries, input_size, read_mapping,
                               read_once, scalar)
from fusion.book.chapters.lecture import _frame  # noqa: F401 (the chapter's modules import it from here)

__all__: list[str] = []   # nothing public: the chapter's functions document these checks in their Raises sections


def _entries(value: object, name: str, keys: Collection[object], maker: str, *, width: int | None = None,
             numbers: bool = True, nonnegative: bool = False) -> Mapping:
    """``value`` when it is a mapping holding ``keys`` (the entries read), each a finite number (``width`` finite
    numbers when given; not checked when not ``numbers``), non-negative when ``nonnegative`` (an RMSE, a NEES, a
    bound, a time: fuzz 24c, NEG); TypeError/ValueError naming ``name`` and ``maker``, the
    function whose result it must be. Returned as a new dict whose checked entries are the floats (float arrays)
    read, so that a caller computes with those, never with the caller's Decimal, Fraction or 0-d array (fuzz 22b,
    FR); not checked entries as given."""
    if not isinstance(value, Mapping):
        raise TypeError(f"{name} must be a mapping (the result of {maker}), got {type(value).__name__}")
    value = read_mapping(value, name)  # read once: its entries checked and used as one read (decision 31a C2)
    missing = [k for k in keys if k not in value]
    if missing:
        raise ValueError(f"{name} lacks the keys {shown(missing, 200)} (a result of {maker} holds them)")
    out = dict(value)
    for k in keys if numbers else ():
        if width is None:
            out[k] = scalar(out[k], f"{name}[{shown(k)}]", 0.0 if nonnegative else None, tiny=True)
        else:
            out[k] = as_array(out[k], f"{name}[{shown(k)}]", shape=(width,), subnormal=True,
                              nonnegative=nonnegative)
    return out


def _counted(value: object, name: str) -> tuple[object, int]:
    """The sequence or array argument ``value`` as read once, and its entries' count (:func:`_given_count`), the
    count a work budget refuses first: an object with ``__array__`` (or a buffer, an ``array.array``, a user's
    Sequence class), which has no shape or length to count, is converted here once (``read_once``, by its protocol:
    the caller then checks and computes with that array, never a second conversion) and counted by the array's
    shape; a list or tuple subclass whose ``len()`` disagrees with its entries is refused naming ``name`` (numpy
    converts its entries, not its ``len()``). Fuzz 68b C1, C1b, C2: both counted one, so 6,000 periods or 150 levels
    ran 20-24 CPU-s under a budget of one."""
    for base in (list, tuple):
        if isinstance(value, base) and type(value) is not base:
            given, held = _length(value, name), base.__len__(value)  # type: ignore[arg-type]
            if given != held:
                raise ValueError(f"{name} has len() {given} but {held} entries (a {type(value).__name__} whose len() "
                                 "disagrees with its entries)")
    value = read_once(value, name)
    return value, _given_count(value, name)


def _length(value: object, name: str) -> int:
    """``len(value)``, the argument's own exception re-raised as a TypeError naming ``name`` (rule 15)."""
    try:
        return len(value)  # type: ignore[arg-type]
    except Exception as exc:  # noqa: BLE001 (the argument's own exception, named and chained)
        raise TypeError(f"{name} has no length: it raised {type(exc).__name__}: {str(exc):.200}") from exc


def _given_count(value: object, name: str) -> int:
    """The number of entries of the sequence or array argument ``value``, read from its lengths or shape before any
    conversion or entry-by-entry check (``fusion._validation.given_entries``; a scalar or anything else counts one:
    an object without shape or length is counted after :func:`_counted` has read it): the count a work budget refuses
    first (book audit 76: a list of 10**7 seeds, omegas or levels was converted and
    checked entry by entry, seconds, before the budget its length sets). Beyond the input budget it is refused
    naming ``name`` (``input_size``)."""
    n = given_entries(value, MAX_INPUT_ELEMENTS)   # one pass over a list's entries (0.7 CPU-s at the input budget)
    if n is not None and n > MAX_INPUT_ELEMENTS:
        input_size(value, name)   # its refusal, by name
    return 1 if n is None else max(1, int(np.ceil(n)))


def _exact_keys(value: Mapping, name: str, keys: Collection[object], maker: str) -> None:
    """A caller's {method: value} mapping beside a study holds exactly the study's methods ``keys``, those of
    ``maker`` on it (fuzz 38b C2, D3): a key the study did not run (its value flowed into a glued minimum) or a
    method it ran left out is a ValueError naming ``name``, both listed."""
    extra = [k for k in value if k not in keys]
    missing = [k for k in keys if k not in value]
    if extra or missing:
        parts = ([f"holds {shown([str(k) for k in extra], 200)} that the study did not run"] if extra else []) + (
            [f"lacks {shown([str(k) for k in missing], 200)} that it ran"] if missing else [])
        raise ValueError(f"{name} must hold exactly the study's methods, as {maker} gives them: it "
                         f"{' and '.join(parts)}")


def _results(value: object, name: str, cls: type, maker: str) -> Mapping:
    """``value`` (a mapping that is not a dict read once into one) when it is a non-empty mapping of labels to ``cls``
    instances (the results of ``maker``); TypeError/ValueError naming ``name``."""
    if not isinstance(value, Mapping):
        raise TypeError(f"{name} must be a mapping of labels to {cls.__name__} (from {maker}), got "
                        f"{type(value).__name__}")
    value = read_mapping(value, name)  # the checked results are the ones returned (decision 31a C2)
    if not value:
        raise ValueError(f"{name} must hold at least one {cls.__name__} (from {maker}), got an empty mapping")
    for k, v in value.items():
        if not isinstance(v, cls):
            raise TypeError(f"{name}[{shown(k)}] must be a {cls.__name__} (from {maker}), got {type(v).__name__}")
    return value


def _steps(value: object, name: str, n: int, what: str = "step") -> np.ndarray:
    """A selection of steps (issue 35, the chapter's registry sweep): an array of bools, one per ``what`` of ``n``;
    TypeError (not bools) / ValueError (another length or shape) naming ``name``, before it indexes anything."""
    from fusion._selections import as_mask

    m = as_mask(value, name)
    if m.shape != (n,):
        raise ValueError(f"{name} must hold one bool per {what} ({n},), got shape {m.shape}")
    return m


def _per_step(value: object, name: str, n: int, what: str = "selected step", *, nonnegative: bool = False,
              unit: bool = False) -> FloatArray:
    """A number per step (a floor, a weight): a finite float array of shape ``(n,)`` (entries in [0, 1] when
    ``unit``); TypeError/ValueError naming ``name``, never numpy's broadcasting or indexing error."""
    arr = as_array(value, name, ndim=1, nonnegative=nonnegative or unit)
    if arr.shape != (n,):
        raise ValueError(f"{name} must hold one number per {what} ({n},), got shape {arr.shape}")
    if unit and (arr > 1.0).any():
        raise ValueError(f"{name} must hold weights in [0, 1], got {shown(float(arr.max()))} at index "
                         f"{int(np.argmax(arr))}")
    return arr


def _step_index(value: object, name: str, length: int) -> int:
    """A step (run) index: an integer (not a bool or a float) in ``0 .. length - 1``, named; never an IndexError or
    a comparison's TypeError from inside."""
    from fusion._counts import index

    return index(value, name, length)


def _indices(value: object, name: str, length: int) -> list[int]:
    """Step or run indices (a non-empty sequence), each an integer in ``0 .. length - 1``, named by position."""
    from fusion._counts import index, sequence

    items = sequence(value, name, minimum=1)
    return [index(v, f"{name}[{i}]", length) for i, v in enumerate(items)]


def _sensor_noises(R1: object, R2: object, names: tuple[str, str] = ("R1", "R2")) -> None:
    """The two sensors' measurement covariances as :func:`fusion.scenarios.two_sensor.two_sensor_scenario` reads
    them (diagonal 2 × 2, positive definite), checked under the chapter function's own names before they are
    passed on (where the scenario would name its ``R_a`` and ``R_b``)."""
    from fusion._covariances import diagonal_covariance

    for R, name in zip((R1, R2), names):
        diagonal_covariance(R, 2, name)


def _narrow(value: object) -> bool:
    """``value`` a float narrower than float64 that ``_period_key`` reads as it prints: a NumPy scalar or a plain
    array (never a masked one, whose mask a rebuild would drop: it goes to its reader unchanged, which refuses it
    by the masked-array rule, ``fusion._counts.not_masked``; fuzz 28b C1)."""
    if isinstance(value, np.floating):
        return value.dtype.itemsize < 8
    return (isinstance(value, np.ndarray) and not isinstance(value, np.ma.MaskedArray) and value.dtype.kind == "f"
            and value.dtype.itemsize < 8)


def _period_key(value: object) -> object:
    """The chapter's one rule for a period or weight that keys a table row or a dict entry (fuzz 26c q2): a float
    narrower than float64 (float32, float16) is read as the number it prints as, its shortest decimal
    (``np.float32(0.02)`` is 0.02 s, not 0.019999999552965164, which no reader of the row 0.02 finds), alone or
    as an entry of an array, list or tuple of them (fuzz 27b B2: a list's float32 entries were kept), or a pandas
    Series or Index of float32/float16 (read as its array; fuzz 30b D1); any
    other value unchanged, checked by its reader: a masked array (fuzz 28b C1) and a nested list (one level only:
    fuzz 28b C2, a deep one recursed) reach the reader's rules as the caller gave them."""
    if isinstance(value, np.floating) and _narrow(value):
        return float(str(value))
    if isinstance(value, (pd.Series, pd.Index)) and value.dtype.kind == "f" and value.dtype.itemsize < 8:
        return _period_key(value.to_numpy())  # the book's usual container, read as its array (fuzz 30b D1)
    if isinstance(value, np.ndarray) and _narrow(value):
        return np.array([float(str(v)) for v in value.ravel()]).reshape(value.shape)
    if isinstance(value, (list, tuple)) and any(_narrow(v) for v in value):
        return (list if isinstance(value, list) else tuple)(_period_key(v) if _narrow(v) else v for v in value)
    return value


#: What the keys of a real-keyed dict mean, as its ``check_key`` (``fusion._results.real_key``; fuzz 32b C2: a period
#: NaN, inf or -1 s was glued under a valid-looking key, ``ci_fig6_d_1`` for -1 s): a period (s) is finite and > 0;
#: a fixed CI weight ω is in [0, 1] (as ``slip_at_weights`` reads it); a λ-cut level in (0, 1) (as ``fuzzy_levels``
#: reads it).
PERIOD_KEY, WEIGHT_KEY, LEVEL_KEY = real_key(0.0, lo_open=True), real_key(0.0, 1.0), real_key(0.0, 1.0, lo_open=True,
                                                                                                hi_open=True)


def _periods(periods: object, name: str = "periods") -> FloatArray:
    """Sampling periods, one table row each (fuzz 19's debatable empties): a non-empty 1-d array of distinct,
    finite, positive numbers (a scalar is one period), float32 ones read as they print (:func:`_period_key`), no
    two alike to 6 significant digits (the ledger keys its readings by ``f"{T:g}"``: fuzz 30b B3);
    TypeError/ValueError naming ``name``."""
    periods = _period_key(periods)
    arr = as_array(periods, name, ndim=(0, 1))
    arr = np.atleast_1d(arr)
    if (arr <= 0).any():
        raise ValueError(f"{name} must hold positive sampling periods (s), got {shown(arr.tolist(), 120)}")
    if np.unique(arr).size != arr.size:
        raise ValueError(f"{name} must hold distinct sampling periods (one row each), got {shown(arr.tolist(), 120)}")
    distinct_printed(arr.tolist(), name, general, "keys a reading of the ledger")  # f"{T:g}" (fuzz 30b B3)
    return arr


def _averaging_start(t_min: object, duration: object, name: str = "t_min") -> tuple[float, float]:
    """The start of a time average over scans at ``0, T, ..., duration`` (fuzz 19, F3/F4): ``0 <= t_min <=
    duration``, so that the average covers at least one scan; ``(t_min, duration)`` as floats."""
    duration = scalar(duration, "duration", lo=0.0, lo_open=True)
    t_min = scalar(t_min, name, lo=0.0, tiny=True)
    if t_min > duration:
        raise ValueError(f"{name} = {t_min:g} s is after the end of the track (duration = {duration:g} s): "
                         "the average would cover no scan")
    return t_min, duration


def _start_on(t_min: object, t: np.ndarray, name: str = "t_min") -> float:
    """The start of a time average over the scans ``t`` (the rule of :func:`_averaging_start` for given scans):
    ``0 <= t_min <= max(t)``; TypeError/ValueError naming ``name``."""
    t_min = scalar(t_min, name, lo=0.0, tiny=True)
    if t_min > float(np.max(t)):
        raise ValueError(f"{name} = {t_min:g} s is after the last scan ({float(np.max(t)):g} s): the average would "
                         "cover no scan")
    return t_min


def _study_of(sc: object, study: object, sc_name: str = "sc", study_name: str = "study") -> None:
    """``study`` a :func:`fusion.scenarios.two_sensor.fusion_study` of the scenario ``sc`` (fuzz 22b MM): both of
    their types, the same steps and truth, and the study's local-filter estimates of the two sensors those of
    ``sc``'s tracks (what identifies the scenario's seed and runs: the truth is the same path at every seed).
    A ValueError names ``study`` and ``sc`` when they differ, before another seed's tracks are set against the
    study's truth (plausible wrong slips) or the study's runs against ``sc``'s."""
    from fusion._validation import instance_of
    from fusion.scenarios.two_sensor import FusionStudy, Scenario, StudyMethod

    instance_of(sc, Scenario, sc_name)
    instance_of(study, FusionStudy, study_name)
    assert isinstance(sc, Scenario) and isinstance(study, FusionStudy)
    if study.t.shape != sc.t.shape or not np.array_equal(study.t, sc.t) or not np.array_equal(study.truth, sc.truth):
        raise ValueError(f"{study_name} must be fusion_study of {sc_name}: their steps or truth differ "
                         f"({study.t.size} and {sc.t.size} steps)")
    for method, track in zip((StudyMethod.SENSOR_1, StudyMethod.SENSOR_2), sc.tracks):
        est = study.est.get(method)
        if est is not None and (est.shape != track.est.shape or not np.array_equal(est, track.est)):
            raise ValueError(f"{study_name} must be fusion_study of {sc_name}: its local tracks ({method.value}) "
                             f"are not {sc_name}'s (another seed, runs or scenario)")


def _optima_of(P1: object, P2: object, res: object = None, seeds: object = None, *,
               names: tuple[str, str, str, str] = ("P1", "P2", "res", "seeds"), rtol: float = 1e-9) -> None:
    """The optima ``res`` (:func:`~fusion.book.chapters.ci.weight_search`) and ``seeds``
    (:func:`fusion.scenarios.two_sensor.fruit_fly_over_seeds`) searched on the CI objective of the pair
    ``(P1, P2)`` (fuzz 24c MM/FA): every recorded :math:`\\operatorname{tr}P` is that objective at the recorded ω
    (relative ``rtol``), so that another pair's optima are a ValueError naming ``res`` (``seeds``) and the pair,
    never a figure or a glued number of one pair's objective with another's optima marked. ``P1``, ``P2`` checked
    covariances of one size; ``res`` and ``seeds`` checked results (or ``None``, not compared)."""
    from fusion.estimates.ci import ci_objective

    p1, p2, res_name, seeds_name = names

    def compare(x: np.ndarray, fun: np.ndarray, what: str) -> None:
        x, fun = np.atleast_1d(np.asarray(x, dtype=float)), np.atleast_1d(np.asarray(fun, dtype=float))
        inside = np.isfinite(x) & (x >= 0.0) & (x <= 1.0)
        expected = np.full(x.shape, np.nan)
        if inside.any():
            expected[inside] = np.atleast_1d(ci_objective(x[inside], P1, P2))
        off = ~(np.abs(fun - expected) <= rtol * np.abs(expected))
        if off.any():
            i = int(np.argmax(off))
            raise ValueError(f"{what} must be searched on the pair ({p1}, {p2}): its tr P {shown(float(fun[i]))} at "
                             f"ω = {shown(float(x[i]))} is not that pair's objective there "
                             f"({shown(float(expected[i]))}; another pair's optima?)")

    if res is not None:
        assert isinstance(res, Mapping)
        for k, r in res.items():
            compare(r.x, r.fun, f"{res_name}[{shown(k)}]")
    if seeds is not None:
        compare(seeds.grid_x, seeds.grid_fun, f"{seeds_name} (its exhaustive search)")   # type: ignore[attr-defined]
        compare(seeds.fruit_fly_x, seeds.fruit_fly_fun, f"{seeds_name} (its FOA runs)")   # type: ignore[attr-defined]


def _same_search(res: Mapping, seeds: object, res_name: str = "res", seeds_name: str = "fruit_fly_seeds",
                 grid: str = "exhaustive, 1001 points", rtol: float = 1e-9) -> None:
    """``res`` (:func:`~fusion.book.chapters.ci.weight_search`) and ``seeds``
    (:func:`fusion.scenarios.two_sensor.fruit_fly_over_seeds`, its 1001-point grid) of one pair, where the pair is
    not given (fuzz 24c MM): both searched the same grid, so their exhaustive optima agree (ω and, to a relative
    ``rtol``, tr P); another pair's is a ValueError naming both."""
    r = res[grid]
    gx, gf = float(seeds.grid_x), float(seeds.grid_fun)   # type: ignore[attr-defined]
    if not (gx == float(r.x) and abs(gf - float(r.fun)) <= rtol * abs(float(r.fun))):
        raise ValueError(f"{seeds_name} and {res_name} must be searches of one pair: their exhaustive searches on "
                         f"1001 points end at different optima (ω = {shown(gx)}, tr P {shown(gf)} and ω = "
                         f"{shown(float(r.x))}, tr P {shown(float(r.fun))}; another pair's?)")


def _leg_of(study: object, leg_floor: np.ndarray, legs_steady: np.ndarray, leg_rmse: Mapping,
            rtol: float = 1e-9) -> None:
    """The straight-leg numbers ``leg_floor``, ``legs_steady`` and ``leg_rmse`` those of
    :func:`~fusion.book.chapters.ci.straight_leg` on ``study`` (fuzz 24c MM): one floor per straight-leg step of
    the study's path (its period ``study.t[1] - study.t[0]``), the study's steady steps among them, and each
    method's RMSE of ``leg_rmse`` that the study ran its mean there (relative ``rtol``); another study's leg is a
    ValueError naming the argument and ``study``, never a plausible wrong glued ratio."""
    from fusion.scenarios.two_sensor import straight_leg_floor

    t = np.asarray(study.t, dtype=float)   # type: ignore[attr-defined]
    if t.size < 2:
        return
    on_leg = straight_leg_floor(float(t[1] - t[0]), 1.0)[1]
    steady = np.asarray(study.steady, dtype=bool)   # type: ignore[attr-defined]
    if on_leg.shape != steady.shape or int(on_leg.sum()) != leg_floor.size:
        raise ValueError(f"leg_floor must be the straight leg of study: it has {leg_floor.size} steps, study's path "
                         f"{int(on_leg.sum())} on its straight leg (another study's?)")
    if not np.array_equal(legs_steady, steady[on_leg]):
        raise ValueError("legs_steady must be study's steady steps on its straight leg (another study's?)")
    rmse = study.rmse   # type: ignore[attr-defined]
    for name, value in leg_rmse.items():
        if name in rmse:
            expected = float(np.asarray(rmse[name])[on_leg & steady, 0].mean())
            if not abs(float(value) - expected) <= rtol * abs(expected):
                raise ValueError(f"leg_rmse[{shown(name)}] = {shown(float(value))} must be study's RMSE on its "
                                 f"straight leg ({shown(expected)}; another study's?)")


def _placement_rules(study: object) -> list:
    """The keys of an ArchitectureStudy's runs of eqs. 11-12 fed back with Q in the sensors' own parts at a fixed
    weight (``placement_omegas``): :func:`~fusion.book.chapters.ci.architecture_studies` runs them on the identical
    sensors only, so they tell its two studies apart (fuzz 26c B2)."""
    from fusion.scenarios.two_sensor import Architecture, ArchRule

    prefix = f"{ArchRule.PRINTED_OWN}_w"
    return [k for k in study.run_rmse if k[0] == Architecture.FEEDBACK and str(k[1]).startswith(prefix)]


def _identical_study(study: object, name: str) -> None:
    """``study`` is architecture_studies' identical-sensor study by the rules it records: it holds the placement
    rules (:func:`_placement_rules`) and the fed-back runs its readers read, at the published weight; ValueError
    naming ``name`` (the anisotropic pair's study lacks the former, a study at other weights the latter)."""
    if not _placement_rules(study):
        raise ValueError(f"{name} must be the identical-sensor study of architecture_studies: it holds no run of "
                         "eqs. 11-12 with Q in the sensors' own parts at a fixed weight, which architecture_studies "
                         "runs on the identical sensors only (the anisotropic pair's study?)")
    from fusion.book.chapters.ci.constants import CI_N, CVX_N, FB, LIT, PRINTED, SPLIT_S
    from fusion.book.chapters.lecture import _holds

    # the runs every reader of the identical sensors' study reads (fuzz 39b C6: other printed weights are valid)
    _holds(study.run_rmse, [(FB, k) for k in (CI_N, SPLIT_S, PRINTED, LIT, CVX_N)], name,
           "fed-back runs (architecture_studies' at the published weight W_PUB)", "this chapter")


def _arch_pair(ai: object, an: object, names: tuple[str, str]) -> None:
    """``(ai, an)`` are architecture_studies' identical-sensor and anisotropic-pair studies, in that order, by the
    rules they record (fuzz 26c B2): ``ai`` holds the placement rules, ``an`` none (so neither the studies swapped nor
    one study twice); ValueError naming ``names``."""
    _identical_study(ai, names[0])
    placed = _placement_rules(an)
    if placed:
        raise ValueError(f"{names[1]} must be the anisotropic pair's study of architecture_studies: it holds "
                         f"{shown([str(k[1]) for k in placed], 120)}, eqs. 11-12 with Q in the sensors' own parts, "
                         "which architecture_studies runs on the identical sensors only (the identical sensors' study?)")


def _objective_grid(flat: object, name: str) -> FloatArray:
    """A CI objective on a grid of ω (``tr P(ω)``) as a 1-D array of finite positive numbers, refused naming ``name``
    otherwise (fuzz 36b B6: a mean of zero was divided by, and the refusal named an inner ``value``)."""
    flat = as_array(flat, name, ndim=1)
    if not np.all(flat > 0):
        raise ValueError(f"{name} must hold positive values (a CI objective is a covariance's trace)")
    return flat


def _every_method(study: object, reader: str, name: str = "study", *, published: bool = False,
                  min_runs: int = 1) -> None:
    """``study`` a FusionStudy with every rule of :func:`fusion.scenarios.two_sensor.fusion_study` run that the reader
    reads (the optional weights' rules; with ``published``, the published ω's too) and at least ``min_runs`` runs
    (2: a Monte-Carlo standard error; fuzz 39b C4, C5); ValueError naming ``name``."""
    from fusion._validation import instance_of
    from fusion.book.chapters.lecture import _holds
    from fusion.scenarios.two_sensor import FusionStudy, StudyMethod
    from fusion.scenarios.two_sensor.study import STUDY_METHODS

    instance_of(study, FusionStudy, name)
    keys = [m for m in STUDY_METHODS if published or m != StudyMethod.CI_PUBLISHED]
    _holds(study.est, keys, name, "rules (give fusion_study w_fruit_fly, w_grid"
           + (" and published_omega" if published else "") + ")", reader)
    runs = int(next(iter(study.est.values())).shape[0])
    if runs < min_runs:
        raise ValueError(f"{name} holds {runs} run, fewer than {min_runs}: a Monte-Carlo standard error needs at "
                         f"least {min_runs} runs (give the scenario more runs)")


def _flat_pair_read(flat_pair: object, n_open: int) -> tuple | None:
    """``fig5_hypotheses``'s ``flat_pair`` as a pair (None: skipped), its grid ``k / n_open`` on the size of its
    matrices counted before any work (fuzz 60a C5: the entry counted the grid on ``P1``'s size only, so a large pair
    was refused by ``ci_objective``'s own budget naming its P1 and P2, after the FOA batch and the pair's four
    ``O(m**3)`` readings, 13.5 CPU-s at m = 3,000). Each matrix is read once by the package's array reader (its
    entries within the input budget, ``O(m**2)``), its size m taken from the array read (fuzz 61a C2: the size read
    from the shape as given took an array-like with only ``__array__`` for m = 1, and the call ran 11.5-12.1 CPU-s
    before ``ci_objective`` refused), the budget checked, and only then the two read as covariances; the checked
    matrices are returned and used by the caller, never the arguments read again. Memory: ``ci_objective``'s own
    count, three ``(n_open, m, m)`` stacks (m = 500, n_open = 300 runs, 6.2-7.2 CPU-s). Work, in
    ``fusion._limits.DENSE_CUBE`` units a ``m**3``: its two readings here (each measured 3.3 CPU-s at m = 3,000 by
    fuzz 60a, ~1.2 cubes, counted 1.5), ``ci_objective``'s reading of the two (1.5 each, its own weight) and its
    ``n_open + 2`` inverses (1 each, its own weight): ``n_open + 8`` cubes."""
    if flat_pair is None:
        return None
    from math import isqrt

    from fusion._counts import allocation, sequence
    from fusion._covariances import as_covariance
    from fusion._limits import DENSE_CUBE, dense_work
    from fusion._validation import _numeric

    pair = tuple(sequence(flat_pair, "flat_pair", 2))   # a pair (P, P): a tuple or a list (fuzz 24e F2)
    read = [_numeric(F, f"flat_pair[{i}]") for i, F in enumerate(pair)]   # once, within the input budget
    m = max(max(isqrt(a.size) for a in read), 1)   # a square's m x m entries (a scalar: m = 1)
    names = "flat_pair and n_open (the grid k/n_open on flat_pair's size)"
    allocation((n_open, m, m), names, arrays=3)
    dense_work(n_open + 8, m, names, DENSE_CUBE)
    return tuple(as_covariance(a, name=f"flat_pair[{i}]") for i, a in enumerate(read))
