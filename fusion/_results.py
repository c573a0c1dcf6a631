"""Result objects validated where they are built: one declarative field spec per result class (issue 35).

A frozen result dataclass that a later public function takes as input (:class:`~fusion.filtering.kalman.GainSequence`
into :func:`~fusion.filtering.kalman.filter_runs`, :class:`~fusion.filtering.tracks.LocalTrack` into
:func:`~fusion.filtering.tracks.fuse_tracks`, ...) is an input like any other: ``dataclasses.replace`` is its public
constructor, so a tampered object (NaN in a gain, a covariance one step short, a track of another state
dimension) must be refused when it is built, by a :class:`ValueError` naming the class and the field
(``"GainSequence.H: ..."``), not reach the next stage as a silent wrong number, a NaN or an ``IndexError``.
:class:`~fusion.estimates.mixtures.GaussianMixture` set the precedent; this module gives every such class the
same rule through one mechanism.

A class declares its fields once, as a class attribute ``__result_spec__`` (a :class:`ResultSpec`, not a
dataclass field), and sets ``__post_init__ = validated_post_init``. The spec says, per field:

* :func:`array`: a finite float array whose axes are named dimensions (``("K", "n", "m")``) or fixed sizes;
  a name bound by one field must have the same length in every other field (steps, runs, state
  dimension), a covariance stack (``covariance=True``) must be symmetric positive semidefinite, times
  (``increasing=True``) strictly increasing. A first entry ``"..."`` (:data:`BATCH`) stands for any number of
  leading batch axes (none included): their shape is bound as one group, the same in every field that
  declares it (``array("...", "K", "n")`` for the ``(..., K, n)`` results of a batch of problems);
* :func:`nested`: an instance of another result class (already validated by its own constructor), whose
  named dimensions are bound to the outer ones (``{"K": "K", "n": 4}``); ``count`` for a tuple of them;
* :func:`number`, :func:`numbers`, :func:`arrays`: a finite float (NaN allowed with ``nan=True``, a value
  undefined in some case), or a dict with exactly the given keys of
  finite floats or of arrays (their named dimensions bound as above); :func:`keyed`: a dict of whichever string
  keys the result holds (the methods a run computed), each a finite array (a covariance stack if asked);
* :func:`integer`, :func:`flag`, :func:`text`, :func:`mask`, :func:`integers`: an int (not a bool) at least
  ``minimum`` (a count, a seed, an index; with ``dim``, the count is that named dimension of the arrays: ``runs`` =
  their length), a bool, a string (one of given choices), a bool array of named dimensions (steps on a leg,
  runs at a corner; kept bool), an integer array of named dimensions (seeds; kept integer); :func:`table`: a
  :class:`pandas.DataFrame` with the columns its consumers read (its rows a named dimension if asked);
  :func:`instance`: an object of given classes (a study of its own, a scenario; optional allows ``None``);
* :func:`tuple_of`, :func:`dict_of`: a tuple of given length or a dict (keys of given types, or exactly given
  keys) whose items each satisfy a spec of any kind above, checked recursively (the chapter layer's results
  hold dicts of dicts of arrays, tuples of numbers, dicts of studies);
* ``bounds=(lo, hi)`` on :func:`array` and :func:`number`: every value in the closed interval (a probability,
  a share, a weight in [0, 1]);
* ``relations``: cross-field checks (``Pd + Pi = gains.P``), each a callable raising a :class:`ValueError`;
  :func:`same_keys`: dict fields holding the same keys (the methods of a clean and a failed run).
  Relations are structural (shapes, keys, orders, rows read by key); a field the producer derives by recomputing
  the study (a verdict, an exact optimum, a moment) is not recomputed from the others, so a result replaced
  (``dataclasses.replace``) with a contradicting value keeps it (fuzz 24b D5).

Every array is then stored as a read-only float64 copy (the object owns its data; a :func:`mask` or
:func:`integers` array keeps its bool or integer dtype). The checks reuse the shared validators of
:mod:`fusion._validation` (:func:`~fusion._validation.as_array`, :func:`~fusion._validation.instance_of`).

*Cost.* The package's own producers (:func:`~fusion.filtering.kalman.gain_sequence`,
:func:`~fusion.filtering.tracks.local_track`, the scenarios' simulations) build these objects from arrays
they have just computed from validated arguments, and their public entries already refuse a non-finite
result (:func:`~fusion._validation.finite_result`). They go through :func:`trusted`, the private
constructor, which skips the checks and only makes the arrays read-only in place (the caller guarantees
they are fresh: not views of a caller's argument). So the large arrays of a study are checked once, where
they come from, and a study costs what it cost before (measured with ``time.process_time``: a
:class:`~fusion.filtering.kalman.GainSequence` of 261 steps costs 600 µs to compute, 180 µs to check
through ``replace``, 3 µs through :func:`trusted`; the two-sensor scenario and fusion study of 200 runs
and the infrared + radar simulation and its errors cost the same before and after, 0.33 s each).

*Bundles.* A class that only gathers other results' values (chapter 05's ledger inputs, whose values are shared
with the cached studies, not copied) sets ``__post_init__ = shared_post_init``: the same checks, the values kept.

*With a frozen-arrays base class.* A base whose ``__post_init__`` freezes the array fields can call
:func:`check_fields` first when the class has a ``__result_spec__``: :func:`check_fields` returns the
converted values without storing them, so either the base or :func:`validated_post_init` stores them.
"""

from __future__ import annotations

import dataclasses
import os
import sys
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from fusion._frozen import ReadOnlyMapping, frozen_value, protect_frames, restore_frozen  # noqa: F401 (ReadOnlyMapping re-exported)
from fusion import _validation
from fusion._covariances import COVARIANCE_RTOL, asymmetric
from fusion._validation import _numeric, as_array, instance_of, shown

__all__: list[str] = []  # private module: nothing public


Dim = str | int

#: ``bounds`` of a non-negative :func:`array` or :func:`number` (an MSE, a variance, a count of runs as a float).
NONNEGATIVE = (0.0, np.inf)

#: The leading batch axes of an :func:`array` spec (first entry only): any number of axes, their shape one group.
BATCH = "..."


@dataclasses.dataclass(frozen=True)
class ArraySpec:
    """A float array field: named or fixed dimensions, and what its values must satisfy."""

    dims: tuple[Dim, ...]
    covariance: bool = False
    increasing: bool = False
    optional: bool = False
    bounds: tuple[float, float] | None = None
    nan: bool = False


@dataclasses.dataclass(frozen=True)
class NestedSpec:
    """A field holding another result object (or a tuple of ``count`` of them) with dimensions bound to ours."""

    cls: type
    dims: Mapping[str, Dim]
    count: int | None = None


@dataclasses.dataclass(frozen=True)
class NumbersSpec:
    """A finite float (``keys`` None) or a dict with exactly the keys ``keys`` of finite floats or of arrays ``item``."""

    keys: tuple[Any, ...] | None
    positive: bool = False
    nonnegative: bool = True
    item: ArraySpec | None = None
    bounds: tuple[float, float] | None = None
    nan: bool = False


@dataclasses.dataclass(frozen=True)
class KeyedSpec:
    """A dict whose keys are whichever strings the result holds (methods computed), each an array ``item``."""

    item: ArraySpec


@dataclasses.dataclass(frozen=True)
class ValueSpec:
    """Any other field (:func:`integer`, :func:`flag`, :func:`text`, :func:`table`, :func:`instance`,
    :func:`tuple_of`, :func:`dict_of`): ``kind`` and its parameters ``args``."""

    kind: str
    args: Mapping[str, Any]


FieldSpec = ArraySpec | NestedSpec | NumbersSpec | KeyedSpec | ValueSpec


@dataclasses.dataclass(frozen=True)
class ResultSpec:
    """The fields of a result class (:class:`ArraySpec`, :class:`NestedSpec`, :class:`NumbersSpec`, :class:`KeyedSpec`,
    :class:`ValueSpec`) and its relations."""

    fields: Mapping[str, FieldSpec]
    relations: tuple[Callable[[Mapping[str, Any], str], None], ...] = ()

    def __set_name__(self, owner: type, name: str) -> None:
        """Declared as ``__result_spec__`` in a class body: the class's copies and unpickled objects keep read-only
        arrays (``__setstate__`` = ``fusion._frozen.restore_frozen``) and its :func:`table` fields are stored as a
        private copy, handed out as a copy on each read (``fusion._frozen.FrameField``: an in-place edit of a
        table read from the object never reaches it)."""
        if "__setstate__" not in vars(owner):
            owner.__setstate__ = restore_frozen  # type: ignore[attr-defined]
        protect_frames(owner, [n for n, fs in self.fields.items() if isinstance(fs, ValueSpec) and fs.kind == "table"])


def array(*dims: Dim, covariance: bool = False, increasing: bool = False, optional: bool = False,
          bounds: tuple[float, float] | None = None, nan: bool = False) -> ArraySpec:
    """Spec of a float array field with the given named (``"K"``) or fixed (``4``) dimensions, after optional
    leading batch axes (a first entry :data:`BATCH`), its values in ``bounds`` if given; with ``nan``, NaN entries
    are allowed (a value undefined there, such as a bound at the first scan), infinities still refused."""
    if BATCH in dims[1:]:
        raise ValueError(f"array spec {dims}: {shown(BATCH)} may only be the first dimension")
    return ArraySpec(tuple(dims), covariance=covariance, increasing=increasing, optional=optional, bounds=bounds,
                     nan=nan)


def nested(cls: type, count: int | None = None, **dims: Dim) -> NestedSpec:
    """Spec of a field holding a ``cls`` result (a tuple of ``count`` of them), its dimensions bound as ``dims``."""
    return NestedSpec(cls, dims, count)


def numbers(*keys: Any, positive: bool = False, nonnegative: bool = True) -> NumbersSpec:
    """Spec of a dict of finite floats (>= 0, > 0 if ``positive``, any sign unless ``nonnegative``) with exactly ``keys``."""
    return NumbersSpec(tuple(keys), positive, nonnegative)


def number(positive: bool = False, nonnegative: bool = True, bounds: tuple[float, float] | None = None,
           nan: bool = False) -> NumbersSpec:
    """Spec of one finite float field (>= 0, > 0 if ``positive``, any sign unless ``nonnegative``; in ``bounds``);
    with ``nan``, NaN is allowed (a value its docstring calls undefined in some case), infinities still refused."""
    return NumbersSpec(None, positive, nonnegative, bounds=bounds, nan=nan)


def integer(minimum: int | None = 0, dim: str | None = None) -> ValueSpec:
    """Spec of an int field (a Python or numpy integer, not a bool) at least ``minimum`` (none if None); with ``dim``,
    the count is that named dimension of the array fields (``runs`` = the length of the per-run arrays)."""
    return ValueSpec("integer", {"minimum": minimum, "dim": dim})


def same_keys(*fields: str) -> Callable[[Mapping[str, Any], str], None]:
    """A relation (``ResultSpec(relations=...)``): the dict fields ``fields`` hold the same keys (the same methods,
    cases or levels: a key dropped from one of them is refused, naming it)."""

    def relation(values: Mapping[str, Any], cls: str) -> None:
        first = set(values[fields[0]])
        for name in fields[1:]:
            if set(values[name]) != first:
                got = sorted(map(str, values[name]))
                raise ValueError(f"{cls}.{name} must have the keys of {cls}.{fields[0]} "
                                 f"{shown(sorted(map(str, first)), 200)}, got {shown(got, 200)}")

    relation.fields = fields  # type: ignore[attr-defined]  (the fields it relates: tests drop a key from each)
    return relation


def mask(*dims: Dim) -> ValueSpec:
    """Spec of a bool array field (steps on a leg, runs at a corner) of the named or fixed dimensions ``dims``:
    a :class:`numpy.ndarray` of dtype bool, stored as a read-only bool copy."""
    return ValueSpec("mask", {"dims": tuple(dims)})


def integers(*dims: Dim, minimum: int | None = 0) -> ValueSpec:
    """Spec of an integer array field (the seeds of a study's runs) of the named or fixed dimensions ``dims``: a
    :class:`numpy.ndarray` of an integer dtype, or of dtype object holding ints (seeds beyond int64), each at least
    ``minimum`` (none if None); stored as a read-only copy of its own dtype (a float copy would round a seed beyond
    2**53)."""
    return ValueSpec("integers", {"dims": tuple(dims), "minimum": minimum})


def flag() -> ValueSpec:
    """Spec of a bool field (``bool`` or ``numpy.bool_``, stored as ``bool``)."""
    return ValueSpec("flag", {})


def text(*choices: str) -> ValueSpec:
    """Spec of a str field, one of ``choices`` if any are given."""
    return ValueSpec("text", {"choices": tuple(choices)})


def table(*columns: Any, rows: Dim | None = None, key: tuple[Any, ...] = (), index: tuple[Any, ...] = (),
          cells: Mapping[Any, tuple[float, float, bool]] | None = None) -> ValueSpec:
    """Spec of a :class:`pandas.DataFrame` field holding at least ``columns`` (those its consumers read), its number
    of rows the named or fixed dimension ``rows`` if given. Rows read by key (fuzz 24b class DR): ``key``, the
    columns that identify a row (among ``columns``), no NaN there and no two rows with the same key (a repeated row
    would be counted twice); ``index``, the index labels its consumers read (``table.loc[label]``), each present and
    no index label twice. ``cells``: column -> ``(lo, hi, whole)``, the cells its producer makes there (fuzz 33b
    B2: a table edited between producer and consumer), each a finite number of a numeric column in [lo, hi], a
    whole number if ``whole``."""
    return ValueSpec("table", {"columns": tuple(columns), "rows": rows, "key": tuple(key), "index": tuple(index),
                               "cells": dict(cells or {})})


def _table_cells(value: Any, label: str, cells: Mapping[Any, tuple[float, float, bool]]) -> None:
    """The ``cells`` rule of :func:`table`: TypeError for a column that does not hold numbers, ValueError naming the
    column and row of the first cell outside its range. A table without rows has no cells to check (a producer's
    empty table keeps its columns, of dtype object: ``AuditResult.full`` when no hypothesis explains all)."""
    for col, (lo, hi, whole) in cells.items():
        where = f"{label}[{shown(col)}]"
        column = value[col]
        if getattr(column, "ndim", 1) != 1:
            raise ValueError(f"{where} must be one column, got {column.shape[1]} columns of that name")
        if len(column) == 0:
            continue
        if column.dtype.kind not in "iuf":
            raise TypeError(f"{where} must hold numbers, got a column of dtype {column.dtype}")
        x = column.to_numpy(dtype=float)
        with np.errstate(invalid="ignore"):
            bad = ~np.isfinite(x) | (x < lo) | (x > hi) | ((x != np.round(x)) if whole else False)
        if bad.any():
            i = int(np.argmax(bad))
            what = "whole numbers" if whole else "finite numbers"
            raise ValueError(f"{where} must hold {what} in [{lo:g}, {hi:g}], got {shown(float(x[i]))} in the row "
                             f"{shown(value.index[i], 80)}")


def instance(*classes: type, optional: bool = False) -> ValueSpec:
    """Spec of a field holding an instance of one of ``classes`` (``None`` too if ``optional``): a study or a
    scenario of its own, which its constructor checks."""
    return ValueSpec("instance", {"classes": tuple(classes), "optional": optional})


def tuple_of(*items: FieldSpec, count: int | None = None) -> ValueSpec:
    """Spec of a tuple field: one item per spec of ``items``, or ``count`` items (any number if None) of the one spec
    ``items[0]``. A list is accepted and stored as a tuple."""
    if count is not None or len(items) == 1:
        return ValueSpec("tuple", {"item": items[0], "count": count})
    return ValueSpec("tuple", {"items": tuple(items)})


def dict_of(value: FieldSpec, keys: tuple[Any, ...] | None = None, key: type | tuple[type, ...] = str,
            nonempty: bool = True, required: tuple[Any, ...] = (), read_key: Callable[[Any], Any] | None = None,
            printed: Callable[[Any], Any] | None = None, check_key: Callable[[Any, str], Any] | None = None
            ) -> ValueSpec:
    """Spec of a dict field whose values each satisfy ``value``: exactly the keys ``keys`` if given, otherwise any
    keys of the type(s) ``key`` (at least one unless not ``nonempty``) among which every key of ``required`` (those
    its consumers read); each key stored as ``read_key`` reads it if given (two keys read alike refused); no two
    keys printing the same under ``printed`` if given (its readers key results by the printed key:
    ``fusion._counts.distinct_printed``); each read key passed to ``check_key(key, name)`` if given, which raises
    naming ``name`` (the field's key) for a key outside its meaning (a period NaN or below 0: fuzz 32b C2). Stored
    as a read-only mapping."""
    return ValueSpec("dict", {"value": value, "keys": keys, "key": key, "nonempty": nonempty, "required": required,
                              "read_key": read_key, "printed": printed, "check_key": check_key})


def real_key(lo: float | None = None, hi: float | None = None, *, lo_open: bool = False,
             hi_open: bool = False) -> Callable[[Any, str], float]:
    """A :func:`dict_of` ``check_key`` for keys that are real numbers of a meaning (a period, a weight, a level, a
    noise level): each key finite and within [``lo``, ``hi``] (open ends as flagged), read by
    ``fusion._validation.scalar``; ValueError naming the field's key otherwise (fuzz 32b C2, D2)."""
    return lambda k, name: _validation.scalar(k, name, lo, hi, lo_open=lo_open, hi_open=hi_open)


def keyed(*dims: Dim, covariance: bool = False) -> KeyedSpec:
    """Spec of a dict of string keys (any set of them) whose values are finite arrays of the dimensions ``dims``."""
    return KeyedSpec(array(*dims, covariance=covariance))


def arrays(keys: tuple[Any, ...], *dims: Dim) -> NumbersSpec:
    """Spec of a dict with exactly ``keys`` whose values are finite arrays of the dimensions ``dims``."""
    return NumbersSpec(tuple(keys), item=array(*dims))


#: Relative tolerance of the symmetry and semidefiniteness checks of covariance stacks (computed values:
#: rounding leaves asymmetries and negative eigenvalues of a few ulps of the largest entry).
RTOL = COVARIANCE_RTOL   # the covariance readers' tolerance (fusion._covariances), one rule for producer and reader


def _covariances(arr: np.ndarray, label: str) -> None:
    """A stack (..., n, n) of symmetric positive-semidefinite matrices (each to ``RTOL`` of its largest entry)."""
    if arr.shape[-1] != arr.shape[-2]:
        raise ValueError(f"{label}: covariances must be square matrices, got shape {arr.shape}")
    if asymmetric(arr, RTOL):
        raise ValueError(f"{label}: every matrix must be symmetric (a covariance)")
    scale = np.maximum(np.abs(arr).max(axis=(-2, -1)), np.finfo(float).tiny)
    sym = 0.5 * (arr + np.swapaxes(arr, -1, -2))
    if (np.linalg.eigvalsh(sym).min(axis=-1) < -RTOL * scale).any():
        raise ValueError(f"{label}: every matrix must be positive semidefinite (a covariance)")


def _shape_text(dims: tuple[Dim, ...], bound: Mapping[str, tuple[Any, str]]) -> str:
    parts = [str(d) if isinstance(d, int) else (f"{d}={bound[d][0]}" if d in bound else d) for d in dims]
    return "(" + ", ".join(parts) + ("," if len(parts) == 1 else "") + ")"


def _ndim(dims: tuple[Dim, ...]) -> int | tuple[int, ...] | None:
    """The numbers of axes ``dims`` allows (``None``: any, checked by :func:`_bind`, with leading batch axes)."""
    return None if dims[:1] == (BATCH,) else len(dims)


def _bind(dims: tuple[Dim, ...], shape: tuple[int, ...], label: str, bound: dict[str, tuple[Any, str]]) -> None:
    """Check ``shape`` against ``dims``, binding new names; a mismatch names the field and where the length came from.

    A first entry :data:`BATCH` takes the leading ``len(shape) - len(dims) + 1`` axes, bound as one shape (a tuple)."""
    if dims[:1] == (BATCH,):
        core = len(dims) - 1
        if len(shape) < core:
            raise ValueError(f"{label} must have shape {_shape_text(dims, bound)} (at least {core} axes), got {shape}")
        lead, rest = tuple(shape[:len(shape) - core]), tuple(shape[len(shape) - core:])
        if BATCH in bound and bound[BATCH][0] != lead:
            raise ValueError(f"{label} must have shape {_shape_text(dims, bound)} (batch shape {bound[BATCH][0]} "
                             f"from {bound[BATCH][1]}), got {shape}")
        bound.setdefault(BATCH, (lead, label))
        dims, shape = dims[1:], rest
    if len(shape) != len(dims):
        raise ValueError(f"{label} must have shape {_shape_text(dims, bound)}, got {shape}")
    for d, size in zip(dims, shape):
        if isinstance(d, int):
            ok, why = size == d, ""
        elif d in bound:
            ok, why = size == bound[d][0], f" ({d} = {bound[d][0]} from {bound[d][1]})"
        else:
            bound[d] = (size, label)
            continue
        if not ok:
            raise ValueError(f"{label} must have shape {_shape_text(dims, bound)}{why}, got {shape}")


def dimensions(obj: object) -> dict[str, Any]:
    """The named dimensions of a result object (already validated), read from its fields' shapes (the batch
    shape, :data:`BATCH`, a tuple)."""
    spec: ResultSpec = type(obj).__result_spec__  # type: ignore[attr-defined]
    out: dict[str, Any] = {}
    for name, fs in spec.fields.items():
        if isinstance(fs, ArraySpec):
            value = getattr(obj, name)
            if value is not None:
                shape, dims = np.shape(value), fs.dims
                if dims[:1] == (BATCH,):
                    lead = len(shape) - len(dims) + 1
                    out[BATCH], dims, shape = tuple(shape[:lead]), dims[1:], shape[lead:]
                out.update((d, n) for d, n in zip(dims, shape) if isinstance(d, str))
    return out


def check_fields(obj: object) -> dict[str, Any]:
    """Validate the fields of ``obj`` against its class's ``__result_spec__``; return the values to store.

    Raises
    ------
    TypeError
        A field of the wrong type (not numeric, not the result class it must hold).
    ValueError
        A field that is not finite, of the wrong shape or inconsistent with another field, a covariance
        that is not symmetric positive semidefinite, times not increasing, a value out of its bounds, a table
        without a column its consumers read, a failed relation: the message starts with ``Class.field`` when the
        caller builds the result, with the caller's arguments when a public function of the package does
        (:func:`_producer_arguments`).
    """
    cls = type(obj)
    spec: ResultSpec = cls.__result_spec__  # type: ignore[attr-defined]
    bound: dict[str, tuple[Any, str]] = {}
    values: dict[str, Any] = {}
    try:
        for name, fs in spec.fields.items():
            values[name] = _check(fs, getattr(obj, name), f"{cls.__name__}.{name}", bound)
        for relation in spec.relations:
            relation(values, cls.__name__)
    except ValueError as exc:
        who = _producer_arguments()
        if who is None:
            raise
        verb = "gives" if " and " not in who and ", " not in who else "give"
        raise ValueError(f"{who} {verb} a result that is refused: {exc}") from None
    return values


_PACKAGE = os.path.dirname(os.path.abspath(__file__)) + os.sep
#: Modules whose frames only pass a call through (the result machinery, the guards' wrappers).
_PASS_THROUGH = frozenset({"_results.py", "_frozen.py", "_guards.py", "_structures.py"})


def _producer_arguments() -> str | None:
    """The arguments of the public function of the package whose result a spec refuses, or None when the caller
    built the result itself (its fields are then the caller's arguments, and the message names them).

    A result spec's refusal of what a public function computed from valid-looking arguments (``linearised_errors``
    at tiny noise: ``LinearisedErrors.rmse_central contains NaN``) named a field of the result, not what the caller
    gave (fuzz 28a C6). The one rule for every producer, on the error path only: the entry is the outermost frame
    of the package below the caller (the guards' wrappers and the dataclass ``__init__`` passed through), and its
    parameters that hold a quantity are named (not a bool, None or a string: a switch or a label selects a
    computation; all of them if none is left). A private entry (a worker process's kernel) names nothing.
    """
    frame = sys._getframe(2)
    entry = None
    while frame is not None:
        path = frame.f_code.co_filename
        if path.startswith(_PACKAGE):
            if os.path.basename(path) not in _PASS_THROUGH:
                entry = frame
        elif path != "<string>":  # the caller's frame (dataclass-generated __init__ frames are "<string>")
            break
        frame = frame.f_back
    if entry is None or entry.f_code.co_name.startswith("_"):
        return None
    code = entry.f_code
    params = [p for p in code.co_varnames[:code.co_argcount + code.co_kwonlyargcount] if p not in ("self", "cls")]
    quantities = [p for p in params if not isinstance(entry.f_locals.get(p), (bool, str, type(None)))]
    names = quantities or params
    if not names:
        return None
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def _in_bounds(arr: Any, label: str, bounds: tuple[float, float] | None) -> None:
    """Every value of ``arr`` within the closed interval ``bounds`` (nothing to check if None)."""
    if bounds is None:
        return
    flat = np.asarray(arr, dtype=float).ravel()
    bad = flat[(flat < bounds[0]) | (flat > bounds[1])]
    if bad.size:
        raise ValueError(f"{label} must lie in [{bounds[0]:g}, {bounds[1]:g}], got {shown(float(bad[0]))}")


def _float_array(value: object, fs: ArraySpec, label: str, bound: dict[str, tuple[Any, str]]) -> np.ndarray:
    """The checks of an :class:`ArraySpec` (type, finiteness, shape and bindings, covariances, increasing, bounds)."""
    _numeric(value, label)  # TypeError for a non-numeric value, before any shape message
    arr = as_array(value, label, ndim=_ndim(fs.dims), subnormal=True, finite=not fs.nan)
    if fs.nan and np.isinf(arr).any():
        raise ValueError(f"{label} contains infinite values")
    _bind(fs.dims, arr.shape, label, bound)
    if fs.covariance:
        _covariances(arr, label)
    if fs.increasing and arr.size > 1 and not (arr[1:] > arr[:-1]).all():
        raise ValueError(f"{label} must be strictly increasing (times)")
    _in_bounds(arr, label, fs.bounds)
    return arr


def _own(arr: np.ndarray) -> np.ndarray:
    """A read-only float64 copy, bool for a :func:`mask` (an array inside a container field: the object owns its
    data)."""
    arr = np.array(arr, dtype=bool if arr.dtype == bool else float)
    arr.setflags(write=False)
    return arr


def _check(fs: FieldSpec, value: Any, label: str, bound: dict[str, tuple[Any, str]]) -> Any:
    """Check one field (or one item of a container field) against its spec; return the value to store."""
    if isinstance(fs, ArraySpec):
        if value is None and fs.optional:
            return None
        return _float_array(value, fs, label, bound)
    if isinstance(fs, NestedSpec):
        items = (value,)
        if fs.count is not None:  # the sequence rule of every tuple field (tuple_of): a list is stored as a tuple
            value = items = _sequence(value, label, fs.count, f"{fs.count} {fs.cls.__name__}")
        for i, item in enumerate(items):
            where = label if fs.count is None else f"{label}[{i}]"
            instance_of(item, fs.cls, where)
            inner = dimensions(item) if fs.dims else {}
            for d_in, d_out in fs.dims.items():
                size = inner[d_in]
                if isinstance(d_out, int):
                    if size != d_out:
                        raise ValueError(f"{where} must have {d_in} = {d_out}, got {size}")
                elif d_out in bound:
                    if size != bound[d_out][0]:
                        raise ValueError(f"{where} has {d_in} = {size}, but {d_out} = {bound[d_out][0]} "
                                         f"from {bound[d_out][1]}")
                else:
                    bound[d_out] = (size, where)
        return value
    if isinstance(fs, KeyedSpec):
        if not isinstance(value, Mapping) or not all(isinstance(k, str) for k in value):
            raise TypeError(f"{label} must be a dict of str keys to arrays, got {type(value).__name__}")
        return {k: _own(_float_array(value[k], fs.item, f"{label}[{shown(k)}]", bound)) for k in value}
    if isinstance(fs, ValueSpec):
        return _value(fs, value, label, bound)
    if fs.keys is None:
        return _number(value, label, fs)
    if not isinstance(value, Mapping) or set(value) != set(fs.keys):
        got = sorted(map(str, value)) if isinstance(value, Mapping) else type(value).__name__
        raise ValueError(f"{label} must be a dict with the keys {sorted(map(str, fs.keys))}, got {got}")
    out: dict[Any, Any] = {}
    for k in fs.keys:
        where = f"{label}[{str(k)!r}]"
        if fs.item is None:
            out[k] = _number(value[k], where, fs)
        else:
            out[k] = _own(_float_array(value[k], fs.item, where, bound))
    return out


def _sequence(value: Any, label: str, count: int | None, what: str = "") -> tuple:
    """The one rule of a sequence field, of values (:func:`tuple_of`) or of nested results (:func:`nested` with a
    ``count``; fuzz 19: a list was refused there, accepted here): a tuple or a list (not a named tuple), stored as a
    tuple, of ``count`` items when given; TypeError for another type, ValueError for another length."""
    if not isinstance(value, (tuple, list)) or hasattr(value, "_fields"):
        raise TypeError(f"{label} must be a tuple{f' of {what}' if what else ''}, got {type(value).__name__}")
    if count is not None and len(value) != count:
        raise ValueError(f"{label} must have {count} items, got {len(value)}")
    return tuple(value)


def _value(fs: ValueSpec, value: Any, label: str, bound: dict[str, tuple[Any, str]]) -> Any:
    """The checks of a :class:`ValueSpec` (an int, bool, str, table, instance, tuple or dict field)."""
    args = fs.args
    if fs.kind == "integer":
        v = _validation.integer(value, label)
        if args["minimum"] is not None and v < args["minimum"]:
            raise ValueError(f"{label} must be at least {args['minimum']}, got {shown(v)}")
        dim = args.get("dim")
        if dim is not None and dim in bound and bound[dim][0] != v:
            raise ValueError(f"{label} must be the {dim} of {bound[dim][1]}, {bound[dim][0]}; got {shown(v)}")
        if dim is not None:
            bound.setdefault(dim, (v, label))
        return v
    if fs.kind == "flag":
        return _validation.flag(value, label)
    if fs.kind == "mask":
        if not isinstance(value, np.ndarray) or value.dtype != bool:
            raise TypeError(f"{label} must be a bool array, got "
                            f"{value.dtype if isinstance(value, np.ndarray) else type(value).__name__}")
        _bind(args["dims"], value.shape, label, bound)
        return value
    if fs.kind == "integers":
        if not isinstance(value, np.ndarray) or not (value.dtype.kind in "iu" or value.dtype == object and all(
                isinstance(v, int) and not isinstance(v, bool) for v in value.flat)):
            raise TypeError(f"{label} must be an integer array, got "
                            f"{value.dtype if isinstance(value, np.ndarray) else type(value).__name__}")
        _bind(args["dims"], value.shape, label, bound)
        if args["minimum"] is not None and value.size and min(value.flat) < args["minimum"]:
            raise ValueError(f"{label} must hold integers of at least {args['minimum']}, got {shown(min(value.flat))}")
        return value
    if fs.kind == "text":
        if args["choices"]:
            return _validation.one_of(value, args["choices"], label)
        return _validation.text(value, label)
    if fs.kind == "table":
        import pandas as pd

        instance_of(value, pd.DataFrame, label)
        missing = [c for c in args["columns"] if c not in value.columns]
        if missing:
            raise ValueError(f"{label} must have the columns {shown(list(args['columns']))}, misses {shown(missing)}")
        if args["rows"] is not None:
            _bind((args["rows"],), (len(value),), f"{label} (rows)", bound)
        if args.get("key"):
            keys = value[list(args["key"])]
            if keys.isna().to_numpy().any():
                raise ValueError(f"{label}: the columns {shown(list(args['key']))} identify a row and must not hold NaN")
            again = keys.duplicated().to_numpy()
            if again.any():
                i = int(np.argmax(again))
                key = tuple(keys.iloc[i].tolist())
                raise ValueError(f"{label} repeats a row: row {i} has the key {shown(key)} of an earlier "
                                 f"row ({shown(list(args['key']))} identify a row)")
        if args.get("index"):
            if not value.index.is_unique:
                again = value.index[value.index.duplicated()].tolist()[0]
                raise ValueError(f"{label} repeats a row: the index label {shown(again)} occurs twice (rows are read "
                                 "by it)")
            missing = [k for k in args["index"] if k not in value.index]
            if missing:
                raise ValueError(f"{label} must hold the rows {shown(list(args['index']))} (read by index), misses "
                                 f"{shown(missing)}")
        if args.get("cells"):
            _table_cells(value, label, args["cells"])
        return value
    if fs.kind == "instance":
        if value is None and args["optional"]:
            return None
        instance_of(value, args["classes"], label)
        return value
    if fs.kind == "tuple":
        fixed = "items" in args
        value = _sequence(value, label, len(args["items"]) if fixed else args["count"])
        items = args["items"] if fixed else (args["item"],) * len(value)
        return tuple(_check(f, v, f"{label}[{i}]", bound) for i, (f, v) in enumerate(zip(items, value)))
    if fs.kind == "dict":
        if not isinstance(value, Mapping):
            raise TypeError(f"{label} must be a dict, got {type(value).__name__}")
        read_key = args.get("read_key")
        if read_key is not None:
            read = [read_key(k) for k in value]
            if len(set(read)) != len(read):
                raise ValueError(f"{label} holds two keys read as one: {shown([str(k) for k in value], 200)}")
            value = dict(zip(read, value.values()))
        keys = args["keys"]
        if keys is not None and set(value) != set(keys):
            raise ValueError(f"{label} must have the keys {shown(sorted(map(str, keys)))}, got "
                             f"{shown(sorted(map(str, value)), 200)}")
        if keys is None:
            for k in value:
                if not isinstance(k, args["key"]) or isinstance(k, (bool, np.bool_)):
                    raise TypeError(f"{label} has a key {shown(k)} of type {type(k).__name__}")
            if args["nonempty"] and not value:
                raise ValueError(f"{label} must not be empty")
            missing = [k for k in args["required"] if k not in value]
            if missing:
                raise ValueError(f"{label} misses the keys {shown(missing, 200)} (its consumers read them)")
            if args.get("check_key") is not None:  # the value each key means (fuzz 32b C2)
                for k in value:
                    args["check_key"](k, f"{label}'s key")
        if args.get("printed") is not None:  # keys that differ but print alike would share a result key (fuzz 30b)
            _validation.distinct_printed(list(value), label, args["printed"])
        out = {k: _check(args["value"], v, f"{label}[{shown(k)}]", bound) for k, v in value.items()}
        return {k: _own(v) if isinstance(v, np.ndarray) else v for k, v in out.items()}
    raise AssertionError(fs.kind)  # pragma: no cover (the spec functions build only the kinds above)


def _number(value: object, label: str, fs: NumbersSpec) -> float:
    """One finite float of the sign ``fs`` asks for, in its bounds."""
    if isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{label} must be a number, got {shown(value)}")
    v = float(as_array(value, label, ndim=0, subnormal=True, finite=not fs.nan))
    if np.isinf(v):
        raise ValueError(f"{label} must not be infinite, got {shown(v)}")
    if np.isnan(v):  # allowed (``nan``): undefined, no sign or bound to check
        return v
    if (fs.positive and not v > 0) or (fs.nonnegative and v < 0):
        raise ValueError(f"{label} must be {'positive' if fs.positive else 'non-negative'}, got {shown(v)}")
    _in_bounds(v, label, fs.bounds)
    return v


def _store(obj: object, values: Mapping[str, Any], copy: bool) -> None:
    """Set the fields of ``obj``: arrays (also a dict's) read-only, as float64 copies if ``copy``, else in place."""
    for name, v in values.items():
        if isinstance(v, np.ndarray):
            if copy:  # an integer array (:func:`integers`) keeps its dtype, any other array is stored as float64
                v = np.array(v, dtype=v.dtype if v.dtype.kind in "biuO" else float)
            v.setflags(write=False)
        else:  # dicts become read-only mappings, lists tuples (check_fields already copied a dict's arrays)
            v = frozen_value(v, name=f"{type(obj).__name__}.{name}")
        object.__setattr__(obj, name, v)


def validated_post_init(self: object) -> None:
    """``__post_init__`` of a result class: :func:`check_fields`, then read-only copies of its arrays, its dicts
    and lists as read-only mappings and tuples (``fusion._frozen.frozen_value``)."""
    values = check_fields(self)
    _store(self, values, copy=True)
    for f in dataclasses.fields(self):  # type: ignore[arg-type]
        if f.name not in values:  # the fields the spec does not check: dicts and lists frozen too, arrays copied
            object.__setattr__(self, f.name, frozen_value(getattr(self, f.name), copy=True,
                                                          name=f"{type(self).__name__}.{f.name}"))


def shared_post_init(self: object) -> None:
    """``__post_init__`` of a bundle of other results' values (chapter 05's ledger inputs): :func:`check_fields`, then
    the given values themselves are stored, not the checked copies: arrays made read-only in place, dicts and lists
    read-only mappings and tuples of the same items (a dict's keys as its spec's ``read_key`` reads them). The
    bundle shares its studies' data (one computation, one copy in memory: the studies are cached and their arrays
    already read-only)."""
    checked = check_fields(self)
    given = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}  # type: ignore[arg-type]
    for name, v in given.items():
        if name in checked:
            given[name] = _shared(v, checked[name])
    _store(self, given, copy=False)


def _shared(given: Any, checked: Any) -> Any:
    """What a bundle stores of a field given as ``given`` and read by its spec as ``checked``: the given values
    (shared, not copied), except that a number or integer is the number read, never a caller's 0-d array or
    ``__index__`` object, also inside a tuple or a dict (fuzz 29a C1, 31b C7: ``arch_seeds`` kept the caller's
    objects, which a later edit changed), and a dict's keys are the keys its spec's ``read_key`` reads."""
    if type(checked) in (int, float):
        return given if isinstance(given, (int, float, np.integer, np.floating)) else checked
    if isinstance(checked, tuple) and isinstance(given, (tuple, list)) and len(given) == len(checked):
        items = tuple(_shared(g, c) for g, c in zip(given, checked))
        return given if all(a is b for a, b in zip(items, given)) else items
    if isinstance(checked, Mapping) and isinstance(given, Mapping) and len(given) == len(checked):
        read = list(checked)  # in the given order (a read_key keeps it), unless a spec of fixed keys reordered them
        if not all(bool(a == b) for a, b in zip(read, given)) and all(k in checked for k in given):
            read = list(given)
        values = [_shared(g, checked[k]) for g, k in zip(given.values(), read)]
        if all(a is b for a, b in zip(read, given)) and all(a is b for a, b in zip(values, given.values())):
            return given
        return dict(zip(read, values))
    return given


def trusted(cls: type, **fields: Any) -> Any:
    """Build a result from validated, freshly computed fields without re-checking them (the private constructor).

    For the package's own producers only: every array must already satisfy ``cls.__result_spec__`` and be
    owned by the new object (computed here, not a view of a caller's argument); it is made read-only in
    place, not copied. Fields with defaults may be left out.
    """
    obj = object.__new__(cls)
    for f in dataclasses.fields(cls):
        if f.name in fields:
            continue
        if f.default is not dataclasses.MISSING:
            fields[f.name] = f.default
        elif f.default_factory is not dataclasses.MISSING:
            fields[f.name] = f.default_factory()
        else:
            raise TypeError(f"trusted({cls.__name__}) misses the field {f.name}")
    _store(obj, fields, copy=False)
    return obj
