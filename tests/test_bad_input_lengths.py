"""Property tests of the sequence arguments of issue 35 (fuzz13 bug 1 and its debatables), over the public API.

* rule 17 counts lengths: a sequence argument of 10**5 to 10**6 valid entries (seeds, sizes, grids of scales,
  periods or true values, generators) is either served within a second or two, or refused at once with a
  ``ValueError`` naming it, never minutes of work (the work budget counted only products of scalar counts);
* key-like sequences refuse a repeated entry: seeds or sizes whose results are keyed or indexed by their entries
  (a dict of cases by seed, rows by size, one bias per sensor) name the argument instead of silently collapsing
  two keys or adding two biases to one sensor.

The callables and their valid example calls are the registry of :mod:`tests.test_bad_input`; the kind of each
argument is the project fuzzer's (:func:`tools.fuzz_public_api.kind_of`), so that a new public function with a
sequence argument is covered without being named here.
"""

from __future__ import annotations

import re
import time
from typing import Any

import numpy as np
import pytest
from hypothesis import Phase, given, settings
from hypothesis import strategies as st

from test_bad_input_properties import CALLABLES, FZ, KIND, NAMES, REG, _valid

#: The argument kinds holding a sequence whose length can set a function's loops.
LONG_KINDS = ("seed_seq", "int_seq", "array", "int_array", "rng_seq", "array_seq", "nested_numbers")
#: (callable, argument) pairs whose long sequence still fails (strict xfails: a fix makes them pass). The pairwise
#: kernels of a long 1-D argument (n readings give an n x n matrix: rule 9's memory budget is not yet checked on
#: them, a MemoryError), and plugin_study's curve (plugin_risk's quadrature over a long grid, seconds).
PENDING_LENGTH: set[tuple[str, str]] = {
    ("fusion.book.audit.parameters_matching", "x"),
    ("fusion.readings.consistency.consistency_mask", "x"),
    *(("fusion.readings.fusion_set." + f, "x") for f in (
        "belief_degree", "belief_matrix", "binary_deletion", "distance_matrix", "fusion_degree_matrix",
        "fusion_set_weights", "mean_distances", "optimal_fusion_set", "optimal_set_members", "support_degree")),
    ("fusion.registration.methods.affine_decomposition", "z0"), ("fusion.registration.methods.expected_mse", "z0"),
    ("fusion.scenarios.correlated_sensors.oriented_covariance", "angles"),
    ("fusion.scenarios.ridge_sensors.plugin_study", "curve")}


def _long(value: Any, n: int) -> Any:
    """``value`` lengthened to ``n`` entries of its own kind: distinct integers (seeds, sizes) counted up from its
    first entry, other entries repeated cyclically; ``None`` when the value is not a 1-D sequence."""
    if isinstance(value, np.ndarray):
        if value.ndim != 1 or not value.size:
            return None
        if value.dtype.kind in "iu":
            return value[0] + np.arange(n, dtype=value.dtype)
        return np.resize(value, n)
    if not isinstance(value, (list, tuple)) or not value:
        return None
    if all(isinstance(e, (int, np.integer)) and not isinstance(e, bool) for e in value):
        return type(value)(range(int(value[0]), int(value[0]) + n))
    return type(value)(value[i % len(value)] for i in range(n))


def _pairs() -> list[Any]:
    out = []
    for name in NAMES:
        for arg in REG[name]:
            if KIND[name][arg] in LONG_KINDS and _long(REG[name][arg].value, 3) is not None:
                marks = [pytest.mark.xfail(strict=True, reason="pending")] if (name, arg) in PENDING_LENGTH else []
                out.append(pytest.param(name, arg, marks=marks, id=f"{name.removeprefix('fusion.')}-{arg}"))
    return out


def _names(exc: BaseException, arg: str) -> bool:
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(arg)}(?![A-Za-z0-9_])", str(exc)) is not None


@pytest.mark.parametrize(("name", "arg"), _pairs())
@settings(max_examples=2, deadline=None, phases=(Phase.explicit, Phase.generate))  # no shrinking: each call
@given(n=st.integers(10**5, 10**6))  # may run for seconds
def test_a_long_sequence_is_served_or_refused_at_once(name: str, arg: str, n: int) -> None:
    """Rule 17 counts the length of a sequence argument (or the sum of its sizes): ``n`` valid entries are served
    within seconds or refused within a second, by a ValueError or TypeError naming the argument (fuzz13 bug 1:
    10**6 seeds ran for minutes; each entry valid, only their number was too large)."""
    kwargs = _valid(name)
    kwargs[arg] = _long(REG[name][arg].value, n)
    t0 = time.perf_counter()
    how, out = FZ.run(CALLABLES[name], kwargs, 8.0)
    dt = time.perf_counter() - t0
    assert how != "timeout", f"{name}: {arg} of {n:,} entries still running after 8 s"
    if how == "raised":
        assert isinstance(out, (ValueError, TypeError)) and _names(out, arg), f"{name}: {arg}: {out!r:.200}"
        assert dt < 1.5, f"{name}: {arg} of {n:,} entries refused after {dt:.2f} s: {out!s:.120}"
    else:
        assert dt < 5.0, f"{name}: {arg} of {n:,} entries served after {dt:.2f} s"


def _self_containing(value: Any) -> list | None:
    """A list of ``value``'s first entries that contains itself (numpy's unnamed ragged-array error)."""
    flat = np.ravel(np.asarray(value, dtype=object))
    if not flat.size:
        return None
    out = list(flat[:2])
    out.append(out)
    return out


def _array_pairs() -> list[Any]:
    return [pytest.param(name, arg, id=f"{name.removeprefix('fusion.')}-{arg}") for name in NAMES for arg in REG[name]
            if KIND[name][arg] in ("array", "mask", "int_array", "int_seq", "seed_seq")]


@pytest.mark.parametrize(("name", "arg"), _array_pairs())
def test_a_list_containing_itself_is_refused_by_name(name: str, arg: str) -> None:
    """Any numpy conversion error of an array argument names it (fuzz13: ``delete_weights(mask=)`` gave numpy's
    "setting an array element with a sequence" without the argument's name)."""
    bad = _self_containing(REG[name][arg].value)
    if bad is None:
        return
    kwargs = _valid(name)
    kwargs[arg] = bad
    how, out = FZ.run(CALLABLES[name], kwargs, 10.0)
    assert how == "raised" and isinstance(out, (ValueError, TypeError)), f"{name}: {arg}: {how} {out!r:.200}"
    assert _names(out, arg), f"{name}: {arg}: {out!r:.200}"


def _list_pairs() -> list[Any]:
    return [pytest.param(name, arg, id=f"{name.removeprefix('fusion.')}-{arg}") for name in NAMES for arg in REG[name]
            if isinstance(REG[name][arg].value, (list, tuple)) and REG[name][arg].value
            and (name, arg) not in TUPLE_FIELDS]


#: Fields documented as a "tuple" of a frozen record (hashable): a tuple only (``fusion._validation.sequence``).
TUPLE_FIELDS: set[tuple[str, str]] = {
    ("fusion.book.recommend.Evidence", "expect"), ("fusion.book.recommend.Recommendation", "evidence"),
    ("fusion.book.recommend.Recommendation", "chapters"), ("fusion.scenarios.fusion_networks.NetworkScenario", "nodes")}


@pytest.mark.parametrize(("name", "arg"), _list_pairs())
def test_any_sequence_is_the_same_argument_as_its_list(name: str, arg: str) -> None:
    """One rule for sequences (``fusion._validation.sequence``): a ``UserList`` of a list or tuple argument's entries
    gives the result of the list itself (fuzz13: rngs, runs and seeds were refused unless a list or tuple)."""
    from collections import UserList

    from test_bad_input_properties import _base_result

    kwargs = _valid(name)
    kwargs[arg] = UserList(kwargs[arg])
    how, out = FZ.run(CALLABLES[name], kwargs, 30.0)
    assert how == "ok", f"{name}: {arg} as a UserList: {how} {out!r:.200}"
    assert not FZ.differs(_base_result(name), out), f"{name}: {arg}: {FZ.differs(_base_result(name), out)}"
