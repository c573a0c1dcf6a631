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

from fusion._shown import shown
from fusion._validation import FloatArray, as_array, scalar
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
    missing = [k for k in keys if k not in value]
    if missing:
        raise ValueError(f"{name} lacks the keys {shown(missing, 200)} (a result of {maker} holds them)")
    out = dict(value)
    for k in keys if numbers else ():
        if width is None:
            out[k] = scalar(value[k], f"{name}[{shown(k)}]", 0.0 if nonnegative else None, tiny=True)
        else:
            out[k] = as_array(value[k], f"{name}[{shown(k)}]", shape=(width,), subnormal=True,
                              nonnegative=nonnegative)
    return out


def _results(value: object, name: str, cls: type, maker: str) -> Mapping:
    """``value`` when it is a non-empty mapping of labels to ``cls`` instances (the results of ``maker``);
    TypeError/ValueError naming ``name``."""
    if not isinstance(value, Mapping):
        raise TypeError(f"{name} must be a mapping of labels to {cls.__name__} (from {maker}), got "
                        f"{type(value).__name__}")
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


def _periods(periods: object, name: str = "periods") -> FloatArray:
    """Sampling periods, one table row each (fuzz 19's debatable empties): a non-empty 1-d array of distinct,
    finite, positive numbers (a scalar is one period); TypeError/ValueError naming ``name``."""
    arr = as_array(periods, name, ndim=(0, 1))
    arr = np.atleast_1d(arr)
    if (arr <= 0).any():
        raise ValueError(f"{name} must hold positive sampling periods (s), got {shown(arr.tolist(), 120)}")
    if np.unique(arr).size != arr.size:
        raise ValueError(f"{name} must hold distinct sampling periods (one row each), got {shown(arr.tolist(), 120)}")
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
