"""Property tests of the last classes of bad input of issue 35, over the whole public API.

* impossible sizes: every count has a ceiling by its kind (:data:`fusion._validation.COUNT_CEILINGS`);
  above it the call is refused with a ``ValueError`` naming the argument, before anything is allocated
  or run (a count of ``10**9`` ran for minutes, raised ``MemoryError`` or gave NaN);
* counts are integers: an integral float (``np.float64(100.0)``), a ``Decimal`` or a ``Fraction`` is
  a ``TypeError`` naming the argument, while a numpy integer or a 0-d integer array is the same count;
* masked arrays and dates/durations are refused by name wherever numbers are expected, ``fusion.book``
  included.

The callables and their valid example calls are the registry of :mod:`tests.test_bad_input` (through
:mod:`tests.test_bad_input_properties`, which infers the kind of each argument with the project's fuzzer).
"""

from __future__ import annotations

import decimal
import fractions
import re
from collections.abc import Sequence
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import fusion._validation as V
from test_bad_input_properties import CALLABLES, FEW, FZ, KIND, REG, _args, _base_result, _names_for, _valid, check


def _raised(name: str, arg: str, value: Any) -> BaseException | None:
    kwargs = _valid(name)
    kwargs[arg] = value
    how, out = FZ.run(CALLABLES[name], kwargs, 20.0)
    assert how != "timeout", f"{name}({arg}={value!r:.60}) ran for more than 20 s"
    return out if how == "raised" else None


def _names(exc: BaseException, arg: str) -> bool:
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(arg)}(?![A-Za-z0-9_])", str(exc)) is not None


# --------------------------------------------------------------------------------------------
# the shared rule
# --------------------------------------------------------------------------------------------


def test_every_kind_of_count_has_a_ceiling_within_the_memory_budget() -> None:
    """A count at its ceiling sizes a float64 vector well inside the budget of :func:`allocation`."""
    assert {k for k, _ in V.COUNT_KINDS} | {"size"} == set(V.COUNT_CEILINGS)
    for kind, ceiling in V.COUNT_CEILINGS.items():
        assert 1 <= ceiling <= V.MAX_COUNT and 8 * ceiling <= 8 * V.MAX_ELEMENTS // 16, kind
    assert V.MAX_ELEMENTS * 8 <= 2 * 2**30  # 2 GiB


@pytest.mark.parametrize("name, kind", [
    ("runs", "runs"), ("n_runs", "runs"), ("nees_runs", "runs"), ("scenarios['a'] runs", "runs"),
    ("n_particles", "particles"), ("population", "particles"), ("iterations", "iterations"),
    ("max_iter", "iterations"), ("draws", "samples"), ("curve_draws", "samples"), ("samples[0]", "samples"),
    ("n_grid", "grid"), ("dim", "dimension"), ("n_sensors", "dimension"), ("level", "level"),
    ("cfg['level']", "level"), ("decimals", "decimals"), ("digits", "decimals"), ("workers", "workers"),
    ("n", "size"), ("ns[2]", "size"), ("runs_factor", "size"),
])
def test_the_kind_of_a_count_comes_from_its_name(name: str, kind: str) -> None:
    assert V.count_kind(name) == kind


@given(st.sampled_from(["runs", "n_particles", "iterations", "draws", "level", "decimals", "dim", "n", "workers"]),
       st.integers(1, 2**70))
def test_count_refuses_exactly_what_is_beyond_the_ceiling(name: str, above: int) -> None:
    ceiling = V.count_ceiling(name)
    assert V.count(ceiling, name) == ceiling
    with pytest.raises(ValueError, match=rf"^{name} = .*ceiling.*{ceiling:,}"):
        V.count(ceiling + above, name)
    assert V.count(ceiling + above, name, maximum=None) == ceiling + above  # seeds and indices: no ceiling


@given(st.integers(0, 10**6), st.sampled_from(["float", "np.float64", "np.float32", "Decimal", "Fraction"]))
def test_a_count_is_an_integer_type(n: int, how: str) -> None:
    bad = {"float": float, "np.float64": np.float64, "np.float32": np.float32, "Decimal": decimal.Decimal,
           "Fraction": fractions.Fraction}[how](n)
    with pytest.raises(TypeError, match=r"^runs must be an integer"):
        V.count(bad, "runs", minimum=0)
    for good in (n, np.int64(n), np.uint32(n)):
        assert V.count(good, "runs", minimum=0) == n and type(V.count(good, "runs", minimum=0)) is int


def test_the_memory_budget_names_the_arguments() -> None:
    V.allocation((V.MAX_ELEMENTS,), "runs")
    with pytest.raises(ValueError, match=r"^runs and frames ask for .*memory budget"):
        V.allocation((V.MAX_ELEMENTS // 2 + 1, 2), "runs and frames")


# --------------------------------------------------------------------------------------------
# class: impossible sizes, across the public API
# --------------------------------------------------------------------------------------------


def _limited(name: str) -> list[str]:
    """Count arguments validated by the shared count rule with their kind's ceiling (not seeds, nor a signed
    integer such as a power of ten's exponent, which sizes nothing)."""
    return [a for a in _args(name, ("count",)) if not FZ.SEED_NAMES.search(a) and not FZ.SIGNED_NAMES.match(a)]


@pytest.mark.parametrize("name", [p for p in _names_for(("count",), "size") if _limited(p.values[0])])
@FEW
@given(data=st.data(), above=st.one_of(st.integers(1, 1000), st.integers(1, 2**80)))
def test_a_count_beyond_its_ceiling_is_refused_by_name(name: str, data: st.DataObject, above: int) -> None:
    """Just above the ceiling of its kind (as well as far above), a count is refused before any work."""
    arg = data.draw(st.sampled_from(_limited(name)))
    check(name, arg, V.count_ceiling(arg) + above, strict=True)


# --------------------------------------------------------------------------------------------
# class: integral floats and Decimals are not counts
# --------------------------------------------------------------------------------------------

NOT_INTEGERS = ("float", "np.float64", "Decimal", "Fraction")


def _not_integer(v: int, how: str) -> Any:
    return {"float": float, "np.float64": np.float64, "Decimal": decimal.Decimal, "Fraction": fractions.Fraction}[how](v)


@pytest.mark.parametrize("name", _names_for(("count", "index", "seed", "int_seq", "seed_seq"), "count_type"))
@FEW
@given(data=st.data(), how=st.sampled_from(NOT_INTEGERS))
def test_integral_floats_and_decimals_are_not_counts(name: str, data: st.DataObject, how: str) -> None:
    arg = data.draw(st.sampled_from(_args(name, ("count", "index", "seed", "int_seq", "seed_seq"))))
    v = REG[name][arg].value
    if KIND[name][arg] in ("int_seq", "seed_seq"):
        k = data.draw(st.integers(0, len(v) - 1))
        bad = type(v)(list(v[:k]) + [_not_integer(int(v[k]), how)] + list(v[k + 1:]))
    else:
        bad = _not_integer(int(v), how)
    out = _raised(name, arg, bad)
    assert isinstance(out, TypeError), f"{name}: {arg} = {bad!r} ({how}): {type(out).__name__}: {out}"
    assert _names(out, arg), f"{name}: {arg}: the message does not name it: {out}"


@pytest.mark.parametrize("name", _names_for(("count", "index", "seed"), "count_type"))
@FEW
@given(data=st.data(), how=st.sampled_from(["np.int64", "np.uint16"]))
def test_numpy_integers_are_the_same_count(name: str, data: st.DataObject, how: str) -> None:
    """The value-preserving side of the rule: a numpy integer is the same count, the same result (a uint16
    used in arithmetic instead of the validated int would overflow)."""
    arg = data.draw(st.sampled_from(_args(name, ("count", "index", "seed"))))
    v = int(REG[name][arg].value)
    if how == "np.uint16" and not 0 <= v < 2**16:
        return
    good = {"np.int64": np.int64, "np.uint16": np.uint16}[how](v)
    kwargs = _valid(name)
    kwargs[arg] = good
    how_, out = FZ.run(CALLABLES[name], kwargs, 20.0)
    assert how_ == "ok", f"{name}: {arg} = {good!r}: {out}"
    assert not FZ.differs(_base_result(name), out), f"{name}: {arg} = {good!r}: {FZ.differs(_base_result(name), out)}"


# --------------------------------------------------------------------------------------------
# class: masked arrays and dates, fusion.book included
# --------------------------------------------------------------------------------------------


def _masked(a: np.ndarray, garbage: bool) -> np.ma.MaskedArray:
    mask = np.zeros(a.shape, bool)
    b = a.copy()
    if garbage and a.size:
        mask.reshape(-1)[-1] = True
        b.reshape(-1)[-1] = 1e6  # what a dropped mask would let through
    return np.ma.masked_array(b, mask=mask)


@pytest.mark.parametrize("name", _names_for(("array", "real"), "masked"))
@FEW
@given(data=st.data(), garbage=st.booleans(), as_date=st.booleans())
def test_masked_arrays_and_dates_are_refused_by_name(name: str, data: st.DataObject, garbage: bool,
                                                     as_date: bool) -> None:
    """A masked array (a mask would be dropped and the values under it used) and a date or duration array
    (its unit guessed) are refused with a TypeError naming the argument, wherever an array is expected."""
    arg = data.draw(st.sampled_from(_args(name, ("array",)) or _args(name, ("real",))))
    a = np.array(REG[name][arg].value, dtype=float, copy=True)
    if as_date:
        bad = (np.round(a * 1000.0).astype("timedelta64[ms]") if data.draw(st.booleans())
               else np.datetime64("2026-12-05T10:00:00") + np.round(a * 1000.0).astype("timedelta64[ms]"))
    else:
        bad = _masked(a, garbage)
    if (name, arg) in FZ.DOCUMENTED_ACCEPTED:
        return  # a renderer that prints whatever it is given (documented)
    out = _raised(name, arg, bad)
    assert isinstance(out, TypeError), f"{name}: {arg} as {type(bad).__name__} {bad.dtype}: {type(out).__name__}: {out}"
    assert _names(out, arg), f"{name}: {arg}: the message does not name it: {out}"


@pytest.mark.parametrize("name", _names_for(("real",), "scalar_type"))
@FEW
@given(data=st.data(), how=st.sampled_from(["Decimal", "Fraction", "0-d masked", "masked"]))
def test_real_scalars_of_other_number_types(name: str, data: st.DataObject, how: str) -> None:
    """A Decimal or a Fraction is a real number (converted by the shared rule: a finite result, or a refusal
    naming the argument); a masked scalar or 0-d masked array is refused naming the argument."""
    arg = data.draw(st.sampled_from(_args(name, ("real",))))
    v = float(REG[name][arg].value)
    if how in ("Decimal", "Fraction"):
        check(name, arg, decimal.Decimal(v) if how == "Decimal" else fractions.Fraction(v), strict=False)
    else:
        check(name, arg, np.ma.masked_array(v) if how == "0-d masked" else np.ma.masked, strict=True)


@pytest.mark.parametrize("name", _names_for(("real",), "scalar_type"))
def test_a_real_scalar_is_its_value_whatever_its_number_type(name: str) -> None:
    """Every real scalar of the callable, exactly as a ``Decimal``, a ``Fraction``, a ``np.longdouble`` and (when
    exact) a ``np.float32``: the same result as the float, digit for digit (the shared rule reads it as that
    float), or, for a ``Decimal`` or a ``Fraction``, a refusal naming the argument. Deterministic: a study whose
    scalar reached its arithmetic before the rule failed here (or gave other digits in extended precision)."""
    for arg in _args(name, ("real",)):
        v = float(REG[name][arg].value)
        same = [decimal.Decimal(v), fractions.Fraction(v), np.longdouble(v)]
        if float(np.float32(v)) == v:
            same.append(np.float32(v))
        for value in same:
            kwargs = _valid(name)
            kwargs[arg] = value
            how, out = FZ.run(CALLABLES[name], kwargs, 20.0)
            what = f"{name}: {arg} = {value!r:.60} ({type(value).__name__})"
            if how == "raised" and isinstance(value, (decimal.Decimal, fractions.Fraction)):
                assert isinstance(out, (ValueError, TypeError)) and _names(out, arg), f"{what}: {out!r:.200}"
                continue
            assert how == "ok", f"{what}: {how}: {out!r:.200}"
            assert not FZ.differs(_base_result(name), out), f"{what}: {FZ.differs(_base_result(name), out)}"


@given(st.integers(0, 10**6))
def test_a_product_of_counts_beyond_the_memory_budget_is_refused_at_entry(extra: int) -> None:
    """Each count within its ceiling, their product beyond the budget: refused by name before any work."""
    from fusion.scenarios import thermocouples, two_mixtures, wavelet_sensors
    from test_bad_input import _objects

    runs = V.count_ceiling("n_runs") - extra
    with pytest.raises(ValueError, match=r"^n_runs, n_samples and n_sensors ask for .*memory budget"):
        thermocouples.simulate(np.random.default_rng(0), n_samples=100, sigma=1.0, n_runs=runs, n_sensors=3)
    with pytest.raises(ValueError, match=r"^runs, gains and length ask for .*memory budget"):
        wavelet_sensors.variance_study(runs=runs)
    o = _objects()
    with pytest.raises(ValueError, match=r"^n and gms ask for .*memory budget"):
        two_mixtures.grid_log_normaliser([o["gA"], o["gB"]], [0.5, 0.5], n=V.count_ceiling("n") - extra)


def _product_calls(runs: int) -> list[tuple[str, Any]]:
    """Calls of the split scenario modules whose counts are each within their ceiling (``runs`` at most
    the ceiling of runs) and whose array is beyond the memory budget: (expected message start, call)."""
    from fusion.filtering.kalman import cv_model
    from fusion.optimise.scalar import fruit_fly_batch
    from fusion.scenarios.ridge_sensors import plugin_study
    from fusion.scenarios import lecture_correlated as lc, lecture_weighting as lw, range_bearing as rb
    from fusion.scenarios import two_sensor as ts

    rng = np.random.default_rng(0)
    steps = V.count_ceiling("n_steps")
    q = np.eye(4)
    rbs = rb.RangeBearingScenario(frames=V.count_ceiling("frames"), n_particles=V.count_ceiling("n_particles"))
    return [
        ("runs, k_max and sigma", lambda: lw.awf_study(runs=runs, k_max=steps, ks=(100,), k_compare=100)),
        ("runs, k and sigma", lambda: lw.ar1_study(runs=runs, k=steps)),
        ("runs, chunk, k and sigma", lambda: lw.tail_study(runs=runs, k=steps)),
        ("runs, samples and sigma", lambda: lw.benchmark(runs=runs, samples=steps)),
        ("runs, samples and sigma", lambda: lw.consistency_study(runs=runs, samples=steps, window=(0, 10))),
        ("runs, epochs and r_sets", lambda: lw.learning_study(runs=runs, epochs=steps)),
        ("runs, samples and sigma", lambda: lw.regime_study(runs=runs, samples=steps)),
        ("runs, samples and sigma", lambda: lw.variance_change_study(runs=runs, samples=steps)),
        ("runs and T", lambda: ts.two_sensor_scenario(np.eye(2), np.eye(2), q, rng, runs=runs, T=1e-3)),
        ("runs and n_steps", lambda: ts.nees_study(rng, q, np.eye(2), np.eye(2), np.zeros(4), n_steps=steps, runs=runs)),
        ("runs, n_steps and F", lambda: ts.model_truth(rng, cv_model(1.0).F, q, np.zeros(4), steps, runs)),
        ("runs, nees_runs and T", lambda: ts.architecture_study(rng, np.eye(2), np.eye(2), q, runs=runs, T=1e-3)),
        ("runs, nees_runs and T", lambda: ts.q_scaling_study(rng, np.eye(2), np.eye(2), q, (1.0,), runs=runs, T=1e-3)),
        ("sigma and runs", lambda: lc.correlated_study(sigma=np.ones(V.count_ceiling("n_sensors")), runs=runs)),
        ("sc.frames, sc.sensors and sc.n_particles", lambda: rb.monte_carlo(rbs, 1, runs)),
        # a product of two counts each within its ceiling (fuzz9's joint sizes: MemoryError of 1 to 4 TiB)
        ("rngs, population and iterations", lambda: fruit_fly_batch(lambda x: x * x, [rng], population=runs,
                                                                    iterations=V.count_ceiling("iterations"))),
        ("seeds, population and iterations", lambda: ts.fruit_fly_over_seeds(
            np.eye(2), 2 * np.eye(2), seeds=(1, 2), population=runs, iterations=V.count_ceiling("iterations"))),
        ("m and runs", lambda: plugin_study([0.5], m=runs, runs=runs, curve=[1.0], seed=0)),
    ]


@pytest.mark.parametrize("i", range(18))
@FEW
@given(extra=st.integers(0, 10**6))
def test_the_split_scenarios_refuse_a_product_beyond_the_budget_at_entry(i: int, extra: int) -> None:
    """Each count within its ceiling, the product of the arrays a study draws beyond the budget: a ValueError
    naming the counts, before anything is drawn (they raised MemoryError or ran for minutes)."""
    what, call = _product_calls(V.count_ceiling("runs") - extra)[i]
    with pytest.raises(ValueError, match=rf"^{re.escape(what)} ask for .*memory budget"):
        call()


@given(span=st.floats(0.0, 1e150), step=st.floats(1e-150, 1e150))
def test_grid_points_count_before_allocating(span: float, step: float) -> None:
    """A regular grid from scalars (fuzz8 bug 7: np.arange's unnamed 'Maximum allowed size exceeded') is counted
    first: above the ceiling of samples it is refused naming the arguments, below it the count is floor(span/step)+1,
    the length np.arange gives."""
    ceiling = V.COUNT_CEILINGS["samples"]
    if span / step > ceiling:
        with pytest.raises(ValueError, match=r"^duration and T ask for a grid"):
            V.grid_points(span, step, "duration and T")
        return
    n = V.grid_points(span, step, "duration and T")
    assert n == int(span / step) + 1 <= ceiling + 1
    if n <= 10**5:
        assert abs(np.arange(0.0, span + 0.5 * step, step).size - n) <= 1  # np.arange rounds its own way at the end


@pytest.mark.parametrize("name,arg,value", [
    ("fusion.registration.methods.sample_times", "period", 1e-150),
    ("fusion.registration.methods.sample_times", "end", 1e150),
    ("fusion.scenarios.time_registration.instants", "period_2", 1e-150),
    ("fusion.scenarios.infrared_radar.truth", "duration", 1e150),
    ("fusion.scenarios.infrared_radar.truth", "T", 1e-150),
    ("fusion.scenarios.infrared_radar.simulate", "duration", 1e150),
])
def test_grids_from_scalars_are_refused_by_name(name: str, arg: str, value: float) -> None:
    """The sites of fuzz8 bug 7: a grid of 1e150 points is refused by a ValueError naming the argument."""
    out = _raised(name, arg, value)
    assert isinstance(out, ValueError) and _names(out, arg), f"{name}: {arg} = {value!r}: {out!r}"


@given(st.integers(1, V.count_ceiling("workers")))
def test_workers_are_capped_at_the_machine(n: int) -> None:
    """A number of worker processes (fuzz9 bug 1: ``workers=1000`` forked 1,000 processes) is served with at
    most the machine's CPUs, and as asked below that; the type and ceiling of a count still apply."""
    assert V.workers(n) == min(n, V.machine_workers())
    assert 1 <= V.machine_workers()
    with pytest.raises(ValueError, match="^workers"):
        V.workers(V.count_ceiling("workers") + n)
    with pytest.raises(TypeError, match="^workers"):
        V.workers(float(n))


def test_a_pool_never_has_more_workers_than_the_machine(monkeypatch: pytest.MonkeyPatch) -> None:
    """``run_tracking_batch(workers=1024)`` (and ``monte_carlo``, which passes it on) starts at most
    :func:`fusion._validation.machine_workers` processes; the blocks are stubbed (the runs take seconds)."""
    from fusion.scenarios import range_bearing as rb

    sizes: list[int] = []

    class Pool(rb.ProcessPoolExecutor):
        def __init__(self, max_workers: int, **kw: Any) -> None:
            sizes.append(max_workers)
            super().__init__(max_workers=1, **kw)

        def map(self, fn: Any, blocks: Any) -> Any:   # type: ignore[override]
            return [[None] * len(b[1]) for b in blocks]

    monkeypatch.setattr(rb, "ProcessPoolExecutor", Pool)
    monkeypatch.delenv("PYTEST_XDIST_WORKER", raising=False)  # under pytest-xdist the runs stay in-process
    seeds = np.random.SeedSequence(0).spawn(4 * rb.RUN_BLOCK)
    out = rb.run_tracking_batch(rb.RangeBearingScenario(), seeds, workers=V.count_ceiling("workers"))
    assert len(out) == len(seeds)
    assert max(sizes, default=1) <= V.machine_workers()
    assert bool(sizes) == (V.machine_workers() > 1)   # one CPU (taskset): no pool at all


class _ArrayOnly:
    """An object numpy reads as an array (``__array__``) that is neither iterable nor sized."""

    def __init__(self, a: np.ndarray) -> None:
        self._a = a

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        return self._a if dtype is None else self._a.astype(dtype)


def _iterables(value: Any) -> list[tuple[str, Any, bool]]:
    """``value`` as other iterables: (label, object, numpy reads it as the same array)."""
    items = list(value)
    return [("dict.values()", {i: v for i, v in enumerate(items)}.values(), False),
            ("iterator", iter(items), False), ("generator", (v for v in items), False),
            ("__array__ only", _ArrayOnly(np.asarray(items)), True)]


@pytest.mark.parametrize("name", _names_for(("int_seq", "seed_seq", "array"), "iterable"))
def test_iterables_that_are_not_sequences(name: str) -> None:
    """One rule for iterables (fuzz9 bugs 4 and 5): an object numpy reads as a numeric array (``__array__``) is
    that array, the same result; a dict view, an iterator or a generator (a 0-d object array to numpy) is a
    TypeError naming the argument, never accepted into a result field or an unnamed ``int()`` error."""
    for arg in _args(name, ("int_seq", "seed_seq", "array")):
        v = REG[name][arg].value
        if isinstance(v, np.ndarray) and v.ndim != 1 or not isinstance(v, (list, tuple, np.ndarray)) or not len(v):
            continue
        if any(isinstance(x, (list, tuple, np.ndarray, bool)) for x in v):
            continue
        for label, value, same in _iterables(v):
            kwargs = _valid(name)
            kwargs[arg] = value
            how, out = FZ.run(CALLABLES[name], kwargs, 20.0)
            what = f"{name}: {arg} as {label}"
            if how == "raised":
                assert isinstance(out, (ValueError, TypeError)) and _names(out, arg), f"{what}: {out!r:.200}"
                assert same or isinstance(out, TypeError), f"{what}: {out!r:.200}"
                continue
            assert how == "ok", f"{what}: {how}"
            assert same, f"{what}: accepted"
            assert not FZ.differs(_base_result(name), out), f"{what}: {FZ.differs(_base_result(name), out)}"


@given(e1=st.integers(-12, 12), e2=st.integers(-12, 12), e3=st.integers(-12, 12),
       sensors=st.sampled_from(["infrared", "radar", "both"]), smoother=st.booleans())
def test_the_many_scan_bound_is_finite_or_refused_by_name(e1: int, e2: int, e3: int, sensors: str,
                                                          smoother: bool) -> None:
    """Noise levels each valid, jointly far apart in scale (fuzz9 bug 3: NaN from the square root of a negative
    'variance' of an information matrix singular to working precision, or LinAlgError): a bound positive and
    finite wherever the scans are enough (NaN before, inf for the infrared's positions: documented), or a
    ValueError naming the noise levels."""
    from fusion import data
    from fusion.scenarios import infrared_radar as ir

    p = data.WANG2024_IR_RADAR
    path = ir.truth(0.1, 2.0, p["range"], p["azimuth"], p["elevation"], (300.0, 100.0, 0.0))
    args = (1e-4 * 10.0**e1, 0.02 * 10.0**e2, 5.0 * 10.0**e3)
    try:
        b = ir.many_scan_bound(path, *args, sensors, smoother=smoother)
    except ValueError as exc:
        assert re.match(r"^sigma_(ir|angle)", str(exc)), exc
        return
    rows = ~np.isnan(b[:, 0])
    assert rows.any() and np.all(np.isnan(b[~rows, :2]))
    cols = slice(0, 2) if sensors == "infrared" else slice(0, 4)
    assert np.all(np.isfinite(b[rows, cols])) and np.all(b[rows, cols] > 0)


@pytest.mark.parametrize("call", ["architecture_study", "q_scaling_study", "nees_study"])
def test_a_path_too_short_for_t_steady_names_the_period(call: str) -> None:
    """Each argument valid, the path they sample ending before ``t_steady`` (fuzz9 bug 6): the refusal names the
    period T and t_steady, not t_steady alone."""
    from fusion.scenarios import two_sensor as ts

    rng, R, Q = np.random.default_rng(0), np.eye(2), np.eye(4)
    calls = {"architecture_study": lambda: ts.architecture_study(rng, R, R, Q, runs=2, T=1e12),
             "q_scaling_study": lambda: ts.q_scaling_study(rng, R, R, Q, (1.0,), runs=2, T=1e12),
             "nees_study": lambda: ts.nees_study(rng, Q, R, R, np.zeros(4), n_steps=25, runs=2, T=1e-6)}
    with pytest.raises(ValueError, match=r"^t_steady = .*\bT = ") as info:
        calls[call]()
    assert _names(info.value, "T") and _names(info.value, "t_steady")


@pytest.mark.parametrize("study", ["q_scaling_study"])  # architecture_study: 13 s under tracemalloc (measured 62)
@pytest.mark.parametrize("path_runs", [True, False])
def test_the_paired_run_studies_hold_what_their_allocation_check_counts(study: str, path_runs: bool) -> None:
    """fuzz12 bug 1: the memory check of the two-sensor run studies counts every array they hold at once (measured
    peak of the allocations, per run and step, at most the counted _HELD float64)."""
    import tracemalloc

    from fusion.scenarios import two_sensor as ts
    from fusion.scenarios.two_sensor import architecture as arch

    runs, nees_runs = (1000, 5) if path_runs else (5, 1000)
    R, Q = np.diag([2500.0, 2500.0]), np.kron(np.eye(2), [[0.25, 0.5], [0.5, 1.0]])
    args = (np.random.default_rng(0), R, R / 4, Q) + (((1.0, 0.5),) if study == "q_scaling_study" else ())
    K = ts.trajectory(1.0).t.size
    tracemalloc.start()
    try:
        getattr(ts, study)(*args, runs=runs, nees_runs=nees_runs)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak / 8 / ((runs + nees_runs) * K) <= arch._HELD, peak / 8 / ((runs + nees_runs) * K)


@pytest.mark.parametrize("name, mods, names", [
    ("fusion.scenarios.two_sensor.q_scaling_study", dict(runs=200_000, nees_runs=200_000), "runs, nees_runs and T"),
    ("fusion.scenarios.two_sensor.architecture_study", dict(runs=200_000, nees_runs=200_000), "runs, nees_runs and T"),
    ("fusion.scenarios.two_sensor.q_scaling_study", dict(T=5e-6, velocity_sigma=1e8), "T, legs and turn_time"),
    ("fusion.scenarios.lecture_weighting.consistency.consistency_study", dict(samples=2_000_000, curve_draws=5_000_000),
     "runs, samples, curve_draws and sigma"),
    ("fusion.scenarios.lecture_weighting.consistency.consistency_study", dict(samples=2_000_000),
     "runs, samples, curve_draws and sigma"),
    ("fusion.scenarios.lecture_weighting.consistency.consistency_study", dict(curve_draws=5_000_000),
     "runs, samples, curve_draws and sigma"),
])
def test_joint_sizes_beyond_the_budgets_are_refused_before_any_work(name: str, mods: dict, names: str) -> None:
    """fuzz12 bugs 1-3: counts each within their ceilings whose joint memory or work is beyond the budget (a
    MemoryError after 26 s, more than 30 s, a refusal after 7-10 s) are refused at entry, naming them."""
    import time

    kwargs = {k: (np.random.default_rng(0) if isinstance(a.value, np.random.Generator) else a.value)
              for k, a in REG[name].items()}
    kwargs.update(mods)
    t0 = time.process_time()
    with pytest.raises(ValueError, match=rf"^{re.escape(names)} ask for .*(memory|work) budget|ceiling") as info:
        CALLABLES[name](**kwargs)
    assert time.process_time() - t0 < 1.0, str(info.value)
    assert str(info.value).startswith(names)


def test_em_and_the_fruit_fly_search_budget_their_joint_work() -> None:
    """The other public functions whose counts multiply (found by a scan for two or more counts without a budget
    check): EM's iterations x samples x components x dimension and the fruit-fly search's population x
    iterations, each count within its ceiling, are refused at entry by name."""
    import time

    from fusion.estimates.mixtures import weighted_em
    from fusion.optimise.scalar import fruit_fly

    x = np.random.default_rng(0).normal(size=(1000, 2))
    t0 = time.process_time()
    with pytest.raises(ValueError, match=r"^max_iter, x and n_components ask for .*work budget"):
        weighted_em(x, np.full(1000, 1e-3), 500, np.random.default_rng(0), max_iter=10**7)
    with pytest.raises(ValueError, match=r"^population and iterations ask for .*work budget"):
        fruit_fly(lambda e: e**2, np.random.default_rng(0), population=10**5, iterations=10**5)
    assert time.process_time() - t0 < 1.0


class _LyingSequence(Sequence):
    """A Sequence of ``items`` whose ``__len__`` says ``n`` (``list()`` would preallocate ``n`` slots)."""

    def __init__(self, items: Any, n: int) -> None:
        self._items, self._n = list(items), n

    def __len__(self) -> int:
        return self._n

    def __getitem__(self, i: Any) -> Any:
        return self._items[i]


@pytest.mark.parametrize("name", _names_for(("int_seq", "seed_seq"), "hugeseq"))
def test_an_impossibly_long_sequence_is_refused_by_name_before_it_is_copied(name: str) -> None:
    """fuzz13 bug 2: ``range(1, 10**12)``, a zero-stride array of 10**12 items and a Sequence whose ``__len__``
    says 10**12 are a ValueError naming the argument at once (a bare MemoryError, or seconds, before)."""
    for arg in _args(name, ("int_seq", "seed_seq")):
        v = list(REG[name][arg].value)
        for label, value in [("range", range(1, 10**12)), ("broadcast", np.broadcast_to(np.int64(1), (10**12,))),
                             ("lying __len__", _LyingSequence(v, 10**12))]:
            kwargs = _valid(name)
            kwargs[arg] = value
            how, out = FZ.run(CALLABLES[name], kwargs, 5.0)
            what = f"{name}: {arg} as {label}"
            assert how == "raised" and isinstance(out, ValueError) and _names(out, arg), f"{what}: {how} {out!r:.200}"


@given(items=st.lists(st.integers(0, 9), max_size=6), lie=st.integers(-3, 3), length=st.none() | st.integers(0, 6))
def test_sequence_checks_the_length_first_and_refuses_a_lying_len(items: list[int], lie: int,
                                                                  length: int | None) -> None:
    """``sequence()`` gives the items of an honest Sequence (as of a list), refuses a wrong ``length`` or more than
    MAX_COUNT items by len() alone, and refuses a Sequence whose len() disagrees with its items, by name."""
    n = max(len(items) + lie, 0)
    value = _LyingSequence(items, n)
    if length is not None and n != length:
        with pytest.raises(ValueError, match=f"^xs must have {length} items"):
            V.sequence(value, "xs", length)
    elif n != len(items):
        with pytest.raises(ValueError, match="^xs has len"):
            V.sequence(value, "xs", length)
    else:
        assert V.sequence(value, "xs", length) == V.sequence(list(items), "xs", length) == items
    with pytest.raises(ValueError, match="^xs has 10000001 items, beyond the ceiling"):
        V.sequence(_LyingSequence(items, V.MAX_COUNT + 1), "xs")
    with pytest.raises(ValueError, match="^xs has"):
        V.sequence(range(10**20), "xs")


def test_a_wrong_length_is_refused_without_reading_an_item() -> None:
    """fuzz13 bug 2: belief_study(seeds=range(1, 10**7)) took 1 s to say "seeds must have 3 items" (sequence()
    copied the items, then derived_inputs converted them to floats for its message): no item is read now."""
    from fusion.scenarios.lecture_weighting.belief import belief_study

    reads: list[int] = []

    class Counting(_LyingSequence):
        def __getitem__(self, i: Any) -> Any:
            reads.append(i)
            return 1

    with pytest.raises(ValueError, match="^seeds must have 3 items, got 10000000$"):
        belief_study(sigma=(1.0, 2.0), x=1.0, seeds=Counting([], 10**7), snapshots=2)
    assert not reads
