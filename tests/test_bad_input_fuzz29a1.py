"""Fuzz 29a (issue 35), cases C1, C2, C5 and C7 (report /work/tmp/fuzz29a/report.md).

C1: a frozen record keeps no caller's 0-d array in a scalar field (the number read, or a read-only copy).
C2: an integer given through ``__index__`` only is validated and then used as the plain int the check returns.
C5: an array-like argument is converted once (``fusion._validation.read_once``), checked and computed as one array.
C7: a callable the package calls (objective, fitness, registration) is given a copy (``argument_copy``): changing its
argument in place does not change what the package reads back.
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import pkgutil
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import fusion
from fusion._frozen import frozen_arrays
from fusion._results import ResultSpec, integer, number, shared_post_init, validated_post_init

from test_bad_input import CALLABLES, REG

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import fuzz_public_api as FZ  # noqa: E402

FEW = settings(settings.get_profile("fusion"), max_examples=6)

#: Slow registry calls (a second or more), left to the fuzzer here.
SLOW = {"fusion.scenarios.two_sensor.architecture_study", "fusion.scenarios.two_sensor.fusion_study",
        "fusion.book.glue.glue_all", "fusion.readings.weighting.difference_variances",
        "fusion.scenarios.range_bearing.monte_carlo", "fusion.scenarios.range_bearing.run_tracking",
        "fusion.scenarios.range_bearing.run_tracking_batch", "fusion.scenarios.fusion_networks.run_network_study",
        "fusion.book.study_cache.process_cache", "fusion.book.study_cache.study_cache"}


class Idx:
    """An integer only through ``__index__`` (as sympy or torch integer scalars are): rule 13 accepts it."""

    def __init__(self, v: int) -> None:
        self.v = v

    def __index__(self) -> int:
        return self.v


def _same(a: object, b: object) -> bool:
    """Equal results: numbers, arrays (NaN equal), tables, containers and dataclasses field by field."""
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        return type(a) is type(b) and all(_same(getattr(a, f.name), getattr(b, f.name)) for f in dataclasses.fields(a)
                                          if f.name not in ("timings", "elapsed"))
    if isinstance(a, (pd.DataFrame, pd.Series)):
        return a.equals(b)
    if hasattr(a, "to_html") and type(a).__name__ == "Styler":
        return a.to_html() == b.to_html()  # type: ignore[union-attr]
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.shape(a) == np.shape(b) and bool(np.array_equal(a, b, equal_nan=np.asarray(a).dtype.kind == "f"))
    if isinstance(a, dict) or hasattr(a, "items") and hasattr(a, "keys"):
        return set(a.keys()) == set(b.keys()) and all(_same(a[k], b[k]) for k in a)  # type: ignore[union-attr,index]
    if isinstance(a, (list, tuple)):
        return type(a) is type(b) and len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))  # type: ignore
    if isinstance(a, float) and isinstance(b, float) and np.isnan(a):
        return bool(np.isnan(b))
    if callable(a):
        return True
    return bool(a == b)


def _valid(name: str) -> dict:
    return FZ._fresh({k: a.value for k, a in REG[name].items()})


# -- C1: no caller's 0-d array in a frozen record's scalar field ---------------------------------------------------


def _scalar_fields(cls: type) -> list[str]:
    return [f.name for f in dataclasses.fields(cls)
            if any(t in ("int", "float") for t in str(f.type).replace(" ", "").split("|"))]


def _kept_no_alias(stored: object, given: np.ndarray) -> bool:
    """The stored value is a plain (or numpy) number, or a read-only array that is not the caller's."""
    if not isinstance(stored, np.ndarray):
        return isinstance(stored, (int, float, np.integer, np.floating))
    return not stored.flags.writeable and not np.shares_memory(stored, given)


def _reported() -> dict:
    from fusion.book.audit import SubsetMatch
    from fusion.book.claims import ReadingSpec
    from fusion.book.ledger import Source
    from fusion.book.rulebook import judge_paired
    from fusion.estimates.chernoff import FirstOrderMixture, FusionTimings
    from fusion.estimates.mixtures import GaussianMixture

    gm = GaussianMixture(np.ones(1), np.zeros((1, 1)), np.ones((1, 1, 1)))
    return {"Judgement": judge_paired(np.arange(10.0) + 0.1, np.arange(10.0), "less", 0.5),
            "Source": Source("k", "s", "t", "notebooks/01_x", 3),
            "SubsetMatch": SubsetMatch((0, 2), 1.5),
            "FirstOrderMixture": FirstOrderMixture(gm, -0.25),
            "FusionTimings": FusionTimings(0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7),
            "ReadingSpec": ReadingSpec("k", "", "", "primary", {}, 5)}


@pytest.mark.parametrize("cls", ["Judgement", "Source", "SubsetMatch", "FirstOrderMixture", "FusionTimings",
                                 "ReadingSpec"])
def test_c1_the_reported_records_store_the_number_read(cls: str) -> None:
    obj = _reported()[cls]
    for name in _scalar_fields(type(obj)):
        value = getattr(obj, name)
        a = np.array(value)
        new = dataclasses.replace(obj, **{name: a})
        assert type(getattr(new, name)) in (int, float), (cls, name, type(getattr(new, name)))
        a[...] = 0
        assert getattr(new, name) == value and a.flags.writeable
        hash(getattr(new, name))  # a number, not an (unhashable) array


def test_c1_subset_match_and_timings_are_checked() -> None:
    from fusion.book.audit import SubsetMatch
    from fusion.estimates.chernoff import FusionTimings

    with pytest.raises(ValueError, match="FusionTimings.sampling"):
        FusionTimings(sampling=-5.0)
    with pytest.raises(ValueError, match=r"SubsetMatch.members\[0\]"):
        SubsetMatch((-1,), 1.0)
    with pytest.raises(TypeError, match="SubsetMatch.value"):
        SubsetMatch((0,), "1.0")  # type: ignore[arg-type]


#: The public constructors of the registry that are frozen dataclasses with int or float fields, and those fields
#: the registry's valid call gives as a plain number.
CONSTRUCTORS = sorted(
    (n, f) for n in REG if isinstance(CALLABLES.get(n), type) and dataclasses.is_dataclass(CALLABLES[n])
    and CALLABLES[n].__dataclass_params__.frozen for f in _scalar_fields(CALLABLES[n])
    if f in REG[n] and type(REG[n][f].value) in (int, float))


@pytest.mark.parametrize("name, field", CONSTRUCTORS)
def test_c1_every_public_constructor_keeps_no_caller_0d_array(name: str, field: str) -> None:
    kw = _valid(name)
    a = np.array(kw[field])
    kw[field] = a
    try:
        obj = CALLABLES[name](**kw)
    except (TypeError, ValueError) as e:  # refused by name (a margin is a Python or numpy number): nothing kept
        assert field in str(e)
        return
    assert _kept_no_alias(getattr(obj, field), a), (name, field, type(getattr(obj, field)))
    assert a.flags.writeable  # the caller's array is not frozen in place either


def _frozen_classes() -> list[type]:
    import fusion._validation  # noqa: F401 (imported first: the package's import order)

    for m in pkgutil.walk_packages(fusion.__path__, "fusion."):
        importlib.import_module(m.name)
    out = set()
    for mod in list(sys.modules.values()):
        name = getattr(mod, "__name__", "")
        if not name.startswith("fusion.") or any(p.startswith("_") for p in name.split(".")[1:]):
            continue
        for c in vars(mod).values():
            if isinstance(c, type) and c.__module__ == name and not c.__name__.startswith("_") \
                    and dataclasses.is_dataclass(c) and c.__dataclass_params__.frozen and _scalar_fields(c):
                out.add(c)
    return sorted(out, key=lambda c: f"{c.__module__}.{c.__qualname__}")


#: The shared rules: a field spec (numbers and ints read, arrays copied), or the frozen-arrays decorator.
SHARED = {"validated_post_init", "shared_post_init", "freeze_arrays", "freeze_shared", "_checked_optimum"}


def test_c1_every_frozen_record_with_numbers_goes_through_a_tested_rule() -> None:
    """Every public frozen dataclass with an int or float field stores it by a shared rule (tested below), or is a
    public constructor of the registry (tested above), or one of the reported records."""
    tested = {n for n, _ in CONSTRUCTORS} | {n for n in REG if isinstance(CALLABLES.get(n), type)}

    def shared(c: type) -> bool:  # the rule itself, or a __post_init__ of the class's own that ends in it
        post = getattr(c, "__post_init__", None)
        wrapped = getattr(post, "__wrapped__", None)  # a __post_init__ that runs the rule, then records more
        return getattr(post, "__name__", None) in SHARED or getattr(wrapped, "__name__", None) in SHARED or (
            post is not None and "validated_post_init(self)" in inspect.getsource(post))

    untested = [f"{c.__module__}.{c.__qualname__}" for c in _frozen_classes() if not shared(c)
                and f"{c.__module__}.{c.__qualname__}" not in tested and c.__name__ not in _reported()]
    assert not untested, untested


@dataclasses.dataclass(frozen=True)
class _Validated:
    x: float
    n: int
    free: float  # not in the spec: frozen as a read-only copy

    __result_spec__ = ResultSpec({"x": number(), "n": integer()})
    __post_init__ = validated_post_init


@dataclasses.dataclass(frozen=True)
class _Shared:
    x: float
    n: int

    __result_spec__ = ResultSpec({"x": number(), "n": integer()})
    __post_init__ = shared_post_init


@dataclasses.dataclass(frozen=True)
@frozen_arrays
class _Decorated:
    x: float


@dataclasses.dataclass(frozen=True)
@frozen_arrays(shared=True)
class _Bundle:
    x: float


@pytest.mark.parametrize("cls", [_Validated, _Shared, _Decorated, _Bundle])
@FEW
@given(v=st.floats(0.0, 1e6), n=st.integers(0, 10**6))
def test_c1_every_shared_rule_keeps_no_caller_0d_array(cls: type, v: float, n: int) -> None:
    given_ = {"x": np.array(v), "n": np.array(n), "free": np.array(v)}
    kw = {f.name: given_[f.name] for f in dataclasses.fields(cls)}
    obj = cls(**kw)
    for name, a in kw.items():
        assert _kept_no_alias(getattr(obj, name), a), (cls.__name__, name)
        assert a.flags.writeable
        a[...] = a + 1
        assert getattr(obj, name) == given_[name] - 1 or getattr(obj, name) == (v if name != "n" else n)


# -- C2: integers through __index__ --------------------------------------------------------------------------------


def test_c2_the_faulty_sensor_given_through_index_is_the_faulty_sensor() -> None:
    from fusion.scenarios.lecture_weighting.consistency import consistency_study

    name = "fusion.scenarios.lecture_weighting.consistency.consistency_study"
    kw = _valid(name)
    plain = consistency_study(**kw)
    kw = _valid(name)
    kw["fault_sensor"] = Idx(kw["fault_sensor"])
    assert _same(consistency_study(**kw), plain)


@pytest.mark.parametrize("name, arg", [
    ("fusion.scenarios.lecture_weighting.regime.regime_study", "change_at"),
    ("fusion.scenarios.lecture_weighting.regime.variance_change_study", "change_at"),
    ("fusion.scenarios.lecture_weighting.readings_benchmark.benchmark", "fault_sensor"),
    ("fusion.book.tables.highlight_mismatches", "decimals"),
    ("fusion.book.ledger.Source", "order"),
])
def test_c2_the_reported_integers_are_used_as_the_int_read(name: str, arg: str) -> None:
    plain = CALLABLES[name](**_valid(name))
    kw = _valid(name)
    kw[arg] = Idx(kw[arg])
    result = CALLABLES[name](**kw)
    assert _same(result, plain)
    if dataclasses.is_dataclass(result) and arg in {f.name for f in dataclasses.fields(result)}:
        assert type(getattr(result, arg)) is int


#: Integer arguments of the registry's calls, by callable (a seed is an int or numpy integer by rule 11: an
#: ``__index__`` object is refused by name there; the slow studies are left to the fuzzer, as in
#: tests/test_bad_input_properties.py).
INT_ARGS = {n: args for n in sorted(REG) if n in CALLABLES and n not in SLOW and (args := [
    a for a, spec in REG[n].items() if type(spec.value) is int and "seed" not in a and a != "workers"])}


@pytest.mark.parametrize("name", sorted(INT_ARGS))
def test_c2_an_index_integer_gives_the_plain_int_s_result(name: str) -> None:
    """Every integer argument of every registry call (but seeds and the slow studies), given as an object with only
    ``__index__``: the result is the plain int's."""
    plain = CALLABLES[name](**_valid(name))
    for arg in INT_ARGS[name]:
        kw = _valid(name)
        kw[arg] = Idx(kw[arg])
        assert _same(CALLABLES[name](**kw), plain), (name, arg)


def test_c2_the_integer_check_returns_a_plain_int() -> None:
    from fusion._validation import count, index, integer

    for f in (lambda v: integer(v, "k"), lambda v: count(v, "k", minimum=0), lambda v: index(v, "k", 10)):
        assert type(f(Idx(3))) is int and type(f(np.array(3))) is int and type(f(np.int8(3))) is int


# -- C5: an array-like converted once --------------------------------------------------------------------------------


class Lazy:
    """An array-like whose later conversions give another array: a NaN first (``grow=False``) or one entry more."""

    def __init__(self, v: np.ndarray, grow: bool = False) -> None:
        self.v, self.n, self.grow = np.asarray(v), 0, grow

    def __array__(self, dtype: object = None, copy: object = None) -> np.ndarray:
        self.n += 1
        a = self.v.copy()
        if self.n > 1:
            if self.grow:
                a = np.concatenate([a, a[:1]])
            else:
                a = a.astype(float)
                a.flat[0] = np.nan
        return a if dtype is None else a.astype(dtype)

    def __len__(self) -> int:
        return len(self.v)


#: The calls fuzz 29a's sweep found converting an argument twice (s5.py, s1.py; and this fix's sweep of the registry).
TWICE = [
    ("fusion.book.ledger.PublishedValues", "published"), ("fusion.estimates.chernoff.is_second_moment", "means"),
    ("fusion.estimates.chernoff.is_second_moment", "covs"), ("fusion.estimates.chernoff.log_densities", "x"),
    ("fusion.estimates.ci.split_ci_objective", "P1d"), ("fusion.filtering.tracks.local_track", "Q"),
    ("fusion.filtering.tracks.local_track", "R"), ("fusion.readings.correlated.gauss_markov_gap", "H"),
    ("fusion.readings.correlated.gauss_markov_gap", "R"), ("fusion.readings.weighting.awf", "X"),
    ("fusion.scenarios.infrared_radar.late_means", "t"), ("fusion.scenarios.thermocouples.scale_sweep", "scales"),
    ("fusion.scenarios.time_registration.expected", "t_src"), ("fusion.scenarios.time_registration.expected", "t_dst"),
    ("fusion.scenarios.time_registration.manoeuvre_truth", "t"),
    ("fusion.scenarios.time_registration.monte_carlo", "t_src"),
    ("fusion.scenarios.time_registration.monte_carlo", "t_dst"),
    ("fusion.scenarios.time_registration.register", "t_src"), ("fusion.scenarios.time_registration.register", "t_dst"),
    ("fusion.scenarios.time_registration.register", "z"), ("fusion.scenarios.time_registration.registrar", "t_src"),
    ("fusion.scenarios.time_registration.registrar", "t_dst"), ("fusion.scenarios.time_registration.truth", "t"),
    ("fusion.scenarios.time_registration.two_point_remainder", "t_src"),
    ("fusion.scenarios.time_registration.two_point_remainder", "t_dst"),
    ("fusion.scenarios.two_sensor.nees_study", "Q"), ("fusion.scenarios.two_sensor.nees_study", "x_start"),
    ("fusion.scenarios.two_sensor.printed_fruit_fly_over_seeds", "P1d"),
    ("fusion.scenarios.two_sensor.run_rmse", "est"), ("fusion.scenarios.two_sensor.run_rmse", "truth"),
    ("fusion.scenarios.two_sensor.two_sensor_scenario", "R_a"),
    ("fusion.scenarios.two_sensor.two_sensor_scenario", "R_b"),
    ("fusion.scenarios.two_sensor.two_sensor_scenario", "Q"),
]


@pytest.mark.parametrize("name, arg", TWICE)
def test_c5_an_array_like_is_converted_once(name: str, arg: str) -> None:
    kw = _valid(name)
    lazy = kw[arg] = Lazy(kw[arg])
    result = CALLABLES[name](**kw)
    assert lazy.n == 1, (name, arg, lazy.n)
    if not callable(result):  # registrar returns a function: the conversion count is the check
        assert _same(result, CALLABLES[name](**_valid(name)))


def test_c5_a_conversion_that_raises_is_named() -> None:
    from fusion.scenarios.time_registration import truth

    class Broken:
        def __array__(self, dtype: object = None, copy: object = None) -> np.ndarray:
            raise RuntimeError("no data")

    with pytest.raises(TypeError, match="^t could not be converted"):
        truth(Broken())


# -- C7: callables are given copies ----------------------------------------------------------------------------------


def _scribbling(op: str):  # noqa: ANN202
    """An objective (x - 0.3)**2 that then changes its argument in place (``op``)."""
    def f(s):  # noqa: ANN001, ANN202
        v = (np.asarray(s, dtype=float) - 0.3) ** 2
        if isinstance(s, np.ndarray):
            {"scale": lambda: s.__imul__(10.0), "nan": lambda: s.fill(np.nan), "shift": lambda: s.__iadd__(5.0)}[op]()
        return v
    return f


@FEW
@given(op=st.sampled_from(["scale", "nan", "shift"]), which=st.sampled_from(["grid", "fly", "batch"]))
def test_c7_an_objective_changing_its_argument_does_not_move_the_optimum(op: str, which: str) -> None:
    from fusion.optimise.scalar import fruit_fly, fruit_fly_batch, grid_search

    f = _scribbling(op)
    if which == "grid":
        r = grid_search(f, 11, vectorized=True)
    elif which == "fly":
        r = fruit_fly(f, np.random.default_rng(1), population=5, iterations=5, vectorized=True)
    else:
        r = fruit_fly_batch(f, [np.random.default_rng(1)], 5, 5)[0]
    assert 0.0 <= r.x <= 1.0 and r.fun == (r.x - 0.3) ** 2


def test_c7_a_registration_changing_its_samples_gives_the_linear_map() -> None:
    from fusion.registration.analysis import affine_decomposition, expected_mse

    M = np.array([[0.5, 0.5, 0.0], [0.0, 0.5, 0.5]])

    def reg(z):  # noqa: ANN001, ANN202
        out = M @ z
        z *= 2.0
        return out

    z0 = np.array([1.0, 2.0, 3.0])
    assert np.allclose(affine_decomposition(reg, z0).A, M) and np.array_equal(z0, [1.0, 2.0, 3.0])
    assert expected_mse(reg, z0, M @ z0, 1.0) == pytest.approx(np.sum(M ** 2) / 2)


def test_c7_a_fitness_changing_the_active_problems_does_not_change_the_batch() -> None:
    from fusion.optimise.swarm import particle_swarm_batch

    def fit(active, eps):  # noqa: ANN001, ANN202
        v = -((eps[..., 0] - 0.3) ** 2)
        active[...] = 0
        return v

    def clean(active, eps):  # noqa: ANN001, ANN202
        return -((eps[..., 0] - 0.3) ** 2)

    rngs = lambda: [np.random.default_rng(i) for i in range(3)]  # noqa: E731
    assert _same(particle_swarm_batch(fit, 2, rngs(), 8, 5), particle_swarm_batch(clean, 2, rngs(), 8, 5))
