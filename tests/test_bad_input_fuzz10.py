"""The last bad-input classes of issue 35 (fuzz10's "debatable" outcomes, settled by rule), over the public API.

Rules 14-16 of :mod:`fusion._validation`, each a property over the registry of valid calls of
:mod:`tests.test_bad_input`:

* rule 14, *results own their data*: after a valid call, every input array is filled in place with a
  drawn value; every array the call returned (inside dataclasses, tuples, lists and dicts) is unchanged;
* rule 15, *an argument's own exception*: an object whose ``__float__``, ``__index__`` or ``__array__``
  raises (a drawn exception class) in place of a number, a count or an array is refused with a
  :class:`TypeError` naming the argument, chained to that exception;
* rule 16, *numeric dtypes only*: a structured, void or text array in place of a float array is refused
  with a :class:`TypeError` naming the argument.
"""

from __future__ import annotations

import copy
import dataclasses
import os
import inspect
import re
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import fusion._validation as V
from test_bad_input import CALLABLES, REG
from test_bad_input_properties import EXAMPLES, FEW, FZ, KIND, NAMES, _args, _names_for, _valid, check


def _private(kwargs: dict[str, Any]) -> dict[str, Any]:
    """The valid call's arguments with private copies of its arrays (and of the arrays inside its lists)."""
    out = {}
    for k, v in kwargs.items():
        if isinstance(v, np.ndarray):
            out[k] = v.copy()
        elif isinstance(v, list) and any(isinstance(e, np.ndarray) for e in v):
            out[k] = [e.copy() if isinstance(e, np.ndarray) else e for e in v]
        else:
            out[k] = v
    return out


def _fill(kwargs: dict[str, Any], value: float) -> int:
    """Fill every writable numeric input array in place with ``value``; how many were filled."""
    n = 0
    for v in kwargs.values():
        for a in (v if isinstance(v, list) else [v]):
            if isinstance(a, np.ndarray) and a.flags.writeable and a.dtype.kind in "fiu" and a.size:
                a.fill(value)
                n += 1
    return n


def _has_array(x: Any, depth: int = 0) -> bool:
    if isinstance(x, np.ndarray):
        return True
    if depth > 4:
        return False
    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        return any(_has_array(getattr(x, f.name), depth + 1) for f in dataclasses.fields(x))
    if isinstance(x, (tuple, list)):
        return any(_has_array(e, depth + 1) for e in x)
    if isinstance(x, dict):
        return any(_has_array(e, depth + 1) for e in x.values())
    return False


ARRAY_IN = [p for p in _names_for(("array", "int_array", "array_seq"), "own")
            if any(isinstance(s.value, np.ndarray) or (isinstance(s.value, list)
                                                       and any(isinstance(e, np.ndarray) for e in s.value))
                   for s in REG[p.values[0]].values())]


@pytest.mark.parametrize("name", ARRAY_IN)
@settings(FEW, max_examples=2)
@given(fill=st.sampled_from([0.0, 3.0, -7.5, 1e6]))
def test_results_own_their_data(name: str, fill: float) -> None:
    """Rule 14: filling the inputs in place after a valid call leaves every returned array as it was."""
    kwargs = _private(_valid(name))
    how, out = FZ.run(CALLABLES[name], kwargs, 60.0)
    assert how == "ok", f"{name}: the valid call failed: {out}"
    if not _has_array(out):
        return
    try:
        before = copy.deepcopy(out)
    except Exception:  # noqa: BLE001 (a result holding a generator or a figure: nothing to compare)
        return
    if _fill(kwargs, fill):
        where = FZ.differs(before, out)
        assert not where, f"{name}: the result changed when its inputs were filled with {fill} afterwards: {where}"


def test_a_validated_float_array_is_a_private_copy() -> None:
    """Rule 14 at its source: the shared conversion never returns the caller's buffer, and copies only once."""
    import pandas as pd

    for x in (np.arange(4.0), np.arange(8.0)[::2], np.asfortranarray(np.eye(3)), pd.Series([1.0, 2.0]),
              memoryview(np.arange(3.0))):
        got = V.as_array(x, "x")
        assert not np.shares_memory(got, np.asarray(x))
        np.testing.assert_array_equal(got, np.asarray(x))
    lst = [1.0, 2.0]
    assert V.as_array(lst, "x").flags.owndata


class _Raises:
    """A number-like object whose conversion (``float``, ``operator.index``) raises ``exc``, its own exception."""

    def __init__(self, exc: BaseException) -> None:
        self.exc = exc

    def __float__(self) -> float:
        raise self.exc

    def __index__(self) -> int:
        raise self.exc

    def __repr__(self) -> str:
        return f"{type(self).__name__}({type(self.exc).__name__})"


class _ArrayRaises(_Raises):
    """An array-like object whose ``__array__`` raises ``exc``."""

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        raise self.exc


class _OwnError(Exception):
    pass


EXCEPTIONS = st.sampled_from([RuntimeError("own"), ZeroDivisionError("own"), KeyError("own"), _OwnError("own"),
                              ArithmeticError("own"), LookupError("own")])


@pytest.mark.parametrize("name", _names_for(("array", "real", "count", "index", "seed"), "own-exception"))
@settings(FEW, max_examples=int(os.environ.get("OWN_EXCEPTION_EXAMPLES", EXAMPLES)))
@given(data=st.data(), exc=EXCEPTIONS, how=st.sampled_from(["float", "array", "entry"]))
def test_an_arguments_own_exception_is_a_named_type_error(name: str, data: st.DataObject, exc: BaseException,
                                                          how: str) -> None:
    """Rule 15: an argument that raises while converted is refused with a TypeError naming it, chained."""
    arg = data.draw(st.sampled_from(_args(name, ("array", "real", "count", "index", "seed"))))
    bad: Any = (_ArrayRaises if how == "array" else _Raises)(exc)
    if how == "entry":  # inside a list of numbers
        bad = [bad, 1.0]
    kwargs = _valid(name)
    kwargs[arg] = bad
    got, out = FZ.run(CALLABLES[name], kwargs, 20.0)
    assert got == "raised", f"{name}: {arg} = {bad!r} accepted: {out!r:.80}"
    assert isinstance(out, TypeError), f"{name}: {arg} = {bad!r}: {type(out).__name__}: {out}"
    assert re.search(rf"(?<![A-Za-z0-9_]){re.escape(arg)}(?![A-Za-z0-9_])", str(out)), f"{name}: {out}"
    if "raised" in str(out):  # converted and raised: the argument's own exception is the cause
        assert out.__cause__ is exc, f"{name}: {arg}: not chained to the argument's exception: {out!r}"


def test_the_shared_conversions_chain_the_arguments_own_exception() -> None:
    """Rule 15 at its source: scalar, count and array conversions."""
    e = RuntimeError("boom")
    for call in (lambda: V.scalar(_Raises(e), "x"), lambda: V.positive_scalar(_Raises(e), "x"),
                 lambda: V.as_array(_ArrayRaises(e), "x"), lambda: V.as_array([_Raises(e)], "x"),
                 lambda: V.as_array(np.array([_Raises(e)], dtype=object), "x"), lambda: V.count(_Raises(e), "n")):
        with pytest.raises(TypeError, match=r"^(x|n) could not be converted") as info:
            call()
        assert info.value.__cause__ is e


def _dtype_values(v: np.ndarray) -> dict[str, np.ndarray]:
    one = np.zeros(v.shape, dtype=[("x", "f8")])
    one["x"] = v
    two = np.zeros(v.shape, dtype=[("x", "f8"), ("y", "f8")])
    two["x"] = v
    return {"one-field": one, "two-field": two, "void": np.zeros(v.shape, dtype="V8"),
            "text": v.astype(str)}


@pytest.mark.parametrize("name", _names_for(("array",), "dtype"))
@FEW
@given(data=st.data(), kind=st.sampled_from(["one-field", "two-field", "void", "text"]))
def test_arrays_without_a_numeric_dtype_are_refused(name: str, data: st.DataObject, kind: str) -> None:
    """Rule 16: a structured, void or text array in place of a float array: a TypeError naming the argument."""
    args = [a for a in _args(name, ("array",)) if isinstance(REG[name][a].value, np.ndarray)
            and REG[name][a].value.dtype.kind == "f"]
    if not args:
        return
    arg = data.draw(st.sampled_from(args))
    bad = _dtype_values(np.array(REG[name][arg].value, dtype=float))[kind]
    check(name, arg, bad, strict=True)
    kwargs = _valid(name)
    kwargs[arg] = bad
    _, out = FZ.run(CALLABLES[name], kwargs, 20.0)
    assert isinstance(out, TypeError), f"{name}: {arg} as a {kind} array: {type(out).__name__}: {out}"


@given(n=st.integers(1, 5))
def test_structured_arrays_are_refused_by_the_shared_validator(n: int) -> None:
    """Rule 16 at its source, for each validator built on the shared conversion."""
    one = np.zeros(n, dtype=[("x", "f8")])
    for call in (lambda: V.as_array(one, "x"), lambda: V.as_readings(one, "x"), lambda: V.as_state(one, "x"),
                 lambda: V.as_covariance(np.zeros((n, n), dtype=[("x", "f8")]), name="x")):
        with pytest.raises(TypeError, match=r"^x must be numeric, got an array of dtype"):
            call()


# --------------------------------------------------------------------------------------------
# fuzz10's two lenient single functions, settled
# --------------------------------------------------------------------------------------------


@given(theta=st.floats(0.0, np.pi), w=st.floats(1e-3, 1e3), d=st.integers(2, 4))
def test_best_ridge_k_refuses_a_rank_deficient_information_matrix(theta: float, w: float, d: int) -> None:
    """A = V diag(0, w, ..., w) V^T: rounding leaves the zero eigenvalue near +-1e-17; refused naming A (by the
    positive-definite check or by the condition number beyond 1/(d eps))."""
    from fusion.readings.biased import best_ridge_k

    c, s = np.cos(theta), np.sin(theta)
    V_ = np.eye(d)
    V_[:2, :2] = [[c, -s], [s, c]]
    A = V_ @ np.diag([0.0] + [w] * (d - 1)) @ V_.T
    with pytest.raises(ValueError, match=r"^A (is numerically singular|must be positive definite)"):
        best_ridge_k(0.5 * (A + A.T), np.arange(1.0, d + 1))


@given(w=st.floats(1e-3, 1e3), d=st.integers(1, 4), inside=st.booleans())
def test_best_ridge_k_accepts_a_condition_number_just_inside_the_limit(w: float, d: int, inside: bool) -> None:
    """The documented threshold, exactly: cond(A) = 1/(2 d eps) is accepted (a finite k and MSE), 2/(d eps) refused."""
    from fusion.readings.biased import MAX_RIDGE_CONDITION, best_ridge_k

    cond = MAX_RIDGE_CONDITION / d * (0.5 if inside else 2.0)
    A = np.diag([w / cond] + [w] * (d - 1)) if d > 1 else np.array([[w]])
    x = np.arange(1.0, d + 1)
    if inside or d == 1:  # a 1x1 matrix has condition number 1
        k, mse = best_ridge_k(A, x)
        assert np.isfinite(k) and k > 0 and np.isfinite(mse) and mse > 0
    else:
        with pytest.raises(ValueError, match=r"^A is numerically singular"):
            best_ridge_k(A, x)


@settings(max_examples=30)
@given(e=st.integers(-1000, 1000), seed=st.integers(0, 2**32 - 1))
def test_hill_tail_index_reads_any_magnitude(e: int, seed: int) -> None:
    """hill_tail_index is documented for finite values of any magnitude (it reads logarithms of ratios), so it does
    not apply the 1e150 cap of rule 2: it is invariant under x -> 2**e x, and an entry at nextafter(1e150, inf)
    gives the estimate of the data it is in (fuzz9/fuzz10's 0.029: a heavy tail, which that entry makes), the
    closed form in logarithms."""
    from fusion.book.rulebook import hill_tail_index

    x = np.random.default_rng(seed).normal(size=100)
    s = 2.0**e
    assert hill_tail_index(x * s) == hill_tail_index(x)
    y = x.copy()
    y[0] = np.nextafter(1e150, np.inf)
    v = np.sort(np.log(np.abs(y)))[::-1]
    k = 10
    assert hill_tail_index(y) == pytest.approx(1.0 / np.mean(v[:k] - v[k]), rel=1e-12)


# --------------------------------------------------------------------------------------------
# rule 17: the work budget
# --------------------------------------------------------------------------------------------


def _work_cases() -> dict[str, tuple[Any, str]]:
    """Calls whose work, a product of counts each within its ceiling (and of arrays within the memory budget), is
    ``over`` times :data:`MAX_WORK`: (call given ``over``, the names of the message)."""
    from fusion.optimise.swarm import particle_swarm, particle_swarm_batch
    from fusion.scenarios import infrared_radar as ir
    from fusion.scenarios import two_sensor as ts
    from fusion.scenarios.lecture_weighting import estimators as E

    R = np.eye(2)
    Q = np.diag([0.0, 1.0, 0.0, 1.0])
    W = V.MAX_WORK

    def fit(x: np.ndarray) -> np.ndarray:
        return np.sum(x * x, axis=1)

    def sq(over: float, per: float = 1.0) -> int:  # n with n * n * per > over * W
        return int(np.ceil((over * W / per) ** 0.5)) + 1

    return {
        "lumv_study": (lambda o: E.lumv_study(k=100, runs=2 * int(np.ceil(o * W / 800)) + 2), "runs, k and sigma"),
        "tail_study": (lambda o: E.tail_study(k=100, runs=int(np.ceil(o * W / 400)) + 1), "runs, k and sigma"),
        "q_scaling_study": (lambda o: ts.q_scaling_study(np.random.default_rng(0), R, R, Q,
                                                         # distinct scales (a repeat is refused first: fuzz 30b)
                                                         tuple(1.0 + 1e-3 * np.arange(int(np.ceil(o * W / (2000 * 53))))),
                                                         runs=1000, nees_runs=1000, T=1.0),
                            "scales, runs, nees_runs and T"),
        "infrared_radar.simulate": (lambda o: ir.simulate(np.random.default_rng(0), runs=sq(o), T=0.01,
                                                          duration=sq(o) / 100), "runs, T and duration"),
        "particle_swarm": (lambda o: particle_swarm(fit, 2, np.random.default_rng(0), n_particles=sq(o, 2),
                                                    iterations=sq(o, 2)), "n_particles, iterations and dim"),
        "particle_swarm_batch": (lambda o: particle_swarm_batch(lambda a, x: np.sum(x * x, axis=1), 2,
                                                                [np.random.default_rng(k) for k in range(2)], n_particles=sq(o, 4),
                                                                iterations=sq(o, 4)),
                                 "rngs, n_particles, iterations and dim"),
    }


@pytest.mark.parametrize("case", sorted(_work_cases()))
@settings(max_examples=5, deadline=None)
@given(over=st.floats(1.01, 3.9))
def test_a_request_beyond_the_work_budget_is_refused_at_once_by_name(case: str, over: float) -> None:
    """Rule 17: counts each within their ceilings whose product exceeds MAX_WORK: a ValueError naming the counts
    and the budget, before any work (well under a second), never minutes of computing."""
    import time

    call, names = _work_cases()[case]
    t0 = time.perf_counter()
    with pytest.raises(ValueError, match=rf"^{re.escape(names)} ask for .* beyond the work budget"):
        call(over)
    assert time.perf_counter() - t0 < 5.0


@given(shape=st.lists(st.integers(1, 10**6), min_size=1, max_size=4))
def test_the_work_budget_is_the_product_of_the_counts(shape: list[int]) -> None:
    """work() returns the product within the budget and refuses it beyond, naming the arguments."""
    n = int(np.prod(np.array(shape, dtype=object)))
    if n <= V.MAX_WORK:
        assert V.work(tuple(shape), "a and b") == n
    else:
        with pytest.raises(ValueError, match=r"^a and b ask for .* beyond the work budget"):
            V.work(tuple(shape), "a and b")


# --------------------------------------------------------------------------------------------
# fuzz11's classes: durations for integers and numbers, low-precision simplex weights, misspelt **options
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", _names_for(("real", "count", "index", "seed"), "duration"))
@FEW
@given(data=st.data(), value=st.integers(0, 5), unit=st.sampled_from(["s", "ms", "D"]),
       kind=st.sampled_from(["timedelta64", "datetime64", "0-d timedelta array"]))
def test_durations_are_refused_where_a_number_or_an_integer_is_expected(name: str, data: st.DataObject, value: int,
                                                                       unit: str, kind: str) -> None:
    """np.timedelta64 is a numpy integer subclass: every integer and number check refuses it (and datetime64) with a
    TypeError naming the argument, never an IndexError or an unnamed int() error (fuzz11 bugs 5-6)."""
    arg = data.draw(st.sampled_from(_args(name, ("real", "count", "index", "seed"))))
    bad = {"timedelta64": np.timedelta64(value, unit), "datetime64": np.datetime64(value, unit),
           "0-d timedelta array": np.array(value, dtype=f"m8[{unit}]")}[kind]
    check(name, arg, bad, strict=True)
    kwargs = _valid(name)
    kwargs[arg] = bad
    how, out = FZ.run(CALLABLES[name], kwargs, 20.0)
    assert how == "raised" and isinstance(out, TypeError), f"{name}: {arg} = {bad!r}: {out!r:.120}"


@given(n=st.integers(2, 30), dtype=st.sampled_from([np.float16, np.float32]), seed=st.integers(0, 2**32 - 1))
def test_simplex_weights_summing_to_one_in_their_own_precision_are_accepted(n: int, dtype: type,
                                                                            seed: int) -> None:
    """Weights normalised in float32 or float16 (0.4f + 0.6f = 1 + 3e-8 in float64) are on the simplex in the
    caller's precision: accepted, and used divided by their sum in float64 (fuzz 28a D1); weights off by more than
    2 n eps are refused."""
    from fusion.filtering.particles import effective_sample_size
    from fusion.optimise.simplex import check_simplex

    w = np.random.default_rng(seed).dirichlet(np.ones(n))
    low = (w / w.sum()).astype(dtype)
    if not low.sum(dtype=np.float64) > 0 or np.any(low < 0):
        return
    np.testing.assert_array_equal(check_simplex(low, n), low.astype(float) / low.astype(float).sum())
    assert 1.0 <= effective_sample_size(low) <= n + 1e-9
    off = low.copy()
    off[0] += dtype(0.1)
    with pytest.raises(ValueError, match=r"^eps must lie on the simplex"):
        check_simplex(off, n)
    np.testing.assert_array_equal(check_simplex(w / w.sum(), n), np.clip(w / w.sum(), 0.0, None))  # float64: as is


@given(key=st.text(alphabet="abcdefghijklmnopqrstuvwxyz_", min_size=1, max_size=12),
       method=st.sampled_from(["mean", "optimal_fusion_set", "fusion_set_weights", "support_degree"]))
def test_a_misspelt_option_keyword_is_a_type_error(key: str, method: str) -> None:
    """fuse_epochs(**options): a keyword that no method takes is Python's TypeError for an unexpected keyword,
    naming it; an option of another method is a ValueError naming it (fuzz11's kwtypo class)."""
    from fusion.readings.fusion_set import METHODS, fuse_epochs

    known = {k for _, names in METHODS.values() for k in names}
    x = [[1.0, 2.0, 3.0]]
    if key in inspect.signature(fuse_epochs).parameters:   # x or method given twice: Python's TypeError names it
        with pytest.raises(TypeError, match=rf"multiple values for argument '{key}'"):
            fuse_epochs(x, method, **{key: 1.0})
        return
    if key in known:
        if key not in METHODS[method][1]:
            with pytest.raises(ValueError, match=re.escape(repr([key]))):
                fuse_epochs(x, method, **{key: 1.0})
        return
    with pytest.raises(TypeError, match=r"^fuse_epochs got unexpected keyword argument\(s\) " + re.escape(repr([key]))):
        fuse_epochs(x, method, **{key: 1.0})
