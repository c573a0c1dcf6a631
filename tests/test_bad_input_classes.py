"""Property tests of the nine classes of bad input of issue 35, over the whole public API.

Each class is one rule of the shared validation (:mod:`fusion._validation`, or the module the rule
belongs to). Hypothesis draws a public callable and one of its arguments from the registry of valid
example calls of :mod:`tests.test_bad_input` (which covers every public callable outside the book's
presentation helpers), replaces that argument by an input of the class, and checks the outcome:

* strict classes (the input is bad whatever the function): the call raises ``ValueError`` or
  ``TypeError`` whose message names the argument;
* classes whose input may be valid for some functions (tiny or huge values, degenerate systems,
  large counts): the call either returns a finite result or raises ``ValueError``/``TypeError``
  naming the argument. Never NaN/inf in the result, never another exception.

The issue's named cases are tested too (at the end), so that each class has a test that fails on the
code before the fix.
"""

from __future__ import annotations

import copy
import inspect
import re
import time
import warnings
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import fusion._validation as V
from _helpers import bounded, parsed
from test_bad_input import CALLABLES, REG, _excluded, _finite

# --------------------------------------------------------------------------------------------
# the arguments of the registry, by kind
# --------------------------------------------------------------------------------------------

#: Callables left out of the property tests: the book's presentation helpers (documented in
#: test_bad_input) and the slow Monte-Carlo studies of the range-bearing network (seconds per call:
#: their arguments are the scenario objects validated by the constructors, which are included).
SLOW = ("fusion.scenarios.range_bearing.monte_carlo", "fusion.scenarios.range_bearing.run_tracking",
        "fusion.scenarios.range_bearing.run_tracking_batch", "fusion.scenarios.fusion_networks.run_network_study")
NAMES = sorted(n for n in REG if not _excluded(n) and not n.startswith("fusion.book.") and n not in SLOW)


def _is_float_array(v: Any) -> bool:
    if isinstance(v, np.ndarray):
        return v.dtype.kind == "f" and v.size > 0
    return isinstance(v, tuple) and len(v) > 0 and all(isinstance(e, float) for e in v)


def _is_number(v: Any) -> bool:
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, (bool, np.bool_))


def _args(pred: Callable[[str, str, Any, tuple[str, ...]], bool]) -> list[tuple[str, str]]:
    return [(n, a) for n in NAMES for a, spec in REG[n].items() if pred(n, a, spec.value, spec.mutations)]


#: Float arrays whose NaN is refused (validated, finite arrays).
ARRAYS = _args(lambda n, a, v, m: _is_float_array(v) and "nan" in m)
#: Real scalars whose NaN is refused.
SCALARS = _args(lambda n, a, v, m: _is_number(v) and "nan_s" in m)
#: Integer counts (sizes, iterations, seeds, indices).
COUNTS = _args(lambda n, a, v, m: _is_number(v) and "frac" in m)
#: Callable arguments (objectives, registrars).
OBJECTIVES = _args(lambda n, a, v, m: callable(v) and not isinstance(v, type) and "str" in m
                   and not isinstance(v, np.random.Generator))
#: Every argument that has some value (for the type class).
EVERY = _args(lambda n, a, v, m: True)


def _default_is_none(name: str, arg: str) -> bool:
    try:
        return inspect.signature(CALLABLES[name]).parameters[arg].default is None
    except (KeyError, ValueError, TypeError):
        return False


def call(name: str, arg: str, value: Any, seconds: int = 60, fresh: bool = False) -> tuple[str, Any]:
    """Call ``name`` with the registry's valid arguments and ``arg`` replaced; ('ok', result) or ('raised', exc).

    A generator argument is a fresh ``default_rng(0)``; with ``fresh``, every other argument is a deep copy too (a
    list of generators, a callable with state), so that two calls that must agree start from the same state."""
    kwargs = {k: (np.random.default_rng(0) if isinstance(a.value, np.random.Generator)
                  else copy.deepcopy(a.value) if fresh else a.value) for k, a in REG[name].items()}
    kwargs[arg] = value

    def quiet() -> Any:
        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore")
            return CALLABLES[name](**kwargs)

    return bounded(quiet, seconds, f"{name}({arg}=...) ran for more than {seconds} s")


def _names(exc: BaseException, arg: str) -> bool:
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(arg)}(?![A-Za-z0-9_])", str(exc)) is not None


def assert_refused(name: str, arg: str, value: Any, types: tuple[type, ...] = (ValueError, TypeError),
                   names: tuple[str, ...] | None = None) -> BaseException:
    """The call must raise one of ``types`` naming ``arg`` (or one of ``names``)."""
    how, out = call(name, arg, value)
    assert how == "raised", f"{name}: {arg} = {value!r:.80} accepted (result finite: {_finite(out)})"
    assert isinstance(out, types), f"{name}: {arg}: {type(out).__name__}: {out}"
    assert any(_names(out, n) for n in (names or (arg,))), f"{name}: {arg}: message does not name it: {out}"
    return out


def assert_finite_or_refused(name: str, arg: str, value: Any, names: tuple[str, ...] | None = None) -> None:
    """A finite result, or ValueError/TypeError naming ``arg``: never NaN, never another exception."""
    how, out = call(name, arg, value)
    if how == "ok":
        assert _finite(out), f"{name}: {arg} = {value!r:.80} gave a non-finite result"
        return
    assert isinstance(out, (ValueError, TypeError)), f"{name}: {arg}: {type(out).__name__}: {out}"
    assert any(_names(out, n) for n in (names or (arg,))), f"{name}: {arg}: message does not name it: {out}"


def test_the_registry_has_arguments_of_every_kind() -> None:
    """The strategies below draw from these lists: each must be large enough to mean something."""
    assert len(NAMES) > 200
    assert len(ARRAYS) > 150 and len(SCALARS) > 150 and len(COUNTS) > 100 and len(OBJECTIVES) >= 8


# --------------------------------------------------------------------------------------------
# class 1: complex numbers are refused (TypeError naming the argument), never cast to their real part
# --------------------------------------------------------------------------------------------


@given(st.sampled_from(ARRAYS + SCALARS + COUNTS), st.floats(-10.0, 10.0, allow_nan=False), st.booleans())
def test_class1_complex_is_refused(target: tuple[str, str], imag: float, numpy_type: bool) -> None:
    name, arg = target
    v = REG[name][arg].value
    if _is_number(v):
        bad = np.complex128(complex(v, imag)) if numpy_type else complex(v, imag)
    else:
        a = np.asarray(v, dtype=float)
        bad = a + 1j * imag  # imag = 0 too: a complex array is refused whatever its imaginary part
        if not numpy_type:
            bad = bad.tolist() if a.ndim else complex(bad)
    exc = assert_refused(name, arg, bad)
    assert "complex" in str(exc) or "real" in str(exc) or isinstance(exc, TypeError), exc


# --------------------------------------------------------------------------------------------
# class 2: subnormal and huge finite values: refused by name or a finite result, never NaN
# --------------------------------------------------------------------------------------------

SUBNORMAL = st.floats(min_value=5e-324, max_value=2.2e-308, allow_subnormal=True)
HUGE = st.floats(min_value=1.01e150, max_value=1.79e308)


@given(st.sampled_from(ARRAYS), st.one_of(SUBNORMAL, HUGE), st.booleans())
def test_class2_extreme_array_entries(target: tuple[str, str], x: float, whole: bool) -> None:
    name, arg = target
    a = np.array(REG[name][arg].value, dtype=float, copy=True)
    if whole:  # every entry scaled to the extreme (subnormal or huge) magnitude
        a = np.where(a != 0, np.sign(a) * x, x)
    else:  # one entry
        a.flat[a.size // 2] = x
    value = tuple(a.tolist()) if isinstance(REG[name][arg].value, tuple) else a
    assert_finite_or_refused(name, arg, value)


@given(st.sampled_from(SCALARS), st.one_of(SUBNORMAL, HUGE), st.booleans())
def test_class2_extreme_scalars(target: tuple[str, str], x: float, negative: bool) -> None:
    name, arg = target
    assert_finite_or_refused(name, arg, -x if negative else x)


@given(st.sampled_from(SCALARS), st.one_of(SUBNORMAL, HUGE))
def test_class2_extreme_scalars_are_refused_by_the_shared_rule(target: tuple[str, str], x: float) -> None:
    """Every real scalar goes through one rule: beyond 1e150 or subnormal is refused by name."""
    name, arg = target
    assert_refused(name, arg, x)


@pytest.mark.parametrize("variances", [[1e-310, 2e-310, 4e-310], [1e200, 2e200, 4e200], [5e-324, 1.0, 2.0]])
def test_class2_the_issues_weights_and_variances(variances: list[float]) -> None:
    from fusion.readings import weighting as w

    with pytest.raises(ValueError, match="variances"):
        w.optimal_weights(variances)
    with pytest.raises(ValueError, match="estimates"):
        w.inverse_variance_weights(np.array([variances]))
    X = np.outer(np.ones(6), variances) * np.array([[1.0], [2.0], [0.5], [1.5], [1.0], [3.0]])
    with pytest.raises(ValueError, match="X"):
        w.running_variances(X)
    with pytest.raises(ValueError, match="Y"):
        w.learned_variances(X)


def test_class2_degenerate_valid_scales_still_work() -> None:
    """The rule's range is wide: the documented extreme-scale behaviour (1e-12, 1e12) is unchanged."""
    from fusion.estimates.ci import ci_weight
    from fusion.readings.weighting import optimal_weights

    np.testing.assert_allclose(optimal_weights(np.array([1.0, 2.0, 4.0]) * 1e-100), optimal_weights([1.0, 2.0, 4.0]))
    P1 = np.array([[2.0, 0.3], [0.3, 1.0]])
    P2 = np.array([[1.0, -0.2], [-0.2, 3.0]])
    assert ci_weight(1e-140 * P1, 1e-140 * P2) == pytest.approx(ci_weight(P1, P2), abs=1e-9)


# --------------------------------------------------------------------------------------------
# class 3: objectives returning NaN, non-numbers, or infinite everywhere
# --------------------------------------------------------------------------------------------


def _objective(kind: str) -> Callable[..., Any]:
    def f(*args: Any, **_: Any) -> Any:
        x = np.asarray(args[-1], dtype=float)
        shape = x.shape[:-1] if x.ndim > 1 else x.shape
        if kind == "str":
            return "abc"
        if kind == "complex":
            return np.full(shape, 1.0 + 1.0j) if shape else 1.0 + 1.0j
        value = {"nan": np.nan, "inf": np.inf, "-inf": -np.inf}[kind]
        return np.full(shape, value) if shape else value
    return f


@given(st.sampled_from(OBJECTIVES), st.sampled_from(["nan", "inf", "-inf", "str", "complex"]))
def test_class3_bad_objectives(target: tuple[str, str], kind: str) -> None:
    name, arg = target
    assert_refused(name, arg, _objective(kind))


def test_class3_fruit_fly_refuses_an_objective_infinite_everywhere() -> None:
    from fusion.optimise import fruit_fly, grid_search

    with pytest.raises(ValueError, match=r"\bf\b.*no finite value"):
        fruit_fly(lambda w: np.inf, np.random.default_rng(0), population=5, iterations=5)
    with pytest.raises(ValueError, match=r"\bf returned NaN"):
        grid_search(lambda w: np.nan, n=5)
    # an objective infinite at some points only is valid: the finite minimum wins
    r = grid_search(lambda w: np.inf if w < 0.5 else (w - 0.7) ** 2, n=11)
    assert r.x == pytest.approx(0.7)


# --------------------------------------------------------------------------------------------
# class 4: mismatched companions (another simulation's tracks, a non-diagonal R, windows)
# --------------------------------------------------------------------------------------------

DIAGONAL_R = _args(lambda n, a, v, m: n.startswith("fusion.scenarios.two_sensor.") and a in ("R1", "R2", "R_a", "R_b"))


@given(st.sampled_from(DIAGONAL_R), st.floats(0.05, 0.9))
def test_class4_a_non_diagonal_R_is_refused_where_only_its_diagonal_is_used(target: tuple[str, str], rho: float) -> None:
    name, arg = target
    R = np.array(REG[name][arg].value, dtype=float)
    c = rho * np.sqrt(R[0, 0] * R[1, 1])
    assert_refused(name, arg, R + np.array([[0.0, c], [c, 0.0]]))


def test_class4_tracks_of_another_simulation_are_refused() -> None:
    from fusion.scenarios import infrared_radar as ir

    sim = ir.simulate(np.random.default_rng(2), runs=2, duration=0.5)
    tracks = ir.cartesian_tracks(sim)
    ir.cartesian_errors(sim, tracks, rules=(ir.IrMethod.SPLIT_CI,))  # its own simulation: fine
    for other in (ir.simulate(np.random.default_rng(3), runs=2, duration=0.5),  # other draws
                  ir.simulate(np.random.default_rng(2), runs=3, duration=0.5),  # other runs
                  ir.simulate(np.random.default_rng(2), runs=2, duration=0.6)):  # other scans
        with pytest.raises(ValueError, match="tracks"):
            ir.cartesian_errors(other, tracks)


WINDOWS = _args(lambda n, a, v, m: a in ("window", "samples") and isinstance(v, tuple) and len(v) == 2)


@given(st.sampled_from(WINDOWS), st.integers(-5, 10**6), st.integers(-5, 10**6))
def test_class4_windows_out_of_range_or_reversed(target: tuple[str, str], lo: int, hi: int) -> None:
    name, arg = target
    assert_finite_or_refused(name, arg, (lo, hi))
    if lo > hi:  # reversed: never a silent empty window
        assert_refused(name, arg, (lo, hi))


# --------------------------------------------------------------------------------------------
# class 5: singular systems and overflow: ValueError naming the argument, not LinAlgError
# --------------------------------------------------------------------------------------------

MATRICES = [(n, a) for n, a in ARRAYS if np.ndim(REG[n][a].value) == 2 and np.shape(REG[n][a].value)[1] >= 2]


@given(st.sampled_from(MATRICES), st.sampled_from(["dupcol", "zerocol", "zeros", "rank1"]))
def test_class5_rank_deficient_matrices(target: tuple[str, str], how: str) -> None:
    name, arg = target
    a = np.array(REG[name][arg].value, dtype=float, copy=True)
    if how == "dupcol":
        a[..., -1] = a[..., 0]
    elif how == "zerocol":
        a[..., -1] = 0.0
    elif how == "zeros":
        a[...] = 0.0
    else:
        a = np.outer(a[:, 0], a[0]) if a.ndim == 2 else a
    assert_finite_or_refused(name, arg, a)


#: Standard deviations that must be positive (zero refused): a filter divides by their square.
STDS = [(n, a) for n, a in SCALARS if re.fullmatch(r"sigma\w*|\w*_sigma|\w*sd\w*", a) and "zero" in REG[n][a].mutations]


@given(st.sampled_from(STDS), st.floats(min_value=1e-300, max_value=1e-155))
def test_class5_a_standard_deviation_whose_square_underflows(target: tuple[str, str], s: float) -> None:
    name, arg = target
    assert_refused(name, arg, s)


def test_class5_the_issues_singular_systems() -> None:
    from fusion.readings import biased as b
    from fusion.readings import weighting as w
    from fusion.registration import methods as m
    from fusion.scenarios import two_sensor as ts

    H = np.array([[1.0, 2.0], [2.0, 4.0], [3.0, 6.0]])
    y = np.array([1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=r"\bH\b"):
        w.wls(np.column_stack([np.ones(4), np.ones(4)]), np.eye(4), np.ones(4))
    with pytest.raises(ValueError, match=r"\bH\b"):
        b.ridge(H, y, 0.0)
    with pytest.raises(ValueError, match="Hs"):
        b.ridge_centralised([H, H], [np.eye(3)] * 2, [y, y], 0.0)
    with pytest.raises(ValueError, match="sigma"):
        ts.pcrb_steady(1.0, 1e140, np.eye(4))
    with pytest.raises(ValueError, match="sigma"):
        m.kalman_filter(np.arange(10.0), np.arange(10.0), 1e-300)
    with pytest.raises(ValueError, match="sigma"):
        m.kalman_runs(np.arange(10.0), np.arange(10.0)[None], 1e-300)


# --------------------------------------------------------------------------------------------
# class 6: wrong types, unknown keys, bad indices: TypeError/ValueError naming the argument
# --------------------------------------------------------------------------------------------

WRONG_TYPES = {"none": None, "bool": True, "str": "abc", "bytes": b"abc", "dict": {"a": 1}, "list_of_str": ["abc"],
               "object": object()}


@given(st.sampled_from(EVERY), st.sampled_from(sorted(WRONG_TYPES)))
def test_class6_wrong_types(target: tuple[str, str], kind: str) -> None:
    name, arg = target
    v = REG[name][arg].value
    bad = WRONG_TYPES[kind]
    if kind == "none" and _default_is_none(name, arg):
        return  # documented default
    if kind == "bool" and isinstance(v, (bool, np.bool_)):
        return
    if isinstance(v, (list, tuple)) and kind == "list_of_str" and v and isinstance(v[0], str):
        return  # a list of names: ["abc"] is an unknown name (class 8 of test_bad_input)
    assert_finite_or_refused(name, arg, bad)
    if _is_number(v) or _is_float_array(v):
        assert_refused(name, arg, bad)  # a number or an array: any of these is a wrong type


OPTION_DICTS = _args(lambda n, a, v, m: a == "swarm_options")


@given(st.sampled_from(OPTION_DICTS), st.sampled_from(["dict", "list", "int"]))
def test_class6_swarm_options(target: tuple[str, str], kind: str) -> None:
    """``swarm_options`` takes a SwarmOptions (or None): the old options dict, a list or a number is refused."""
    name, arg = target
    bad = {"dict": {"iterations": 3}, "list": [1, 2], "int": 3}[kind]
    assert_refused(name, arg, bad)


INDICES = _args(lambda n, a, v, m: "big" in m)


@given(st.sampled_from(INDICES), st.one_of(st.integers(-10**6, -1), st.integers(50, 10**6), st.just(2.5)))
def test_class6_indices_out_of_range(target: tuple[str, str], i: int | float) -> None:
    name, arg = target
    if arg == "axis" and isinstance(i, int) and i < 0 and i >= -np.ndim(REG[name]["Z"].value if "Z" in REG[name] else 0):
        return  # a negative axis within the array's dimensions is valid (numpy convention)
    assert_refused(name, arg, i)


# --------------------------------------------------------------------------------------------
# class 7: chapter 05's path helpers validate their start point and legs
# --------------------------------------------------------------------------------------------

NUMBER = st.one_of(st.floats(-1e3, 1e3), st.sampled_from([np.nan, np.inf, -np.inf, 1e200]))


@given(st.lists(NUMBER, min_size=0, max_size=4))
def test_class7_start_point(start: list[float]) -> None:
    from fusion.scenarios.two_sensor import trajectory

    ok = len(start) == 2 and all(np.isfinite(s) and abs(s) <= 1e150 for s in start)
    if ok:
        assert np.all(np.isfinite(trajectory(T=5.0, start=tuple(start)).states))
    else:
        with pytest.raises(ValueError, match="start"):
            trajectory(T=5.0, start=tuple(start))


@given(st.lists(st.one_of(st.floats(-50.0, 150.0), st.sampled_from([np.nan, np.inf, 1e200])), min_size=0, max_size=4),
       st.sampled_from(["trajectory", "straight_leg_floor"]))
def test_class7_legs(legs: list[float], helper: str) -> None:
    from fusion.scenarios import two_sensor as ts

    def run() -> Any:
        if helper == "trajectory":
            return ts.trajectory(T=5.0, legs=tuple(legs)).states
        return ts.straight_leg_floor(5.0, 150.0, legs=tuple(legs))[2]

    ok = len(legs) == 3 and all(np.isfinite(x) and 0.0 <= x <= 1e6 for x in legs)
    if ok:
        assert np.all(np.isfinite(run()))
    else:
        with pytest.raises(ValueError, match="legs"):
            run()


@pytest.mark.parametrize("bad", ["ab", None, {"a": 1}, (1j, 0.0)])
def test_class7_start_and_legs_of_the_wrong_type(bad: Any) -> None:
    from fusion.scenarios.two_sensor import straight_leg_floor, trajectory

    with pytest.raises(TypeError, match="start"):
        trajectory(start=bad)
    with pytest.raises(TypeError, match="legs"):
        trajectory(legs=bad)
    with pytest.raises(TypeError, match="legs"):
        straight_leg_floor(5.0, 150.0, legs=bad)


# --------------------------------------------------------------------------------------------
# class 8: documented constraints are enforced
# --------------------------------------------------------------------------------------------


def _documented_bounds(fn: Callable[..., Any]) -> dict[str, list[float]]:
    """Values violating the constraints a numpydoc parameter entry states ("> 0", ">= 0", "[0, 1]")."""
    doc = inspect.getdoc(fn) or ""
    if inspect.isclass(fn):
        doc += "\n" + (inspect.getdoc(fn.__init__) or "")
    out: dict[str, list[float]] = {}
    for m in re.finditer(r"^(\w+) : ([^\n]*)\n((?:    [^\n]*\n?)*)", doc, flags=re.M):
        name, head, body = m.group(1), m.group(2), m.group(3)
        text = " ".join((head + " " + body).split())
        bad: list[float] = []
        if re.search(r"(?:^|[\s(,])>\s*0(?![.\d])", text) or re.search(r"\bfloat > 0\b|\bpositive\b(?![- ]?(?:semi|def))", text):
            bad += [0.0, -1.0]
        elif re.search(r">=\s*0(?![.\d])|\bnon-negative\b", text):
            bad += [-1.0]
        if re.search(r"in \[0, 1\]", text):
            bad += [-0.25, 1.25]
        if bad:
            out[name] = bad
    return out


DOCUMENTED = [(n, a, x) for n in NAMES for a, xs in _documented_bounds(CALLABLES[n]).items()
              if a in REG[n] and _is_number(REG[n][a].value) for x in xs]


def test_class8_documented_constraints_were_found() -> None:
    assert len(DOCUMENTED) > 40


@given(st.sampled_from(DOCUMENTED))
def test_class8_documented_constraints_are_enforced(case: tuple[str, str, float]) -> None:
    name, arg, x = case
    v = REG[name][arg].value
    assert_refused(name, arg, int(x) if isinstance(v, (int, np.integer)) and x == int(x) else x)


# --------------------------------------------------------------------------------------------
# class 9: impossible sizes: ValueError naming the argument, not MemoryError
# --------------------------------------------------------------------------------------------


@given(st.sampled_from(COUNTS), st.integers(V.MAX_COUNT + 1, 2**80))
def test_class9_impossible_sizes(target: tuple[str, str], n: int) -> None:
    name, arg = target
    assert_finite_or_refused(name, arg, n)  # a seed may be that large: then a finite result


def _impossible_view(value: Any, total: int) -> np.ndarray:
    """A zero-stride view of ``value``'s first row, its leading axis grown to at least ``total`` entries (8 bytes
    of data whatever its size: only a copy or a conversion would allocate it)."""
    v = np.asarray(value, dtype=float)
    if v.ndim == 0:
        v = v.reshape(1)
    row = int(np.prod(v.shape[1:], dtype=np.int64)) or 1
    return np.broadcast_to(v[:1], (-(-total // row),) + v.shape[1:])


@pytest.mark.parametrize("target", ARRAYS, ids=[f"{n.rsplit('.', 1)[-1]}-{a}" for n, a in ARRAYS])
@settings(max_examples=4, deadline=None)
@given(st.one_of(st.just(V.MAX_INPUT_ELEMENTS + 1), st.integers(V.MAX_INPUT_ELEMENTS + 1, 10**12)))
def test_class9_an_impossible_array_is_refused_by_its_shape_before_any_copy(target: tuple[str, str],
                                                                           total: int) -> None:
    """fuzz14 bugs 1-2: every float-array argument of the registry, given a broadcast view of more than
    ``MAX_INPUT_ELEMENTS`` entries (10**10 of them convert to 80 GB; 10**8 rows copy for seconds), is refused
    by a ValueError naming it, at once (under 0.5 CPU-s: before any copy, conversion or work)."""
    name, arg = target
    view = _impossible_view(REG[name][arg].value, total)
    t0 = time.process_time()
    how, out = call(name, arg, view, seconds=20)
    spent = time.process_time() - t0
    assert how == "raised" and isinstance(out, ValueError), f"{name}: {arg} of shape {view.shape}: {how} {out!r:.200}"
    assert _names(out, arg), f"{name}: {arg}: message does not name it: {out}"
    assert spent < 0.5, f"{name}: {arg} of shape {view.shape} refused after {spent:.2f} CPU-s"


def test_class9_the_input_size_rule() -> None:
    """The shared rule reads the shape only: a view of 10**10 entries (8 bytes) is refused, the budget accepted."""
    with pytest.raises(ValueError, match=r"^x has 1e\+10 entries"):
        V.as_array(np.broadcast_to(0.5, (10**10,)), "x")
    with pytest.raises(ValueError, match="P1"):
        V.as_array(np.broadcast_to(np.eye(2)[:1], (10**8, 2)), "P1", ndim=2)
    assert V.as_array(np.broadcast_to(0.5, (V.MAX_INPUT_ELEMENTS,)), "x").size == V.MAX_INPUT_ELEMENTS
    with pytest.raises(ValueError, match="mask"):
        V.as_mask(np.broadcast_to(True, (10**10,)), "mask")


def test_class9_the_shared_rules() -> None:
    with pytest.raises(ValueError, match="runs"):
        V.count(10**12, "runs")
    assert V.seed(2**70) == 2**70
    with pytest.raises(ValueError, match="legs and turn_time"):
        V.allocation((4, 10**12), "legs and turn_time")
    from fusion.scenarios.two_sensor import trajectory

    with pytest.raises(ValueError, match="legs"):
        trajectory(legs=(1e140, 1.0, 1.0))


# ----------------------------------------------------------------------------- round 3


@given(st.one_of(st.just(0.0), st.floats(1e-100, 1e3), st.floats(-1e3, -1e-100)), st.sampled_from(["soft", "hard"]),
       st.sampled_from(["dwt", "swt"]))
def test_denoise_of_a_constant_signal_is_finite_and_constant(c: float, mode: str, transform: str) -> None:
    """A zero threshold (sigma-hat = 0, a constant signal) leaves the coefficients: no 0/0 from PyWavelets."""
    from fusion.readings.wavelet import denoise

    y = denoise(np.full((2, 64), c), "db4", 2, mode=mode, transform=transform)
    assert np.all(np.isfinite(y)) and np.allclose(y, c, atol=1e-9 * max(1.0, abs(c)))


@given(st.floats(1e-300, 9e-151), st.booleans())
def test_a_tiny_signed_scalar_is_refused_by_its_own_name(x: float, negative: bool) -> None:
    """Rule 2 for scalars is the array entries' rule: a start angle of 1e-300 is refused as az0, not as az."""
    from fusion.scenarios.infrared_radar import truth

    with pytest.raises(ValueError, match=r"\baz0\b"):
        truth(0.1, 1.0, 1000.0, -x if negative else x, 0.3)


def test_a_derived_quantity_refused_inside_names_the_public_arguments() -> None:
    """F = 0 with a low-rank Q makes a local covariance singular: the message names F and Q."""
    from fusion.filtering.feedback import fusion_loop

    n, m, runs, K = 4, 2, 2, 3
    H = np.eye(m, n)
    Q = np.diag([0.0, 1.0, 0.0, 1.0])
    z = np.zeros((runs, K, m))
    with pytest.raises(ValueError, match=r"\bF\b.*\bQ\b"):
        fusion_loop(z, z, np.zeros((runs, n)), np.zeros((runs, n)), np.zeros((n, n)), H, Q, np.eye(m), np.eye(m),
                    np.eye(n), np.eye(n), np.eye(n), "split", feedback="split")


@pytest.mark.parametrize("bad, what", [
    (np.ma.array([1.0, 2.0, 1e6], mask=[False, False, True]), "masked array"),
    (np.array(["2026-12-05T10:00", "2026-12-05T10:01"], dtype="datetime64[s]"), "datetime64"),
    (np.array([1, 2], dtype="timedelta64[s]"), "timedelta64"),
])
def test_masked_arrays_and_dates_are_refused_by_name(bad, what) -> None:
    """A masked array's mask would be dropped, a date's unit guessed: both are refused, naming the argument."""
    from fusion._validation import as_array

    with pytest.raises(TypeError, match=r"^x must be .*" + what.split("6")[0][:6]):
        as_array(bad, "x")


# --------------------------------------------------------------------------------------------
# the shared rules added for the independent fuzz (fuzz8)
# --------------------------------------------------------------------------------------------


@given(power=st.integers(1, 6), x=st.floats(1e-150, 1e150))
def test_a_step_is_bounded_by_the_powers_the_model_forms(power: int, x: float) -> None:
    """step_scalar accepts exactly the steps whose power stays within MAX_MAGNITUDE, naming the step otherwise."""
    top = V.MAX_MAGNITUDE ** (1.0 / power)
    if x <= top:
        assert V.step_scalar(x, "T", power) == x
        assert np.isfinite(x ** power)
    else:
        with pytest.raises(ValueError, match=r"^T = .* too large"):
            V.step_scalar(x, "T", power)


@given(x=st.floats(1e-160, 1e160))
def test_a_standard_deviation_has_a_square_that_is_a_valid_variance(x: float) -> None:
    """std_scalar's bound is the covariance rule on its square: [MIN_VARIANCE, MAX_MAGNITUDE]."""
    ok = x >= 1e-150 and V.MIN_VARIANCE <= x * x <= V.MAX_MAGNITUDE
    if ok:
        assert V.std_scalar(x, "sigma") == x
    else:
        with pytest.raises(ValueError, match=r"^sigma"):
            V.std_scalar(x, "sigma")


@given(v=st.floats(0.0, 1e-155), n=st.integers(1, 4))
def test_semidefinite_matrices_follow_the_covariance_rule(v: float, n: int) -> None:
    """A zero variance is valid in a positive-semidefinite matrix (low-rank process noise), a non-zero one below
    MIN_VARIANCE is refused naming the matrix, as in as_covariance (fuzz8 bug 6)."""
    Q = np.diag([v] + [1.0] * (n - 1))
    if v == 0.0:
        np.testing.assert_array_equal(V.as_semidefinite(Q, n, name="Q"), Q)
    else:
        with pytest.raises(ValueError, match=r"^Q has a variance below"):
            V.as_semidefinite(Q, n, name="Q")


@given(scale=st.floats(1.0, 1e150), n=st.integers(1, 5))
def test_finite_result_refuses_an_overflowing_product_by_name(scale: float, n: int) -> None:
    """finite_result returns a finite result unchanged and refuses a non-finite one naming the inputs."""
    @V.finite_result("F and Q")
    def square(F: float, Q: float) -> dict:
        return {"P": np.full(n, F * F * Q)}

    with np.errstate(over="ignore"):
        finite = np.isfinite(scale * scale * scale)
    if finite:
        np.testing.assert_array_equal(square(scale, scale)["P"], np.full(n, scale * scale * scale))
    else:
        with pytest.raises(ValueError, match=r"^F and Q give a non-finite result \(in \['P'\]\)"):
            square(scale, scale)


@given(sigma=st.sampled_from([1e150, 1e-150, 1e80, 2.0]))
def test_derived_inputs_names_the_extreme_argument(sigma: float) -> None:
    """An inner refusal of a derived array is re-raised naming the public argument at an extreme magnitude."""
    @V.derived_inputs()
    def study(sigma: float, x: float = 3.0, runs: int = 10) -> float:
        V.as_array(np.array([x, sigma * sigma]), "X")
        return sigma

    if sigma == 2.0:
        assert study(sigma) == 2.0
        return
    with pytest.raises(ValueError, match=r"^sigma gives a derived quantity that is refused: X has"):
        study(sigma)


@given(n=st.integers(0, 10**5))
def test_echoed_values_are_bounded(n: int) -> None:
    """An unknown option is echoed in full when short, cut to MAX_SHOWN characters (with its length) when long."""
    value = "x" * n
    with pytest.raises(ValueError) as info:
        V.one_of(value, ("a", "b"), "method")
    assert len(str(info.value)) <= 60 + V.MAX_SHOWN + 30
    assert (repr(value) in str(info.value)) == (len(repr(value)) <= V.MAX_SHOWN)


@settings(max_examples=25, deadline=None)
@given(k=st.integers(-100, 4))  # beyond 2**4 the fixed 0.01 s integration step is refused by size
def test_two_sensor_path_is_invariant_under_a_change_of_time_unit(k: int) -> None:
    """fuzz10 bug 1: T, legs and turn_time scaled by s = 2**k give the same steps (t / s) and the path scaled by s."""
    from fusion.scenarios.two_sensor import trajectory
    from fusion.scenarios.two_sensor.bounds import straight_leg_floor

    s = 2.0**k
    ref = trajectory(1.0, start=(0.0, 0.0))
    got = trajectory(s, start=(0.0, 0.0), legs=(100.0 * s, 30.0 * s, 90.0 * s), turn_time=20.0 * s)
    assert got.t.shape == ref.t.shape
    np.testing.assert_allclose(got.t / s, ref.t, rtol=1e-12, atol=0)
    if k <= -7:  # the integration step min(T, 0.01) is T for both: the path itself scales exactly
        s0 = 2.0**-7
        ref0 = trajectory(s0, start=(0.0, 0.0), legs=(100.0 * s0, 30.0 * s0, 90.0 * s0), turn_time=20.0 * s0)
        scale = np.array([s / s0, 1.0, s / s0, 1.0])  # positions scale with time (constant speed), velocities do not
        np.testing.assert_allclose(got.states / scale, ref0.states, rtol=1e-9, atol=1e-9 * 50.0 * ref0.t[-1])
    floors = straight_leg_floor(s, 1.0, legs=(100.0 * s, 30.0 * s, 90.0 * s), turn_time=20.0 * s)
    ref_floors = straight_leg_floor(1.0, 1.0)
    np.testing.assert_array_equal(floors[1], ref_floors[1])  # the same steps on a leg
    np.testing.assert_allclose(floors[2], ref_floors[2], rtol=1e-6)  # a position floor does not depend on the unit


def test_two_sensor_path_too_fine_is_refused_by_name() -> None:
    """A step count beyond the ceiling is refused naming T, legs and turn_time, not by numpy."""
    from fusion.scenarios.two_sensor import trajectory

    with pytest.raises(ValueError, match=r"^T, legs and turn_time ask for"):
        trajectory(1e-100)


@settings(max_examples=20, deadline=None)
@given(e=st.integers(-100, 400))
@example(e=400)  # the fuzz's case
def test_overflowing_products_of_in_range_inputs_are_refused_by_name(e: int) -> None:
    """fuzz10 bugs 2-4: inputs scaled by s = 2**e (each within range): the result scales as its closed form or is refused."""
    from fusion.readings.biased import ridge_risk
    from fusion.readings.weighting import wls
    from fusion.scenarios.correlated_sensors import covariance

    s = 2.0**e
    H, W, Y = np.array([[1.0], [2.0], [3.0]]), np.array([1.0, 2.0, 0.5]), np.array([1.0, 2.5, 2.0])
    A, x, k = np.array([[2.0, 0.5], [0.5, 1.0]]), np.array([1.0, -2.0]), np.array([0.0, 0.3])
    own, c, env = np.array([0.5, 1.0, 1.5]), np.array([1.0, 2.0, 3.0]), 1.0
    cases = [(lambda: wls(H * s, W * s, Y * s), lambda: wls(H, W, Y), 0, "H, W and Y"),          # x scales as 1
             # bias**2 (k (A + kI)^-1 x)**2 and variance tr((A + kI)^-2 A) both scale as 1/s with x / sqrt(s)
             (lambda: ridge_risk(A * s, x * 2.0**(-e / 2), k * s), lambda: ridge_risk(A, x, k), -1, "A, x and k"),
             (lambda: covariance(own * s, c, env * s), lambda: covariance(own, c, env), 2, "own, coupling and env")]
    for scaled, ref, power, names in cases:
        try:
            got = scaled()
        except ValueError as exc:
            assert str(exc).startswith(names), str(exc)
            assert e > 200  # only where a product of the inputs leaves the float range
            continue
        assert np.all(np.isfinite(got))
        if power is not None:
            np.testing.assert_allclose(got, ref() * s**power, rtol=1e-9)
    if e >= 400:  # the fuzz's calls: every input x 2**400
        for fuzzed, names in [(lambda: wls(H * s, W * s, Y * s), "H, W and Y"),
                              (lambda: ridge_risk(A * s, x * s, k * s), "A, x and k"),
                              (lambda: covariance(own * s, c * s, env * s), "own, coupling and env")]:
            with pytest.raises(ValueError, match=f"^{names} give a non-finite result"):
                fuzzed()


@settings(max_examples=20, deadline=None)
@given(x=st.integers(-10**6, 10**6).map(lambda i: i / 8), y=st.integers(-10**6, 10**6).map(lambda i: i / 8),
       layout=st.sampled_from(["tuple", "list", "array", "object", "structured"]))
def test_network_coordinates_are_stored_converted(x: float, y: float, layout: str) -> None:
    """fuzz10 bug 6: NetworkNode.position and NetworkScenario.truth hold the validated floats, not the caller's object."""
    from fusion.scenarios.fusion_networks import NetworkNode, NetworkScenario

    if layout == "structured":  # rule 16: a structured array is not read as its field
        raw: Any = np.zeros(2, dtype=[("x", "f8")])
        raw["x"] = (x, y)
        with pytest.raises(TypeError, match=r"^position must be numeric, got an array of dtype"):
            NetworkNode(raw)
        with pytest.raises(TypeError, match=r"^truth must be numeric, got an array of dtype"):
            NetworkScenario("s", (NetworkNode((x, y)), NetworkNode((0.0, 0.0))), truth=raw)
        return
    raw = {"tuple": (x, y), "list": [x, y], "array": np.array([x, y]),
           "object": np.array([x, y], dtype=object)}[layout]
    node = NetworkNode(raw)
    scenario = NetworkScenario("s", (node, NetworkNode((0.0, 0.0))), truth=raw)
    for stored in (node.position, scenario.truth):
        assert type(stored) is tuple and all(type(v) is float for v in stored)
        assert stored == (x, y)


@settings(max_examples=20, deadline=None)
@given(n=st.integers(1, 4), data=st.data())
def test_too_short_series_and_too_large_steps_name_the_times(n: int, data: st.DataObject) -> None:
    """fuzz10 bugs 7-8: a series too short for a method names t (and z) or t_src; a step too large names t_src and t_dst."""
    from fusion.registration import methods as M
    from fusion.scenarios import time_registration as tr

    t = np.arange(20.0)
    fn, least = data.draw(st.sampled_from([(M.two_point, 2), (M.three_point, 3), (M.quadratic_ls, 3),
                                           (M.spline_register, 4)]))
    if n < least:
        with pytest.raises(ValueError, match=rf"^t and z must hold at least {least} samples, got {n}"):
            fn(t[:n], 2.0 * t[:n], t[:3] + 0.5)
    d1, d2 = tr.instants()
    name = data.draw(st.sampled_from(list(tr.METHODS)))
    try:
        tr.expected(name=name, sigma=1.0, t_src=d1[:n], t_dst=d2)
    except ValueError as exc:  # the method's own names (t and z) are not the scenario's arguments
        assert not str(exc).startswith("t and z"), str(exc)
        if "samples, got" in str(exc):
            assert str(exc).startswith("t_src must hold at least"), str(exc)
    s = 2.0**100
    try:
        tr.expected(name, s, t_src=d1 * s, t_dst=d2 * s, q_v=tr.Q_V * s, q_a=tr.Q_A * s)
    except ValueError as exc:
        assert not str(exc).startswith("dt ="), str(exc)


# --------------------------------------------------------------------------------------------
# rule 18: a flag is a bool (fuzz12 bugs 1-2: 'False' was read as its truthiness, True)
# --------------------------------------------------------------------------------------------


def _flag_parameters() -> list[tuple[str, str]]:
    """(callable, parameter) for every parameter annotated ``bool`` of every registry callable."""
    import typing

    out = []
    for n in sorted(REG):
        if _excluded(n) or n in SLOW:
            continue
        try:
            params = inspect.signature(CALLABLES[n]).parameters
            hints = typing.get_type_hints(CALLABLES[n])
        except (TypeError, ValueError, NameError):
            continue
        out += [(n, a) for a, p in params.items() if hints.get(a, p.annotation) is bool]
    return out


FLAGS = _flag_parameters()


def test_the_registry_has_flags() -> None:
    assert len(FLAGS) > 25
    assert ("fusion.book.rulebook.record_status", "assumptions") in FLAGS
    assert ("fusion.book.style.method_style", "markers") in FLAGS


@settings(max_examples=60, deadline=None)
@given(target=st.sampled_from(FLAGS), value=st.sampled_from(["False", "True", None, 0, 1, np.int64(1), 0.0, "",
                                                             np.array([True])]))
def test_rule18_a_flag_refuses_anything_but_a_bool(target: tuple[str, str], value: Any) -> None:
    """Every bool parameter of the public API refuses a string, None, a number or an array (TypeError naming it)."""
    assert_refused(*target, value, types=(TypeError,))


@settings(max_examples=30, deadline=None)
@given(target=st.sampled_from(FLAGS))
def test_rule18_a_numpy_bool_is_a_flag(target: tuple[str, str]) -> None:
    """``numpy.bool_`` is accepted wherever ``bool`` is: whatever the call gives, it is not a refusal of the flag."""
    name, arg = target
    default = inspect.signature(CALLABLES[name]).parameters[arg].default
    value = REG[name][arg].value if arg in REG[name] else default
    how, out = call(name, arg, np.bool_(value if isinstance(value, bool) else False))
    assert how == "ok" or not _names(out, arg), f"{name}: {arg}: np.bool_ refused: {out}"


@pytest.mark.parametrize("fn", ["position_sq_errors", "nees_per_frame"])
def test_class6_a_documented_method_the_runs_did_not_compute_is_named(fn: str) -> None:
    """fuzz12 bug 6: a key of METHODS that the runs did not compute (a variant) is a ValueError naming key and listing
    the run's methods, not a KeyError; the keys the runs hold still give finite values."""
    from fusion.scenarios import range_bearing as rb

    runs = REG[f"fusion.scenarios.range_bearing.{fn}"]["runs"].value
    held = set(runs[0].covariances if fn == "nees_per_frame" else runs[0].estimates)
    allowed = [k for k in rb.METHODS if fn != "nees_per_frame" or k != "mean_of_local_means"]
    missing = [k for k in allowed if k not in held]
    assert missing and len(missing) < len(allowed)
    for k in allowed:
        if k in held:
            assert np.isfinite(getattr(rb, fn)(runs, k)).all()
            continue
        with pytest.raises(ValueError, match=rf"^key: runs\[0\] did not compute the method '{k}'") as info:
            getattr(rb, fn)(runs, k)
        assert all(h in str(info.value) for h in sorted(held)[:3])


def test_a_bounded_scalars_signed_zero_is_its_zero() -> None:
    """fuzz 15: -0.0 passed a `>= 0` check and reached numpy as a negative upper end (belief_parameter_study's
    shift); the shared rule returns +0.0 for a bounded scalar, so -0.0 and 0.0 are served alike."""
    import math

    from fusion._validation import scalar
    from fusion.scenarios.lecture_weighting.belief import belief_parameter_study

    assert math.copysign(1.0, scalar(-0.0, "v", lo=0.0)) == 1.0
    assert math.copysign(1.0, scalar(-0.0, "v", hi=1.0)) == 1.0
    a, b = belief_parameter_study(shift=0.0, snapshots=4), belief_parameter_study(shift=-0.0, snapshots=4)
    assert np.array_equal(a.fused, b.fused)


def test_a_window_is_an_ordered_pair() -> None:
    """fuzz 15: a frozenset or a two-key mapping has a length of 2 but no order; the shared window rule refuses it
    by name (it gave "'frozenset' object is not subscriptable" and a bare KeyError in consistency_study and
    thermocouples.scale_sweep); a tuple, a list and a 1-D array are pairs."""
    from types import MappingProxyType

    from fusion._frozen import ReadOnlyMapping
    from fusion._validation import window

    for pair in ((2, 5), [2, 5], np.array([2, 5])):
        assert window(pair, "window", 10) == (2, 5)
    for bad in (frozenset({2, 5}), {0: 2, 1: 5}, MappingProxyType({0: 2, 1: 5}), ReadOnlyMapping({0: 2, 1: 5}),
                np.array([[2, 5]]), "25", range(3)):
        with pytest.raises(TypeError, match="window must be a pair"):
            window(bad, "window", 10)


def test_chapter_functions_check_the_seed_they_draw_from() -> None:
    """fuzz 15: chapter studies passed their ``seed`` straight to ``default_rng`` (1.0 gave numpy's unnamed
    TypeError, True was served as seed 1). Every function under fusion/book/chapters with a ``seed`` parameter
    that draws from ``default_rng(seed ...)`` checks it first with the shared rule (``fusion._counts.seed``).
    Issue 35: so does every public (module-level, unprefixed) chapter function with a ``seed`` parameter, and one
    with a ``runs`` parameter that casts it (``int(runs)``) checks it with the shared count rule: ``int(seed)``
    had turned a seed of 1.5 into 1 and True into 1."""
    import ast
    from pathlib import Path

    from fusion.book.chapters.chernoff import studies

    missing, public = [], 0
    for path in sorted((Path(__file__).resolve().parents[1] / "fusion" / "book" / "chapters").rglob("*.py")):
        src = path.read_text(encoding="utf-8")
        tree = parsed(path)   # the tree of src (read once per process: tests/_helpers.parsed)
        top = {id(n) for n in tree.body}
        lines = src.splitlines(keepends=True)
        for node in ast.walk(tree):
            if not isinstance(node, ast.FunctionDef):
                continue
            params = [a.arg for a in node.args.args + node.args.kwonlyargs]
            # the def's lines (ast.get_source_segment re-splits the file at every call: a second per run)
            body = "".join(lines[node.lineno - 1:node.end_lineno])
            entry = id(node) in top and not node.name.startswith("_")
            if "seed" in params and "check_seed(seed" not in body and ("default_rng(seed" in body or entry):
                missing.append(f"{path.name}:{node.name} (seed)")
            if entry and "runs" in params and "int(runs)" in body and not re.search(r"\bcount\(runs", body):
                missing.append(f"{path.name}:{node.name} (runs)")
            public += entry and "seed" in params
    assert missing == []
    assert public > 100  # the walk reaches the chapters' public seeded functions
    for bad in (1.0, True):
        with pytest.raises(TypeError, match="seed must be an integer seed"):
            studies.isv_study(bad)


@pytest.mark.parametrize("module, fn, kwargs, name", [
    ("ofs.studies", "fair", {"seed": 1.5}, "seed"), ("ofs.studies", "fair", {"seed": True}, "seed"),
    ("ofs.studies", "fair", {"seed": 1, "runs": 2.0}, "runs"), ("ofs.studies", "study", {"seed": 1, "runs": True}, "runs"),
    ("chernoff.studies", "tracking_study", {"seed": 1.5}, "seed"), ("chernoff.studies", "design", {"seed": 1, "runs": 2.5}, "runs"),
    ("ofs_fair", "fair_study", {"seed": np.float64(3.0)}, "seed"),
    ("lecture_weighting.records", "ev_awf_accuracy", {"settings": {"reading": "x"}, "seed": 1.5}, "seed"),
    ("lecture_weighting.records", "ev_awf_accuracy", {"settings": {"reading": "x"}, "runs": 2.0}, "runs"), ("lecture_weighting.studies", "study", {"key": "s21", "seed": True}, "seed"),
])
def test_chapter_wrappers_refuse_a_cast_seed_or_runs(module: str, fn: str, kwargs: dict, name: str) -> None:
    """Issue 35: the chapter wrappers that cast ``int(seed)``/``int(runs)`` refuse a float or a bool by name."""
    import importlib

    with pytest.raises(TypeError, match=rf"^{name} must be an integer"):
        getattr(importlib.import_module(f"fusion.book.chapters.{module}"), fn)(**kwargs)


# --------------------------------------------------------------------------------------------
# fuzz 17, class G: a refusal must not fail on the value it shows
# --------------------------------------------------------------------------------------------

class _BadRepr(float):
    """A valid float type whose own ``__repr__`` raises."""

    def __repr__(self) -> str:
        raise RuntimeError("no repr")


class _BadReprStr(str):
    def __repr__(self) -> str:
        raise RuntimeError("no repr")


def test_no_error_message_formats_a_value_with_its_own_repr() -> None:
    """Every ``raise`` of the package shows a value through ``fusion._shown.shown`` (cut, and safe when the value's
    ``__repr__`` raises), never with an f-string's ``!r``: an AST scan of every module of ``fusion/``."""
    import ast
    from pathlib import Path

    root = Path(V.__file__).resolve().parent
    found = []
    for path in sorted(root.rglob("*.py")):
        for node in ast.walk(parsed(path)):
            if isinstance(node, ast.Raise) and node.exc is not None:
                found += [f"{path.relative_to(root)}:{node.lineno}" for v in ast.walk(node.exc)
                          if isinstance(v, ast.FormattedValue) and v.conversion == ord("r")]
    assert found == []


@pytest.mark.parametrize("call", [
    lambda: __import__("fusion.readings.fusion_set", fromlist=["x"]).optimal_fusion_set(
        np.linspace(899.0, 901.0, 5), scale=_BadRepr(-1.0)),
    lambda: __import__("fusion.readings.fusion_set", fromlist=["x"]).optimal_fusion_set(
        np.linspace(899.0, 901.0, 5), threshold=_BadReprStr("nope")),
    lambda: __import__("fusion.estimates", fromlist=["x"]).covariance_intersection(
        np.zeros(2), np.eye(2), np.ones(2), np.eye(2), omega=_BadRepr(float("nan"))),
])
def test_a_value_whose_repr_raises_is_refused_by_name(call) -> None:  # noqa: ANN001
    with pytest.raises(ValueError, match=r"(scale|threshold|omega).*a _BadRepr"):
        call()


def test_a_seed_beyond_256_bits_is_refused_before_any_generator() -> None:
    """A seed of 10**6 bits cost 3.6 CPU-s a SeedSequence (quadratic in its size), paid again by every child a
    study spawns, and no budget counted it: refused by its bit length, naming the seed, whatever its size."""
    import time

    import numpy as np

    from fusion._counts import SEED_MAX, seeds
    from fusion.scenarios.range_bearing import RangeBearingScenario, monte_carlo

    assert V.seed(SEED_MAX) == SEED_MAX and seeds(np.array([0, 2**63 - 1])) == [0, 2**63 - 1]
    t = time.process_time()
    for bad in (SEED_MAX + 1, 1 << 10**6):
        with pytest.raises(ValueError, match="^seed must be a seed of at most 256 bits"):
            V.seed(bad)
        with pytest.raises(ValueError, match=r"^seeds\[1\] must be a seed of at most 256 bits"):
            seeds([1, bad])
    assert time.process_time() - t < 0.5
    t = time.process_time()
    with pytest.raises(ValueError, match="^seed must be a seed of at most 256 bits"):   # a public root seed
        monte_carlo(RangeBearingScenario(frames=3, n_particles=50), 1 << 10**6, 100)
    assert time.process_time() - t < 0.5


def test_derived_inputs_decorates_public_entries_only() -> None:
    """``fusion._guards.derived_inputs`` decorates a public entry (its docstring). A budget helper inserted between
    the decorator and its study took it (fix61a, fix62a: ``consistency_study``, ``regime_study``, ``scale_sweep`` and
    ``plugin_study`` then refused sigma = 1e150 naming an internal X); no private function carries it."""
    import ast
    from pathlib import Path

    root = Path(__file__).resolve().parents[1] / "fusion"
    private = [f"{p.relative_to(root)}:{n.name}" for p in sorted(root.rglob("*.py"))
               for n in ast.walk(parsed(p)) if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))
               and n.name.startswith("_") and any("derived_inputs" in ast.unparse(d) for d in n.decorator_list)]
    assert not private, private
