"""Independent fuzzer of the public API of :mod:`fusion` (issue 35).

Walks every public callable (the ``__all__`` of every package and module of :mod:`fusion`, ``fusion.book``
included since round 3 but for its per-chapter helpers and :data:`BOOK_SKIPPED`), builds one valid call for each, then replaces one argument
at a time by a mutated value of one *class* of bad input and classifies the outcome.

Valid calls come from the known examples of ``tests/test_bad_input.py`` (its registry: one valid call
per public callable); a callable without one is called with its signature's defaults, and reported as
``no valid call`` when that is impossible. The registry's own mutation lists are *not* used: the kind of
each argument is inferred here from its valid value, its name and its docstring, and every mutation of
the classes below is applied to every argument of that kind.

Classes (``--list`` prints the mutations of each):

========== =====================================================================================
complex    complex arrays and numbers (``+0j`` included)
bool       boolean arrays and ``True`` where numbers are expected (masks documented as such excepted)
nonfinite  NaN, +inf, -inf in one entry or a scalar
magnitude  subnormal, near-subnormal ("tiny normal"), and huge finite values, one entry or all
shape      one dimension more or less, a transposed matrix, a scalar for an array
empty      zero-length arrays and sequences
companion  one axis one shorter than the companion arrays of the same call
type       strings, bytes, None, dicts, lists of strings, plain objects
index      negative, past-the-end and fractional indices; reversed, empty or out-of-range windows
seed       float seeds (integral or not) and floats for a Generator
nested     bad entries inside sequences of arrays, tuples of numbers and options dicts
size       counts beyond anything that can be allocated or run
layout     the same numbers as a strided view, a read-only array, Fortran order, big-endian or
           integer dtype (value-preserving: the result must equal the valid call's)
object     object-dtype arrays of the same numbers (value-preserving), numeric strings, a ``None``
           inside an object array
zero_d     0-d arrays and numpy scalars for numbers (value-preserving), a 0-d array for a 1-D one
signed     negative zero for zeros (one entry, all, a scalar), and +inf beside -inf in one array
bigint     overflow-sized integers (2**63, uint64 maxima) inside integer arrays and as numpy counts;
           numpy integer scalars for counts and seeds (value-preserving)
order      duplicated and reversed time stamps (refused where the docstring says increasing)
========== =====================================================================================

Outcomes counted as bad:

* ``nonfinite``: the call returned NaN or infinity (anywhere in its result) where the valid call did not;
* ``exception``: anything but ``ValueError``/``TypeError`` escaped (``LinAlgError``, being a
  ``ValueError`` from inside numpy, counts as unnamed);
* ``unnamed``: ``ValueError``/``TypeError`` whose message names neither the argument nor a companion;
* ``accepted``: a mutation that is invalid whatever the function (complex, bool, NaN, wrong types for
  numbers, float seeds, reversed windows, negative indices, bad nested entries) returned normally;
* ``timeout``: the call ran longer than ``--timeout`` seconds;
* ``changed``: a value-preserving mutation (layout, object dtype, 0-d, numpy scalars) returned a
  result that differs from the valid call's (beyond a relative 1e-9: a Fortran-order matrix may
  take another BLAS path).

Usage::

    .venv/bin/python tools/fuzz_public_api.py [--seed 35] [--json out.json] [--show 5] [--only NAME]

Seeded; about a minute on one core.
"""

from __future__ import annotations

import argparse
import collections
import copy
import dataclasses
import decimal
import importlib
import inspect
import json
import pkgutil
import re
import typing
import signal
import sys
import time
import warnings
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

import fusion  # noqa: E402

CLASSES = ("complex", "bool", "nonfinite", "magnitude", "shape", "empty", "companion", "type", "index", "seed",
           "nested", "size", "layout", "object", "zero_d", "signed", "bigint", "order")
BAD = ("nonfinite", "exception", "unnamed", "accepted", "timeout", "changed")
#: Names of time-stamp arguments (the ``order`` class).
TIME_NAMES = re.compile(r"^(t|ts|times?|t_[a-z]+|t[0-9]|stamps|timestamps)$")

#: Names of count arguments that are indices (into sensors, samples, ...), not sizes.
INDEX_NAMES = re.compile(r"^(axis|index|i|j|fault_sensor|sensor|node|component|first|last|start|stop|block)$")
SEED_NAMES = re.compile(r"(^|_)seeds?($|_)")
#: Integer arguments that may be negative (a power of ten's exponent): a negative value is not strict.
SIGNED_NAMES = re.compile(r"^(exponent|offset|shift)$")
#: Sequences of labels (row labels of a table): any values, only a non-sequence is wrong.
LABEL_NAMES = re.compile(r"^(index|labels|columns)$")


# --------------------------------------------------------------------------------------------
# the public callables and their valid calls
# --------------------------------------------------------------------------------------------


#: Public callables of ``fusion.book`` not fuzzed, by reason (everything else of it is, since round 3).
BOOK_SKIPPED = {
    # renderers and figure state: they take a matplotlib figure or axes, or set global style
    "fusion.book.style.use_book_style": "sets matplotlib's global style", "fusion.book.figures.audit_figure": "takes a figure",
    "fusion.book.figures.glue_figure": "takes a figure", "fusion.book.glue.glue_all": "glues into a running notebook",
    "fusion.book.tables.use_book_tables": "sets pandas' global display options",
    # file- and cluster-bound: paths, a dask client, a command line, a notebook record executed
    "fusion.book.claims.load": "reads a claims file (schema errors tested in tests/test_rulebook.py)",
    "fusion.book.claims.load_all": "reads the claims directory", "fusion.book.claims.claims_dir": "finds a directory",
    "fusion.book.claims.evaluate": "runs a record's evidence function (seconds to minutes)",
    "fusion.book.claims.build_ledger": "takes the Evidence objects of a whole chapter",
    "fusion.book.ledger.ledger_dir": "finds a directory", "fusion.book.stability.sweep": "takes a dask client",
    "fusion.book.stability.main": "a command line", "fusion.book.stability.run_task": "executes a record (minutes)",
    "fusion.book.stability.run_batch": "executes records (minutes)",
    "fusion.book.stability.stochastic_readings": "reads the claims directory",
}


def public_callables(book: bool = True) -> dict[str, Callable[..., Any]]:
    """Every callable in the ``__all__`` of a package or module of :mod:`fusion`.

    ``fusion.book.chapters`` (per-chapter presentation helpers, exercised by the notebooks) and
    :data:`BOOK_SKIPPED` are left out; ``book=False`` leaves out all of ``fusion.book`` (rounds 1-2).
    """
    out: dict[str, Callable[..., Any]] = {}
    names = ["fusion"] + [m.name for m in pkgutil.walk_packages(fusion.__path__, "fusion.")
                          if not m.name.startswith("fusion.book.chapters") and (book or not m.name.startswith("fusion.book"))]
    for modname in names:
        mod = importlib.import_module(modname)
        for n in getattr(mod, "__all__", []):
            obj = getattr(mod, n)
            if callable(obj) and typing.get_origin(obj) is None:  # type aliases are not callables
                key = f"{obj.__module__}.{obj.__qualname__}"
                if key.startswith("fusion.book.chapters.") or key in BOOK_SKIPPED or (
                        not book and key.startswith("fusion.book.")):
                    continue
                out[key] = obj
    return out


def book_examples() -> dict[str, dict[str, Any]]:
    """Valid calls of the ``fusion.book`` callables that the test registry does not hold (stability helpers, specs)."""
    from fusion.book import stability as st

    t = [st.Task("ci", "ci-a", "primary", "primary", 11, 100), st.Task("ci", "ci-a", "alt", "reseed", 11, 100),
         st.Task("ci", "ci-a", "primary", "primary", 12, 100)]
    res = [st.TaskResult(x, "reproduced", 1.5) for x in t]
    return {
        "fusion.book.stability.Task": dict(source="ci", record="ci-a", reading="primary", kind="stochastic", seed=11,
                                           runs=100, scaled=False),
        "fusion.book.stability.TaskResult": dict(task=t[0], status="reproduced", seconds=1.5, error=""),
        "fusion.book.stability.seeds": dict(k=3, root_seed=7, avoid=(5,)),
        "fusion.book.stability.tasks": dict(readings={("ci", "ci-a"): {"primary": ("primary", 100),
                                                                       "alt": ("reseed", 50)}},
                                            seed_list=[11, 12], runs_factor=3),
        "fusion.book.stability.batches": dict(task_list=t),
        "fusion.book.stability.summarise": dict(results=res, seed_list=[11, 12], committed={"ci-a": "reproduced"}),
    }


def _is_result_type(obj: Any) -> bool:
    """A frozen result container or an exception type: not an input-taking function."""
    return inspect.isclass(obj) and (issubclass(obj, BaseException) or (
        dataclasses.is_dataclass(obj) and obj.__dataclass_params__.frozen and not obj.__init__.__doc__
        and not getattr(obj, "__post_init__", None)))


def known_examples() -> tuple[dict[str, dict[str, Any]], set[str]]:
    """Valid calls from the test registry (values only) and its list of result types."""
    import test_bad_input as tb

    return {n: {k: a.value for k, a in spec.items()} for n, spec in tb.registry().items()}, set(tb.RESULT_TYPES)


# --------------------------------------------------------------------------------------------
# argument kinds
# --------------------------------------------------------------------------------------------


def _numbers(v: Any) -> bool:
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, (bool, np.bool_))


def kind_of(name: str, value: Any, doc: str) -> str:
    """The kind of an argument, from its valid value, its name and the callable's docstring."""
    if isinstance(value, np.random.Generator):
        return "rng"
    if isinstance(value, (bool, np.bool_)):
        return "flag"
    if isinstance(value, str):
        return "option"
    if isinstance(value, dict):
        return "options"
    if isinstance(value, (int, np.integer)):
        if SEED_NAMES.search(name):
            return "seed"
        return "index" if INDEX_NAMES.match(name) else "count"
    if isinstance(value, (float, np.floating)):
        return "real"
    if isinstance(value, np.ndarray):
        if value.dtype.kind == "b":
            return "mask"
        if value.dtype.kind in "iu":
            return "int_array"
        if value.dtype.kind == "f":
            return "array" if value.size else "other"
        return "other"
    if isinstance(value, (list, tuple)) and value:
        if LABEL_NAMES.match(name):
            return "labels"
        if all(isinstance(e, np.ndarray) and e.dtype.kind == "f" for e in value):
            return "array_seq"
        if all(isinstance(e, np.random.Generator) for e in value):
            return "rng_seq"
        if all(isinstance(e, (bool, np.bool_)) for e in value):
            return "mask"
        if all(isinstance(e, (int, np.integer)) and not isinstance(e, bool) for e in value):
            if name in ("window", "samples") and len(value) == 2:
                return "window"
            return "seed_seq" if SEED_NAMES.search(name) else "int_seq"
        if all(_numbers(e) for e in value):
            return "array"
        if all(isinstance(e, (list, tuple)) and e and all(_numbers(x) for x in e) for e in value):
            return "nested_numbers"
        if all(isinstance(e, str) for e in value):
            return "names"
    if callable(value) and not inspect.isclass(value):
        return "callable"
    if value is None:
        return "none"
    return "object"


def _as_like(template: Any, arr: np.ndarray) -> Any:
    """``arr`` in the container type of ``template`` (a tuple stays a tuple of numbers)."""
    if isinstance(template, tuple):
        return tuple(arr.tolist())
    if isinstance(template, list):
        return arr.tolist()
    return arr


# --------------------------------------------------------------------------------------------
# mutations
# --------------------------------------------------------------------------------------------


@dataclasses.dataclass(frozen=True)
class Mutation:
    """One mutated value of one argument: its class, a label, and whether it is invalid for any function."""

    cls: str
    label: str
    value: Any
    strict: bool  # invalid whatever the function: acceptance is a bad outcome
    same: bool = False  # value-preserving: an accepted call must return the valid call's result


def _array_mutations(v: Any, rng: np.random.Generator, companions: list[tuple[str, int]]) -> Iterator[Mutation]:
    a = np.array(v, dtype=float, copy=True)
    flat = a.reshape(-1)
    i = int(rng.integers(flat.size))
    imag = float(rng.uniform(0.1, 2.0))
    yield Mutation("complex", "complex array", a + 1j * imag, True)
    yield Mutation("complex", "complex array +0j", a.astype(complex), True)
    if isinstance(v, (tuple, list)):
        yield Mutation("complex", "complex entry in a sequence", tuple(complex(x, imag) if k == i else x
                                                                      for k, x in enumerate(a.tolist())), True)
    yield Mutation("bool", "bool array", a != 0, True)
    yield Mutation("bool", "all-True bool array", np.ones(a.shape, dtype=bool), True)
    for lab, x, strict in (("NaN entry", np.nan, True), ("+inf entry", np.inf, False), ("-inf entry", -np.inf, False)):
        b = a.copy()
        b.reshape(-1)[i] = x
        yield Mutation("nonfinite", lab, _as_like(v, b), strict)
    for lab, x in (("subnormal 5e-324", 5e-324), ("subnormal 1e-310", 1e-310), ("tiny normal 3e-308", 3e-308),
                   ("tiny normal 1e-300", 1e-300), ("huge 1e200", 1e200), ("huge 1e300", 1e300)):
        b = a.copy()
        b.reshape(-1)[i] = x * (np.sign(b.reshape(-1)[i]) or 1.0)
        yield Mutation("magnitude", lab + " (one entry)", _as_like(v, b), False)
        c = np.where(a != 0, np.sign(a) * x, x)
        yield Mutation("magnitude", lab + " (all entries)", _as_like(v, c), False)
    yield Mutation("magnitude", "all zeros", _as_like(v, np.zeros_like(a)), False)
    yield Mutation("magnitude", "all equal", _as_like(v, np.full_like(a, flat[i])), False)
    yield Mutation("shape", "one dimension more", np.stack([a, a], axis=-1), False)
    if a.ndim >= 1:
        yield Mutation("shape", "one dimension less", a[0], False)
    if a.ndim == 2 and a.shape[0] != a.shape[1]:
        yield Mutation("shape", "transposed", a.T.copy(), False)
    if a.ndim >= 1:
        yield Mutation("empty", "zero-length first axis", np.empty((0,) + a.shape[1:]), False)
        yield Mutation("empty", "empty list", [], False)
    for axis in sorted({ax for _, ax in companions}):
        if a.ndim > axis and a.shape[axis] > 1:
            yield Mutation("companion", f"axis {axis} one shorter than its companions",
                           _as_like(v, np.take(a, range(a.shape[axis] - 1), axis=axis)), False)


def _new_array_mutations(name: str, v: Any, doc: str) -> Iterator[Mutation]:
    """The classes added in round 3: layout, object dtype, 0-d, signed zeros and infinities, big integers, order."""
    a = np.array(v, dtype=float, copy=True)
    if isinstance(v, np.ndarray):
        if a.ndim >= 1 and a.shape[-1] > 0:
            wide = np.repeat(a, 2, axis=-1)
            yield Mutation("layout", "strided view", wide[..., ::2], False, True)
        ro = a.copy()
        ro.setflags(write=False)
        yield Mutation("layout", "read-only array", ro, False, True)
        if a.ndim >= 2:
            yield Mutation("layout", "Fortran order", np.asfortranarray(a), False, True)
        yield Mutation("layout", "big-endian float64", a.astype(">f8"), False, True)
        if a.size and np.all(a == np.round(a)) and np.abs(a).max() < 2**53:
            yield Mutation("layout", "int64 array of the same integers", a.astype(np.int64), False, True)
        if a.size and np.array_equal(a.astype(np.float32).astype(float), a):
            yield Mutation("layout", "float32 array of the same numbers", a.astype(np.float32), False, True)
    obj = np.empty(a.shape, dtype=object)
    obj[...] = a.tolist() if a.ndim else float(a)
    yield Mutation("object", "object-dtype array of the same numbers", obj, False, True)
    yield Mutation("object", "numeric strings", np.array([repr(x) for x in a.reshape(-1).tolist()]).reshape(a.shape),
                   True)
    if a.size:
        bad = obj.copy()
        bad.reshape(-1)[0] = None
        yield Mutation("object", "None inside an object array", bad, True)
    if a.ndim == 1 and a.size:
        yield Mutation("zero_d", "0-d array for a 1-D one", np.array(a[0]), False)
    zeros = a == 0
    if zeros.any():
        b = a.copy()
        b[zeros] = -0.0
        yield Mutation("signed", "negative zero for the zeros", _as_like(v, b), False, True)
    yield Mutation("signed", "all entries negative zero", _as_like(v, np.full_like(a, -0.0)), False)
    if a.size >= 2:
        b = a.copy()
        b.reshape(-1)[0], b.reshape(-1)[-1] = np.inf, -np.inf
        yield Mutation("signed", "+inf and -inf in one array", _as_like(v, b), False)
    if TIME_NAMES.match(name) and a.ndim == 1 and a.size >= 3:
        increasing = bool(re.search(rf"^{re.escape(name)} :[^\n]*(\n    [^\n]*)*?(increasing|sorted|ascending)", doc,
                                    flags=re.M))
        b = a.copy()
        b[1] = b[0]
        yield Mutation("order", "duplicated time stamp", _as_like(v, b), increasing)
        yield Mutation("order", "reversed time stamps", _as_like(v, a[::-1].copy()), increasing)


def _int_array_mutations(v: np.ndarray) -> Iterator[Mutation]:
    """Big integers inside an integer array (the ``bigint`` class)."""
    a = np.array(v, copy=True)
    if a.size:
        b = a.astype(object)
        b.reshape(-1)[0] = 2**63
        yield Mutation("bigint", "2**63 inside (object array)", b, False)
        yield Mutation("bigint", "uint64 maximum inside", np.where(np.arange(a.size).reshape(a.shape) == 0,
                                                                     np.uint64(2**64 - 1), a.astype(np.uint64)), False)
        yield Mutation("layout", "int32 array of the same integers", a.astype(np.int32), False, True)


def _scalar_mutations(v: float, kind: str, rng: np.random.Generator) -> Iterator[Mutation]:
    imag = float(rng.uniform(0.1, 2.0))
    yield Mutation("complex", "complex number", complex(v, imag), True)
    yield Mutation("complex", "numpy complex +0j", np.complex128(v), True)
    yield Mutation("bool", "True", True, True)
    yield Mutation("bool", "numpy bool", np.bool_(False), True)
    yield Mutation("nonfinite", "NaN", float("nan"), True)
    yield Mutation("nonfinite", "+inf", float("inf"), False)
    yield Mutation("nonfinite", "-inf", float("-inf"), False)
    yield Mutation("shape", "1-element array", np.array([v]), False)
    yield Mutation("shape", "2-element array", np.array([v, v]), False)
    yield Mutation("zero_d", "0-d array", np.array(v), False, True)
    yield Mutation("zero_d", "numpy float64 scalar", np.float64(v), False, True)
    yield Mutation("object", "0-d object array", np.array(v, dtype=object), False, True)
    if v == 0:
        yield Mutation("signed", "negative zero", -0.0, False, True)
    if kind == "real":
        for lab, x in (("subnormal", 1e-310), ("tiny normal", 3e-308), ("tiny normal 1e-300", 1e-300),
                       ("huge 1e200", 1e200), ("huge 1e300", 1e300)):
            yield Mutation("magnitude", lab, x * (np.sign(v) or 1.0), False)
        yield Mutation("magnitude", "negative tiny normal", -3e-308, False)


def _count_mutations(name: str, v: int, kind: str) -> Iterator[Mutation]:
    yield Mutation("complex", "complex count", complex(v, 1.0), True)
    yield Mutation("bool", "True", True, True)
    yield Mutation("nonfinite", "NaN", float("nan"), True)
    yield Mutation("nonfinite", "+inf", float("inf"), True)
    yield Mutation("type", "fractional", v + 0.5, True)
    yield Mutation("type", "integral float", float(v), True)  # a count is an integer type (rule 13)
    yield Mutation("type", "integral Decimal", decimal.Decimal(v), True)
    yield Mutation("shape", "array of counts", np.array([v, v]), False)
    yield Mutation("zero_d", "0-d integer array", np.array(v), False, True)
    yield Mutation("bigint", "numpy int32 scalar", np.int32(v), False, True)
    if v >= 0:
        yield Mutation("bigint", "numpy uint64 scalar", np.uint64(v), False, True)
    if kind != "index":
        yield Mutation("bigint", "int64 maximum", np.int64(2**63 - 1), False)
        yield Mutation("bigint", "uint64 maximum", np.uint64(2**64 - 1), False)
    if kind == "seed":
        yield Mutation("seed", "integral float seed", float(v), True)
        yield Mutation("seed", "fractional seed", v + 0.25, True)
        yield Mutation("seed", "negative seed", -1, True)
        yield Mutation("size", "seed 2**80", 2**80, False)
    elif kind == "index":
        yield Mutation("index", "negative index", -1, name != "axis")
        yield Mutation("index", "index past the end", 10**6, True)
        yield Mutation("index", "fractional index", 1.5, True)
    else:
        yield Mutation("index", "negative count", -3, not SIGNED_NAMES.match(name))
        for lab, x in (("10**9", 10**9), ("10**12", 10**12), ("2**63", 2**63), ("2**80", 2**80), ("1e20 as a float", 1e20)):
            yield Mutation("size", lab, x, False)


def _window_mutations(v: tuple[int, int]) -> Iterator[Mutation]:
    a, b = int(v[0]), int(v[1])
    yield Mutation("index", "reversed window", (b, a), True)
    yield Mutation("index", "empty window", (a, a), False)
    yield Mutation("index", "negative window start", (-1, b), True)
    yield Mutation("index", "window past the end", (a, 10**7), False)
    yield Mutation("index", "fractional window", (a + 0.5, b), True)
    yield Mutation("index", "three-element window", (a, b, b + 1), True)
    yield Mutation("complex", "complex window", (complex(a, 1), b), True)
    yield Mutation("bool", "bool window", (True, b), True)


def _sequence_mutations(name: str, v: Any, kind: str, rng: np.random.Generator) -> Iterator[Mutation]:
    """Nested structures: one bad entry inside an otherwise valid sequence."""
    seq = list(v)
    wrap = tuple if isinstance(v, tuple) else list
    i = int(rng.integers(len(seq)))

    def at(x: Any) -> Any:
        return wrap(seq[:i] + [x] + seq[i + 1:])

    yield Mutation("empty", "empty sequence", wrap([]), False)
    yield Mutation("type", "a string for the sequence", "abc", True)
    if kind == "array_seq":
        e = np.array(seq[i], dtype=float, copy=True)
        k = int(rng.integers(e.size))
        for lab, x, strict in (("NaN", np.nan, True), ("+inf", np.inf, False), ("subnormal", 1e-310, False),
                               ("huge", 1e300, False)):
            b = e.copy()
            b.reshape(-1)[k] = x
            yield Mutation("nested", f"{lab} inside entry {i}", at(b), strict)
        yield Mutation("nested", f"complex entry {i}", at(e + 0.5j), True)
        yield Mutation("nested", f"bool entry {i}", at(e != 0), True)
        yield Mutation("nested", f"string entry {i}", at("abc"), True)
        yield Mutation("nested", f"None entry {i}", at(None), True)
        yield Mutation("nested", f"entry {i} one dimension more", at(np.stack([e, e], -1)), False)
        if e.ndim >= 1 and e.shape[0] > 1:
            yield Mutation("nested", f"entry {i} one shorter", at(e[:-1]), False)
        yield Mutation("companion", "one entry fewer", wrap(seq[:-1]), False) if len(seq) > 1 else None
    elif kind == "nested_numbers":
        e = list(seq[i])
        for lab, x, strict in (("NaN", float("nan"), True), ("complex", 1 + 1j, True), ("string", "abc", True),
                               ("None", None, True), ("bool", True, True), ("huge", 1e300, False)):
            yield Mutation("nested", f"{lab} inside entry {i}", at(type(seq[i])([x] + e[1:])), strict)
        yield Mutation("nested", f"ragged entry {i}", at(type(seq[i])(e + e)), False)
    elif kind in ("int_seq", "seed_seq"):
        strict_seed = kind == "seed_seq"
        yield Mutation("nested", f"fractional entry {i}", at(seq[i] + 0.5), True)
        yield Mutation("nested", f"complex entry {i}", at(complex(seq[i], 1)), True)
        yield Mutation("nested", f"bool entry {i}", at(True), True)
        yield Mutation("nested", f"string entry {i}", at("abc"), True)
        yield Mutation("nested", f"NaN entry {i}", at(float("nan")), True)
        yield Mutation("nested", f"nested list entry {i}", at([seq[i]]), True)
        if strict_seed:
            yield Mutation("seed", f"integral float seed entry {i}", at(float(seq[i])), True)
        else:
            yield Mutation("size", f"entry {i} = 10**12", at(10**12), False)
            yield Mutation("index", f"negative entry {i}", at(-1), False)
    elif kind == "rng_seq":
        yield Mutation("seed", f"float for generator {i}", at(0.5), True)
        yield Mutation("seed", f"integral float for generator {i}", at(3.0), True)
        yield Mutation("nested", f"string for generator {i}", at("abc"), True)
        yield Mutation("companion", "one generator fewer", wrap(seq[:-1]), False) if len(seq) > 1 else None
    elif kind == "names":
        yield Mutation("nested", f"number for name {i}", at(3.0), True)
        yield Mutation("nested", f"None for name {i}", at(None), True)
        yield Mutation("nested", f"unknown name {i}", at("no-such-name"), False)
        yield Mutation("nested", f"nested list for name {i}", at([seq[i]]), True)


#: Dicts of options (every key is read, a misspelt key must be refused), as opposed to a study's
#: result passed back in (read for some of its entries: an extra key is harmless).
OPTION_NAMES = re.compile(r"options|^cfg$|config|^kf$|^failure$")


def _options_mutations(name: str, v: dict) -> Iterator[Mutation]:
    strict = bool(OPTION_NAMES.search(name))
    yield Mutation("nested", "unknown key", dict(v, no_such_key=1), strict)
    for k in v:
        yield Mutation("nested", f"None for option {k!r}", {**v, k: None}, False)
        yield Mutation("nested", f"string for option {k!r}", {**v, k: "abc"}, False)
        yield Mutation("nested", f"nested dict for option {k!r}", {**v, k: {"a": 1}}, False)
        yield Mutation("nested", f"NaN for option {k!r}", {**v, k: float("nan")}, strict)
        yield Mutation("nested", f"complex for option {k!r}", {**v, k: 1 + 1j}, strict)
        yield Mutation("nested", f"bool for option {k!r}", {**v, k: True}, False)
    yield Mutation("type", "a list for the options", [1, 2], True)


WRONG_TYPES: tuple[tuple[str, Any], ...] = (("string", "abc"), ("bytes", b"abc"), ("None", None), ("dict", {"a": 1}),
                                            ("list of strings", ["a", "b"]), ("object", object()))


def mutations(name: str, value: Any, kind: str, default_none: bool, rng: np.random.Generator,
              companions: list[tuple[str, int]], doc: str = "") -> Iterator[Mutation]:
    """Every mutation of one argument of the given kind."""
    numeric = kind in ("array", "real", "count", "index", "seed", "int_array")
    for lab, bad in WRONG_TYPES:
        if lab == "None" and default_none:
            continue
        if kind in ("option", "names") and lab == "list of strings":
            continue
        yield Mutation("type", lab, bad, numeric)
    if kind in ("array", "int_array"):
        yield from _array_mutations(value, rng, companions)
        if kind == "array":
            yield from _new_array_mutations(name, value, doc)
        else:
            yield from _int_array_mutations(value)
        if isinstance(value, (tuple, list)) and all(_numbers(e) for e in value):
            yield Mutation("nested", "a nested list inside the numbers", type(value)([[value[0]]] + list(value[1:])), True)
            yield Mutation("nested", "a string inside the numbers", type(value)(["1.0"] + list(value[1:])), True)
    elif kind == "real":
        yield from _scalar_mutations(float(value), kind, rng)
    elif kind in ("count", "index", "seed"):
        yield from _count_mutations(name, int(value), kind)
    elif kind == "window":
        yield from _window_mutations(value)
    elif kind in ("array_seq", "nested_numbers", "int_seq", "seed_seq", "rng_seq", "names"):
        yield from (m for m in _sequence_mutations(name, value, kind, rng) if m is not None)
    elif kind == "options":
        yield from _options_mutations(name, value)
    elif kind == "rng":
        yield Mutation("seed", "float seed for the generator", 0.5, True)
        yield Mutation("seed", "integral float seed for the generator", 3.0, True)
        yield Mutation("seed", "complex seed for the generator", 1 + 1j, True)
        yield Mutation("seed", "bool for the generator", True, True)
    elif kind == "option":
        yield Mutation("type", "number for an option", 3.0, True)
        yield Mutation("type", "bool for an option", True, True)
        yield Mutation("nested", "unknown option", "no-such-option", True)
    elif kind == "mask":
        yield Mutation("bool", "float 0/1 mask", np.asarray(value, dtype=float), False)
        yield Mutation("empty", "empty mask", np.zeros((0,), dtype=bool), False)


# --------------------------------------------------------------------------------------------
# outcomes
# --------------------------------------------------------------------------------------------


def nonfinite_paths(result: Any, path: str = "", depth: int = 0) -> set[str]:
    """Paths inside ``result`` that hold NaN or infinity (arrays, numbers, tuples, dicts, dataclasses)."""
    if depth > 6:
        return set()
    if isinstance(result, (float, np.floating, complex, np.complexfloating)):
        return set() if np.isfinite(result) else {path or "."}
    if isinstance(result, np.ndarray):
        if result.dtype.kind in "fc" and not np.all(np.isfinite(result)):
            return {path or "."}
        if result.dtype.kind == "O":
            return set().union(*(nonfinite_paths(e, f"{path}[{k}]", depth + 1) for k, e in enumerate(result.flat[:50])))
        return set()
    if isinstance(result, (tuple, list)):
        return set().union(set(), *(nonfinite_paths(e, f"{path}[{k}]", depth + 1) for k, e in enumerate(result[:200])))
    if isinstance(result, dict):
        return set().union(set(), *(nonfinite_paths(e, f"{path}[{k!r}]", depth + 1) for k, e in list(result.items())[:200]))
    if dataclasses.is_dataclass(result) and not isinstance(result, type):
        return set().union(set(), *(nonfinite_paths(getattr(result, f.name), f"{path}.{f.name}", depth + 1)
                                    for f in dataclasses.fields(result)))
    return set()


#: Fields and keys that hold wall-clock times: not compared.
TIMING_FIELDS = {"timings", "seconds", "elapsed", "wall"}


def differs(a: Any, b: Any, path: str = "", depth: int = 0) -> str:
    """Where ``b`` differs from ``a`` (``""`` if nowhere): float arrays beyond a relative 1e-9 of their scale."""
    if depth > 6:
        return ""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        x, y = np.asarray(a), np.asarray(b)
        if x.shape != y.shape:
            return f"{path or '.'}: shape {x.shape} != {y.shape}"
        if x.dtype.kind in "fc" and y.dtype.kind in "fciu":
            with np.errstate(all="ignore"):
                scale = float(np.nanmax(np.abs(x), initial=0.0)) if x.size else 0.0
                bad = ~((x == y) | (np.isnan(x) & np.isnan(y)) | (np.abs(x - y) <= 1e-9 * scale))
            return f"{path or '.'}: {int(bad.sum())} entries differ" if bad.any() else ""
        if x.dtype.kind == "O":
            for k, (e, f) in enumerate(zip(x.flat[:50], y.flat[:50])):
                if d := differs(e, f, f"{path}[{k}]", depth + 1):
                    return d
            return ""
        return "" if np.array_equal(x, y) else f"{path or '.'}: values differ"
    if isinstance(a, (float, np.floating)) and isinstance(b, (int, float, np.integer, np.floating)):
        return "" if (a == b or (a != a and b != b) or abs(a - b) <= 1e-9 * abs(a)) else f"{path or '.'}: {a!r} != {b!r}"
    if isinstance(a, (tuple, list)) and isinstance(b, (tuple, list)):
        if len(a) != len(b):
            return f"{path or '.'}: length {len(a)} != {len(b)}"
        for k, (e, f) in enumerate(zip(a[:200], b[:200])):
            if d := differs(e, f, f"{path}[{k}]", depth + 1):
                return d
        return ""
    if isinstance(a, dict) and isinstance(b, dict):
        if list(a) != list(b):
            return f"{path or '.'}: keys differ"
        for k in list(a)[:200]:
            if k in TIMING_FIELDS:
                continue
            if d := differs(a[k], b[k], f"{path}[{k!r}]", depth + 1):
                return d
        return ""
    if dataclasses.is_dataclass(a) and not isinstance(a, type) and type(a) is type(b):
        for f in dataclasses.fields(a):
            if f.name in TIMING_FIELDS:
                continue
            if d := differs(getattr(a, f.name), getattr(b, f.name), f"{path}.{f.name}", depth + 1):
                return d
        return ""
    if isinstance(a, (int, str, bool, type(None))):
        return "" if a == b else f"{path or '.'}: {a!r} != {b!r}"
    return ""


#: Values of a strict class that a callable documents as valid (renderers of missing and infinite values):
#: ``(callable, argument) -> (mutation labels, the documentation)``; their acceptance is not counted.
DOCUMENTED_ACCEPTED = {
    ("fusion.book.ledger.fmt", "x"): (("NaN",), 'docstring: "n/a" for NaN'),
    ("fusion.book.tables.sci", "x"): (("NaN", "True", "numpy bool", "None"),
                                      "docstring: missing values read -, booleans yes and no"),
    ("fusion.book.style.color", "method"): (("unknown option",), "docstring: grey for methods without a colour"),
}

#: Non-finite results that are documented (and tested) for degenerate valid input: reported apart, not as bad.
DOCUMENTED_NONFINITE = {
    ("fusion.book.rulebook.hill_tail_index", "."): "inf when the top values are all equal or zero (docstring: no tail)",
    **{("fusion.book.rulebook.judge_paired", p): "+/-inf for a run whose statistic is infinite (docstring: rule R3)"
       for p in (".estimate", ".low", ".high")},
    **{("fusion.book.ledger.Comparison", p): "+inf marks a run whose statistic is infinite (docstring; rule R3)"
       for p in (".a", ".b", ".judgement.estimate", ".judgement.low", ".judgement.high")},
    ("fusion.book.rulebook.judge_paired", ".tail_index"): "inf for degenerate runs, all top differences equal or "
                                                          "10 or fewer finite (docstring: no tail to estimate)",
    ("fusion.book.ledger.Comparison", ".judgement.tail_index"): "inf for degenerate runs (judge_paired's docstring)",
    ("fusion.book.rulebook.median_interval", "."): "infinite values allowed (docstring): an infinite median or bound",
    ("fusion.estimates.chernoff.is_second_moment", "."): "inf outside the finite-variance region, and where log rho "
                                                         "is beyond the float range of rho (docstring)",
    ("fusion.readings.biased.plugin_ridge", ".k"): "k = inf where the least-squares estimate is exactly 0 "
                                                   "(RidgeFit docstring; tests/test_ridge.py); x stays finite (0)",
    ("fusion.readings.fusion_set.distribution_balance", "."): "inf where S_i = 0, a row whose fusion degrees are "
                                                              "all equal (docstring: identical readings)",
}


def documented_nonfinite(name: str, path: str) -> str | None:
    """The documented reason for a non-finite ``path`` in the result of ``name`` (a path or its parent listed), or ``None``."""
    for (n, p), why in DOCUMENTED_NONFINITE.items():
        if n == name and (path == p or path.startswith((p + "[", p + "."))):
            return why
    return None


class _Timeout(BaseException):
    pass


def _alarm(*_: Any) -> None:
    raise _Timeout


def _names(exc: BaseException, names: tuple[str, ...]) -> bool:
    text = str(exc)
    return any(re.search(rf"(?<![A-Za-z0-9_]){re.escape(n)}(?![A-Za-z0-9_])", text) for n in names)


def run(fn: Callable[..., Any], kwargs: dict[str, Any], timeout: float) -> tuple[str, Any]:
    """('ok', result), ('raised', exc) or ('timeout', None): ``timeout`` in CPU seconds of this process (a profiling
    timer, so that a loaded machine does not time a call out: a wall-clock alarm failed the bad-input length tests
    under `make test` beside other work), with a wall-clock backstop of ten times it (a call blocked on I/O)."""
    signal.signal(signal.SIGPROF, _alarm)
    signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_PROF, timeout)
    signal.setitimer(signal.ITIMER_REAL, 10 * timeout)
    try:
        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore")
            return "ok", fn(**kwargs)
    except _Timeout:
        return "timeout", None
    except RecursionError as exc:
        return "raised", exc
    except Exception as exc:  # noqa: BLE001 - classified by the caller
        return "raised", exc
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.setitimer(signal.ITIMER_REAL, 0)


def _fresh(kwargs: dict[str, Any]) -> dict[str, Any]:
    """The valid call's arguments with fresh generators (a call must not depend on the previous ones)."""
    out = {}
    for k, v in kwargs.items():
        if isinstance(v, np.random.Generator):
            out[k] = np.random.default_rng(0)
        elif isinstance(v, (list, tuple)) and v and all(isinstance(e, np.random.Generator) for e in v):
            out[k] = type(v)(np.random.default_rng(j) for j in range(len(v)))
        elif isinstance(v, (list, tuple)) and v and all(isinstance(e, np.random.SeedSequence) for e in v):
            out[k] = type(v)(copy.deepcopy(e) for e in v)  # spawning advances a SeedSequence
        else:
            out[k] = v
    return out


def _companions(arg: str, valid: dict[str, Any]) -> list[tuple[str, int]]:
    """Axes of ``arg`` whose length another array argument of the call shares (its companions)."""
    try:
        shape = np.shape(valid[arg])
    except Exception:  # noqa: BLE001
        return []
    out = []
    for axis, n in enumerate(shape):
        for k, v in valid.items():
            if k == arg or isinstance(v, (str, dict)) or callable(v):
                continue
            try:
                other = np.shape(v)
            except Exception:  # noqa: BLE001
                continue
            if n > 1 and n in other:
                out.append((k, axis))
                break
    return out


@dataclasses.dataclass(frozen=True)
class Finding:
    callable: str
    arg: str
    cls: str
    label: str
    outcome: str
    detail: str


def fuzz_one(name: str, fn: Callable[..., Any], valid: dict[str, Any], rng: np.random.Generator,
             timeout: float, budget: int | None) -> tuple[int, list[Finding]]:
    """Fuzz one callable; (number of calls, bad outcomes)."""
    how, base = run(fn, _fresh(valid), max(timeout, 10.0))
    if how != "ok":
        return 1, [Finding(name, "-", "valid", "valid call", "exception", f"{type(base).__name__}: {base}")]
    base_nonfinite = nonfinite_paths(base)
    try:
        params = inspect.signature(fn).parameters
    except (TypeError, ValueError):
        params = {}
    doc = (inspect.getdoc(fn) or "") + ("\n" + (inspect.getdoc(fn.__init__) or "") if inspect.isclass(fn) else "")
    todo: list[tuple[str, Mutation]] = []
    for arg, value in valid.items():
        kind = kind_of(arg, value, doc)
        # None is valid where it is the default or the annotation says so (``float | None``)
        default_none = arg in params and (params[arg].default is None or "None" in str(params[arg].annotation))
        for m in mutations(arg, value, kind, default_none, rng, _companions(arg, valid), doc):
            if m.label == "unknown option" and not _has_choices(doc, arg):
                m = dataclasses.replace(m, strict=False)  # a free string (a name, a label), not a choice
            todo.append((arg, m))
    if budget is not None and len(todo) > budget:
        keep = sorted(rng.choice(len(todo), size=budget, replace=False).tolist())
        todo = [todo[k] for k in keep]
    findings = []
    for arg, m in todo:
        kwargs = _fresh(valid)
        kwargs[arg] = m.value
        how, out = run(fn, kwargs, timeout)
        # a mismatch is a property of the pair: naming a companion is enough (shape and companion classes)
        names = (arg,) + tuple(k for k in valid if m.cls in ("companion", "shape") and k != arg)
        if how == "timeout":
            findings.append(Finding(name, arg, m.cls, m.label, "timeout", f"more than {timeout} s"))
        elif how == "raised":
            if not isinstance(out, (ValueError, TypeError)) or isinstance(out, np.linalg.LinAlgError):
                findings.append(Finding(name, arg, m.cls, m.label, "exception", f"{type(out).__name__}: {out}"[:200]))
            elif not _names(out, names):
                findings.append(Finding(name, arg, m.cls, m.label, "unnamed", f"{type(out).__name__}: {out}"[:200]))
        else:
            bad_paths = nonfinite_paths(out) - base_nonfinite
            documented = {p for p in bad_paths if documented_nonfinite(name, p)}
            if documented:
                findings.append(Finding(name, arg, m.cls, m.label, "documented", ", ".join(sorted(documented))))
            bad_paths -= documented
            if bad_paths:
                findings.append(Finding(name, arg, m.cls, m.label, "nonfinite", ", ".join(sorted(bad_paths))[:200]))
            elif m.strict and m.label in DOCUMENTED_ACCEPTED.get((name, arg), ((),))[0]:
                findings.append(Finding(name, arg, m.cls, m.label, "documented", "accepted: "
                                        + DOCUMENTED_ACCEPTED[(name, arg)][1]))
            elif m.strict:
                findings.append(Finding(name, arg, m.cls, m.label, "accepted", "returned normally"))
            elif m.same and (diff := differs(base, out)):
                findings.append(Finding(name, arg, m.cls, m.label, "changed", diff[:200]))
    return len(todo) + 1, findings


def _has_choices(doc: str, arg: str) -> bool:
    """Whether the numpydoc entry of ``arg`` lists its choices (``kind : {"a", "b"}``) or names them."""
    m = re.search(rf"^{re.escape(arg)} : ([^\n]*)((?:\n    [^\n]*)*)", doc, flags=re.M)
    if m is None:
        return True  # undocumented: an unknown string is taken to be invalid
    return "{" in m.group(1) or bool(re.search(r"one of|:data:", m.group(1) + m.group(2)))


def default_call(fn: Callable[..., Any]) -> dict[str, Any] | None:
    """A valid call from the signature alone (every parameter has a default), or ``None``."""
    try:
        params = inspect.signature(fn).parameters.values()
    except (TypeError, ValueError):
        return None
    out = {}
    for p in params:
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
            continue
        if p.default is inspect.Parameter.empty:
            return None
        out[p.name] = p.default
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seed", type=int, default=35)
    ap.add_argument("--timeout", type=float, default=3.0,
                    help="seconds per mutated call (at least 10 times the valid call's)")
    ap.add_argument("--slow", type=float, default=0.15, help="a valid call slower than this gets --slow-budget mutations")
    ap.add_argument("--slow-budget", type=int, default=12)
    ap.add_argument("--only", default=None, help="fuzz the callables whose name contains this")
    ap.add_argument("--show", type=int, default=4, help="examples shown per class and outcome")
    ap.add_argument("--json", default=None, help="write every finding to this file")
    ap.add_argument("--list", action="store_true", help="list the public callables and exit")
    args = ap.parse_args(argv)

    t0 = time.perf_counter()
    callables = public_callables()
    examples, result_types = known_examples()
    examples = {**book_examples(), **examples}
    if args.list:
        print("\n".join(sorted(callables)))
        return 0
    rng = np.random.default_rng(args.seed)
    calls = 0
    findings: list[Finding] = []
    by_class_calls: collections.Counter[str] = collections.Counter()
    no_call = []
    fuzzed = 0
    for name in sorted(callables):
        if args.only and args.only not in name:
            continue
        fn = callables[name]
        if name in result_types or _is_result_type(fn):
            continue
        valid = examples.get(name) or default_call(fn)
        if valid is None:
            no_call.append(name)
            continue
        t = time.perf_counter()
        run(fn, _fresh(valid), 30.0)
        took = time.perf_counter() - t
        # a mutated call may take 10 times as long as the valid one (a loaded machine slows both)
        timeout = max(args.timeout, 10.0 * took)
        n, f = fuzz_one(name, fn, valid, np.random.default_rng([args.seed, len(name), sum(map(ord, name))]),
                        timeout, args.slow_budget if took > args.slow else None)
        calls += n
        fuzzed += 1
        findings.extend(f)
    elapsed = time.perf_counter() - t0
    documented = [f for f in findings if f.outcome == "documented"]
    findings = [f for f in findings if f.outcome != "documented"]
    table: dict[str, collections.Counter[str]] = collections.defaultdict(collections.Counter)
    for f in findings:
        table[f.cls][f.outcome] += 1
    print(f"fuzzed {fuzzed} public callables with {calls} calls in {elapsed:.0f} s (seed {args.seed}); "
          f"{len(findings)} bad outcomes")
    for f in documented:
        why = f.detail if f.detail.startswith("accepted: ") else \
            f"{f.detail}: {documented_nonfinite(f.callable, f.detail.split(', ')[0])}"
        print(f"documented (not counted): {f.callable}({f.arg}={f.label}): {why}")
    if no_call:
        print(f"no valid call for {len(no_call)}: {', '.join(no_call)}")
    print(f"{'class':<11}" + "".join(f"{o:>11}" for o in BAD) + f"{'total':>8}")
    for cls in CLASSES + ("valid",):
        if cls in table or cls != "valid":
            row = table.get(cls, collections.Counter())
            print(f"{cls:<11}" + "".join(f"{row[o]:>11}" for o in BAD) + f"{sum(row.values()):>8}")
    for cls in CLASSES + ("valid",):
        group = [f for f in findings if f.cls == cls]
        if not group:
            continue
        print(f"\n== {cls}: {len(group)}")
        for outcome in BAD:
            sub = [f for f in group if f.outcome == outcome]
            for f in sub[:args.show]:
                print(f"  [{outcome}] {f.callable}({f.arg}={f.label}): {f.detail}")
            if len(sub) > args.show:
                print(f"  [{outcome}] ... {len(sub) - args.show} more")
    if args.json:
        Path(args.json).write_text(json.dumps({"seed": args.seed, "calls": calls, "callables": fuzzed,
                                               "seconds": round(elapsed, 1),
                                               "counts": {c: dict(v) for c, v in table.items()},
                                               "findings": [dataclasses.asdict(f) for f in findings],
                                               "documented": [dataclasses.asdict(f) for f in documented]}, indent=1))
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
