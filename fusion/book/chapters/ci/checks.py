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
             numbers: bool = True) -> Mapping:
    """``value`` when it is a mapping holding ``keys`` (the entries read), each a finite number (``width`` finite
    numbers when given; not checked when not ``numbers``); TypeError/ValueError naming ``name`` and ``maker``, the
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
            out[k] = scalar(value[k], f"{name}[{shown(k)}]", tiny=True)
        else:
            out[k] = as_array(value[k], f"{name}[{shown(k)}]", shape=(width,), subnormal=True)
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
